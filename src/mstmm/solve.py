"""The Python API: a scene in, natural frequencies and mode shapes out."""

from __future__ import annotations

import math

import numpy as np

from .kernels import Kernel
from .limits import MAX_MODES, check_count
from .plain import plain
from .scene import Scene, SceneError, check_band
from .topology import topology_of
from .undamped import Solution, solve_undamped

__all__ = ["Solution", "checked_request", "exact_zeros", "solve"]


def checked_request(
    scene: Scene, modes, band, source: str = "<solve>"
) -> tuple[int | None, tuple[float, float] | None]:
    """``modes`` and ``band`` of :func:`solve`, checked (ValueError, as the command line
    refuses them): ``modes`` a whole number >= 1, ``band`` two finite ``0 <= lo <= hi``
    within :func:`mstmm.scene.check_band`'s bounds, not both."""
    if modes is not None and band is not None:
        raise ValueError("give modes= or band=, not both")
    if modes is not None:
        if isinstance(modes, bool) or not isinstance(modes, (int, np.integer)) or modes < 1:
            raise SceneError(source, "modes", "must be a whole number >= 1", plain(modes))
        modes = int(modes)
        check_count(modes, MAX_MODES, "modes", source, "modes")
    if band is not None:
        try:
            lo, hi = (float(v) for v in band)
        except (TypeError, ValueError):
            raise SceneError(source, "band", "must be two numbers (lo, hi), rad/s", band) from None
        if not (math.isfinite(lo) and math.isfinite(hi)) or lo < 0.0:
            raise SceneError(source, "band", "lo and hi must be finite and >= 0 rad/s", [lo, hi])
        if hi < lo:
            raise SceneError(source, "band", "hi must not be below lo", [lo, hi])
        band = (lo, hi)
        check_band(scene, band, source, "band")
    return modes, band


#: A part of a damped root at most this many ulp of |omega| is round-off: returned as 0.
SIGMA_ROUNDOFF = 64


def exact_zeros(omega: np.ndarray) -> np.ndarray:
    """Damped roots with round-off removed where the model says zero: a part (``sigma`` or
    ``w_d``) of at most 64 eps ``|omega|`` is 0. An undamped mode of a damped scene (one
    whose shape has no motion at any damper) has sigma = 0 exactly, an overdamped root
    w_d = 0; the complex search leaves ~1e-18 relative of noise there, of either sign. No
    part is a negative zero."""
    omega = np.asarray(omega, dtype=complex)
    w_d, sigma = omega.real.copy(), omega.imag.copy()
    bound = SIGMA_ROUNDOFF * np.finfo(float).eps * np.abs(omega)
    finite = np.isfinite(omega)
    sigma[finite & (np.abs(sigma) <= bound)] = 0.0
    w_d[finite & (np.abs(w_d) <= bound)] = 0.0
    out = np.empty_like(omega)
    out.real, out.imag = w_d + 0.0, sigma + 0.0  # + 0.0 turns -0.0 into 0.0
    return out


def solve(
    scene: Scene,
    modes: int | None = None,
    band: tuple[float, float] | None = None,
    *,
    formulation: str = "stable",
    shapes: bool = True,
    rtol: float = 0.0,
    kernel: Kernel | None = None,
) -> Solution:
    """Natural frequencies of ``scene``: the lowest ``modes`` (default 10) or all in ``band``.

    ``formulation`` is ``"stable"`` (second-compound chain, default) or
    ``"paper"`` (det U_bar of paper Eq. (4) as printed). Mode shapes follow
    paper Eq. (5) unless ``shapes=False``: one per entry of ``omega``, rigid-body zeros
    included, a mass-orthonormal basis of the eigenspace of a multiple root or of a
    cluster of roots too close to separate (:mod:`mstmm.modes`). ``rtol`` is the relative
    tolerance of Brent's refinement (0: to machine precision). One root search serves
    both formulations and both ``modes=`` and ``band=`` (:mod:`mstmm.scan`): every root
    is certified by the Wittrick-Williams count; one it does not confirm (see
    :func:`mstmm.scan.verify`) is marked not converged, with a warning, and a search the
    count could not certify says so (``count_checked`` False, a warning).

    Both edges of ``band = (lo, hi)`` are inclusive by 4 ulp: a root is
    reported when ``lo (1 - 4 eps) <= omega <= hi (1 + 4 eps)``, eps = 2.2e-16
    (:data:`mstmm.scan.BAND_EDGE`), decided by its refined value. When the
    lowest ``modes`` end inside a multiple root, ``multiplicity`` gives its true
    multiplicity, ``truncated`` is True and a warning says so; ``omega`` keeps
    exactly ``modes`` values.

    Raises ValueError when ``modes`` is not a whole number >= 1, ``band`` not two finite
    numbers ``0 <= lo <= hi`` within the bounds of ``mstmm solve --band``
    (:func:`mstmm.scene.check_band`), or both are given.
    """
    modes, band = checked_request(scene, modes, band)
    topology = topology_of(scene)
    if topology.damped:
        if formulation != "stable":
            raise ValueError(
                "a damped scene has one formulation, the complex stable chain: the paper's"
                " det U_bar is real-valued (undamped scenes only)"
            )
        from .damped import solve_damped  # here: an undamped solve never pays its import

        # the damped search meets inf and nan where a bound or a box overflows (a dashpot
        # of 1e200 N s/m): values its argument-principle check reports (count_checked
        # False, a warning), never numpy's "overflow encountered" for the user to decode
        with np.errstate(all="ignore"):
            sol = solve_damped(scene, modes, band, shapes=shapes)
        sol.omega = exact_zeros(sol.omega)
        return sol
    return solve_undamped(
        scene, modes, band, formulation=formulation, shapes=shapes, rtol=rtol, kernel=kernel
    )

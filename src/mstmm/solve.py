"""The Python API: a scene in, natural frequencies and mode shapes out."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from .kernels import Kernel, load_kernel
from .modes import ModeShape, mode_shapes
from .scan import TRUST, find_roots
from .scene import Scene, SceneError, check_band
from .topology import parameter_vector, topology_of


@dataclass
class Solution:
    """Natural frequencies (rad/s, ascending, repeated by multiplicity) and what to trust."""

    scene: Scene
    omega: np.ndarray
    multiplicity: np.ndarray
    converged: np.ndarray
    formulation: str
    kernel_origin: str
    timings: dict[str, float]
    count_checked: bool = False
    shapes: list[ModeShape] | None = None
    warnings: list[str] = field(default_factory=list)
    #: How the kernel's root search ran: ``"compiled"`` (numba) or ``"interpreted"``
    #: (plain Python, for a small first solve: :mod:`mstmm.interpret`).
    kernel_mode: str = "compiled"
    #: True when the lowest ``modes`` end inside a multiple root: its multiplicity
    #: (the true one, in :attr:`multiplicity`) exceeds the copies in :attr:`omega`.
    truncated: bool = False

    @property
    def hz(self) -> np.ndarray:
        """Frequencies in Hz."""
        return self.omega / (2.0 * math.pi)

    def to_dict(self, shapes: bool = False) -> dict:
        """JSON-ready summary; with ``shapes``, one entry per mode shape under ``mode_shapes``.

        Each shape gives ``omega`` (rad/s), ``hz``, the samples ``x`` (m) with ``Y`` (m),
        ``theta`` (rad), ``M`` (N m), ``Q`` (N), the carried masses ``mass_x``, ``mass_Y``
        (m), ``singular_ratio``, ``modal_mass`` (kg), ``participation``, ``effective_mass``
        (kg) and ``multiplicity``. Numbers are Python floats; a non-finite one stays as it
        is (the command line writes it as ``null``, with a warning).
        """
        out = {
            "scene": self.scene.name,
            "formulation": self.formulation,
            "omega": [float(w) for w in self.omega],
            "hz": [float(f) for f in self.hz],
            "multiplicity": [int(m) for m in self.multiplicity],
            "converged": [bool(c) for c in self.converged],
            "count_checked": bool(self.count_checked),
            "truncated": bool(self.truncated),
            "warnings": list(self.warnings),
            "kernel": self.kernel_origin,
            "kernel_mode": self.kernel_mode,
            "timings": {k: float(v) for k, v in self.timings.items()},
        }
        if shapes and self.shapes is not None:
            out["mode_shapes"] = [
                {
                    "omega": float(s.omega),
                    "hz": float(s.omega) / (2.0 * math.pi),
                    "x": s.x.tolist(),
                    "Y": s.Y.tolist(),
                    "theta": s.theta.tolist(),
                    "M": s.M.tolist(),
                    "Q": s.Q.tolist(),
                    "mass_x": s.mass_x.tolist(),
                    "mass_Y": s.mass_Y.tolist(),
                    "singular_ratio": float(s.singular_ratio),
                    "modal_mass": float(s.modal_mass),
                    "participation": float(s.participation),
                    "effective_mass": float(s.effective_mass),
                    "multiplicity": int(s.multiplicity),
                }
                for s in self.shapes
            ]
        return out


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
            raise SceneError(source, "modes", "must be a whole number >= 1", _plain(modes))
        modes = int(modes)
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


def _plain(value):
    return value.item() if isinstance(value, np.generic) else value


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
        from .damped import solve_damped

        # the damped search meets inf and nan where a bound or a box overflows (a dashpot
        # of 1e200 N s/m): values its argument-principle check reports (count_checked
        # False, a warning), never numpy's "overflow encountered" for the user to decode
        with np.errstate(all="ignore"):
            sol = solve_damped(scene, modes, band, shapes=shapes)
        sol.omega = exact_zeros(sol.omega)
        return sol
    if modes is None and band is None:
        modes = 10
    timings: dict[str, float] = {}
    t0 = time.perf_counter()
    if kernel is None:
        kernel = load_kernel(topology)
    p = parameter_vector(scene)
    t1 = time.perf_counter()
    timings["load"] = t1 - t0
    if 0.0 < kernel.derive_seconds <= timings["load"]:  # derived by this call
        timings["derive"] = kernel.derive_seconds
    # a small first solve of the stable formulation runs the kernel as Python
    # (mstmm.interpret); otherwise compile, or load from numba's cache, before timing
    interpreted = modes is not None and formulation == "stable" and kernel.interprets(p, modes)
    if not interpreted:
        kernel.warm_up(p, formulation)
    t2 = time.perf_counter()
    timings["compile"] = t2 - t1
    found = find_roots(kernel, p, band=band, modes=modes, formulation=formulation, rtol=rtol)
    roots = found.roots
    t3 = time.perf_counter()
    timings["scan_refine"] = t3 - t2
    omega = np.array([r.omega for r in roots for _ in range(r.reported)], dtype=float)
    mult = np.array([r.multiplicity for r in roots for _ in range(r.reported)], dtype=int)
    conv = np.array([r.converged for r in roots for _ in range(r.reported)], dtype=bool)
    truncated = bool(roots) and roots[-1].reported < roots[-1].multiplicity
    warnings = [
        f"omega = {r.omega:.17g} rad/s: refinement did not converge, or neither the count"
        f" nor the stable function confirms a root within {max(TRUST, 4.0 * rtol):.0e}"
        " of it; this value is not trusted"
        for r in roots
        if not r.converged
    ] + found.notes
    if not found.count_checked:
        warnings.append("the roots disagree with the Wittrick-Williams count: some may be missing")
    if truncated:
        r = roots[-1]
        warnings.append(
            f"the last root, omega = {r.omega:.17g} rad/s, has multiplicity {r.multiplicity}:"
            f" only {r.reported} of its copies fit in the {len(omega)} modes asked for"
        )
    shape_list = None
    if shapes:
        shape_list = mode_shapes(kernel, p, omega)
        timings["shapes"] = time.perf_counter() - t3
    return Solution(
        scene,
        omega,
        mult,
        conv,
        formulation,
        kernel.origin,
        timings,
        found.count_checked,
        shape_list,
        warnings,
        "interpreted" if interpreted else "compiled",
        truncated,
    )

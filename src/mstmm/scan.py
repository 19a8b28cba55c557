"""The root search's driver: the kernel's certified scan, band edges, and the last checks.

One search finds the roots, the kernel's (``lowest`` in ``mstmm.numerics.search``,
:meth:`mstmm.kernels.Kernel.lowest`), for either formulation, ``modes=`` or ``band=``:

* sign changes of the pole-free characteristic function on a grid uniform in
  ``beta = lam L`` (beam modes lie about ``pi`` apart) plus a node on either side of
  every component's own frequency (where roots crowd), each refined by Brent's method
  when its root is reported;
* one Wittrick-Williams count ``N(omega)`` (independent of the characteristic
  function) per block of sign changes: when ``N(top) - N(bottom)`` equals their number,
  each brackets exactly one simple root and none lies elsewhere;
* where the two disagree, bisection on the count: a spurious sign change (a function
  that has lost its digits, as the paper's at high modes) is dropped, a root without
  one (a double root: identical oscillators at one point) is found, and a count jump
  that stays above one down to round-off width is a multiple root of that multiplicity;
* where the count itself cannot certify (it does not settle on the rigid-body modes at
  the bottom, or decreases), the search goes on without it and the result says so.

This module turns the kernel's answer into :class:`Root` values: it widens a band by
a margin and keeps roots by value (both edges inclusive by 4 ulp), checks again every
root the kernel flagged, and every root of the paper formulation (whose Brent root
may sit anywhere in its bracket once the function is noise), and cuts ``modes=`` at
the true multiplicity of the last root.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .kernels import Found, Kernel

#: A root is trusted when the count finds a root within this relative distance
#: (the count itself resolves roots to about 1e-9 relative up to the 100th mode)
#: (or within the refinement tolerance, when that is looser) ...
TRUST = 1e-8
#: ... or when the stable characteristic function changes sign within this distance.
STABLE_TRUST = 1e-12
#: Both edges of a band are inclusive by this relative tolerance (4 ulp of 1):
#: the band ``(lo, hi)`` means ``[lo (1 - BAND_EDGE), hi (1 + BAND_EDGE)]``.
BAND_EDGE = 4.0 * 2.220446049250313e-16
#: The search of a band runs on one this much wider (relative) on each side; the
#: roots are then kept by value (:func:`band_roots`).
BAND_MARGIN = 1e-6
#: The lowest node of the kernel's scan, in beta = lam L.
LOWEST_NODE = 1e-3


@dataclass(frozen=True)
class Root:
    """A natural frequency (rad/s) with its multiplicity and how far it can be trusted."""

    omega: float
    multiplicity: int = 1
    converged: bool = True
    how: str = "scan"  # scan | rigid
    #: Copies reported when the lowest ``modes`` end inside this root (fewer than
    #: ``multiplicity``); 0: all of them.
    copies: int = 0

    @property
    def reported(self) -> int:
        """How many times this root appears in a list repeated by multiplicity."""
        return self.copies or self.multiplicity


@dataclass(frozen=True)
class Roots:
    """The roots of a search, whether the count certified them, and what to tell the user."""

    roots: list[Root]
    count_checked: bool
    notes: list[str]


def omega_of(beta, p):
    """``omega`` of ``beta = lam L = L (mbar omega^2 / EI)^(1/4)``."""
    L, EI, mbar = p[0], p[1], p[2]
    return np.square(np.asarray(beta) / L) * math.sqrt(EI / mbar)


def find_roots(
    kernel: Kernel,
    p: np.ndarray,
    *,
    band: tuple[float, float] | None = None,
    modes: int | None = None,
    formulation: str = "stable",
    rtol: float = 0.0,
    certify: bool = True,
) -> Roots:
    """Natural frequencies in ``band`` (rad/s), or the lowest ``modes``, with multiplicity.

    Rigid-body modes (omega = 0) are included whenever the band starts at 0 or
    ``modes`` is given. With ``certify`` the roots are checked (and completed)
    against the Wittrick-Williams count. Both edges of ``band = (lo, hi)`` are
    inclusive by a relative tolerance of 4 ulp, :data:`BAND_EDGE`: a root
    ``omega`` is reported when ``lo (1 - BAND_EDGE) <= omega <= hi (1 + BAND_EDGE)``
    (see :func:`band_roots`).
    """
    if (band is None) == (modes is None):
        raise ValueError("give exactly one of band= or modes=")
    p = np.ascontiguousarray(p, dtype=np.float64)
    if band is not None:
        return band_roots(kernel, p, band, formulation, rtol, certify)
    found = kernel.lowest(p, int(modes), certify, formulation, rtol)
    out = _roots(kernel, p, found, formulation, rtol, certify)
    if len(found.omega) < int(modes):
        out.notes.append(
            f"the search found {len(found.omega)} of the {int(modes)} roots asked for and"
            f" stalled above omega = {found.failed_at:.6g} rad/s"
        )
        return Roots(out.roots, False, out.notes)
    return out


def band_roots(
    kernel: Kernel,
    p: np.ndarray,
    band: tuple[float, float],
    formulation: str = "stable",
    rtol: float = 0.0,
    certify: bool = True,
) -> Roots:
    """The roots in ``[lo (1 - BAND_EDGE), hi (1 + BAND_EDGE)]``, decided by their values.

    A count taken within its resolution of a root (about 1e-9 relative, see
    :data:`TRUST`) may or may not include it, so the search and its count run on
    a band :data:`BAND_MARGIN` wider on each side (wider again when a root lies
    within ``TRUST`` of that edge), and the refined roots, accurate to an ulp or
    two, are kept by value. A root within 1-2 ulp of an edge is then reported
    exactly once, and the count certifies every root of the wider band.
    """
    lo, hi = float(band[0]), float(band[1])
    margin = BAND_MARGIN
    for _ in range(4):
        wide = (lo * (1.0 - margin), hi * (1.0 + margin))
        from_bottom = wide[0] <= float(omega_of(LOWEST_NODE, p))
        if certify:
            found = kernel.roots_in_band(p, *wide, from_bottom, formulation, rtol)
        else:  # unchecked: the lowest sign changes up to the band's top
            found = _unchecked_up_to(kernel, p, wide[1], formulation, rtol)
        out = _roots(kernel, p, found, formulation, rtol, certify)
        if not any(
            r.omega > 0.0 and abs(r.omega - edge) <= TRUST * edge
            for r in out.roots
            for edge in wide
        ):
            break
        margin *= 16.0
    keep = [r for r in out.roots if lo * (1.0 - BAND_EDGE) <= r.omega <= hi * (1.0 + BAND_EDGE)]
    return Roots(keep, out.count_checked, out.notes)


def _unchecked_up_to(kernel: Kernel, p: np.ndarray, top: float, formulation: str, rtol: float):
    """The sign-change roots below ``top`` without the count (``certify=False``)."""
    modes = 16
    while True:
        found = kernel.lowest(p, modes, False, formulation, rtol)
        if len(found.omega) < modes or found.omega[-1] > top:
            keep = found.omega <= top
            return Found(found.omega[keep], found.untrusted[keep], 1, False, 0.0)
        modes *= 2


def _roots(
    kernel: Kernel, p: np.ndarray, found: Found, formulation: str, rtol: float, certify: bool
) -> Roots:
    """:class:`Root` values from the kernel's answer, the doubtful ones checked again."""
    roots = simple_roots(found.omega, found.last, found.untrusted)
    notes: list[str] = []
    if certify and not found.certified and len(found.omega):
        notes.append(
            "the Wittrick-Williams count could not certify the roots above omega ="
            f" {found.failed_at:.6g} rad/s: some may be missing or spurious"
        )
    if formulation != "stable" or found.untrusted.any():
        roots = verify(kernel, p, roots, rtol, recheck=formulation != "stable")
    return Roots(roots, bool(found.certified) or not certify, notes)


def verify(
    kernel: Kernel, p: np.ndarray, roots: list[Root], rtol: float = 0.0, recheck: bool = True
) -> list[Root]:
    """Confirm doubtful roots; mark as not converged every one that neither check confirms.

    A root ``omega`` of multiplicity ``m`` is confirmed when the count finds at
    least ``m`` natural frequencies within ``max(TRUST, 4 rtol)`` relative of
    it, or (odd ``m``: the count resolves roots only to about 1e-9, worse next
    to a very short segment at a constrained end) when the stable characteristic
    function, accurate to round-off (``docs/stability.md``), changes sign within
    ``max(STABLE_TRUST, 4 rtol)`` of it. A value that Brent's method took from round-off
    noise (the paper's formulation at high modes) fails both and is flagged
    instead of being printed as a frequency. ``recheck``: check every root (else only
    those already marked not converged, which a check may confirm).
    """
    inner = [i for i, r in enumerate(roots) if r.how != "rigid" and (recheck or not r.converged)]
    if not inner:
        return roots
    rel, rel_stable = max(TRUST, 4.0 * rtol), max(STABLE_TRUST, 4.0 * rtol)
    w = np.array([roots[i].omega for i in inner])
    n = kernel.count_below(np.concatenate([w * (1.0 - rel), w * (1.0 + rel)]), p)
    out = list(roots)
    for j, i in enumerate(inner):
        r = roots[i]
        confirmed = int(n[len(inner) + j]) - int(n[j]) >= r.multiplicity or (
            r.multiplicity % 2 == 1 and _stable_sign_change(kernel, p, r.omega, rel_stable)
        )
        out[i] = Root(r.omega, r.multiplicity, confirmed, r.how, r.copies)
    return out


def _stable_sign_change(kernel: Kernel, p: np.ndarray, omega: float, rel: float) -> bool:
    """Whether the stable characteristic function changes sign across ``omega (1 -+ rel)``."""
    mant, _ = kernel.evaluate(np.array([omega * (1.0 - rel), omega * (1.0 + rel)]), p, "stable")
    return bool(mant[0] * mant[1] < 0.0)


def simple_roots(
    omega: np.ndarray, last_multiplicity: int = 0, untrusted: np.ndarray | None = None
) -> list[Root]:
    """Roots from an ascending array repeated by multiplicity (zeros: the rigid-body modes).

    ``last_multiplicity``: the true multiplicity of the last root when the array
    may end inside it (the kernel's search reports it); its ``copies`` are then the
    values present. ``untrusted``: per value, a root the search could not confirm
    (the root is then not converged until :func:`verify` confirms it).
    """
    roots: list[Root] = []
    for i, w in enumerate(omega):
        ok = untrusted is None or not untrusted[i]
        if roots and roots[-1].omega == w:
            last = roots[-1]
            roots[-1] = Root(last.omega, last.multiplicity + 1, last.converged and ok, last.how)
        else:
            roots.append(Root(float(w), 1, ok, "rigid" if w == 0.0 else "scan"))
    if roots and last_multiplicity > roots[-1].multiplicity:
        last = roots[-1]
        roots[-1] = Root(last.omega, last_multiplicity, last.converged, last.how, last.multiplicity)
    return roots

"""Root search on the characteristic function: grid scan, recursive minimum search, refinement.

The idea of the seed's recursive eigenvalue search (paper ref. [9]): look at
``|Delta(omega)|``, not only at its sign. On a grid uniform in ``beta = lam L``
(beam modes are spaced about ``pi`` apart in ``beta``), with extra nodes
clustered around each oscillator frequency ``sqrt(k/m)`` (where roots crowd):

* a sign change between two nodes is refined by Brent's method (in the kernel);
* a local minimum of ``log|Delta|`` without a sign change is searched
  recursively on finer grids: a sign change found there gives two close roots;
  a minimum that keeps falling to round-off level is an even-multiplicity root,
  located on the derivative's sign change;
* zero-frequency rigid-body modes are counted from the end conditions.

Then every root is checked against the kernel's root count ``N(omega)``
(Wittrick-Williams, independent of the characteristic function): the band is
cut at the midpoints between consecutive roots and each piece must hold
exactly the roots found in it. A piece holding more is searched by bisection
on the count (which cannot miss a root), a root in a piece holding none is
dropped, and a piece whose count stays above one down to round-off width is a
multiple root of that multiplicity.

The interface is :func:`find_roots`; the kernel supplies the evaluations.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .kernels import Kernel

#: Grid nodes per ``pi`` of ``beta`` (about one beam mode).
NODES_PER_MODE = 24
#: Relative offsets of the extra nodes around an oscillator frequency.
CLUSTER = np.concatenate([-np.logspace(-1, -9, 9), [0.0], np.logspace(-9, -1, 9)])
#: Depth of the recursive minimum search (each level refines a cell 16-fold).
MAX_DEPTH = 12
#: A minimum counts as a double root when |Delta| falls this far below its neighbours.
DOUBLE_ROOT_DROP = 1e-12
#: Evaluations the recursive search may spend per grid node. A characteristic
#: function that has lost its digits (the paper's, at high modes) is noise with
#: a sign change and a local minimum in every cell; without a budget the
#: recursion would branch without end. The count fills in what is left.
BUDGET_PER_NODE = 64
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


@dataclass(frozen=True)
class Root:
    """A natural frequency (rad/s) with its multiplicity and how far it can be trusted."""

    omega: float
    multiplicity: int = 1
    converged: bool = True
    how: str = "sign"  # sign | minimum | rigid
    #: Copies reported when the lowest ``modes`` end inside this root (fewer than
    #: ``multiplicity``); 0: all of them.
    copies: int = 0

    @property
    def reported(self) -> int:
        """How many times this root appears in a list repeated by multiplicity."""
        return self.copies or self.multiplicity


def beta_of(omega, p):
    """``beta = lam L = L (mbar omega^2 / EI)^(1/4)``."""
    L, EI, mbar = p[0], p[1], p[2]
    return L * np.sqrt(np.sqrt(mbar * np.square(omega) / EI))


def omega_of(beta, p):
    """Inverse of :func:`beta_of`."""
    L, EI, mbar = p[0], p[1], p[2]
    return np.square(np.asarray(beta) / L) * math.sqrt(EI / mbar)


def oscillator_frequencies(kernel: Kernel, p: np.ndarray) -> np.ndarray:
    """The components' own frequencies (a spring-mass's ``sqrt(k/m)``, a chain's with its
    beam point held), the places where roots crowd."""
    return np.unique(kernel.oscillator_frequencies(p))


def grid(w_lo: float, w_hi: float, p: np.ndarray, oscillators: np.ndarray) -> np.ndarray:
    """Scan nodes in ``[w_lo, w_hi]``: uniform in ``beta`` plus clusters at the oscillators."""
    b_lo, b_hi = float(beta_of(w_lo, p)), float(beta_of(w_hi, p))
    n = max(2, int(math.ceil((b_hi - b_lo) / math.pi * NODES_PER_MODE)) + 1)
    nodes = [omega_of(np.linspace(b_lo, b_hi, n), p)]
    for w in oscillators:
        c = w * (1.0 + CLUSTER)
        nodes.append(c[(c > w_lo) & (c < w_hi)])
    out = np.unique(np.concatenate(nodes))
    out[0], out[-1] = w_lo, w_hi
    return out


def _logabs(mant: np.ndarray, logs: np.ndarray) -> np.ndarray:
    with np.errstate(divide="ignore"):
        return np.log(np.abs(mant)) + logs


def _sign_brackets(w, mant):
    s = np.sign(mant)
    return [i for i in range(len(w) - 1) if s[i] * s[i + 1] < 0]


def _exact_zeros(w, mant):
    return [i for i in range(1, len(w) - 1) if mant[i] == 0.0]


def _local_minima(w, mant, la):
    s = np.sign(mant)
    out = []
    for i in range(1, len(w) - 1):
        if la[i] < la[i - 1] and la[i] < la[i + 1] and s[i - 1] == s[i] == s[i + 1] != 0:
            out.append(i)
    return out


class _Search:
    def __init__(self, kernel: Kernel, p: np.ndarray, formulation: str, rtol: float):
        self.kernel, self.p, self.formulation, self.rtol = kernel, p, formulation, rtol
        self.roots: list[Root] = []
        self.budget = 0
        self.exhausted = False

    def evaluate(self, w):
        self.budget -= len(w)
        mant, logs = self.kernel.evaluate(w, self.p, self.formulation)
        return mant, _logabs(mant, logs)

    def bracket(self, a: float, b: float) -> None:
        root, _its, ok = self.kernel.refine(a, b, self.p, self.formulation, self.rtol)
        self.roots.append(Root(root, 1, ok, "sign"))

    def scan(self, w: np.ndarray) -> None:
        self.budget += BUDGET_PER_NODE * len(w)
        mant, la = self.evaluate(w)
        self.scan_values(w, mant, la, depth=0)

    def scan_values(self, w, mant, la, depth: int) -> None:
        for i in _sign_brackets(w, mant):
            self.bracket(w[i], w[i + 1])
        for i in _exact_zeros(w, mant):
            self.roots.append(Root(float(w[i]), 1, True, "sign"))
        for i in _local_minima(w, mant, la):
            self.minimum(w[i - 1], w[i + 1], la[i - 1], la[i + 1], depth)

    def minimum(self, a: float, b: float, la: float, lb: float, depth: int) -> None:
        """Recursive search of a cell around a local minimum of log|Delta|."""
        if self.budget <= 0:
            self.exhausted = True
            return
        w = np.linspace(a, b, 17)
        mant, lw = self.evaluate(w)
        if _sign_brackets(w, mant) or _exact_zeros(w, mant):
            self.scan_values(w, mant, lw, depth + 1)
            return
        i = int(np.argmin(lw))
        if i in (0, len(w) - 1):
            return  # the minimum left the cell: a slope, no root
        drop = lw[i] - min(la, lb)
        if (
            drop < math.log(DOUBLE_ROOT_DROP)
            or depth >= MAX_DEPTH
            or w[i + 1] - w[i] <= 4e-16 * w[i]
        ):
            if drop < math.log(DOUBLE_ROOT_DROP):
                self.double_root(w[i - 1], w[i + 1])
            return
        self.minimum(w[i - 1], w[i + 1], la, lb, depth + 1)

    def double_root(self, a: float, b: float) -> None:
        """Even-multiplicity root: bisect on the sign of the slope of |Delta|."""
        h = (b - a) * 1e-3

        def slope(x):
            (m1, m2), (g1, g2) = self.kernel.evaluate(
                np.array([x - h, x + h]), self.p, self.formulation
            )
            return abs(m2) * math.exp(g2 - g1) - abs(m1)

        lo, hi = a, b
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if hi - lo <= 4e-16 * mid:
                break
            if slope(mid) < 0.0:
                lo = mid
            else:
                hi = mid
            h = min(h, 0.25 * (hi - lo)) or h
        self.roots.append(Root(0.5 * (lo + hi), 2, True, "minimum"))


@dataclass
class Roots:
    """The roots of a search and whether the independent count confirmed them."""

    roots: list[Root]
    count_checked: bool
    notes: list[str]


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
    return _search_roots(kernel, p, None, modes, formulation, rtol, certify)


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
    exactly once, and the count certifies every root of the wider band. The
    stable formulation runs the kernel's search (one count per block of sign
    changes, as for ``modes=``; :meth:`mstmm.kernels.Kernel.roots_in_band`), the
    general search below only where that cannot certify.
    """
    lo, hi = float(band[0]), float(band[1])
    margin = BAND_MARGIN
    for _ in range(4):
        wide = (lo * (1.0 - margin), hi * (1.0 + margin))
        found = None
        if formulation == "stable" and certify:  # the kernel's search, as for modes=
            w = kernel.roots_in_band(p, *wide, from_bottom=wide[0] <= float(omega_of(1e-3, p)))
            if w is not None:
                found = Roots(simple_roots(w, kernel.rigid_body_modes(p)), True, [])
        if found is None:
            found = _search_roots(kernel, p, wide, None, formulation, rtol, certify)
        if not any(
            r.omega > 0.0 and abs(r.omega - edge) <= TRUST * edge
            for r in found.roots
            for edge in wide
        ):
            break
        margin *= 16.0
    keep = [r for r in found.roots if lo * (1.0 - BAND_EDGE) <= r.omega <= hi * (1.0 + BAND_EDGE)]
    return Roots(keep, found.count_checked, found.notes)


def _search_roots(
    kernel: Kernel,
    p: np.ndarray,
    band: tuple[float, float] | None,
    modes: int | None,
    formulation: str,
    rtol: float,
    certify: bool,
) -> Roots:
    """:func:`find_roots` on exactly ``band`` (edges as the count sees them), or ``modes``."""
    search = _Search(kernel, p, formulation, rtol)
    osc = oscillator_frequencies(kernel, p)
    rigid = kernel.rigid_body_modes(p)
    floor = _floor(p, osc)
    notes: list[str] = []
    if certify:  # nothing but rigid-body modes may lie below the scan
        floor, note = _settle_floor(kernel, p, floor, rigid)
        notes += note
    if band is not None:
        w_lo, w_hi = float(band[0]), float(band[1])
        start = max(w_lo, floor)
    else:
        w_lo, start = 0.0, floor
        b_hi = (modes + 1.5) * math.pi
        w_hi = float(omega_of(b_hi, p))
        # the count says how far the lowest `modes` reach
        while certify and int(kernel.count_below(w_hi, p)[0]) < modes:
            b_hi *= 1.5
            w_hi = float(omega_of(b_hi, p))
    if w_lo <= 0.0 and rigid:
        search.roots.append(Root(0.0, rigid, True, "rigid"))
    if w_hi > start:
        search.scan(grid(start, w_hi, p, osc))
    roots = _merge(search.roots)
    checked = True
    if certify and w_hi > start:
        roots, checked, more = _certify(search, roots, start, w_hi)
        notes += more
        roots = verify(kernel, p, roots, rtol)
    if search.exhausted:
        notes.append(
            f"the {formulation} characteristic function is noise in places: the recursive"
            " search stopped at its evaluation budget"
        )
    while band is None and _count(roots) < modes and not certify:
        start, w_hi = w_hi, 2.0 * w_hi  # without a count: scan further until enough
        search.roots = []
        search.scan(grid(start, w_hi, p, osc))
        roots = _merge(roots + search.roots)
    if band is None:
        roots = _truncate(roots, modes)
    return Roots(roots, checked, notes)


def _settle_floor(kernel: Kernel, p: np.ndarray, floor: float, rigid: int):
    """Move the bottom of the scan until the count there is exactly the rigid-body modes.

    Above it the count must hold every elastic root. Lower when the count sees a
    root below the floor; higher when it has not yet registered a rigid-body
    mode: its ``-omega^2`` pivot drowns in round-off at very low frequency when a
    constrained end sits next to a very short segment (an attachment 1e-6 L from
    a pin). A count of exactly ``rigid`` at the new floor proves that no elastic
    root lies below it.
    """
    n = int(kernel.count_below(floor, p)[0])
    while n > rigid and floor > 1e-300:
        floor *= 1e-3
        n = int(kernel.count_below(floor, p)[0])
    raised = floor
    while n < rigid and raised < 1e300:
        raised *= 2.0
        n = int(kernel.count_below(raised, p)[0])
    if n == rigid:
        return raised, []
    return floor, [
        f"the count does not settle on the {rigid} rigid-body mode(s) near omega = {floor:.3g}:"
        " roots there are not certified"
    ]


def _certify(search: _Search, roots: list[Root], lo: float, hi: float):
    """Check the roots in (lo, hi] against the count; add missing ones, drop spurious ones."""
    kernel, p = search.kernel, search.p
    fixed = [r for r in roots if r.how == "rigid"]
    inner = [r for r in roots if r.how != "rigid"]
    cuts = [lo] + [0.5 * (a.omega + b.omega) for a, b in zip(inner, inner[1:])] + [hi]
    counts = kernel.count_below(np.array(cuts), p)
    out: list[Root] = []
    notes: list[str] = []
    dropped: list[float] = []
    for i, r in enumerate(inner):
        expected = int(counts[i + 1] - counts[i])
        if expected == 1:
            out.append(Root(r.omega, 1, r.converged, r.how))
        elif expected == 0:
            dropped.append(r.omega)
        else:
            out.extend(_isolate(search, cuts[i], cuts[i + 1], int(counts[i]), int(counts[i + 1])))
    if not inner:
        out.extend(_isolate(search, lo, hi, int(counts[0]), int(counts[-1])))
    if dropped:
        notes.append(
            f"{len(dropped)} zero(s) of the characteristic function between {min(dropped):.6g}"
            f" and {max(dropped):.6g} rad/s are not roots by the count: dropped"
        )
    total = int(counts[-1] - counts[0])
    # a sign change of the pole-free stable function is a root: if the count disowns
    # one, one of the two is wrong here
    checked = _count(out) == total and not (dropped and search.formulation == "stable")
    if not checked:
        notes.append(f"count says {total} roots in ({lo:.6g}, {hi:.6g}), found {_count(out)}")
    # pieces are disjoint: no duplicates to merge, and close roots must stay apart
    return sorted(fixed + out, key=lambda r: r.omega), checked, notes


def _isolate(search: _Search, a: float, b: float, na: int, nb: int) -> list[Root]:
    """All roots in (a, b) by bisection on the count ``N(b) - N(a)``, then Brent."""
    if nb <= na:
        return []
    kernel, p = search.kernel, search.p
    if b - a <= 8e-16 * b:
        return [Root(0.5 * (a + b), nb - na, True, "count")]
    if nb - na == 1:
        (ma, mb), _ = kernel.evaluate(np.array([a, b]), p, search.formulation)
        if ma * mb < 0.0:
            root, _its, ok = kernel.refine(a, b, p, search.formulation, search.rtol)
            return [Root(root, 1, ok, "count")]
    mid = 0.5 * (a + b)
    # clamped as in the kernel's isolate: a count off by one at round-off distance
    # from a root must not add or lose one
    nm = min(max(int(kernel.count_below(mid, p)[0]), na), nb)
    return _isolate(search, a, mid, na, nm) + _isolate(search, mid, b, nm, nb)


def verify(kernel: Kernel, p: np.ndarray, roots: list[Root], rtol: float = 0.0) -> list[Root]:
    """Mark as not converged every root that neither check below confirms.

    A root ``omega`` of multiplicity ``m`` is confirmed when the count finds at
    least ``m`` natural frequencies within ``max(TRUST, 4 rtol)`` relative of
    it, or (odd ``m``: the count resolves roots only to about 1e-9, worse next
    to a very short segment at a constrained end) when the stable characteristic
    function, accurate to round-off (``docs/stability.md``), changes sign within
    ``max(STABLE_TRUST, 4 rtol)`` of it. A value that Brent's method took from round-off
    noise (the paper's formulation at high modes) fails both and is flagged
    instead of being printed as a frequency.
    """
    inner = [i for i, r in enumerate(roots) if r.how != "rigid" and r.converged]
    if not inner:
        return roots
    rel, rel_stable = max(TRUST, 4.0 * rtol), max(STABLE_TRUST, 4.0 * rtol)
    w = np.array([roots[i].omega for i in inner])
    n = kernel.count_below(np.concatenate([w * (1.0 - rel), w * (1.0 + rel)]), p)
    out = list(roots)
    for j, i in enumerate(inner):
        r = roots[i]
        if int(n[len(inner) + j]) - int(n[j]) >= r.multiplicity:
            continue
        if r.multiplicity % 2 == 1 and _stable_sign_change(kernel, p, r.omega, rel_stable):
            continue
        out[i] = Root(r.omega, r.multiplicity, False, r.how)
    return out


def _stable_sign_change(kernel: Kernel, p: np.ndarray, omega: float, rel: float) -> bool:
    """Whether the stable characteristic function changes sign across ``omega (1 -+ rel)``."""
    mant, _ = kernel.evaluate(np.array([omega * (1.0 - rel), omega * (1.0 + rel)]), p, "stable")
    return bool(mant[0] * mant[1] < 0.0)


def simple_roots(omega: np.ndarray, rigid: int, last_multiplicity: int = 0) -> list[Root]:
    """Roots from an ascending array repeated by multiplicity (zeros: the rigid-body modes).

    ``last_multiplicity``: the true multiplicity of the last root when the array
    may end inside it (the kernel's ``lowest`` reports it); its ``copies`` are
    then the values present.
    """
    roots: list[Root] = []
    for w in omega:
        if roots and roots[-1].omega == w:
            last = roots[-1]
            roots[-1] = Root(last.omega, last.multiplicity + 1, True, last.how)
        else:
            roots.append(Root(float(w), 1, True, "rigid" if w == 0.0 else "sign"))
    if roots and last_multiplicity > roots[-1].multiplicity:
        last = roots[-1]
        roots[-1] = Root(last.omega, last_multiplicity, True, last.how, last.multiplicity)
    return roots


def _floor(p, osc) -> float:
    """Lowest scanned frequency: below every beam mode and every oscillator."""
    w = float(omega_of(1e-3, p))
    if osc.size:
        w = min(w, 0.01 * float(osc.min()))
    return w


def _count(roots: list[Root]) -> int:
    return sum(r.multiplicity for r in roots)


def _merge(roots: list[Root]) -> list[Root]:
    """Sort and drop duplicates (a root found from two neighbouring scans)."""
    out: list[Root] = []
    for r in sorted(roots, key=lambda r: r.omega):
        if (
            out
            and abs(r.omega - out[-1].omega) <= 1e-13 * max(abs(r.omega), 1e-300)
            and r.how == out[-1].how
        ):
            continue
        out.append(r)
    return out


def _truncate(roots: list[Root], modes: int) -> list[Root]:
    """The lowest ``modes`` values; a multiple root cut keeps its true multiplicity."""
    out, n = [], 0
    for r in roots:
        if n >= modes:
            break
        take = min(r.multiplicity, modes - n)
        cut = take != r.multiplicity
        out.append(Root(r.omega, r.multiplicity, r.converged, r.how, take) if cut else r)
        n += take
    return out

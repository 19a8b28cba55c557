"""Periodic structures: the Bloch-Floquet dispersion of a unit cell and its certified
band-gap edges (issue 23; ``mstmm.numerics.bloch``, docs/periodic.md).

A cell is a scene: its beam (uniform or stepped, any segment physics) and its components
at 0 <= x < L; its end conditions play no part. The infinite structure repeats it. At
each frequency the cell's end-state subspace gives the two roots mu = 2 cos(k L) of the
palindromic characteristic polynomial of its transfer matrix, so the two wave pairs +-k
(real k: propagating; imaginary or complex: evanescent, Im k the attenuation per metre).

Band edges are the frequencies where a pair turns propagating at k L = 0 or pi: the
eigenvalues of the cell closed on itself periodically or antiperiodically. Each is found
with its multiplicity by bisection on a Wittrick-Williams count (the cell clamped at
both ends, ``Kernel.count_below``, plus the negative eigenvalues of the closed cell's
2x2 joint stiffness) and polished by Brent on det(X_L -+ X_0), kept where the count
steps beside it (that sign also flips where the subspace's basis turns over): none is
missed. A band
can also end where two propagating pairs meet at an interior k and turn complex (at the
edges of a locally resonant gap, above a Timoshenko cut-off): between consecutive edges
the pairs propagating at the two ends prove whether that happens, and once (``_gaps``);
where two propagate at both ends, their Krein signatures and the cell closed with a
Bloch phase between theirs prove whether they meet and part again (``_two_pairs``).
Where neither decides, the stretch is said in a note and an edge found there is marked
uncertified.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .buckling import compressed, probe_frequency
from .kernels import Kernel, load_kernel
from .limits import MAX_BAND_POINTS, check_bands_band, check_count
from .scene import (
    Scene,
    SceneError,
    load_scene,
    scene_from_dict,
    scene_to_dict,
)
from .topology import parameter_vector, topology_of

__all__ = ["Bands", "Edge", "bands", "cell_of"]

#: Nodes of the edge search per pi of the cell's lam L (the count splits what they miss).
EDGE_NODES_PER_PI = 8
#: Bisection on the count stops at this relative width: the roots left there are one
#: multiple root (or a cluster closer than this) with the count's jump as multiplicity.
CLUSTER_RTOL = 1e-15
#: Relative offsets of the extra dispersion points around each edge (the curves are
#: steep there: k L - pi ~ sqrt(omega - edge)).
_NEAR_EDGE = (0.0, *(sgn * 10.0**-j for j in range(2, 8) for sgn in (-1.0, 1.0)))
#: Roots of one edge function closer than this (relative) are one multiple root: a
#: double root's count can step twice by one within round-off of it.
MERGE_RTOL = 1e-12
#: An edge from Brent is kept where the count steps within this of it (relative); else the
#: count alone locates it.
CONFIRM_RTOL = 1e-12
#: mu within this of the real interval [-2, 2] counts as propagating.
MU_TOL = 1e-9


@dataclass(frozen=True)
class Edge:
    """A band edge: ``omega`` (rad/s) where a wave pair turns propagating or evanescent at
    k L = 0 (``kind`` "periodic") or pi ("antiperiodic"), with its ``multiplicity`` (2
    where two branches meet and no gap opens); "coalescence" where two pairs meet at an
    interior k (``certified`` where ``_gaps`` proves it the only one of its stretch)."""

    omega: float
    kind: str
    multiplicity: int
    certified: bool = True

    @property
    def hz(self) -> float:
        return self.omega / (2.0 * math.pi)


@dataclass
class Bands:
    """Dispersion of a periodic cell (SI; omega in rad/s).

    ``k`` (n, 2): the two wavenumbers (1/m) at each ``omega``, one per pair +-k, with
    Im k >= 0 (the wave decaying towards +x) and, undamped, 0 <= Re k <= pi / L; the
    first column is the more attenuated pair. ``mu`` (n, 2) = 2 cos(k L).
    ``propagating`` (n,): how many pairs propagate (undamped; -1 for damped cells,
    where every wave decays). ``edges``: every band edge in ``band`` (undamped cells),
    ``gaps``: the stop bands in ``band`` as (lo, hi) pairs (a gap reaching an end of
    ``band`` is cut there). ``count_checked``: the count proved every edge at k L = 0 or
    pi (none missed, multiplicities exact) and, between them, every band end at an
    interior k (a "coalescence": two pairs meet and turn complex), by ``_gaps``' argument,
    and in the sliver beside each edge that argument leaves out, by the sign of the
    discriminant (``_sliver_meeting``); False where that argument does not settle a
    stretch, or a meeting lies too near an edge to be told apart from it (``notes`` says
    where; an edge found there is not certified).
    ``buckling``: a compressed cell whose periodic structure has no stable equilibrium
    says so here in one line (:func:`periodic_buckling`; then no edge is searched, and
    ``count_checked`` is False); None otherwise."""

    cell: Scene
    omega: np.ndarray
    k: np.ndarray
    mu: np.ndarray
    propagating: np.ndarray
    band: tuple[float, float]
    edges: tuple[Edge, ...] = ()
    gaps: tuple[tuple[float, float], ...] = ()
    count_checked: bool = True
    damped: bool = False
    notes: list[str] = field(default_factory=list)
    timings: dict[str, float] = field(default_factory=dict)
    buckling: str | None = None

    @property
    def length(self) -> float:
        """The cell's length L (m)."""
        return self.cell.beam.length

    @property
    def hz(self) -> np.ndarray:
        return self.omega / (2.0 * math.pi)

    @property
    def attenuation(self) -> np.ndarray:
        """Im k L of the least attenuated pair at each omega: the decay of the slowest wave
        per cell (nepers; 0 in a pass band). A finite structure of N cells driven at one
        end transmits ~exp(-N attenuation) in a gap."""
        return self.length * np.min(self.k.imag, axis=1)


def cell_of(scene: Scene | str | Path) -> Scene:
    """The unit cell of ``scene``: a repeated scene's cell (``repeat = N``), or the scene
    itself (a path is loaded). A graded scene has none; components at x = L are refused:
    the next cell's x = 0 is the same point."""
    if not isinstance(scene, Scene):
        scene = load_scene(scene)
    if getattr(scene, "graded", False):
        raise SceneError(
            scene.source,
            "repeat",
            "a graded structure has no single cell to repeat (give the cell's values as"
            " plain numbers for its bands)",
            scene.repeat,
        )
    cell = getattr(scene, "cell", None) or scene
    L = cell.beam.length
    for i, a in enumerate(cell.attachments):
        if a.x >= L:
            raise SceneError(
                cell.source,
                f"attachments[{i}].x",
                "a cell's component must lie in 0 <= x < length (x = length is the next"
                " cell's x = 0)",
                a.x,
            )
    return cell


def _joint(cell: Scene) -> float:
    """Where to cut the ring of cells: the middle of the longest stretch without a
    component (0 for a cell without components)."""
    xs = sorted(a.x for a in cell.attachments)
    if not xs:
        return 0.0
    L = cell.beam.length
    best, at = xs[0] + L - xs[-1], 0.5 * (xs[-1] + xs[0] + L)
    for a, b in zip(xs, xs[1:]):
        if b - a > best:
            best, at = b - a, 0.5 * (a + b)
    return math.fmod(at, L)


def closed_cell(cell: Scene) -> Scene:
    """The cell cut at its joint (``_joint``) with both ends clamped: the same periodic
    structure (the spectrum of a ring does not depend on where it is cut), no component at
    an end, and the scene whose count is the Wittrick-Williams J0 of the closed cell."""
    d = scene_to_dict(cell)
    beam = d["beam"]
    beam["left"] = beam["right"] = "clamped"
    L = cell.beam.length
    xj = _joint(cell)
    if xj > 0.0:
        for a in d["attachments"]:
            a["x"] = (a["x"] - xj) % L if a["x"] != xj else 0.0
        if "segments" in beam:
            beam["segments"] = _rotated_segments(beam["segments"], xj)
    d["name"] = f"{cell.name}_closed"
    return scene_from_dict(d, source=cell.source)


def _rotated_segments(segments: list[dict], xj: float) -> list[dict]:
    """Segments of a stepped cell starting at xj (the one holding xj split there)."""
    after, before = [], []
    x = 0.0
    for s in segments:
        a, b = x, x + s["length"]
        if b <= xj:
            before.append(s)
        elif a >= xj:
            after.append(s)
        else:
            before.append(s | {"length": xj - a})
            after.append(s | {"length": b - xj})
        x = b
    return after + before


def default_band(cell: Scene) -> tuple[float, float]:
    """0 up to where the first segment's bare beam has k L = 3 pi (its third Bragg
    frequency): the first few pass bands and gaps."""
    b = cell.beam
    EI = b.segments[0].EI if b.segments else b.EI
    mbar = b.segments[0].mass_per_length if b.segments else b.mass_per_length
    return 0.0, (3.0 * math.pi / b.length) ** 2 * math.sqrt(EI / mbar)


class _Cell:
    """The closed cell's kernel and parameters, and its functions at one frequency."""

    def __init__(self, cell: Scene):
        self.cell = cell
        self.closed = closed_cell(cell)
        self.kernel: Kernel = load_kernel(topology_of(self.closed))
        self.p = np.ascontiguousarray(parameter_vector(self.closed), dtype=np.float64)
        self.damped = bool(self.kernel.topology.damped)
        self._waves = self.kernel.compiled("bloch_waves")
        if not self.damped:  # the real march (``numerics.bloch``) and the count
            self._closed = self.kernel.compiled("closed")
            self._subspace = self.kernel.compiled("subspace")
        self._K = np.zeros((2, 2))

    def waves(self, omegas: np.ndarray) -> np.ndarray:
        """(mu_1, mu_2, k_1 L, k_2 L, propagating pairs) at each omega, the more attenuated
        pair first."""
        ws = np.ascontiguousarray(omegas, dtype=np.complex128)
        out = np.zeros((ws.size, 5), dtype=np.complex128)
        self._waves(self.damped, ws, self.p, out)
        return out

    def mu(self, omegas: np.ndarray) -> np.ndarray:
        return self.waves(omegas)[:, :2]

    def propagating(self, omegas: np.ndarray) -> np.ndarray:
        """Pairs that propagate at each omega (``numerics.bloch.propagating_count``)."""
        return self.waves(omegas)[:, 4].real.astype(np.int64)

    def edge_function(
        self, w: float, s: float, count: bool = True
    ) -> tuple[float, float, int | None]:
        """(sign, log) of det(X_L - s X_0) and the count of the closed cell below w (None
        exactly at a frequency of the clamped cell, where the joint stiffness is not
        defined)."""
        sign, log, ok = self._closed(float(w), self.p, float(s), self._K)
        if not ok or not count:
            return sign, log, None
        K = self._K
        a, c = K[0, 0], K[1, 1]
        off = 0.5 * (K[0, 1] + K[1, 0])
        det = a * c - off * off
        neg = 1 if det < 0.0 else (2 if a + c < 0.0 and det > 0.0 else 0)
        if det == 0.0:
            neg = int(a < 0.0) + int(c < 0.0)
        j0 = int(self.kernel.count_below(np.array([float(w)]), self.p)[0])
        return sign, log, j0 + neg

    def count(self, w: float, s: float) -> int | None:
        return self.edge_function(w, s)[2]

    def phase_count(self, w: float, theta: float) -> int | None:
        """Eigenvalues below w of the cell closed with Z_L = exp(i theta) Z_0 (Wittrick-
        Williams: the clamped cell's count plus the negative eigenvalues of the Hermitian
        joint stiffness, :func:`phase_stiffness`); None where that is not defined (a
        frequency of the clamped cell) or not Hermitian to round-off."""
        X = self._subspace(False, complex(float(w), 0.0), self.p)
        K = phase_stiffness(X, theta) if X.shape[0] == 8 else None
        if K is None:
            return None
        H = 0.5 * (K + K.conj().T)
        if not np.abs(K - K.conj().T).max() <= HERMITIAN_RTOL * np.abs(H).max():
            return None
        j0 = int(self.kernel.count_below(np.array([float(w)]), self.p)[0])
        return j0 + int(np.sum(np.linalg.eigvalsh(H) < 0.0))

    def phase_span(self, a: float, b: float, theta: float) -> int | None:
        """D(theta): how many eigenvalues of the cell closed with phase theta lie in (a, b)."""
        na, nb = self.phase_count(a, theta), self.phase_count(b, theta)
        return None if na is None or nb is None else nb - na


#: The closed cell's joint stiffness at a Bloch phase is Hermitian: a larger skew part
#: (relative) means the subspace lost its accuracy, and the count is not used.
HERMITIAN_RTOL = 1e-8


def phase_stiffness(X: np.ndarray, theta: float) -> np.ndarray | None:
    """The 2x2 Hermitian joint stiffness of the cell closed on itself with the Bloch phase
    theta (Z_L = s Z_0 on the displacements Y, theta; s = exp(i theta)): the pairs of
    X = [X0; XL] (``cell_subspace``) with (Y, theta) = d at x = 0 and s d at x = L need
    the joint forces F = (M, Q)_L - s (M, Q)_0, which virtual work pairs with the joint's
    displacement s d: K d = conj(s) F (rows -Q, M). ``numerics.bloch.closed_stiffness``
    is the real case s = +-1. None where no pair has a given d."""
    s = complex(math.cos(theta), math.sin(theta))
    A = np.concatenate((X[4:6, :] - s * X[0:2, :], X[0:2, :]))
    R = np.zeros((4, 2), dtype=np.complex128)
    R[2, 0] = R[3, 1] = 1.0
    try:
        C = np.linalg.solve(A, R)
    except np.linalg.LinAlgError:
        return None
    F = (X[6:8, :] - s * X[2:4, :]) @ C  # rows: M, Q
    K = np.conj(s) * np.stack((-F[1], F[0]))
    return K if np.all(np.isfinite(K)) else None


def propagating_pairs(mu: np.ndarray) -> np.ndarray:
    """Whether each pair (entry of mu) propagates: undamped, mu real within [-2, 2]."""
    real = np.abs(mu.imag) <= MU_TOL * np.maximum(1.0, np.abs(mu.real))
    inside = np.abs(mu.real) <= 2.0 + MU_TOL
    return real & inside & np.isfinite(mu.real)


def bands(
    cell: Scene | str | Path,
    band: tuple[float, float] | None = None,
    points: int = 1000,
    omegas: np.ndarray | None = None,
    edges: bool = True,
) -> Bands:
    """Dispersion of the periodic structure made of ``cell`` repeated (a :class:`Scene`,
    a repeated scene's cell, or a path) at ``points`` frequencies uniform in ``band``
    (rad/s; default :func:`default_band`) or at the given ``omegas``; with ``edges``,
    every band edge in ``band`` found and certified, and the gaps.

    >>> import mstmm
    >>> b = mstmm.bands(mstmm.example_path("metamaterial"))  # doctest: +SKIP
    >>> b.gaps  # doctest: +SKIP
    """
    t0 = time.perf_counter()
    cell = cell_of(cell)
    lo, hi = default_band(cell) if band is None else (float(band[0]), float(band[1]))
    if not (math.isfinite(lo) and math.isfinite(hi)) or lo < 0.0 or hi <= lo:
        raise SceneError(cell.source, "band", "must be finite with 0 <= lo < hi (rad/s)", [lo, hi])
    given = omegas is not None
    check_bands_band(cell, (lo, hi), cell.source, "band")
    if omegas is None:
        if int(points) < 2:
            raise SceneError(cell.source, "points", "must be a whole number >= 2", points)
        check_count(points, MAX_BAND_POINTS, "frequencies", cell.source, "points")
        omegas = np.linspace(lo, hi, int(points))
    omegas = np.asarray(omegas, dtype=np.float64)
    c = _Cell(cell)
    t1 = time.perf_counter()
    out = _dispersion(c, omegas, (lo, hi))
    out.timings = {"kernel": t1 - t0, "dispersion": time.perf_counter() - t1}
    out.buckling = periodic_buckling(c)
    if out.buckling is not None:  # no edge of an unstable equilibrium
        out.count_checked = False
    elif edges and not c.damped:
        t3 = time.perf_counter()
        found, checked, notes = find_edges(c, lo, hi)
        found, gaps, more = _gaps(c, found, lo, hi)
        out.edges = tuple(found)
        out.gaps = tuple(gaps)
        out.count_checked = checked and not more  # a coalescence is not proved
        out.notes = notes + more + out.notes
        out.timings["edges"] = time.perf_counter() - t3
        if not given:  # the curves reach every edge and resolve every gap
            extra = [e.omega * (1.0 + d) for e in found for d in _NEAR_EDGE]
            for a, b in gaps:
                extra += list(a + (b - a) * (0.5 - 0.5 * np.cos(np.linspace(0, np.pi, 41))))
            fine = _dispersion(c, np.unique(np.concatenate((omegas, extra))), (lo, hi))
            out.omega, out.k, out.mu = fine.omega, fine.k, fine.mu
            out.propagating = fine.propagating
            out.notes = notes + more + fine.notes
    elif edges:  # nothing to certify
        out.notes = [
            "damped cell: every wave decays, no sharp band edge (k is complex)"
        ] + out.notes
    return out


def _waves(c: _Cell, omegas: np.ndarray) -> np.ndarray:
    """:meth:`_Cell.waves` in time-bounded chunks (:func:`mstmm.chunks.spans`): Ctrl-C gets
    through between them, and a long run draws a bar (:func:`mstmm.progress.counted`)."""
    from .chunks import spans
    from .progress import counted

    out = np.empty((omegas.size, 5), dtype=np.complex128)
    for at in counted(spans(omegas.size), omegas.size, "dispersion"):
        out[at] = c.waves(omegas[at])
    return out


#: Bloch phases k L = pi j / BUCKLING_PHASES (j = 1 .. BUCKLING_PHASES) at which a
#: compressed cell is tested for buckling: a compression that destabilises only waves
#: longer than 2 BUCKLING_PHASES cells (k L < pi / BUCKLING_PHASES) is not seen.
BUCKLING_PHASES = 32


def periodic_buckling(c: _Cell) -> str | None:
    """Whether the infinite structure of compressed cells has no stable equilibrium, as one
    line (None: stable, not compressed, or damped). As ``solve`` decides it
    (:mod:`mstmm.buckling`): at a probe frequency far below every natural one, the cell
    closed with a Bloch phase k L (:meth:`_Cell.phase_count`) has as many eigenvalues below
    it as its stiffness has negative ones (no rigid motion for k L in (0, pi]); any is a
    buckling mode exceeded. The phases tried are :data:`BUCKLING_PHASES`, longest waves
    last."""
    if c.damped or not compressed(c.p):
        return None
    probe = probe_frequency(c.kernel, c.p)
    for j in range(BUCKLING_PHASES, 0, -1):
        theta = math.pi * j / BUCKLING_PHASES
        n = c.phase_count(probe, theta)
        if n:
            return (
                f"buckled: the axial forces exceed the buckling load of the periodic structure"
                f" (at k L = {theta:.4g}, {n} buckling mode(s) exceeded); it has no dispersion"
                " about an unstable equilibrium"
            )
    return None


def _dispersion(c: _Cell, omegas: np.ndarray, band: tuple[float, float]) -> Bands:
    """Bands with the wavenumbers at ``omegas`` only (no edges)."""
    waves = _waves(c, omegas)
    mu = waves[:, :2]
    k = np.empty_like(mu)  # part by part: (pi + i inf) / L stays finite in its real part
    k.real = waves[:, 2:4].real / c.cell.beam.length + 0.0  # no -0.0
    k.imag = waves[:, 2:4].imag / c.cell.beam.length + 0.0
    prop = waves[:, 4].real.astype(np.int64)
    if c.damped:
        prop[:] = -1
    out = Bands(c.cell, omegas, k, mu, prop, band, damped=c.damped)
    out.notes += _evanescent_note(waves[:, 2:4])
    return out


#: Relative error of mu said in a note: the waves' k where both pairs are evanescent carry
#: about eps exp(Im k_2 L) (k_2 the less attenuated pair): P's middle coefficient is then
#: ~ exp(-Im k_2 L) of the others and known only to eps of them.
MU_TRUSTED = 1e-8


def _evanescent_note(kL: np.ndarray) -> list[str]:
    """A note where both wave pairs decay by so much across a cell that their k lose
    digits (a beam on a stiff foundation below its cut-on): mu is accurate to about
    eps exp(min Im k L) relative (a pair with one propagating or one mildly evanescent
    pair is accurate to round-off: c0 = det X0 is followed, ``cell_subspace_in``)."""
    with np.errstate(invalid="ignore", over="ignore"):
        least = np.min(kL.imag, axis=1)
        err = np.finfo(float).eps * np.exp(np.where(np.isfinite(least), least, 0.0))
    bad = err > MU_TRUSTED
    if not np.any(bad):
        return []
    return [
        f"at {int(np.sum(bad))} of the frequencies both wave pairs decay by"
        f" exp({np.min(least[bad]):.1f}) or more across a cell: their k are accurate to"
        f" about {np.max(err[bad]):.0e} (relative to mu = 2 cos k L) only"
    ]


def _scaled(c: _Cell, s: float, ref: list[float]):
    def f(w: float) -> float:
        sign, log, _ = c.edge_function(w, s, count=False)
        if not ref:
            ref.append(log)
        return sign * math.exp(min(log - ref[0], 700.0))

    return f


def find_edges(c: _Cell, lo: float, hi: float) -> tuple[list[Edge], bool, list[str]]:
    """Every zero of det(X_L -+ X_0) in [lo, hi] with its multiplicity, proved by the count
    of the closed cell (periodic and antiperiodic)."""
    L = c.cell.beam.length
    b = c.cell.beam
    EI = min(s.EI for s in b.segments) if b.segments else b.EI
    mbar = max(s.mass_per_length for s in b.segments) if b.segments else b.mass_per_length
    lam_hi = (hi * hi * mbar / EI) ** 0.25 * L
    nodes = max(16, int(math.ceil(lam_hi / math.pi * EDGE_NODES_PER_PI)) + 1)
    beta = np.linspace(0.0, math.sqrt(hi), nodes) ** 2
    grid = np.unique(np.concatenate(([lo, hi], beta[(beta > lo) & (beta < hi)])))
    own = c.kernel.oscillator_frequencies(c.p)
    side = 1e-7
    extra = np.concatenate((own * (1 - side), own * (1 + side)))
    grid = np.unique(np.concatenate((grid, extra[(extra > lo) & (extra < hi)])))
    if grid[0] == 0.0:
        grid[0] = hi * 1e-12  # the rigid motions sit at 0: count them as edges there
    edges: list[Edge] = []
    checked = True
    notes: list[str] = []
    for s, kind in ((1.0, "periodic"), (-1.0, "antiperiodic")):
        ref: list[float] = []
        f = _scaled(c, s, ref)
        counts = [c.count(w, s) for w in grid]
        values = [f(w) for w in grid]
        if lo == 0.0 and counts[0]:
            edges.append(Edge(0.0, kind, counts[0]))
        for i in range(len(grid) - 1):
            roots, ok = _isolate(
                c, s, f, grid[i], grid[i + 1], counts[i], counts[i + 1], values[i], values[i + 1]
            )
            checked = checked and ok
            for w, m in roots:  # a multiple root the count split in round-off: one edge
                if edges and edges[-1].kind == kind and w - edges[-1].omega <= MERGE_RTOL * w:
                    e = edges.pop()
                    w, m, ok = e.omega, e.multiplicity + m, e.certified and ok
                edges.append(Edge(w, kind, m, ok))
        if not checked:
            notes.append(f"{kind} edges: the count is not monotone somewhere (see edges)")
    edges.sort(key=lambda e: e.omega)
    return edges, checked, notes


def _isolate(c: _Cell, s: float, f, a, b, na, nb, fa, fb) -> tuple[list, bool]:
    """Roots of f in (a, b] with the count rising from na to nb: bisection on the count,
    Brent on a single sign change, a multiple root where the bracket shrinks to
    CLUSTER_RTOL. Returns ([(omega, multiplicity)], whether the count was consistent)."""
    if na is None or nb is None:  # a frequency of the clamped cell on a node: step off it
        return _isolate_nudged(c, s, f, a, b, na, nb, fa, fb)
    d = nb - na
    if d == 0:
        return [], True
    if d < 0:
        return [], False
    if d == 1 and (fa > 0.0) != (fb > 0.0):
        from scipy.optimize import brentq  # here: importing SciPy costs every process 0.35 s

        x = brentq(f, a, b, xtol=1e-300, rtol=1e-15, maxiter=200)
        h = CONFIRM_RTOL * x
        if c.count(x - h, s) == na and c.count(x + h, s) == nb:
            return [(x, 1)], True
        # not where the count steps: the sign of det(X_L - s X_0) also flips where the
        # subspace's basis turns over (a component's elimination changes its pivot), and
        # Brent found such a flip: bisection on the count alone
    if b - a <= CLUSTER_RTOL * b:
        return [(0.5 * (a + b), d)], True
    m = 0.5 * (a + b)
    nm = c.count(m, s)
    if nm is None:
        m = a + 0.499 * (b - a)
        nm = c.count(m, s)
    fm = f(m)
    left, ok1 = _isolate(c, s, f, a, m, na, nm, fa, fm)
    right, ok2 = _isolate(c, s, f, m, b, nm, nb, fm, fb)
    return left + right, ok1 and ok2


def _isolate_nudged(c: _Cell, s, f, a, b, na, nb, fa, fb):
    eps = 1e-12 * b
    if na is None:
        a = a + eps
        na, fa = c.count(a, s), f(a)
    if nb is None:
        b = b - eps
        nb, fb = c.count(b, s), f(b)
    if na is None or nb is None:
        return [], False
    return _isolate(c, s, f, a, b, na, nb, fa, fb)


def _gaps(c: _Cell, edges: list[Edge], lo: float, hi: float):
    """Stop bands in [lo, hi] from the edges, and the notes that make ``count_checked``
    False.

    Between consecutive edges (a, b) the counts of the cell closed periodically and
    antiperiodically do not change (the edges are all their jumps). For a Bloch phase
    theta in [0, pi] the cell closed with Z_L = exp(i theta) Z_0 is a self-adjoint problem
    with eigenvalues w_n(theta) continuous in theta, and D(theta), how many lie in [a', b']
    (a' = a + h, b' = b - h, h = EDGE_SLIVER (b - a) but at least SLIVER_FLOOR b: beside
    an edge the pairs are read from the signs of P(+-2), which it zeroes; stretches
    shorter than MERGE_RTOL b, the edges' own accuracy, are read at their middle),
    changes only at a theta
    where a wave propagates at a' or at b' with k L = theta; D(0) = D(pi) = 0. So:

    * no pair propagates at a' nor at b': D = 0 for every theta, no wave propagates
      anywhere in [a', b']: a stop band, proved;
    * one pair at a' and at b': one branch w_n(theta) crosses [a', b'] and no other enters
      it; the branch is monotone (a turn would give three propagating pairs), so exactly
      one pair propagates throughout: a pass band, proved;
    * none at one end and two at the other: D = 1 between the two waves' theta and 0
      elsewhere, so one branch dips into [a', b'] from beyond the end with two, and turns
      there exactly once (twice more would give four propagating values of theta): the
      two pairs meet at an interior k at exactly one frequency, a band edge inside the
      zone ("coalescence", proved; located by bisection on the number of pairs);
    * two at both ends: they may meet and part again inside; ``_two_pairs`` decides
      from their phases at a' and b' and the cell closed with a phase between them:
      no meeting, or exactly one stretch of none (two proved "coalescence" edges).

    Where it does not decide (phases that cannot be told apart), the stretch is read at a
    few points, said in a note, and not proved, and a change found between the points
    is an uncertified "coalescence" edge; so is any other pattern of the ends (one pair at
    one end only would need an edge at k L = 0 or pi inside: a misread)."""
    cuts = sorted({lo, hi, *(e.omega for e in edges if lo <= e.omega <= hi)})
    # (a double edge is where two pairs meet at k L = 0 or pi: nothing to look for beside)
    at_edge = {e.omega for e in edges if e.multiplicity == 1}
    found = list(edges)
    notes: list[str] = []
    spans: list[tuple[float, float, int]] = []
    slivers: list[tuple[float, float]] = []  # (edge, the sliver's other end)
    for a, b in zip(cuts, cuts[1:]):
        if b <= a:
            continue
        if b - a <= MERGE_RTOL * b:  # two edges within their own accuracy: nothing between
            spans.append((a, b, int(c.propagating(np.array([0.5 * (a + b)]))[0])))
            continue
        h = max((b - a) * EDGE_SLIVER, SLIVER_FLOOR * b)  # not within round-off of an edge
        ea, eb = a + h, b - h
        slivers += [(e, inner) for e, inner in ((a, ea), (b, eb)) if e in at_edge]
        na, nb = (int(v) for v in c.propagating(np.array([ea, eb])))
        if na == nb and na < 2:  # proved: none or one pair throughout
            spans.append((a, b, na))
            continue
        if {na, nb} == {0, 2}:  # proved: two pairs meet at exactly one frequency inside
            x = _bisect_change(c, ea, eb, na)
            found.append(Edge(x, "coalescence", 1, certified=True))
            spans += [(a, x, na), (x, b, nb)]
            continue
        if na == nb == 2:
            verdict = _two_pairs(c, ea, eb)
            if verdict is not None:  # proved: no meeting, or exactly one stretch of none
                if verdict:
                    wa, wb = verdict
                    if wa < wb:
                        found += [Edge(wa, "coalescence", 1), Edge(wb, "coalescence", 1)]
                        spans += [(a, wa, 2), (wa, wb, 0), (wb, b, 2)]
                        continue
                    found.append(Edge(wa, "coalescence", 2))  # they meet and part at once
                spans.append((a, b, 2))
                continue
        inner = a + (b - a) * np.array([0.05, 0.25, 0.5, 0.75, 0.95])
        probe = np.concatenate(([ea], inner, [eb]))
        n = np.concatenate(([na], c.propagating(inner), [nb]))
        if np.all(n == n[0]):
            spans.append((a, b, int(n[0])))
            notes.append(
                f"two wave pairs propagate between {a:.12g} and {b:.12g} rad/s: that they"
                " do not meet at an interior k there (a gap inside) is not proved"
            )
            continue
        # pairs meet inside, not proved how often: split at each change found between
        # the points, by bisection on the pattern
        xs = [a]
        for i in range(len(probe) - 1):
            if n[i] != n[i + 1]:
                x = _bisect_change(c, probe[i], probe[i + 1], int(n[i]))
                found.append(Edge(x, "coalescence", 1, certified=False))
                notes.append(f"a pass band ends inside k L in (0, pi) at {x:.12g} rad/s")
                xs.append(x)
        xs.append(b)
        for u, v in zip(xs, xs[1:]):
            spans.append((u, v, int(c.propagating(np.array([0.5 * (u + v)]))[0])))
    for edge, inner in slivers:
        spans = _sliver_meeting(c, edge, inner, spans, found, notes)
    gaps: list[tuple[float, float]] = []
    for a, b, n in sorted(spans):
        if n == 0:
            if gaps and gaps[-1][1] == a:
                gaps[-1] = (gaps[-1][0], b)
            else:
                gaps.append((a, b))
    found.sort(key=lambda e: e.omega)
    return found, gaps, notes


def _quartet(c: _Cell, w: float) -> bool:
    """Whether the two pairs' mu are a complex conjugate pair at w (the discriminant of
    the cell's quadratic negative: ``numerics.bloch.shifted_roots`` gives real roots
    exactly, imaginary parts 0, where it is not)."""
    mu = c.mu(np.array([w]))[0]
    return bool(np.any(mu.imag != 0.0))


def _pairs_from_mu(c: _Cell, w: float) -> int:
    """Propagating pairs at w read from the roots mu themselves (``propagating_pairs``),
    not from the signs of P(+-2), which an edge beside w zeroes."""
    return int(np.sum(propagating_pairs(c.mu(np.array([w]))[0])))


#: A meeting of two pairs nearer an edge than this (relative) is not told apart from it.
MEETING_RTOL = 64 * np.finfo(float).eps


def _sliver_meeting(c, edge, inner, spans, found, notes):
    """The sliver between an edge (k L = 0 or pi) and ``inner`` (``_gaps``' a' or b'),
    where the pairs were read from the signs of P(+-2): where two pairs meet inside it
    (at the top of a locally resonant gap, the complex quartet turns into two real pairs
    a hair before one of them reaches k L = 0), the discriminant of the cell's quadratic
    changes sign between the edge and ``inner``; the meeting is bisected on that sign
    (``_quartet``; the roots about +-2 keep their digits there), listed as a "coalescence"
    edge, and the span it falls in split there, the pairs on the edge's side read from
    the roots (``_pairs_from_mu``). A meeting within MEETING_RTOL of the edge is not
    separated from it in float64: said, and not certified."""
    near = edge
    for _ in range(4):  # a few ulps off the edge, towards inner
        near = float(np.nextafter(near, inner))
    qa = _quartet(c, near)
    if qa == _quartet(c, inner):
        return spans
    x = _bisect(lambda m: _quartet(c, m) == qa, near, inner)
    apart = bool(abs(x - edge) > MEETING_RTOL * abs(edge))
    found.append(Edge(x, "coalescence", 1, certified=apart))
    found.sort(key=lambda e: e.omega)
    if not apart:
        notes.append(
            f"two wave pairs meet within {abs(x - edge):.1e} rad/s of the band edge at"
            f" {edge:.12g} rad/s: not told apart from it in float64 (the gap may end at"
            " either)"
        )
    lo, hi = min(edge, x), max(edge, x)
    n_beside = _pairs_from_mu(c, 0.5 * (lo + hi))  # between the edge and the meeting
    out = []
    for u, v, n in spans:
        if u < x < v:  # the meeting splits its span: the edge's side changes
            if edge > x:
                out += [(u, x, n), (x, v, n_beside)]
            else:
                out += [(u, x, n_beside), (x, v, n)]
        else:
            out.append((u, v, n))
    return out


#: The stretch beside each edge left out of ``_gaps``' proof (relative to the stretch): the
#: propagating pairs are read there from the signs of P(+-2), which the edge zeroes.
EDGE_SLIVER = 1e-9
#: ... and at least this of the frequency (relative): nearer, P(+-2) is round-off.
SLIVER_FLOOR = 1e-13


#: Phases (rad) of the waves at a stretch's two ends closer than this are not told apart
#: (``_two_pairs``; beside an edge, where k L ~ sqrt(omega - edge), round-off in mu moves
#: them by ~1e-8).
PHASE_GAP = 1e-6


def _two_pairs(c: _Cell, ea: float, eb: float) -> tuple[float, ...] | None:
    """Two pairs propagate at both ends ea < eb of a stretch with no edge inside: () where
    they propagate throughout (proved), (wa, wb) where they meet at wa, are a complex
    quartet (no wave propagates) up to wb and part there (proved: the only such
    interval; wa == wb where they meet and part at once), None where the argument below
    does not decide (the caller says so).

    Each propagating wave exp(i theta) (theta in (0, pi)) has a Krein signature, the
    sign of d theta / d omega, and its branch theta(omega) turns only where it meets a
    wave of the other signature (a multiplier leaves the unit circle only through such a
    meeting, and a turn is one). So two branches of one signature never meet; two of
    opposite signatures that move apart never meet; two that approach each other meet
    once, become a quartet (or part at once), and come back (no edge inside) moving apart,
    to meet no more. D(theta), how many frequencies of (ea, eb) carry a wave of phase
    theta (the eigenvalues there of the cell closed with that phase, ``phase_span``),
    changes only at the four end phases p1 < p2 < p3 < p4, is 1 between p1 and p2 and
    between p3 and p4 (one branch ends in each), and between p2 and p3 tells the cases
    apart: with no meeting each branch runs from an ea phase to an eb phase, so D = 2
    there when both ea phases lie on one side (p1, p2 from ea) and 0 when they are
    interleaved or nested; a meeting covers the span of the ea phases (the branches
    approaching theta_a) and that of the eb phases (leaving theta_b): D = 0 or 2 the other
    way round. The quartet is then bracketed by bisection: at a frequency where two pairs
    propagate with phases f1 < f2, D over (ea, omega) at (f1 + f2) / 2 is 0 before the
    meeting (the branches approach from outside [f1, f2]) and at least 1 after it (they
    left theta_b inside it); its two ends by bisection on the number of pairs."""
    w = np.minimum(np.abs(c.waves(np.array([ea, eb]))[:, 2:4].real), math.pi)  # mu ~ -2 - 0
    ends = sorted([(t, 0) for t in w[0]] + [(t, 1) for t in w[1]])
    th = [t for t, _ in ends]
    if not th[2] - th[1] > PHASE_GAP:  # which end p1, p2 come from is what decides
        return None
    d = [c.phase_span(ea, eb, 0.5 * (th[i] + th[i + 1])) for i in range(3)]
    close = [th[1] - th[0] <= PHASE_GAP, False, th[3] - th[2] <= PHASE_GAP]
    if any(d[i] != 1 and not close[i] for i in (0, 2)) or d[1] not in (0, 2):
        return None
    apart = ends[0][1] == ends[1][1]  # the ea phases on one side of the eb phases
    if (d[1] == 2) == apart:
        return ()
    lo, hi = ea, eb  # two pairs approaching at lo, moving apart at hi
    while True:
        m = 0.5 * (lo + hi)
        if not lo < m < hi:
            return (m, m)
        row = c.waves(np.array([m]))[0]
        n = int(row[4].real)
        if n == 0:
            return _bisect_change(c, lo, m, 2), _bisect_change(c, m, hi, 0)
        t = 0.5 * (min(abs(row[2].real), math.pi) + min(abs(row[3].real), math.pi))
        after = c.phase_span(ea, m, t) if n == 2 else None
        if after is None:
            return None
        lo, hi = (m, hi) if after == 0 else (lo, m)


def _bisect_change(c: _Cell, a: float, b: float, na: int) -> float:
    """Where the number of propagating pairs changes from ``na`` (at a) in (a, b)."""
    return _bisect(lambda m: int(c.propagating(np.array([m]))[0]) == na, a, b)


def _bisect(same, a: float, b: float) -> float:
    """Where ``same`` (true at a, false at b; a > b allowed) turns false, to the last bit
    between them."""
    for _ in range(200):
        m = 0.5 * (a + b)
        if not min(a, b) < m < max(a, b):
            break
        if same(m):
            a = m
        else:
            b = m
    return 0.5 * (a + b)

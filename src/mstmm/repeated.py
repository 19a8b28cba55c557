"""The natural frequencies of N identical cells end to end (``repeat = N``) with a count and
a characteristic function that cost O(log N) each (``mstmm.numerics.doubling``: the cell's
transfer squared, its dynamic stiffness doubled), so that a cluster of N roots costs
O(N log N) instead of N walks over N components.

:func:`mstmm.solve` takes this path for a repeated scene of at least :data:`MIN_CELLS`
cells, all the same (not graded), undamped, in the stable formulation, whose cell has a
transfer matrix (no component that constrains the state: a support, a pinned joint), and
whose waves grow by at most exp(MAX_GROWTH) across a cell up to the top root (else its
transfer keeps too few digits: thousands of modes of 500 cells); any other scene, and one
where this path cannot start, goes through the general search.
Every root is isolated by the Wittrick-Williams count over the cells (each cell clamped at
both ends: its kernel's own count) and certified as in the general search; Brent's method
on the characteristic function refines it. Mode shapes, modal masses and everything after
the frequencies come from the expanded scene's kernel as before.
"""

from __future__ import annotations

import math

import numpy as np

from .catalog import END_CODES, KNOWN_ZERO
from .kernels import Kernel, load_kernel, numerics
from .physics import segment as segment_terms
from .scan import BAND_EDGE, Root, Roots
from .scene import Scene, scene_from_dict, scene_to_dict
from .topology import parameter_vector, topology_of

#: Fewest cells for which this path is taken: one evaluation costs about 10 us here against
#: 25 ns a component in the general walk, so below some hundreds of cells the general
#: search is as fast, and it needs no more compiling on a machine's first run.
MIN_CELLS = DEFAULT_MIN_CELLS = 500


#: The shared driver of this path (``numerics.entries.entry_repeated_search``; the cell
#: kernel's functions it calls: ``numerics.entries.DRIVERS``).
DRIVER = "repeated_search"
#: Python time a root of this path costs while its driver compiles in a helper, for
#: ``compiling.python_instead`` (measured: 12 ms a root, 1,000 metamaterial cells).
PYTHON_SECONDS_PER_ROOT = 0.02


class Chain:
    """A repeated scene's cell clamped at both ends (its kernel and parameters) and the end
    displacements the structure's end conditions leave free."""

    def __init__(self, scene: Scene):
        cell = scene.cell
        d = scene_to_dict(cell)
        d["beam"]["left"] = d["beam"]["right"] = "clamped"
        d["name"] = f"{cell.name}_clamped_cell"
        self.cell = scene_from_dict(d, source=cell.source)
        self.n_cells = int(scene.repeat)
        self.kernel: Kernel = load_kernel(topology_of(self.cell))
        self.p = np.ascontiguousarray(parameter_vector(self.cell), dtype=np.float64)
        free = [i for i in (0, 1) if i not in KNOWN_ZERO[scene.beam.left]]
        free += [2 + i for i in (0, 1) if i not in KNOWN_ZERO[scene.beam.right]]
        self.free = np.array(free + [-1] * (4 - len(free)), dtype=np.int64)
        n = numerics()
        left, right = END_CODES.index(scene.beam.left), END_CODES.index(scene.beam.right)
        self.ends = np.array([n.START_PAIR[left], n.END_PAIR[right]], dtype=np.int64)
        self.scale = _scale(scene)
        self._at = self.kernel.compiled("repeated_at")

    def at(self, omegas: np.ndarray) -> np.ndarray:
        """(J, mantissa, log, ok) at each omega (rad/s): the count of the whole structure
        below it and its characteristic function (``numerics.doubling.structure_at``)."""
        ws = np.ascontiguousarray(np.atleast_1d(omegas), dtype=np.float64)
        out = np.zeros((ws.size, 4))
        self._at(ws, self.p, self.n_cells, self.ends, self.free, out)
        return out

    def search(
        self, rigid: int, want: int, lo: float, hi: float, most: int
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, bool] | None:
        """The natural frequencies in (lo, hi], or (hi = 0) the lowest ``want`` of them
        counted with the ``rigid`` zero ones, at most ``most`` distinct values: (omega,
        multiplicity, not converged, certified); None where the search cannot start
        (``numerics.doubling.repeated_search``). Its driver compiles in a helper process
        on a machine's first run (``mstmm.compiling``)."""
        out = np.zeros(most)
        mult = np.zeros(most, dtype=np.int64)
        flags = np.zeros(most, dtype=np.int64)
        args = (self.p, self.n_cells, self.ends, self.free, int(rigid), int(want), float(lo))
        args += (float(hi), self.scale, out, mult, flags)

        def body(call):
            out[:], mult[:], flags[:] = 0.0, 0, 0
            return call(DRIVER, *args)

        # its Python copy around the cell kernel's compiled functions while a helper
        # compiles the driver, else compiled (never the interpreted tier: modes None)
        cost = PYTHON_SECONDS_PER_ROOT * max(most, 1)
        k, certified, started = self.kernel.run(
            body, self.p, None, what=DRIVER, driver=DRIVER, cost=cost
        )
        if not started:
            return None
        return out[:k], mult[:k], flags[:k].astype(bool), bool(certified)

    def count_below(self, omegas: np.ndarray) -> np.ndarray:
        """The natural frequencies of the whole structure below each omega (-1: not
        defined there, a clamped-clamped frequency of a power of the cell)."""
        r = self.at(omegas)
        return np.where(r[:, 3] == 1.0, r[:, 0], -1).astype(np.int64)


def qualifies(scene: Scene) -> bool:
    """Whether :func:`mstmm.solve` takes this path for ``scene`` (in the stable formulation):
    at least :data:`MIN_CELLS` cells of one cell, not graded, undamped. A cell without a
    transfer matrix is found out by the search itself (:func:`find_roots` returns None)."""
    return (
        getattr(scene, "repeat", 1) >= max(2, MIN_CELLS)
        and scene.cell is not None
        and not scene.graded
        and not topology_of(scene).damped
    )


def chain_of(scene: Scene) -> Chain | None:
    """The :class:`Chain` of a scene that :func:`qualifies` (kept on the scene), else None."""
    known = scene.__dict__.get("_chain")
    if known is None:
        known = Chain(scene) if qualifies(scene) else False
        object.__setattr__(scene, "_chain", known)
    return known or None


#: The most a wave may grow across one cell, as ln: the cell's transfer, its second
#: compound and its stiffness are formed from entries ~exp(lam h) and keep eps exp(lam h)
#: of their smaller terms (a root 1.7e-11 off at lam h = 13.8, 8 cells, the 40th mode).
#: Above, the general search runs (thousands of modes of 500 cells).
MAX_GROWTH = 6.0


def growth(cell: Scene, w: float) -> float:
    """An upper bound on ln of how much a wave of the beam grows across ``cell`` at w
    (rad/s): the sum over its segments of lam l, lam = sqrt(T / EI) + ((mbar w^2 + k_w) /
    EI)^(1/4) with T the tension-like terms (a tensile axial force, a Pasternak layer) and
    k_w a Winkler foundation; shear deformation, rotary inertia and compression only lower
    it (``physics.segment.wavenumber_bound``, from the roles of its terms)."""
    b = cell.beam
    total = 0.0
    for s in b.segments or (b,):
        values = {t.name: getattr(s, t.name, 0.0) for t in segment_terms.terms()}
        lam = segment_terms.wavenumber_bound(values, s.EI, s.mass_per_length, w)
        total += lam * s.length
    return total


def _scale(scene: Scene) -> float:
    """The first bending frequency's scale of the whole bare beam, (pi / L)^2 sqrt(EI /
    mbar) (rad/s), of its first segment's properties."""
    b = scene.beam
    EI = b.segments[0].EI if b.segments else b.EI
    mbar = b.segments[0].mass_per_length if b.segments else b.mass_per_length
    return (math.pi / b.length) ** 2 * math.sqrt(EI / mbar)


def find_roots(
    scene: Scene,
    chain: Chain,
    rigid: int,
    *,
    modes: int | None = None,
    band: tuple[float, float] | None = None,
) -> Roots | None:
    """The lowest ``modes`` natural frequencies, or those in ``band`` (its edges inclusive
    by ``scan.BAND_EDGE``), as :func:`mstmm.scan.find_roots` gives them; ``rigid``: the
    number of zero frequencies (the expanded kernel's ``rigid_body_modes``). None where
    the cells' path cannot start (a cell without a transfer matrix) or would not be
    accurate (a wave grows by more than exp(MAX_GROWTH) across a cell below the top root):
    the general search runs instead."""
    roots: list[Root] = []
    if band is None:
        want = int(modes)
        if rigid and want > 0:
            roots.append(Root(0.0, rigid, True, "rigid"))
        found = chain.search(rigid, want, 0.0, 0.0, max(want - rigid, 0))
    else:
        a, b = band
        a, b = a * (1.0 - BAND_EDGE), b * (1.0 + BAND_EDGE)
        if a <= 0.0 and rigid:
            roots.append(Root(0.0, rigid, True, "rigid"))
        if growth(chain.cell, b) > MAX_GROWTH:
            return None
        n_band = int(chain.count_below(np.array([b]))[0])
        found = chain.search(rigid, 0, max(a, 0.0), b, max(n_band, 1))
    if found is None:
        return None
    w, m, bad, certified = found
    if w.size and growth(chain.cell, float(w[-1])) > MAX_GROWTH:
        return None
    roots += [Root(float(x), int(k), not f) for x, k, f in zip(w, m, bad)]
    notes: list[str] = []
    if band is None:
        have = sum(r.multiplicity for r in roots)
        if have < want:
            certified = False
            notes.append(f"the doubled count found {have} of the {want} roots asked for")
        while roots and have - roots[-1].multiplicity >= want:  # past the modes asked for
            have -= roots.pop().multiplicity
        if have > want:
            last = roots[-1]
            copies = last.multiplicity - (have - want)
            roots[-1] = Root(last.omega, last.multiplicity, last.converged, last.how, copies)
    if not certified:
        notes.append("the count of the repeated cells could not certify every root")
    return Roots(roots, certified, notes)

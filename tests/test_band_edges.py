"""Band edges are inclusive by 4 ulp: a root on an edge is reported exactly once.

The roots come from ``tests/reference_model.py`` (mpmath, 30 digits, global
assembly), independent of the kernels: each band edge is put exactly on the
nearest double of a root and 1-2 ulp either side of it (the root must be reported
exactly once), and on the wrong side by the tolerance (4 eps relative: 4-8 ulp
depending on the mantissa) plus 4 ulp for the refinement's error of an ulp or two
(the root must not be reported).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import reference_model as ref

import mstmm
from mstmm.scan import BAND_EDGE

ULP = [-2, -1, 0, 1, 2]


@pytest.fixture(scope="module")
def paper():
    sc = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    return sc, [float(w) for w in ref.frequencies(sc, 6, dps=30)]


def shifted(x: float, ulps: int) -> float:
    """``x`` moved by ``ulps`` units in the last place."""
    return x + ulps * math.ulp(x)


def hits(sol, root: float) -> int:
    """Values of the solution within 4e-16 relative of ``root``."""
    return int(np.sum(np.abs(sol.omega - root) <= 4e-16 * root))


def test_band_edge_tolerance_is_four_ulp():
    assert BAND_EDGE == 4 * np.finfo(float).eps


@pytest.mark.parametrize("mode", [0, 2, 4])
@pytest.mark.parametrize("ulps", ULP)
def test_root_on_the_lower_edge_is_reported_once(paper, mode, ulps):
    sc, roots = paper
    root = roots[mode]
    sol = mstmm.solve(sc, band=(shifted(root, ulps), 1.001 * root), shapes=False)
    assert sol.count_checked, sol.warnings
    assert hits(sol, root) == 1, (list(sol.omega), root)
    assert len(sol.omega) == 1


@pytest.mark.parametrize("mode", [0, 2, 4])
@pytest.mark.parametrize("ulps", ULP)
def test_root_on_the_upper_edge_is_reported_once(paper, mode, ulps):
    sc, roots = paper
    root = roots[mode]
    sol = mstmm.solve(sc, band=(0.999 * root, shifted(root, ulps)), shapes=False)
    assert sol.count_checked, sol.warnings
    assert hits(sol, root) == 1, (list(sol.omega), root)
    assert len(sol.omega) == 1


@pytest.mark.parametrize("mode", [0, 2, 4])
def test_band_of_one_root_between_adjacent_edges(paper, mode):
    """Both edges within an ulp of the root: [r - ulp, r + ulp] and [r, r]."""
    sc, roots = paper
    root = roots[mode]
    for lo, hi in [(shifted(root, -1), shifted(root, 1)), (root, root)]:
        sol = mstmm.solve(sc, band=(lo, hi), shapes=False)
        assert len(sol.omega) == 1 and hits(sol, root) == 1, (lo, hi, list(sol.omega))


@pytest.mark.parametrize("mode", [0, 2, 4])
def test_root_beyond_the_tolerance_is_not_reported(paper, mode):
    sc, roots = paper
    root = roots[mode]
    away = math.ceil(BAND_EDGE * root / math.ulp(root)) + 4
    above = mstmm.solve(sc, band=(shifted(root, away), 1.001 * root), shapes=False)
    below = mstmm.solve(sc, band=(0.999 * root, shifted(root, -away)), shapes=False)
    for sol in (above, below):
        assert sol.count_checked, sol.warnings
        assert hits(sol, root) == 0 and len(sol.omega) == 0, list(sol.omega)


def test_band_edges_in_the_paper_formulation(paper):
    """The paper's determinant goes through the same band search."""
    sc, roots = paper
    root = roots[0]
    for ulps in ULP:
        sol = mstmm.solve(
            sc, band=(shifted(root, ulps), 1.001 * root), formulation="paper", shapes=False
        )
        assert len(sol.omega) == 1 and abs(sol.omega[0] - root) < 1e-13 * root


BANDS = [
    # (left, right, attachments, band): a 6-fold root inside the band, a band from 0 with
    # two rigid-body zeros, a band starting above the lowest scan node, close roots
    ("clamped", "free", [(0.5, 100.0, 1.0)] * 7, (5.0, 60.0)),
    ("free", "free", [(0.3, 50.0, 0.5)], (0.0, 400.0)),
    ("pinned", "sliding", [(0.2, 1e4, 0.1), (0.7, 10.0, 2.0)], (30.0, 3000.0)),
    ("pinned", "pinned", [(0.3, (2 * math.pi) ** 4 * 0.01, 0.01)] * 2, (10.0, 100.0)),
]


@pytest.mark.parametrize("left, right, atts, band", BANDS)
def test_band_matches_the_reference_band(left, right, atts, band):
    """Every root of a band, with multiplicity, against the reference's own band search."""
    from test_roots import make

    sc = make(left, right, atts)
    exact = [float(w) for w in ref.band(sc, *band, dps=30)]
    sol = mstmm.solve(sc, band=band, shapes=False)
    assert sol.count_checked and sol.converged.all(), sol.warnings
    assert len(sol.omega) == len(exact), (list(sol.omega), exact)
    for got, want in zip(sol.omega, exact):
        assert got == 0.0 if want == 0.0 else abs(got - want) <= 1e-12 * want, (got, want)

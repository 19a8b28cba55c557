"""Many modes: the block-by-block search (one count per block) against the reference count.

The cost is measured in ``benchmarks/many_modes.py``, not here. These tests check
that a search spanning several blocks (``mstmm.kernels.BLOCK_MODES`` each, at
least) returns exactly the roots of ``tests/reference_model.py``'s own
Wittrick-Williams count (mpmath, independent of the kernels) at sample modes.
"""

from __future__ import annotations

import numpy as np
import pytest
import reference_model as ref
from eigenspaces import check_shapes

import mstmm
from mstmm import progress
from mstmm.kernels import BLOCK_MODES

N = 2000
WINDOW = 1e-9


@pytest.fixture(scope="module")
def paper():
    return mstmm.load_scene(mstmm.example_path("wu_chou_1998"))


def test_two_thousand_modes_match_the_reference_count(paper):
    assert N > 4 * BLOCK_MODES  # several blocks
    sol = mstmm.solve(paper, modes=N, shapes=False)
    assert len(sol.omega) == N
    assert np.all(np.diff(sol.omega) > 0.0)
    assert sol.count_checked and sol.converged.all(), sol.warnings
    assert not sol.truncated
    for i in [0, BLOCK_MODES - 1, BLOCK_MODES, 999, N - 1]:
        w = float(sol.omega[i])
        below = ref.count_below(paper, w * (1 - WINDOW), dps=30)
        above = ref.count_below(paper, w * (1 + WINDOW), dps=30)
        assert below == i and above == i + 1, (i, w, below, above)


def test_blocks_across_a_multiple_root_keep_every_copy():
    """Seven identical oscillators at one point tuned far up (mode ~ 400): the 6-fold root
    falls inside a block of the block-by-block search."""
    from test_roots import make

    w = 1.6e6  # rad/s, about the 400th mode of a unit beam
    m = 1e-3
    sc = make("pinned", "free", [(0.37, w * w * m, m)] * 7)
    below = ref.count_below(sc, w * (1 - WINDOW), dps=30)
    above = ref.count_below(sc, w * (1 + WINDOW), dps=30)
    assert above - below == 6 and below > BLOCK_MODES
    sol = mstmm.solve(sc, modes=above + 5)
    check_shapes(sc, sol)
    assert sol.count_checked, sol.warnings
    hit = np.flatnonzero(np.abs(sol.omega - w) <= 1e-12 * w)
    assert list(hit) == list(range(below, above))
    assert list(sol.multiplicity[hit]) == [6] * 6
    for i in [below - 1, above]:
        wi = float(sol.omega[i])
        assert ref.count_below(sc, wi * (1 - WINDOW), dps=30) <= i
        assert ref.count_below(sc, wi * (1 + WINDOW), dps=30) >= i + 1


def test_progress_bar_is_drawn_between_blocks(paper, monkeypatch, capsys):
    monkeypatch.setattr(progress, "enabled", True)
    mstmm.solve(paper, modes=3 * BLOCK_MODES, shapes=False)
    err = capsys.readouterr().err
    assert f"{3 * BLOCK_MODES}/{3 * BLOCK_MODES}" in err
    assert err.count("\rmstmm: modes [") >= 3

"""Numerical stability on extreme cases: the default formulation against the independent reference.

The cases are data in ``benchmarks/cases.py`` (shared with ``python -m
benchmarks.stability``, which writes ``docs/stability.md`` from the same
:func:`benchmarks.cases.compare`): springs 1e-6 .. 1e12 EI/L^3, masses 1e-6 ..
1e6 mbar L, attachments at x = 0 and x = L, two attachments 1e-9 L apart,
several at one x, 1000 attachments, the paper's example up to its 100th mode,
all 16 pairs of end conditions, free-free with its two zero frequencies, beams
of other scales. Each must hold its tolerance (1e-12 where well conditioned,
1e-10 otherwise) against ``tests/reference_model.py``; reference frequencies are
computed once per session (module-level memo in ``benchmarks.cases``), never
stored on disk.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from eigenspaces import check_shapes  # noqa: E402

import mstmm  # noqa: E402
from benchmarks.cases import CASES, compare, reference, solution  # noqa: E402
from benchmarks.cases import rm as reference_model  # noqa: E402

RIGID = [c for c in CASES if reference_model.rigid_body_mode_count(c.scene) > 0]


def test_cases_cover_the_issue():
    """The list holds every condition the issue names (guards against silent pruning)."""
    pairs = {(c.scene["beam"]["left"], c.scene["beam"]["right"]) for c in CASES}
    assert len(pairs) == 16
    atts = [a for c in CASES for a in c.scene["attachments"]]
    beams = [c.scene["beam"] for c in CASES]

    def dimless(c, a):
        b = c.scene["beam"]
        return (
            a["k"] * b["length"] ** 3 / b["EI"],
            a["m"] / (b["mass_per_length"] * b["length"]),
        )

    K = [dimless(c, a)[0] for c in CASES for a in c.scene["attachments"]]
    M = [dimless(c, a)[1] for c in CASES for a in c.scene["attachments"]]
    assert min(K) <= 1e-6 * (1 + 1e-9) and max(K) >= 1e12 * (1 - 1e-9)
    assert min(M) <= 1e-6 * (1 + 1e-9) and max(M) >= 1e6 * (1 - 1e-9)
    assert any(a["x"] == 0.0 for a in atts)
    assert any(a["x"] == c.scene["beam"]["length"] for c in CASES for a in c.scene["attachments"])
    gaps = [
        np.diff(sorted({a["x"] for a in c.scene["attachments"]})).min() / c.scene["beam"]["length"]
        for c in CASES
        if len({a["x"] for a in c.scene["attachments"]}) > 1
    ]
    assert min(gaps) <= 1.01e-9
    assert any(
        len(c.scene["attachments"]) > len({a["x"] for a in c.scene["attachments"]}) for c in CASES
    )
    assert max(len(c.scene["attachments"]) for c in CASES) >= 1000
    assert max(c.modes for c in CASES) >= 100
    assert any(
        c.modes >= 100 and c.build() == mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
        for c in CASES
    )
    assert {0.01, 100.0} <= {b["length"] for b in beams}
    assert {1.0, 1e9} <= {b["EI"] for b in beams}
    assert any(
        c.scene["beam"]["left"] == c.scene["beam"]["right"] == "free" and c.modes > 2 for c in CASES
    )
    assert all(c.tol in (1e-12, 1e-10) for c in CASES)


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.name)
def test_default_formulation_matches_reference(case):
    comp = compare(case, "stable")
    assert comp.max_rel_error <= case.tol, comp.describe()
    assert comp.passed, comp.describe()  # count, zeros exactly 0, ascending, converged
    sol, _ = solution(case, "stable")  # the default path: mode shapes too
    check_shapes(case.build(), sol)


@pytest.mark.parametrize("case", RIGID, ids=lambda c: c.name)
def test_zero_frequencies_are_exactly_zero(case):
    """Rigid-body modes: exact zeros in the reference, the default and the paper's formulation."""
    n_rigid = reference_model.rigid_body_mode_count(case.scene)
    ref = reference(case).omega
    assert [w == 0 for w in ref[: n_rigid + 1]] == [True] * n_rigid + [False]
    stable = compare(case, "stable").omega
    assert stable[:n_rigid].tolist() == [0.0] * n_rigid and stable[n_rigid] > 0.0
    # the paper's det U_bar on the lowest modes only (it loses ~1 digit per pi of lam L)
    paper = mstmm.solve(case.build(), modes=n_rigid + 2, formulation="paper", shapes=False)
    assert paper.omega[:n_rigid].tolist() == [0.0] * n_rigid
    assert np.all(paper.omega[n_rigid:] > 0.0)
    assert paper.omega.size == n_rigid + 2

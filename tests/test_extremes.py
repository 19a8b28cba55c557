"""Numerical stability on extreme cases: the default formulation against the independent reference.

The cases are data in ``benchmarks/cases.py`` (shared with ``python -m
benchmarks.stability``, which writes ``docs/stability.md`` from the same
:func:`benchmarks.cases.compare`): springs 1e-6 .. 1e12 EI/L^3, masses 1e-6 ..
1e6 mbar L, attachments at x = 0 and x = L, two attachments 1e-9 L apart,
several at one x, 1000 attachments, the paper's example up to its 100th mode,
all 16 pairs of end conditions, free-free with its two zero frequencies, beams
of other scales; and the component library's extremes (issue 13): springs to ground
from 1e-6 to 1e12 EI/L^3, rotary inertia 1e3 mbar L^3, segments with EI ratios of 1e6,
a hinge 1e-9 L from a support, 20 identical chains at one point, every kind at extreme
values on one stepped beam. Each must hold its tolerance (1e-12 where well conditioned,
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

#: The spring-mass cases (issue 3); the component library's are named kind_*.
BASE = [c for c in CASES if not c.name.startswith("kind_")]
RIGID = [c for c in CASES if reference_model.rigid_body_mode_count(c.scene) > 0]


def test_cases_cover_the_issue():
    """The list holds every condition issue 3 names (guards against silent pruning)."""
    pairs = {(c.scene["beam"]["left"], c.scene["beam"]["right"]) for c in BASE}
    assert len(pairs) == 16
    atts = [a for c in BASE for a in c.scene["attachments"]]
    beams = [c.scene["beam"] for c in BASE]

    def dimless(c, a):
        b = c.scene["beam"]
        return (
            a["k"] * b["length"] ** 3 / b["EI"],
            a["m"] / (b["mass_per_length"] * b["length"]),
        )

    spring_masses = [
        (c, a) for c in BASE for a in c.scene["attachments"] if a["type"] == "spring_mass"
    ]
    K = [dimless(c, a)[0] for c, a in spring_masses]
    M = [dimless(c, a)[1] for c, a in spring_masses]
    assert min(K) <= 1e-6 * (1 + 1e-9) and max(K) >= 1e12 * (1 - 1e-9)
    assert min(M) <= 1e-6 * (1 + 1e-9) and max(M) >= 1e6 * (1 - 1e-9)
    assert any(a["x"] == 0.0 for a in atts)
    assert any(a["x"] == c.scene["beam"]["length"] for c in BASE for a in c.scene["attachments"])
    gaps = [
        np.diff(sorted({a["x"] for a in c.scene["attachments"]})).min() / c.scene["beam"]["length"]
        for c in BASE
        if len({a["x"] for a in c.scene["attachments"]}) > 1
    ]
    assert min(gaps) <= 1.01e-9
    assert any(
        len(c.scene["attachments"]) > len({a["x"] for a in c.scene["attachments"]}) for c in BASE
    )
    assert max(len(c.scene["attachments"]) for c in BASE) >= 1000
    assert max(c.modes for c in BASE) >= 100
    assert any(
        c.modes >= 100 and c.build() == mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
        for c in BASE
    )
    assert {0.01, 100.0} <= {b["length"] for b in beams}
    assert {1.0, 1e9} <= {b["EI"] for b in beams}
    assert any(
        c.scene["beam"]["left"] == c.scene["beam"]["right"] == "free" and c.modes > 2 for c in BASE
    )
    assert all(c.tol in (1e-12, 1e-10) for c in BASE)


def test_kind_cases_cover_the_issue():
    """Issue 13's extremes, on unit beams (values are in EI/L^3, EI/L, mbar L^3), each held
    to 1e-12."""
    kind = [c for c in CASES if c.name.startswith("kind_")]
    atts = [a for c in kind for a in c.scene["attachments"]]
    springs = [a["k"] for a in atts if a["type"] == "spring"]
    assert min(springs) <= 1e-6 and max(springs) >= 1e12
    assert max(a.get("J", 0.0) for a in atts if a["type"] == "mass") >= 1e3
    ratios = [
        max(s["EI"] for s in c.scene["beam"]["segments"])
        / min(s["EI"] for s in c.scene["beam"]["segments"])
        for c in kind
        if "segments" in c.scene["beam"]
    ]
    assert max(ratios) >= 1e6
    gaps = [
        abs(h["x"] - s["x"])
        for c in kind
        for h in c.scene["attachments"]
        if h["type"] == "hinge"
        for s in c.scene["attachments"]
        if s["type"] == "support"
    ]
    assert min(gaps) <= 1.01e-9
    chains = [
        sum(a["type"] == "oscillator_chain" and a["x"] == x for a in c.scene["attachments"])
        for c in kind
        for x in {a["x"] for a in c.scene["attachments"]}
    ]
    assert max(chains) >= 20
    assert all(c.tol == 1e-12 for c in kind)


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

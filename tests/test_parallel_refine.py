"""Roots refined in parallel after the search, and serially in a thread.

Among many components each evaluation of the characteristic function walks them all, and
Brent's method on the roots a block writes was most of a search (``docs/clusters.md``):
from ``kernels.DEFER_EVENTS`` components on, ``Kernel.lowest`` on the main thread leaves
each sign change's bracket pending and refines them all afterwards on numba's threads
(``numerics.entries.entry_refine_pending``, an entry called from Python). In another
Python thread it refines them itself (numba's workqueue layer must not start parallel
work from two threads at once). Both against the mpmath reference model (independent of
mstmm), through the default solve (mode shapes on).
"""

from __future__ import annotations

import math
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).parent))
import reference_model as rm  # noqa: E402

import mstmm  # noqa: E402
from mstmm import compiling, interpret, kernels  # noqa: E402
from mstmm.numerics import entries  # noqa: E402
from mstmm.topology import parameter_vector  # noqa: E402

MODES = 6


def _scene() -> dict:
    """The paper's cantilever (L = 1, EI = mbar = 1 here) with DEFER_EVENTS + 40 random
    spring-masses whose own frequencies lie among its lowest modes."""
    n = kernels.DEFER_EVENTS + 40
    rng = np.random.default_rng(23)
    x = rng.uniform(0.0, 1.0, n)
    m = rng.uniform(0.5, 1.5, n) / (2 * n)
    w = np.exp(rng.uniform(math.log(3.5), math.log(200.0), n))
    beam = {"length": 1.0, "EI": 1.0, "mass_per_length": 1.0, "left": "clamped"}
    atts = [
        {"type": "spring_mass", "x": float(a), "k": float(c * b * b), "m": float(c)}
        for a, b, c in zip(x, w, m)
    ]
    return {"name": "parallel_refine", "beam": beam | {"right": "free"}, "attachments": atts}


@pytest.fixture(scope="module")
def exact() -> np.ndarray:
    return np.array([float(w) for w in rm.frequencies(_scene(), MODES, dps=30)])


def _solve() -> tuple[mstmm.Solution, bool]:
    scene = mstmm.scene_from_dict(_scene())
    defers = kernels.Kernel._defers(parameter_vector(scene))
    return mstmm.solve(scene, modes=MODES), defers


def test_roots_refined_in_parallel_on_the_main_thread_match_the_reference(exact):
    budget = interpret._Process.budget
    interpret.set_budget(0.0)  # compiled: the search and the parallel refinement
    compiling.wait("lowest")  # not the search as Python while a helper compiles it
    try:
        sol, defers = _solve()
    finally:
        interpret.set_budget(budget)
    assert defers and entries.entry_refine_pending.signatures  # the parallel path ran
    assert sol.count_checked and not sol.warnings, sol.warnings
    assert np.max(np.abs(sol.omega - exact) / exact) <= 1e-12
    assert sol.shapes is not None and len(sol.shapes) == MODES


def test_roots_refined_in_another_thread_match_the_reference(exact):
    budget = interpret._Process.budget
    interpret.set_budget(0.0)
    try:
        with ThreadPoolExecutor(2) as pool:
            done = [pool.submit(_solve) for _ in range(2)]  # two solves at once
            results = [f.result() for f in done]
    finally:
        interpret.set_budget(budget)
    for sol, defers in results:
        assert not defers
        assert sol.count_checked and not sol.warnings, sol.warnings
        assert np.max(np.abs(sol.omega - exact) / exact) <= 1e-12

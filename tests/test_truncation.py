"""``modes=N`` cutting through a multiple root: the true multiplicity, and a warning.

The multiplicity is checked against the count of ``tests/reference_model.py``
(mpmath, global assembly), independent of the kernels: the reference count
jumps across the root by exactly the multiplicity reported.
"""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
import reference_model as ref
from test_roots import make

import mstmm

K, M = 100.0, 1.0
W = 10.0  # sqrt(K / M), rad/s
DELTA = 1e-9


def cluster(count: int, left: str = "clamped", right: str = "free"):
    """``count`` identical spring-masses at x = 0.5: sqrt(k/m) has multiplicity count - 1."""
    return make(left, right, [(0.5, K, M)] * count)


def reference_jump(sc, w: float) -> tuple[int, int]:
    """Reference count just below and just above ``w``."""
    return (
        ref.count_below(sc, w * (1 - DELTA), dps=30),
        ref.count_below(sc, w * (1 + DELTA), dps=30),
    )


def check_cut(sol, sc, copies: int) -> None:
    """The solution ends with ``copies`` copies of sqrt(k/m), reported with its true
    multiplicity, flagged as truncated."""
    below, above = reference_jump(sc, W)
    assert len(sol.omega) == below + copies
    assert all(abs(w - W) < 1e-13 * W for w in sol.omega[-copies:])
    assert list(sol.multiplicity[-copies:]) == [above - below] * copies
    assert above - below > copies
    assert sol.truncated
    assert sol.count_checked
    assert any(f"multiplicity {above - below}" in w for w in sol.warnings), sol.warnings
    assert sol.to_dict()["truncated"] is True


@pytest.mark.parametrize("copies", [1])
def test_double_root_cut_at_its_first_copy(copies, tier):
    sc = cluster(3)
    below, _ = reference_jump(sc, W)
    sol = mstmm.solve(sc, modes=below + copies, shapes=False)
    check_cut(sol, sc, copies)


def test_sixfold_root_cut_at_its_third_copy(tier):
    sc = cluster(7)
    below, _ = reference_jump(sc, W)
    sol = mstmm.solve(sc, modes=below + 3, shapes=False)
    check_cut(sol, sc, 3)


def test_paper_formulation_reports_the_true_multiplicity_too():
    """The general search (scan.find_roots) cuts the same way."""
    sc = cluster(7)
    below, _ = reference_jump(sc, W)
    sol = mstmm.solve(sc, modes=below + 3, formulation="paper", shapes=False)
    check_cut(sol, sc, 3)


def test_all_copies_asked_for_is_not_truncated():
    sc = cluster(7)
    below, above = reference_jump(sc, W)
    sol = mstmm.solve(sc, modes=above, shapes=False)
    assert len(sol.omega) == above
    assert list(sol.multiplicity[below:]) == [above - below] * (above - below)
    assert not sol.truncated
    assert not any("multiplicity" in w for w in sol.warnings)


def test_free_free_one_mode_is_a_rigid_body_zero_of_multiplicity_two(tier):
    sc = make("free", "free", [], L=2.0, EI=3.0, mbar=0.5)
    sol = mstmm.solve(sc, modes=1, shapes=False)
    assert list(sol.omega) == [0.0]
    assert list(sol.multiplicity) == [ref.rigid_body_mode_count(sc)] == [2]
    assert sol.truncated
    assert any("multiplicity 2" in w for w in sol.warnings)


def test_cli_json_reports_the_cut(tmp_path):
    sc_path = tmp_path / "cluster.toml"
    lines = [
        "[beam]",
        "length = 1.0",
        "EI = 1.0",
        "mass_per_length = 1.0",
        'left = "clamped"',
        'right = "free"',
    ]
    for _ in range(7):
        lines += ["[[attachments]]", 'type = "spring_mass"', "x = 0.5", f"k = {K}", f"m = {M}"]
    sc_path.write_text("\n".join(lines) + "\n")
    sc = mstmm.load_scene(sc_path)
    below, above = reference_jump(sc, W)
    out = subprocess.run(
        [sys.executable, "-m", "mstmm", "solve", str(sc_path), "--modes", str(below + 3)]
        + ["--format", "json"],
        capture_output=True,
        text=True,
        check=True,
    )
    res = json.loads(out.stdout)
    assert len(res["omega"]) == below + 3
    assert res["multiplicity"][-3:] == [above - below] * 3
    assert res["truncated"] is True
    assert f"multiplicity {above - below}" in out.stderr

"""The acceptance of the pipeline: every bundled scene against the independent references.

``tests/data/reference.json`` is ``../shared/reference/reference.json``: global
assembly of the exact segment solutions in 50-digit mpmath, independent of MSTMM.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy as np
import pytest
from eigenspaces import check_shapes

import mstmm

SCENES = ["wu_chou_1998", "bare_cantilever"]


def rel_err(got, exact) -> np.ndarray:
    got, exact = np.asarray(got, float), np.asarray(exact, float)
    return np.abs(got - exact) / np.abs(exact)


@pytest.mark.parametrize("budget,mode", [("", "interpreted"), ("0", "compiled")])
@pytest.mark.parametrize("name", SCENES)
def test_cli_json_ten_modes_match_reference(name, budget, mode, reference, data_dir):
    """`mstmm solve SCENE --modes 10 --format json`: all within 1e-10 (we hold 1e-13).

    A fresh process runs this small solve as Python (mstmm.interpret) unless
    ``MSTMM_INTERPRET_BUDGET=0``: both against the reference."""
    env = {k: v for k, v in os.environ.items() if k != "MSTMM_INTERPRET_BUDGET"}
    if budget:
        env["MSTMM_INTERPRET_BUDGET"] = budget
    out = subprocess.run(
        [
            sys.executable,
            "-m",
            "mstmm",
            "solve",
            str(data_dir / f"{name}.toml"),
            "--modes",
            "10",
            "--format",
            "json",
        ],
        capture_output=True,
        text=True,
        check=True,
        env=env,
    )
    result = json.loads(out.stdout)
    assert result["kernel_mode"] == mode
    assert len(result["omega"]) == 10
    assert np.all(np.diff(result["omega"]) > 0)
    assert rel_err(result["omega"], reference[name]).max() < 1e-13
    assert np.allclose(np.array(result["hz"]) * 2 * np.pi, result["omega"], rtol=1e-15)
    assert all(result["converged"]) and result["warnings"] == []
    assert {"load", "scan_refine"} <= set(result["timings"])


def test_default_scene_is_the_paper_example(reference):
    out = subprocess.run(
        [sys.executable, "-m", "mstmm", "solve", "--format", "csv", "--modes", "5"],
        capture_output=True,
        text=True,
        check=True,
    )
    rows = out.stdout.strip().splitlines()
    assert rows[0].startswith("mode,omega [rad/s],f [Hz]")
    omega = [float(r.split(",")[1]) for r in rows[1:]]
    assert rel_err(omega, reference["wu_chou_1998"][:5]).max() < 1e-13


def test_paper_formulation_reproduces_table_1(reference):
    """The paper's det U_bar as printed is exact on the low modes it reports (Table 1)."""
    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    sol = mstmm.solve(scene, modes=5, formulation="paper", shapes=False)
    assert rel_err(sol.omega, reference["wu_chou_1998"][:5]).max() < 1e-13


def test_band_returns_every_frequency_inside(reference):
    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    ref = np.array(reference["wu_chou_1998"])
    sol = mstmm.solve(scene, band=(150.0, 8000.0))
    check_shapes(scene, sol)
    inside = ref[(ref > 150) & (ref < 8000)]
    assert len(sol.omega) == len(inside)
    assert rel_err(sol.omega, inside).max() < 1e-13


def test_kernel_reused_for_other_parameters(reference):
    """One compiled kernel serves any parameter vector of its topology."""
    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    kernel = mstmm.kernel_for(scene)
    bare = mstmm.load_scene(mstmm.example_path("bare_cantilever"))
    # the bare beam as a spring-mass scene with a vanishing mass: same kernel, bare frequencies
    p = mstmm.parameter_vector(bare)
    p = np.concatenate([p, [0.5, 1e3, 1e-30]])
    sol = mstmm.solve(
        bare.replace(attachments=[{"type": "spring_mass", "x": 0.5, "k": 1e3, "m": 1e-30}]),
        modes=5,
        shapes=False,
        kernel=kernel,
    )
    assert rel_err(sol.omega, reference["bare_cantilever"][:5]).max() < 1e-13
    mant, _ = kernel.evaluate(np.array([reference["bare_cantilever"][0]]), p)
    assert abs(mant[0]) < 1e-10

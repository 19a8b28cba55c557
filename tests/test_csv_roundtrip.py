"""Every CSV mstmm writes reads back (issue 20, item 13): ``mstmm.output.read_csv``.

Each test runs the command line twice, ``--format csv`` and ``--format json`` (the same
scene and options), reads the CSV back and compares it with the JSON: frequencies,
damped frequencies, undamped and damped mode shapes (``read_shapes_csv`` too), frf and
sweep. CSV numbers are written as ``repr(float)``: the comparison is exact.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from mstmm.output import read_csv, read_shapes_csv

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
DAMPED = str(EXAMPLES / "tmd_den_hartog.toml")


def _both(*args: str) -> tuple[dict, dict]:
    out = {}
    for fmt in ("csv", "json"):
        run = subprocess.run(
            [sys.executable, "-m", "mstmm", *args, "--format", fmt],
            capture_output=True,
            text=True,
            timeout=600,
        )
        assert run.returncode == 0, run.stderr
        out[fmt] = run.stdout
    return read_csv(out["csv"]), json.loads(out["json"]) | {"_csv_text": out["csv"]}


def test_frequencies():
    csv, js = _both("solve", "--modes", "6")
    assert csv["kind"] == "frequencies"
    np.testing.assert_array_equal(csv["omega_rad_s"], js["omega"])
    np.testing.assert_array_equal(csv["f_hz"], js["hz"])
    np.testing.assert_array_equal(csv["multiplicity"], js["multiplicity"])
    np.testing.assert_array_equal(csv["converged"], js["converged"])
    np.testing.assert_array_equal(csv["mode"], np.arange(1, 7))


def test_damped_frequencies():
    csv, js = _both("solve", DAMPED, "--modes", "3")
    assert csv["kind"] == "damped"
    for col, key in (
        ("w_d_rad_s", "w_d"),
        ("sigma_1_s", "sigma"),
        ("abs_omega_rad_s", "abs_omega"),
        ("zeta", "zeta"),
        ("f_d_hz", "hz"),
        ("multiplicity", "multiplicity"),
        ("converged", "converged"),
    ):
        np.testing.assert_array_equal(csv[col], js[key], err_msg=col)


def test_undamped_shapes():
    csv, js = _both("solve", "--modes", "4", "--shapes")
    assert csv["kind"] == "shapes"
    back = read_shapes_csv(js["_csv_text"])
    shapes = js["mode_shapes"]
    np.testing.assert_array_equal(back["omega"], js["omega"])
    np.testing.assert_array_equal(back["x"], shapes[0]["x"])
    np.testing.assert_array_equal(back["mass_x"], shapes[0]["mass_x"])
    assert back["Y"].shape == (len(shapes[0]["x"]), 4) and back["mass_Y"].shape == (3, 4)
    for j, s in enumerate(shapes):
        np.testing.assert_array_equal(back["Y"][:, j], s["Y"])
        np.testing.assert_array_equal(back["mass_Y"][:, j], s["mass_Y"])
        for key in ("modal_mass", "participation", "effective_mass", "multiplicity"):
            assert back[key][j] == s[key], key


def test_damped_shapes():
    """The damped ``--shapes --format csv`` (``damped_shapes_csv``): complex shapes."""
    csv, js = _both("solve", DAMPED, "--modes", "3", "--shapes")
    assert csv["kind"] == "damped_shapes"
    back = read_shapes_csv(js["_csv_text"])
    np.testing.assert_array_equal(back["omega"], np.array(js["w_d"]) + 1j * np.array(js["sigma"]))
    np.testing.assert_array_equal(back["zeta"], js["zeta"])
    shapes = js["mode_shapes"]
    assert np.iscomplexobj(back["Y"]) and back["Y"].shape == (len(shapes[0]["x"]), 3)
    np.testing.assert_array_equal(back["x"], shapes[0]["x"])
    np.testing.assert_array_equal(back["mass_x"], shapes[0]["mass_x"])
    for j, s in enumerate(shapes):
        np.testing.assert_array_equal(
            back["Y"][:, j], np.array(s["Y_re"]) + 1j * np.array(s["Y_im"])
        )
        np.testing.assert_array_equal(
            back["mass_Y"][:, j], np.array(s["mass_Y_re"]) + 1j * np.array(s["mass_Y_im"])
        )


def test_frf():
    csv, js = _both(
        "frf", DAMPED, "--input", "force:x=5.0", "--output", "displacement:x=5.0",
        "--output", "displacement:mass=0", "--band", "1", "20", "--points", "25",
    )  # fmt: skip
    assert csv["kind"] == "frf" and csv["outputs"] == js["outputs"]
    np.testing.assert_array_equal(csv["omega_rad_s"], js["omega"])
    np.testing.assert_array_equal(csv["f_hz"], js["hz"])
    H = np.array(js["re"]).T + 1j * np.array(js["im"]).T
    np.testing.assert_array_equal(csv["H"], H)
    np.testing.assert_allclose(csv["displacement:x=5.0_abs"], np.abs(H[:, 0]), rtol=1e-15)
    np.testing.assert_allclose(
        csv["displacement:mass=0_phase_deg"], np.degrees(np.angle(H[:, 1])), rtol=1e-13
    )


def test_sweep():
    """``sweep`` writes CSV only: compared with the API's sweep of the same points."""
    import mstmm

    scene = str(EXAMPLES / "wu_chou_1998.toml")
    run = subprocess.run(
        [sys.executable, "-m", "mstmm", "sweep", scene, "--modes", "3", "--vary",
         "attachments[2].k=LOG:1e3:1e9:7"],
        capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr
    csv = read_csv(run.stdout)
    ks = np.geomspace(1e3, 1e9, 7)
    assert csv["kind"] == "sweep" and csv["omega"].shape == (7, 3)
    np.testing.assert_allclose(csv["attachments[2].k"], ks, rtol=1e-15)
    omega = mstmm.sweep(mstmm.load_scene(scene), {"attachments[2].k": ks}, modes=3)
    np.testing.assert_allclose(csv["omega"], omega, rtol=1e-14)
    np.testing.assert_array_equal(csv["omega"][:, 0], csv["omega_1"])


def test_not_a_csv_of_mstmm():
    with pytest.raises(ValueError, match="not a"):
        read_csv("a,b\n1,2\n")
    with pytest.raises(ValueError, match="not a mode-shape CSV"):
        read_shapes_csv("mode,omega_rad_s,f_hz,multiplicity,converged\n1,2.0,0.3,1,True\n")

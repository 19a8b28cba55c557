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
    np.testing.assert_array_equal(csv["omega"], js["omega"])
    np.testing.assert_array_equal(csv["f"], js["hz"])
    assert csv["units"] == {"omega": "rad/s", "f": "Hz"}
    np.testing.assert_array_equal(csv["multiplicity"], js["multiplicity"])
    np.testing.assert_array_equal(csv["converged"], js["converged"])
    np.testing.assert_array_equal(csv["mode"], np.arange(1, 7))


def test_damped_frequencies():
    csv, js = _both("solve", DAMPED, "--modes", "3")
    assert csv["kind"] == "damped"
    for col, key in (
        ("w_d", "w_d"),
        ("sigma", "sigma"),
        ("abs_omega", "abs_omega"),
        ("zeta", "zeta"),
        ("f_d", "hz"),
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
        for name in ("Y", "theta", "M", "Q", "mass_Y"):
            np.testing.assert_array_equal(back[name][:, j], s[name], err_msg=name)
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
        for name in ("Y", "theta", "M", "Q", "mass_Y"):
            np.testing.assert_array_equal(
                back[name][:, j], np.array(s[f"{name}_re"]) + 1j * np.array(s[f"{name}_im"])
            )


def test_frf():
    csv, js = _both(
        "frf", DAMPED, "--input", "force:x=5.0", "--output", "displacement:x=5.0",
        "--output", "displacement:mass=0", "--band", "1", "20", "--points", "25",
    )  # fmt: skip
    assert csv["kind"] == "frf" and csv["outputs"] == js["outputs"]
    np.testing.assert_array_equal(csv["omega"], js["omega"])
    np.testing.assert_array_equal(csv["f"], js["hz"])
    assert csv["units"]["displacement:x=5.0_abs"] == "m/N"
    assert csv["units"]["displacement:mass=0_phase"] == "deg"
    H = np.array(js["re"]).T + 1j * np.array(js["im"]).T
    np.testing.assert_array_equal(csv["H"], H)
    np.testing.assert_allclose(csv["displacement:x=5.0_abs"], np.abs(H[:, 0]), rtol=1e-15)
    np.testing.assert_allclose(
        csv["displacement:mass=0_phase"], np.degrees(np.angle(H[:, 1])), rtol=1e-13
    )


def _sweep(scene: str, modes: str, vary: str) -> dict:
    """``mstmm sweep`` (it writes CSV only) read back."""
    run = subprocess.run(
        [sys.executable, "-m", "mstmm", "sweep", scene, "--modes", modes, "--vary", vary],
        capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr
    return read_csv(run.stdout)


def test_sweep():
    """``sweep`` writes CSV only: compared with the API's sweep of the same points."""
    import mstmm

    scene = str(EXAMPLES / "wu_chou_1998.toml")
    csv = _sweep(scene, "3", "attachments[2].k=LOG:1e3:1e9:7")
    ks = np.geomspace(1e3, 1e9, 7)
    assert csv["kind"] == "sweep" and csv["omega"].shape == (7, 3)
    np.testing.assert_allclose(csv["attachments[2].k"], ks, rtol=1e-15)
    omega = mstmm.sweep(mstmm.load_scene(scene), {"attachments[2].k": ks}, modes=3)
    np.testing.assert_allclose(csv["omega"], omega, rtol=1e-14)
    np.testing.assert_array_equal(csv["omega"][:, 0], csv["omega_1"])
    assert csv["units"]["attachments[2].k"] == "N/m" and csv["units"]["omega_1"] == "rad/s"


def test_not_a_csv_of_mstmm():
    with pytest.raises(ValueError, match="not a"):
        read_csv("a,b\n1,2\n")
    with pytest.raises(ValueError, match="not a mode-shape CSV"):
        read_shapes_csv("mode,omega [rad/s],f [Hz],multiplicity,converged\n1,2.0,0.3,1,True\n")


def test_bands():
    """``bands --format csv`` (the dispersion curves, k in 1/m) against its JSON."""
    csv, js = _both("bands", str(EXAMPLES / "wu_chou_1998.toml"), "--points", "40")
    assert csv["kind"] == "bands"
    np.testing.assert_array_equal(csv["omega"], js["omega"])
    np.testing.assert_array_equal(csv["propagating"], js["propagating"])
    k = np.array(js["k"])
    np.testing.assert_array_equal(csv["k"], k[:, :, 0] + 1j * k[:, :, 1])
    assert csv["units"] == {"omega": "rad/s", "f": "Hz"} | {
        f"{p}_k{i}": "1/m" for i in (1, 2) for p in ("re", "im")
    }


def test_damped_sweep():
    """A damped sweep's ``w_d_<i> [rad/s], sigma_<i> [1/s], zeta_<i> [-]`` read back as
    complex omega, against the API's sweep of the same points."""
    import mstmm

    csv = _sweep(DAMPED, "2", "attachments[0].c=1,10")
    assert csv["kind"] == "sweep" and csv["omega"].shape == (2, 2)
    assert csv["units"]["attachments[0].c"] == "N s/m" and csv["units"]["zeta_1"] == "-"
    omega = mstmm.sweep(mstmm.load_scene(DAMPED), {"attachments[0].c": [1.0, 10.0]}, modes=2)
    np.testing.assert_allclose(csv["omega"], omega, rtol=1e-14)


#: CSVs as mstmm wrote them before their headers carried units: still read.
LEGACY = {
    "frequencies": "mode,omega_rad_s,f_hz,multiplicity,converged\n1,2.0,0.5,1,True\n",
    "shapes": "mode,omega_rad_s,f_hz,multiplicity,converged,modal_mass_kg,participation,"
    "effective_mass_kg\n1,2.0,0.5,1,True,3.0,0.25,0.1875\n\nx,Y_1\n0.0,0.0\n1.0,1.0\n",
    "frf": "omega_rad_s,f_hz,d_re,d_im,d_abs,d_phase_deg\n1.0,0.25,0.0,-2.0,2.0,-90.0\n",
    "sweep": "beam.EI,omega_1,omega_2\n1.0,3.0,4.0\n",
    "damped": "mode,w_d_rad_s,sigma_1_s,abs_omega_rad_s,zeta,f_d_hz,multiplicity,converged\n"
    "1,3.0,4.0,5.0,0.8,0.5,1,True\n",
}


@pytest.mark.parametrize("kind", sorted(LEGACY))
def test_csv_written_before_units_reads_the_same(kind):
    csv = read_csv(LEGACY[kind])
    assert csv["kind"] == kind and csv["units"] == {}
    if kind in ("frequencies", "shapes", "frf"):
        assert csv["omega"][0] == (2.0 if kind != "frf" else 1.0)
    if kind == "shapes":
        back = read_shapes_csv(LEGACY[kind])
        assert back["Y"].tolist() == [[0.0], [1.0]] and "theta" not in back
        assert back["modal_mass"][0] == 3.0
    if kind == "frf":
        assert csv["H"][0, 0] == -2j and csv["d_phase"][0] == -90.0
    if kind == "sweep":
        assert csv["omega"].tolist() == [[3.0, 4.0]]
    if kind == "damped":
        assert csv["w_d"][0] == 3.0 and csv["sigma"][0] == 4.0

"""Units in every CSV header and the whole state [Y, theta, M, Q] in the shape CSV (issue 41,
"What an engineer misses").

The shape CSV's theta, M and Q are checked against the closed form of a pinned-pinned
uniform Euler-Bernoulli beam: mode n is Y = c sin(k x), k = n pi / L, with theta = Y',
M = EI Y'', Q = EI Y''' (the convention of the paper's state vector, README "Sign
conventions") and c = +-1 (the shape scaled to max |Y| = 1 m, its largest entry
positive: which of the equal peaks is largest is round-off, so c's sign is not asserted,
only that one c serves all four quantities).
"""

from __future__ import annotations

import csv
import io
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import mstmm
from mstmm.units import field_unit, frf_unit, split_header

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"

L, EI, MBAR = 2.0, 3.0, 1.5
PINNED = f"""
name = "pp"
[beam]
length = {L}
EI = {EI}
mass_per_length = {MBAR}
left = "pinned"
right = "pinned"
"""


def _blocks(text: str) -> list[list[list[str]]]:
    """The CSV's blocks, read with the csv module (not mstmm's reader)."""
    blocks = [[]]
    for row in csv.reader(io.StringIO(text)):
        if row:
            blocks[-1].append(row)
        else:
            blocks.append([])
    return [b for b in blocks if b]


def test_shape_csv_holds_y_theta_m_q_of_the_closed_form(tmp_path):
    scene = tmp_path / "pp.toml"
    scene.write_text(PINNED)
    out = tmp_path / "shapes.csv"
    run = subprocess.run(
        [sys.executable, "-m", "mstmm", "solve", str(scene), "--modes", "4", "--shapes",
         "--out", str(out)],
        capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip() == str(out)  # --out defaults to CSV, its name on stdout
    summary, points = _blocks(out.read_text())
    head = points[0]
    assert head[0] == "x [m]"
    values = np.array(points[1:], dtype=float)
    x = values[:, 0]
    column = {split_header(h)[0]: values[:, j] for j, h in enumerate(head)}
    units = dict(split_header(h) for h in head)
    omegas = [float(r[1]) for r in summary[1:]]
    for n in range(1, 5):
        k = n * math.pi / L
        assert omegas[n - 1] == pytest.approx(k * k * math.sqrt(EI / MBAR), rel=1e-13)
        exact = {
            "Y": np.sin(k * x),
            "theta": k * np.cos(k * x),
            "M": -EI * k**2 * np.sin(k * x),
            "Q": -EI * k**3 * np.cos(k * x),
        }
        c = float(np.dot(column[f"Y_{n}"], exact["Y"]) / np.dot(exact["Y"], exact["Y"]))
        assert abs(c) == pytest.approx(1.0, abs=1e-12)
        c = math.copysign(1.0, c)
        for name, unit in (("Y", "m"), ("theta", "rad"), ("M", "N m"), ("Q", "N")):
            assert units[f"{name}_{n}"] == unit
            scale = np.max(np.abs(exact[name]))
            np.testing.assert_allclose(
                column[f"{name}_{n}"], c * exact[name], atol=1e-12 * scale, err_msg=name
            )


def test_frequency_and_summary_headers_carry_units():
    run = subprocess.run(
        [sys.executable, "-m", "mstmm", "solve", "--modes", "2", "--shapes", "--format", "csv"],
        capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr
    summary, points, masses = _blocks(run.stdout)
    assert summary[0] == [
        "mode", "omega [rad/s]", "f [Hz]", "multiplicity", "converged",
        "modal_mass [kg m^2]", "participation [1/m]", "effective_mass [kg]",
    ]  # fmt: skip
    assert masses[0] == ["mass_x [m]", "Y_1 [m]", "Y_2 [m]"]
    # effective mass = participation^2 modal mass (kg from kg m^2 and 1/m)
    for row in summary[1:]:
        modal, gamma, effective = (float(v) for v in row[5:8])
        assert effective == pytest.approx(gamma * gamma * modal, rel=1e-14)


@pytest.mark.parametrize(
    "path, unit",
    [
        ("beam.EI", "N m^2"),
        ("beam.length", "m"),
        ("beam.mass_per_length", "kg/m"),
        ("beam.axial_force", "N"),
        ("beam.kappa_GA", "N"),
        ("beam.rho_I", "kg m"),
        ("beam.foundation_k", "N/m^2"),
        ("beam.foundation_kG", "N"),
        ("beam.loss_factor", "-"),
        ("beam.segments[1].axial_force", "N"),
        ("attachments[0].x", "m"),
        ("attachments[0].k", "N/m"),
        ("attachments[0].m", "kg"),
        ("attachments[0].c", "N s/m"),
    ],
)
def test_sweep_field_units(path, unit):
    scene = mstmm.load_scene(EXAMPLES / "tmd_den_hartog.toml")
    assert field_unit(scene, path) == unit


def test_sweep_over_axial_force_heads_its_column_in_newtons(tmp_path):
    scene = tmp_path / "pp.toml"
    scene.write_text(PINNED)
    run = subprocess.run(
        [sys.executable, "-m", "mstmm", "sweep", str(scene), "--modes", "1", "--vary",
         "beam.axial_force=0,10"],
        capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr
    head, *rows = list(csv.reader(io.StringIO(run.stdout)))
    assert head == ["beam.axial_force [N]", "omega_1 [rad/s]"]
    # a tensioned pinned-pinned beam: omega^2 mbar = EI k^4 + P k^2, k = pi / L
    k = math.pi / L
    for P, omega in ((float(r[0]), float(r[1])) for r in rows):
        assert omega == pytest.approx(math.sqrt((EI * k**4 + P * k**2) / MBAR), rel=1e-12)


@pytest.mark.parametrize(
    "quantity, response, load, unit",
    [
        ("receptance", "displacement", "force", "m/N"),
        ("receptance", "rotation", "moment", "rad/(N m)"),
        ("mobility", "displacement", "force", "m/s/N"),
        ("accelerance", "rotation", "force", "rad/s^2/N"),
    ],
)
def test_frf_units(quantity, response, load, unit):
    assert frf_unit(quantity, response, load) == unit

"""Mode shapes where a user looks: ``solve --shapes`` as JSON, CSV and table; plots of copies.

The writers are tested on solutions carrying made-up ``mstmm.modes.ModeShape``
values, so that they check the layout and the round trip, not the shapes; other
tests check real shapes against closed forms.
"""

from __future__ import annotations

import json
import math
import sys

import numpy as np
import pytest

import mstmm
from mstmm import output
from mstmm.cli import main
from mstmm.modes import ModeShape


def with_made_up_shapes(sol):
    """``sol`` with one made-up shape per entry of ``omega`` (sin waves, numbered)."""
    L = sol.scene.beam.length
    mass_x = np.array([a.x for a in sol.scene.attachments])
    x = np.unique(np.concatenate([np.linspace(0.0, L, 11), mass_x]))
    shapes = []
    for i, (w, m) in enumerate(zip(sol.omega, sol.multiplicity, strict=True), start=1):
        Y = np.sin(i * x / L)
        shapes.append(
            ModeShape(
                omega=float(w),
                x=x,
                Y=Y,
                theta=np.cos(i * x / L) * i / L,
                M=-Y * i,
                Q=Y * i * i,
                mass_x=mass_x,
                mass_Y=np.sin(i * mass_x / L) * 1.5,
                singular_ratio=1e-14 * i,
                modal_mass=2.0 * i,
                participation=0.5 / i,
                effective_mass=0.5 / i,
                multiplicity=int(m),
            )
        )
    sol.shapes = shapes
    return sol


@pytest.fixture(scope="module")
def scene():
    return mstmm.load_scene(mstmm.example_path("wu_chou_1998"))


@pytest.fixture
def solved(scene, monkeypatch):
    """The paper example's lowest 5 with made-up shapes; the CLI's solve returns it."""
    sol = with_made_up_shapes(mstmm.solve(scene, modes=5, shapes=False))
    monkeypatch.setattr(sys.modules["mstmm.solve"], "solve", lambda *a, **k: sol)
    return sol


def test_json_shapes_hold_every_field(solved, capsys):
    assert main(["solve", "--shapes", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert len(data["mode_shapes"]) == len(data["omega"]) == 5
    for got, shape in zip(data["mode_shapes"], solved.shapes, strict=True):
        assert got["hz"] == shape.omega / (2.0 * math.pi)
        for name in ("x", "Y", "theta", "M", "Q", "mass_x", "mass_Y"):
            assert got[name] == getattr(shape, name).tolist(), name
        for name in ("omega", "singular_ratio", "modal_mass", "participation", "effective_mass"):
            assert got[name] == getattr(shape, name), name
        assert got["multiplicity"] == shape.multiplicity


def test_csv_shapes_round_trip(solved, capsys):
    assert main(["solve", "--shapes", "--format", "csv"]) == 0
    text = capsys.readouterr().out
    back = output.read_shapes_csv(text)
    shapes = solved.shapes
    np.testing.assert_array_equal(back["omega"], solved.omega)
    np.testing.assert_array_equal(back["x"], shapes[0].x)
    np.testing.assert_array_equal(back["Y"], np.column_stack([s.Y for s in shapes]))
    np.testing.assert_array_equal(back["mass_x"], shapes[0].mass_x)
    np.testing.assert_array_equal(back["mass_Y"], np.column_stack([s.mass_Y for s in shapes]))
    np.testing.assert_array_equal(back["effective_mass"], [s.effective_mass for s in shapes])
    np.testing.assert_array_equal(back["multiplicity"], solved.multiplicity)
    # what a spreadsheet sees: three blocks, each under its own header row
    blocks = text.split("\n\n")
    assert len(blocks) == 3
    assert blocks[0].splitlines()[0].startswith("mode,omega [rad/s],f [Hz],multiplicity")
    state = [f"{q}_{i} [{u}]" for q, u in output.STATE for i in range(1, 6)]
    assert blocks[1].splitlines()[0] == ",".join(["x [m]", *state])
    assert blocks[2].splitlines()[0] == "mass_x [m]," + ",".join(state[:5])
    for name in ("theta", "M", "Q"):
        expected = np.column_stack([getattr(s, name) for s in shapes])
        np.testing.assert_array_equal(back[name], expected)
    assert len(blocks[1].splitlines()) == 1 + len(shapes[0].x)
    assert len(blocks[2].strip().splitlines()) == 1 + 3


def test_table_shapes_summary(solved, scene, capsys):
    assert main(["solve", "--shapes"]) == 0
    out = capsys.readouterr().out
    assert "NOT TRUSTED" not in out and "effective mass [kg]" in out
    total = scene.beam.mass_per_length * scene.beam.length + sum(a.m for a in scene.attachments)
    summed = sum(0.5 / i for i in range(1, 6))
    assert f"sum of effective masses: {summed:.6g} kg of the total mass {total:.6g} kg" in out
    assert "Y_1" not in out  # a summary, not the arrays


def test_plot_draws_every_copy_of_a_double_root(scene):
    """Two identical oscillators at one point: sqrt(k/m) twice, drawn as 'a' and 'b'."""
    pytest.importorskip("matplotlib")
    from mstmm import plot

    extra = {"type": "spring_mass", "x": 0.0, "k": 1.0e6, "m": 10.0}
    doubled = scene.replace(attachments=[*scene.attachments, extra, extra])
    sol = with_made_up_shapes(mstmm.solve(doubled, modes=6, shapes=False))
    double = int(np.flatnonzero(sol.multiplicity == 2)[0]) + 1  # its mode number
    fig = plot.mode_shapes(sol, modes=6)
    labels = [ln.get_label() for ln in fig.axes[0].get_lines() if ln.get_gid() == "mode"]
    assert len(labels) == 6
    assert labels[double - 1].startswith(f"mode {double}a: ")
    assert labels[double].startswith(f"mode {double}b: ")
    assert labels[double - 1].endswith(", x2")


def test_plot_counts_rigid_body_zeros_and_skips_them():
    """Free-free: --modes 4 means omega_1..4, two of them zeros; two shapes are drawn."""
    pytest.importorskip("matplotlib")
    from pathlib import Path

    from mstmm import plot

    path = Path(__file__).resolve().parent.parent / "examples" / "launch_vehicle.toml"
    sol = with_made_up_shapes(mstmm.solve(mstmm.load_scene(path), modes=4, shapes=False))
    assert list(sol.omega[:2]) == [0.0, 0.0]
    fig = plot.mode_shapes(sol, modes=4)
    labels = [ln.get_label() for ln in fig.axes[0].get_lines() if ln.get_gid() == "mode"]
    assert [label.split(":")[0] for label in labels] == ["mode 3", "mode 4"]


# ---------------------------------------------------------------------------
# Real shapes against closed forms (after the merge of the new ModeShape)


def test_cantilever_effective_mass_closed_form(capsys):
    """Bare cantilever: m_eff,n / (mbar L) = 4 sigma_n^2 / beta_n^2 (0.6131, 0.1883, 0.0647)."""
    path = mstmm.example_path("bare_cantilever")
    scene = mstmm.load_scene(path)
    assert main(["solve", str(path), "--shapes", "--format", "json", "--modes", "3"]) == 0
    shapes = json.loads(capsys.readouterr().out)["mode_shapes"]
    mass = scene.beam.mass_per_length * scene.beam.length
    for beta, shape in zip((1.8751040687, 4.6940911330, 7.8547574382), shapes, strict=True):
        sigma = (math.sinh(beta) - math.sin(beta)) / (math.cosh(beta) + math.cos(beta))
        assert shape["effective_mass"] / mass == pytest.approx(4 * sigma**2 / beta**2, rel=1e-6)


def test_free_free_rigid_modes_carry_the_total_mass(capsys):
    """The two rigid-body zeros of a free-free beam span rigid translation: 100 % of the mass."""
    from pathlib import Path

    path = Path(__file__).resolve().parent.parent / "examples" / "launch_vehicle.toml"
    scene = mstmm.load_scene(path)
    total = scene.beam.mass_per_length * scene.beam.length + sum(a.m for a in scene.attachments)
    assert main(["solve", str(path), "--shapes", "--modes", "2"]) == 0
    out = capsys.readouterr().out
    assert f"of the total mass {total:.6g} kg (100 %" in out

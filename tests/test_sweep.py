"""Parameter studies against the independent reference model, and the sweep command."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
import reference_model as ref

import mstmm
from mstmm.study import parameter_matrix, parse_range, sweep


def test_sweep_matches_reference_at_every_point():
    """Vary the third spring over six decades (it crosses the beam modes: veering)."""
    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    ks = np.logspace(3, 9, 7)
    omega = sweep(scene, {"attachments[2].k": ks}, modes=5)
    assert omega.shape == (7, 5)
    for k, row in zip(ks, omega):
        atts = list(scene.attachments)
        atts[2] = {"type": "spring_mass", "x": atts[2].x, "k": float(k), "m": atts[2].m}
        exact = ref.frequencies(scene.replace(attachments=atts), 5, dps=30)
        assert np.max(np.abs(row - np.array(exact, float)) / np.array(exact, float)) < 1e-13


def test_sweep_moving_an_attachment_resorts_the_parameters():
    """Moving the first spring-mass past the others keeps the parameter vector sorted by x."""
    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    xs = np.array([0.05, 0.5, 0.95])
    P = parameter_matrix(scene, {"attachments[0].x": xs})
    positions = P[:, 3::3]
    assert np.all(np.diff(positions, axis=1) >= 0)
    omega = sweep(scene, {"attachments[0].x": xs}, modes=4)
    for x, row in zip(xs, omega):
        atts = list(scene.attachments)
        atts[0] = {"type": "spring_mass", "x": float(x), "k": atts[0].k, "m": atts[0].m}
        exact = np.array(ref.frequencies(scene.replace(attachments=atts), 4, dps=30), float)
        assert np.max(np.abs(row - exact) / exact) < 1e-13


def test_sweep_certifies_double_roots():
    """Identical oscillators at one point, swept in stiffness: sqrt(k/m) twice at every point."""
    beam = {"length": 1.0, "EI": 1.0, "mass_per_length": 1.0, "left": "clamped", "right": "free"}
    atts = [{"type": "spring_mass", "x": 0.5, "k": 100.0, "m": 1.0}] * 3
    scene = mstmm.scene_from_dict({"beam": beam, "attachments": atts})
    ks = np.array([50.0, 100.0, 400.0])
    omega = sweep(
        scene, {"attachments[0].k": ks, "attachments[1].k": ks, "attachments[2].k": ks}, modes=6
    )
    for k, row in zip(ks, omega):
        assert np.sum(np.abs(row - np.sqrt(k)) < 1e-12 * np.sqrt(k)) == 2


@pytest.mark.parametrize("bad", [{"attachments[9].k": [1.0]}, {"beam.EI": [-1.0]}, {"nope": [1]}])
def test_sweep_rejects_bad_paths_and_values(bad):
    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    with pytest.raises(mstmm.SceneError):
        sweep(scene, bad, modes=2)


def test_parse_range():
    assert np.allclose(parse_range("LOG:1e3:1e9:7"), np.logspace(3, 9, 7))
    assert np.allclose(parse_range("LIN:1:2:3"), [1.0, 1.5, 2.0])
    assert np.allclose(parse_range("1,2.5"), [1.0, 2.5])


def test_cli_sweep_writes_csv(tmp_path, data_dir):
    out = tmp_path / "sweep.csv"
    subprocess.run(
        [
            sys.executable,
            "-m",
            "mstmm",
            "sweep",
            str(data_dir / "wu_chou_1998.toml"),
            "--vary",
            "attachments[2].k=LOG:1e3:1e9:4",
            "--modes",
            "3",
            "--out",
            str(out),
        ],
        check=True,
        capture_output=True,
        text=True,
    )
    rows = out.read_text().strip().splitlines()
    assert rows[0] == "attachments[2].k,omega_1,omega_2,omega_3"
    assert len(rows) == 5
    assert not list(tmp_path.glob(".tmp-*"))


def test_cli_sweep_bad_path_exits_2(tmp_path, data_dir):
    res = subprocess.run(
        [
            sys.executable,
            "-m",
            "mstmm",
            "sweep",
            str(data_dir / "wu_chou_1998.toml"),
            "--vary",
            "attachments[7].k=1,2",
            "--out",
            str(tmp_path / "x.csv"),
        ],
        capture_output=True,
        text=True,
    )
    assert res.returncode == 2
    assert res.stderr.count("\n") == 1 and "attachments[7].k" in res.stderr
    assert not (tmp_path / "x.csv").exists()


def test_sweep_on_a_dask_cluster_matches_local():
    """The same call on a distributed.LocalCluster started here (two worker processes)."""
    import distributed

    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    ks = np.logspace(3, 9, 9)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as lc:
        remote = sweep(
            scene, {"attachments[2].k": ks}, modes=4, scheduler=lc.scheduler_address, chunk=4
        )
    for k, row in zip(ks[::4], remote[::4]):
        atts = list(scene.attachments)
        atts[2] = {"type": "spring_mass", "x": atts[2].x, "k": float(k), "m": atts[2].m}
        exact = np.array(ref.frequencies(scene.replace(attachments=atts), 4, dps=30), float)
        assert np.max(np.abs(row - exact) / exact) < 1e-13

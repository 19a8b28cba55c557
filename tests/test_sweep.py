"""Parameter studies against the independent reference model, and the sweep command."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest
import reference_model as ref

import mstmm
from mstmm.study import column, columns, parameter_matrix, parse_range, sweep


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


def wu_chou_vector(x, k, m):
    """The parameter vector of the paper's scene written out by hand (docs/components.md,
    section 4): [L, EI_0, mbar_0, n_seg, n_ev, left end, right end] (codes of
    catalog.END_CODES: clamped 0, free 2), the one segment (x_end, EI, mbar, eta, kappa_GA,
    rho_I, P, k_w, k_G: Euler-Bernoulli, all 0), the event rows (tag, x, offset) sorted by
    x, then each spring-mass's (k, m, c) in scene order (no dashpot given: c = 0)."""
    ei, mbar = 63476.125002707834, 15.3875
    head = [1.0, ei, mbar, 1.0, 3.0, 0.0, 2.0, 1.0, ei, mbar, 0.0] + [0.0] * 5
    offsets = [25.0, 28.0, 31.0]  # 7 + 9 + 3 * 3 = 25: after the event table
    rows = sorted(zip(x, range(3)), key=lambda r: r[0])  # stable, by x
    events = [v for xi, i in rows for v in (0.0, xi, offsets[i])]
    return np.array(head + events + [v for i in range(3) for v in (k[i], m[i], 0.0)])


WU_CHOU_K = [190428.3750081235, 285642.56251218525, 380856.750016247]
WU_CHOU_M = [3.0775, 7.69375, 15.3875]


def test_moving_an_attachment_resorts_the_event_rows():
    """Moving the first spring-mass past the others re-sorts the event rows; its data
    block stays where it was (the offset travels with the row)."""
    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    xs = [0.05, 0.5, 0.95]
    P = parameter_matrix(scene, {"attachments[0].x": xs})
    for x, row in zip(xs, P):
        expected = wu_chou_vector([x, 0.4, 0.8], WU_CHOU_K, WU_CHOU_M)
        assert row.tolist() == expected.tolist()


def test_varying_a_stiffness_and_the_beam():
    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    P = parameter_matrix(scene, {"attachments[2].k": [1.0, 2.0], "beam.length": [1.0, 2.0]})
    for k, length, row in zip([1.0, 2.0], [1.0, 2.0], P):
        expected = wu_chou_vector([0.1, 0.4, 0.8], [*WU_CHOU_K[:2], k], WU_CHOU_M)
        expected[0] = expected[7] = length  # the total length and the segment's end
        assert row.tolist() == expected.tolist()
    P = parameter_matrix(scene, {"beam.EI": [7.0], "beam.mass_per_length": [3.0]})
    expected = wu_chou_vector([0.1, 0.4, 0.8], WU_CHOU_K, WU_CHOU_M)
    expected[[1, 8]] = 7.0  # the kernel's unit EI_0 and the segment's own EI
    expected[[2, 9]] = 3.0
    assert P[0].tolist() == expected.tolist()


def test_moving_the_last_attachment_outside_a_shorter_beam_is_named():
    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    with pytest.raises(mstmm.SceneError) as info:
        parameter_matrix(scene, {"beam.length": [1.0, 0.5]})
    assert info.value.field == "attachments[2].x" and "at point 1" in str(info.value)  # x = 0.8


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


@pytest.mark.parametrize(
    "bad, field, words",
    [
        ({"attachments[9].k": [1.0]}, "attachments[9].k", "has 3 attachments"),
        ({"attachments[1].J": [1.0]}, "attachments[1].J", "attachments[1].m"),
        ({"beam.EI": [-1.0]}, "beam.EI", "must be > 0"),
        ({"beam.EI": [1.0, math.nan]}, "beam.EI", "at point 1, must be finite"),
        ({"attachments[0].x": [1.5]}, "attachments[0].x", "must lie in [0, length]"),
        ({"beam.segments[0].EI": [1.0]}, "beam.segments[0].EI", "beam.mass_per_length"),
        ({"nope": [1]}, "nope", "not a parameter"),
    ],
)
def test_sweep_rejects_bad_paths_and_values(bad, field, words):
    """Rejected before any kernel is loaded: one line naming the field."""
    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    with pytest.raises(mstmm.SceneError) as info:
        sweep(scene, bad, modes=2)
    assert info.value.field == field
    assert words in str(info.value) and len(str(info.value).splitlines()) == 1


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
    assert rows[0] == "attachments[2].k [N/m],omega_1 [rad/s],omega_2 [rad/s],omega_3 [rad/s]"
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


# ---------------------------------------------------------------------------
# Fields of every kind and of stepped beams (no solving)

EVERY_KIND = {
    "beam": {
        "left": "clamped",
        "right": "free",
        "segments": [
            {"length": 0.4, "EI": 2.0e4, "mass_per_length": 12.0},
            {"length": 0.6, "EI": 1.0e4, "mass_per_length": 8.0},
        ],
    },
    "attachments": [  # in x order, so the indices are those of the scene
        {"type": "spring", "x": 0.0, "k": 5.0},
        {"type": "hinge", "x": 0.3},
        {"type": "oscillator_chain", "x": 0.5, "k": [1.0e4, 2.0e4], "m": [1.0, 2.0]},
        {"type": "support", "x": 0.7},
        {"type": "mass", "x": 1.0, "m": 2.0, "J": 0.1},
        {"type": "rotational_spring", "x": 1.0, "k": 3.0},
    ],
}


def every_kind_vector() -> list[float]:
    """The layout of EVERY_KIND written out by hand (tags: the kinds present, sorted)."""
    # the ends' codes (catalog.END_CODES: clamped 0, free 2); the chain's dashpots, none
    # given, as zeros
    # segment rows (x_end, EI, mbar, eta, kappa_GA, rho_I, P, k_w, k_G): Euler-Bernoulli
    head = [1.0, 2.0e4, 12.0, 2, 6, 0, 2, 0.4, 2.0e4, 12.0, 0.0, 0, 0, 0, 0, 0]
    head += [1.0, 1.0e4, 8.0, 0.0, 0, 0, 0, 0, 0]
    events = [4, 0.0, 43, 0, 0.3, 44, 2, 0.5, 45, 5, 0.7, 54, 1, 1.0, 54, 3, 1.0, 56]
    data = [5.0, 0.0, 2, 1.0e4, 2.0e4, 2, 1.0, 2.0, 2, 0.0, 0.0, 2.0, 0.1, 3.0]
    return [float(v) for v in head + events + data]


@pytest.mark.parametrize(
    "path, cols",
    [
        ("beam.segments[0].EI", (1, 8)),  # the kernel's unit EI_0 and the segment's own
        ("beam.segments[0].mass_per_length", (2, 9)),
        ("beam.segments[1].EI", (17,)),
        ("beam.segments[1].mass_per_length", (18,)),
        ("attachments[0].k", (43,)),
        ("attachments[1].k", (44,)),
        ("attachments[2].k[0]", (46,)),
        ("attachments[2].k[1]", (47,)),
        ("attachments[2].m[1]", (50,)),
        ("attachments[3].x", (35,)),
        ("attachments[4].J", (55,)),
        ("attachments[5].x", (41,)),
    ],
)
def test_columns_of_every_kind(path, cols):
    scene = mstmm.scene_from_dict(EVERY_KIND)
    assert mstmm.parameter_vector(scene).tolist() == every_kind_vector()
    assert columns(scene, path) == cols
    assert column(scene, path) == cols[0]


def test_varying_values_of_every_kind():
    scene = mstmm.scene_from_dict(EVERY_KIND)
    vary = {
        "beam.segments[0].EI": [3.0e4],
        "beam.segments[1].mass_per_length": [9.0],
        "attachments[2].k[1]": [4.0e4],
        "attachments[4].J": [0.0],
        "attachments[1].k": [7.0],
    }
    (row,) = parameter_matrix(scene, vary)
    expected = every_kind_vector()
    expected[1] = expected[8] = 3.0e4
    expected[18] = 9.0
    expected[47] = 4.0e4
    expected[55] = 0.0
    expected[44] = 7.0
    assert row.tolist() == expected


def test_moving_a_support_keeps_it_apart_from_the_mass_sharing_its_offset():
    """A support has no data: its offset equals the next block's (the mass's). Moving it
    past the mass and the rotational spring re-sorts its row with its own tag."""
    scene = mstmm.scene_from_dict(EVERY_KIND)
    P = parameter_matrix(scene, {"attachments[3].x": [0.7, 0.2, 0.95]})
    rows = [
        [4, 0.0, 43, 0, 0.3, 44, 2, 0.5, 45, 5, 0.7, 54, 1, 1.0, 54, 3, 1.0, 56],
        [4, 0.0, 43, 5, 0.2, 54, 0, 0.3, 44, 2, 0.5, 45, 1, 1.0, 54, 3, 1.0, 56],
        [4, 0.0, 43, 0, 0.3, 44, 2, 0.5, 45, 5, 0.95, 54, 1, 1.0, 54, 3, 1.0, 56],
    ]
    for row, events in zip(P, rows):
        assert row[25:43].tolist() == [float(v) for v in events]


@pytest.mark.parametrize(
    "vary, field, words",
    [
        ({"beam.length": [2.0]}, "beam.length", "stepped beam's total length"),
        ({"beam.segments[2].EI": [1.0]}, "beam.segments[2].EI", "beam.segments[1].EI"),
        ({"beam.segments[0].length": [1.0]}, "beam.segments[0].length", "not a field"),
        ({"attachments[2].k[2]": [1.0]}, "attachments[2].k[2]", "attachments[2].k[1]"),
        ({"attachments[3].k": [1.0]}, "attachments[3].k", "(it has: attachments[3].x)"),
        ({"attachments[2].k[0]": [1.0, -1.0]}, "attachments[2].k[0]", "at point 1, must be > 0"),
        ({"attachments[4].J": [1.0, -1.0]}, "attachments[4].J", "at point 1, must be >= 0"),
        ({"attachments[1].x": [0.5, 1.0]}, "attachments[1].x", "at point 1, must lie inside"),
        ({"attachments[3].x": [0.5, 0.0]}, "attachments[3].x", "at point 1, a support where"),
        ({"attachments[4].x": [0.6, 0.3]}, "attachments[4].x", "at point 1, at exactly the x"),
        ({"attachments[2].m[1]": [1.0, 1e-300]}, "attachments[2].m[1]", "at point 1, must lie"),
        ({"beam.segments[1].EI": [1.0, 1e300]}, "beam.segments[1].EI", "at point 1, must lie"),
    ],
)
def test_sweep_of_every_kind_rejects(vary, field, words):
    scene = mstmm.scene_from_dict(EVERY_KIND)
    with pytest.raises(mstmm.SceneError) as info:
        parameter_matrix(scene, vary)
    assert info.value.field == field and info.value.source == "<sweep>"
    assert words in str(info.value), str(info.value)
    assert len(str(info.value).splitlines()) == 1


def test_rotary_inertia_swept_onto_a_hinge_position_is_rejected():
    """A mass without J at a hinge is fine; giving it J at one point of a sweep is not."""
    data = {
        **EVERY_KIND,
        "attachments": [*EVERY_KIND["attachments"], {"type": "mass", "x": 0.3, "m": 1.0}],
    }
    scene = mstmm.scene_from_dict(data)
    i = next(i for i, a in enumerate(scene.attachments) if a.kind == "mass" and a.x == 0.3)
    with pytest.raises(mstmm.SceneError) as info:
        parameter_matrix(scene, {f"attachments[{i}].J": [0.0, 0.0, 0.5]})
    assert info.value.field == f"attachments[{i}].x" and "at point 2," in str(info.value)
    assert "ambiguous" in str(info.value)


# ---------------------------------------------------------------------------
# Damped studies (issue 20, item 5) and a stepped beam's per-segment fields


def _pinned(eta: float = 0.0) -> mstmm.Scene:
    beam = {"length": 2.0, "EI": 3.0, "mass_per_length": 1.5, "left": "pinned", "right": "pinned"}
    if eta:
        beam["loss_factor"] = eta
    return mstmm.scene_from_dict({"beam": beam, "attachments": []})


def _pinned_exact(eta: float, modes: int) -> np.ndarray:
    """omega^2 = (1 + i eta) (n pi / L)^4 EI / mbar, the root with sigma > 0."""
    n = np.arange(1, modes + 1)
    return np.sqrt((1.0 + 1j * eta) * (n * np.pi / 2.0) ** 4 * 3.0 / 1.5)


def test_loss_factor_swept_from_an_undamped_scene_gives_the_closed_form():
    """The scene starts undamped (eta = 0): the varied loss factor makes it damped, every
    point (eta = 0 included) is solved for complex roots."""
    etas = np.array([0.0, 0.02, 0.3, 1.0])
    omega = sweep(_pinned(), {"beam.loss_factor": etas}, modes=3)
    assert omega.shape == (4, 3) and np.iscomplexobj(omega)
    for eta, row in zip(etas, omega):
        exact = _pinned_exact(eta, 3)
        assert np.max(np.abs(row - exact) / np.abs(exact)) < 1e-12, (eta, row, exact)


def test_damped_scene_sweeps_its_stiffness():
    """A damped scene (eta = 0.1) swept in EI: the closed form at every point."""
    eis = np.array([1.5, 3.0, 6.0])
    omega = sweep(_pinned(0.1), {"beam.EI": eis}, modes=2)
    for ei, row in zip(eis, omega):
        exact = _pinned_exact(0.1, 2) * np.sqrt(ei / 3.0)
        assert np.max(np.abs(row - exact) / np.abs(exact)) < 1e-12


TMD = {
    "beam": {
        "length": 1.0,
        "EI": 1.0e3,
        "mass_per_length": 2.0,
        "left": "clamped",
        "right": "free",
    },
    "attachments": [{"type": "spring_mass", "x": 1.0, "k": 3.0e3, "m": 0.2}],
}


def test_absorber_damping_sweep_matches_the_mpmath_reference():
    """A tuned mass at the free end, its dashpot c swept from 0 (the scene is undamped):
    each point's complex roots against the independent global-assembly reference."""
    scene = mstmm.scene_from_dict(TMD)
    cs = np.array([0.0, 3.0, 30.0])
    omega = sweep(scene, {"attachments[0].c": cs}, modes=3)
    for c, row in zip(cs, omega):
        data = {**TMD, "attachments": [{**TMD["attachments"][0], "c": float(c)}]}
        exact = np.array([complex(w) for w in ref.damped_frequencies(data, 3, dps=30)])
        assert np.max(np.abs(row - exact) / np.abs(exact)) < 1e-11, (c, row, exact)
    assert np.all(omega[1:].imag > 0) and np.all(np.abs(omega[0].imag) < 1e-12 * omega[0].real)


def _cli(*args: str, **kw) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "mstmm", "sweep", *args], capture_output=True, text=True, **kw
    )


def test_cli_damped_sweep_writes_w_d_sigma_zeta(tmp_path):
    scene = tmp_path / "tmd.toml"
    scene.write_text(
        "[beam]\nlength = 1.0\nEI = 1000.0\nmass_per_length = 2.0\nleft = 'clamped'\n"
        "right = 'free'\n[[attachments]]\ntype = 'spring_mass'\nx = 1.0\nk = 3000.0\n"
        "m = 0.2\n"
    )
    out = tmp_path / "sweep.csv"
    res = _cli(str(scene), "--vary", "attachments[0].c=0,30", "--modes", "2", "--out", str(out))
    assert res.returncode == 0, res.stderr
    rows = [line.split(",") for line in out.read_text().strip().splitlines()]
    units = {"w_d": "rad/s", "sigma": "1/s", "zeta": "-"}
    assert rows[0] == [
        "attachments[0].c [N s/m]",
        *(f"{q}_{i} [{units[q]}]" for i in (1, 2) for q in ("w_d", "sigma", "zeta")),
    ]
    for row, c in zip(rows[1:], (0.0, 30.0)):
        data = {**TMD, "attachments": [{**TMD["attachments"][0], "c": c}]}
        exact = [complex(w) for w in ref.damped_frequencies(data, 2, dps=30)]
        values = [float(v) for v in row]
        assert values[0] == c
        for i, w in enumerate(exact):
            w_d, sigma, zeta = values[1 + 3 * i : 4 + 3 * i]
            assert abs(complex(w_d, sigma) - w) < 1e-11 * abs(w)
            assert abs(zeta - w.imag / abs(w)) < 1e-11
    assert float(rows[2][3]) > 0.01  # the absorber's dashpot damps the coupled modes


@pytest.mark.parametrize("name", ["EI", "mass_per_length", "loss_factor"])
def test_a_stepped_beams_field_is_refused_naming_its_segments(name):
    """beam.EI on a stepped beam would change its first segment only: refused."""
    scene = mstmm.scene_from_dict(EVERY_KIND)
    with pytest.raises(ValueError) as info:
        sweep(scene, {f"beam.{name}": [1.0, 2.0]}, modes=2)
    assert info.value.field == f"beam.{name}"
    assert f"beam.segments[i].{name}" in str(info.value) and "i = 0..1" in str(info.value)


def test_cli_refuses_beam_ei_on_a_stepped_beam(tmp_path):
    scene = tmp_path / "stepped.toml"
    scene.write_text(
        "[beam]\nleft = 'clamped'\nright = 'free'\n"
        "[[beam.segments]]\nlength = 0.5\nEI = 2.0\nmass_per_length = 1.0\n"
        "[[beam.segments]]\nlength = 0.5\nEI = 1.0\nmass_per_length = 1.0\n"
    )
    out = tmp_path / "x.csv"
    res = _cli(str(scene), "--vary", "beam.EI=1,2", "--out", str(out))
    assert res.returncode == 2
    assert res.stderr.count("\n") == 1 and "beam.segments[i].EI" in res.stderr
    assert not out.exists()


def test_sigint_stops_a_long_sweep_within_two_seconds(tmp_path):
    """Ctrl-C during a sweep of 20000 points: status 130 and one line within 2 s, and the
    --out file is not written (not even in part)."""
    from interrupt import interrupt

    out = tmp_path / "sweep.csv"
    argv = ["sweep", str(mstmm.example_path("wu_chou_1998")), "--vary"]
    argv += ["attachments[2].k=LOG:1e3:1e9:20000", "--modes", "100", "--out", str(out)]
    status, _, err, took = interrupt(argv, 4.0)
    assert status == 130, err
    assert err == "mstmm: interrupted\n"
    assert took < 2.0, took
    assert not out.exists() and not list(tmp_path.glob(".tmp-*"))

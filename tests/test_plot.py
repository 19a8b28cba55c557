"""Plots (paper Fig. 2, veering): images are written, and the figures hold what they claim."""

from __future__ import annotations

import os
import stat
import struct
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import mstmm

pytest.importorskip("matplotlib")

from mstmm import plot  # noqa: E402
from mstmm.units import field_unit  # noqa: E402

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


@pytest.fixture(scope="module")
def scene():
    return mstmm.load_scene(mstmm.example_path("wu_chou_1998"))


@pytest.fixture(scope="module")
def free_free():
    return mstmm.load_scene(EXAMPLES / "launch_vehicle.toml")


def png_size(path: Path) -> tuple[int, int]:
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    return struct.unpack(">II", data[16:24])


def lines(fig, gid: str, ax: int = 0) -> list:
    return [line for line in fig.axes[ax].get_lines() if line.get_gid() == gid]


def test_import_mstmm_does_not_import_matplotlib():
    code = "import sys, mstmm; mstmm.solve; assert 'matplotlib' not in sys.modules"
    subprocess.run([sys.executable, "-c", code], check=True, timeout=120)


def test_agg_backend_without_a_display():
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    env.pop("MPLBACKEND", None)
    code = "import matplotlib, mstmm.plot; print(matplotlib.get_backend())"
    out = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120
    )
    assert out.returncode == 0, out.stderr
    if sys.platform.startswith("linux"):
        assert out.stdout.strip().lower() == "agg"


def test_figure2_writes_both_panels(scene, tmp_path):
    path = tmp_path / "fig2.png"
    fig = plot.figure2(scene, path, modes=4)
    assert path.is_file() and path.stat().st_size > 50_000
    assert png_size(path) == (13 * plot.DPI, round(4.8 * plot.DPI))
    assert stat.S_IMODE(path.stat().st_mode) & 0o044  # not left 0600 by the temporary file
    assert not list(tmp_path.glob(".tmp-*"))
    assert len(fig.axes) == 2
    sol = mstmm.solve(scene, band=fig.axes[0].get_xlim())
    assert len(lines(fig, "roots")[0].get_xdata()) == len(sol.omega) >= 4
    assert len(lines(fig, "mode", ax=1)) == 4


def test_characteristic_marks_every_root_in_the_band(scene, tmp_path):
    path = tmp_path / "delta.png"
    fig = plot.characteristic(scene, modes=5, path=path)
    assert path.stat().st_size > 20_000
    assert png_size(path) == (round(7 * plot.DPI), round(4.8 * plot.DPI))
    lo, hi = fig.axes[0].get_xlim()
    assert lo == 0.0
    sol = mstmm.solve(scene, band=(lo, hi))
    assert len(sol.omega) == 5  # 8 % past the 5th root holds no 6th here
    (curve,) = lines(fig, "delta")
    w, y = curve.get_xdata(), curve.get_ydata()
    assert len(w) == 2000 and np.all(np.isfinite(y))
    assert w[0] > 0 and w[-1] == pytest.approx(hi)
    (roots,) = lines(fig, "roots")
    np.testing.assert_array_equal(roots.get_xdata(), sol.omega)
    assert [ln.get_xdata()[0] for ln in lines(fig, "root-line")] == list(sol.omega)
    # the curve dips at every marked root, a decade below its level 3 % away
    for r in sol.omega:
        near, around = np.abs(w - r) < 0.005 * r, np.abs(w - r) < 0.03 * r
        assert y[near].min() < y[around].max() - 1.0, r
    # the top axis is in Hz
    (sec,) = fig.axes[0].child_axes
    assert "Hz" in sec.get_xlabel()


def test_characteristic_band_and_paper_formulation(scene):
    band = (150.0, 2000.0)
    fig = plot.characteristic(scene, band=band, formulation="paper", n=500)
    sol = mstmm.solve(scene, band=band, formulation="paper")
    assert fig.axes[0].get_xlim() == band
    assert len(lines(fig, "delta")[0].get_xdata()) == 500
    np.testing.assert_array_equal(lines(fig, "roots")[0].get_xdata(), sol.omega)
    assert len(sol.omega) == 4  # 188.7, 248.6, 349.1, 1428.0


def test_characteristic_multiple_root_one_line_two_markers(scene):
    """Two identical oscillators on the clamped end: sqrt(k/m) is a double root."""
    extra = {"type": "spring_mass", "x": 0.0, "k": 1.0e6, "m": 10.0}
    doubled = scene.replace(attachments=[*scene.attachments, extra, extra])
    fig = plot.characteristic(doubled, band=(50.0, 500.0), n=400)
    sol = mstmm.solve(doubled, band=(50.0, 500.0))
    assert 2 in sol.multiplicity
    assert len(lines(fig, "roots")[0].get_xdata()) == len(sol.omega) == 6
    assert len(lines(fig, "root-line")) == 5
    assert any(t.get_text() == "x2" for t in fig.axes[0].texts)


def test_mode_shapes_draw_beam_masses_and_attachments(scene, tmp_path):
    sol = mstmm.solve(scene, modes=6)
    path = tmp_path / "shapes.png"
    fig = plot.mode_shapes(sol, modes=4, path=path)
    assert path.stat().st_size > 20_000
    curves, masses = lines(fig, "mode"), lines(fig, "mass")
    assert len(curves) == len(masses) == len(lines(fig, "spring")) == 4
    assert len(lines(fig, "axis")) == 1
    (att,) = lines(fig, "attachment")  # three spring-masses: one kind, one marker line
    np.testing.assert_array_equal(att.get_xdata(), [a.x for a in scene.attachments])
    np.testing.assert_array_equal(att.get_ydata(), 0.0)
    for curve, mass, shape in zip(curves, masses, sol.shapes, strict=False):
        scale = 1.0 / np.max(np.abs(shape.Y))  # the beam at its own scale
        np.testing.assert_allclose(curve.get_ydata(), shape.Y * scale, rtol=1e-15)
        np.testing.assert_array_equal(mass.get_xdata(), shape.mass_x)
        want = np.clip(shape.mass_Y * scale, -plot.MASS_CLIP, plot.MASS_CLIP)
        np.testing.assert_allclose(mass.get_ydata(), want, rtol=1e-15)
    labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    for i, w in enumerate(sol.omega[:4]):
        assert f"{w:.6g} rad/s" in labels[i] and f"{w / (2 * np.pi):.6g} Hz" in labels[i]
    assert "spring-mass (3)" in labels


def test_mode_shapes_of_a_free_free_scene_skip_rigid_modes(free_free):
    """--modes counts every natural frequency: 5 of a free-free beam are 2 zeros, 3 shapes."""
    fig = plot.mode_shapes(free_free, modes=5)
    assert len(lines(fig, "mode")) == 3
    labels = [ln.get_label() for ln in lines(fig, "mode")]
    assert labels[0].startswith("mode 3:")  # modes 1 and 2 are the rigid-body zeros


def test_mode_shapes_into_given_axes(scene):
    from matplotlib.figure import Figure

    mine = Figure()
    ax = mine.add_subplot()
    assert plot.mode_shapes(scene, modes=2, ax=ax) is mine
    assert len(lines(mine, "mode")) == 2


def test_veering_one_line_per_mode(scene, tmp_path):
    ks = np.logspace(3, 9, 25)
    path = tmp_path / "veer.png"
    fig = plot.veering(scene, "attachments[2].k", ks, modes=5, path=path)
    assert path.stat().st_size > 20_000
    ax = fig.axes[0]
    assert ax.get_xscale() == "log"
    curves = lines(fig, "mode")
    assert len(curves) == 5
    omega = mstmm.sweep(scene, {"attachments[2].k": ks}, modes=5)
    for j, curve in enumerate(curves):
        np.testing.assert_array_equal(curve.get_xdata(), ks)
        np.testing.assert_array_equal(curve.get_ydata(), omega[:, j])
    (unc,) = lines(fig, "uncoupled")
    m = scene.attachments[2].m
    np.testing.assert_allclose(unc.get_ydata(), np.sqrt(ks / m))


def test_veering_linear_axis_and_rigid_modes_left_out(free_free):
    xs = np.linspace(5.0, 35.0, 7)
    fig = plot.veering(free_free, "attachments[1].x", xs, modes=5)  # 2 zeros, 3 drawn
    ax = fig.axes[0]
    assert ax.get_xscale() == "linear"
    curves = lines(fig, "mode")
    assert [c.get_label() for c in curves] == ["mode 3", "mode 4", "mode 5"]
    assert all(np.all(c.get_ydata() > 0) for c in curves)
    assert not lines(fig, "uncoupled")


def test_unknown_image_format_writes_nothing(scene, tmp_path):
    fig = plot.characteristic(scene, modes=2, n=50)
    with pytest.raises(ValueError, match="unsupported image format"):
        plot.save(fig, tmp_path / "out.xyz")
    assert not list(tmp_path.iterdir())
    plot.save(fig, tmp_path / "out.svg")
    assert (tmp_path / "out.svg").read_text().lstrip().startswith("<?xml")


def test_without_matplotlib_the_error_names_the_extra(tmp_path):
    """Issue 20 item 14: ``pip install .`` then ``mstmm plot``: one line naming the extra."""
    code = (
        "import sys; sys.modules['matplotlib'] = None; from mstmm.cli import main;"
        f" sys.exit(main(['plot', '-o', {str(tmp_path / 'f.png')!r}]))"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert run.returncode == 1
    (line,) = run.stderr.splitlines()
    assert line.startswith("mstmm: error: plotting needs matplotlib")
    assert 'pip install ".[plot]"' in line and "mstmm[plot]" in line
    assert not list(tmp_path.iterdir())


def test_readme_says_how_to_install_plotting_before_the_first_plot():
    """The README's set-up installs the plot extra, before its first ``mstmm plot``."""
    text = (Path(__file__).resolve().parent.parent / "README.md").read_text()
    lines = text.splitlines()
    first = next(i for i, ln in enumerate(lines) if ln.startswith("    ") and "mstmm plot" in ln)
    install = next(i for i, ln in enumerate(lines) if ln.startswith("    pip install"))
    assert install < first
    assert 'pip install ".[plot]"' in lines[install]


# ---------------------------------------------------------------- issue 20, item 16


def _legend_outside(fig, ax) -> None:
    """The legend lies right of the axes: it covers no curve."""
    fig.draw_without_rendering()
    leg = ax.get_legend().get_window_extent()
    box = ax.get_window_extent()
    assert leg.x0 >= box.x1, (leg, box)


def test_markers_tell_the_kinds_apart_with_a_legend(tmp_path):
    """A hinge, a support, a mass, two spring-masses and a spring: one marker line per kind,
    each its own marker, labelled with the kind and its count; every axis has a unit."""
    scene = mstmm.scene_from_dict(
        {
            "name": "kinds",
            "beam": {"length": 4.0, "EI": 1e4, "mass_per_length": 10.0, "left": "clamped",
                     "right": "free"},
            "attachments": [
                {"type": "hinge", "x": 1.0, "k": 1e3},
                {"type": "support", "x": 2.0},
                {"type": "mass", "x": 3.0, "m": 5.0},
                {"type": "spring_mass", "x": 3.5, "k": 1e4, "m": 2.0},
                {"type": "spring_mass", "x": 4.0, "k": 2e4, "m": 2.0},
                {"type": "spring", "x": 2.5, "k": 1e3},
            ],
        }
    )  # fmt: skip
    path = tmp_path / "kinds.png"
    fig = plot.figure2(scene, path, modes=4)
    att = lines(fig, "attachment", ax=1)
    labels = sorted(a.get_label() for a in att)
    assert labels == ["hinge (1)", "mass (1)", "spring (1)", "spring-mass (2)", "support (1)"]
    assert len({a.get_marker() for a in att}) == 5
    legend = [t.get_text() for t in fig.axes[1].get_legend().get_texts()]
    assert set(labels) <= set(legend)
    for ax in fig.axes[:2]:
        for text in (ax.get_xlabel(), ax.get_ylabel()):
            assert "[" in text and "]" in text, text
    for ax in fig.axes[:2]:
        _legend_outside(fig, ax)


def test_plot_modes_8_marks_8_roots():
    """absorbers: 8 % past the 8th root holds four more (a cluster); exactly 8 marked."""
    scene = mstmm.load_scene(EXAMPLES / "absorbers.toml")
    fig = plot.figure2(scene, modes=8)
    (roots,) = lines(fig, "roots")
    sol = mstmm.solve(scene, modes=8, shapes=False)
    np.testing.assert_array_equal(roots.get_xdata(), sol.omega)
    assert len(lines(fig, "mode", ax=1)) == 8


def test_frf_figure_units_and_unwrapped_phase():
    """A damped absorber: |H| in m/N, the phase unwrapped past -180 (the mass's response lags
    by up to 360 deg), the axis in rad/s or in Hz."""
    scene = mstmm.load_scene(EXAMPLES / "tmd_den_hartog.toml")
    omegas = np.linspace(3.0, 20.0, 400)
    out = ["displacement:x=5.0", "displacement:mass=0"]
    fig = plot.frf_figure(scene, "force:x=5.0", out, omegas)
    mag, ph = fig.axes[0], fig.axes[1]
    assert "[m/N]" in mag.get_ylabel() and "[deg]" in ph.get_ylabel()
    assert ph.get_xlabel() == r"$\omega$ [rad/s]"
    curves = [ln for ln in ph.get_lines() if ln.get_gid() == "phase"]
    H = mstmm.frf(scene, "force:x=5.0", out[1], omegas)
    H = np.asarray(H).reshape(len(omegas), -1)[:, -1]
    np.testing.assert_allclose(curves[1].get_ydata(), np.degrees(np.unwrap(np.angle(H))))
    assert curves[1].get_ydata().min() < -270.0  # unwrapped, not folded into (-180, 180]
    assert np.all(np.abs(np.diff(curves[1].get_ydata())) < 30.0)
    _legend_outside(fig, mag)
    hz = plot.frf_figure(scene, "force:x=5.0", out, omegas, hz=True, quantity="mobility")
    assert hz.axes[1].get_xlabel() == "f [Hz]" and "[m/s/N]" in hz.axes[0].get_ylabel()
    np.testing.assert_allclose(hz.axes[0].get_lines()[0].get_xdata(), omegas / (2 * np.pi))
    rot = plot.frf_figure(scene, "moment:x=2.0", "rotation:x=2.0", omegas, quantity="accelerance")
    assert "[rad/s^2/(N m)]" in rot.axes[0].get_ylabel()


def test_cli_plot_frf_in_hz(tmp_path):
    path = tmp_path / "frf.png"
    run = subprocess.run(
        [sys.executable, "-m", "mstmm", "plot", str(EXAMPLES / "tmd_den_hartog.toml"), "--frf",
         "--band", "0.5", "3", "--hz", "--input", "force:x=5.0", "--output",
         "displacement:x=5.0", "-o", str(path)],
        capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr
    assert png_size(path) == (8 * plot.DPI, 6 * plot.DPI)
    bad = subprocess.run(
        [sys.executable, "-m", "mstmm", "plot", "--hz", "-o", str(tmp_path / "x.png")],
        capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert bad.returncode == 2 and "--hz" in bad.stderr


def test_veering_x_label_has_the_keys_unit(scene):
    fig = plot.veering(scene, "attachments[2].k", np.logspace(3, 9, 5), modes=3)
    assert fig.axes[0].get_xlabel() == "attachments[2].k [N/m]"
    fig = plot.veering(scene, "beam.EI", np.linspace(5e4, 7e4, 3), modes=3)
    assert fig.axes[0].get_xlabel() == "beam.EI [N m^2]"


def test_veering_legend_covers_neither_curves_nor_the_hz_axis(scene):
    fig = plot.veering(scene, "attachments[2].k", np.logspace(3, 9, 5), modes=3)
    fig.draw_without_rendering()
    (legend,) = fig.legends
    ax = fig.axes[0]
    right = max(c.get_tightbbox().x1 for c in ax.child_axes)  # the Hz ticks and label
    assert legend.get_window_extent().x0 >= right


def test_veering_draws_the_own_frequencies_of_any_kind():
    """A two-stage chain's own frequencies (beam point held): the eigenvalues of
    [[k1 + k2, -k2], [-k2, k2]] u = w^2 diag(m1, m2) u, at every value of k[1]."""
    beam = {"length": 2.0, "EI": 1.0e4, "mass_per_length": 10.0, "left": "clamped"}
    chain = {"type": "oscillator_chain", "x": 1.5, "k": [2.0e4, 1.0e4], "m": [1.0, 2.0]}
    sc = mstmm.scene_from_dict({"beam": {**beam, "right": "free"}, "attachments": [chain]})
    k2s = np.linspace(5.0e3, 4.0e4, 6)
    fig = plot.veering(sc, "attachments[0].k[1]", k2s, modes=3)
    unc = lines(fig, "uncoupled")
    assert len(unc) == 2
    for i, k2 in enumerate(k2s):
        K = np.array([[2.0e4 + k2, -k2], [-k2, k2]])
        want = np.sqrt(
            np.linalg.eigvalsh(np.diag([1.0, 0.5]) ** 0.5 @ K @ np.diag([1.0, 0.5]) ** 0.5)
        )
        got = [line.get_ydata()[i] for line in unc]
        np.testing.assert_allclose(got, want, rtol=1e-12)


# ---------------------------------------------------------------- issue 41, plots


def test_delta_is_continuous_away_from_roots():
    """hinged_absorber: the chain's condensation takes out powers of two; dropped, they
    scaled Delta by a factor that jumped (steps of log10 2 between 15 and 52 rad/s)."""
    scene = mstmm.load_scene(EXAMPLES / "hinged_absorber.toml")
    fig = plot.characteristic(scene, band=(1.0, 66.0), n=2000)
    (curve,) = lines(fig, "delta")
    w, y = curve.get_xdata(), curve.get_ydata()
    roots = lines(fig, "roots")[0].get_xdata()
    away = np.all(np.abs(w[:-1, None] - roots[None, :]) > 0.03 * roots, axis=1)
    assert np.max(np.abs(np.diff(y))[away]) < 0.05


def _inside_canvas(fig) -> None:
    """Everything drawn of ``fig`` lies inside its canvas, and no legend covers another
    axes than its own."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(fig)  # as the PNG is drawn
    canvas.draw()
    renderer = canvas.get_renderer()
    tight, box = fig.get_tightbbox(renderer), fig.bbox_inches
    assert tight.x0 >= box.x0 - 0.01 and tight.x1 <= box.x1 + 0.01, (tight, box)
    assert tight.y0 >= box.y0 - 0.01 and tight.y1 <= box.y1 + 0.01, (tight, box)
    for ax in fig.axes:
        legend = ax.get_legend()
        if legend is None:
            continue
        ext = legend.get_window_extent(renderer)
        assert fig.bbox.x0 <= ext.x0 and ext.x1 <= fig.bbox.x1 + 1, ext
        assert fig.bbox.y0 <= ext.y0 and ext.y1 <= fig.bbox.y1 + 1, ext
        for other in fig.axes:
            if other is not ax and other not in ax.child_axes:
                assert not ext.overlaps(other.get_window_extent(renderer)), (ax, other)


@pytest.fixture
def no_warnings():
    """Any warning raised inside the test is an error."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        yield


def test_mode_shapes_show_the_beam_at_its_own_scale(no_warnings):
    """absorbers: 36 light masses swing 60-80 times the beam; the beam's line spans
    max |Y| = 1, every mass sits within the clip, and the legend says how far they go."""
    scene = mstmm.load_scene(EXAMPLES / "absorbers.toml")
    fig = plot.figure2(scene, modes=4, n=200)
    curves = lines(fig, "mode", ax=1)
    assert len(curves) == 4
    for curve in curves:
        assert np.max(np.abs(curve.get_ydata())) == pytest.approx(1.0)
        assert "masses to" in curve.get_label()
    for mass in lines(fig, "mass", ax=1):
        assert np.max(np.abs(mass.get_ydata())) <= plot.MASS_CLIP
    assert lines(fig, "mass-clipped", ax=1)
    assert "clipped at 1.5" in fig.axes[1].get_ylabel()
    _inside_canvas(fig)


def test_fifty_modes_on_a_colour_scale_inside_the_figure(no_warnings):
    """metamaterial --modes 50: a colour bar of mode numbers instead of a legend that ran
    off the figure (modes 28-50 lost) and over panel (b)."""
    scene = mstmm.load_scene(EXAMPLES / "metamaterial.toml")
    fig = plot.figure2(scene, modes=50, n=200)
    curves = lines(fig, "mode", ax=1)
    assert len(curves) == 48  # two rigid-body zeros
    legend = [t.get_text() for t in fig.axes[1].get_legend().get_texts()]
    assert legend == ["spring-mass (200)"]
    (bar,) = [a for a in fig.axes if a.get_label() == "<colorbar>"]
    assert "mode number" in bar.get_xlabel()
    assert bar.get_xlim() == (3.0, 50.0)
    _inside_canvas(fig)


def test_plot_a_buckled_cantilever_says_buckled(tmp_path):
    """axial_force < 0 is compression: beyond the buckling load there is nothing to plot;
    plot says so as solve does (exit 3, the same line), instead of an IndexError."""
    text = (
        'name = "buckled"\n[beam]\nlength = 10.0\nEI = 7.8e5\nmass_per_length = 78.0\n'
        'axial_force = -1e8\nleft = "clamped"\nright = "free"\n'
    )
    path = tmp_path / "buckled.toml"
    path.write_text(text)
    with pytest.raises(plot.Buckled, match="buckled: the axial forces exceed"):
        plot.figure2(mstmm.load_scene(path))
    out = tmp_path / "b.png"
    runs = [
        subprocess.run([sys.executable, "-m", "mstmm", *args, str(path)], capture_output=True,
                       text=True, timeout=300)
        for args in (["plot", "-o", str(out)], ["solve"])
    ]  # fmt: skip
    assert [r.returncode for r in runs] == [3, 3], runs[0].stderr
    assert runs[0].stdout == runs[1].stdout and "buckled" in runs[0].stdout
    assert not out.exists()


def test_every_sweep_field_has_its_unit():
    """Units from the declarations (catalog.SEGMENT_PHYSICS, each kind's KEYS): every
    field a sweep may vary has one; only a loss factor is dimensionless."""
    from mstmm.study import _paths

    scene = mstmm.scene_from_dict(
        {
            "beam": {"length": 4.0, "EI": 1e4, "mass_per_length": 10.0, "left": "clamped",
                     "right": "free", "axial_force": 10.0, "kappa_GA": 1e6, "loss_factor": 0.01},
            "attachments": [
                {"type": "hinge", "x": 1.0, "k": 1e3},
                {"type": "oscillator_chain", "x": 2.0, "k": [1e3, 1e3], "m": [1.0, 1.0]},
                {"type": "dashpot", "x": 2.5, "c": 3.0},
                {"type": "mass", "x": 3.0, "m": 5.0},
            ],
        }
    )  # fmt: skip
    units = {path: field_unit(scene, path) for path in _paths(scene)}
    assert [p for p, u in units.items() if u == "-"] == ["beam.loss_factor"]
    assert units["beam.axial_force"] == units["beam.kappa_GA"] == "N"
    assert units["beam.foundation_k"] == "N/m^2" and units["beam.rho_I"] == "kg m"
    assert units["attachments[0].k"] == "N m/rad" and units["attachments[1].k[1]"] == "N/m"
    assert units["attachments[2].c"] == "N s/m" and units["attachments[3].J"] == "kg m^2"


def test_axial_force_sweep_marks_the_buckled_range(no_warnings):
    """A cantilever from -1e5 N (compression) to 1e5 N: the axis in N, the range beyond the
    buckling load pi^2 EI / (4 L^2) shaded and labelled "buckled", no warning."""
    scene = mstmm.scene_from_dict(
        {"beam": {"length": 10.0, "EI": 7.8e5, "mass_per_length": 78.0, "left": "clamped",
                  "right": "free"}}
    )  # fmt: skip
    forces = np.linspace(-1e5, 1e5, 11)
    fig = plot.veering(scene, "beam.axial_force", forces, modes=2)
    ax = fig.axes[0]
    assert ax.get_xlabel() == "beam.axial_force [N]"
    (span,) = [p for p in ax.patches if p.get_gid() == "buckled"]
    x = np.array([span.get_x(), span.get_x() + span.get_width()])
    critical = -(np.pi**2) * 7.8e5 / (4 * 10.0**2)
    assert x.min() == -1e5 and x.max() == pytest.approx(critical, rel=1e-9)
    assert [t.get_text() for t in ax.texts if t.get_gid() == "buckled-text"] == ["buckled"]
    assert "buckled" in [t.get_text() for t in fig.legends[0].get_texts()]
    for curve in lines(fig, "mode"):
        y = curve.get_ydata()
        assert np.all(np.isnan(y[forces < critical])) and np.all(y[forces > critical] > 0)
    _inside_canvas(fig)


def test_damped_sweep_draws_w_d_and_zeta(no_warnings):
    """The TMD designer's figure: w_d and zeta of each mode against the damper's c (no
    ComplexWarning); the two modes the damper splits reach one zeta near Den Hartog's c."""
    scene = mstmm.load_scene(EXAMPLES / "tmd_den_hartog.toml")
    cs = np.logspace(-1, 2, 7)
    fig = plot.veering(scene, "attachments[0].c", cs, modes=2)
    ax_w, ax_z = fig.axes[:2]
    assert "[rad/s]" in ax_w.get_ylabel() and "zeta" in ax_z.get_ylabel()
    assert ax_z.get_xlabel() == "attachments[0].c [N s/m]"
    omega = mstmm.sweep(scene, {"attachments[0].c": cs}, modes=2)
    w = [c.get_ydata() for c in lines(fig, "mode", ax=0)]
    z = [c.get_ydata() for c in lines(fig, "mode", ax=1)]
    np.testing.assert_array_equal(np.array(w).T, omega.real)
    np.testing.assert_allclose(np.array(z).T, omega.imag / np.abs(omega))
    assert 0.0 < np.min(z) and np.max(z) < 1.0
    _inside_canvas(fig)


def test_frf_legend_names_the_plotted_quantity(scene, no_warnings):
    omegas = np.linspace(50.0, 400.0, 200)
    out = ["displacement:x=1.0", "rotation:x=1.0"]
    names = {
        quantity: [t.get_text() for t in plot.frf_figure(
            scene, "force:x=0.5", out, omegas, quantity=quantity).axes[0].get_legend().get_texts()]
        for quantity in ("receptance", "mobility", "accelerance")
    }  # fmt: skip
    assert names["receptance"][0].startswith("displacement:x=1.0")
    assert names["mobility"][0].startswith("velocity:x=1.0")
    assert names["accelerance"][0].startswith("acceleration:x=1.0")
    assert names["accelerance"][1].startswith("angular acceleration:x=1.0")


def test_undamped_frf_phase_falls_through_each_resonance(scene, no_warnings):
    """An undamped response is real: its sign flips by exactly 180 deg, which unwrapping
    cannot orient (it toggled 0/180). Through a resonance the phase falls by 180."""
    omegas = np.linspace(20.0, 2000.0, 4000)
    fig = plot.frf_figure(scene, "force:x=1.0", "displacement:x=1.0", omegas)
    (phase,) = [ln.get_ydata() for ln in fig.axes[1].get_lines() if ln.get_gid() == "phase"]
    assert np.allclose(np.mod(phase, 180.0), 0.0)
    roots = mstmm.solve(scene, band=(20.0, 2000.0), shapes=False).omega
    changed = 0
    for r in roots:
        i = np.searchsorted(omegas, r)
        step = phase[i] - phase[i - 1]
        assert step in (0.0, -180.0), (r, step)
        changed += step != 0.0
    assert changed >= 3
    assert np.all(np.abs(np.diff(phase)) <= 180.0)


def test_frf_magnitude_axis_clipped_and_said(scene, no_warnings):
    """A response at x = 1e-20 next to the clamped end is ~1e-40 of the others: the axis
    stops 10 decades below the peak and says so."""
    omegas = np.linspace(50.0, 400.0, 200)
    fig = plot.frf_figure(scene, "force:x=0.5", ["displacement:x=1e-20", "displacement:x=1.0"],
                          omegas)  # fmt: skip
    ax = fig.axes[0]
    mags = [ln.get_ydata() for ln in ax.get_lines() if ln.get_gid() == "frf"]
    peak = max(np.nanmax(m) for m in mags)
    assert np.nanmin(mags[0]) < 1e-20 * peak
    lo, hi = ax.get_ylim()
    assert lo == pytest.approx(peak * 10.0**-plot.FRF_DECADES) and hi >= peak
    (note,) = [t for t in ax.texts if t.get_gid() == "clip-note"]
    assert "10 decades below the peak" in note.get_text()
    _inside_canvas(fig)


def test_dispersion_legend_tells_the_pairs_and_parts_apart(no_warnings):
    from mstmm.bands import bands, cell_of

    cell = cell_of(mstmm.load_scene(EXAMPLES / "metamaterial.toml"))
    fig = plot.dispersion(bands(cell, band=(0.0, 6000.0), points=60))
    (legend,) = fig.legends
    labels = [t.get_text() for t in legend.get_texts()]
    for pair in plot._PAIRS:
        assert f"{pair}: Re k L / pi" in labels and f"{pair}: Im k L" in labels
    assert "stop band" in labels and "band edge" in labels
    for ax in fig.axes[:2]:
        assert "[" in ax.get_xlabel() and "]" in ax.get_xlabel()
    _inside_canvas(fig)

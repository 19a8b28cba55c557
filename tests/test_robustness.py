"""Issue 20 items 7, 8, 9 (frf), 10 and 15: what a new user hit, each against a closed form.

* 7: ``frf`` of a structure with a rigid-body mode over a band from 0: NaN (JSON null)
  at omega = 0 with one warning, every other point the free-free beam's closed-form end
  receptance; a cantilever at omega = 0 gives its static compliance L^3 / (3 EI).
* 8: ``frf --points 100000000``: exit 2 at once, one line naming ``--points``; the CSV is
  computed and written in chunks (the peak memory of 100000 points stays small).
* 9: Ctrl-C in ``frf`` and ``plot --frf`` over 2 million points: exit 130 and
  ``mstmm: interrupted`` within 2 s, nothing written.
* 10: ``--out`` / ``-o`` where no file can be made (a read-only directory, a path under
  a file): exit 2 naming the option and the directory, for every command that writes.
* 15: ``frf --band 1 1e300`` refused as ``solve --band``; ``plot --input`` without
  ``--frf`` refused; a damped scene's ``solve --shapes --format table`` prints a summary
  of its shapes; the API refuses ``modes=0``, a reversed band, a negative or NaN omega.
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
import subprocess
import sys
import tempfile
import time
import tracemalloc
import warnings
from pathlib import Path

import mpmath
import numpy as np
import pytest
from interrupt import interrupt

import mstmm
from mstmm import response
from mstmm.cli import main

L, EI, MBAR = 2.0, 3.0, 1.5
FREE_FREE = f"""name = "free_free"
[beam]
length = {L}
EI = {EI}
mass_per_length = {MBAR}
left = "free"
right = "free"
"""
END = ["--input", "force:x=0", "--output", "displacement:x=0"]


def free_free_end(w: float) -> float:
    """Point receptance at an end of a free-free uniform beam (closed form, 40 digits):
    (cos bL sinh bL - sin bL cosh bL) / (EI b^3 (1 - cos bL cosh bL)), b^4 = mbar w^2 / EI;
    it tends to the rigid body's -(1/m + (L/2)^2 / J) / w^2 = -4 / (m w^2) as w -> 0."""
    with mpmath.workdps(40):
        b = mpmath.sqrt(mpmath.sqrt(MBAR * mpmath.mpf(w) ** 2 / EI))
        x = b * L
        num = mpmath.cos(x) * mpmath.sinh(x) - mpmath.sin(x) * mpmath.cosh(x)
        return float(num / (EI * b**3 * (1 - mpmath.cos(x) * mpmath.cosh(x))))


@pytest.fixture
def free_free(tmp_path):
    path = tmp_path / "free_free.toml"
    path.write_text(FREE_FREE)
    return path


def _run(*args: str, cwd=None):
    return subprocess.run(
        [sys.executable, "-m", "mstmm", *args],
        capture_output=True,
        text=True,
        timeout=300,
        cwd=cwd,
    )


def _one_error(stderr: str, *words: str) -> str:
    lines = [ln for ln in stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("mstmm: error: "), stderr
    for w in words:
        assert w in lines[0], lines[0]
    return lines[0]


# ---------------------------------------------------------------------------
# item 7: a rigid-body mode at omega = 0


def test_frf_api_rigid_body_mode_at_zero(free_free):
    scene = mstmm.load_scene(free_free)
    w = np.linspace(0.0, 3.0, 13)
    with pytest.warns(RuntimeWarning, match=r"omega = 0 the receptance is infinite.*rigid-body"):
        H = mstmm.frf(scene, "force:x=0", "displacement:x=0", w)
    assert np.isnan(H[0].real) and np.isnan(H[0].imag)
    want = np.array([free_free_end(v) for v in w[1:]])
    assert np.all(np.abs(H[1:] - want) <= 1e-9 * np.abs(want))
    # close to 0 the rigid body's -4 / (m w^2) (m = 3 kg), as the closed form says
    h = mstmm.frf(scene, "force:x=0", "displacement:x=0", [1e-3])[0]
    assert abs(h.real / (-4.0 / (MBAR * L * 1e-6)) - 1.0) < 1e-6
    for quantity in ("mobility", "accelerance"):
        with pytest.warns(RuntimeWarning, match=f"the {quantity} is undefined"):
            Q = mstmm.frf(scene, "force:x=0", "displacement:x=0", w[:2], quantity=quantity)
        assert np.isnan(Q[0]) and np.isfinite(Q[1])


def test_frf_without_rigid_body_mode_at_zero_is_the_static_compliance():
    scene = mstmm.load_scene(mstmm.example_path("bare_cantilever"))
    beam = scene.beam
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no warning: nothing is infinite
        H = mstmm.frf(scene, "force:x=1.0", "displacement:x=1.0", [0.0, 0.0])
    want = beam.length**3 / (3.0 * beam.EI)
    assert np.all(np.abs(H - want) <= 1e-12 * want)


def test_frf_cli_rigid_body_mode_band_from_zero(free_free):
    r = _run("frf", str(free_free), *END, "--band", "0", "2", "--points", "5", "--format", "json")
    assert r.returncode == 0, r.stderr
    data = json.loads(r.stdout)
    assert data["re"][0][0] is None and data["im"][0][0] is None
    want = [free_free_end(w) for w in data["omega"][1:]]
    assert np.allclose(data["re"][0][1:], want, rtol=1e-9, atol=0.0)
    lines = r.stderr.splitlines()
    assert any("receptance is infinite" in ln and "rigid-body mode" in ln for ln in lines)
    assert not any("natural frequency" in ln for ln in lines), r.stderr  # not the reason
    r = _run("frf", str(free_free), *END, "--band", "0", "2", "--points", "5")
    rows = list(csv.reader(io.StringIO(r.stdout)))
    assert (
        r.returncode == 0
        and rows[1][2] == "nan"
        and float(rows[2][2]) == pytest.approx(free_free_end(0.5), rel=1e-9)
    )


# ---------------------------------------------------------------------------
# item 8: bounded points, streamed output


def test_frf_too_many_points_exits_2_at_once(free_free, tmp_path):
    t0 = time.perf_counter()
    out = tmp_path / "out" / "h.csv"
    out.parent.mkdir()
    r = _run("frf", str(free_free), *END, "--band", "1", "2", "--points", "100000000")
    assert r.returncode == 2 and r.stdout == ""
    _one_error(r.stderr, "--points", "100000000", "1e+07")
    r = _run(
        "frf", str(free_free), *END, "--output", "rotation:x=1", "--band", "1", "2",
        "--points", "6000000", "--out", str(out),
    )  # fmt: skip
    assert r.returncode == 2, r.stderr
    _one_error(r.stderr, "--points", "2 output(s)")
    assert time.perf_counter() - t0 < 60.0
    assert list(out.parent.iterdir()) == []


def test_frf_api_bounds_responses(free_free, monkeypatch):
    scene = mstmm.load_scene(free_free)
    monkeypatch.setattr(response, "MAX_RESPONSES", 10)
    with pytest.raises(ValueError, match="more than"):
        mstmm.frf(scene, "force:x=0", ["displacement:x=0", "rotation:x=0"], np.ones(6))


def test_frf_csv_is_streamed_in_chunks(free_free, tmp_path):
    """100000 points to a file: right values, and the peak memory (tracemalloc, numpy's
    arrays included) far below the whole output's text (about 9 MB)."""
    out = tmp_path / "h.csv"
    args = ["frf", str(free_free), *END, "--band", "0.5", "40", "--points", "100000"]
    main([*args, "--points", "10"])  # load the kernel first
    tracemalloc.start()
    try:
        status = main([*args, "--out", str(out)])
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert status == 0
    text = out.read_text()
    assert len(text) > 8_000_000
    assert peak < 6_000_000, peak
    rows = list(csv.reader(io.StringIO(text)))
    assert len(rows) == 100_001
    for k in (1, 2, 50_000, 99_999, 100_000):
        w = float(rows[k][0])
        assert float(rows[k][2]) == pytest.approx(free_free_end(w), rel=1e-8)


# ---------------------------------------------------------------------------
# item 9: Ctrl-C


@pytest.mark.parametrize("command", ["frf", "plot"])
def test_ctrl_c_in_frf_exits_130_within_2_s(command, tmp_path):
    out = tmp_path / ("h.csv" if command == "frf" else "h.png")
    args = ["frf"] if command == "frf" else ["plot", "--frf"]
    args += [
        "--input", "force:x=1.0", "--output", "displacement:x=0.5", "--band", "0", "3000",
        "--points", "2000000", "--out", str(out),
    ]  # fmt: skip
    status, out_text, err, took = interrupt(args, 6.0)  # past the kernel's load
    assert status == 130, err
    assert err == "mstmm: interrupted\n"
    assert took < 2.0, took
    assert out_text == "" and list(tmp_path.iterdir()) == []  # nothing half-written


# ---------------------------------------------------------------------------
# item 10: --out where nothing can be written


def _commands(scene, out_file):
    """Every command that writes a file, with ``out_file`` as its output."""
    return [
        ["frf", str(scene), *END, "--band", "1", "2", "--points", "3", "--out", str(out_file)],
        ["sweep", str(scene), "--vary", "beam.EI=1,2", "--modes", "1", "--out", str(out_file)],
        ["plot", str(scene), "-o", str(out_file.with_suffix(".png"))],
        ["derive", str(scene), "--out", str(out_file)],
    ]


def test_out_under_a_file_exits_2_naming_option_and_directory(free_free, tmp_path):
    """Root-independent: the 'directory' is a regular file."""
    blocker = tmp_path / "a_file"
    blocker.write_text("x")
    for args in _commands(free_free, blocker / "out.csv"):
        r = _run(*args)
        assert r.returncode == 2, (args, r.stderr)
        line = _one_error(r.stderr, "--out", str(blocker), "not a directory")
        assert ".tmp" not in line
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a_file", "free_free.toml"]
    assert blocker.read_text() == "x"


def test_out_in_read_only_directory_exits_2(free_free, tmp_path):
    """A directory chmod'ed read-only; root writes there anyway (then only the exit 2 on
    a directory that refuses everyone, /sys where it does, is checked)."""
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    targets = [ro] if not os.access(ro, os.W_OK) else []
    try:
        with tempfile.TemporaryFile(dir="/sys"):
            pass
    except OSError:
        targets.append(Path("/sys"))
    if not targets:
        ro.chmod(0o755)
        pytest.skip("running as root: every directory here takes a file")
    try:
        for target in targets:
            for args in _commands(free_free, target / "out_mstmm.csv"):
                r = _run(*args)
                assert r.returncode == 2, (args, r.stderr)
                line = _one_error(r.stderr, "--out", f"cannot write to {target}")
                assert ".tmp" not in line and "Traceback" not in r.stderr
                assert not (target / "out_mstmm.csv").exists()
        assert list(ro.iterdir()) == []
    finally:
        ro.chmod(0o755)


def test_write_atomically_names_the_directory(tmp_path):
    from mstmm import output

    blocker = tmp_path / "f"
    blocker.write_text("")
    with pytest.raises(output.CannotWrite, match=f"cannot write to {blocker}"):
        output.write_atomically(blocker / "x.csv", "text")
    # a file written is readable as any new file is (not mkstemp's 0600)
    mask = os.umask(0o022)
    os.umask(mask)
    output.write_atomically(tmp_path / "y.csv", "text")
    assert (tmp_path / "y.csv").stat().st_mode & 0o777 == 0o666 & ~mask
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f", "y.csv"]


# ---------------------------------------------------------------------------
# item 15


def test_frf_band_beyond_float64_refused_as_solve(free_free):
    r = _run("frf", str(free_free), *END, "--band", "1", "1e300")
    assert r.returncode == 2 and r.stdout == ""
    frf_line = _one_error(r.stderr, "--band", "float64", "1e+300")
    s = _run("solve", str(free_free), "--band", "1", "1e300")
    assert s.returncode == 2
    assert frf_line == _one_error(s.stderr)  # the same bound, the same words
    scene = mstmm.load_scene(free_free)
    with pytest.raises(ValueError, match="omega: HI is beyond"):
        mstmm.frf(scene, "force:x=0", "displacement:x=0", [1.0, 1e300])


def test_frf_api_refuses_negative_and_nan_omega(free_free):
    scene = mstmm.load_scene(free_free)
    for bad, words in (([1.0, -1.0], ">= 0 rad/s; index 1"), ([math.nan], "finite")):
        with pytest.raises(ValueError, match=words) as info:
            mstmm.frf(scene, "force:x=0", "displacement:x=0", np.array(bad))
        assert "np.float64" not in str(info.value)
    with pytest.raises(ValueError, match="finite"):
        mstmm.frf(scene, "force:x=0", "displacement:x=0", [complex(1.0, math.inf)])
    assert mstmm.frf(scene, "force:x=0", ["displacement:x=0"], []).shape == (0, 1, 1)


def test_solve_api_refuses_what_the_cli_refuses(free_free):
    scene = mstmm.load_scene(free_free)
    with pytest.raises(ValueError, match="modes: must be a whole number >= 1"):
        mstmm.solve(scene, modes=0)
    with pytest.raises(ValueError, match="band: hi must not be below lo"):
        mstmm.solve(scene, band=(10.0, 1.0))
    with pytest.raises(ValueError, match="finite"):
        mstmm.solve(scene, band=(0.0, math.nan))
    with pytest.raises(ValueError, match="not both"):
        mstmm.solve(scene, modes=2, band=(0.0, 1.0))
    # still right: the free-free beam's two rigid-body zeros and 22.373 / L^2 sqrt(EI/m)
    sol = mstmm.solve(scene, modes=3, shapes=False)
    b1 = 4.730040744862704
    assert sol.omega[:2].tolist() == [0.0, 0.0]
    assert sol.omega[2] == pytest.approx((b1 / L) ** 2 * math.sqrt(EI / MBAR), rel=1e-12)


def test_plot_input_without_frf_refused(free_free, tmp_path):
    out = tmp_path / "p.png"
    r = _run("plot", str(free_free), "-o", str(out), "--input", "force:x=0")
    assert r.returncode == 2
    _one_error(r.stderr, "--input", "--frf")
    r = _run("plot", str(free_free), "-o", str(out), "--output", "displacement:x=0")
    assert r.returncode == 2
    _one_error(r.stderr, "--output", "--frf")
    assert not out.exists()


def test_damped_shapes_table(tmp_path):
    """A uniform cantilever with a loss factor: w = w_n sqrt(1 + i eta) with the undamped
    (real) shapes, so each shape's complexity is 0 and |Y| peaks at the free end."""
    eta = 0.02
    path = tmp_path / "lossy.toml"
    path.write_text(
        '[beam]\nlength = 1.0\nEI = 1.0\nmass_per_length = 1.0\nleft = "clamped"\n'
        f'right = "free"\nloss_factor = {eta}\n'
    )
    r = _run("solve", str(path), "--modes", "3", "--shapes")
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    at = next(i for i, ln in enumerate(lines) if ln.startswith("damped mode shapes"))
    rows = [ln.split() for ln in lines[at + 2 : at + 5]]
    assert len(rows) == 3 and len(lines) == at + 5
    for n, row in enumerate(rows, start=1):
        b = [1.8751040687119611, 4.6940911329741746, 7.8547574382376126][n - 1]
        w = b**2 * np.sqrt(1.0 + 1j * eta)
        assert float(row[1]) == pytest.approx(w.real, rel=1e-10)
        assert float(row[2]) == pytest.approx(w.imag, rel=1e-8)
        assert float(row[3]) == 1.0  # the tip
        assert row[4] == "-"  # no hanging mass
        assert abs(float(row[5])) < 1e-12

"""Failure modes of the command line: one clear line, a non-zero status, no traceback.

Issue 6 lists them: a bad scene (``tests/test_scene.py`` covers every class), a
band with no roots, a kernel cache that cannot be written, numba missing. Also
``--verbose`` (where the time went) and the empty-band check against the
closed-form cantilever frequencies.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys

import mstmm
from mstmm.cli import main


def _cantilever_omega(scene, n: int) -> float:
    """n-th root of 1 + cos(b) cosh(b) = 0 (closed form, by bisection), as omega."""
    lo, hi = (n - 0.5) * math.pi, (n + 0.5) * math.pi - 1e-9
    f = lambda b: 1.0 + math.cos(b) * math.cosh(b)  # noqa: E731
    if n == 1:
        lo, hi = 1.0, 3.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if f(lo) * f(mid) <= 0.0:
            hi = mid
        else:
            lo = mid
    b = 0.5 * (lo + hi)
    L, EI, mbar = scene.beam.length, scene.beam.EI, scene.beam.mass_per_length
    return (b / L) ** 2 * math.sqrt(EI / mbar)


def _run(*args: str, env: dict | None = None, code: str | None = None):
    cmd = [sys.executable, "-c", code] if code else [sys.executable, "-m", "mstmm", *args]
    return subprocess.run(
        cmd, capture_output=True, text=True, env={**os.environ, **(env or {})}, timeout=300
    )


def _one_error_line(stderr: str, *words: str) -> str:
    lines = [ln for ln in stderr.splitlines() if ln.strip()]
    assert len(lines) == 1, stderr
    assert lines[0].startswith("mstmm: error: "), stderr
    assert "Traceback" not in stderr
    for w in words:
        assert w in lines[0], lines[0]
    return lines[0]


def test_band_between_two_cantilever_modes_has_no_roots(capsys):
    """Strictly between the closed-form 2nd and 3rd modes of the bare cantilever: nothing."""
    path = mstmm.example_path("bare_cantilever")
    scene = mstmm.load_scene(path)
    w2, w3 = _cantilever_omega(scene, 2), _cantilever_omega(scene, 3)
    lo, hi = w2 * (1 + 1e-6), w3 * (1 - 1e-6)
    status = main(["solve", str(path), "--band", repr(lo), repr(hi), "--format", "json"])
    out, err = capsys.readouterr()
    assert status == 1
    assert out == ""  # nothing half-written
    _one_error_line(err, "no natural frequency in the band", "count confirms")
    # and the band that holds the 3rd mode gives exactly it
    status = main(
        ["solve", str(path), "--band", repr(lo), repr(w3 * (1 + 1e-6)), "--format", "json"]
    )
    out, err = capsys.readouterr()
    assert status == 0, err
    got = json.loads(out)["omega"]
    assert len(got) == 1 and abs(got[0] - w3) <= 1e-12 * w3


def test_kernel_cache_not_writable(tmp_path):
    """A topology that is not bundled, with the cache under a regular file: one line, status 1."""
    blocker = tmp_path / "a_file"
    blocker.write_text("")
    scene = tmp_path / "pinned.toml"
    scene.write_text(
        "[beam]\nlength = 1.0\nEI = 1.0\nmass_per_length = 1.0\n"
        'left = "pinned"\nright = "sliding"\n'
    )
    result = _run("solve", str(scene), env={"MSTMM_CACHE": str(blocker / "cache")})
    assert result.returncode == 1
    assert result.stdout == ""
    _one_error_line(result.stderr, "kernel cache", "not writable", str(blocker / "cache"))


def test_numba_missing():
    """numba not importable: one line naming it, status 1, no traceback."""
    code = (
        "import sys; sys.modules['numba'] = None\n"
        "from mstmm.cli import main\n"
        "raise SystemExit(main(['solve', '--modes', '3']))\n"
    )
    result = _run(code=code)
    assert result.returncode == 1
    assert result.stdout == ""
    _one_error_line(result.stderr, "dependency is missing", "numba")


def test_debug_shows_the_traceback():
    code = (
        "import sys; sys.modules['numba'] = None\n"
        "from mstmm.cli import main\n"
        "raise SystemExit(main(['--debug', 'solve', '--modes', '3']))\n"
    )
    result = _run(code=code)
    assert result.returncode != 0
    assert "Traceback" in result.stderr


def test_verbose_says_where_the_time_went(capsys):
    assert main(["--verbose", "solve", "--modes", "3", "--format", "json"]) == 0
    out, err = capsys.readouterr()
    json.loads(out)  # standard output stays one JSON object
    phases = [ln.split(": ")[3] for ln in err.splitlines() if ln.startswith("mstmm: time: ")]
    assert {
        "scene and kernel module",
        "machine code (numba cache load or compile)",
        "root search, refinement, count",
        "total",
    } <= set(phases), err
    total = float(err.split("total: ")[1].split()[0])
    assert total > 0.0


def test_verbose_in_a_fresh_process_reports_start_up():
    result = _run("--verbose", "solve", "--modes", "2")
    assert result.returncode == 0, result.stderr
    assert "start-up (Python, numpy, numba, mstmm imports)" in result.stderr


def test_progress_draws_only_when_enabled(capsys, monkeypatch):
    """Status lines and bars go to standard error, and only when enabled (a terminal)."""
    from mstmm import progress

    monkeypatch.setattr(progress, "enabled", False)
    with progress.status("deriving"):
        pass
    bar = progress.Bar(3, "sweep")
    bar.update(3)
    bar.close()
    assert capsys.readouterr() == ("", "")
    monkeypatch.setattr(progress, "enabled", True)
    monkeypatch.setattr(progress, "KEEP_AFTER", 0.0)
    with progress.status("deriving the kernel"):
        pass
    bar = progress.Bar(4, "sweep")
    bar.update(4)
    bar.close()
    out, err = capsys.readouterr()
    assert out == ""
    assert "mstmm: deriving the kernel: " in err
    assert "[" + "#" * 40 + "] 4/4" in err


def test_sweep_progress_bar_counts_every_point(capsys):
    scene = mstmm.load_scene(mstmm.example_path())
    omega = mstmm.sweep(
        scene,
        {"attachments[2].k": [1e5 * (1 + i / 200) for i in range(200)]},
        modes=2,
        progress=True,
    )
    assert omega.shape == (200, 2)
    err = capsys.readouterr().err
    assert "200/200" in err

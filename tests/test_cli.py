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

import pytest

import mstmm
from mstmm.cli import main


def _cantilever_omega(scene, n: int) -> float:
    """n-th root of 1 + cos(b) cosh(b) = 0 (closed form, by bisection), as omega."""
    # the n-th root lies within 0.2 of (n - 1/2) pi (1.8751, 4.6941, 7.8548, ...)
    lo, hi = (n - 0.5) * math.pi - 0.5, (n - 0.5) * math.pi + 0.5
    f = lambda b: 1.0 + math.cos(b) * math.cosh(b)  # noqa: E731
    assert f(lo) * f(hi) < 0.0
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
    """A kernel that is not bundled (a point mass: every end pair of a bare beam or of
    spring-masses is), with the cache under a regular file: one line, status 1."""
    blocker = tmp_path / "a_file"
    blocker.write_text("")
    scene = tmp_path / "pinned.toml"
    scene.write_text(
        "[beam]\nlength = 1.0\nEI = 1.0\nmass_per_length = 1.0\n"
        'left = "pinned"\nright = "sliding"\n'
        '[[attachments]]\ntype = "mass"\nx = 0.5\nm = 0.1\n'
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


# ---------------------------------------------------------------------------
# Issue 12 items 7 and 8: version, help, exit statuses, strict JSON, Ctrl-C, sweep errors


def test_version(capsys):
    import pytest

    with pytest.raises(SystemExit) as info:
        main(["--version"])
    assert info.value.code == 0
    assert capsys.readouterr().out.strip() == f"mstmm {mstmm.__version__}"


def test_every_option_has_help_and_the_exit_statuses_are_documented():
    import argparse

    from mstmm.cli import build_parser

    parser = build_parser()
    assert "exit status" in parser.format_help() and "130" in parser.format_help()
    (sub,) = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    for name, command in sub.choices.items():
        text = command.format_help()
        assert "3    results written, but a root is NOT TRUSTED" in text, name
        for action in command._actions:
            assert action.help, (name, action.dest)
            if action.default not in (None, False, argparse.SUPPRESS) and action.dest != "help":
                assert "default" in action.help, (name, action.dest)
    for name in ("solve", "plot"):  # one rule for --modes
        (modes,) = [a for a in sub.choices[name]._actions if a.dest == "modes"]
        assert "rigid-body zeros included" in modes.help


def test_untrusted_roots_exit_3():
    """The paper's determinant loses its digits past the 10th mode: flagged, status 3."""
    result = _run("solve", "--formulation", "paper", "--modes", "14")
    assert result.returncode == 3, result.stderr
    assert "NOT TRUSTED" in result.stdout
    assert "mstmm: warning: " in result.stderr and "Traceback" not in result.stderr


def _solution_with(scene, **changes):
    import numpy as np

    from mstmm.solve import Solution

    base = dict(
        scene=scene,
        omega=np.array([100.0, 200.0]),
        multiplicity=np.array([1, 1]),
        converged=np.array([True, True]),
        formulation="stable",
        kernel_origin="test",
        timings={"load": 0.0, "compile": 0.0, "scan_refine": 0.0},
        count_checked=True,
    )
    return Solution(**(base | changes))


def test_json_never_holds_nan(monkeypatch, capsys):
    """A non-finite number forced into a Solution: null in valid JSON, a warning, status 3."""
    import sys

    import numpy as np

    solve_module = sys.modules["mstmm.solve"]
    scene = mstmm.load_scene(mstmm.example_path())
    forced = _solution_with(
        scene,
        omega=np.array([100.0, np.nan]),
        converged=np.array([True, False]),
        timings={"load": np.inf, "compile": 0.0, "scan_refine": 0.0},
    )
    monkeypatch.setattr(solve_module, "solve", lambda *a, **k: forced)
    status = main(["solve", "--format", "json"])
    out, err = capsys.readouterr()

    def reject(name):
        raise AssertionError(f"invalid JSON constant {name}")

    data = json.loads(out, parse_constant=reject)
    assert data["omega"] == [100.0, None] and data["timings"]["load"] is None
    assert data["converged"] == [True, False]
    assert status == 3
    assert "3 non-finite number(s) written as null" in err and "omega[1]" in err  # and hz[1]


def test_sigint_prints_one_line_and_exits_130():
    """Ctrl-C during a long solve (a band of about 7000 modes): one line, status 130."""
    from interrupt import interrupt

    status, _, err, _ = interrupt(["solve", "--band", "0", "3e10", "--format", "csv"], 2.0)
    assert status == 130, err
    assert err == "mstmm: interrupted\n"


def _sweep_error(*args: str) -> str:
    result = _run("sweep", str(mstmm.example_path()), *args)
    assert result.returncode == 2, result.stderr
    assert result.stdout == ""
    return _one_error_line(result.stderr)


def test_sweep_zero_points_missing_directory_and_repeated_field(tmp_path):
    line = _sweep_error("--vary", "attachments[2].k=LOG:1e3:1e9:0")
    assert "--vary attachments[2].k" in line and "at least 1 point" in line
    line = _sweep_error("--vary", "beam.EI=LOG:-1:1e9:3")
    assert "lo > 0" in line
    missing = tmp_path / "nowhere" / "out.csv"
    line = _sweep_error("--vary", "beam.EI=1e4,2e4", "--out", str(missing))
    assert "--out" in line and "directory does not exist" in line and str(missing.parent) in line
    assert not missing.parent.exists()
    line = _sweep_error("--vary", "beam.EI=1e4,2e4", "--vary", "beam.EI=3e4,4e4")
    assert "--vary beam.EI" in line and "twice" in line


def test_sweep_point_beyond_float64_exits_2():
    line = _sweep_error("--vary", "attachments[1].k=1e5,5e-324")
    assert "attachments[1].k" in line and "point 1" in line and "5e-324" in line


# ---------------------------------------------------------------------------
# Issue 12 item 7c: mstmm show has no size limit


def _scene_with(tmp_path, n: int, left: str = "clamped", right: str = "free"):
    text = (
        f'[beam]\nlength = 1.0\nEI = 1.0\nmass_per_length = 1.0\nleft = "{left}"\n'
        f'right = "{right}"\n'
    )
    for i in range(n):
        text += (
            f'[[attachments]]\ntype = "spring_mass"\nx = {(i + 1) / (n + 1)}\nk = 1.0\nm = 1.0\n'
        )
    path = tmp_path / f"n{n}.toml"
    path.write_text(text)
    return path


def test_show_ten_attachments_is_quick_and_small(tmp_path):
    import time

    path = _scene_with(tmp_path, 10)
    t0 = time.perf_counter()
    result = _run("show", str(path))
    assert time.perf_counter() - t0 < 60.0  # a few seconds; generous on a busy machine
    assert result.returncode == 0, result.stderr
    out = result.stdout
    assert len(out) < 20_000
    assert max(len(line) for line in out.splitlines() if str(path) not in line) < 200
    for part in ("beam segment U_B(l)", "spring U_S(k)", "lumped mass U_M(m)", "U_I1", "U_I2"):
        assert part in out
    assert "H_I1" in out and "H_I2" in out
    assert "U_bar: 14x14" in out  # 4 + 2 n + 4 states, half known at the boundaries
    assert "--full" in out and "det U_bar =" not in out


def test_show_small_scene_prints_u_bar_and_det_in_latex(tmp_path):
    result = _run("show", "--latex", str(_scene_with(tmp_path, 0)))
    assert result.returncode == 0, result.stderr
    assert "U_bar =\n\\left[\\begin{matrix}" in result.stdout
    assert "det U_bar =" in result.stdout and "\\cosh" in result.stdout


def test_show_pattern_is_that_of_the_evaluated_derivation():
    """The fast (unevaluated) structure has the zero pattern of the full SymPy derivation."""
    from mstmm.derive import symbolic

    for n, (left, right) in [
        (0, ("pinned", "free")),
        (2, ("clamped", "free")),
        (2, ("free", "sliding")),
    ]:
        scene = mstmm.scene_from_dict(
            {
                "beam": {
                    "length": 1.0,
                    "EI": 1.0,
                    "mass_per_length": 1.0,
                    "left": left,
                    "right": right,
                },
                "attachments": [
                    {"type": "spring_mass", "x": 0.2 * (i + 1), "k": 1.0, "m": 1.0}
                    for i in range(n)
                ],
            }
        )
        fast, full = symbolic(scene, evaluate=False), symbolic(scene)
        assert fast.Z_bar == full.Z_bar
        assert fast.sparsity() == [
            " ".join("." if _vanishes(e) else "X" for e in full.U_bar.row(i))
            for i in range(full.U_bar.rows)
        ]


def _vanishes(e) -> bool:
    """Whether the entry e of U_bar is identically zero: at three random points of its
    symbols (positive, with 40 digits) it is 0 to 30 digits of its terms' size. A
    nonzero analytic function of the parameters vanishes at random points with
    probability zero, so this is the zero pattern ``simplify`` would give, in a fraction
    of its time (``simplify`` of every entry took half a minute)."""
    import random

    import sympy

    if e == 0:
        return True
    rng = random.Random(7)
    symbols = sorted(e.free_symbols, key=str)
    terms = sympy.Add.make_args(sympy.expand(e))
    for _ in range(3):
        at = {s: sympy.Rational(rng.randint(1, 10**6), 10**6) + 1 for s in symbols}
        size = max(abs(sympy.N(t.xreplace(at), 40)) for t in terms)
        if abs(sympy.N(e.xreplace(at), 40)) > sympy.Float(10) ** -30 * size:
            return False
    return True


# ---------------------------------------------------------------------------
# Issue 12 items 9-11: the package namespace, example_path, the test cache


def test_namespace_holds_only_the_public_api_and_submodules():
    import types

    stray = [
        name
        for name in dir(mstmm)
        if not name.startswith("__")
        and name not in mstmm.__all__
        and not isinstance(getattr(mstmm, name), types.ModuleType)
    ]
    assert stray == []


def test_example_path_by_name_from_any_directory(tmp_path):
    import pytest

    code = (
        "import mstmm\n"
        "for name in ('wu_chou_1998', 'bare_cantilever', 'wu_chou_1998.toml'):\n"
        "    mstmm.load_scene(mstmm.example_path(name))\n"
        "scene = mstmm.load_scene(mstmm.example_path('wu_chou_1998'))\n"
        "print(mstmm.solve(scene, modes=1).omega[0])\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, timeout=300
    )
    assert result.returncode == 0, result.stderr
    with pytest.raises(ValueError) as info:
        mstmm.example_path("wu_chou")
    assert "bare_cantilever, wu_chou_1998" in str(info.value)


def test_test_session_removes_its_kernel_cache(tmp_path):
    """A pytest session (this directory's conftest) leaves no mstmm-test-cache-* behind."""
    here = os.path.dirname(__file__)
    result = subprocess.run(
        [
            sys.executable,
            "-m",
            "pytest",
            "-q",
            "-p",
            "no:cacheprovider",
            os.path.join(here, "test_cli.py")
            + "::test_namespace_holds_only_the_public_api_and_submodules",
        ],
        capture_output=True,
        text=True,
        env={**os.environ, "TMPDIR": str(tmp_path)},
        timeout=300,
    )
    assert result.returncode == 0, result.stdout + result.stderr
    assert not list(tmp_path.glob("mstmm-test-cache-*"))


def test_the_command_keeps_blas_to_one_thread_unless_the_user_says(monkeypatch, capsys):
    """OpenBLAS's extra threads only spin on mstmm's small matrices (0.2 s of a second core
    on a first solve, benchmarks.busy): the command sets one thread before numpy loads,
    and leaves a user's setting alone."""
    from mstmm import cli

    monkeypatch.delenv("OPENBLAS_NUM_THREADS", raising=False)
    monkeypatch.setenv("MKL_NUM_THREADS", "3")
    with pytest.raises(SystemExit):  # argparse refuses it, after main set the pools up
        cli.main(["solve", "--modes", "0"])
    capsys.readouterr()
    assert os.environ["OPENBLAS_NUM_THREADS"] == "1"
    assert os.environ["MKL_NUM_THREADS"] == "3"

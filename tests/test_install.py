"""The README's two commands one after the other on one machine: ``pip install .``, a run,
then ``pip install -e .``. A run writes nothing into the installed package's folder (numba's
machine code and derived kernels go to the user cache, ``mstmm.cachedir``), so an
uninstall leaves no folder behind to shadow the editable install as a namespace package,
and the editable install then runs."""

from __future__ import annotations

import fcntl
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _run(*args, env=None) -> str:
    done = subprocess.run(args, env=env, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, (args, done.stdout[-2000:], done.stderr[-2000:])
    return done.stdout


def _files(folder: Path) -> set[str]:
    return {str(p.relative_to(folder)) for p in folder.rglob("*") if p.is_file()}


def _helpers_done(cache: Path, seconds: float = 300.0) -> None:
    """Wait until no compile helper holds a lock in ``cache`` (they outlive their run)."""
    end = time.monotonic() + seconds
    for lock in cache.rglob("*.compiling"):
        fd = os.open(lock, os.O_RDWR)
        try:
            while time.monotonic() < end:
                try:
                    fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                    break
                except OSError:
                    time.sleep(0.2)
        finally:
            os.close(fd)


@pytest.mark.slow
def test_install_run_then_editable_install_leaves_nothing_behind(tmp_path, reference):
    venv = tmp_path / "venv"
    _run(sys.executable, "-m", "venv", "--system-site-packages", str(venv))
    python = str(venv / "bin" / "python")
    cache = tmp_path / "cache"
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR", "PYTHONPATH")}
    env.update(MSTMM_CACHE=str(cache), MSTMM_COMPILE_HELPERS="1")
    _run(python, "-m", "pip", "install", "-q", "--no-deps", str(ROOT), env=env)
    where = "import json, mstmm; print(json.dumps(mstmm.__file__.rsplit('/', 1)[0]))"
    package = Path(json.loads(_run(python, "-c", where, env=env))).resolve()
    assert package.is_relative_to(venv), package
    installed = _files(package)

    # the main job, as a user runs it: answers, and compile helpers writing numba's cache
    out = _run(str(venv / "bin" / "mstmm"), "solve", "--modes", "4", "--format", "csv", env=env)
    omega = [float(line.split(",")[1]) for line in out.splitlines()[1:]]
    for w, exact in zip(omega, reference["wu_chou_1998"][:4], strict=True):
        assert abs(w / exact - 1.0) < 1e-12
    _helpers_done(cache)
    assert (cache / "numba").is_dir()  # the machine code went to the user cache
    assert _files(package) == installed  # and nothing into the package

    _run(python, "-m", "pip", "uninstall", "-q", "-y", "mstmm", env=env)
    assert not package.exists()  # nothing left to shadow the next install
    _run(python, "-m", "pip", "install", "-q", "--no-deps", "-e", str(ROOT), env=env)
    here = Path(json.loads(_run(python, "-c", where, env=env))).resolve()
    assert here == ROOT / "src" / "mstmm"
    out = _run(str(venv / "bin" / "mstmm"), "solve", "--modes", "2", "--format", "csv", env=env)
    assert len(out.splitlines()) == 3

"""A copy of the installed package in a temporary folder, for the contract tests that drop
one new file into it and touch nothing else (tests/test_new_kind.py, tests/test_inerter.py)."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import mstmm


def package_copy(root: Path) -> Path:
    """The installed package laid out as one folder (``mstmm/``, its ``derive`` and
    ``generated`` subpackages) with numba's caches beside the files, as pip installs it."""
    src = Path(mstmm.__file__).resolve().parent
    from mstmm import derive, generated

    dest = root / "mstmm"
    ignore = shutil.ignore_patterns("derive", "generated")
    shutil.copytree(src, dest, ignore=ignore)
    shutil.copytree(Path(derive.__file__).resolve().parent, dest / "derive")
    shutil.copytree(Path(generated.__file__).resolve().parent, dest / "generated")
    return root


def run_with_kind(root: Path, kind_file: Path, script: str, timeout: float = 900) -> dict:
    """``kind_file`` dropped into ``src/mstmm/kinds/`` of a copy of the package under
    ``root`` and nothing else touched; ``script`` run there in a fresh process (its own
    kernel cache); its JSON output, after checking that the copy ran."""
    return run_with_file(root, kind_file, "kinds", script, timeout)


def run_with_file(root: Path, file: Path, folder: str, script: str, timeout: float = 900) -> dict:
    """``file`` dropped into ``folder`` (``kinds``, ``physics/terms``) of a copy of the
    package under ``root`` and nothing else touched; ``script`` run there in a fresh
    process (its own kernel cache); its JSON output, after checking that the copy ran."""
    root = package_copy(root)
    shutil.copy(file, root / "mstmm" / folder / file.name)
    env = dict(os.environ, PYTHONPATH=str(root), MSTMM_CACHE=str(root / "cache"))
    run = subprocess.run(
        [sys.executable, "-c", script], env=env, capture_output=True, text=True, timeout=timeout
    )
    assert run.returncode == 0, run.stderr
    out = json.loads(run.stdout)
    assert out["package"].startswith(str(root))  # the copy ran, not the installed package
    return out

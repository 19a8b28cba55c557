"""The oldest SymPy that pyproject.toml accepts derives kernels that compute the same numbers.

mstmm depends on ``sympy>=OLDEST`` (not a pin, so that it installs beside
packages that pin their own SymPy, PyTorch among them). This test builds a venv
on top of this environment (``--system-site-packages``: numpy, numba, ... are
shared), installs exactly ``sympy==OLDEST`` from the package index into it, and
there:

* prints the kernel of every topology (16 end pairs, bare and with
  spring-masses); each is compared numerically with the kernel printed by this
  environment's SymPy (the committed one for the bundled topologies): every
  public function at random parameters and frequencies, 1e-13 relative, counts
  exactly (``tests/kernel_equivalence.py``);
* solves the paper example from an empty kernel cache (so with a kernel that
  SymPy OLDEST derived there) and checks its lowest ten against
  ``tests/data/reference.json`` to 1e-13.

It needs the package index (CI reaches it) and takes a minute or two; it is
marked ``slow`` (deselect with ``-m "not slow"``). ``MSTMM_SYMPY_PYTHON=/path/to/python``
runs it against an existing environment instead (to check another SymPy version by hand).
"""

from __future__ import annotations

import json
import os
import re
import site
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest
import sympy
from kernel_equivalence import all_topologies, compare, printed_by
from mstmm.derive.bundled import BUNDLED_TOPOLOGIES, generated_dir
from mstmm.derive.emit import kernel_source, numerics_source

ROOT = Path(__file__).resolve().parent.parent
SCRIPT = Path(__file__).resolve().parent / "kernel_equivalence.py"

pytestmark = pytest.mark.slow


def oldest_supported() -> str:
    """The lower bound of the ``sympy`` requirement in pyproject.toml."""
    deps = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["dependencies"]
    for dep in deps:
        m = re.fullmatch(r"\s*sympy\s*>=\s*([0-9][0-9.]*)\s*(,.*)?", dep)
        if m:
            return m.group(1)
    raise AssertionError(f"pyproject.toml: no 'sympy>=X' among the dependencies {deps}")


def _run(cmd: list[str], what: str, **kw) -> subprocess.CompletedProcess:
    proc = subprocess.run(cmd, capture_output=True, text=True, check=False, **kw)
    assert proc.returncode == 0, f"{what} failed ({proc.returncode}):\n{proc.stderr[-3000:]}"
    return proc


@pytest.fixture(scope="module")
def old_python(tmp_path_factory) -> tuple[str, str]:
    """(interpreter with the oldest supported SymPy, the version it must have)."""
    given = os.environ.get("MSTMM_SYMPY_PYTHON")
    if given:
        out = _run([given, "-c", "import sympy; print(sympy.__version__)"], given)
        return given, out.stdout.strip()
    oldest = oldest_supported()
    venv = tmp_path_factory.mktemp("sympy-oldest") / "venv"
    _run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)], "venv")
    python = str(venv / "bin" / "python")
    pip = [python, "-m", "pip", "install", "-q", "--disable-pip-version-check"]
    _run([*pip, f"sympy=={oldest}"], f"pip install sympy=={oldest} (needs the package index)")
    # this process's mstmm (and everything else it sees), behind the venv's own SymPy
    dirs = [d for d in site.getsitepackages() if Path(d).is_dir()]
    venv_site = _run([python, "-c", "import sysconfig; print(sysconfig.get_path('purelib'))"], "")
    (Path(venv_site.stdout.strip()) / "mstmm_under_test.pth").write_text(
        f"import site; list(map(site.addsitedir, {dirs!r}))\n"
    )
    where = _run(
        [python, "-c", "import mstmm, sympy; print(mstmm.__file__, sympy.__version__)"], ""
    )
    assert where.stdout.split() == [str(ROOT / "src" / "mstmm" / "__init__.py"), oldest], (
        f"the venv does not run this checkout's mstmm under SymPy {oldest}: {where.stdout}"
    )
    return python, oldest


def _environment(cache: Path) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "MSTMM_CACHE")}
    env["MSTMM_CACHE"] = str(cache)
    return env


def test_oldest_sympy_prints_kernels_that_compute_the_same(old_python, tmp_path):
    python, version = old_python
    out = tmp_path / "kernels"
    # print there while this process prints the same topologies with its own SymPy
    proc = subprocess.Popen(
        [python, str(SCRIPT), "derive", str(out)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=_environment(tmp_path / "cache"),
        cwd=tmp_path,
    )
    try:
        bundled = {t.kernel_key for t in BUNDLED_TOPOLOGIES}
        current = {}
        committed = generated_dir() / "euler_bernoulli.py"
        if printed_by(committed.read_text()) == sympy.__version__:
            current["euler_bernoulli"] = committed.read_text()
        else:
            current["euler_bernoulli"] = numerics_source()
        for topology in all_topologies():
            committed = generated_dir() / f"{topology.kernel_key}.py"
            fresh = printed_by(committed.read_text()) == sympy.__version__
            if topology.kernel_key in bundled and fresh:
                current[topology.kernel_key] = committed.read_text()  # equal to a fresh printing
            else:
                current[topology.kernel_key] = kernel_source(topology)
        stdout, stderr = proc.communicate(timeout=600)
    finally:
        proc.kill()
    assert proc.returncode == 0, stderr[-3000:]
    assert json.loads(stdout.splitlines()[-1])["sympy"] == version
    failures = {}
    for key, source in current.items():
        old = (out / f"{key}.py").read_text()
        assert printed_by(old) == version
        problems = compare(source, old, points=12)
        if problems:
            failures[key] = problems[:3]
    report = "\n".join(f"{key}: {'; '.join(p[:300] for p in v)}" for key, v in failures.items())
    assert not failures, f"SymPy {version} vs {sympy.__version__}:\n{report[:5000]}"


def test_oldest_sympy_solves_the_paper_example(old_python, tmp_path):
    python, version = old_python
    proc = _run(
        [python, str(SCRIPT), "solve"],
        f"solve under SymPy {version}",
        env=_environment(tmp_path / "cache"),
        cwd=tmp_path,
    )
    result = json.loads(proc.stdout.splitlines()[-1])
    assert result["sympy"] == version
    if version != printed_by((generated_dir() / "beam__spring_mass.py").read_text()):
        # the committed kernel's signature names another SymPy: this one derived its own
        assert result["kernel_origin"].startswith(str(tmp_path / "cache"))
    assert np.isfinite(result["error"]) and result["error"] < 1e-13

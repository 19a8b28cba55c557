"""Smoke test of the benchmark suite: ``python -m benchmarks --quick`` writes its report.

The numbers of a quick run mean little; what is checked is that the whole
pipeline runs (mstmm warm and cold, the FE model, scaling), that the Markdown
report and the plots are written, and that without matplotlib the report is
still written and says the plots were skipped. OpenSeesPy is never needed.
"""

from __future__ import annotations

import importlib.util
import math
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
HAVE_MPL = importlib.util.find_spec("matplotlib") is not None


@pytest.fixture(scope="module")
def quick_report(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("bench")
    proc = subprocess.run(
        [sys.executable, "-m", "benchmarks", "--quick", "--out", str(out)],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert proc.returncode == 0, proc.stderr[-3000:]
    return out


def test_quick_run_writes_the_report(quick_report: Path) -> None:
    text = (quick_report / "benchmarks.md").read_text()
    headings = ("## Machine", "## Targets", "## 1. Work-precision", "## 2. Scaling", "## 3. Param")
    for heading in headings:
        assert heading in text
    assert "python -m benchmarks --quick" in text  # the command is recorded
    assert "mstmm warm, stable" in text
    assert "FE sparse" in text
    assert "paper Table 1" in text  # quoted points, marked as such
    assert "quoted, not measured" in text
    assert "Log-log slopes" in text
    assert "Speed-up on all cores" in text
    assert "mstmm cold, compiled only" in text  # both tiers of a fresh process


@pytest.mark.skipif(not HAVE_MPL, reason="matplotlib is not installed")
def test_quick_run_draws_the_plots(quick_report: Path) -> None:
    for name in ("workprecision.png", "scaling.png"):
        data = (quick_report / "img" / name).read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 10_000
    text = (quick_report / "benchmarks.md").read_text()
    assert "](img/workprecision.png)" in text and "](img/scaling.png)" in text


def test_report_without_matplotlib(tmp_path, monkeypatch) -> None:
    """No matplotlib: the Markdown is still written and says the plots were skipped."""
    monkeypatch.setitem(sys.modules, "matplotlib", None)  # import matplotlib -> ImportError
    monkeypatch.syspath_prepend(str(ROOT))
    from benchmarks import machine, workprecision
    from benchmarks.__main__ import report

    wp = workprecision.Results(quick=True)
    wp.points = [
        workprecision.Point("mstmm warm, stable", "mstmm-warm", 5, "rtol=0", 1e-4, 3e-16, 10),
        workprecision.Point("FE sparse (eigsh shift-invert)", "fe", 5, "n=8", 5e-3, 7e-5, 5),
        workprecision.Point("OpenSeesPy", "opensees", 5, "n=8", 1e-3, math.inf, 0, "failed"),
    ]
    info = machine.info(["benchmarks", "--quick"])
    path = report(tmp_path, wp, None, info, info, 1.0)
    text = path.read_text()
    assert "matplotlib is not installed: plots skipped" in text
    assert "(plot skipped: matplotlib is not installed)" in text
    assert not (tmp_path / "img" / "workprecision.png").exists()
    assert "Intel" in text or "CPU" in text

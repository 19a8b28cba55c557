"""Progress on long ``frf`` and ``bands`` runs, in a terminal and in Jupyter (issue 41).

tqdm is optional: a stand-in ``tqdm.auto`` module records what a bar would show (the
test environment need not have tqdm, and a real one would draw). Without tqdm the
terminal bar is drawn. A quick run draws nothing; the command line draws only on a
terminal, never into ``--out`` or standard output.
"""

from __future__ import annotations

import os
import pty
import subprocess
import sys
import threading
import types
from pathlib import Path

import numpy as np
import pytest

import mstmm
from mstmm import progress

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
SCENE = EXAMPLES / "wu_chou_1998.toml"


class FakeTqdm:
    """What a tqdm bar was given: its total, description, delay, updates and close."""

    made: list[FakeTqdm] = []

    def __init__(self, total, desc, file, delay):
        self.total, self.desc, self.file, self.delay = total, desc, file, delay
        self.updates: list[int] = []
        self.closed = False
        FakeTqdm.made.append(self)

    def update(self, n):
        self.updates.append(n)

    def close(self):
        self.closed = True


@pytest.fixture
def fake_tqdm(monkeypatch):
    FakeTqdm.made = []
    auto = types.ModuleType("tqdm.auto")
    auto.tqdm = FakeTqdm
    package = types.ModuleType("tqdm")
    package.auto = auto
    monkeypatch.setitem(sys.modules, "tqdm", package)
    monkeypatch.setitem(sys.modules, "tqdm.auto", auto)
    return FakeTqdm


@pytest.fixture
def no_tqdm(monkeypatch):
    monkeypatch.setitem(sys.modules, "tqdm", None)  # import tqdm raises ImportError
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)


@pytest.fixture(scope="module")
def scene():
    return mstmm.load_scene(SCENE)


def _frf(scene, n: int) -> np.ndarray:
    return mstmm.frf(scene, "force:x=1.0", "displacement:x=0.5", np.linspace(1.0, 3000.0, n))


def test_frf_bar_is_tqdm_when_installed(scene, fake_tqdm, monkeypatch):
    monkeypatch.setattr(progress, "enabled", True)
    H = _frf(scene, 20000)
    assert H.shape == (20000,)
    (bar,) = fake_tqdm.made
    assert bar.desc == "mstmm: frf" and bar.total == 20000 and bar.file is sys.stderr
    assert bar.delay == progress.LONG_RUN  # a quick run draws nothing
    assert len(bar.updates) > 1 and sum(bar.updates) == 20000 and bar.closed


def test_bands_bar_counts_every_frequency(scene, fake_tqdm, monkeypatch):
    monkeypatch.setattr(progress, "enabled", True)
    b = mstmm.bands(scene, points=3000)
    bars = [t for t in fake_tqdm.made if t.desc == "mstmm: dispersion"]
    assert bars[0].total == 3000 and sum(bars[0].updates) == 3000
    assert sum(bars[-1].updates) == b.omega.size  # the curves refined at the edges
    assert all(t.closed for t in fake_tqdm.made)


def test_jupyter_gets_the_notebook_bar_without_the_command_line(scene, fake_tqdm, monkeypatch):
    monkeypatch.setattr(progress, "enabled", False)
    monkeypatch.setitem(sys.modules, "ipykernel", types.ModuleType("ipykernel"))
    _frf(scene, 2000)
    assert [t.total for t in fake_tqdm.made] == [2000]


def test_no_bar_in_jupyter_without_tqdm_nor_outside_a_terminal(scene, no_tqdm, monkeypatch, capsys):
    monkeypatch.setattr(progress, "LONG_RUN", 0.0)
    monkeypatch.setattr(progress, "enabled", False)
    monkeypatch.setitem(sys.modules, "ipykernel", types.ModuleType("ipykernel"))
    _frf(scene, 2000)
    assert capsys.readouterr() == ("", "")


def test_terminal_bar_without_tqdm(scene, no_tqdm, monkeypatch, capsys):
    monkeypatch.setattr(progress, "enabled", True)
    monkeypatch.setattr(progress, "LONG_RUN", 0.0)
    _frf(scene, 5000)
    out, err = capsys.readouterr()
    assert out == ""
    assert "mstmm: frf [" + "#" * 40 + "] 5000/5000" in err and err.endswith("\n")


def test_a_quick_run_draws_nothing(scene, no_tqdm, monkeypatch, capsys):
    monkeypatch.setattr(progress, "enabled", True)
    _frf(scene, 50)  # well under LONG_RUN
    assert capsys.readouterr() == ("", "")


def test_command_line_draws_on_the_terminal_only(tmp_path):
    """``mstmm frf --out`` with standard error a terminal (a pty): the bar there, the file
    and standard output clean."""
    out = tmp_path / "h.csv"
    master, slave = pty.openpty()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    proc = subprocess.Popen(
        [sys.executable, "-c",
         "import sys; sys.modules['tqdm'] = None\n"  # the terminal bar, tqdm or not
         "from mstmm.cli import main; raise SystemExit(main())",
         "frf", str(SCENE), "--input", "force:x=1.0", "--output", "displacement:x=0.5",
         "--band", "1", "3000", "--points", "200000", "--out", str(out)],
        stdout=subprocess.PIPE, stderr=slave, env=env,
    )  # fmt: skip
    os.close(slave)
    seen = bytearray()

    def read() -> None:  # keep the pty drained, or the child blocks on a full buffer
        while True:
            try:
                chunk = os.read(master, 4096)
            except OSError:
                return
            if not chunk:
                return
            seen.extend(chunk)

    reader = threading.Thread(target=read)
    reader.start()
    stdout, _ = proc.communicate(timeout=600)
    reader.join(timeout=10)
    os.close(master)
    assert proc.returncode == 0, seen.decode(errors="replace")
    assert stdout.decode().strip() == str(out)
    assert "200000/200000" in seen.decode(errors="replace")
    text = out.read_text()
    assert "mstmm" not in text and "\r" not in text and len(text.splitlines()) == 200001

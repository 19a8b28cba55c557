"""The README's example output: ``mstmm solve`` in a fresh process, as a user sees it.

Run: ``python -m benchmarks.example``.

Runs ``mstmm solve`` (the bundled paper example, lowest ten) once to fill the
kernel and numba caches, then again in a fresh process, and records that
second run's standard output verbatim, time line included, in
``docs/figures.json`` (key ``example``); ``python -m benchmarks.readme`` quotes
it. The machine-readable twin (``--format json``) gives the time of the
in-process work for the prose around it.
"""

from __future__ import annotations

import json
import subprocess
import sys

from . import figures

COMMAND = ("solve",)


def _mstmm(*args: str) -> str:
    cmd = [sys.executable, "-m", "mstmm", *args]
    return subprocess.run(cmd, check=True, capture_output=True, text=True).stdout


def measure() -> dict:
    """The fresh-process output of ``mstmm solve`` and its JSON timings."""
    _mstmm(*COMMAND)  # kernel and numba's on-disk cache in place, as for a returning user
    output = _mstmm(*COMMAND)
    data = json.loads(_mstmm(*COMMAND, "--format", "json"))
    return {
        "command": "mstmm " + " ".join(COMMAND),
        "output": output,
        "timings": data["timings"],
        "kernel_mode": data.get("kernel_mode", ""),
    }


def main() -> None:
    fig = measure()
    print(f"$ {fig['command']}\n{fig['output']}", end="")
    print(f"recorded in {figures.record('example', fig, command='python -m benchmarks.example')}")


if __name__ == "__main__":
    main()

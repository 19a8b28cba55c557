"""A machine's first ``mstmm solve`` and ``mstmm plot``, idle and kept busy.

The busy machine: two CPU-bound processes at the default priority (one a core of this
2-core machine), started before the command and stopped after it, as a browser and a
build keep a laptop busy. Each run is a machine's first: an empty ``MSTMM_CACHE`` and no
``NUMBA_CACHE_DIR``, so nothing is compiled, and the compile helpers that run starts
(they outlive it) are stopped before the next run, which they would otherwise slow down.
Idle and busy runs alternate; the median of ``--repeats`` each.

Goal (the first-run issue): busy at most 1.5x idle, for both commands.

``python -m benchmarks.busy [--repeats N] [--record]`` (``--record`` stores the figures
in docs/figures.json under ``busy``).
"""

from __future__ import annotations

import argparse
import os
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from . import figures

#: The commands measured: the main job, and the paper's Fig. 2 (its default).
COMMANDS = {"solve": ["solve"], "plot": ["plot", "-o", "{tmp}/fig2.png"]}
GOAL = 1.5
_HOG = "while True:\n    pass\n"


def _helpers_of(cache: str) -> list[int]:
    """Processes whose environment names ``cache`` as their ``MSTMM_CACHE`` (the compile
    helpers a run left behind)."""
    pids = []
    needle = f"MSTMM_CACHE={cache}".encode()
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit() and int(entry.name) != os.getpid():
            try:
                if needle in (entry / "environ").read_bytes().split(b"\0"):
                    pids.append(int(entry.name))
            except OSError:
                continue
    return pids


def first_run(command: str, busy: bool) -> float:
    """Wall seconds of a machine's first ``mstmm COMMAND`` (busy: beside two hogs)."""
    with tempfile.TemporaryDirectory(prefix="mstmm-busy-") as tmp:
        cache = str(Path(tmp) / "cache")
        env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
        env.update(MSTMM_CACHE=cache, MPLBACKEND="Agg")
        args = [a.format(tmp=tmp) for a in COMMANDS[command]]
        hogs = [subprocess.Popen([sys.executable, "-c", _HOG]) for _ in range(2 if busy else 0)]
        try:
            time.sleep(0.5 if busy else 0.0)  # the hogs running before the command starts
            t0 = time.perf_counter()
            subprocess.run(
                [sys.executable, "-m", "mstmm", *args], env=env, check=True, capture_output=True
            )
            return time.perf_counter() - t0
        finally:
            for hog in hogs:
                hog.kill()
                hog.wait()
            for pid in _helpers_of(cache):
                try:
                    os.kill(pid, signal.SIGKILL)
                except OSError:
                    pass


def measure(repeats: int) -> dict:
    """Median idle and busy first runs of each command, interleaved, and their ratio."""
    out = {}
    for command in COMMANDS:
        times: dict[str, list[float]] = {"idle": [], "busy": []}
        for _ in range(repeats):
            for state in ("idle", "busy"):
                times[state].append(first_run(command, state == "busy"))
                print(f"{command} {state}: {times[state][-1]:.2f} s", file=sys.stderr)
        idle, busy = (statistics.median(times[s]) for s in ("idle", "busy"))
        out[command] = {
            "idle_seconds": idle,
            "busy_seconds": busy,
            "ratio": busy / idle,
            "met": busy / idle <= GOAL,
            "runs": times,
        }
    return out


def report(result: dict) -> str:
    """The table of :func:`measure`'s figures."""
    lines = [
        f"| first run | idle | busy (2 CPU-bound processes) | ratio | goal {GOAL}x |",
        "|---|---|---|---|---|",
    ]
    for command, r in result.items():
        status = "met" if r["met"] else "missed"
        lines.append(
            f"| `mstmm {command}` | {r['idle_seconds']:.2f} s | {r['busy_seconds']:.2f} s"
            f" | {r['ratio']:.2f}x | {status} |"
        )
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--record", action="store_true", help="store under 'busy' in figures.json")
    args = ap.parse_args(argv)
    result = measure(args.repeats)
    print(report(result))
    if args.record:
        figures.record("busy", result, command="python -m benchmarks.busy --record")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""What the benchmark ran on: platform, CPU, cores, load, library versions, the command."""

from __future__ import annotations

import importlib.metadata
import os
import platform
import shlex
import sys
import time
from pathlib import Path

#: Distributions whose versions are recorded (absent ones are reported as such).
PACKAGES = ("mstmm", "numpy", "scipy", "numba", "sympy", "mpmath", "matplotlib", "openseespy")

#: Environment variables that change the timings (thread pools, caches).
ENV_VARS = (
    "OPENBLAS_NUM_THREADS",
    "OMP_NUM_THREADS",
    "MKL_NUM_THREADS",
    "NUMBA_NUM_THREADS",
    "MSTMM_CACHE",
    "NUMBA_CACHE_DIR",
)


def new_topology_env(cache: str | Path, **extra: str) -> dict[str, str]:
    """The environment of a fresh process whose kernel cache is ``cache`` (empty: every
    topology new to it) while numba's machine code of the shared numerics stays where this
    process has it (mstmm keeps both under ``MSTMM_CACHE`` unless ``NUMBA_CACHE_DIR`` is
    set): the first run of a new topology on a machine that has run mstmm before."""
    from mstmm.numerics.cache import numba_dir

    env = dict(os.environ, MSTMM_CACHE=str(cache), NUMBA_CACHE_DIR=str(numba_dir()))
    env.update(extra)
    return env


def cpu_model() -> str:
    """``model name`` of /proc/cpuinfo (or ``platform.processor()``)."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.lower().startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def cpu_flags() -> str:
    """The vector extensions the CPU reports (what numba and BLAS can use)."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("flags"):
                flags = set(line.split(":", 1)[1].split())
                wanted = ("sse4_2", "avx", "avx2", "fma", "avx512f")
                return " ".join(f for f in wanted if f in flags) or "none of sse4_2/avx/avx2"
    except OSError:
        pass
    return "unknown"


def load_average() -> str:
    try:
        one, five, fifteen = os.getloadavg()
    except OSError:
        return "unknown"
    return f"{one:.2f} / {five:.2f} / {fifteen:.2f}"


def versions() -> dict[str, str]:
    out = {"python": platform.python_version()}
    for name in PACKAGES:
        try:
            out[name] = importlib.metadata.version(name)
        except importlib.metadata.PackageNotFoundError:
            out[name] = "not installed"
    return out


def info(argv: list[str] | None = None) -> dict:
    """Everything :func:`markdown` prints, taken now."""
    argv = sys.argv if argv is None else argv
    try:
        affinity = len(os.sched_getaffinity(0))
    except AttributeError:
        affinity = os.cpu_count() or 0
    return {
        "date": time.strftime("%Y-%m-%d %H:%M:%S %Z"),
        "platform": platform.platform(),
        "cpu": cpu_model(),
        "cpu_flags": cpu_flags(),
        "cores": os.cpu_count() or 0,
        "usable_cores": affinity,
        "load": load_average(),
        "versions": versions(),
        "env": {k: os.environ[k] for k in ENV_VARS if k in os.environ},
        "command": "python -m benchmarks" + "".join(" " + shlex.quote(a) for a in argv[1:]),
    }


def markdown(start: dict, end: dict | None = None, elapsed: float | None = None) -> str:
    """The machine section of the report (``end``: the load average when the run finished)."""
    v = start["versions"]
    lines = [
        "| | |",
        "|---|---|",
        f"| command | `{start['command']}` |",
        f"| date | {start['date']} |",
        f"| platform | {start['platform']} |",
        f"| CPU | {start['cpu']} ({start['cpu_flags']}) |",
        f"| cores | {start['cores']} ({start['usable_cores']} usable by this process) |",
        "| load average (1/5/15 min) | at start "
        + start["load"]
        + (f"; at end {end['load']}" if end else "")
        + " |",
        "| Python | " + v["python"] + " |",
        "| packages | " + ", ".join(f"{k} {val}" for k, val in v.items() if k != "python") + " |",
        "| environment | "
        + (", ".join(f"`{k}={val}`" for k, val in start["env"].items()) or "(none set)")
        + " |",
    ]
    if elapsed is not None:
        lines.append(f"| run time | {elapsed:.0f} s |")
    return "\n".join(lines)

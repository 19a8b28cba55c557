"""The shared numerics compiled by helper processes while this one compiles its kernel.

numba compiles on one core. The first compiled run on a machine compiles the
shared drivers (``mstmm.numerics.entries``: the root search, the mode-shape
march) besides the topology's kernel, and each of the three takes several
seconds. The drivers do not depend on the topology (they take its functions as
first-class function values), so a helper process can compile them into
numba's on-disk cache while this process compiles the kernel; when this process
reaches a driver, it waits for its helper and loads the machine code from the
cache. A helper that fails costs nothing but the wait: the driver then compiles
here, as it would have without it.

Helpers start only when a driver is not in numba's cache yet (the first
compiled run after installing, or after a change in ``mstmm.numerics``), and
only on a machine with more than one core. A helper still compiling when this
process exits goes on and leaves its driver in the cache for the next run.
``MSTMM_COMPILE_HELPERS=0`` turns them off.
"""

from __future__ import annotations

import os
import subprocess
import sys

#: The drivers a default solve calls (``entry_<name>``), each compiled by a helper of
#: its own when numba's cache does not hold it.
BACKGROUND = ("lowest", "mode_shapes")


class _State:
    started: bool = False
    helpers: dict[str, subprocess.Popen] = {}


def enabled() -> bool:
    """Whether helpers may start (``MSTMM_COMPILE_HELPERS``, and more than one core)."""
    if os.environ.get("MSTMM_COMPILE_HELPERS", "1").strip() == "0":
        return False
    return len(os.sched_getaffinity(0)) > 1 if hasattr(os, "sched_getaffinity") else True


def cached(name: str) -> bool:
    """Whether numba's cache holds machine code of ``entry_<name>`` for the current sources
    (an unreadable cache counts as holding it: no helper then)."""
    from mstmm.numerics import entries

    try:
        cache_file = getattr(entries, f"entry_{name}")._cache._cache_file
        return bool(cache_file._load_index())
    except Exception:  # numba's private cache API: a change there must not break a solve
        return True


def start() -> None:
    """Start a helper for each driver of :data:`BACKGROUND` numba has not cached (once per
    process)."""
    if _State.started:
        return
    _State.started = True
    if not enabled():
        return
    for name in BACKGROUND:
        if not cached(name):
            _State.helpers[name] = subprocess.Popen(
                [sys.executable, "-m", "mstmm.compiling", name],
                stdin=subprocess.DEVNULL,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            )


def wait(name: str) -> None:
    """Wait until the helper compiling ``entry_<name>`` (if any) is done."""
    helper = _State.helpers.pop(name, None)
    if helper is not None:
        helper.wait()


def compile_driver(name: str) -> None:
    """Compile ``entry_<name>`` for the one signature the kernels call it with (numba
    writes it to its cache)."""
    from mstmm.numerics import entries

    getattr(entries, f"entry_{name}").compile(entries.SIGNATURES[name])


if __name__ == "__main__":
    for arg in sys.argv[1:]:
        compile_driver(arg)

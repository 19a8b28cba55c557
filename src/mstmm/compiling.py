"""The shared numerics compiled by helper processes while this one compiles its kernel.

numba compiles on one core. The first compiled run on a machine compiles the
shared drivers (``mstmm.numerics.entries``: the root search, the mode-shape
march) besides the topology's kernel, and each of the three takes several
seconds. The drivers do not depend on the topology (they take its functions as
first-class function values), so a helper process can compile them into
numba's on-disk cache while this process compiles the kernel. When this process
reaches a driver its helper has not finished, the driver runs as Python around the
compiled kernel (the interpreted tier's copy of it, :mod:`mstmm.interpret`) if that
is estimated to keep its Python time within :data:`PYTHON_WHILE_COMPILING`, all
its calls together; past that (a bigger problem, many calls) the process waits
for the helper and loads the machine code from the cache. The helpers run at a
lower priority (``nice`` 10), so that this process keeps a core.

**The foreground never waits on lower-priority work** (:func:`_wait_for`). Before it
waits on a helper (its own, or another process's that holds the lock) it tries to give
the helper its own priority; it then waits only while the helper makes progress: at its
own priority, while it runs at all; still at a lower one, only while it gets most of a
core (an idle core on an idle machine). A helper that is starved (a busy machine), stopped
or gone is left behind after one short look (:data:`LOOK`): this process compiles the
function itself (numba loads it from the cache if the helper finished meanwhile) and stops
its own starved helper. ``--verbose`` lists each wait and how it ended (:func:`waits`).
A helper that fails costs nothing but the look: the driver then compiles here, as it
would have without it.

The first compiled run of a topology is split the same way: this process compiles the
characteristic function (the hot one: every step of the search evaluates it), a helper
the kernel functions of :data:`KERNEL_BACKGROUND` (the mode-shape descriptor, the count,
the components' own frequencies, the rigid-body count), in that order. Until the helper
has one of them in numba's cache, this process runs it as Python (the interpreted tier's
copy, with the compiled characteristic function) within the same budget; past it, it
compiles the function itself unless the helper is compiling it now (each function's
lock, beside numba's index of it: one compiles, the other waits and loads it). A solve
of a small new topology thus waits for one compile, not six.

Helpers start only when a driver is not in numba's cache yet (the first
compiled run after installing, or after a change in ``mstmm.numerics``), and
only on a machine with more than one core. One helper per driver and cache: it
holds a lock beside numba's index of the driver, and another process that needs
the driver meanwhile waits for that helper (or runs the driver as Python) instead
of starting its own. A helper still compiling when this
process exits goes on and leaves its driver in the cache for the next run.
``MSTMM_COMPILE_HELPERS=0`` turns them off.
"""

from __future__ import annotations

import atexit
import os
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

try:
    import fcntl
except ImportError:  # not POSIX: no locks, each process starts its own helpers
    fcntl = None

from . import loader

#: The drivers a default solve calls (``entry_<name>``), each compiled by a helper of
#: its own when numba's cache does not hold it.
BACKGROUND = ("lowest", "mode_shapes")
#: The kernel functions a helper compiles on a topology's first compiled run while this
#: process compiles its characteristic function (``start_kernel``), in this order: the
#: mode shapes' (which cost most as Python), then the search's.
KERNEL_BACKGROUND = (
    "shape_sizes",
    "shape_inertia",
    "shape_event",
    "count_below",
    "oscillator_frequencies",
    "rigid_body_modes",
)
#: Seconds of Python a driver still compiling in a helper may take in this process, all
#: its calls together (those spent, plus the interpreted tier's estimate of the next,
#: ``interpret.estimated_cost``); past it, the next call waits for the helper.
PYTHON_WHILE_COMPILING = 2.0
#: The helpers' niceness (added to this process's).
NICENESS = 10
#: Seconds between two looks at a helper this process waits on (its CPU time is read
#: at each): one look is what a starved helper costs the foreground.
LOOK = 0.2
#: Share of a core a lower-priority helper must get, over a look, to be waited on.
FULL_SPEED = 0.5
#: Share of a core a helper at this process's priority must get to be waited on (it is
#: not stopped: on a busy machine it gets what this process would compiling itself).
RUNNING = 0.02


class _State:
    started: bool = False
    #: The drivers :func:`start` gives helpers (``register``; default :data:`BACKGROUND`).
    drivers: tuple[str, ...] | None = None
    #: This process's helpers, by driver.
    helpers: dict[str, subprocess.Popen] = {}
    #: Drivers another process's helper is compiling: the lock file it holds.
    elsewhere: dict[str, Path] = {}
    #: Seconds each driver has run as Python while its helper compiled it.
    python: dict[str, float] = {}
    #: Helpers compiling a kernel's functions, by the kernel module's name (None: none
    #: needed or allowed).
    kernels: dict[str, subprocess.Popen | None] = {}
    #: Where each of those helpers writes numba's cache (``_cache_location``).
    kernel_caches: dict[str, Path | None] = {}
    #: What this process waited for: ``(what, seconds, how it ended)`` (``waits``).
    waited: list[tuple[str, float, str]] = []


def enabled() -> bool:
    """Whether helpers may start (``MSTMM_COMPILE_HELPERS``, and more than one core)."""
    if os.environ.get("MSTMM_COMPILE_HELPERS", "1").strip() == "0":
        return False
    return len(os.sched_getaffinity(0)) > 1 if hasattr(os, "sched_getaffinity") else True


def _holds(dispatcher) -> bool:
    """Whether numba's cache holds machine code of ``dispatcher`` for the current sources
    (an unreadable cache counts as holding it: no helper then)."""
    try:
        return bool(dispatcher._cache._cache_file._load_index())
    except Exception:  # numba's private cache API: a change there must not break a solve
        return True


def _driver(name: str):
    """The shared driver ``entry_<name>`` (its dispatcher)."""
    from mstmm.numerics import entries

    return getattr(entries, f"entry_{name}")


def cached(name: str) -> bool:
    """Whether numba's cache holds machine code of ``entry_<name>`` (``_holds``)."""
    return _holds(_driver(name))


def _lock_beside(dispatcher) -> Path | None:
    """The lock whichever process compiles ``dispatcher`` holds, beside numba's index of
    it; None without locks."""
    if fcntl is None:
        return None
    try:
        return Path(str(dispatcher._cache._cache_file._index_path) + ".compiling")
    except Exception:
        return None


def _lock_path(name: str) -> Path | None:
    """The lock a helper compiling ``entry_<name>`` holds (one helper per driver and cache,
    whichever process started it)."""
    return _lock_beside(_driver(name))


def _kernel_lock(module, function: str) -> Path | None:
    """The lock whichever process compiles ``function`` of ``module`` holds."""
    return _lock_beside(getattr(module, function))


def _try_lock(path: Path, block: bool = False) -> int | None:
    """A descriptor holding the exclusive lock on ``path``, or None if another holds it
    (``block``: wait until it is released instead). The lock file then names this
    process as its holder (``_mark``)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o644)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX if block else fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        os.close(fd)
        return None
    _mark(fd, os.getpid())
    return fd


def _mark(fd: int, pid: int) -> None:
    """Write ``pid`` into the lock file held through ``fd``: the process that compiles, for
    another that would wait on it (``_holder``)."""
    try:
        os.ftruncate(fd, 0)
        os.pwrite(fd, str(pid).encode(), 0)
    except OSError:
        pass


def _holder(path: Path) -> int | None:
    """The process named in the lock file ``path`` (None if it names none)."""
    try:
        return int(path.read_text().strip() or "x")
    except (OSError, ValueError):
        return None


def _claim(path: Path | None, block: bool = False) -> tuple[int | None, bool]:
    """``(fd, busy)``: a descriptor holding the lock on ``path`` (None without one: no
    path, or none can be made where the cache is), and whether another process holds it
    (``block``: wait until it is released instead)."""
    if path is None:
        return None, False
    try:
        fd = _try_lock(path, block)
    except OSError:  # no lock where the cache is: go on without one
        return None, False
    return fd, fd is None and not block


def _spawn(*args: str, fds: tuple[int, ...] = ()) -> subprocess.Popen:
    """A helper: ``python -m mstmm.compiling ARGS``, silent, inheriting ``fds``."""
    return subprocess.Popen(
        [sys.executable, "-m", "mstmm.compiling", *args],
        stdin=subprocess.DEVNULL,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        pass_fds=fds,
    )


def register(drivers: tuple[str, ...]) -> None:
    """The drivers this process's work calls, for :func:`start` (a damped solve calls the
    search and ``damped_shapes``, not ``mode_shapes``): before anything is compiled."""
    if not _State.started and _State.drivers is None:
        _State.drivers = tuple(drivers)


def start() -> None:
    """Start a helper for each driver the process's work calls (:func:`register`, else
    :data:`BACKGROUND`) that numba has not cached and no other process is compiling (once
    per process). The helper inherits the driver's lock and holds it until it exits."""
    if _State.started:
        return
    _State.started = True
    if not enabled():
        return
    for name in BACKGROUND if _State.drivers is None else _State.drivers:
        if cached(name):
            continue
        path = _lock_path(name)
        fd, busy = _claim(path)
        if busy:
            _State.elsewhere[name] = path
            continue
        try:
            if fd is None or not cached(name):
                helper = _State.helpers[name] = _spawn(name, fds=() if fd is None else (fd,))
                if fd is not None:
                    _mark(fd, helper.pid)
        finally:
            if fd is not None:
                os.close(fd)


def running(name: str) -> bool:
    """Whether a helper (this process's or another's) is still compiling ``entry_<name>``."""
    helper = _State.helpers.get(name)
    if helper is not None:
        return helper.poll() is None
    path = _State.elsewhere.get(name)
    if path is None:
        return False
    fd = _try_lock(path)
    if fd is None:
        return True
    os.close(fd)
    del _State.elsewhere[name]
    return False


def any_helper() -> bool:
    """Whether a helper (this process's, of a driver or a kernel, or another process's this
    one saw) may still be compiling: nothing else here needs asking when none is."""
    return bool(_State.helpers or _State.elsewhere) or any(
        h is not None for h in _State.kernels.values()
    )


def python_instead(name: str, estimate: float, pending: bool = False) -> bool:
    """Whether to run the driver ``entry_<name>`` as Python now: its helper is still
    compiling it (or, ``pending``, a kernel function it calls: ``kernel_pending``), and the
    Python time spent on it so far plus ``estimate`` (seconds) stays within
    :data:`PYTHON_WHILE_COMPILING`."""
    spent = _State.python.get(name, 0.0)
    return spent + estimate <= PYTHON_WHILE_COMPILING and (pending or running(name))


def python_left(name: str) -> float:
    """Seconds of Python the driver ``entry_<name>`` may still take in this process (the
    rest of :data:`PYTHON_WHILE_COMPILING`): where a run as Python is stopped."""
    return max(PYTHON_WHILE_COMPILING - _State.python.get(name, 0.0), 0.0)


def charge(name: str, seconds: float) -> None:
    """Count ``seconds`` of the driver ``entry_<name>`` run as Python."""
    _State.python[name] = _State.python.get(name, 0.0) + seconds


def timed_call(name: str, fn, *args):
    """``fn(*args)`` (the driver ``entry_<name>`` as Python), its time charged to it."""
    t0 = time.perf_counter()
    try:
        return fn(*args)
    finally:
        charge(name, time.perf_counter() - t0)


def wait(name: str) -> None:
    """Wait for the helper compiling ``entry_<name>`` (if any) while it makes progress
    (:func:`_wait_for`); a starved one is left behind (this process's own stopped): the
    caller then compiles the driver itself, or loads it if the helper finished."""
    helper = _State.helpers.pop(name, None)
    if helper is not None:
        if not _wait_for(f"entry_{name}", helper.pid, lambda: helper.poll() is not None):
            helper.kill()  # starved or stopped (SIGKILL ends a stopped process too)
        return
    path = _State.elsewhere.pop(name, None)
    if path is not None:
        _wait_for_lock(f"entry_{name}", path)


def _wait_for_lock(what: str, path: Path) -> bool:
    """Wait for the process holding the lock ``path`` (named in it) while it makes
    progress; True when the lock is free (the work is in numba's cache)."""

    def free() -> bool:
        fd = _try_lock(path)
        if fd is None:
            return False
        os.close(fd)
        return True

    return free() or _wait_for(what, _holder(path), free)


def _cpu_seconds(pid: int) -> float | None:
    """CPU time (user + system) of process ``pid`` so far (Linux ``/proc``; None elsewhere
    or when it is gone)."""
    try:
        with open(f"/proc/{pid}/stat") as fh:
            fields = fh.read().rsplit(")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError):
        return None


def _raise_priority(pid: int) -> bool:
    """Give process ``pid`` this process's priority if the system allows it (lowering a
    niceness takes privileges most users lack); whether it now runs at it."""
    try:
        own = os.getpriority(os.PRIO_PROCESS, 0)
        if os.getpriority(os.PRIO_PROCESS, pid) > own:
            os.setpriority(os.PRIO_PROCESS, pid, own)
        return os.getpriority(os.PRIO_PROCESS, pid) <= own
    except (OSError, AttributeError):
        return False


def _wait_for(what: str, pid: int | None, done) -> bool:
    """Wait until ``done()`` while process ``pid`` (the helper doing the work) makes
    progress: at this process's priority (given it if allowed, ``_raise_priority``) while
    it gets :data:`RUNNING` of a core, at a lower one while it gets :data:`FULL_SPEED`.
    Checked once a :data:`LOOK`; True if done, False when the helper is starved,
    stopped or gone (or cannot be watched: no ``/proc``), recorded for :func:`waits`."""
    t0 = time.perf_counter()
    equal = pid is not None and _raise_priority(pid)
    need = RUNNING if equal else FULL_SPEED
    before = None if pid is None else _cpu_seconds(pid)
    while not done():
        if before is None:
            return _record(what, t0, "no helper to watch: compiled here")
        time.sleep(LOOK)
        now = _cpu_seconds(pid)
        if done():
            break
        share = 0.0 if now is None else (now - before) / LOOK
        if share < need:
            priority = "its" if equal else "a lower"
            return _record(
                what, t0, f"helper at {priority} priority got {share:.0%} of a core: compiled here"
            )
        before = now
    return _record(what, t0, "done by the helper, loaded from numba's cache", True)


def _record(what: str, t0: float, how: str, result: bool = False) -> bool:
    """Note a wait for :func:`waits`; returns ``result``."""
    _State.waited.append((what, time.perf_counter() - t0, how))
    return result


def waits() -> list[str]:
    """One line per wait on a helper in this process: what, how long, how it ended."""
    return [f"{what}: {seconds:.3f} s, {how}" for what, seconds, how in _State.waited]


def _kernel_functions(module) -> tuple[str, ...]:
    """The functions of :data:`KERNEL_BACKGROUND` that ``module`` has (an undamped kernel:
    all; a damped one: none, its search is another)."""
    if not hasattr(module, "count_below"):
        return ()
    return KERNEL_BACKGROUND


def start_kernel(module) -> None:
    """Start a helper that compiles the kernel functions of :data:`KERNEL_BACKGROUND` of
    ``module`` into numba's cache, if numba's cache lacks one of them (once per kernel and
    process, and none while another kernel's helper of this process runs). It runs beside
    the drivers' helpers of a machine's first run too: this process needs the kernel's
    functions before the drivers (it runs those as Python)."""
    name = module.__name__
    if name in _State.kernels:
        return
    _State.kernels[name] = None
    if not enabled():
        return
    # one kernel helper at a time: a process solving many new topologies in a row compiles
    # (or runs as Python) what the running one does not cover, rather than pile helpers up
    if any(h is not None and h.poll() is None for h in _State.kernels.values()):
        return
    functions = _kernel_functions(module)
    if any(not _holds(getattr(module, f)) for f in functions):
        _State.kernels[name] = _spawn("--kernel", module.__file__, name)
        _State.kernel_caches[name] = _cache_location(getattr(module, functions[0]))


def _helper(module) -> subprocess.Popen | None:
    """This process's helper compiling ``module``'s functions, while it runs."""
    helper = _State.kernels.get(module.__name__)
    return helper if helper is not None and helper.poll() is None else None


def kernel_pending(module, function: str) -> bool:
    """Whether this process's helper is to compile ``function`` of ``module`` and numba's
    cache does not hold it yet (the function then runs as Python, within the budget)."""
    if function not in _kernel_functions(module) or _helper(module) is None:
        return False
    return not _holds(getattr(module, function))


def kernel_busy(module, function: str) -> bool:
    """Whether another process (the helper) is compiling ``function`` of ``module`` now."""
    if function not in _kernel_functions(module) or _helper(module) is None:
        return False
    fd, busy = _claim(_kernel_lock(module, function))
    if fd is not None:
        os.close(fd)
    return busy


@contextmanager
def kernel_claim(module, function: str) -> Iterator[None]:
    """Hold ``function`` of ``module`` while this process compiles (or loads) it: if the
    helper is compiling it, wait while it makes progress (``_wait_for``: it is then in
    numba's cache); a starved helper is stopped and the function compiled here."""
    fd = None
    helper = _State.kernels.get(module.__name__)
    if function in _kernel_functions(module) and helper is not None:
        path = _kernel_lock(module, function)
        fd, busy = _claim(path)
        if busy and not _wait_for_lock(f"{module.__name__}.{function}", path):
            helper.kill()  # starved: what it has not compiled yet is compiled here
        elif busy:
            fd, _ = _claim(path)
    try:
        yield
    finally:
        if fd is not None:
            os.close(fd)


def wait_all() -> None:
    """Wait for every helper this process started (drivers' and kernels')."""
    for name in list(_State.helpers):
        wait(name)
    for helper in _State.kernels.values():
        if helper is not None:
            helper.wait()


def _cache_location(dispatcher) -> Path | None:
    """The directory numba caches ``dispatcher`` in (None if it cannot say)."""
    try:
        return Path(dispatcher._cache._cache_path).resolve()
    except Exception:
        return None


def _temporary(path: Path | None) -> bool:
    """Whether ``path`` lies in the system's temporary directory (or is unknown): a cache
    there is a test's or a benchmark's, removed when it ends."""
    if path is None:
        return True
    return path.is_relative_to(Path(tempfile.gettempdir()).resolve())


@atexit.register
def _stop_kernel_helpers() -> None:
    """A helper still compiling when this process exits (a small solve answers before it
    is done) goes on, at its low priority (given back if a wait raised it), and leaves its
    work in numba's cache for the next run; unless it is a kernel's and that kernel's
    cache lies in the temporary directory (``_temporary``): the helper is stopped then,
    rather than write into a directory its owner is removing (what it compiled stays
    cached; the next run starts a helper for the rest and runs it as Python meanwhile)."""
    kernels = [(h, _temporary(_State.kernel_caches.get(n))) for n, h in _State.kernels.items()]
    for helper, stop in kernels + [(h, False) for h in _State.helpers.values()]:
        if helper is None or helper.poll() is not None:
            continue
        if stop:
            helper.terminate()
            continue
        try:
            low = os.getpriority(os.PRIO_PROCESS, 0) + NICENESS
            if os.getpriority(os.PRIO_PROCESS, helper.pid) < low:
                os.setpriority(os.PRIO_PROCESS, helper.pid, low)
        except (OSError, AttributeError):
            pass


def compile_kernel(path: str, name: str) -> None:
    """Compile the functions of :data:`KERNEL_BACKGROUND` of the kernel module ``name`` (at
    ``path``) for the signatures the shared drivers call them with, each under its lock,
    skipping those another process compiles or has compiled."""
    from mstmm.numerics import entries

    module = loader.load(path, name)
    for function in _kernel_functions(module):
        dispatcher = getattr(module, function)
        fd, busy = _claim(_kernel_lock(module, function))
        if busy:
            continue  # the main process compiles it
        try:
            if not _holds(dispatcher):
                ftype = entries.FUNCTION_TYPES[function][1]
                dispatcher.compile(ftype.signature)  # as _get_wrapper_address asks
        finally:
            if fd is not None:
                os.close(fd)


def compile_driver(name: str) -> None:
    """Compile ``entry_<name>`` for the one signature the kernels call it with (numba
    writes it to its cache)."""
    from mstmm.numerics import entries

    getattr(entries, f"entry_{name}").compile(entries.SIGNATURES[name])


if __name__ == "__main__":
    if hasattr(os, "nice"):
        os.nice(NICENESS)
    if sys.argv[1:2] == ["--kernel"]:
        compile_kernel(sys.argv[2], sys.argv[3])
    else:
        for arg in sys.argv[1:]:
            compile_driver(arg)

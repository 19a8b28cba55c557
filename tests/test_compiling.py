"""The shared drivers compile in helper processes on a machine's first compiled run
(``mstmm.compiling``): the main process compiles its kernel meanwhile and loads the
drivers from numba's cache, with the same answers."""

from __future__ import annotations

import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from test_cli import _cantilever_omega

import mstmm
from mstmm import compiling, interpret
from mstmm.numerics import entries

#: A child script's head: the qualified names of what numba compiles in it, in
#: ``compiled``.
_LISTENER = """
import json
from numba.core import event
compiled = []

class Listener(event.Listener):
    def on_start(self, e):
        pass

    def on_end(self, e):
        compiled.append(e.data["dispatcher"].py_func.__qualname__)

event.register("numba:compile", Listener())
"""

_COLD = (
    _LISTENER
    + """
import mstmm
from mstmm import compiling
scene = mstmm.load_scene(mstmm.example_path("bare_cantilever"))
sol = mstmm.solve(scene, modes=4)
print(json.dumps({
    "omega": [float(w) for w in sol.omega],
    "certified": bool(sol.count_checked),
    "shapes": [[list(map(float, s.x)), list(map(float, s.Y))] for s in sol.shapes],
    "compiled": list(compiled),
    "waits": compiling.waits(),
    "cached": [compiling.wait(n) or compiling.cached(n) for n in compiling.BACKGROUND],
}))
"""
)


def _fresh_state(monkeypatch, started: bool):
    """A fresh ``compiling._State`` for this test (no helper, nothing spent)."""

    class Fresh:
        drivers = None
        helpers: dict = {}
        elsewhere: dict = {}
        python: dict = {}
        kernels: dict = {}
        kernel_caches: dict = {}
        waited: list = []

    Fresh.started = started
    monkeypatch.setattr(compiling, "_State", Fresh)
    return Fresh


def test_the_drivers_are_compiled_for_the_signatures_the_kernels_call(monkeypatch):
    """``entries.SIGNATURES`` (what a helper compiles) is what a solve calls: an undamped
    and a damped solve forced to run compiled, mode shapes on, add no other signature to
    the drivers (no helpers: everything runs compiled here, none of it as Python)."""
    monkeypatch.setenv("MSTMM_COMPILE_HELPERS", "0")
    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    budget = interpret._Process.budget
    interpret.set_budget(0.0)
    try:
        sol = mstmm.solve(scene, modes=3)
    finally:
        interpret.set_budget(budget)
    assert sol.count_checked and len(sol.shapes) == 3
    damped = mstmm.load_scene(Path(__file__).parents[1] / "examples" / "tmd_den_hartog.toml")
    interpret.set_budget(0.0)
    try:
        sol = mstmm.solve(damped, modes=3)  # a damped solve: damped_shapes, and lowest
    finally:
        interpret.set_budget(budget)
    assert sol.count_checked and len(sol.shapes) == 3
    for name in (*compiling.BACKGROUND, "damped_shapes"):
        dispatcher = getattr(entries, f"entry_{name}")
        assert dispatcher.signatures == [entries.SIGNATURES[name]], name


def _cold_cantilever(script: str) -> tuple[dict, mstmm.Scene]:
    """``script`` run on a machine's first compiled run (fresh numba and kernel caches,
    compiled forced, helpers on): its JSON line, checked against the cantilever's
    closed-form roots and certified, and the scene."""
    with tempfile.TemporaryDirectory() as numba_cache, tempfile.TemporaryDirectory() as kc:
        env = dict(os.environ, NUMBA_CACHE_DIR=numba_cache, MSTMM_CACHE=kc)
        env.update(MSTMM_INTERPRET_BUDGET="0", MSTMM_COMPILE_HELPERS="1")
        done = subprocess.run(
            [sys.executable, "-c", script], env=env, capture_output=True, text=True, check=True
        )
    out = json.loads(done.stdout.splitlines()[-1])
    scene = mstmm.load_scene(mstmm.example_path("bare_cantilever"))
    for n, w in enumerate(out["omega"], start=1):
        assert abs(w / _cantilever_omega(scene, n) - 1.0) < 1e-12, n
    assert out["certified"]
    return out, scene


def test_a_first_compiled_run_on_a_cold_machine_loads_the_drivers_from_its_helpers():
    """Nothing in numba's cache (a fresh ``NUMBA_CACHE_DIR``), the solve forced compiled:
    the drivers of ``compiling.BACKGROUND`` are compiled by helpers, not by the main
    process (it runs them as Python around its compiled kernel until they are), the
    roots are the cantilever's closed-form ones, mode shapes on, and the helpers leave
    the drivers in the cache."""
    out, scene = _cold_cantilever(_COLD)
    assert len(out["shapes"]) == 4
    for n, (x, Y) in enumerate(out["shapes"], start=1):  # the closed-form mode shapes
        b = (
            _cantilever_omega(scene, n) ** 0.5
            * (scene.beam.mass_per_length / scene.beam.EI) ** 0.25
        )
        s = (math.cosh(b) + math.cos(b)) / (math.sinh(b) + math.sin(b))
        phi = [
            math.cosh(b * t) - math.cos(b * t) - s * (math.sinh(b * t) - math.sin(b * t)) for t in x
        ]
        assert max(abs(y / Y[-1] - f / phi[-1]) for y, f in zip(Y, phi)) < 1e-9, n
    if compiling.enabled():
        for name in compiling.BACKGROUND:  # unless its helper was starved (a busy machine)
            starved = any(w.startswith(f"entry_{name}:") and "here" in w for w in out["waits"])
            assert starved or f"entry_{name}" not in out["compiled"], name
        # the search ran as Python while its helper compiled it: never waited for (its
        # Python time, milliseconds here, is far inside compiling.PYTHON_WHILE_COMPILING)
        assert not any(w.startswith("entry_lowest:") for w in out["waits"]), out["waits"]
        assert "delta_stable" in " ".join(out["compiled"])  # the kernel: here
    assert out["cached"] == [True] * len(compiling.BACKGROUND)


_STOPPED = """
import json, os, signal
import mstmm
from mstmm import compiling
spawn = compiling._spawn
helpers = []

def stopped(*args, fds=()):  # a helper that cannot run: the machine is kept busy
    helper = spawn(*args, fds=fds)
    os.kill(helper.pid, signal.SIGSTOP)
    helpers.append(helper)
    return helper

compiling._spawn = stopped
compiling.PYTHON_WHILE_COMPILING = 0.0  # no Python while compiling: wait, or compile
try:
    scene = mstmm.load_scene(mstmm.example_path("bare_cantilever"))
    sol = mstmm.solve(scene, modes=3)
finally:
    for helper in helpers:
        helper.kill()
print(json.dumps({
    "omega": [float(w) for w in sol.omega],
    "certified": bool(sol.count_checked),
    "shapes": len(sol.shapes),
    "helpers": len(helpers),
    "waits": compiling.waits(),
}))
"""


def test_a_first_run_whose_helpers_cannot_run_finishes_in_its_own_time():
    """A machine's first compiled run (nothing in numba's cache) whose compile helpers
    never get the CPU (stopped as soon as they start: a machine kept busy, the helpers at
    a lower priority): the solve does not wait on them; it compiles the drivers itself,
    says so in its waits (``--verbose``), and its roots are the closed-form ones."""
    if not compiling.enabled():
        return  # one core: no helpers to wait on
    out, _ = _cold_cantilever(_STOPPED)
    assert out["shapes"] == 3 and out["helpers"] >= 1
    assert out["waits"] and all("compiled here" in w for w in out["waits"]), out["waits"]


def test_helpers_can_be_turned_off(monkeypatch):
    monkeypatch.setenv("MSTMM_COMPILE_HELPERS", "0")
    assert not compiling.enabled()


def test_a_driver_another_process_compiles_is_waited_for_not_compiled_again(monkeypatch, tmp_path):
    """One helper per driver and cache: while another process's helper holds the driver's
    lock, ``start`` starts none, ``running`` says so (the driver then runs as Python or is
    waited for), and the lock's release ends it."""
    if compiling.fcntl is None:
        return  # no locks on this platform: nothing to check
    lock = tmp_path / "entry_lowest.nbi.compiling"
    state = _fresh_state(monkeypatch, started=False)
    monkeypatch.setattr(compiling, "BACKGROUND", ("lowest",))
    monkeypatch.setattr(compiling, "enabled", lambda: True)
    monkeypatch.setattr(compiling, "cached", lambda name: False)
    monkeypatch.setattr(compiling, "_lock_path", lambda name: lock)
    held = compiling._try_lock(lock)  # another process's helper (its own open file)
    assert held is not None
    try:
        compiling.start()
        assert state.helpers == {} and state.elsewhere == {"lowest": lock}
        assert compiling.running("lowest")
    finally:
        os.close(held)  # that helper exits
    assert not compiling.running("lowest")
    compiling.wait("lowest")  # returns at once


_NEW_TOPOLOGY = (
    _LISTENER
    + """
import sys
import mstmm
from mstmm import compiling
compiling.PYTHON_WHILE_COMPILING = float(sys.argv[1])
scene = mstmm.scene_from_dict({
    "name": "pinned_pinned",
    "beam": {"length": 2.0, "EI": 1.0e4, "mass_per_length": 3.0, "left": "pinned",
             "right": "pinned"},
})
sol = mstmm.solve(scene, modes=3)
here = list(compiled)
compiling.wait_all()  # the helper's work done, its cache in place
kernel = mstmm.kernel_for(scene)
print(json.dumps({
    "omega": [float(w) for w in sol.omega],
    "certified": bool(sol.count_checked),
    "shapes": [[list(map(float, s.x)), list(map(float, s.Y))] for s in sol.shapes],
    "compiled": here,
    "cached": [compiling._holds(getattr(kernel.module, f)) for f in compiling.KERNEL_BACKGROUND],
}))
"""
)


def _new_topology(python_while_compiling: float) -> dict:
    """A kernel never compiled solved compiled forced, with helpers, in a fresh process;
    the shared drivers compiled on the machine first. numba's cache is keyed by content
    (``numerics.cache``): the fresh process gets a numba cache holding what this session
    compiled (the drivers among it) except the bare beam's kernel (bundled, every end pair)."""
    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    budget = interpret._Process.budget
    interpret.set_budget(0.0)
    try:
        mstmm.solve(scene, modes=2)  # the drivers compiled here, or by helpers: waited for
    finally:
        interpret.set_budget(budget)
    for name in compiling.BACKGROUND:
        compiling.wait(name)
        assert compiling.cached(name), name
    with tempfile.TemporaryDirectory() as kc:
        here = Path(compiling._cache_location(entries.entry_lowest)).parent
        numba_cache = Path(kc) / "numba"
        shutil.copytree(here, numba_cache, ignore=shutil.ignore_patterns("beam_*", "*.lock"))
        env = dict(os.environ, MSTMM_CACHE=kc, MSTMM_INTERPRET_BUDGET="0")
        env.update(MSTMM_COMPILE_HELPERS="1", NUMBA_CACHE_DIR=str(numba_cache))
        done = subprocess.run(
            [sys.executable, "-c", _NEW_TOPOLOGY, str(python_while_compiling)],
            env=env,
            capture_output=True,
            text=True,
            check=True,
        )
    out = json.loads(done.stdout.splitlines()[-1])
    L, EI, mbar = 2.0, 1.0e4, 3.0
    for n, w in enumerate(out["omega"], start=1):
        assert abs(w / ((n * math.pi / L) ** 2 * math.sqrt(EI / mbar)) - 1.0) < 1e-12, n
    assert out["certified"] and len(out["shapes"]) == 3
    for n, (x, Y) in enumerate(out["shapes"], start=1):  # sin(n pi x / L), up to a factor
        phi = [math.sin(n * math.pi * t / L) for t in x]
        k = max(range(len(x)), key=lambda i: abs(phi[i]))
        assert max(abs(y / Y[k] - f / phi[k]) for y, f in zip(Y, phi)) < 1e-9, n
    assert all(out["cached"])  # every function of KERNEL_BACKGROUND, by one or the other
    return out


def _kernel_compiles(out: dict, name: str) -> int:
    return sum(q.startswith("kernel_") and q.endswith("." + name) for q in out["compiled"])


def test_a_new_topology_compiles_its_characteristic_function_and_a_helper_the_rest():
    """The main process compiles the characteristic function only; the count, the own
    frequencies, the rigid-body count and the mode-shape functions compile in a helper
    while the solve runs them as Python (``PYTHON_WHILE_COMPILING``), and the roots and
    shapes are the pinned-pinned beam's closed forms."""
    out = _new_topology(compiling.PYTHON_WHILE_COMPILING)
    if compiling.enabled():
        assert _kernel_compiles(out, "delta_stable") == 1
        for name in compiling.KERNEL_BACKGROUND:
            assert _kernel_compiles(out, name) == 0, name


def test_past_the_budget_a_kernel_function_is_compiled_once_here_or_by_the_helper():
    """No Python while compiling (a budget of 0): the main process compiles what the solve
    needs and the helper has not started, waits for what the helper compiles now, and
    loads it from the cache; no function is compiled twice here, and the answers hold."""
    out = _new_topology(0.0)
    for name in ("delta_stable",) + compiling.KERNEL_BACKGROUND:
        assert _kernel_compiles(out, name) <= 1, name


#: A process holding a lock the way a helper does (its pid in the lock file), working for
#: ``argv[2]`` seconds (or sleeping, ``argv[3] == "sleep"``: a helper that gets no CPU).
_HOLDER = """
import fcntl, os, sys, time
fd = os.open(sys.argv[1], os.O_RDWR | os.O_CREAT, 0o644)
fcntl.flock(fd, fcntl.LOCK_EX)
os.ftruncate(fd, 0)
os.write(fd, str(os.getpid()).encode())
print("held", flush=True)
end = time.time() + float(sys.argv[2])
while time.time() < end:
    if sys.argv[3] == "sleep":
        time.sleep(0.05)
"""


def _holder(lock: Path, seconds: float, how: str) -> subprocess.Popen:
    """A process holding ``lock`` for ``seconds``, working (``"work"``) or not."""
    holder = subprocess.Popen(
        [sys.executable, "-c", _HOLDER, str(lock), str(seconds), how],
        stdout=subprocess.PIPE,
        text=True,
    )
    assert holder.stdout.readline().strip() == "held"
    return holder


def _claim_kernel_function(tmp_path, monkeypatch, how: str) -> tuple[float, list, list]:
    """``kernel_claim`` on a function whose lock a helper holds (working or starved):
    seconds it took, the waits recorded, the helpers it stopped."""

    class Module:
        __name__ = "kernel_under_test"

    lock = tmp_path / "count_below.nbi.compiling"
    state = _fresh_state(monkeypatch, started=True)
    monkeypatch.setattr(compiling, "_kernel_functions", lambda module: ("count_below",))
    monkeypatch.setattr(compiling, "_kernel_lock", lambda module, function: lock)
    stopped = []

    class Helper:
        def poll(self):
            return None

        def kill(self):
            stopped.append(self)

    state.kernels = {Module.__name__: Helper()}
    holder = _holder(lock, 1.5, how)
    try:
        assert compiling.kernel_busy(Module, "count_below")
        t0 = time.perf_counter()
        with compiling.kernel_claim(Module, "count_below"):
            seconds = time.perf_counter() - t0
    finally:
        holder.kill()
        holder.wait()
    return seconds, compiling.waits(), stopped


def test_a_kernel_function_a_working_helper_compiles_is_waited_for(tmp_path, monkeypatch):
    """``kernel_claim`` waits while the process holding a function's lock (the helper
    compiling it) runs, and goes through once it is released."""
    if compiling.fcntl is None or not Path("/proc/self/stat").exists():
        return  # no locks, or no way to watch a helper: nothing is waited for
    seconds, waits, stopped = _claim_kernel_function(tmp_path, monkeypatch, "work")
    assert seconds > 1.0 and not stopped
    assert len(waits) == 1 and "done by the helper" in waits[0]


def test_a_helper_that_gets_no_cpu_is_not_waited_for(tmp_path, monkeypatch):
    """A helper that cannot run (stopped, or starved on a busy machine; here: one that
    sleeps while it holds the lock) is left behind after one look: ``kernel_claim``
    returns at once (this process compiles the function itself), stops the helper, and
    the wait says so (``--verbose``)."""
    if compiling.fcntl is None:
        return  # no locks on this platform: nothing to check
    seconds, waits, stopped = _claim_kernel_function(tmp_path, monkeypatch, "sleep")
    assert seconds < 1.0 and len(stopped) == 1
    assert len(waits) == 1 and "compiled here" in waits[0]


def test_a_driver_runs_as_python_while_compiling_within_a_budget(monkeypatch):
    """While a helper compiles a driver, its calls run as Python as long as their Python
    time together stays within ``PYTHON_WHILE_COMPILING``; then they wait for it."""
    _fresh_state(monkeypatch, started=True)
    monkeypatch.setattr(compiling, "running", lambda name: True)
    budget = compiling.PYTHON_WHILE_COMPILING
    assert compiling.python_instead("lowest", 0.75 * budget)
    compiling.charge("lowest", 0.75 * budget)
    assert compiling.python_instead("lowest", 0.2 * budget)
    assert not compiling.python_instead("lowest", 0.3 * budget)  # past the budget: wait
    assert compiling.python_instead("mode_shapes", 0.3 * budget)  # each driver its own
    monkeypatch.setattr(compiling, "running", lambda name: False)
    assert not compiling.python_instead("mode_shapes", 0.0)  # compiled: no Python


def test_a_damped_solve_asks_helpers_for_its_own_drivers(monkeypatch):
    """A damped solve registers the drivers it calls (the search for its undamped start,
    ``damped_shapes``), so that a machine's first run does not compile ``mode_shapes``
    in a helper for nothing."""

    _fresh_state(monkeypatch, started=False)
    spawned = []
    monkeypatch.setattr(compiling, "enabled", lambda: True)
    monkeypatch.setattr(compiling, "cached", lambda name: False)
    monkeypatch.setattr(compiling, "_lock_path", lambda name: None)
    monkeypatch.setattr(compiling.subprocess, "Popen", lambda args, **kw: spawned.append(args[-1]))
    compiling.register(("lowest", "damped_shapes"))
    compiling.start()
    assert spawned == ["lowest", "damped_shapes"]


def test_a_kernel_helper_outlives_its_process_unless_its_cache_is_temporary(monkeypatch):
    """At exit a kernel's helper still compiling goes on when numba's cache it writes is a
    lasting one (a user's), and is stopped when that cache lies in the temporary
    directory (a test's or a benchmark's, about to be removed)."""
    state = _fresh_state(monkeypatch, started=True)
    stopped = []

    class Running:
        def __init__(self, name):
            self.name = name

        def poll(self):
            return None

        def terminate(self):
            stopped.append(self.name)

    lasting = Path.home() / ".cache" / "mstmm" / "__pycache__"
    temporary = Path(tempfile.gettempdir()) / "mstmm-test" / "__pycache__"
    state.kernels = {"user": Running("user"), "test": Running("test"), "unknown": Running("?")}
    state.kernel_caches = {"user": lasting, "test": temporary.resolve(), "unknown": None}
    compiling._stop_kernel_helpers()
    assert stopped == ["test", "?"]

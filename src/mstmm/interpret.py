"""Run a kernel's ``lowest`` as plain Python when that is cheaper than loading its machine code.

A fresh process pays numba a fixed price before the first compiled call, even
from numba's on-disk cache: about 0.5 s on the 2-core machines measured (a
trivial cached ``@njit`` function costs the same; see docs/benchmarks.md, "A
fresh process, piece by piece"). The paper's example needs about 10 ms of
plain-Python work for its lowest five frequencies. So the first solves of a
process run the very same generated functions uncompiled (each numba
dispatcher keeps its Python function as ``py_func``), until the Python time
spent would have paid for the compiled kernel: a tiered JIT, rent before you
buy. A problem estimated to cost more than what is left of the budget, and any
process that has already loaded machine code for a kernel, runs compiled.

The cost model only decides whether to start: a run whose estimate proves wrong (a
string-like tensioned beam needs far more evaluations than its mode count suggests) is
stopped once it has taken twice what was left of the budget (:func:`deadline`,
:class:`Overrun`), and the caller runs it compiled from the start.

The arithmetic is the same IEEE double arithmetic either way (numba does not
reassociate without ``fastmath``); the two agree to the last bit or two.
"""

from __future__ import annotations

import math
import os
import time
import types
from collections.abc import Iterator
from contextlib import contextmanager
from types import ModuleType

#: Seconds of plain-Python kernel work a process may spend before it loads machine
#: code instead: about what that load costs a fresh process (0.5 - 0.7 s measured),
#: halved so that a run which turns out to need the compiled kernel loses little.
#: ``MSTMM_INTERPRET_BUDGET`` overrides it; 0 turns interpretation off.
DEFAULT_BUDGET = 0.3

#: Seconds of plain-Python work allowed instead where the kernel's machine code is not in
#: numba's cache yet (a machine's or a topology's first run): the other choice is then to
#: compile, and the characteristic function alone takes 1.8 s or more to compile.
COLD_BUDGET = 1.5

#: Cost model of the interpreted ``lowest``, seconds per mode: ``A + B * attachments``
#: (fitted on the clamped-free spring-mass kernel, 1 .. 30 attachments, 5 .. 60 modes,
#: with a margin; the run is timed, the model only decides whether to start it).
COST_PER_MODE = 2.5e-3
COST_PER_MODE_PER_ATTACHMENT = 0.25e-3
#: Evaluations of the characteristic function that cost about one mode of ``lowest`` as
#: Python (measured: 12-25 on the paper's example and a bare cantilever, nodes, Brent
#: and counts together).
EVALUATIONS_PER_MODE = 15
#: An interpreted mode shape costs about this many modes of ``lowest`` (``estimated_cost``).
SHAPE_COST_FACTOR = 4
#: A scene with a Timoshenko, axial-force or foundation segment costs the interpreted
#: ``lowest`` up to this many times more (its ``exp(A h)`` per piece; measured 1.1 - 4x on
#: the examples, 1 .. 8 attachments).
GENERAL_SEGMENT_FACTOR = 5


def _budget_from_env() -> float:
    raw = os.environ.get("MSTMM_INTERPRET_BUDGET", "")
    try:
        return max(0.0, float(raw)) if raw else DEFAULT_BUDGET
    except ValueError:
        return DEFAULT_BUDGET


class _Process:
    """What this process has spent and loaded (shared by every kernel)."""

    budget: float = _budget_from_env()
    spent: float = 0.0
    #: True once any kernel ran compiled here: numba is initialised, loads are cheap.
    compiled: bool = False


def mark_compiled() -> None:
    """Record that machine code was loaded in this process."""
    _Process.compiled = True


def machine_code_loaded() -> bool:
    """Whether this process has loaded machine code for any kernel yet."""
    return _Process.compiled


def set_budget(seconds: float) -> None:
    """Seconds of interpreted kernel work allowed in this process (0: always compiled)."""
    _Process.budget = max(0.0, float(seconds))


def estimated_cost(modes: int, attachments: int) -> float:
    """Seconds the interpreted ``lowest`` is expected to take."""
    return modes * (COST_PER_MODE + COST_PER_MODE_PER_ATTACHMENT * attachments)


def _limit(cold: bool) -> float:
    """The budget; at least :data:`COLD_BUDGET` for a kernel with nothing in numba's cache
    (``cold``), unless interpretation is off."""
    budget = _Process.budget
    return max(budget, COLD_BUDGET) if cold and budget > 0.0 else budget


def worthwhile(modes: int, attachments: int, general: bool = False, cold: bool = False) -> bool:
    """Whether ``lowest`` should run as Python: no machine code yet and it fits the budget
    (``cold``: the kernel's machine code would have to be compiled, not loaded)."""
    if _Process.compiled:
        return False
    cost = estimated_cost(modes, attachments) * (GENERAL_SEGMENT_FACTOR if general else 1)
    return _Process.spent + cost <= _limit(cold)


def python_copy(module: ModuleType) -> dict:
    """The kernel module's namespace with every numba dispatcher replaced by its Python function.

    The namespace holds the shared numerics' modules too (their private names as well:
    they were written as one namespace, ``mstmm.numerics``), and every function is
    rebound to the copy, so a call stays in Python all the way down; nothing is compiled.
    """
    import sys

    ns: dict = {}
    shared = set()
    for name, mod in list(sys.modules.items()):
        if mod is not None and (
            name.startswith("mstmm.numerics.") or name == "mstmm.generated.euler_bernoulli"
        ):
            ns.update(vars(mod))
            shared.add(name)
    ns.update(vars(module))
    for name, obj in list(ns.items()):
        f = getattr(obj, "py_func", None)
        if not isinstance(f, types.FunctionType) and getattr(obj, "__module__", None) in shared:
            f = obj  # a plain function of the numerics (``generic``'s real and complex twins)
        if isinstance(f, types.FunctionType):
            ns[name] = types.FunctionType(f.__code__, ns, f.__name__, f.__defaults__, f.__closure__)
    for name in PULSES:
        if name in ns:
            ns[name] = _watch(ns[name])
    return ns


class Overrun(Exception):
    """A run as Python took longer than it was allowed: the caller runs it compiled."""


def allowance(cold: bool = False) -> float:
    """Seconds an interpreted run may take before it is stopped: twice what is left of the
    budget (at least a tenth of it, so that a last small run may finish)."""
    limit = _limit(cold)
    return 2.0 * max(limit - _Process.spent, 0.1 * limit)


#: When a run as Python must stop (``deadline``; none outside one).
_DEADLINE = [math.inf]
#: Functions of the numerics that a run as Python calls once per piece of a segment: the
#: deadline is checked in them too, since one evaluation of a long field (a string-like
#: tensioned beam: 10^5 pieces) takes seconds as Python.
PULSES = ("compound_step", "segment_piece")


@contextmanager
def deadline(seconds: float) -> Iterator[None]:
    """Within: a function made by :func:`watched` (or a pulse of the copy, :data:`PULSES`)
    raises :class:`Overrun` once ``seconds`` have passed."""
    _DEADLINE[0] = time.perf_counter() + seconds
    try:
        yield
    finally:
        _DEADLINE[0] = math.inf


def _watch(f):
    """``f`` checking the deadline before each call."""

    def checked(*args):
        if time.perf_counter() > _DEADLINE[0]:
            raise Overrun
        return f(*args)

    return checked


def watched(functions: tuple) -> tuple:
    """``functions`` (handed to a driver run as Python: what every evaluation of the
    search goes through), each checking the deadline (:func:`deadline`), so that a run
    whose estimate proved wrong stops soon after it."""
    return tuple(_watch(f) for f in functions)


def timed_call(fn, *args):
    """``fn(*args)``, its duration charged to this process's budget."""
    t0 = time.perf_counter()
    try:
        return fn(*args)
    finally:
        _Process.spent += time.perf_counter() - t0

"""Topology -> compiled kernel: the committed module, the user cache, or a fresh derivation.

A kernel is a generated module (printed by ``mstmm.derive.emit``) whose functions,
compiled with the shared numerics, compute the characteristic functions of one topology
for any parameter vector. Lookup order:

1. ``mstmm.generated.<key>`` (committed for the bundled scenes), if its
   ``SIGNATURE`` matches the current derivation code;
2. ``<cache>/<key>_<signature>.py`` in the user cache (``MSTMM_CACHE`` or
   ``$XDG_CACHE_HOME/mstmm`` or ``~/.cache/mstmm``);
3. derive it with SymPy (only now is SymPy imported), write it to the cache
   atomically, and load it from there.

Files carry a hash of everything that decides their content in their name, so
numba's on-disk cache (keyed on the file) stays valid (DESIGN.md, tool-chain facts).
"""

from __future__ import annotations

import functools
import importlib
import importlib.metadata
import importlib.util
import math
import sys
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from types import ModuleType
from typing import NamedTuple

import numpy as np

from mstmm import catalog
from mstmm.cachedir import cache_dir
from mstmm.catalog import EVENT_WIDTH, HEAD, SEGMENT_WIDTH, TERMS_COLUMN, event_rows, march_ends
from mstmm.sign import signature

from . import compiling, interpret, progress
from .loader import KernelError, load_file
from .topology import Topology

#: Characteristic functions every kernel carries (``evaluate_<name>``, ``refine_<name>``).
FORMULATIONS = ("stable", "paper")

#: Modes :meth:`Kernel.lowest` finds in one kernel call; more go block by block.
BLOCK_MODES = 256
#: Components from which ``Kernel.lowest`` refines its roots in parallel (``_defers``).
DEFER_EVENTS = 200


class Found(NamedTuple):
    """What the kernel's root search found (:meth:`Kernel.lowest`)."""

    #: Frequencies (rad/s), ascending, repeated by multiplicity (rigid-body zeros first).
    omega: np.ndarray
    #: Per value, nonzero where the count holds a root that the function does not confirm,
    #: or Brent's method did not converge (checked again by :func:`mstmm.scan.verify`).
    untrusted: np.ndarray
    #: The true multiplicity of the last root (it may exceed its copies in ``omega``).
    last: int
    #: Whether the Wittrick-Williams count certified every root (none missed, none extra).
    certified: bool
    #: Where the count stopped certifying (rad/s; 0 when ``certified``).
    failed_at: float


def _bundled(topology: Topology, sig: str) -> ModuleType | None:
    name = f"mstmm.generated.{topology.kernel_key}"
    try:
        module = importlib.import_module(name)
    except ModuleNotFoundError as exc:
        if exc.name != name:  # numba (or numpy) missing: not a kernel that is absent
            raise
        return None
    if getattr(module, "SIGNATURE", None) != sig or not reads_this_layout(module, topology):
        return None
    return module


def reads_this_layout(module: ModuleType, topology: Topology) -> bool:
    """Whether a kernel was printed for the parameter layout ``catalog.layout`` writes
    today (its ``SEGMENT_COLUMNS`` and ``DATA_BLOCKS``, the contract printed into it):
    the signature covers what the layout comes from; this reads the contract itself."""
    columns = getattr(module, "SEGMENT_COLUMNS", None)
    blocks = getattr(module, "DATA_BLOCKS", None)
    return columns == catalog.segment_columns() and blocks == catalog.data_blocks(topology.kinds)


_NUMERICS: list[ModuleType] = []


def numerics() -> ModuleType:
    """The numerics every kernel shares (``mstmm.numerics``): the drivers that take a
    kernel's characteristic functions as arguments."""
    if not _NUMERICS:
        _NUMERICS.append(importlib.import_module("mstmm.numerics"))
    return _NUMERICS[0]


def _check_numerics() -> None:
    """The printed beam functions (``mstmm.generated.euler_bernoulli``) must be the ones the
    derive code prints: the numerics and every kernel use them."""
    from mstmm.sign import derive_digest

    printed = importlib.import_module("mstmm.generated.euler_bernoulli")
    if printed.DIGEST != derive_digest():
        raise KernelError(
            "mstmm/generated/euler_bernoulli.py is older than the derive code: regenerate it"
            " with python -m mstmm.derive --bundled"
        )


def write_kernel(topology: Topology, directory: Path, name: str | None = None) -> Path:
    """Derive the kernel of ``topology`` into ``directory`` (``mstmm.derive.emit``; SymPy
    is imported only now)."""
    from mstmm.derive.emit import write_kernel as derive_and_write

    return derive_and_write(topology, directory, name)


def kernel_module(topology: Topology) -> tuple[ModuleType, str, float]:
    """The kernel module of ``topology``, where it came from, and the seconds spent deriving it.

    The origin is a package name (bundled) or a path (user cache); the derive
    time is 0 unless SymPy had to write the kernel now.
    """
    _check_numerics()
    sig = signature(topology)
    module = _bundled(topology, sig)
    if module is not None:
        return module, module.__name__, 0.0
    directory = cache_dir()
    path = directory / f"{topology.kernel_key}_{sig[:16]}.py"
    derived = 0.0
    if not path.exists():
        t0 = time.perf_counter()
        try:
            with progress.status(f"deriving the {topology.kernel_key} kernel with SymPy"):
                write_kernel(topology, directory)
        except OSError as exc:
            raise KernelError(f"kernel cache {directory} is not writable: {exc}") from exc
        derived = time.perf_counter() - t0
    module_name = f"mstmm_kernel_{topology.kernel_key}_{sig[:16]}"
    module = sys.modules.get(module_name) or load_file(path, module_name)
    if not reads_this_layout(module, topology):
        raise KernelError(
            f"kernel {path} reads another parameter layout than this mstmm writes"
            " (SEGMENT_COLUMNS, DATA_BLOCKS): delete it and it is derived again"
        )
    return module, str(path), derived


@dataclass
class Kernel:
    """A loaded kernel: the characteristic functions of one topology, for any parameters."""

    topology: Topology
    module: ModuleType
    origin: str
    #: Seconds SymPy spent writing this kernel in this process (0: it existed).
    derive_seconds: float = 0.0
    #: Entry points already compiled or loaded from numba's cache in this process.
    warmed: set = field(default_factory=set)
    #: The module's functions as plain Python, built on first use (:mod:`mstmm.interpret`).
    _python: dict | None = field(default=None, repr=False)
    #: Addresses of the compiled functions the shared drivers call (:meth:`_addresses`).
    _fa: np.ndarray | None = field(default=None, repr=False)
    #: The shared drivers bound to ``_fa`` (:meth:`compiled`), by (driver, formulation).
    _bound: dict = field(default_factory=dict, repr=False)
    #: Kernel functions compiled or loaded from numba's cache in this process.
    _loaded: set = field(default_factory=set, repr=False)
    #: Whether numba's cache lacked the characteristic function when first asked (``_cold``).
    _was_cold: bool | None = field(default=None, repr=False)

    @staticmethod
    def shape_ends(p: np.ndarray) -> np.ndarray:
        """The ends for the shared mode-shape march of ``p``: the left end's unknowns, the
        right end's knowns (state indices of [Y, theta, M, Q]), as p's head holds them."""
        return np.array(march_ends(p), dtype=np.int64)

    def warm_up(self, p: np.ndarray, formulation: str = "stable") -> None:
        """Compile (or load from numba's cache) what a solve of ``formulation`` calls (the
        root search with its characteristic function and the count), once per process.
        Each compiled function loaded costs a fresh process tens of milliseconds, so only
        these."""
        if formulation in self.warmed:
            return
        interpret.mark_compiled()
        with progress.status(f"compiling the {self.topology.kernel_key} kernel (numba caches it)"):
            self.lowest(p, 1, formulation=formulation)
        self.warmed.add(formulation)

    def evaluate(
        self, omegas: np.ndarray, p: np.ndarray, formulation: str = "stable"
    ) -> tuple[np.ndarray, np.ndarray]:
        """Characteristic function at each ``omega`` as ``(mantissa, log)`` arrays."""
        omegas = np.ascontiguousarray(omegas, dtype=np.float64)
        mant = np.empty_like(omegas)
        logs = np.empty_like(omegas)
        p = _params(p)
        modes = omegas.size / interpret.EVALUATIONS_PER_MODE
        self.run(lambda call: call("evaluate", omegas, p, mant, logs), p, modes, formulation)
        return mant, logs

    def run(
        self,
        body,
        p: np.ndarray,
        modes: float | None,
        formulation: str = "stable",
        what: str | None = None,
        driver: str | None = None,
        cost: float | None = None,
    ):
        """``body(call)`` in the cheapest tier that may run it now, where ``call(name,
        *args)`` runs the shared driver ``name`` (``numerics.entries.DRIVERS``: its own
        arguments, the kernel's functions put in by the tier); the one place that chooses:

        1. as plain Python (:mod:`mstmm.interpret`), when the interpreted tier takes work of
           ``modes`` modes of :meth:`lowest` (:meth:`interprets` of ``what``, the
           formulation by default; the stable formulation only; not at all for ``modes``
           None), stopped at its deadline;
        2. the driver ``driver`` as Python while a helper compiles it or a kernel function
           it takes (``compiling.python_instead``, ``cost`` seconds or the interpreted
           tier's estimate), around the kernel's functions (compiled, but those a helper is
           still compiling), stopped where its Python allowance ends;
        3. compiled (``call.compiled``): the driver's machine code with the addresses of the
           kernel's compiled functions (:meth:`compiled`).

        A run stopped at its deadline is run again from the start in the next tier: ``body``
        must begin by clearing what it writes."""
        what = what or formulation
        if (
            modes is not None
            and formulation == "stable"
            and self.interprets(p, math.ceil(modes), what)
        ):
            call = _Call(lambda name, *a: interpret.timed_call(self._in_python(name), *a))
            try:
                with interpret.deadline(interpret.allowance(self._cold())):
                    return body(call)
            except interpret.Overrun:  # the estimate was wrong: compiled, from the start,
                interpret.mark_compiled()  # and so is the rest of this process's work
        if driver is not None:
            # past the interpreted tier: machine code from here on, and the helpers
            # compile what numba's cache lacks meanwhile (before they are asked about)
            interpret.mark_compiled()
            compiling.start()
            compiling.start_kernel(self.module)
        if driver is not None and compiling.any_helper():
            names = self._functions(driver, formulation)
            pending = self._pending(*names)
            own = driver in self.PYTHON_WHILE_COMPILING
            if cost is None:
                walks = pending or own  # the events run as Python: they cost per component
                n = self.attachments(p) if walks else 0
                cost = interpret.estimated_cost(modes or 0, n)
            if compiling.python_instead(driver, cost, pending):
                get = self._python_function if own else self._for_python
                run = self._in_python

                def python(name, *a):
                    return compiling.timed_call(driver, run(name, formulation, get), *a)

                try:
                    with interpret.deadline(compiling.python_left(driver)):
                        return body(_Call(python))
                except interpret.Overrun:  # past its allowance: the driver is waited for
                    pass
        result = body(_Call(lambda name, *a: self.compiled(name, formulation)(*a), True))
        self.warmed.add(what)
        return result

    #: Drivers whose run as Python while they compile takes the kernel's functions as Python
    #: too (they walk the components themselves: machine code for one event gains little).
    PYTHON_WHILE_COMPILING = ("counts", "mode_shapes")

    def _functions(self, driver: str, formulation: str = "stable") -> tuple[str, ...]:
        """The kernel functions the driver ``driver`` takes (``numerics.entries.DRIVERS``),
        ``delta`` the formulation's characteristic function."""
        names = _DRIVER_FUNCTIONS.get((driver, formulation))
        if names is None:
            if formulation not in FORMULATIONS:
                choose = f"choose from {FORMULATIONS}"
                raise ValueError(f"unknown formulation {formulation!r}; {choose}")
            declared = numerics().DRIVERS[driver][1]
            names = tuple(f"delta_{formulation}" if n == "delta" else n for n in declared)
            _DRIVER_FUNCTIONS[(driver, formulation)] = names
        return names

    def _in_python(self, driver: str, formulation: str = "stable", get=None):
        """The driver ``driver`` as plain Python around the kernel's functions (``get``: as
        plain Python by default), each checking the run's deadline."""
        get = get or self._python_function
        functions = interpret.watched(tuple(get(n) for n in self._functions(driver, formulation)))
        python = self._python_function(numerics().DRIVERS[driver][0])
        return lambda *args: python(*functions, *args)

    def _for_python(self, name: str):
        """A kernel function for a driver run as Python: compiled, or as Python while a
        helper compiles it; a frequency passed on as a float (an int would make numba
        compile another specialization)."""
        f = self._ready(name)
        if name in _FREQUENCY_FIRST:
            return lambda w, *a: f(float(w), *a)
        return f

    def compiled(self, driver: str, formulation: str = "stable"):
        """The shared driver ``entry_<driver>`` bound to this kernel's compiled functions
        (``numerics.entries.DRIVERS``; compiled or loaded from numba's cache on first use):
        call it with the driver's own arguments."""
        bound = self._bound.get((driver, formulation))
        if bound is None:
            # those the kernel has: a damped kernel has no real march (``bloch_waves`` then
            # marches in complex arithmetic only)
            names = self._functions(driver, formulation)
            fa = self._addresses(*(n for n in names if hasattr(self.module, n)))
            entry = self._entry(driver)
            if "delta" in numerics().DRIVERS[driver][1]:
                at = numerics().FUNCTION_TYPES[f"delta_{formulation}"][0]
                bound = functools.partial(entry, fa, at)
            else:
                bound = functools.partial(entry, fa)
            self._bound[(driver, formulation)] = bound
        return bound

    def delta(
        self, omega: float, p: np.ndarray, formulation: str = "stable"
    ) -> tuple[float, float]:
        """``(mantissa, log)`` of the characteristic function at one frequency."""
        mant, logs = self.evaluate(np.array([omega]), p, formulation)
        return float(mant[0]), float(logs[0])

    def refine(
        self,
        a: float,
        b: float,
        p: np.ndarray,
        formulation: str = "stable",
        rtol: float = 0.0,
        maxiter: int = 200,
    ) -> tuple[float, int, bool]:
        """Root in a sign-change bracket ``[a, b]``: ``(omega, iterations, converged)``."""
        refine = self.compiled("refine", formulation)
        root, its, ok = refine(float(a), float(b), _params(p), float(rtol), int(maxiter))
        return float(root), int(its), bool(ok)

    def _entry(self, name: str):
        """A shared driver of ``mstmm.numerics`` (``entry_<name>``)."""
        interpret.mark_compiled()
        compiling.start()
        compiling.wait(name)
        return getattr(numerics(), f"entry_{name}")

    def _addresses(self, *names: str) -> np.ndarray:
        """The array ``fa`` the shared drivers take: the addresses of this kernel's compiled
        functions (C wrapper, numba entry), those in ``names`` compiled or loaded from
        numba's cache first (once per process)."""
        from numba.experimental.function_type import _get_jit_address, _get_wrapper_address

        n = numerics()
        if self._fa is None:
            self._fa = np.zeros(n.FA_SIZE, dtype=np.int64)
        todo = [name for name in names if self._fa[n.FUNCTION_TYPES[name][0]] == 0]
        # those a helper is compiling now last: this process compiles the others meanwhile
        todo.sort(key=lambda name: compiling.kernel_busy(self.module, name))
        for name in todo:
            at, ftype = n.FUNCTION_TYPES[name]
            f = self._compiled(name)
            sig = ftype.signature
            self._fa[at] = _get_wrapper_address(f, sig)
            self._fa[at + 1] = _get_jit_address(f, sig)
        return self._fa

    def _compiled(self, name: str):
        interpret.mark_compiled()
        compiling.start()  # the shared drivers compile in helpers meanwhile, if not cached
        compiling.start_kernel(self.module)  # and some of this kernel's functions
        f = getattr(self.module, name)
        if name not in self._loaded and name in compiling.KERNEL_BACKGROUND:
            # compiled here, or by the helper (waited for, then loaded from numba's cache)
            with compiling.kernel_claim(self.module, name):
                f.compile(numerics().FUNCTION_TYPES[name][1].signature)
        self._loaded.add(name)
        return f

    def _pending(self, *names: str) -> bool:
        """Whether a helper is still to compile one of this kernel's functions ``names``
        (this process then runs them as Python, within ``compiling``'s budget)."""
        for n in names:
            if n not in self._loaded and compiling.kernel_pending(self.module, n):
                return True
        return False

    def _ready(self, name: str):
        """The kernel function ``name`` compiled, or as Python while a helper compiles it."""
        if self._pending(name):
            return self._python_function(name)
        return self._compiled(name)

    def attachments(self, p: np.ndarray) -> int:
        """Number of point components a parameter vector describes."""
        return int(p[4])

    def oscillator_frequencies(self, p: np.ndarray) -> np.ndarray:
        """The components' own frequencies (rad/s, ascending), where roots crowd."""
        return np.asarray(self._cheapest("oscillator_frequencies")(_params(p))[0])

    def rigid_body_modes(self, p: np.ndarray) -> int:
        """Number of zero natural frequencies (rigid motions the ends and components allow)."""
        return int(self._cheapest("rigid_body_modes")(_params(p)))

    def _cheapest(self, name: str):
        """A small kernel function: as plain Python until this process has loaded machine
        code (loading it costs a fresh process far more than the call)."""
        if interpret.machine_code_loaded():
            return self._ready(name)
        return self._python_function(name)

    def interprets(self, p: np.ndarray, modes: int, what: str = "stable") -> bool:
        """Whether :meth:`lowest` runs as plain Python (see :mod:`mstmm.interpret`); for
        another entry point ``what``, ``modes`` is its cost in modes of ``lowest``."""
        if what in self.warmed or interpret.machine_code_loaded():
            return False  # decided before looking at p: a warm call costs microseconds
        general = _general_segments(p)
        return interpret.worthwhile(modes, self.attachments(p), general, self._cold())

    def _cold(self) -> bool:
        """Whether numba's cache lacks this kernel's characteristic function (a first run:
        machine code would be compiled, not loaded; looked at once a process)."""
        if self._was_cold is None:
            delta = getattr(self.module, "delta_stable", None)
            self._was_cold = delta is not None and not compiling._holds(delta)
        return self._was_cold

    def _python_function(self, name: str):
        """The kernel's (or the shared numerics') function ``name`` as plain Python
        (:func:`interpret.python_copy`)."""
        if self._python is None:
            self._python = interpret.python_copy(self.module)
        return _ieee(self._python[name])

    def lowest(
        self,
        p: np.ndarray,
        modes: int,
        certify: bool = True,
        formulation: str = "stable",
        rtol: float = 0.0,
    ) -> Found:
        """The lowest ``modes`` frequencies by the kernel's certified scan (the root search;
        :func:`mstmm.scan.find_roots` drives it).

        Sign changes of the characteristic function on a grid uniform in beta plus a node
        on either side of every component's own frequency, one Wittrick-Williams count
        per block, Brent's method on each sign change whose root is reported; where the
        count disagrees, bisection on the count (which finds double roots and drops
        spurious sign changes). Where the count cannot certify a block
        the search goes on without it and says so (``Found.certified``). Without
        ``certify`` the sign-change roots come unchecked. Up to :data:`BLOCK_MODES`
        modes run in one kernel call; more run block by block (a progress bar on a
        terminal).
        """
        modes = int(modes)
        p = _params(p)
        certify = bool(certify)
        rtol = float(rtol)
        size = self.module.STATE_SIZE

        def body(call) -> Found:
            out = np.zeros(modes)
            flags = np.zeros(modes, dtype=np.int64)
            state = np.zeros(size)
            if call.compiled and modes > BLOCK_MODES:
                k = self._lowest_in_blocks(p, modes, out, flags, state, certify, formulation, rtol)
                return self._found(out, flags, state, k)
            if call.compiled and self._defers(p):  # room for the brackets left pending
                state = np.full(size + self.module.PENDING_WIDTH * modes, np.nan)
                state[:size] = 0.0
            k = call("lowest", p, modes, out, flags, state, certify, rtol)
            if call.compiled:
                self._refine_pending(formulation, p, state, out, flags, k, rtol)
            return self._found(out, flags, state, int(k))

        return self.run(body, p, modes, formulation, driver="lowest")

    @staticmethod
    def _defers(p: np.ndarray) -> bool:
        """Whether ``lowest`` leaves its roots' refinement to ``_refine_pending`` (roots
        refined in parallel): with at least :data:`DEFER_EVENTS` components (each
        evaluation a walk long enough to outweigh starting the threads), and only on the
        main thread (numba's workqueue threading layer, the fork-safe one ``mstmm.jit``
        picks where TBB is missing, must not start parallel work from two threads at once;
        a solve in another thread refines its roots itself)."""
        return p[4] >= DEFER_EVENTS and threading.current_thread() is threading.main_thread()

    def _refine_pending(self, formulation, p, state, out, flags, k: int, rtol: float) -> None:
        """Refine the roots ``lowest`` left pending (their brackets in ``state`` beyond
        STATE_SIZE, ``numerics.search.PENDING_WIDTH``), in parallel over the roots."""
        m = self.module
        if state.size == m.STATE_SIZE:
            return
        k = k if k >= 0 else int(state[m.STATE_K])
        pending = state[m.STATE_SIZE :].reshape(-1, m.PENDING_WIDTH)[:k, 0]
        rows = np.flatnonzero(np.isfinite(pending)).astype(np.int64)
        if rows.size:
            refine = self.compiled("refine_pending", formulation)
            refine(p, state, rows, out, flags, float(rtol))

    def _found(self, out: np.ndarray, flags: np.ndarray, state: np.ndarray, k: int) -> Found:
        m = self.module
        if k < 0:  # the search gave up: the roots written before it did still stand
            k = int(state[m.STATE_K])
        certified = bool(state[m.STATE_CERTIFIED] == 1.0) and k == out.size
        failed = 0.0
        if not certified:
            failed = float(state[m.STATE_FAILED]) or float(state[m.STATE_W])
        if k < out.size:
            out, flags = out[:k], flags[:k]
        return Found(out, flags, int(state[m.STATE_LAST]), certified, failed)

    def _lowest_in_blocks(
        self,
        p: np.ndarray,
        modes: int,
        out: np.ndarray,
        flags: np.ndarray,
        state: np.ndarray,
        certify: bool,
        formulation: str,
        rtol: float,
    ) -> int:
        """:meth:`lowest` as a Python loop over kernel blocks, drawing progress between them.

        A block holds :data:`BLOCK_MODES` modes or a quarter of those found so
        far, whichever is more: the count that certifies it costs O(lambda L)
        (about 0.25 us per mode below it on the paper's example, against about
        12 us per mode for the scan and Brent), so the counts add under 10% and
        the cost stays linear in ``modes``."""
        k = int(self.compiled("lowest_start")(p, modes, out, flags, state, certify))
        run = self.compiled("lowest_run", formulation)
        bar = progress.Bar(modes, "modes")
        try:
            bar.update(max(k, 0))
            while 0 <= k < modes:
                stop = min(modes, k + max(BLOCK_MODES, k // 4))
                k_new = int(run(p, modes, out, flags, state, stop, certify, np.inf, rtol))
                bar.update(max(k_new - k, 0))
                k = k_new
        finally:
            bar.close()
        return k

    def roots_in_band(
        self,
        p: np.ndarray,
        lo: float,
        hi: float,
        from_bottom: bool,
        formulation: str = "stable",
        rtol: float = 0.0,
    ) -> Found:
        """The roots between ``lo`` and ``hi`` as the count sees them (rad/s, ascending,
        repeated by multiplicity) by the search of :meth:`lowest`, started at ``lo`` and
        stopped at ``hi``. ``from_bottom``: start where :meth:`lowest` starts instead
        (``lo`` is below its lowest scan node, beta = 1e-3), rigid-body zeros included.
        Roots within the count's resolution of an edge may fall either way: callers
        search a wider band and keep roots by value (:func:`mstmm.scan.band_roots`)."""
        p = _params(p)
        m = self.module
        n_hi = int(self.count_below(hi, p)[0])
        n_lo = 0 if from_bottom else int(self.count_below(lo, p)[0])
        size = max(n_hi - n_lo, 0)

        def body(call) -> Found:
            out = np.zeros(size)
            flags = np.zeros(size, dtype=np.int64)
            state = np.zeros(m.STATE_SIZE)
            if from_bottom:
                k = int(call("lowest_start", p, size, out, flags, state, True))
            else:
                state[m.STATE_W], state[m.STATE_COUNT] = lo, n_lo
                state[m.STATE_CERTIFIED] = 1.0
                k = 0
            if n_hi < n_lo:  # a count that decreases: nothing it says can be certified
                state[m.STATE_CERTIFIED], state[m.STATE_FAILED] = 0.0, lo
            if 0 <= k < size:
                args = (p, size, out, flags, state, size, True, float(hi), rtol)
                k = int(call("lowest_run", *args))
            return self._found(out, flags, state, k)

        return self.run(body, p, size, formulation)

    def sweep(self, P: np.ndarray, modes: int) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`lowest` for every row of ``P``, in parallel on all cores (numba prange)."""
        P = np.ascontiguousarray(P, dtype=np.float64)
        out = np.zeros((P.shape[0], int(modes)))
        certified = np.zeros(P.shape[0], dtype=np.bool_)
        self.compiled("sweep_lowest")(P, int(modes), out, certified)
        return out, certified

    def count_below(self, omegas: np.ndarray, p: np.ndarray) -> np.ndarray:
        """Number of natural frequencies below each ``omega`` (Wittrick-Williams).

        An ``omega`` within ``POLE_GUARD`` (4e-15, relative) of a component's own
        frequency w is counted at w (1 - POLE_GUARD) instead: exactly at w the
        component stands like a support and the count is not defined there (the search
        keeps its own counts off those points the same way: ``search.near_pole``)."""
        omegas = np.ascontiguousarray(np.atleast_1d(omegas), dtype=np.float64)
        out = np.empty(omegas.shape, dtype=np.int64)
        p = _params(p)
        modes = omegas.size / interpret.EVALUATIONS_PER_MODE
        counts = lambda call: call("counts", omegas, p, out)  # noqa: E731
        self.run(counts, p, modes, what="counts", driver="counts")
        return out

    def event_positions(self, p: np.ndarray) -> np.ndarray:
        """x (m) of every point component of a parameter vector, sorted by x."""
        rows = np.asarray(p[event_rows(p)]).reshape(-1, EVENT_WIDTH)
        return np.sort(rows[:, 1], kind="stable")

    def mode_shapes(self, omega: float, p: np.ndarray, m: int, xs: np.ndarray):
        """The shared ``mode_shapes`` at ``omega`` for an ``m``-dimensional eigenspace.

        Returns ``(Z, q, q_x, q_mass, gram, part, ratio)`` in units ``L = EI_0 = mbar_0 =
        1``: the states ``[Y, theta, M, Q]`` at ``xs`` (m, len(xs), 4), every point
        component's unknowns (m, n_q) with the x (m) of their component and (2, n_q)
        the mass (or rotary inertia) moving with each and the share of it a rigid
        translation carries (0 for a reaction), the mass Gram matrix, the
        mass-weighted integrals of Y, and each shape's singular value over the end
        matrix's largest (see :mod:`mstmm.modes`).
        """
        p = _params(p)
        xs = np.ascontiguousarray(xs, dtype=np.float64)
        m = int(m)
        nq = int(self._cheapest("shape_sizes")(p)[0])
        ends = self.shape_ends(p)

        def body(call) -> tuple:
            Z = np.zeros((m, xs.shape[0], 4))
            q = np.zeros((m, nq))
            q_x = np.zeros(nq)
            q_mass = np.zeros((2, nq))
            gram = np.zeros((m, m))
            part = np.zeros(m)
            ratio = np.zeros(m)
            args = (ends, float(omega), p, m, xs, Z, q, q_x, q_mass, gram, part, ratio)
            call("mode_shapes", *args)
            return Z, q, q_x, q_mass, gram, part, ratio

        cost = m * interpret.SHAPE_COST_FACTOR
        return self.run(body, p, cost, what="mode_shapes", driver="mode_shapes")

    def frf(
        self, omegas: np.ndarray, p: np.ndarray, inputs: np.ndarray, outputs: np.ndarray
    ) -> np.ndarray:
        """Responses (complex, SI) at each frequency (rad/s, real or complex) to unit loads:
        ``inputs`` and ``outputs`` rows ``(kind, x, q index, scale)`` (``frf_march`` in
        ``mstmm.numerics.frf``); returns an array (frequencies, inputs, outputs). The
        frequencies run in parallel on all cores."""
        ws = np.ascontiguousarray(np.atleast_1d(omegas), dtype=np.complex128)
        inputs = np.ascontiguousarray(inputs, dtype=np.float64)
        outputs = np.ascontiguousarray(outputs, dtype=np.float64)
        out = np.zeros((ws.size, inputs.shape[0], outputs.shape[0]), dtype=np.complex128)
        p = _params(p)
        damped = self.topology.damped
        self.compiled("frf")(self.shape_ends(p), damped, ws, p, inputs, outputs, out)
        return out

    def unknowns(self, p: np.ndarray) -> list[tuple[float, float, float]]:
        """``(x, mass, inertia)`` of every component unknown in order (the q index of
        ``frf``): ``mass`` the mass a rigid translation carries (> 0 for a hanging mass,
        units mbar_0 L), ``inertia`` the mass or rotary inertia moving with it (a rotary
        inertia is an unknown with ``inertia > 0`` and ``mass = 0``, such as a torsional
        absorber's rotation); both 0 for a reaction or a hinge's rotation."""
        p = _params(p)
        m = self.module
        total, most = (int(v) for v in self._compiled("shape_sizes")(p))
        nb = max(1, most)
        Cz, Cq = np.zeros((nb, 4), complex), np.zeros((nb, nb), complex)
        from .numerics.shapes import QMASS_ROWS

        A, B = np.zeros((4, 4), complex), np.zeros((4, nb), complex)
        qmass = np.zeros((QMASS_ROWS, nb))
        out = []
        event = self._compiled("shape_event_c")
        for row in m.event_order(p):
            nc, nq = event(p, int(row), 1.0 + 0.0j, Cz, Cq, A, B, qmass)
            out += [(float(p[row + 1]), float(qmass[1, j]), float(qmass[0, j])) for j in range(nq)]
        return out

    def u_bar(self, omega: float, p: np.ndarray) -> np.ndarray:
        """``U_bar(omega)`` of paper Eq. (4), reduced by the boundary conditions."""
        return self._compiled("u_bar_paper")(float(omega), _params(p))


class _Call:
    """How one tier of :meth:`Kernel.run` runs a shared driver: ``call(name, *args)``;
    ``compiled``: whether it runs machine code (the compiled tier)."""

    __slots__ = ("run", "compiled")

    def __init__(self, run, compiled: bool = False):
        self.run = run
        self.compiled = compiled

    def __call__(self, name: str, *args):
        return self.run(name, *args)


#: The kernel functions each (driver, formulation) takes (``Kernel._functions``).
_DRIVER_FUNCTIONS: dict[tuple[str, str], tuple[str, ...]] = {}

#: Kernel functions whose first argument is a frequency (passed on as a float by
#: :meth:`Kernel._for_python`).
_FREQUENCY_FIRST = ("delta_stable", "delta_paper", "count_below")


def _ieee(f):
    """``f`` run as the machine code runs it: IEEE arithmetic without numpy's warnings.

    The compiled kernel divides by zero and overflows silently (inf and nan are values the
    count and the search handle, e.g. ``k^2/d`` at a pole of a chain's stage); the same
    function interpreted on numpy scalars would warn about them, and those warnings would
    reach the user."""

    @functools.wraps(f)
    def quiet(*args):
        with np.errstate(all="ignore"):
            return f(*args)

    return quiet


def _general_segments(p: np.ndarray) -> bool:
    """Whether a segment of p has a term beyond Euler-Bernoulli (its ``exp(A h)`` per piece
    makes the interpreted search dearer: ``interpret.GENERAL_SEGMENT_FACTOR``)."""
    n = int(p[3])
    rows = np.asarray(p[HEAD : HEAD + SEGMENT_WIDTH * n]).reshape(n, SEGMENT_WIDTH)
    return bool(np.any(rows[:, TERMS_COLUMN:] != 0.0))


def _params(p) -> np.ndarray:
    return np.ascontiguousarray(p, dtype=np.float64)


_LOADED: dict[str, Kernel] = {}


def load_kernel(topology: Topology) -> Kernel:
    """The kernel of ``topology`` (memoised per process)."""
    kernel = _LOADED.get(topology.key)
    if kernel is None:
        module, origin, derived = kernel_module(topology)
        kernel = Kernel(topology, module, origin, derived)
        _LOADED[topology.key] = kernel
    return kernel

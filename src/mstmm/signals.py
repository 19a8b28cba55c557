"""SIGTERM handled as Ctrl-C is: the command line's cleanup runs, then one line.

A command writing ``--out`` writes a hidden temporary file beside its target and
removes it when interrupted (:func:`mstmm.output.atomic_file`): by ``except
BaseException``, which a Python ``KeyboardInterrupt`` reaches but a default SIGTERM
(the process killed outright) does not. :func:`sigterm_as_interrupt` raises
:class:`Terminated`, a ``KeyboardInterrupt``, on SIGTERM, so that the same cleanup runs.

This module imports nothing heavy: the command line installs the handler before numpy
and numba load.
"""

from __future__ import annotations

import _thread
import os
import signal
import sys
import threading
from collections.abc import Iterator
from contextlib import contextmanager

#: Exit status after SIGTERM: the conventional 128 + 15 (SIGINT gives 128 + 2 = 130).
EXIT_TERMINATED = 128 + signal.SIGTERM


class Terminated(KeyboardInterrupt):
    """SIGTERM arrived: raised where the program was, as Ctrl-C raises KeyboardInterrupt."""


def _raise_terminated(signum: int, frame: object, owner: int) -> None:
    if os.getpid() != owner:  # a forked child (a worker): die as SIGTERM would have it
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        os.kill(os.getpid(), signal.SIGTERM)
        return
    raise Terminated("SIGTERM")


@contextmanager
def sigterm_as_interrupt() -> Iterator[None]:
    """While the block runs, SIGTERM raises :class:`Terminated` (in this process only; a
    forked child dies as by default). The previous handler comes back after the block.
    Nothing is installed outside the main thread (Python allows signal handlers there only)."""
    owner = os.getpid()
    try:
        previous = signal.signal(
            signal.SIGTERM, lambda signum, frame: _raise_terminated(signum, frame, owner)
        )
    except ValueError:  # not the main thread
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


@contextmanager
def interrupts_kept() -> Iterator[None]:
    """While the block runs (the heavy imports), a Ctrl-C or SIGTERM is raised as the
    interrupt it is even where C code turns it into another error: numpy's C extension,
    interrupted while it imports ``datetime``, raises ``ImportError: PyCapsule_Import
    could not import module "datetime"`` (seen in a CI run). The signal is noted as it
    arrives (where Python's own handler, or :func:`sigterm_as_interrupt`'s, would have
    raised); an exception that leaves the block after one is replaced by the interrupt.
    The previous handlers come back after the block; outside the main thread nothing is
    installed."""
    arrived: list[int] = []
    handlers = {}

    def note(signum: int, frame: object) -> None:
        arrived.append(signum)
        handlers[signum](signum, frame)

    try:
        for signum in (signal.SIGINT, signal.SIGTERM):
            handler = signal.getsignal(signum)
            if callable(handler):  # not SIG_IGN (a background job's Ctrl-C) nor SIG_DFL
                handlers[signum] = handler
                signal.signal(signum, note)
    except ValueError:  # not the main thread
        yield
        return
    try:
        yield
    except Exception as exc:
        if not arrived:
            raise
        if arrived[0] == signal.SIGTERM:
            raise Terminated("SIGTERM") from exc
        raise KeyboardInterrupt from exc
    finally:
        for signum, handler in handlers.items():
            signal.signal(signum, handler)


@contextmanager
def interrupts_not_lost() -> Iterator[None]:
    """While the block runs, a Ctrl-C or SIGTERM that arrives inside a ctypes callback is
    raised again in the main thread, not lost: numba's machine-code cache is called back
    from C while LLVM emits code (``ExecutionEngine._raw_object_cache_getbuffer``), and
    ctypes "ignores" an exception raised there, printing "Exception ignored on calling
    ctypes callback function" and a traceback (a CI run's ``mstmm solve`` interrupted
    while compiling). Nothing is printed; the interrupt is re-armed a millisecond later
    from a timer thread (``_thread.interrupt_main`` with its signal: the handler in place
    raises it again in the main thread; re-armed from the hook itself, it would be raised
    inside the hook, and lost again). Should it land in a callback again, it is re-armed
    again."""
    previous = sys.unraisablehook

    def hook(unraisable) -> None:
        exc = unraisable.exc_value
        if isinstance(exc, KeyboardInterrupt):
            signum = signal.SIGTERM if isinstance(exc, Terminated) else signal.SIGINT
            threading.Timer(REARM_S, _thread.interrupt_main, (signum,)).start()
            return
        previous(unraisable)

    sys.unraisablehook = hook
    try:
        yield
    finally:
        sys.unraisablehook = previous


#: Seconds after which an interrupt lost in a ctypes callback is raised again.
REARM_S = 0.001

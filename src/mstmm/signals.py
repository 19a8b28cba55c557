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

import os
import signal
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

"""Progress on a terminal: bars for sweeps, status lines for derivations and compilations.

Quiet unless :data:`enabled` is set; the command line sets it when standard
error is a terminal and the output is not JSON. Everything goes to standard
error, so standard output stays clean for tables, CSV and JSON.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager

#: Whether to draw anything at all (the command line decides).
enabled = False

#: A status line stays on the screen only when its step took at least this long (s).
KEEP_AFTER = 1.0


@contextmanager
def status(label: str) -> Iterator[None]:
    """``label ...`` while the block runs, then ``label: 6.4 s`` (or nothing if quick)."""
    if not enabled:
        yield
        return
    sys.stderr.write(f"\rmstmm: {label} ...")
    sys.stderr.flush()
    t0 = time.perf_counter()
    try:
        yield
    finally:
        dt = time.perf_counter() - t0
        sys.stderr.write("\r\x1b[K")
        if dt >= KEEP_AFTER:
            sys.stderr.write(f"mstmm: {label}: {dt:.1f} s\n")
        sys.stderr.flush()


class Bar:
    """``label [#####.....] done/total`` redrawn in place; :meth:`close` ends the line."""

    def __init__(self, total: int, label: str, width: int = 40, show: bool | None = None):
        self.total, self.label, self.width = max(int(total), 1), label, width
        self.show = enabled if show is None else show
        self.done = 0
        self.t0 = time.perf_counter()
        self._draw()

    def update(self, n: int = 1) -> None:
        self.done = min(self.total, self.done + n)
        self._draw()

    def _draw(self) -> None:
        if not self.show:
            return
        filled = self.width * self.done // self.total
        bar = "#" * filled + "." * (self.width - filled)
        dt = time.perf_counter() - self.t0
        sys.stderr.write(f"\rmstmm: {self.label} [{bar}] {self.done}/{self.total} {dt:.1f} s")
        sys.stderr.flush()

    def close(self) -> None:
        if self.show:
            sys.stderr.write("\n")
            sys.stderr.flush()

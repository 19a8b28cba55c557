"""Long work in time-bounded chunks, so that Ctrl-C gets through between them.

A numba call cannot be interrupted: Python raises :class:`KeyboardInterrupt` only
when the call returns. Work over many independent items (frequencies of an FRF,
points of a study) therefore runs in chunks whose size adapts so that each takes
about :data:`TARGET_SECONDS`, measured on the chunk before (the time between two
yields of :func:`spans`, so the caller's own work on a chunk, e.g. writing it,
counts too). A chunk may grow at most :data:`GROWTH` times the one before, so a
cost per item that rises along the work (higher frequencies march more pieces)
cannot make one chunk much longer than the target.
"""

from __future__ import annotations

import time
from collections.abc import Iterator

#: Aimed-at duration of one chunk (s): Ctrl-C is seen within about this.
TARGET_SECONDS = 0.2
#: Items of the first chunk (its cost per item is not known yet).
FIRST = 8
#: A chunk holds at most this many times the items of the one before.
GROWTH = 2
#: And never more than this many items (bounds the memory of one chunk).
MOST = 1 << 16


def spans(
    n: int,
    *,
    target: float = TARGET_SECONDS,
    first: int = FIRST,
    most: int = MOST,
) -> Iterator[slice]:
    """Slices covering ``range(n)`` in order, each sized to take about ``target`` seconds
    by the time per item of the previous slice (timed until the next one is asked for)."""
    start, size = 0, max(1, int(first))
    while start < n:
        stop = min(n, start + size)
        t0 = time.perf_counter()
        yield slice(start, stop)
        per_item = (time.perf_counter() - t0) / (stop - start)
        fit = int(target / per_item) if per_item > 0.0 else most
        size = max(1, min(fit, GROWTH * size, most))
        start = stop

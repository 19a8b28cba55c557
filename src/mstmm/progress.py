"""Progress on a terminal and in Jupyter: bars for sweeps, frequency responses and
dispersion curves, status lines for derivations and compilations.

Quiet unless :data:`enabled` is set (the command line sets it when standard error is a
terminal and the output is not JSON) or the code runs in a Jupyter kernel with tqdm
installed. Bars are tqdm's (``tqdm.auto``: a notebook widget in Jupyter) when tqdm can be
imported, else a line redrawn in place. Everything goes to standard error, so standard
output and ``--out`` files stay clean for tables, CSV and JSON.
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

#: A bar of a long run (``frf``, ``bands``) appears only once its work has taken this
#: long (s): a quick run draws nothing.
LONG_RUN = 1.0

#: Whether bars are tqdm's: None tries ``import tqdm.auto`` (False: never, True: always).
use_tqdm: bool | None = None


def _tqdm_class():
    """``tqdm.auto.tqdm``, or None when tqdm is not installed or not wanted."""
    if use_tqdm is False:
        return None
    try:
        from tqdm.auto import tqdm
    except ImportError:
        if use_tqdm:
            raise
        return None
    return tqdm


def in_notebook() -> bool:
    """Whether this runs in a Jupyter (IPython) kernel."""
    return "ipykernel" in sys.modules


def active() -> bool:
    """Whether to draw: :data:`enabled` (a terminal, said by the command line), or a
    Jupyter kernel where tqdm's notebook bar can be drawn."""
    return enabled or (in_notebook() and _tqdm_class() is not None)


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
    """``label [#####.....] done/total`` redrawn in place (or tqdm's bar); :meth:`close`
    ends it. ``show`` None: :func:`active`. Nothing is drawn before ``delay`` seconds
    have passed (a quick run shows no bar)."""

    def __init__(
        self,
        total: int,
        label: str,
        width: int = 40,
        show: bool | None = None,
        delay: float = 0.0,
    ):
        self.total, self.label, self.width = max(int(total), 1), label, width
        self.show = active() if show is None else show
        self.done = 0
        self.delay = float(delay)
        self.drawn = False
        self.t0 = time.perf_counter()
        self._tqdm = None
        tqdm = _tqdm_class() if self.show else None
        if tqdm is not None:
            self._tqdm = tqdm(
                total=self.total, desc=f"mstmm: {label}", file=sys.stderr, delay=self.delay
            )
            self.show = False
        self._draw()

    def update(self, n: int = 1) -> None:
        self.done = min(self.total, self.done + n)
        if self._tqdm is not None:
            self._tqdm.update(n)
        self._draw()

    def _draw(self) -> None:
        if not self.show:
            return
        dt = time.perf_counter() - self.t0
        if dt < self.delay:
            return
        self.drawn = True
        filled = self.width * self.done // self.total
        bar = "#" * filled + "." * (self.width - filled)
        sys.stderr.write(f"\rmstmm: {self.label} [{bar}] {self.done}/{self.total} {dt:.1f} s")
        sys.stderr.flush()

    def close(self) -> None:
        if self._tqdm is not None:
            self._tqdm.close()
        elif self.show and self.drawn:
            sys.stderr.write("\n")
            sys.stderr.flush()


def counted(spans: Iterator[slice], total: int, label: str) -> Iterator[slice]:
    """``spans`` (slices of ``range(total)``, as :func:`mstmm.chunks.spans` gives) passed on,
    a bar counting the items of each once it is done; the bar of a long run only
    (:data:`LONG_RUN`), closed however the loop ends."""
    bar = Bar(total, label, delay=LONG_RUN)
    try:
        for at in spans:
            yield at
            bar.update(at.stop - at.start)
    finally:
        bar.close()

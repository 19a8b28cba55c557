"""The field paths that messages name: a key in a TOML table (:func:`_path`), and the
components and segments of a scene by their rows in a parameter vector (:class:`_Names`,
``attachments[2].k``; :class:`_CellNames` for a repeated scene, ``attachments[2].k (cell
7)``), formed only when a message needs one (:class:`_Paths`)."""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from .errors import _short_repr

_BARE_KEY_RE = re.compile(r"[A-Za-z0-9_-]+")


def _path(prefix: str, key: Any) -> str:
    """TOML path of ``key`` inside the table at ``prefix`` ("" for the top level)."""
    if isinstance(key, str) and _BARE_KEY_RE.fullmatch(key):
        text = key
    elif isinstance(key, str):
        text = '"' + key.encode("unicode_escape").decode("ascii").replace('"', '\\"') + '"'
    else:
        text = _short_repr(key)
    return f"{prefix}.{text}" if prefix else text


class _Names:
    """How messages name the components (by event row) and segments of a scene: the
    component in event row ``r`` is ``attachments[labels[r]]`` (default ``r``), and
    ``labels`` order them ("the later of two" is the larger label)."""

    #: The field path of a uniform beam's total length.
    length_path = "beam.length"

    def __init__(self, labels: Sequence[int] | None, n_events: int) -> None:
        self.labels = range(n_events) if labels is None else labels
        self._order: np.ndarray | None = None

    def order(self, rows: np.ndarray) -> np.ndarray:
        """The labels of event rows ``rows``, as integers that order them."""
        if self._order is None:
            self._order = np.asarray(self.labels, dtype=np.int64)
        return self._order[np.asarray(rows, dtype=np.int64)]

    def attachment(self, row: int) -> str:
        return f"attachments[{self.labels[int(row)]}]"

    def path(self, row: int, rest: str) -> str:
        return f"attachments[{self.labels[int(row)]}].{rest}"

    def segment(self, s: int, key: str) -> str:
        return f"beam.segments[{s}].{key}"


class _CellNames(_Names):
    """The names of a repeated scene's components and segments, as the file gives them:
    ``attachments[i].k (cell j)``, ``beam.segments[s].EI (cell j)``. ``cell_labels[p]`` is
    the place in the file of the cell's ``p``-th attachment by x; the event rows are
    cell-major (``perm``: the cell-major index of each row, when rounding re-sorted them)."""

    length_path = "beam.length (times repeat)"

    def __init__(self, cell_labels: Sequence[int], n_seg: int, perm: np.ndarray | None) -> None:
        self.cell_labels = np.asarray(cell_labels, dtype=np.int64)
        self.n_cell = len(cell_labels)
        self.n_seg = n_seg
        self.perm = perm

    def _cell(self, row: int) -> tuple[int, int]:
        q = int(row if self.perm is None else self.perm[row])
        return int(self.cell_labels[q % self.n_cell]), q // self.n_cell

    def order(self, rows: np.ndarray) -> np.ndarray:
        q = np.asarray(rows, dtype=np.int64)
        if self.perm is not None:
            q = self.perm[q]
        return (q // self.n_cell) * self.n_cell + self.cell_labels[q % self.n_cell]

    def attachment(self, row: int) -> str:
        i, j = self._cell(row)
        return f"attachments[{i}] (cell {j})"

    def path(self, row: int, rest: str) -> str:
        i, j = self._cell(row)
        return f"attachments[{i}].{rest} (cell {j})"

    def segment(self, s: int, key: str) -> str:
        return f"beam.segments[{s % self.n_seg}].{key} (cell {s // self.n_seg})"


def _names(labels: Sequence[int] | _Names | None, n_events: int) -> _Names:
    return labels if isinstance(labels, _Names) else _Names(labels, n_events)


class _Paths(Sequence[str]):
    """The field paths of a factor's elements, formed only when a message needs one."""

    def __init__(self, size: int, path: Callable[[int], str]) -> None:
        self.size = size
        self.path = path

    def __len__(self) -> int:
        return self.size

    def __getitem__(self, e):  # type: ignore[override]
        if isinstance(e, slice):
            return [self.path(i) for i in range(self.size)[e]]
        if not -self.size <= e < self.size:
            raise IndexError(e)
        return self.path(e % self.size)

"""The components of a scene in its parameter vectors, by kind: their event rows and the
columns of each key (vectorised over the components of one kind), for the checks of
placement and of what float64 can carry."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from mstmm import catalog


@dataclass(frozen=True)
class _KeyColumns:
    """The columns in a parameter vector of one key of the components of one kind:
    ``cols`` (every element of a list key, component by component), ``owner`` (the
    component of each column, an index into the kind's rows), ``element`` (its index in
    its list; None for a scalar key), ``start`` (each component's first column in
    ``cols``)."""

    key: catalog.Key
    cols: np.ndarray
    owner: np.ndarray
    element: np.ndarray | None
    start: np.ndarray

    @property
    def length(self) -> np.ndarray:
        """Each component's number of elements."""
        return np.diff(np.append(self.start, len(self.cols)))


@dataclass(frozen=True)
class _KindColumns:
    """The components of one kind in parameter vectors: their event ``rows`` (their
    index in the scene) and the columns of each key after x."""

    kind: str
    module: Any
    rows: np.ndarray
    keys: tuple[_KeyColumns, ...]


def _kind_columns(P: np.ndarray, kinds: Sequence[str]) -> list[_KindColumns]:
    """The components of parameter rows ``P`` (2-D, all of one scene) by kind, in the order
    of ``kinds`` (the topology's, which the tags index); vectorised over the components
    of one kind (:func:`mstmm.events.read_events` reads the same, one at a time)."""
    p = P[0]
    table = p[catalog.event_rows(p)].reshape(-1, catalog.EVENT_WIDTH)
    tags = table[:, 0].astype(np.int64)
    offsets = table[:, 2].astype(np.int64)
    out = []
    for tag, kind in enumerate(kinds):
        rows = np.flatnonzero(tags == tag)
        if not rows.size:
            continue
        module = catalog.kind(kind)
        j = offsets[rows]
        everyone = np.arange(rows.size)
        keys = []
        for key in module.KEYS[1:]:
            if key.shape == "list":
                n = p[j].astype(np.int64)
                start = np.concatenate([[0], np.cumsum(n)[:-1]]).astype(np.int64)
                owner = np.repeat(everyone, n)
                element = np.arange(int(n.sum())) - start[owner]
                keys.append(_KeyColumns(key, j[owner] + 1 + element, owner, element, start))
                j = j + 1 + n
            else:
                keys.append(_KeyColumns(key, j, everyone, None, everyone))
                j = j + 1
        out.append(_KindColumns(kind, module, rows, tuple(keys)))
    return out


def _rows_of(groups: Sequence[_KindColumns], which: Callable[[Any], bool]) -> np.ndarray:
    """The event rows, ascending, of the components whose kind's module passes ``which``."""
    rows = [g.rows for g in groups if which(g.module)]
    return np.sort(np.concatenate(rows)) if rows else np.zeros(0, np.int64)

"""Reading the components back out of parameter vectors (the layout of ``derive.catalog``).

A parameter vector holds each component as an event row ``(tag, x, offset)`` and a data
block at ``offset`` (its keys after x in declared order, a list preceded by its length).
For a scene whose attachments are sorted by x (every validated scene), the vector
:func:`mstmm.topology.parameter_vector` gives has event row ``r`` for attachment ``r``:
that is the order :func:`read_events` expects. Offsets alone cannot tell components
apart (a kind without data, a support, shares its offset with the next block), so a sweep
that moves an x reads its rows before :func:`sort_events` re-sorts them.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from mstmm import catalog

__all__ = ["Block", "Events", "read_events", "sort_events"]


@dataclass(frozen=True)
class Block:
    """One component's data block: its kind, its index in the scene (its event row) and
    the column of each key after x (a tuple of columns for a list key)."""

    kind: str
    label: int
    columns: tuple[tuple[catalog.Key, int | tuple[int, ...]], ...]


@dataclass(frozen=True)
class Events:
    """The components of parameter rows ``P`` (one vector per row), in scene order."""

    blocks: tuple[Block, ...]
    #: (rows, components): each component's x in every row, in scene order.
    positions: np.ndarray


def _table(P: np.ndarray) -> tuple[slice, np.ndarray]:
    """The event table's columns in parameter rows ``P`` (2-D) and its rows, (n, n_ev, 3)."""
    cols = catalog.event_rows(P[0])
    return cols, P[:, cols].reshape(len(P), -1, catalog.EVENT_WIDTH)


def read_events(P: np.ndarray, kinds: Sequence[str]) -> Events:
    """The components of parameter rows ``P`` (2-D, all of one scene, event row ``r``
    holding attachment ``r``); ``kinds`` are the topology's sorted kinds, which the
    tags index."""
    _, table = _table(P)
    blocks = []
    for label, (tag, _, offset) in enumerate(table[0]):
        kind = kinds[int(tag)]
        j = int(offset)
        columns: list[tuple[catalog.Key, int | tuple[int, ...]]] = []
        for key in catalog.kind(kind).KEYS[1:]:
            if key.shape == "list":
                n = int(P[0, j])
                columns.append((key, tuple(range(j + 1, j + 1 + n))))
                j += 1 + n
            else:
                columns.append((key, j))
                j += 1
        blocks.append(Block(kind, label, tuple(columns)))
    return Events(tuple(blocks), table[:, :, 1])


def sort_events(P: np.ndarray) -> None:
    """Re-sort the event rows of every parameter row by x (stable), in place; each row's
    tag and offset travel with it."""
    cols, table = _table(P)
    order = np.argsort(table[:, :, 1], axis=1, kind="stable")
    P[:, cols] = np.take_along_axis(table, order[:, :, None], axis=1).reshape(len(P), -1)

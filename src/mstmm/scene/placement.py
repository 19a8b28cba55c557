"""Where components may sit: no redundant constraint (at an end that fixes Y, or two at one
x), no two hinges at one x, nothing acting on the rotation at exactly a hinge; read from
the kinds' declarations, vectorised over the components.

``scene`` is a :class:`~mstmm.scene.Scene`, read as data (unannotated, as
:func:`mstmm.topology.topology_of` takes it): a scene is built a layer above."""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from mstmm import catalog

from ..topology import topology_of
from .columns import _kind_columns, _rows_of
from .errors import SceneError
from .paths import _Names, _names


def _fixes_y(end: str) -> bool:
    return 0 in catalog.KNOWN_ZERO[end]


def _acts_on_rotation(key: catalog.Key) -> bool:
    return key.unit in ("N m/rad", "kg m^2")


#: The one message of every redundant constraint (a second fix of Y at one point: the
#: damped chain is singular there). A spring where its motion is already fixed is no
#: constraint: accepted, it changes nothing.
_REDUNDANT = (
    "a {kind} where {why} already fixes Y is a redundant constraint (refused: it changes"
    " nothing, and leaves the damped chain singular); leave it out"
)


def check_placement(
    P: np.ndarray,
    source: str,
    scene,
    point: str = "",
    labels: Sequence[int] | _Names | None = None,
) -> None:
    """Reject components placed where the transfer chain is degenerate or ambiguous.

    ``P`` holds parameter vectors of ``scene`` (one per row). Read from the kinds'
    declarations, for any kind: a constraint (``CONSTRAINS``, which fixes Y)
    at an end whose condition already fixes Y, or two constraints at one x, fix
    nothing more and leave the chain singular; a component acting on the rotation
    (a key in N m/rad or kg m^2 with a value > 0) at exactly the x of a hinge
    (``RELEASES``) is ambiguous, since the two sides of the hinge rotate apart.
    Raises :class:`SceneError` on ``attachments[i].x``; ``P``, ``point`` and ``labels``
    as for :func:`check_representable`. Vectorised: the cost grows as n log n with the
    number of components.
    """
    P = np.atleast_2d(np.asarray(P, dtype=float))
    if not scene.attachments:
        return
    names = _names(labels, len(scene.attachments))
    groups = _kind_columns(P, topology_of(scene).kinds)
    where = (lambda row: f"at {point} {row}, ") if point else (lambda row: "")
    kind_of = np.empty(len(scene.attachments), dtype=object)
    for g in groups:
        kind_of[g.rows] = g.kind
    ev = catalog.event_rows(P[0])
    x = P[:, ev][:, 1 :: catalog.EVENT_WIDTH]

    constraints = _rows_of(groups, lambda m: "Y" in catalog.constrained(m))
    if constraints.size:
        xc = x[:, constraints]
        ends = (scene.beam.left, scene.beam.right)
        hits = [
            (xc == at).any(axis=0) if _fixes_y(end) else np.zeros(constraints.size, bool)
            for end, at in zip(ends, (0.0, P[:, [0]]))
        ]
        hit = hits[0] | hits[1]
        if hit.any():
            c = int(np.argmax(hit))
            side = 0 if hits[0][c] else 1
            at_end = xc[:, c] == (0.0 if side == 0 else P[:, 0])
            row = int(np.argmax(at_end))
            why = f"the {ends[side]} end"
            raise SceneError(
                source,
                names.path(constraints[c], "x"),
                f"{where(row)}{_REDUNDANT.format(kind=kind_of[constraints[c]], why=why)}",
                float(xc[row, c]),
            )
    if constraints.size > 1:
        _no_coincidence(
            x,
            constraints,
            None,
            np.ones((len(P), constraints.size), bool),
            names,
            lambda other: _REDUNDANT.format(
                kind="constraint", why=f"the {other} constraint at the same x"
            ),
            source,
            where,
        )
    hinges = _rows_of(groups, lambda m: catalog.count_rule(m) == "split")
    if hinges.size > 1:
        _no_coincidence(
            x,
            hinges,
            None,
            np.ones((len(P), hinges.size), bool),
            names,
            lambda other: (
                f"at the same x as the hinge {other}: two hinges at one point"
                " are one hinge (give one, with the stiffness of the two in series)"
            ),
            source,
            where,
        )
    turning = [
        g
        for g in groups
        if catalog.count_rule(g.module) != "split"
        and any(_acts_on_rotation(k) for k in g.module.KEYS)
    ]
    if hinges.size and turning:
        active_all = np.zeros((len(P), len(scene.attachments)), bool)
        for g in turning:
            for kc in g.keys:
                if _acts_on_rotation(kc.key):
                    positive = P[:, kc.cols] > 0.0
                    if kc.element is not None:
                        positive = np.logical_or.reduceat(positive, kc.start, axis=1)
                    active_all[:, g.rows] |= positive
        rows = np.sort(np.concatenate([g.rows for g in turning]))
        _no_coincidence(
            x,
            rows,
            hinges,
            active_all[:, rows],
            names,
            lambda other: (
                f"at exactly the x of the hinge {other}: which side of"
                f" the hinge it acts on is ambiguous; move it off the hinge"
            ),
            source,
            where,
        )


def _no_coincidence(
    x_all: np.ndarray,
    rows_a: np.ndarray,
    rows_b: np.ndarray | None,
    active: np.ndarray,
    names: _Names,
    problem: Callable[[str], str],
    source: str,
    where: Callable[[int], str],
) -> None:
    """Raise on the first row where an active component of event rows ``rows_a`` sits at
    the x of a component of ``rows_b`` (``x_all``: every component's x in each row;
    ``problem`` takes the other's name). ``rows_b`` None: ``rows_a`` against itself, and
    the later of two at one x (the larger label) is named. Sorted per row, so the cost
    grows as n log n with the number of components, not n^2."""
    n_a = rows_a.size
    if rows_b is None:
        rows, active_all = rows_a, active
        is_b = np.zeros(n_a, bool)
    else:
        rows = np.concatenate([rows_a, rows_b])
        active_all = np.concatenate([active, np.zeros((len(x_all), rows_b.size), bool)], axis=1)
        is_b = np.arange(rows.size) >= n_a
    x = x_all[:, rows]
    label = names.order(rows)
    # per row: by x, then the b's first, then by label
    rank = np.lexsort((np.broadcast_to(label, x.shape), np.broadcast_to(~is_b, x.shape), x))
    xs = np.take_along_axis(x, rank, axis=1)
    starts = np.ones(xs.shape, bool)
    starts[:, 1:] = xs[:, 1:] != xs[:, :-1]
    first = np.maximum.accumulate(np.where(starts, np.arange(xs.shape[1]), 0), axis=1)
    head = np.take_along_axis(rank, first, axis=1)  # column of the first of each run
    conflict = np.take_along_axis(active_all, rank, axis=1) & ~starts
    if rows_b is not None:
        conflict &= is_b[head]
    if not conflict.any():
        return
    row = int(np.argmax(conflict.any(axis=1)))
    named = label[rank[row]]
    i = int(np.argmin(np.where(conflict[row], named, np.iinfo(np.int64).max)))
    raise SceneError(
        source,
        names.path(rows[rank[row, i]], "x"),
        where(row) + problem(names.attachment(rows[head[row, i]])),
        float(xs[row, i]),
    )

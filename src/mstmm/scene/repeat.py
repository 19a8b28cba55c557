"""Finite periodic structures: ``repeat = N`` cells of one cell's beam and attachments, and
graded values (``{linear = [first, last]}``, ``{each = [...]}``); the scene built is the
expanded one, its parameter vector tiled from the cell's."""

from __future__ import annotations

import dataclasses
import gc
import itertools
import math
import numbers
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from mstmm import catalog

from ..topology import field_index, parameter_vector, topology_of
from .attachments import (
    Attachment,
    Value,
    _attachment,
    _attachment_list,
    _gradable,
    attachment_types,
)
from .errors import SceneError, _plain
from .fields import CHECKS, _choice, _number, _reject_unknown, _require, _table
from .model import Scene
from .paths import _CellNames
from .placement import check_placement
from .representable import check_representable
from .segments import Beam, _beam

#: Most cells ``repeat`` may ask for.
REPEAT_MAX = 10_000_000
#: The keys of a grading table (``k = {linear = [first, last]}``, ``{each = [...]}``).
_GRADINGS: tuple[str, ...] = ("linear", "each")


def _repeat(value: Any, source: str) -> int:
    if (
        isinstance(value, bool)
        or not isinstance(value, numbers.Integral)
        or not 1 <= value <= REPEAT_MAX
    ):
        raise SceneError(
            source,
            "repeat",
            f"must be an integer from 1 to {REPEAT_MAX} (a TOML integer: the number of cells)",
            value,
        )
    return int(value)


def _repeated(data: Mapping[str, Any], name: str, n: int, source: str) -> Scene:
    """The scene of ``n`` cells that ``data`` describes one of (``repeat = n``), expanded.

    The cell's beam and attachments are validated once, each graded value is checked, and
    the expanded attachments and parameter vector are built from the cell directly (not
    through :func:`_attachment` and :func:`mstmm.catalog.layout` per cell); placement and
    what float64 can carry are checked on the whole structure, vectorised."""
    if "beam" not in data:
        raise SceneError(source, "beam", "missing")
    cell_beam = _beam(data["beam"], source)
    read = [
        _cell_attachment(item, f"attachments[{i}]", cell_beam, n, source)
        for i, item in enumerate(_attachment_list(data, source))
    ]
    order = sorted(range(len(read)), key=lambda i: read[i][0].x)  # stable
    cell_attachments = tuple(read[i][0] for i in order)
    grades = [read[i][1] for i in order]
    cell = Scene(name=name, beam=cell_beam, attachments=cell_attachments, source=source)

    length = cell_beam.length
    if cell_beam.segments:
        segments = cell_beam.segments * n
        total = float(sum(s.length for s in segments))  # as _beam forms it
        if not math.isfinite(total):
            raise SceneError(
                source, "beam.segments", f"the total length of {n} cells must be finite", total
            )
        beam = dataclasses.replace(cell_beam, length=total, segments=segments)
    else:
        total = n * length
        if not math.isfinite(total):
            raise SceneError(
                source,
                "beam.length",
                f"the total length of {n} cells (repeat * length) must be finite",
                length,
            )
        beam = dataclasses.replace(cell_beam, length=total)

    n_cell = len(cell_attachments)
    offsets = np.arange(n, dtype=np.float64) * length  # j * length, as Python forms it
    # (cell, attachment): cell-major, each cell sorted by x
    x = np.add.outer(offsets, np.array([a.x for a in cell_attachments], dtype=np.float64))
    for p, a in enumerate(cell_attachments):  # rounding must keep the last cell on the beam
        passes, problem = CHECKS[catalog.kind(a.kind).KEYS[0].check]
        bad = ~passes(x[:, p], total)
        if bad.any():
            j = int(np.argmax(bad))
            raise SceneError(
                source,
                f"attachments[{order[p]}].x (cell {j})",
                problem.format(length=_plain(total))
                + " (x + cell * cell length, rounded): move it off the cell's end",
                float(x[j, p]),
            )
    x = x.ravel()
    # the explicit scene's order: by x, equal x in file order (cell by cell, the place in
    # the file within a cell); cell-major is that order unless rounding made a cell's x
    # equal to (or past) the next one's
    file_order = (
        np.arange(n)[:, None] * n_cell + np.asarray(order, dtype=np.int64)[None, :]
    ).ravel()
    sorted_ = bool(
        np.all((x[1:] > x[:-1]) | ((x[1:] == x[:-1]) & (file_order[1:] > file_order[:-1])))
    )

    was_enabled = gc.isenabled()
    gc.disable()  # a cycle collection per few hundred new objects would double the cost
    try:
        kinds = [a.kind for a in cell_attachments]
        per_cell = [_cell_values(a, g, n) for a, g in zip(cell_attachments, grades)]
        xs = x.tolist()
        attachments = [
            Attachment(kinds[p], xs[j * n_cell + p], per_cell[p][j])
            for j in range(n)
            for p in range(n_cell)
        ]
    finally:
        if was_enabled:
            gc.enable()
    perm = None
    if not sorted_:
        perm = np.lexsort((file_order, x))
        attachments = [attachments[k] for k in perm]
    scene = Scene(
        name=name,
        beam=beam,
        attachments=tuple(attachments),
        source=source,
        repeat=n,
        cell=cell,
        graded=any(grades),
    )
    # the topology of the whole: the cell's kinds, damped if the cell is or a graded
    # damping value is not zero anywhere (topology_of would read every attachment)
    damping = any(
        bool(np.any(values != 0.0))
        for a, g in zip(cell_attachments, grades)
        for key in catalog.kind(a.kind).KEYS
        if key.damping and (values := g.get(key.name)) is not None
    )
    topology = topology_of(cell)
    if damping and not topology.damped:
        topology = dataclasses.replace(topology, damped=True)
    object.__setattr__(scene, "_topology", topology)

    P = _repeated_parameters(cell, beam, x, grades, n) if perm is None else None
    if P is None:
        P = parameter_vector(scene)
    names = _CellNames(order, len(cell_beam.segments), perm)
    check_placement(P, source, scene, labels=names)
    check_representable(P, source, scene, labels=names)
    P.flags.writeable = False
    object.__setattr__(scene, "_parameters", P)  # parameter_vector returns a copy
    return scene


def _cell_values(
    a: Attachment, graded: Mapping[str, np.ndarray], n: int
) -> Sequence[tuple[tuple[str, Value], ...]]:
    """The values of attachment ``a`` in each of the ``n`` cells (one shared tuple when
    nothing is graded)."""
    if not graded:
        return [a.values] * n
    names = [key for key, _ in a.values]
    columns = [
        graded[key].tolist() if key in graded else itertools.repeat(value, n)
        for key, value in a.values
    ]
    return [tuple(zip(names, row)) for row in zip(*columns)]


def _cell_attachment(
    value: Any, prefix: str, beam: Beam, n: int, source: str
) -> tuple[Attachment, dict[str, np.ndarray]]:
    """One attachment of a repeated cell: validated at cell 0, and the values of each
    graded key in every cell (each checked)."""
    table = _table(value, prefix, source)
    kind = _choice(
        _require(table, "type", prefix, source), attachment_types(), f"{prefix}.type", source
    )
    module = catalog.kind(kind)
    _reject_unknown(table, ("type", *(key.name for key in module.KEYS)), prefix, source)
    plain = dict(table)
    graded: dict[str, np.ndarray] = {}
    for key in module.KEYS:
        raw = table.get(key.name)
        if isinstance(raw, Mapping):
            path = f"{prefix}.{key.name}"
            _gradable(key, raw, path, source)
            graded[key.name] = _grading(raw, key, path, n, beam.length, source)
            plain[key.name] = float(graded[key.name][0])
    if "x" in table:
        _cell_position(table["x"], module.KEYS[0].check, f"{prefix}.x", beam.length, source)
    return _attachment(plain, prefix, beam, source), graded


def _cell_position(value: Any, check: str, path: str, length: float, source: str) -> None:
    """With ``repeat``, x lies in one cell: ``0 <= x < length`` (``0 < x`` for a kind that
    must sit inside the beam: cell 0's x = 0 is the left end)."""
    x = _number(value, path, source)
    above = x > 0.0 if check == "interior" else x >= 0.0
    if above and x < length:
        return
    interval = "(0, cell length)" if check == "interior" else "[0, cell length)"
    if x == length:
        problem = (
            f"with repeat, x = the cell length {_plain(length)!r} is x = 0 of the next cell:"
            f" x must lie in {interval}" + ("; give x = 0" if check != "interior" else "")
        )
    else:
        problem = (
            f"with repeat, x is measured in one cell and must lie in {interval}, with cell"
            f" length {_plain(length)!r}"
        )
    raise SceneError(source, path, problem, value)


def _grading(
    raw: Mapping[str, Any], key: catalog.Key, path: str, n: int, length: float, source: str
) -> np.ndarray:
    """The ``n`` values of a graded key, each checked as the plain key would be:
    ``{linear = [first, last]}`` (cell j: ``first + (last - first) * j / (n - 1)``, the
    last cell exactly ``last``; ``n`` 1: ``first``) or ``{each = [v_0, ..., v_(n-1)]}``."""
    _reject_unknown(raw, tuple(_GRADINGS), path, source)
    if len(raw) != 1:
        raise SceneError(
            source,
            path,
            "a grading table holds one of linear = [first, last] or each = [one value per cell]",
            dict(raw),
        )
    ((how, spec),) = raw.items()
    where = f"{path}.{how}"
    if isinstance(spec, (str, bytes, Mapping)) or not isinstance(spec, (list, tuple)):
        raise SceneError(source, where, "must be a list of numbers", spec)
    if how == "linear":
        if len(spec) != 2:
            raise SceneError(source, where, "must be [first, last] (two numbers)", spec)
        first, last = (_number(v, f"{where}[{i}]", source) for i, v in enumerate(spec))
        values = np.full(n, first)
        if n > 1:
            with np.errstate(over="ignore", invalid="ignore"):
                j = np.arange(n, dtype=np.float64)
                values = first + (last - first) * j / (n - 1)
            values[-1] = last
        if not np.isfinite(values).all():
            j = int(np.argmax(~np.isfinite(values)))
            raise SceneError(
                source, f"{path} (cell {j})", "the grading gives a value that is not finite", spec
            )
    else:
        if len(spec) != n:
            raise SceneError(
                source, where, f"must hold one value per cell: {n} (repeat), not {len(spec)}", spec
            )
        values = _numbers(spec, path, source)
    passes, problem = CHECKS[key.check]
    bad = ~passes(values, length)
    if bad.any():
        j = int(np.argmax(bad))
        raise SceneError(
            source, f"{path} (cell {j})", problem.format(length=_plain(length)), float(values[j])
        )
    return values + 0.0  # + 0.0 turns -0.0 into 0.0


def _numbers(spec: Sequence[Any], path: str, source: str) -> np.ndarray:
    """The numbers of an ``each`` list as floats; the first that is no finite number is
    refused as ``path (cell j)``."""
    if all(type(v) is float or type(v) is int for v in spec):
        try:
            values = np.array(spec, dtype=np.float64)
        except OverflowError:
            pass
        else:
            if np.isfinite(values).all():
                return values
    return np.array([_number(v, f"{path} (cell {j})", source) for j, v in enumerate(spec)])


def _repeated_parameters(
    cell: Scene, beam: Beam, x: np.ndarray, grades: Sequence[Mapping[str, np.ndarray]], n: int
) -> np.ndarray:
    """The parameter vector of the ``n``-cell structure of ``cell`` (whole ``beam``,
    attachment positions ``x`` cell-major and sorted, ``grades`` the graded values of each
    of the cell's attachments), equal to :func:`mstmm.topology.parameter_vector` of the
    expanded scene, built from the cell's vector by tiling."""
    cp = parameter_vector(cell)
    fields = field_index(cell)
    n_seg_c, n_cell = int(cp[3]), int(cp[4])
    seg_start = catalog.HEAD
    ev_start = seg_start + catalog.SEGMENT_WIDTH * n_seg_c
    data_start_c = ev_start + catalog.EVENT_WIDTH * n_cell
    segments_c = cp[seg_start:ev_start].reshape(n_seg_c, catalog.SEGMENT_WIDTH)
    events_c = cp[ev_start:data_start_c].reshape(n_cell, catalog.EVENT_WIDTH)
    data_c = cp[data_start_c:]
    width = data_c.size

    if beam.segments:
        segments = np.tile(segments_c, (n, 1))
        lengths = np.tile([s.length for s in cell.beam.segments], n)
        segments[:, 0] = np.cumsum(lengths)  # sequential, as catalog.layout adds them
        segments[-1, 0] = beam.length
    else:
        segments = segments_c.copy()
        segments[0, 0] = beam.length
    n_seg, n_ev = len(segments), n * n_cell
    data_start = seg_start + catalog.SEGMENT_WIDTH * n_seg + catalog.EVENT_WIDTH * n_ev
    events = np.tile(events_c, (n, 1))
    events[:, 1] = x
    events[:, 2] = (
        data_start
        + width * np.repeat(np.arange(n), n_cell)
        + np.tile(events_c[:, 2] - data_start_c, n)
    )
    data = np.tile(data_c, n)
    for p, graded in enumerate(grades):
        for key, values in graded.items():
            data[fields[f"attachments[{p}].{key}"] - data_start_c :: width] = values
    head = np.array([beam.length, cp[1], cp[2], n_seg, n_ev], dtype=np.float64)
    head = np.concatenate([head, cp[catalog.LEFT_END : catalog.HEAD]])  # the ends
    return np.concatenate([head, segments.ravel(), events.ravel(), data])

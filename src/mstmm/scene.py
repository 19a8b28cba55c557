"""Scene files: a beam with its boundary conditions and the components it carries.

A scene is a TOML file (SI units), read as data and never evaluated::

    name = "wu_chou_1998"          # optional; default: the file stem
    [beam]
    left = "clamped"               # clamped | pinned | free | sliding
    right = "free"
    length = 1.0                   # a uniform beam: length (m), EI (N m^2) and
    EI = 63476.125002707834        # mass_per_length (kg/m), OR a stepped beam:
    mass_per_length = 15.3875      # [[beam.segments]] from the left end, each with
                                   # length, EI and mass_per_length (then none of the three here)
    kappa_GA = 2.1e9               # optional on [beam] or on each segment: Timoshenko shear
    rho_I = 0.004                  # stiffness (N) and rotary inertia per length (kg m),
    axial_force = 1e4              # axial force (N, tension positive), Winkler foundation
    foundation_k = 0.0             # (N/m^2) and Pasternak shear layer (N); all default 0
    foundation_kG = 0.0            # (kappa_GA 0: no shear deformation, Euler-Bernoulli)
    [[attachments]]                # zero or more components
    type = "spring_mass"           # any kind of mstmm.catalog.kinds()
    x = 0.1                        # m from the left end
    k = 190428.3750081235          # the kind's keys (src/mstmm/kinds/<kind>.py, KEYS)
    m = 3.0775

Every kind is read from its declared keys (``KEYS``: name, unit, check, default,
shape): there is no per-kind code here. A key of another kind is an unknown key; a
key without a default is required; a list key (an oscillator chain's ``k`` and ``m``)
is a non-empty list of numbers, and the keys a kind names in ``SAME_LENGTH`` have equal
lengths. Placement rules that hold for any kind that declares the same physics: a
constraint of Y (``CONSTRAINS``, a support) may not sit where an end or another
constraint already fixes Y (one message, "a redundant constraint"), nor two hinges at
one x; a component
that acts on the rotation (a key in N m/rad or kg m^2 with a value > 0) may not sit
at exactly the x of a hinge (``RELEASES``), whose two sides rotate apart.

A finite periodic structure (a metamaterial beam of N cells) is one cell and a count::

    repeat = 100                   # optional: N cells end to end (an integer, 1 to 10_000_000)
    [beam]                         # ONE cell (uniform or [[beam.segments]]); left and
    left = "clamped"               # right are the ends of the whole structure
    right = "free"
    length = 0.1
    EI = 63.5
    mass_per_length = 1.5
    [[attachments]]                # the attachments of ONE cell, 0 <= x < cell length
    type = "spring_mass"           # (x = cell length would be x = 0 of the next cell)
    x = 0.05
    k = {linear = [1e3, 2e3]}      # graded: cell j gets first + (last - first) j / (N - 1)
    m = {each = [0.01, 0.02, ...]} # or one value per cell (exactly N numbers)

The scene built is the expanded one, which every solver reads: a uniform beam of length
``N * length`` (or the cell's segments N times), cell ``j``'s attachments at ``x + j *
length`` (sorted by x as ever). Any scalar value of an attachment but ``x`` may be graded
(``linear``: the last cell gets exactly ``last``; one cell: ``first``); every graded value
passes the key's check (a failure names ``attachments[i].k (cell
j)``); placement and what float64 can carry are checked on the whole structure.
``Scene.repeat`` and ``Scene.cell`` (the validated cell, graded values at cell 0;
``Scene.graded`` says whether any value is graded) keep the cell; they take no part in
``==``.

Every problem found in a scene raises :class:`SceneError`, whose message is a
single line ``{source}: {field}: {problem} (got {value!r})``, where ``field`` is
the TOML path of the offending entry (``beam.EI``, ``beam.segments[1].EI``,
``attachments[2].k``, ``attachments[2].k[1]``; the index is the position in the
file, counted from 0) or ``-`` when the file as a whole is at fault.  For a
missing key there is no value and the ``(got ...)`` part is left out.

This module only reads; it writes nothing anywhere.
"""

from __future__ import annotations

import dataclasses
import difflib
import gc
import itertools
import math
import numbers
import os
import re
import tomllib
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from mstmm import catalog

from .plain import plain as _plain
from .topology import field_index, parameter_vector, topology_of

__all__ = [
    "ATTACHMENT_TYPES",  # noqa: F822 (module __getattr__: read from the registry)
    "BOUNDARY_KINDS",
    "Attachment",
    "Beam",
    "Scene",
    "SceneError",
    "Segment",
    "SpringMass",
    "attachment_types",
    "check_band",
    "check_placement",
    "check_representable",
    "load_scene",
    "scene_from_dict",
    "scene_to_dict",
]

BOUNDARY_KINDS: tuple[str, ...] = ("clamped", "pinned", "free", "sliding")


def attachment_types() -> tuple[str, ...]:
    """The component kinds a scene may use: built-in and registered, read now."""
    return tuple(catalog.kinds())


def __getattr__(name: str) -> Any:
    # ATTACHMENT_TYPES is read from the kind registry when asked for, so a kind
    # registered after this module was imported is listed (PEP 562).
    if name == "ATTACHMENT_TYPES":
        return attachment_types()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


_TOP_KEYS: tuple[str, ...] = ("name", "repeat", "beam", "attachments")
#: Most cells ``repeat`` may ask for.
REPEAT_MAX = 10_000_000
#: The keys of a grading table (``k = {linear = [first, last]}``, ``{each = [...]}``).
_GRADINGS: tuple[str, ...] = ("linear", "each")
_UNIFORM_KEYS: tuple[str, ...] = ("length", "EI", "mass_per_length")
#: Optional keys of a uniform beam or of a segment: its loss factor and its beam physics
#: beyond Euler-Bernoulli (``catalog.SEGMENT_PHYSICS``), each with its check.
_OPTIONAL_KEYS: dict[str, str] = {
    "loss_factor": "nonnegative",
    **{key: check for key, check, _ in catalog.SEGMENT_PHYSICS},
}
_BEAM_KEYS: tuple[str, ...] = (*_UNIFORM_KEYS, *_OPTIONAL_KEYS, "left", "right", "segments")

_NAME_RE = re.compile(r"[A-Za-z0-9_.-]+")
_NAME_MAX = 128
_REPR_MAX = 80
_BARE_KEY_RE = re.compile(r"[A-Za-z0-9_-]+")
_TOML_LINE_RE = re.compile(r"at line (\d+)")
_DICT_SOURCE = "<dict>"


class _NoValue:
    """Marker for an error that has no offending value (a missing key)."""

    def __repr__(self) -> str:
        return "<no value>"


_NO_VALUE: Any = _NoValue()


def _one_line(text: str) -> str:
    return " ".join(part for part in str(text).splitlines() if part) or "?"


def _short_repr(value: Any) -> str:
    if isinstance(value, os.PathLike):  # a path is shown whole: its end names the file
        return _one_line(repr(os.fspath(value)))
    try:
        text = repr(_plain(value))
    except Exception:  # a broken __repr__ must not hide the real error
        text = f"<{type(value).__name__}>"
    text = _one_line(text)
    if len(text) > _REPR_MAX:
        text = text[: _REPR_MAX - 3] + "..."
    return text


class SceneError(ValueError):
    """One-line, user-facing message naming the file, the field and the value.

    The message is ``{source}: {field}: {problem} (got {value!r})``; the
    ``(got ...)`` part is absent when there is no value (a missing key).  The
    parts are kept as the attributes ``source``, ``field``, ``problem`` and
    ``value`` (``has_value`` tells whether ``value`` is meaningful).
    """

    def __init__(self, source: str, field: str, problem: str, value: Any = _NO_VALUE) -> None:
        self.source = source
        self.field = field
        self.problem = problem
        self.has_value = value is not _NO_VALUE
        self.value = value if self.has_value else None
        message = f"{source}: {field}: {problem}"
        if self.has_value:
            message += f" (got {_short_repr(value)})"
        super().__init__(_one_line(message))

    def __reduce__(self) -> tuple[Any, ...]:
        args: tuple[Any, ...] = (self.source, self.field, self.problem)
        if self.has_value:
            args += (self.value,)
        return (type(self), args)


@dataclass(frozen=True)
class Segment:
    """One piece of a stepped beam (SI): its length, bending stiffness, mass per length,
    loss factor (hysteretic damping, ``EI -> EI (1 + i eta)``; 0: none), and its physics
    beyond Euler-Bernoulli (``catalog.SEGMENT_PHYSICS``; 0: none): the Timoshenko shear
    stiffness ``kappa_GA`` (N; 0: no shear deformation) and rotary inertia per length
    ``rho_I`` (kg m), the ``axial_force`` (N, tension positive), a Winkler foundation
    ``foundation_k`` (N/m^2) and a Pasternak shear layer ``foundation_kG`` (N)."""

    length: float
    EI: float
    mass_per_length: float
    loss_factor: float = 0.0
    kappa_GA: float = 0.0
    rho_I: float = 0.0
    axial_force: float = 0.0
    foundation_k: float = 0.0
    foundation_kG: float = 0.0


@dataclass(frozen=True)
class Beam:
    """Euler-Bernoulli beam: SI values and the two boundary kinds.

    ``length`` is the total length; ``EI`` and ``mass_per_length`` are those of a
    uniform beam, or of the first segment of a stepped beam. ``segments`` lists a
    stepped beam's pieces from the left end, and is empty for a uniform beam.
    ``loss_factor`` is a uniform beam's hysteretic damping ``eta`` (``EI -> EI (1 + i
    eta)``, a frequency-domain model; a stepped beam gives it per segment), and so are
    the physics keys of a uniform beam (:class:`Segment`).
    """

    length: float
    EI: float
    mass_per_length: float
    left: str
    right: str
    segments: tuple[Segment, ...] = ()
    loss_factor: float = 0.0
    kappa_GA: float = 0.0
    rho_I: float = 0.0
    axial_force: float = 0.0
    foundation_k: float = 0.0
    foundation_kG: float = 0.0


Value = float | tuple[float, ...]


@dataclass(frozen=True)
class Attachment:
    """A component on the beam: its kind (``catalog.kinds()``), position ``x`` (m) and
    its other values in the order of the kind's ``KEYS`` (defaults filled in; a list
    key as a tuple). The values read as attributes: ``a.k``, ``a.m``, ``a.J``."""

    kind: str
    x: float
    values: tuple[tuple[str, Value], ...] = ()

    def __getattr__(self, name: str) -> Value:
        # Only called when ordinary lookup fails; reads __dict__ directly so that
        # copying and unpickling (which probe a half-built object) never recurse.
        kind = self.__dict__.get("kind", "?")
        if not name.startswith("__"):
            values = self.__dict__.get("values", ())
            for key, value in values:
                if key == name:
                    return value
            default = _absent_default(kind, name, values)
            if default is not None:
                return default
        raise AttributeError(f"a {kind} attachment has no value {name!r}")


def _absent_default(kind: str, name: str, values) -> Value | None:
    """The value of a damping key the scene left out: its default (a list key's repeated
    to the length of the kind's first list), or None when ``name`` is no such key."""
    try:
        module = catalog.kind(kind)
    except ValueError:
        return None
    for key in module.KEYS:
        if key.name == name and key.damping and key.default is not None:
            if key.shape != "list":
                return key.default
            first = getattr(module, "SAME_LENGTH", (None,))[0]
            n = next((len(v) for k, v in values if k == first), 1)
            return (key.default,) * n
    return None


def SpringMass(x: float, k: float, m: float) -> Attachment:  # noqa: N802 (the old class name)
    """Point mass ``m`` (kg) hung from the beam at ``x`` (m) by a linear spring ``k`` (N/m)."""
    return Attachment("spring_mass", x, (("k", k), ("m", m)))


@dataclass(frozen=True)
class Scene:
    """A validated scene.

    ``attachments`` are sorted by ``x`` (a stable sort: equal ``x`` keep the
    file order).  ``source`` is the file the scene was read from, or
    ``"<dict>"``; it only labels error messages and takes no part in ``==``.
    Build scenes with :func:`load_scene`, :func:`scene_from_dict` or
    :meth:`Scene.replace`, which validate; the constructor does not. A scene read with
    ``repeat`` is the expanded structure; ``repeat``, ``cell`` and ``graded`` keep its
    cell and take no part in ``==`` (the content decides).
    """

    name: str
    beam: Beam
    attachments: tuple[Attachment, ...]
    source: str = field(default=_DICT_SOURCE, compare=False)
    #: The number of cells of a scene read with ``repeat`` (1 otherwise).
    repeat: int = field(default=1, compare=False)
    #: The validated cell of a scene read with ``repeat`` (its beam, its attachments
    #: sorted by x, graded values at cell 0), else None. Its values passed their keys'
    #: checks; placement and float64 range were checked on the whole structure.
    cell: Scene | None = field(default=None, compare=False, repr=False)
    #: Whether a value of the cell is graded (differs from cell to cell).
    graded: bool = field(default=False, compare=False)

    def replace(self, **changes: Any) -> Scene:
        """Return a copy with ``changes`` applied (as ``dataclasses.replace``), re-validated.

        ``beam`` may be given as a :class:`Beam` or as a ``[beam]`` mapping;
        ``attachments`` as any sequence of :class:`Attachment` or attachment
        mappings; they are sorted again.  A repeated scene gives its expanded form
        (explicit attachments, no ``cell``).  Raises :class:`SceneError`.
        """
        new = dataclasses.replace(self, **changes)
        return scene_from_dict(_loose_dict(new), source=new.source)


# ---------------------------------------------------------------------------
# Reading


def load_scene(path: str | os.PathLike[str]) -> Scene:
    """Read and validate the scene file at ``path``.  Raises :class:`SceneError`."""
    source = os.fsdecode(path)
    try:
        with open(path, "rb") as fh:
            raw = fh.read()
    except FileNotFoundError:
        raise SceneError(source, "-", "file not found", source) from None
    except IsADirectoryError:
        raise SceneError(source, "-", "is a directory, not a file", source) from None
    except OSError as exc:
        reason = exc.strerror or str(exc) or type(exc).__name__
        raise SceneError(source, "-", f"cannot read file: {reason}", source) from None
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise SceneError(
            source,
            "-",
            f"not UTF-8 text ({exc.reason} at byte {exc.start})",
            raw[exc.start : exc.start + 8],
        ) from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        message = _one_line(str(exc))
        value: Any = _NO_VALUE
        match = _TOML_LINE_RE.search(message)
        if match:
            lines = text.split("\n")
            lineno = int(match.group(1))
            if 1 <= lineno <= len(lines):
                value = lines[lineno - 1].rstrip("\r")
        raise SceneError(source, "-", f"malformed TOML: {message}", value) from None
    return scene_from_dict(data, source=source)


def scene_from_dict(data: Mapping[str, Any], source: str = _DICT_SOURCE) -> Scene:
    """Validate ``data`` (the parsed TOML document) and build a :class:`Scene`.

    ``source`` names the origin in error messages and, when ``data`` has no
    ``name``, gives the default name (the file stem).  Raises :class:`SceneError`.
    """
    source = _one_line(source)
    if not isinstance(data, Mapping):
        raise SceneError(source, "-", "the scene must be a table", data)
    _reject_unknown(data, _TOP_KEYS, "", source)

    if "name" in data:
        name = _name(data["name"], source)
    else:
        name = _default_name(source)

    if "repeat" in data:
        return _repeated(data, name, _repeat(data["repeat"], source), source)
    if "beam" not in data:
        raise SceneError(source, "beam", "missing")
    beam = _beam(data["beam"], source)

    attachments = [
        _attachment(item, f"attachments[{i}]", beam, source)
        for i, item in enumerate(_attachment_list(data, source))
    ]
    in_file = {id(a): i for i, a in enumerate(attachments)}  # messages name the file's index
    attachments.sort(key=lambda a: a.x)  # list.sort is stable
    scene = Scene(name=name, beam=beam, attachments=tuple(attachments), source=source)
    P = parameter_vector(scene)
    labels = [in_file[id(a)] for a in attachments]
    check_placement(P, source, scene, labels=labels)
    check_representable(P, source, scene, labels=labels)
    return scene


def _attachment_list(data: Mapping[str, Any], source: str) -> Sequence[Any]:
    raw = data.get("attachments", [])
    if isinstance(raw, (str, bytes, Mapping)) or not isinstance(raw, (list, tuple)):
        raise SceneError(source, "attachments", "must be an array of tables ([[attachments]])", raw)
    return raw


# ---------------------------------------------------------------------------
# Finite periodic structures: repeat = N cells, graded values


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


def _gradable(key: catalog.Key, raw: Any, path: str, source: str) -> None:
    """Refuse a grading table on a key that takes none (a position, a list)."""
    if key.name == "x":
        raise SceneError(
            source,
            path,
            "a position is not graded: with repeat, x is the place in every cell",
            raw,
        )
    if key.shape == "list":
        raise SceneError(
            source,
            path,
            "a list value is not graded (a grading table gives one number per cell)",
            raw,
        )


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
    return np.concatenate([head, segments.ravel(), events.ravel(), data])


def scene_to_dict(scene: Scene) -> dict[str, Any]:
    """Return the plain-data form of ``scene``; ``scene_from_dict`` inverts it.

    The result holds only str, float, list and dict, in the key order of the
    file format, so it can also be written out as TOML. A uniform beam gives
    ``length``, ``EI`` and ``mass_per_length``; a stepped beam its ``segments``.
    """
    return {
        "name": scene.name,
        "beam": _beam_dict(scene.beam),
        "attachments": [_attachment_dict(a) for a in scene.attachments],
    }


def _beam_dict(beam: Beam) -> dict[str, Any]:
    if not beam.segments:
        out = {"length": beam.length, "EI": beam.EI, "mass_per_length": beam.mass_per_length}
        return out | _optional_dict(beam) | {"left": beam.left, "right": beam.right}
    return {
        "left": beam.left,
        "right": beam.right,
        "segments": [_segment_dict(s) if isinstance(s, Segment) else s for s in beam.segments],
    }


def _segment_dict(s: Segment) -> dict[str, Any]:
    out = {"length": s.length, "EI": s.EI, "mass_per_length": s.mass_per_length}
    return out | _optional_dict(s)


def _optional_dict(s: Segment | Beam) -> dict[str, float]:
    """The optional keys of a uniform beam or a segment that are set (nonzero)."""
    return {key: getattr(s, key) for key in _OPTIONAL_KEYS if getattr(s, key, 0.0)}


def _attachment_dict(a: Attachment) -> dict[str, Any]:
    data: dict[str, Any] = {"type": a.kind, "x": a.x}
    for key, value in a.values:
        data[key] = list(value) if isinstance(value, tuple) else value
    return data


# ---------------------------------------------------------------------------
# Where components may sit


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


def check_placement(
    P: np.ndarray,
    source: str,
    scene: Scene,
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


# ---------------------------------------------------------------------------
# What float64 arithmetic can carry

#: Every value a scene gives, and every product the numerics form from them (the
#: frequency scale, the nondimensional value of each key, ...), must lie within
#: [REPRESENTABLE_MIN, REPRESENTABLE_MAX] (zero is allowed where a key allows it).
#: float64 is normal from 2.2e-308 to 1.8e308; the margin of 58 decades leaves room
#: for the powers of lam L up to the 4th that the root search forms on top of these.
REPRESENTABLE_MIN = 1e-250
REPRESENTABLE_MAX = 1e250
_LOG_MIN, _LOG_MAX = math.log10(REPRESENTABLE_MIN), math.log10(REPRESENTABLE_MAX)
#: The largest loss factor a beam or a segment may have (``PHYSICS_LIMITS``).
LOSS_FACTOR_MAX = 1e4

#: Products of the beam's parameters that the kernels and mode shapes form, as
#: exponents of (length, EI, mass_per_length) (the first segment's EI and mass per
#: length: the kernel's units).
_BEAM_PRODUCTS: tuple[tuple[str, tuple[int, int, int]], ...] = (
    ("length", (1, 0, 0)),
    ("EI", (0, 1, 0)),
    ("mass_per_length", (0, 0, 1)),
    ("length^4", (4, 0, 0)),
    ("EI/mass_per_length", (0, 1, -1)),
    ("the squared frequency scale EI/(mass_per_length length^4)", (-4, 1, -1)),
    ("EI/length^4", (-4, 1, 0)),
    ("mass_per_length length", (1, 0, 1)),
)
#: Stiffness and inertia units whose ratio within one component is a squared
#: frequency the numerics form (an oscillator's k/m).
_RATIOS = {"N/m": "kg", "N m/rad": "kg m^2"}
_BEAM_LABELS = ("length", "EI", "mass_per_length")


@dataclass(frozen=True)
class _Factor:
    """One factor of a product: values (rows x elements, either may be 1 to broadcast),
    the field path of each element, its name in the product and its exponent."""

    label: str
    values: np.ndarray
    paths: Sequence[str]
    exponent: float = 1
    zero_ok: bool = False

    def __pow__(self, exponent: float) -> _Factor:
        return dataclasses.replace(self, exponent=exponent)


def _product_name(factors: Sequence[_Factor]) -> str:
    def term(f: _Factor) -> str:
        e = abs(f.exponent)
        return f.label if e == 1 else f"{f.label}^{e:g}"

    top = " ".join(term(f) for f in factors if f.exponent > 0) or "1"
    bottom = [term(f) for f in factors if f.exponent < 0]
    if not bottom:
        return top
    return f"{top}/{bottom[0]}" if len(bottom) == 1 else f"{top}/({' '.join(bottom)})"


def _beam_factors(P: np.ndarray, beam: Beam, names: _Names) -> list[_Factor]:
    """The kernel's units: total length, the first segment's EI and mass per length."""
    paths = (
        ("beam.segments", names.segment(0, "EI"), names.segment(0, "mass_per_length"))
        if beam.segments
        else (names.length_path, "beam.EI", "beam.mass_per_length")
    )
    return [_Factor(n, P[:, [j]], (p,)) for j, (n, p) in enumerate(zip(_BEAM_LABELS, paths))]


def _beam_checks(
    P: np.ndarray, beam: Beam, head: Sequence[_Factor], names: _Names
) -> list[tuple[str, list[_Factor]]]:
    """The beam's values and products; for a stepped beam each segment's values and
    their ratios to the kernel's units."""
    checks = [
        (name, [f**e for f, e in zip(head, exponents) if e]) for name, exponents in _BEAM_PRODUCTS
    ]
    if beam.segments:
        n = len(beam.segments)
        rows = catalog.HEAD + catalog.SEGMENT_WIDTH * np.arange(n)
        paths = [
            _Paths(n, lambda s, k=k: names.segment(s, k))  # type: ignore[misc]
            for k in _BEAM_LABELS
        ]
        lengths = np.array([[s.length for s in beam.segments]], dtype=float)
        length = _Factor("length", lengths, paths[0])
        ei = _Factor("EI", P[:, rows + 1], paths[1])
        mu = _Factor("mass_per_length", P[:, rows + 2], paths[2])
        total = dataclasses.replace(head[0], label="(total length)")
        ei0 = dataclasses.replace(head[1], label="(first segment's EI)")
        mu0 = dataclasses.replace(head[2], label="(first segment's mass_per_length)")
        checks += [
            ("length", [length]),
            ("EI", [ei]),
            ("mass_per_length", [mu]),
            ("", [length, total**-1]),
            ("", [ei, ei0**-1]),
            ("", [mu, mu0**-1]),
            ("EI/mass_per_length", [ei, mu**-1]),
            ("", [mu, ei**-1, ei0, mu0**-1]),
        ]
    return checks


def _component_checks(
    P: np.ndarray, scene: Scene, head: Sequence[_Factor], names: _Names
) -> list[tuple[str, list[_Factor]]]:
    """Each key's value and its dimensionless form (``Key.scale``), the scale itself, and
    each stiffness/inertia ratio within a component with its dimensionless form;
    vectorised over the components of one kind.

    Positions are left out: the numerics use them only as x/L <= 1 and as differences,
    so a tiny x rounds towards the end it is next to, which is what it means."""
    checks: list[tuple[str, list[_Factor]]] = []

    def scaled(exponents) -> list[_Factor]:
        return [h ** float(e) for h, e in zip(head, exponents) if e]

    for g in _kind_columns(P, topology_of(scene).kinds):
        for kc in g.keys:
            zero_ok = kc.key.check == "nonnegative"
            f = _Factor(kc.key.name, P[:, kc.cols], _key_paths(g, kc, names), zero_ok=zero_ok)
            scale = scaled(kc.key.scale)
            checks += [(kc.key.name, [f])] + ([("", scale), ("", [f, *scale])] if scale else [])
        for stiff in g.keys:
            for inert in g.keys:
                if _RATIOS.get(stiff.key.unit) == inert.key.unit:
                    ratio = _ratio(g, stiff, inert, P, names)
                    scale = scaled([a - b for a, b in zip(stiff.key.scale, inert.key.scale)])
                    checks += [("", ratio), ("", [*ratio, *scale])] if ratio else []
    return checks


def _key_paths(g: _KindColumns, kc: _KeyColumns, names: _Names) -> _Paths:
    """The field path of each column of ``kc`` (list elements flattened)."""
    name, rows, owner, element = kc.key.name, g.rows, kc.owner, kc.element
    if element is None:
        return _Paths(len(kc.cols), lambda e: names.path(rows[owner[e]], name))
    return _Paths(len(kc.cols), lambda e: names.path(rows[owner[e]], f"{name}[{int(element[e])}]"))


def _ratio(
    g: _KindColumns, stiff: _KeyColumns, inert: _KeyColumns, P: np.ndarray, names: _Names
) -> list[_Factor]:
    """``stiff/inert`` of each component; for list keys, of each inertia with the
    stiffness on either side of it (an oscillator chain's k[j]/m[j], k[j+1]/m[j])."""
    if (stiff.element is None) != (inert.element is None):
        return []
    rows = g.rows
    if stiff.element is None:
        top, bottom = stiff.cols, inert.cols
        owner_top = owner_bottom = stiff.owner

        def top_path(e: int) -> str:
            return names.path(rows[owner_top[e]], stiff.key.name)

        def bottom_path(e: int) -> str:
            return names.path(rows[owner_bottom[e]], inert.key.name)

    else:
        # for each inertia element m[j] (component by component), k[j] then k[j + 1]
        m_flat = np.repeat(np.arange(len(inert.cols)), 2)
        owner = inert.owner[m_flat]
        j = inert.element[m_flat]  # type: ignore[index]
        i = j + np.tile([0, 1], len(inert.cols))
        keep = i < stiff.length[owner]
        m_flat, owner, j, i = m_flat[keep], owner[keep], j[keep], i[keep]
        top, bottom = stiff.cols[stiff.start[owner] + i], inert.cols[m_flat]

        def top_path(e: int) -> str:
            return names.path(rows[owner[e]], f"{stiff.key.name}[{int(i[e])}]")

        def bottom_path(e: int) -> str:
            return names.path(rows[owner[e]], f"{inert.key.name}[{int(j[e])}]")

    if not len(top):
        return []
    zero_ok = [k.key.check == "nonnegative" for k in (stiff, inert)]
    f_top = _Factor(stiff.key.name, P[:, top], _Paths(len(top), top_path), 1, zero_ok[0])
    f_bottom = _Factor(
        inert.key.name, P[:, bottom], _Paths(len(bottom), bottom_path), -1, zero_ok[1]
    )
    return [f_top, f_bottom]


def check_representable(
    P: np.ndarray,
    source: str,
    scene: Scene,
    point: str = "",
    labels: Sequence[int] | _Names | None = None,
) -> None:
    """Reject parameter vectors whose values or derived products float64 cannot carry.

    ``P`` holds parameter vectors of ``scene`` (one per row) whose event row ``r`` is
    ``scene.attachments[r]``, as :func:`mstmm.topology.parameter_vector` gives them (a
    sweep checks before it re-sorts the rows); ``scene`` gives the kinds the event tags
    index. ``labels[r]`` is the index attachment ``r`` is named by in messages (default
    ``r``; the place in the file when loading). Every
    beam and segment value, every component value but positions (zero allowed for
    nonnegative keys), each value's dimensionless form and the products the numerics
    form must lie in [:data:`REPRESENTABLE_MIN`, :data:`REPRESENTABLE_MAX`]. Raises
    :class:`SceneError` naming the field whose value is the most extreme contributor
    to the first product out of range, with that value; ``point`` (e.g. ``"point"``)
    makes the message say which row. Vectorised over the components of each kind.
    """
    P = np.atleast_2d(np.asarray(P, dtype=float))
    names = _names(labels, len(scene.attachments))
    head = _beam_factors(P, scene.beam, names)
    checks = _beam_checks(P, scene.beam, head, names)
    if scene.attachments:
        checks += _component_checks(P, scene, head, names)
    for name, factors in checks:
        _check_product(name, factors, source, point)
    _check_physics(P, scene.beam, names, source, point)


_WAVES = "beyond, the root search cannot resolve the beam's waves in a reasonable time"
_DAMPING = (
    "the most damped materials reach about 2; up to 1e4 the roots match the closed form,"
    " at 1e6 the count can no longer certify them"
)
#: The beam physics the root search can carry, beyond what float64 can: each optional key
#: of a beam or a segment (when not 0) as a dimensionless form, its exponents of (the
#: total length, the segment's EI, its mass_per_length), and the least and most it may
#: be. The cost of a search grows with the square root of each form (the pieces a walk
#: cuts a segment into to resolve its shortest wave) or stalls outright beyond these
#: (measured: minutes at 1e3 times the limit); every real beam lies far inside them.
PHYSICS_LIMITS: dict[str, tuple[str, tuple[int, int, int], float, float, str]] = {
    # a shear stiffness this soft (kappa G A over E I/L^2): waves 1e3 times slower
    # than bending ones; stiffer is fine (Euler-Bernoulli is the limit)
    "kappa_GA": ("kappa_GA length^2/EI", (2, -1, 0), 1e-6, math.inf, _WAVES),
    # (radius of gyration / length)^2: 1 is already a block, not a beam
    "rho_I": ("rho_I/(mass_per_length length^2)", (-2, 0, -1), 0.0, 1e6, _WAVES),
    # (length / the bending boundary layer sqrt(EI/|P|))^2: 1e12 is a taut string of
    # 1e6 boundary layers, or a compression 1e11 times the buckling load
    "axial_force": ("|axial_force| length^2/EI", (2, -1, 0), 0.0, 1e12, _WAVES),
    "foundation_k": ("foundation_k length^4/EI", (4, -1, 0), 0.0, 1e20, _WAVES),
    "foundation_kG": ("foundation_kG length^2/EI", (2, -1, 0), 0.0, 1e12, _WAVES),
    # hysteretic damping EI (1 + i eta): the most damped polymers reach eta ~ 2; a pinned
    # beam matches sqrt(1 + i eta) (n pi / L)^2 to 1e-10 up to eta = 1e4 (tests of damped
    # certification), at 1e6 the count no longer certifies its roots
    "loss_factor": ("loss_factor", (0, 0, 0), 0.0, LOSS_FACTOR_MAX, _DAMPING),
}


def _physics_paths(beam: Beam, names: _Names, key: str) -> _Paths:
    """The field path of ``key`` on each segment (``beam.<key>`` on a uniform beam)."""
    if beam.segments:
        return _Paths(len(beam.segments), lambda s: names.segment(s, key))
    return _Paths(1, lambda s: f"beam.{key}")


def _check_physics(P: np.ndarray, beam: Beam, names: _Names, source: str, point: str) -> None:
    """Refuse an optional key of a beam or a segment whose dimensionless form lies beyond
    :data:`PHYSICS_LIMITS` (0 means the key is off and passes), vectorised over rows."""
    n = max(1, len(beam.segments))
    rows = catalog.HEAD + catalog.SEGMENT_WIDTH * np.arange(n)
    base = (np.log10(P[:, [0]]), np.log10(P[:, rows + 1]), np.log10(P[:, rows + 2]))
    for key, (form, exponents, least, most, why) in PHYSICS_LIMITS.items():
        column = rows + 1 + catalog.SEGMENT_KEYS.index(key)
        values = np.abs(P[:, column])
        with np.errstate(divide="ignore"):
            own = np.log10(values)
            log = own + sum(e * b for e, b in zip(exponents, base) if e)
        floor = math.log10(least) if least > 0.0 else -math.inf
        for bad, problem in (
            ((own < _LOG_MIN) | (own > _LOG_MAX), _range_problem),
            ((log < floor) | (log > math.log10(most)), None),
        ):
            bad &= values != 0.0
            if not bad.any():
                continue
            row, s = (int(i) for i in np.argwhere(bad)[0])
            where = f"at {point} {row}, " if point else ""
            if problem is None:
                side = f"at least {least:g}" if log[row, s] < floor else f"at most {most:g}"
                text = f"{where}{form} is {10.0 ** log[row, s]:.3g}; it must be {side} ({why})"
            else:
                text = problem(where)
            paths = _physics_paths(beam, names, key)
            raise SceneError(source, paths[s], text, float(P[row, column[s]]))


def _range_problem(where: str) -> str:
    """What a value outside [REPRESENTABLE_MIN, REPRESENTABLE_MAX] is told."""
    return (
        f"{where}must lie in [{REPRESENTABLE_MIN:g}, {REPRESENTABLE_MAX:g}]"
        " (what float64 arithmetic can carry with room for the products formed)"
    )


def _check_product(name: str, factors: Sequence[_Factor], source: str, point: str) -> None:
    with np.errstate(divide="ignore", invalid="ignore"):
        logs = [f.exponent * np.log10(f.values) for f in factors]
        total = sum(logs[1:], logs[0])
        ok = (total >= _LOG_MIN) & (total <= _LOG_MAX)
        for f in factors:
            if f.zero_ok:
                ok = ok | (f.values == 0.0)
    if ok.all():
        return
    row, el = (int(i) for i in np.argwhere(~np.broadcast_to(ok, np.shape(total)))[0])

    def at(a: np.ndarray) -> float:
        return float(a[min(row, a.shape[0] - 1), min(el, a.shape[1] - 1)])

    size = np.nan_to_num(np.abs([at(g) for g in logs]), nan=np.inf)
    worst = factors[int(np.argmax(size))]
    where = f"at {point} {row}, " if point else ""
    value = at(np.broadcast_to(total, np.shape(total)))
    if len(factors) == 1 and factors[0].exponent == 1:
        problem = _range_problem(where)
    else:
        size_text = f"1e{value:+.0f}" if np.isfinite(value) else "0"
        problem = (
            f"{where}{name or _product_name(factors)} is about {size_text}, beyond what"
            f" float64 arithmetic can carry (every value and product must lie in"
            f" [{REPRESENTABLE_MIN:g}, {REPRESENTABLE_MAX:g}])"
        )
    path = worst.paths[min(el, len(worst.paths) - 1)]
    raise SceneError(source, path, problem, at(worst.values))


#: Most beam modes (lam L / pi) a band may span: the search evaluates the characteristic
#: function about 8 times per mode of the band.
MAX_BAND_MODES = 100_000


def _pieces(beam: Beam) -> list[tuple[float, float, float]]:
    """``(length, EI, mass_per_length)`` of each piece of the beam from the left end."""
    if beam.segments:
        return [(s.length, s.EI, s.mass_per_length) for s in beam.segments]
    return [(beam.length, beam.EI, beam.mass_per_length)]


def check_band(
    scene: Scene,
    band: tuple[float, float],
    source: str,
    option: str,
    most: int = MAX_BAND_MODES,
) -> None:
    """Reject a band (rad/s) that the numerics cannot carry or search for ``scene``.

    ``omega^2``, ``mass_per_length omega^2`` and ``(lam L)^4`` of every segment at the
    top of the band must lie below :data:`REPRESENTABLE_MAX`, and the band may span at
    most ``most`` (:data:`MAX_BAND_MODES`) beam modes (``sum of lam l / pi`` over the
    segments).
    """
    lo, hi = band
    if hi <= 0.0:
        return
    beam = scene.beam
    span = 0.0
    for length, ei, mu in _pieces(beam):
        log_mw2 = math.log10(mu) + 2.0 * math.log10(hi)
        log_beta = math.log10(beam.length) + 0.25 * (log_mw2 - math.log10(ei))
        if 2.0 * math.log10(hi) > _LOG_MAX or log_mw2 > _LOG_MAX or 4.0 * log_beta > _LOG_MAX:
            raise SceneError(
                source,
                option,
                "HI is beyond what float64 arithmetic can carry for this beam (omega^2,"
                f" mass_per_length omega^2 and (lam L)^4 must stay below {REPRESENTABLE_MAX:g})",
                [lo, hi],
            )
        scale = math.sqrt(math.sqrt(mu / ei)) * length
        span += scale * (math.sqrt(hi) - math.sqrt(lo)) / math.pi
    if span > most:
        raise SceneError(
            source,
            option,
            f"the band spans about {span:.3g} beam modes (lam L / pi); at most"
            f" {most} are searched: narrow it",
            [lo, hi],
        )


# ---------------------------------------------------------------------------
# Validation helpers


def _path(prefix: str, key: Any) -> str:
    """TOML path of ``key`` inside the table at ``prefix`` ("" for the top level)."""
    if isinstance(key, str) and _BARE_KEY_RE.fullmatch(key):
        text = key
    elif isinstance(key, str):
        text = '"' + key.encode("unicode_escape").decode("ascii").replace('"', '\\"') + '"'
    else:
        text = _short_repr(key)
    return f"{prefix}.{text}" if prefix else text


def _reject_unknown(
    table: Mapping[Any, Any], allowed: tuple[str, ...], prefix: str, source: str
) -> None:
    for key in table:
        if key not in allowed:
            raise SceneError(
                source,
                _path(prefix, key),
                "unknown key"
                + _did_you_mean(key, allowed)
                + " (allowed: "
                + ", ".join(allowed)
                + ")",
                table[key],
            )


def _did_you_mean(key: Any, allowed: Sequence[str]) -> str:
    """``; did you mean 'kappa_GA'?`` for the allowed key closest to a mistyped one (case
    aside, :func:`difflib.get_close_matches`), or "" when none is close."""
    if not isinstance(key, str):
        return ""
    lowered = {name.lower(): name for name in allowed}
    close = difflib.get_close_matches(key.lower(), list(lowered), n=1)
    return f"; did you mean {lowered[close[0]]!r}?" if close else ""


def _table(value: Any, field_path: str, source: str) -> Mapping[str, Any]:
    if not isinstance(value, Mapping):
        raise SceneError(source, field_path, "must be a table", value)
    return value


def _require(table: Mapping[str, Any], key: str, prefix: str, source: str) -> Any:
    if key not in table:
        raise SceneError(source, _path(prefix, key), "missing")
    return table[key]


def _number(value: Any, field_path: str, source: str) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise SceneError(source, field_path, "must be a number", value)
    try:
        number = float(value)
    except (OverflowError, ValueError, TypeError):
        raise SceneError(source, field_path, "must be finite", value) from None
    if not math.isfinite(number):
        raise SceneError(source, field_path, "must be finite", value)
    return number


#: A key's check: whether a value passes (for a float or an array, given the beam's
#: length) and what the message says when it does not.
CHECKS: dict[str, tuple[Callable[[Any, Any], Any], str]] = {
    "positive": (lambda v, length: v > 0.0, "must be > 0"),
    "nonnegative": (lambda v, length: v >= 0.0, "must be >= 0"),
    "finite": (lambda v, length: v == v, "must be finite"),
    "position": (
        lambda v, length: (v >= 0.0) & (v <= length),
        "must lie in [0, length] with beam length {length!r}",
    ),
    "interior": (
        lambda v, length: (v > 0.0) & (v < length),
        "must lie inside the beam, 0 < x < length, with beam length {length!r}",
    ),
}


def _checked(value: Any, check: str, field_path: str, source: str, length: float = 0.0) -> float:
    """``value`` as a float that passes ``check`` (a key of :data:`CHECKS`)."""
    number = _number(value, field_path, source)
    passes, problem = CHECKS[check]
    if not passes(number, length):
        raise SceneError(source, field_path, problem.format(length=_plain(length)), value)
    return number + 0.0  # + 0.0 turns -0.0 into 0.0


def _choice(value: Any, allowed: tuple[str, ...], field_path: str, source: str) -> str:
    if not isinstance(value, str) or value not in allowed:
        raise SceneError(
            source, field_path, "must be one of " + ", ".join(map(repr, allowed)), value
        )
    return value


def _name(value: Any, source: str) -> str:
    if (
        not isinstance(value, str)
        or not _NAME_RE.fullmatch(value)
        or len(value) > _NAME_MAX
        or set(value) == {"."}
    ):
        raise SceneError(
            source,
            "name",
            f"must be a non-empty string of at most {_NAME_MAX} letters, digits, '_', '.', '-'"
            " (and not only dots)",
            value,
        )
    return value


def _default_name(source: str) -> str:
    if source == _DICT_SOURCE:
        return "scene"
    name = re.sub(r"[^A-Za-z0-9_.-]", "_", Path(source).stem)[:_NAME_MAX]
    if not name or set(name) == {"."}:
        return "scene"
    return name


def _beam(value: Any, source: str) -> Beam:
    table = _table(value, "beam", source)
    _reject_unknown(table, _BEAM_KEYS, "beam", source)
    if "segments" in table:
        for key in (*_UNIFORM_KEYS, *_OPTIONAL_KEYS):
            if key in table:
                raise SceneError(
                    source,
                    f"beam.{key}",
                    "not with [[beam.segments]]: a stepped beam gives length, EI,"
                    f" mass_per_length and {key if key not in _UNIFORM_KEYS else 'the rest'}"
                    " per segment",
                    table[key],
                )
        segments = _segments(table["segments"], source)
        # the total as the parameter layout forms it (catalog.layout)
        length = float(sum(s.length for s in segments))
        ei, mu = segments[0].EI, segments[0].mass_per_length
        if not math.isfinite(length):
            raise SceneError(source, "beam.segments", "the total length must be finite", length)
    else:
        segments = ()
        length, ei, mu = (
            _checked(_require(table, key, "beam", source), "positive", f"beam.{key}", source)
            for key in _UNIFORM_KEYS
        )
    optional = _optional(table, "beam", source)
    left, right = (
        _choice(_require(table, key, "beam", source), BOUNDARY_KINDS, f"beam.{key}", source)
        for key in ("left", "right")
    )
    return Beam(length, ei, mu, left, right, segments, **optional)


def _optional(table: Mapping[str, Any], prefix: str, source: str) -> dict[str, float]:
    """The optional keys of a beam or a segment (default 0): its ``loss_factor`` (>= 0)
    and its physics (``catalog.SEGMENT_PHYSICS``). A segment in compression beyond its
    shear stiffness (``kappa_GA + axial_force + foundation_kG <= 0``) has no static
    equilibrium (shear buckling) and is refused here."""
    values = {
        key: _checked(table[key], check, f"{prefix}.{key}", source) if key in table else 0.0
        for key, check in _OPTIONAL_KEYS.items()
    }
    g = values["kappa_GA"] + values["axial_force"] + values["foundation_kG"]
    if values["kappa_GA"] > 0.0 and g <= 0.0:
        raise SceneError(
            source,
            f"{prefix}.axial_force",
            "a compression of kappa_GA + foundation_kG or more buckles the segment in shear"
            " (kappa_GA + axial_force + foundation_kG must be > 0)",
            values["axial_force"],
        )
    return values


def _segments(value: Any, source: str) -> tuple[Segment, ...]:
    if isinstance(value, (str, bytes, Mapping)) or not isinstance(value, (list, tuple)):
        raise SceneError(
            source, "beam.segments", "must be an array of tables ([[beam.segments]])", value
        )
    if not value:
        raise SceneError(source, "beam.segments", "must hold at least one segment", value)
    segments = []
    for s, item in enumerate(value):
        prefix = f"beam.segments[{s}]"
        table = _table(item, prefix, source)
        _reject_unknown(table, (*_UNIFORM_KEYS, *_OPTIONAL_KEYS), prefix, source)
        values = (_require(table, key, prefix, source) for key in _UNIFORM_KEYS)
        segments.append(
            Segment(
                *(
                    _checked(v, "positive", f"{prefix}.{key}", source)
                    for key, v in zip(_UNIFORM_KEYS, values)
                ),
                **_optional(table, prefix, source),
            )
        )
    return tuple(segments)


def _attachment(value: Any, prefix: str, beam: Beam, source: str) -> Attachment:
    table = _table(value, prefix, source)
    kind = _choice(
        _require(table, "type", prefix, source), attachment_types(), f"{prefix}.type", source
    )
    module = catalog.kind(kind)
    _reject_unknown(table, ("type", *(key.name for key in module.KEYS)), prefix, source)
    values: dict[str, Value] = {}
    same = getattr(module, "SAME_LENGTH", ())
    for key in module.KEYS:
        path = f"{prefix}.{key.name}"
        if key.name in table:
            raw = table[key.name]
        elif key.damping and key.default is not None:
            continue  # an absent damping value is none (Attachment reads its default)
        elif key.default is None:
            raise SceneError(source, path, "missing")
        elif key.shape == "list":  # as long as the kind's first list
            raw = [key.default] * len(values.get(same[0], ())) if same else [key.default]
        else:
            raw = key.default
        if key.shape == "list":
            if isinstance(raw, Mapping):
                _gradable(key, raw, path, source)
            if isinstance(raw, (str, bytes, Mapping)) or not isinstance(raw, (list, tuple)):
                raise SceneError(source, path, "must be a list of numbers", raw)
            if not raw:
                raise SceneError(source, path, "must be a non-empty list of numbers", raw)
            values[key.name] = tuple(
                _checked(v, key.check, f"{path}[{j}]", source, beam.length)
                for j, v in enumerate(raw)
            )
        else:
            try:
                values[key.name] = _checked(raw, key.check, path, source, beam.length)
            except SceneError:
                if isinstance(raw, Mapping):  # a grading table, read only with repeat
                    _gradable(key, raw, path, source)
                    raise SceneError(
                        source,
                        path,
                        "a grading table ({linear = [first, last]} or {each = [...]}) needs"
                        " a top-level repeat = N (the number of cells)",
                        raw,
                    ) from None
                raise
    for name in same[1:]:
        n = len(values[same[0]])  # type: ignore[arg-type]
        if name in values and len(values[name]) != n:  # type: ignore[arg-type]
            raise SceneError(
                source,
                f"{prefix}.{name}",
                f"must have as many entries as {same[0]} ({n})",
                table.get(name, values[name]),
            )
    x = values.pop("x")
    return Attachment(kind, x, tuple(values.items()))  # type: ignore[arg-type]


def _loose_dict(scene: Scene) -> dict[str, Any]:
    """Like ``scene_to_dict`` but passes through parts that are not dataclasses yet."""
    beam, attachments = scene.beam, scene.attachments
    return {
        "name": scene.name,
        "beam": _beam_dict(beam) if isinstance(beam, Beam) else beam,
        "attachments": [
            _attachment_dict(a) if isinstance(a, Attachment) else a for a in attachments
        ]
        if isinstance(attachments, (list, tuple))
        else attachments,
    }

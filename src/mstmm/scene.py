"""Scene files: a beam with its boundary conditions and its spring-mass attachments.

A scene is a TOML file (SI units), read as data and never evaluated::

    name = "wu_chou_1998"          # optional; default: the file stem
    [beam]
    length = 1.0
    EI = 63476.125002707834        # N m^2
    mass_per_length = 15.3875      # kg/m
    left = "clamped"               # clamped | pinned | free | sliding
    right = "free"
    [[attachments]]                # zero or more
    type = "spring_mass"
    x = 0.1                        # m from the left end, 0 <= x <= length
    k = 190428.3750081235          # N/m, > 0
    m = 3.0775                     # kg, > 0

Every problem found in a scene raises :class:`SceneError`, whose message is a
single line ``{source}: {field}: {problem} (got {value!r})``, where ``field`` is
the TOML path of the offending entry (``beam.EI``, ``attachments[2].k``; the
index is the position in the file, counted from 0) or ``-`` when the file as a
whole is at fault.  For a missing key there is no value and the ``(got ...)``
part is left out.

This module only reads; it writes nothing anywhere.
"""

from __future__ import annotations

import dataclasses
import math
import numbers
import os
import re
import tomllib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, ClassVar

import numpy as np

__all__ = [
    "ATTACHMENT_TYPES",
    "BOUNDARY_KINDS",
    "Beam",
    "Scene",
    "SceneError",
    "SpringMass",
    "check_band",
    "check_representable",
    "load_scene",
    "scene_from_dict",
    "scene_to_dict",
]

BOUNDARY_KINDS: tuple[str, ...] = ("clamped", "pinned", "free", "sliding")
ATTACHMENT_TYPES: tuple[str, ...] = ("spring_mass",)

_TOP_KEYS: tuple[str, ...] = ("name", "beam", "attachments")
_BEAM_KEYS: tuple[str, ...] = ("length", "EI", "mass_per_length", "left", "right")
_ATTACHMENT_KEYS: dict[str, tuple[str, ...]] = {"spring_mass": ("type", "x", "k", "m")}

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
    try:
        text = repr(value)
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
class Beam:
    """Uniform Euler-Bernoulli beam: SI values and the two boundary kinds."""

    length: float
    EI: float
    mass_per_length: float
    left: str
    right: str


@dataclass(frozen=True)
class SpringMass:
    """Point mass ``m`` hung from the beam at ``x`` by a linear spring ``k``."""

    x: float
    k: float
    m: float
    kind: ClassVar[str] = "spring_mass"


@dataclass(frozen=True)
class Scene:
    """A validated scene.

    ``attachments`` are sorted by ``x`` (a stable sort: equal ``x`` keep the
    file order).  ``source`` is the file the scene was read from, or
    ``"<dict>"``; it only labels error messages and takes no part in ``==``.
    Build scenes with :func:`load_scene`, :func:`scene_from_dict` or
    :meth:`Scene.replace`, which validate; the constructor does not.
    """

    name: str
    beam: Beam
    attachments: tuple[SpringMass, ...]
    source: str = field(default=_DICT_SOURCE, compare=False)

    def replace(self, **changes: Any) -> Scene:
        """Return a copy with ``changes`` applied (as ``dataclasses.replace``), re-validated.

        ``beam`` may be given as a :class:`Beam` or as a ``[beam]`` mapping;
        ``attachments`` as any sequence of :class:`SpringMass` or attachment
        mappings; they are sorted again.  Raises :class:`SceneError`.
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

    if "beam" not in data:
        raise SceneError(source, "beam", "missing")
    beam = _beam(data["beam"], source)

    raw_attachments = data.get("attachments", [])
    if isinstance(raw_attachments, (str, bytes, Mapping)) or not isinstance(
        raw_attachments, (list, tuple)
    ):
        raise SceneError(
            source, "attachments", "must be an array of tables ([[attachments]])", raw_attachments
        )
    attachments = [
        _attachment(item, f"attachments[{i}]", beam, source)
        for i, item in enumerate(raw_attachments)
    ]
    raw_index = {id(a): i for i, a in enumerate(attachments)}  # file position, for messages
    attachments.sort(key=lambda a: a.x)  # list.sort is stable
    check_representable(
        np.array(
            [
                [beam.length, beam.EI, beam.mass_per_length]
                + [v for a in attachments for v in (a.x, a.k, a.m)]
            ]
        ),
        source,
        [raw_index[id(a)] for a in attachments],
    )
    return Scene(name=name, beam=beam, attachments=tuple(attachments), source=source)


def scene_to_dict(scene: Scene) -> dict[str, Any]:
    """Return the plain-data form of ``scene``; ``scene_from_dict`` inverts it.

    The result holds only str, float, list and dict, in the key order of the
    file format, so it can also be written out as TOML.
    """
    beam = scene.beam
    return {
        "name": scene.name,
        "beam": {
            "length": beam.length,
            "EI": beam.EI,
            "mass_per_length": beam.mass_per_length,
            "left": beam.left,
            "right": beam.right,
        },
        "attachments": [{"type": a.kind, "x": a.x, "k": a.k, "m": a.m} for a in scene.attachments],
    }


# ---------------------------------------------------------------------------
# What float64 arithmetic can carry

#: Every value a scene gives, and every product the numerics form from them (the
#: frequency scale, the nondimensional stiffness and mass of each attachment, ...),
#: must lie within [REPRESENTABLE_MIN, REPRESENTABLE_MAX]. float64 is normal from
#: 2.2e-308 to 1.8e308; the margin of 58 decades leaves room for the powers of
#: lam L up to the 4th that the root search forms on top of these.
REPRESENTABLE_MIN = 1e-250
REPRESENTABLE_MAX = 1e250
_LOG_MIN, _LOG_MAX = math.log10(REPRESENTABLE_MIN), math.log10(REPRESENTABLE_MAX)

#: Products of the parameters that the kernels and mode shapes form, as exponents of
#: (length, EI, mass_per_length, k, m): name, exponents.
_BEAM_PRODUCTS: tuple[tuple[str, tuple[float, float, float]], ...] = (
    ("length", (1, 0, 0)),
    ("EI", (0, 1, 0)),
    ("mass_per_length", (0, 0, 1)),
    ("length^4", (4, 0, 0)),
    ("EI/mass_per_length", (0, 1, -1)),
    ("the squared frequency scale EI/(mass_per_length length^4)", (-4, 1, -1)),
    ("EI/length^4", (-4, 1, 0)),
    ("mass_per_length length", (1, 0, 1)),
)
_ATTACHMENT_PRODUCTS: tuple[tuple[str, tuple[float, float, float, float, float]], ...] = (
    ("k", (0, 0, 0, 1, 0)),
    ("m", (0, 0, 0, 0, 1)),
    ("k/m", (0, 0, 0, 1, -1)),
    ("k length^3", (3, 0, 0, 1, 0)),
    ("k length^3/EI", (3, -1, 0, 1, 0)),
    ("m/(mass_per_length length)", (-1, 0, -1, 0, 1)),
)
_BEAM_FIELDS: tuple[str, ...] = ("length", "EI", "mass_per_length")


def check_representable(
    P: np.ndarray, source: str, labels: Sequence[int] | None = None, point: str = ""
) -> None:
    """Reject parameter rows whose values or derived products float64 cannot carry.

    ``P`` holds one parameter vector per row, ``[L, EI, mbar, x1, k1, m1, ...]``
    (all > 0 except positions). ``labels`` gives the index each attachment is
    named by in messages (default: its column order). Raises :class:`SceneError`
    naming the field whose value is the most extreme contributor to the first
    product out of range, with that value; ``point`` (e.g. ``"point"``) makes the
    message say which row.
    """
    P = np.asarray(P, dtype=float)
    n_att = (P.shape[1] - 3) // 3
    labels = list(range(n_att)) if labels is None else list(labels)
    with np.errstate(divide="ignore", invalid="ignore"):
        logs = np.log10(P)
    beam_logs = logs[:, :3]
    checks = [
        (name, np.array(e, float), beam_logs, list(_BEAM_FIELDS), None)
        for name, e in _BEAM_PRODUCTS
    ]
    for j in range(n_att):
        cols = np.concatenate([beam_logs, logs[:, 4 + 3 * j : 6 + 3 * j]], axis=1)
        fields = [*_BEAM_FIELDS, "k", "m"]
        checks += [(name, np.array(e, float), cols, fields, j) for name, e in _ATTACHMENT_PRODUCTS]
    for name, exponents, cols, fields, j in checks:
        value = cols @ exponents
        bad = ~((value >= _LOG_MIN) & (value <= _LOG_MAX))
        if not bad.any():
            continue
        row = int(np.argmax(bad))
        used = np.flatnonzero(exponents)
        worst = int(used[np.argmax(np.abs(cols[row, used] * exponents[used]))])
        field_path = (
            f"beam.{fields[worst]}" if worst < 3 else f"attachments[{labels[j]}].{fields[worst]}"
        )
        column = worst if worst < 3 else 4 + 3 * j + (worst - 3)
        where = f"at {point} {row}, " if point else ""
        size = f"1e{value[row]:+.0f}" if np.isfinite(value[row]) else "0"
        problem = (
            f"{where}{name} is about {size}, beyond what float64 arithmetic can carry"
            f" (every value and product must lie in [{REPRESENTABLE_MIN:g},"
            f" {REPRESENTABLE_MAX:g}])"
        )
        if name in (*_BEAM_FIELDS, "k", "m"):
            problem = (
                f"{where}must lie in [{REPRESENTABLE_MIN:g}, {REPRESENTABLE_MAX:g}]"
                " (what float64 arithmetic can carry with room for the products formed)"
            )
        raise SceneError(source, field_path, problem, float(P[row, column]))


#: Most beam modes (lam L / pi) a band may span: the search evaluates the characteristic
#: function about 8 times per mode of the band.
MAX_BAND_MODES = 100_000


def check_band(scene: Scene, band: tuple[float, float], source: str, option: str) -> None:
    """Reject a band (rad/s) that the numerics cannot carry or search for ``scene``.

    ``omega^2``, ``mass_per_length omega^2`` and ``(lam L)^4`` at the top of the band
    must lie below :data:`REPRESENTABLE_MAX`, and the band may span at most
    :data:`MAX_BAND_MODES` beam modes (``lam L / pi``).
    """
    lo, hi = band
    if hi <= 0.0:
        return
    beam = scene.beam
    log_mw2 = math.log10(beam.mass_per_length) + 2.0 * math.log10(hi)
    log_beta = math.log10(beam.length) + 0.25 * (log_mw2 - math.log10(beam.EI))
    if 2.0 * math.log10(hi) > _LOG_MAX or log_mw2 > _LOG_MAX or 4.0 * log_beta > _LOG_MAX:
        raise SceneError(
            source,
            option,
            "HI is beyond what float64 arithmetic can carry for this beam (omega^2,"
            f" mass_per_length omega^2 and (lam L)^4 must stay below {REPRESENTABLE_MAX:g})",
            [lo, hi],
        )
    scale = math.sqrt(math.sqrt(beam.mass_per_length / beam.EI)) * beam.length
    span = scale * (math.sqrt(hi) - math.sqrt(lo)) / math.pi
    if span > MAX_BAND_MODES:
        raise SceneError(
            source,
            option,
            f"the band spans about {span:.3g} beam modes (lam L / pi); at most"
            f" {MAX_BAND_MODES} are searched: narrow it",
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
                "unknown key (allowed: " + ", ".join(allowed) + ")",
                table[key],
            )


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


def _positive(value: Any, field_path: str, source: str) -> float:
    number = _number(value, field_path, source)
    if number <= 0.0:
        raise SceneError(source, field_path, "must be > 0", value)
    return number


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
    length, ei, mu = (
        _positive(_require(table, key, "beam", source), f"beam.{key}", source)
        for key in ("length", "EI", "mass_per_length")
    )
    left, right = (
        _choice(_require(table, key, "beam", source), BOUNDARY_KINDS, f"beam.{key}", source)
        for key in ("left", "right")
    )
    return Beam(length=length, EI=ei, mass_per_length=mu, left=left, right=right)


def _attachment(value: Any, prefix: str, beam: Beam, source: str) -> SpringMass:
    table = _table(value, prefix, source)
    kind = _choice(
        _require(table, "type", prefix, source), ATTACHMENT_TYPES, f"{prefix}.type", source
    )
    _reject_unknown(table, _ATTACHMENT_KEYS[kind], prefix, source)
    raw_x = _require(table, "x", prefix, source)
    x = _number(raw_x, f"{prefix}.x", source)
    if not 0.0 <= x <= beam.length:
        raise SceneError(
            source,
            f"{prefix}.x",
            f"must lie in [0, length] with beam.length = {beam.length!r}",
            raw_x,
        )
    k = _positive(_require(table, "k", prefix, source), f"{prefix}.k", source)
    m = _positive(_require(table, "m", prefix, source), f"{prefix}.m", source)
    return SpringMass(x=x + 0.0, k=k, m=m)  # + 0.0 turns -0.0 into 0.0


def _loose_dict(scene: Scene) -> dict[str, Any]:
    """Like ``scene_to_dict`` but passes through parts that are not dataclasses yet."""
    data: dict[str, Any] = {"name": scene.name}
    beam = scene.beam
    if isinstance(beam, Beam):
        data["beam"] = {f.name: getattr(beam, f.name) for f in dataclasses.fields(Beam)}
    else:
        data["beam"] = beam
    attachments = scene.attachments
    if isinstance(attachments, (list, tuple)):
        data["attachments"] = [
            {"type": a.kind, "x": a.x, "k": a.k, "m": a.m} if isinstance(a, SpringMass) else a
            for a in attachments
        ]
    else:
        data["attachments"] = attachments
    return data

"""The components on the beam: :class:`Attachment` (a kind, a position and the kind's
values), read from an ``[[attachments]]`` table by the kind's declared keys (``KEYS``:
there is no per-kind code here), and its plain-data form."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from mstmm import catalog

from .errors import SceneError
from .fields import _checked, _choice, _reject_unknown, _require, _table
from .segments import Beam


def attachment_types() -> tuple[str, ...]:
    """The component kinds a scene may use: built-in and registered, read now."""
    return tuple(catalog.kinds())


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


def _attachment_list(data: Mapping[str, Any], source: str) -> Sequence[Any]:
    raw = data.get("attachments", [])
    if isinstance(raw, (str, bytes, Mapping)) or not isinstance(raw, (list, tuple)):
        raise SceneError(source, "attachments", "must be an array of tables ([[attachments]])", raw)
    return raw


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


def _attachment_dict(a: Attachment) -> dict[str, Any]:
    data: dict[str, Any] = {"type": a.kind, "x": a.x}
    for key, value in a.values:
        data[key] = list(value) if isinstance(value, tuple) else value
    return data

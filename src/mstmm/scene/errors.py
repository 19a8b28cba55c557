"""The one error of a scene, :class:`SceneError`, and how its message shows a value: on one
line, numpy scalars as Python numbers, cut at 80 characters (a path whole)."""

from __future__ import annotations

import os
from typing import Any

from mstmm.plain import plain as _plain

_REPR_MAX = 80


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

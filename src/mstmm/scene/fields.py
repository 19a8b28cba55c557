"""Reading one entry of a scene table: a table, a required key, no unknown key (with the
closest allowed one suggested), a finite number that passes a key's check (:data:`CHECKS`),
one of a few strings."""

from __future__ import annotations

import difflib
import math
import numbers
from collections.abc import Callable, Mapping, Sequence
from typing import Any

from .errors import SceneError, _plain
from .paths import _path


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

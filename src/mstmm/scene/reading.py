"""Reading a scene: a file (UTF-8 TOML) or a table (the parsed document), sent to the
explicit scene (:mod:`mstmm.scene.model`) or to the repeated one
(:mod:`mstmm.scene.repeat`)."""

from __future__ import annotations

import os
import re
import tomllib
from collections.abc import Mapping
from typing import Any

from .errors import _NO_VALUE, SceneError, _one_line
from .model import _DICT_SOURCE, Scene, _explicit, _head
from .repeat import _repeat, _repeated

_TOML_LINE_RE = re.compile(r"at line (\d+)")


def is_frame(data: Any) -> bool:
    """Whether a scene table describes a frame (``[[members]]``, ``[[nodes]]``: read by
    ``mstmm.frame``) rather than a beam."""
    return isinstance(data, Mapping) and ("members" in data or "nodes" in data)


def read_table(path: str | os.PathLike[str]) -> tuple[Any, str]:
    """The TOML document of the file at ``path`` and the source its messages name: a
    beam's or a frame's (``mstmm.frame.reading``). Raises :class:`SceneError` (unreadable,
    not UTF-8, malformed TOML, with the offending line)."""
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
    return data, source


def load_scene(path: str | os.PathLike[str]) -> Scene:
    """Read and validate the scene file at ``path``.  Raises :class:`SceneError`."""
    data, source = read_table(path)
    return scene_from_dict(data, source=source)


def scene_from_dict(data: Mapping[str, Any], source: str = _DICT_SOURCE) -> Scene:
    """Validate ``data`` (the parsed TOML document) and build a :class:`Scene`.

    ``source`` names the origin in error messages and, when ``data`` has no
    ``name``, gives the default name (the file stem).  Raises :class:`SceneError`.
    """
    if is_frame(data):
        raise SceneError(
            source, "members", "a frame scene: read it with mstmm.frame.load_frame"
            " (mstmm solve reads both; docs/frames.md)",
        )  # fmt: skip
    source, name = _head(data, source)
    if "repeat" in data:
        return _repeated(data, name, _repeat(data["repeat"], source), source)
    return _explicit(data, name, source)

"""The scene: :class:`Scene`, built from the table of a scene without ``repeat`` (its
name, its beam, its attachments sorted by x, placement and what float64 can carry
checked), and its plain-data form. A scene with ``repeat`` is built one layer up
(:mod:`mstmm.scene.repeat`), and :func:`mstmm.scene.scene_from_dict` sends each table to
one of the two."""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..topology import parameter_vector
from .attachments import Attachment, _attachment, _attachment_dict, _attachment_list
from .errors import SceneError, _one_line
from .fields import _reject_unknown
from .placement import check_placement
from .representable import check_representable
from .segments import Beam, _beam, _beam_dict

_TOP_KEYS: tuple[str, ...] = ("name", "repeat", "beam", "attachments")
_NAME_RE = re.compile(r"[A-Za-z0-9_.-]+")
_NAME_MAX = 128
_DICT_SOURCE = "<dict>"


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
        data = _loose_dict(new)  # no repeat: read as scene_from_dict reads it
        source, name = _head(data, new.source)
        return _explicit(data, name, source)


def _head(data: Mapping[str, Any], source: str) -> tuple[str, str]:
    """``source`` on one line and the scene's name (``name``, else the file stem), once
    ``data`` is a table of the top-level keys."""
    source = _one_line(source)
    if not isinstance(data, Mapping):
        raise SceneError(source, "-", "the scene must be a table", data)
    _reject_unknown(data, _TOP_KEYS, "", source)

    if "name" in data:
        name = _name(data["name"], source)
    else:
        name = _default_name(source)
    return source, name


def _explicit(data: Mapping[str, Any], name: str, source: str) -> Scene:
    """The scene of a table without ``repeat``: its beam and its attachments (sorted by x),
    placement and what float64 can carry checked; messages name an attachment by its place
    in the file."""
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

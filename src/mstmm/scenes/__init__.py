"""The bundled scene files, found by name from any directory."""

from __future__ import annotations

from importlib.resources import files
from pathlib import Path

__all__ = ["bundled_names", "example_path"]


def _folder() -> Path:
    return Path(str(files(__name__)))


def bundled_names() -> list[str]:
    """Names of the bundled scenes (file stems), sorted."""
    return sorted(p.stem for p in _folder().glob("*.toml"))


def example_path(name: str = "wu_chou_1998") -> Path:
    """Path of a bundled scene, by name (``wu_chou_1998``, ``bare_cantilever``).

    Works from any directory; the ``.toml`` suffix may be given or left out.
    An unknown name raises :class:`ValueError` listing the bundled names.
    """
    stem = name[: -len(".toml")] if name.endswith(".toml") else name
    names = bundled_names()
    if stem not in names:
        raise ValueError(f"no bundled scene {name!r}; the bundled scenes are: {', '.join(names)}")
    return _folder() / f"{stem}.toml"

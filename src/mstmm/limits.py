"""The largest sizes a command or an API call may ask for, each refused at once.

A request beyond one of these would not fail quickly: numpy allocates gigabytes (and dies
with MemoryError after a while) or the search runs for hours. Each is refused before any
work with one line naming the field, the limit and the value (a :class:`SceneError`, a
ValueError), the same from the command line (``--modes``, ``--points``, ``--vary``) and
from the API (``modes=``, ``points=``, the length of a ``vary`` array). The frequency
band of ``bands`` is checked as ``solve --band`` checks it
(:func:`mstmm.scene.check_band`); ``frf --points`` by
:data:`mstmm.response.MAX_RESPONSES`.
"""

from __future__ import annotations

from typing import Any

from .scene import Scene, SceneError, check_band

__all__ = [
    "MAX_BAND_POINTS",
    "MAX_CELL_MODES",
    "MAX_MODES",
    "MAX_SWEEP_POINTS",
    "check_bands_band",
    "check_command_line",
    "check_count",
]

#: Most modes one ``solve`` (``--modes``, ``modes=``) or one sweep point may ask for: as
#: many as a band may span (:data:`mstmm.scene.MAX_BAND_MODES`); every mode costs a
#: bracket, a refinement and, with shapes, a shape of some thousand points.
MAX_MODES = 100_000
#: Most points of a parameter study (``sweep --vary ...:n``, a ``vary`` array): each is a
#: solve of some milliseconds, so a million already takes an hour or more on one core.
MAX_SWEEP_POINTS = 1_000_000
#: Most frequencies of the dispersion curves of ``bands`` (``--points``, ``points=``):
#: a million points is some minutes of kernel calls and 64 MB of wavenumbers.
MAX_BAND_POINTS = 1_000_000
#: Most modes of the bare cell (lam L / pi of the cell) the band of ``bands`` may span:
#: every one holds up to two band edges, each found and certified (measured on the
#: metamaterial cell: 300 in 12 s, 950 in 100 s).
MAX_CELL_MODES = 1_000


def check_bands_band(cell: Scene, band: tuple[float, float], source: str, field: str) -> None:
    """Refuse a band (rad/s) of ``bands`` as ``solve --band`` does
    (:func:`mstmm.scene.check_band`: what float64 carries), spanning at most
    :data:`MAX_CELL_MODES` modes of the cell."""
    check_band(cell, band, source, field, most=MAX_CELL_MODES)


def check_count(value: Any, limit: int, what: str, source: str, field: str) -> None:
    """Refuse a count above ``limit`` of ``what`` (e.g. ``"modes"``): a :class:`SceneError`
    ``{source}: {field}: at most {limit} {what} ... (got {value})``. Counts that are not
    whole numbers are left to the caller's own check."""
    try:
        too_many = int(value) > limit
    except (TypeError, ValueError, OverflowError):
        return
    if too_many:
        raise SceneError(
            source,
            field,
            f"at most {limit:,} {what} in one run (a limit of mstmm: more would take"
            " hours or exhaust memory); split the work into several runs",
            value,
        )


#: The count options of each command the command line bounds here: (option, attribute,
#: limit, what). ``frf --points`` and ``plot --points`` are bounded by
#: :data:`mstmm.response.MAX_RESPONSES` (with the number of outputs).
_OPTIONS: dict[str, tuple[tuple[str, str, int, str], ...]] = {
    "solve": (("--modes", "modes", MAX_MODES, "modes"),),
    "sweep": (("--modes", "modes", MAX_MODES, "modes"),),
    "plot": (("--modes", "modes", MAX_MODES, "modes"),),
    "bands": (("--points", "points", MAX_BAND_POINTS, "frequencies"),),
}


def check_command_line(args: Any, source: str) -> None:
    """Refuse every count option of the parsed command line ``args`` above its limit, before
    any file is read."""
    for option, attribute, limit, what in _OPTIONS.get(getattr(args, "command", ""), ()):
        value = getattr(args, attribute, None)
        if value is not None:
            check_count(value, limit, what, source, option)

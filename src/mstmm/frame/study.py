"""Parameter studies of a frame: the lowest natural frequencies as fields of its scene vary.

``sweep_frame(table, vary, modes)``: ``vary`` maps a field of the frame's scene table
(``members[3].EI``, ``nodes[2].mass``, ``attachments[0].k``, ``members[1].segments[0].EA``)
to its values; the varied arrays run together (point i takes the i-th value of each), as
the beam's :func:`mstmm.study.sweep` does. Each point is the scene with those values, read
as a file would be (every value checked; a refused one names the field and the point) and
solved by the count (:func:`mstmm.frame.solve_frame`, frequencies only). A frame
with dashpots (an absorber's ``c``) or loss factors, given or varied, is a damped study:
its points' damped roots ``w_d + i sigma`` (:mod:`mstmm.frame.damped`), complex, as the
beam's damped study.
"""

from __future__ import annotations

import copy
import math
import re
from collections.abc import Mapping
from typing import Any

import numpy as np

from mstmm.limits import MAX_MODES, MAX_SWEEP_POINTS, check_count
from mstmm.scene import SceneError
from mstmm.units import BEAM_UNITS

from .api import solve_frame
from .damped import is_damped
from .reading import frame_from_dict

__all__ = ["field_unit", "sweep_frame"]

_STEP = re.compile(r"^(\w+)(?:\[(\d+)\])?$")

#: The unit of a frame scene's fields by their key (attachments: by their kind): a
#: segment's as a beam's, and the frame's own.
UNITS: dict[str, str] = {
    **BEAM_UNITS,
    "x": "m",
    "y": "m",
    "EA": "N",
    "GJ": "N m^2",
    "rho_Ip": "kg m",
    "k_x": "N/m",
    "k_y": "N/m",
    "k_z": "N/m",
    "k_t": "N m/rad",
    "mass": "kg",
    "J": "kg m^2",
    "start_k": "N m/rad",
    "end_k": "N m/rad",
    "m": "kg",
    "c": "N s/m",
}


def _steps(path: str, source: str, option: str) -> list[tuple[str, int | None]]:
    steps = []
    for part in path.split("."):
        m = _STEP.match(part)
        if m is None:
            raise SceneError(source, option, "expected a field path like members[3].EI", path)
        steps.append((m.group(1), None if m.group(2) is None else int(m.group(2))))
    return steps


def _set(table: dict, path: str, value: float, source: str, option: str) -> None:
    """``table`` at ``path`` <- value (the last key may be absent: it is then added)."""
    here: Any = table
    steps = _steps(path, source, option)
    for depth, (key, index) in enumerate(steps):
        last = depth == len(steps) - 1
        if not isinstance(here, dict) or (key not in here and not (last and index is None)):
            raise SceneError(source, option, "the scene has no such field", path)
        if index is None:
            if last:
                here[key] = value
            else:
                here = here[key]
            continue
        items = here[key]
        if not isinstance(items, list) or index >= len(items):
            raise SceneError(source, option, f"the scene has no {key}[{index}]", path)
        if last:
            items[index] = value
        else:
            here = items[index]


def field_unit(table: Mapping[str, Any], path: str) -> str:
    """The unit of a varied field (``members[3].EI``: ``N m^2``; an attachment's ``k``:
    ``N m/rad`` for a rotational spring, else ``N/m``); ``-`` when it has none."""
    key = path.rsplit(".", 1)[-1]
    m = re.match(r"attachments\[(\d+)\]\.k$", path)
    if m:
        items = table.get("attachments", [])
        index = int(m.group(1))
        rotational = index < len(items) and items[index].get("type") == "rotational_spring"
        return "N m/rad" if rotational else "N/m"
    return UNITS.get(key, "-")


def sweep_frame(
    table: Mapping[str, Any],
    vary: Mapping[str, Any],
    modes: int = 5,
    source: str = "<frame>",
) -> np.ndarray:
    """The lowest ``modes`` natural frequencies (rad/s) at every point, ``(points,
    modes)``, complex where the study is damped (a dashpot given or varied); NaN where
    the count could not confirm a point's roots."""
    check_count(modes, MAX_MODES, "modes", source, "modes")
    values = {path: np.atleast_1d(np.asarray(v, dtype=float)) for path, v in vary.items()}
    if not values:
        raise SceneError(source, "--vary", "nothing is varied", dict(vary))
    sizes = {v.shape[0] for v in values.values()}
    if len(sizes) != 1:
        raise SceneError(source, ",".join(values), "varied arrays differ in length", sorted(sizes))
    n = sizes.pop()
    for path in values:
        check_count(n, MAX_SWEEP_POINTS, "points", source, path)
        _set(copy.deepcopy(dict(table)), path, 0.0, source, f"--vary {path}")  # the path exists
    damped = is_damped(frame_from_dict(table, source))
    damped |= any(path.rsplit(".", 1)[-1] in ("c", "loss_factor") for path in values)
    out = np.full((n, modes), complex(math.nan, math.nan) if damped else math.nan)
    for i in range(n):
        point = copy.deepcopy(dict(table))
        for path, v in values.items():
            _set(point, path, float(v[i]), source, f"--vary {path}")
        try:
            frame = frame_from_dict(point, source)
            sol = solve_frame(frame, modes, shapes=False)
        except SceneError as exc:
            value = (exc.value,) if exc.has_value else ()
            raise SceneError(source, f"{exc.field} at point {i}", exc.problem, *value) from None
        if sol.count_checked:
            out[i] = sol.omega[:modes]
    return out

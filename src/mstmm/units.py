"""SI units of what mstmm writes: a sweep field's, a frequency response's, a CSV header's.

Every CSV column that carries a unit is headed ``name [unit]`` (``omega [rad/s]``,
``attachments[2].k [N/m]``, ``displacement:x=0.5_abs [m/N]``); ``[-]`` marks a
dimensionless number; counts and flags (``mode``, ``multiplicity``, ``converged``,
``propagating``) have none. :func:`split_header` reads such a header back.
"""

from __future__ import annotations

import re

from . import catalog

__all__ = ["BEAM_UNITS", "field_unit", "frf_unit", "header", "split_header"]

#: A beam's (or a segment's) fields and their units.
BEAM_UNITS: dict[str, str] = {
    "length": "m",
    "EI": "N m^2",
    "mass_per_length": "kg/m",
    "loss_factor": "-",
    **{key: unit for key, _, unit in catalog.SEGMENT_PHYSICS},
}

_ATTACHMENT = re.compile(r"attachments\[(\d+)\]\.(\w+)(?:\[\d+\])?$")
_RESPONSES = {"displacement": "m", "y": "m", "rotation": "rad", "theta": "rad"}
_LOADS = {"force": "N", "moment": "N m"}
_RATES = {"receptance": "", "mobility": "/s", "accelerance": "/s^2"}
_HEADER = re.compile(r"(.*?) \[([^\[\]]*)\]")


def field_unit(scene, path: str) -> str:
    """The unit of a sweep field ``path`` of ``scene`` (``beam.EI``: ``N m^2``,
    ``beam.segments[1].axial_force``: ``N``, ``attachments[2].k``: the unit its kind
    declares, ``attachments[i].k[j]`` of a chain: the same); ``-`` when it has none."""
    match = _ATTACHMENT.match(path)
    if match:
        index, name = int(match.group(1)), match.group(2)
        if name == "x":
            return "m"
        if index < len(scene.attachments):
            for key in catalog.kind(scene.attachments[index].kind).KEYS:
                if key.name == name:
                    return key.unit or "-"
        return "-"
    return BEAM_UNITS.get(path.rsplit(".", 1)[-1], "-")


def frf_unit(quantity: str, response: str, load: str) -> str:
    """``m/N``, ``rad/(N m)``, ``m/s/N``, ``m/s^2/N``, ... : the unit of ``quantity``
    (receptance, mobility, accelerance) of a ``response`` (displacement, rotation) to a
    unit ``load`` (force, moment)."""
    top = _RESPONSES[response] + _RATES[quantity]
    bottom = _LOADS[load]
    return f"{top}/({bottom})" if " " in bottom else f"{top}/{bottom}"


def header(name: str, unit: str | None) -> str:
    """``name [unit]`` (``name`` alone when ``unit`` is None)."""
    return name if unit is None else f"{name} [{unit}]"


def split_header(text: str) -> tuple[str, str | None]:
    """``("omega", "rad/s")`` from ``"omega [rad/s]"``; ``(text, None)`` without a unit."""
    match = _HEADER.fullmatch(text)
    return (match.group(1), match.group(2)) if match else (text, None)

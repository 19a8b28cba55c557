"""The beam and its segments: the dataclasses :class:`Segment` and :class:`Beam`, reading
``[beam]`` and ``[[beam.segments]]`` (the keys of a uniform beam or a segment, its optional
terms of ``catalog.SEGMENT_PHYSICS`` and the shear-buckling limit,
``physics.segment.shear_limit_broken``), their plain-data form, and the physics limits of
those keys (:data:`PHYSICS_LIMITS`). The terms are declared in ``mstmm/physics/terms/``
(one file each): their keys become fields of both dataclasses, their limits entries of
:data:`PHYSICS_LIMITS`; nothing here names one."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, make_dataclass
from typing import Any

import numpy as np

from mstmm import catalog
from mstmm.physics import segment as segment_terms

from .errors import SceneError
from .fields import _checked, _choice, _reject_unknown, _require, _table
from .float64 import _LOG_MAX, _LOG_MIN, _range_problem
from .paths import _Names, _Paths

BOUNDARY_KINDS: tuple[str, ...] = ("clamped", "pinned", "free", "sliding")
_UNIFORM_KEYS: tuple[str, ...] = ("length", "EI", "mass_per_length")
#: Optional keys of a uniform beam or of a segment: its loss factor and its beam physics
#: beyond Euler-Bernoulli (``catalog.SEGMENT_PHYSICS``), each with its check.
_OPTIONAL_KEYS: dict[str, str] = {
    "loss_factor": "nonnegative",
    **{key: check for key, check, _ in catalog.SEGMENT_PHYSICS},
}
_BEAM_KEYS: tuple[str, ...] = (*_UNIFORM_KEYS, *_OPTIONAL_KEYS, "left", "right", "segments")


#: A field of each segment term (``mstmm/physics/terms/``), default 0 (the term absent).
_TERM_FIELDS = [(t.name, float, field(default=0.0)) for t in segment_terms.terms()]


@dataclass(frozen=True)
class _SegmentValues:
    length: float
    EI: float
    mass_per_length: float
    loss_factor: float = 0.0


Segment = make_dataclass("Segment", _TERM_FIELDS, bases=(_SegmentValues,), frozen=True)
Segment.__module__ = __name__  # pickled by name (Python 3.11 has no module= argument)
Segment.__doc__ = """One piece of a stepped beam (SI): its length, bending stiffness, mass
per length, loss factor (hysteretic damping, ``EI -> EI (1 + i eta)``; 0: none), and a
field for each term beyond Euler-Bernoulli (``catalog.SEGMENT_PHYSICS``, the files of
``mstmm/physics/terms/``; 0: none): the Timoshenko shear stiffness ``kappa_GA`` (N; 0: no
shear deformation) and rotary inertia per length ``rho_I`` (kg m), the ``axial_force`` (N,
tension positive), a Winkler foundation ``foundation_k`` (N/m^2), a Pasternak shear layer
``foundation_kG`` (N), and any term a file adds."""


@dataclass(frozen=True)
class _BeamValues:
    length: float
    EI: float
    mass_per_length: float
    left: str
    right: str
    segments: tuple = ()
    loss_factor: float = 0.0


Beam = make_dataclass("Beam", _TERM_FIELDS, bases=(_BeamValues,), frozen=True)
Beam.__module__ = __name__
Beam.__doc__ = """Euler-Bernoulli beam: SI values and the two boundary kinds.

``length`` is the total length; ``EI`` and ``mass_per_length`` are those of a uniform
beam, or of the first segment of a stepped beam. ``segments`` lists a stepped beam's
pieces from the left end (:class:`Segment`), and is empty for a uniform beam.
``loss_factor`` is a uniform beam's hysteretic damping ``eta`` (``EI -> EI (1 + i eta)``,
a frequency-domain model; a stepped beam gives it per segment), and so are the terms of a
uniform beam (:class:`Segment`).
"""


def _beam(value: Any, source: str) -> Beam:
    table = _table(value, "beam", source)
    _reject_unknown(table, _BEAM_KEYS, "beam", source)
    if "segments" in table:
        for key in (*_UNIFORM_KEYS, *_OPTIONAL_KEYS):
            if key in table:
                raise SceneError(
                    source,
                    f"beam.{key}",
                    "not with [[beam.segments]]: a stepped beam gives length, EI,"
                    f" mass_per_length and {key if key not in _UNIFORM_KEYS else 'the rest'}"
                    " per segment",
                    table[key],
                )
        segments = _segments(table["segments"], source)
        # the total as the parameter layout forms it (catalog.layout)
        length = float(sum(s.length for s in segments))
        ei, mu = segments[0].EI, segments[0].mass_per_length
        if not math.isfinite(length):
            raise SceneError(source, "beam.segments", "the total length must be finite", length)
    else:
        segments = ()
        length, ei, mu = (
            _checked(_require(table, key, "beam", source), "positive", f"beam.{key}", source)
            for key in _UNIFORM_KEYS
        )
    optional = _optional(table, "beam", source)
    left, right = (
        _choice(_require(table, key, "beam", source), BOUNDARY_KINDS, f"beam.{key}", source)
        for key in ("left", "right")
    )
    return Beam(length, ei, mu, left, right, segments, **optional)


def _optional(table: Mapping[str, Any], prefix: str, source: str) -> dict[str, float]:
    """The optional keys of a beam or a segment (default 0): its ``loss_factor`` (>= 0)
    and its terms (``catalog.SEGMENT_PHYSICS``). A segment in compression beyond its
    shear stiffness (``physics.segment.shear_limit_broken``) has no static equilibrium
    (shear buckling) and is refused here."""
    values = {
        key: _checked(table[key], check, f"{prefix}.{key}", source) if key in table else 0.0
        for key, check in _OPTIONAL_KEYS.items()
    }
    if segment_terms.shear_limit_broken(values):
        key = segment_terms.compression_key()
        raise SceneError(
            source, f"{prefix}.{key}", segment_terms.shear_limit_message(), values[key]
        )
    return values


def _segments(value: Any, source: str) -> tuple[Segment, ...]:
    if isinstance(value, (str, bytes, Mapping)) or not isinstance(value, (list, tuple)):
        raise SceneError(
            source, "beam.segments", "must be an array of tables ([[beam.segments]])", value
        )
    if not value:
        raise SceneError(source, "beam.segments", "must hold at least one segment", value)
    segments = []
    for s, item in enumerate(value):
        prefix = f"beam.segments[{s}]"
        table = _table(item, prefix, source)
        _reject_unknown(table, (*_UNIFORM_KEYS, *_OPTIONAL_KEYS), prefix, source)
        values = (_require(table, key, prefix, source) for key in _UNIFORM_KEYS)
        segments.append(
            Segment(
                *(
                    _checked(v, "positive", f"{prefix}.{key}", source)
                    for key, v in zip(_UNIFORM_KEYS, values)
                ),
                **_optional(table, prefix, source),
            )
        )
    return tuple(segments)


def _beam_dict(beam: Beam) -> dict[str, Any]:
    if not beam.segments:
        out = {"length": beam.length, "EI": beam.EI, "mass_per_length": beam.mass_per_length}
        return out | _optional_dict(beam) | {"left": beam.left, "right": beam.right}
    return {
        "left": beam.left,
        "right": beam.right,
        "segments": [_segment_dict(s) if isinstance(s, Segment) else s for s in beam.segments],
    }


def _segment_dict(s: Segment) -> dict[str, Any]:
    out = {"length": s.length, "EI": s.EI, "mass_per_length": s.mass_per_length}
    return out | _optional_dict(s)


def _optional_dict(s: Segment | Beam) -> dict[str, float]:
    """The optional keys of a uniform beam or a segment that are set (nonzero)."""
    return {key: getattr(s, key) for key in _OPTIONAL_KEYS if getattr(s, key, 0.0)}


#: The largest loss factor a beam or a segment may have (``PHYSICS_LIMITS``).
LOSS_FACTOR_MAX = 1e4


_WAVES = "beyond, the root search cannot resolve the beam's waves in a reasonable time"
_DAMPING = (
    "the most damped materials reach about 2; up to 1e4 the roots match the closed form,"
    " at 1e6 the count can no longer certify them"
)
#: The beam physics the root search can carry, beyond what float64 can: each optional key
#: of a beam or a segment (when not 0) as a dimensionless form, its exponents of (the
#: total length, the segment's EI, its mass_per_length), and the least and most it may
#: be. The cost of a search grows with the square root of each form (the pieces a walk
#: cuts a segment into to resolve its shortest wave) or stalls outright beyond these
#: (measured: minutes at 1e3 times the limit); every real beam lies far inside them.
PHYSICS_LIMITS: dict[str, tuple[str, tuple[int, int, int], float, float, str]] = {
    # each term's LIMIT (its file says why its range is what it is); exponents: its unit's
    **{
        t.name: (t.limit[0], tuple(int(e) for e in t.scale), t.limit[1], t.limit[2], _WAVES)
        for t in segment_terms.terms()
    },
    # hysteretic damping EI (1 + i eta): the most damped polymers reach eta ~ 2; a pinned
    # beam matches sqrt(1 + i eta) (n pi / L)^2 to 1e-10 up to eta = 1e4 (tests of damped
    # certification), at 1e6 the count no longer certifies its roots
    "loss_factor": ("loss_factor", (0, 0, 0), 0.0, LOSS_FACTOR_MAX, _DAMPING),
}


def _physics_paths(beam: Beam, names: _Names, key: str) -> _Paths:
    """The field path of ``key`` on each segment (``beam.<key>`` on a uniform beam)."""
    if beam.segments:
        return _Paths(len(beam.segments), lambda s: names.segment(s, key))
    return _Paths(1, lambda s: f"beam.{key}")


def _check_physics(P: np.ndarray, beam: Beam, names: _Names, source: str, point: str) -> None:
    """Refuse an optional key of a beam or a segment whose dimensionless form lies beyond
    :data:`PHYSICS_LIMITS` (0 means the key is off and passes), vectorised over rows."""
    n = max(1, len(beam.segments))
    rows = catalog.HEAD + catalog.SEGMENT_WIDTH * np.arange(n)
    EI, mbar = catalog.SEGMENT_COLUMNS["EI"], catalog.SEGMENT_COLUMNS["mass_per_length"]
    base = (np.log10(P[:, [0]]), np.log10(P[:, rows + EI]), np.log10(P[:, rows + mbar]))
    for key, (form, exponents, least, most, why) in PHYSICS_LIMITS.items():
        column = rows + catalog.SEGMENT_COLUMNS[key]
        values = np.abs(P[:, column])
        with np.errstate(divide="ignore"):
            own = np.log10(values)
            log = own + sum(e * b for e, b in zip(exponents, base) if e)
        floor = math.log10(least) if least > 0.0 else -math.inf
        for bad, problem in (
            ((own < _LOG_MIN) | (own > _LOG_MAX), _range_problem),
            ((log < floor) | (log > math.log10(most)), None),
        ):
            bad &= values != 0.0
            if not bad.any():
                continue
            row, s = (int(i) for i in np.argwhere(bad)[0])
            where = f"at {point} {row}, " if point else ""
            if problem is None:
                side = f"at least {least:g}" if log[row, s] < floor else f"at most {most:g}"
                text = f"{where}{form} is {10.0 ** log[row, s]:.3g}; it must be {side} ({why})"
            else:
                text = problem(where)
            paths = _physics_paths(beam, names, key)
            raise SceneError(source, paths[s], text, float(P[row, column[s]]))

"""Whether the numerics can carry and search a band of frequencies for a scene.

``scene`` is a :class:`~mstmm.scene.Scene`, read as data (unannotated, as
:func:`mstmm.topology.topology_of` takes it): a scene is built a layer above."""

from __future__ import annotations

import math

from .errors import SceneError
from .float64 import _LOG_MAX, REPRESENTABLE_MAX
from .segments import Beam

#: Most beam modes (lam L / pi) a band may span: the search evaluates the characteristic
#: function about 8 times per mode of the band.
MAX_BAND_MODES = 100_000


def _pieces(beam: Beam) -> list[tuple[float, float, float]]:
    """``(length, EI, mass_per_length)`` of each piece of the beam from the left end."""
    if beam.segments:
        return [(s.length, s.EI, s.mass_per_length) for s in beam.segments]
    return [(beam.length, beam.EI, beam.mass_per_length)]


def check_band(
    scene,
    band: tuple[float, float],
    source: str,
    option: str,
    most: int = MAX_BAND_MODES,
) -> None:
    """Reject a band (rad/s) that the numerics cannot carry or search for ``scene``.

    ``omega^2``, ``mass_per_length omega^2`` and ``(lam L)^4`` of every segment at the
    top of the band must lie below :data:`REPRESENTABLE_MAX`, and the band may span at
    most ``most`` (:data:`MAX_BAND_MODES`) beam modes (``sum of lam l / pi`` over the
    segments).
    """
    lo, hi = band
    if hi <= 0.0:
        return
    beam = scene.beam
    span = 0.0
    for length, ei, mu in _pieces(beam):
        log_mw2 = math.log10(mu) + 2.0 * math.log10(hi)
        log_beta = math.log10(beam.length) + 0.25 * (log_mw2 - math.log10(ei))
        if 2.0 * math.log10(hi) > _LOG_MAX or log_mw2 > _LOG_MAX or 4.0 * log_beta > _LOG_MAX:
            raise SceneError(
                source,
                option,
                "HI is beyond what float64 arithmetic can carry for this beam (omega^2,"
                f" mass_per_length omega^2 and (lam L)^4 must stay below {REPRESENTABLE_MAX:g})",
                [lo, hi],
            )
        scale = math.sqrt(math.sqrt(mu / ei)) * length
        span += scale * (math.sqrt(hi) - math.sqrt(lo)) / math.pi
    if span > most:
        raise SceneError(
            source,
            option,
            f"the band spans about {span:.3g} beam modes (lam L / pi); at most"
            f" {most} are searched: narrow it",
            [lo, hi],
        )

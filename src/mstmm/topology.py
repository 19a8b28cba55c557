"""A scene's topology and its run-time parameter vector (the layout is ``derive.catalog``'s)."""

from __future__ import annotations

import numpy as np

from mstmm.catalog import (
    BEAM_PARAMETERS,
    KNOWN_ZERO,
    SEGMENT_KEYS,
    STATE,
    Component,
    Topology,
    damped,
    layout,
    unknown,
)

__all__ = [
    "BEAM_PARAMETERS",
    "KNOWN_ZERO",
    "STATE",
    "Topology",
    "field_index",
    "parameter_vector",
    "topology_of",
    "unknown",
]


def topology_of(scene) -> Topology:
    """The topology of a :class:`mstmm.scene.Scene`: its end conditions, component kinds,
    and whether it is damped (``catalog.damped``). Kept on the scene (immutable) after the
    first call: the damping test reads every value, and each solve asks."""
    known = getattr(scene, "__dict__", {}).get("_topology")
    if known is not None:
        return known
    kinds = tuple(sorted({a.kind for a in scene.attachments}))
    damped_ = damped(_segments(scene), _components(scene))
    topology = Topology(scene.beam.left, scene.beam.right, kinds, damped_)
    if hasattr(scene, "__dict__"):
        object.__setattr__(scene, "_topology", topology)
    return topology


def _segments(scene) -> list[tuple[float, ...]]:
    """``(length, EI, mbar, eta, kappa_GA, rho_I, P, k_w, k_G)`` of each segment
    (``catalog.SEGMENT_KEYS``; an optional value a beam-like object lacks is 0)."""
    beam = scene.beam
    segments = getattr(beam, "segments", ()) or (beam,)
    return [
        (s.length, s.EI, s.mass_per_length, *(getattr(s, k, 0.0) for k in SEGMENT_KEYS[2:]))
        for s in segments
    ]


def _components(scene) -> list[Component]:
    return [Component(a.kind, a.x, dict(a.values)) for a in scene.attachments]


def _layout(scene) -> tuple[np.ndarray, dict[str, int]]:
    return layout(_segments(scene), _components(scene), topology_of(scene))


def parameter_vector(scene) -> np.ndarray:
    """Run-time parameters of a scene (SI): ``[L, EI_0, mbar_0, n_seg, n_ev, left end, right
    end (codes of catalog.END_CODES), segment rows
    (x_end, EI, mbar, eta, kappa_GA, rho_I, P, k_w, k_G), event rows (tag, x, offset)
    sorted by x, data...]`` (:func:`mstmm.catalog.layout`). Laid out once and kept on the
    scene (immutable), as its topology is: 10,000 components take 40 ms of Python, more
    than their lowest 20 frequencies; a scene read with ``repeat`` keeps the vector it was
    checked with (tiled from its cell). Each call returns a fresh copy."""
    known = getattr(scene, "__dict__", {}).get("_parameters")
    if known is None:
        known = _layout(scene)[0]
        if hasattr(scene, "__dict__"):
            object.__setattr__(scene, "_parameters", known)
    return known.copy()


def field_index(scene) -> dict[str, int]:
    """Index in the parameter vector of every field path of the scene (``beam.EI``,
    ``beam.segments[1].EI``, ``attachments[3].J``, ``attachments[2].k[1]``)."""
    return _layout(scene)[1]

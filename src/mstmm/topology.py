"""Topology of a scene and its run-time parameter vector (the catalog: ``mstmm.derive.catalog``)."""

from __future__ import annotations

import numpy as np

from mstmm.derive.catalog import (
    ATTACHMENT_PARAMETERS,
    BEAM_PARAMETERS,
    KNOWN_ZERO,
    STATE,
    Topology,
    unknown,
)

__all__ = [
    "ATTACHMENT_PARAMETERS",
    "BEAM_PARAMETERS",
    "KNOWN_ZERO",
    "STATE",
    "Topology",
    "parameter_vector",
    "topology_of",
    "unknown",
]


def topology_of(scene) -> Topology:
    """The topology of a :class:`mstmm.scene.Scene`."""
    kinds = tuple(sorted({a.kind for a in scene.attachments}))
    return Topology(scene.beam.left, scene.beam.right, kinds)


def parameter_vector(scene) -> np.ndarray:
    """Run-time parameters of a scene: ``[L, EI, mbar, x_1, k_1, m_1, x_2, ...]``.

    Attachments follow in the order of the scene (sorted by ``x``); each
    contributes the fields :data:`ATTACHMENT_PARAMETERS` lists for its kind.
    """
    beam = scene.beam
    values = [beam.length, beam.EI, beam.mass_per_length]
    for a in scene.attachments:
        values.extend(float(getattr(a, name)) for name in ATTACHMENT_PARAMETERS[a.kind])
    return np.asarray(values, dtype=np.float64)

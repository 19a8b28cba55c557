"""Which kernels are committed in ``generated/``: those of the bundled scenes."""

from __future__ import annotations

from pathlib import Path

from mstmm.catalog import Topology

#: Topologies of the scenes shipped in ``mstmm/scenes`` (wu_chou_1998, bare_cantilever).
BUNDLED_TOPOLOGIES = (
    Topology("clamped", "free", ("spring_mass",)),
    Topology("clamped", "free", ()),
)


def generated_dir() -> Path:
    """The ``generated/`` folder beside ``derive/`` in the source tree."""
    return Path(__file__).resolve().parent.parent / "generated"

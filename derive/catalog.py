"""The catalog of what decides a kernel's code: end conditions, attachment kinds, topologies.

SymPy-free (imported by the runtime to name, validate and look up kernels); the
derivation stages (``emit``, ``reduce``) read the same definitions, so nothing in
``mstmm.derive`` imports the runtime package ``mstmm``. Two scenes share a kernel
when they have the same end conditions and the same *kinds* of attachments:
positions, stiffnesses, masses and the number of attachments are run-time
parameters, because the kernel loops over the attachments instead of unrolling
them (DESIGN.md, "Scale of the symbolic step").
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

#: State vector of planar bending, paper Eq. (1): displacement, rotation, moment, shear.
STATE = ("Y", "theta", "M", "Q")

#: Indices of the state variables that vanish at an end of each kind.
KNOWN_ZERO: dict[str, tuple[int, int]] = {
    "clamped": (0, 1),  # Y = theta = 0
    "pinned": (0, 2),  # Y = M = 0
    "free": (2, 3),  # M = Q = 0
    "sliding": (1, 3),  # theta = Q = 0
}

#: Number of parameters of each attachment kind in the parameter vector, in order.
ATTACHMENT_PARAMETERS: dict[str, tuple[str, ...]] = {"spring_mass": ("x", "k", "m")}

#: Parameters of the beam at the head of the parameter vector.
BEAM_PARAMETERS = ("L", "EI", "mbar")


def unknown(kind: str) -> tuple[int, int]:
    """Indices of the state variables left unknown at an end of the given kind."""
    zero = KNOWN_ZERO[kind]
    return tuple(i for i in range(4) if i not in zero)  # type: ignore[return-value]


@dataclass(frozen=True)
class Topology:
    """End conditions and the attachment kinds present: everything the kernel code depends on."""

    left: str
    right: str
    kinds: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        for end in (self.left, self.right):
            if end not in KNOWN_ZERO:
                raise ValueError(f"unknown end condition {end!r}")
        for kind in self.kinds:
            if kind not in ATTACHMENT_PARAMETERS:
                raise ValueError(f"unknown attachment kind {kind!r}")
        if tuple(sorted(set(self.kinds))) != self.kinds:
            raise ValueError(f"kinds must be sorted and unique, got {self.kinds!r}")

    @property
    def key(self) -> str:
        """File-name-safe name of the topology, e.g. ``clamped_free__spring_mass``."""
        return "__".join([f"{self.left}_{self.right}", *self.kinds])

    @classmethod
    def from_key(cls, key: str) -> Topology:
        """Inverse of :attr:`key`."""
        ends, *kinds = key.split("__")
        left, right = ends.split("_")
        return cls(left, right, tuple(kinds))

    @cached_property
    def rigid_body_modes(self) -> int:
        """Number of zero natural frequencies: rigid motions ``Y = a + b x`` the ends allow.

        Springs and hanging masses move with a rigid beam without force, so they
        do not change this number.
        """
        rows = []
        for end, x in ((self.left, 0.0), (self.right, 1.0)):
            if 0 in KNOWN_ZERO[end]:
                rows.append((1.0, x))  # Y(x) = a + b x = 0
            if 1 in KNOWN_ZERO[end]:
                rows.append((0.0, 1.0))  # theta = b = 0
        if not rows:
            return 2
        return 2 - int(np.linalg.matrix_rank(np.array(rows)))

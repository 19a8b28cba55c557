"""Rotational spring from the beam to the ground.

At its node ``EI [W''] = k W'``. As a descriptor: no unknowns,
``A = I + kappa e_M e_theta^T``.
"""

from __future__ import annotations

from mstmm.catalog import Key

KIND = "rotational_spring"
DOC = "rotational spring k from the beam at x to the ground"
KEYS = (
    Key("x", "m", check="position", doc="position from the left end"),
    Key("k", "N m/rad", doc="stiffness"),
)
#: Its marker and colour in plots (matplotlib).
MARKER = ("P", "C6")


def energy(v: dict):
    """Potential energy ``kappa theta^2 / 2``: ``M+ = M + kappa theta``."""
    import sympy as sp

    from mstmm.physics import Energy

    return Energy(K=sp.diag(0, v["k"]), C=sp.zeros(2, 2), M=sp.zeros(2, 2))

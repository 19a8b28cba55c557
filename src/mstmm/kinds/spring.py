"""Translational spring from the beam to the ground.

At its node ``EI [W'''] = -k W``. As a descriptor: no unknowns,
``A = I - kappa e_Q e_Y^T`` (paper Eq. (1)'s spring, grounded). An elastically
restrained end is a free end with a spring (and a rotational spring) at x = 0 or L.
"""

from __future__ import annotations

from mstmm.catalog import Key

KIND = "spring"
DOC = "translational spring k from the beam at x to the ground"
KEYS = (
    Key("x", "m", check="position", doc="position from the left end"),
    Key("k", "N/m", doc="stiffness"),
)
#: Its marker and colour in plots (matplotlib).
MARKER = ("d", "C5")


def energy(v: dict):
    """Potential energy ``kappa Y^2 / 2``: ``Q+ = Q - kappa Y``."""
    import sympy as sp

    from mstmm.physics import Energy

    return Energy(K=sp.diag(v["k"], 0), C=sp.zeros(2, 2), M=sp.zeros(2, 2))

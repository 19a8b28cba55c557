"""Rotational spring from the beam to the ground.

At its node ``EI [W''] = k W'``. As a descriptor: no unknowns,
``A = I + kappa e_M e_theta^T``.
"""

from __future__ import annotations

from ..catalog import Key

KIND = "rotational_spring"
DOC = "rotational spring k from the beam at x to the ground"
KEYS = (
    Key("x", "m", check="position", doc="position from the left end"),
    Key("k", "N m/rad", doc="stiffness"),
)
COUNT = "stiffness"
#: A rigid-body motion does no work on it only where theta = 0.
RIGID = ("theta",)


def descriptor(v: dict):
    """``M+ = M + kappa theta``."""
    import sympy as sp

    from ..descriptor import point

    A = sp.eye(4)
    A[2, 1] = v["k"]
    return point(A)

"""Maxwell element: a spring k in series with a dashpot c from the beam at x to the ground
(test kind, tests/test_declared_physics.py). Its middle node has no mass, so the proved
decay bound of damped roots does not cover it: its energy says so, nothing else does.
"""

from __future__ import annotations

from mstmm.catalog import Key

KIND = "maxwell"
DOC = "spring k in series with a dashpot c to the ground (test kind)"
KEYS = (
    Key("x", "m", check="position", doc="position from the left end"),
    Key("k", "N/m", doc="spring stiffness"),
    Key("c", "N s/m", check="nonnegative", default=0.0, doc="dashpot", damping=True),
)


def energy(v: dict):
    """The spring ``k (u - Y)^2 / 2`` and the dashpot ``c u'^2 / 2`` to the ground, over
    ``[Y, theta, u]``; no mass at u."""
    import sympy as sp

    from mstmm.physics import Energy

    spring = sp.Matrix([[1, 0, -1], [0, 0, 0], [-1, 0, 1]])
    return Energy(K=v["k"] * spring, C=sp.diag(0, 0, v.get("c", 0)), M=sp.zeros(3, 3), moves=("Y",))

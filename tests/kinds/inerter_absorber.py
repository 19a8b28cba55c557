"""Inerter absorber: a mass m on a spring k (and a dashpot c beside it) hanging from the
beam at x, with an inerter b in parallel with the spring, between the mass and the beam.

An inerter's force is ``b`` times the relative acceleration of its two ends, so its kinetic
energy ``b (Y_m' - Y')^2 / 2`` couples the beam's own Y to the absorber's unknown ``Y_m``:
the mass matrix over ``[Y, theta, Y_m]`` has off-diagonal terms ``-b`` and a term ``b`` on
the beam's Y. The kind of issue 42 (an inertial coupling in one file):
tests/test_inerter.py drops this file into ``src/mstmm/kinds/`` of a copy of the package,
touching nothing else, and checks it against an independent 40-digit model of the beam.
"""

from __future__ import annotations

from mstmm.catalog import Key

KIND = "inerter_absorber"
DOC = "mass m on a spring k (dashpot c) with an inerter b in parallel, hanging at x"
KEYS = (
    Key("x", "m", check="position", doc="position from the left end"),
    Key("k", "N/m", doc="spring stiffness"),
    Key("m", "kg", doc="mass of the absorber"),
    Key("b", "kg", check="nonnegative", doc="inertance between the mass and the beam"),
    Key(
        "c",
        "N s/m",
        check="nonnegative",
        default=0.0,
        doc="dashpot parallel to the spring",
        damping=True,
    ),
)


def energy(v: dict):
    """The spring ``k (Y_m - Y)^2 / 2``, the dashpot ``c (Y_m' - Y')^2 / 2``, the inerter
    ``b (Y_m' - Y')^2 / 2`` and the mass ``m Y_m'^2 / 2``; a rigid translation of the beam
    carries Y_m."""
    import sympy as sp
    from mstmm.derive.descriptor import Energy

    spring = sp.Matrix([[1, 0, -1], [0, 0, 0], [-1, 0, 1]])  # over [Y, theta, Y_m]
    b = v["b"]
    mass = sp.Matrix([[b, 0, -b], [0, 0, 0], [-b, 0, v["m"] + b]])
    return Energy(K=v["k"] * spring, C=v.get("c", 0) * spring, M=mass, moves=("Y",))

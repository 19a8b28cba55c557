"""A component kind defined outside the package (tests/test_components.py registers it).

A translational spring to the ground whose stiffness is called ``stiffness``: the same
physics as the built-in ``spring``, so the reference model checks it as a ``spring``.
Nothing else in mstmm is edited for it: this file is the whole kind.
"""

from __future__ import annotations

from mstmm.catalog import Key

KIND = "ground_spring"
DOC = "translational spring from the beam at x to the ground (test kind)"
KEYS = (
    Key("x", "m", check="position", doc="position from the left end"),
    Key("stiffness", "N/m", doc="spring stiffness"),
)
COUNT = "stiffness"
RIGID = ("Y",)


def descriptor(v: dict):
    """``Q+ = Q - kappa Y``."""
    import sympy as sp
    from mstmm.derive.descriptor import point

    A = sp.eye(4)
    A[3, 0] = -v["stiffness"]
    return point(A)

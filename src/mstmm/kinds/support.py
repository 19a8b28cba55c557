"""Rigid point support inside the span: Y = 0 there; slope and moment continuous.

As a descriptor: ``q = [R]`` (the reaction, units EI_0 / L^2), ``Cz = e_Y``, ``Cq = 0``,
``A = I``, ``B = e_Q``. Its compound step is the constrained map
``v+ = (i_{e_Y} v) ^ e_Q``: finite and nonzero, the pole factor Cq = 0 taken out.
The count treats it as a constraint (the node's Y removed; in the kernel, a stiffness
PENALTY on Y).
"""

from __future__ import annotations

from mstmm.catalog import Key

KIND = "support"
DOC = "rigid point support at x: Y = 0, slope and moment continuous"
KEYS = (Key("x", "m", check="position", doc="position from the left end"),)
COUNT = "constraint"
#: Its marker and colour in plots (matplotlib).
MARKER = ("^", "k")
#: Name of its unknown in Z_all (the reaction).
UNKNOWNS = "R"
RIGID = ("Y",)


def descriptor(v: dict):
    """``Y = 0``, ``Q+ = Q + R``."""
    import sympy as sp

    from mstmm.derive.descriptor import Descriptor, unit

    return Descriptor(Cz=unit(0).T, Cq=sp.Matrix([[0]]), A=sp.eye(4), B=unit(3), qmass=(0,))

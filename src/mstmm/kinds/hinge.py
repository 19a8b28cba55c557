"""Internal hinge: the slope may jump by phi; a rotational spring k across it.

``EI W''(x-) = EI W''(x+) = k (W'(x+) - W'(x-))``; k = 0 (the default) is a free hinge.
As a descriptor: ``q = [phi]``, ``Cz = e_M``, ``Cq = -kappa``, ``A = I``, ``B = e_theta``
(no special case at kappa = 0: the compound step is then the constrained map M = 0).
The count splits the node: its rotation left of the hinge is eliminated with the pivot
``S_theta + kappa`` before the right piece is joined.
"""

from __future__ import annotations

from mstmm.catalog import Key

KIND = "hinge"
DOC = "internal hinge at x (0 < x < L) with a rotational spring k across it (0: free)"
KEYS = (
    Key("x", "m", check="interior", doc="position from the left end"),
    Key("k", "N m/rad", check="nonnegative", default=0.0, doc="stiffness across the hinge"),
)
COUNT = "split"
#: Its marker and colour in plots (matplotlib).
MARKER = ("o", "C1")
#: Name of its unknown in Z_all (the jump of the slope).
UNKNOWNS = "phi"
#: A free hinge (k = 0) lets a rigid-body motion kink there.
RIGID = ("kink_if_free",)


def descriptor(v: dict):
    """``M - kappa phi = 0``, ``theta+ = theta + phi``."""
    import sympy as sp

    from mstmm.derive.descriptor import Descriptor, unit

    return Descriptor(Cz=unit(2).T, Cq=sp.Matrix([[-v["k"]]]), A=sp.eye(4), B=unit(1), qmass=(0,))

"""Internal hinge: the slope may jump by phi; a rotational spring k across it.

``EI W''(x-) = EI W''(x+) = k (W'(x+) - W'(x-))``; k = 0 (the default) is a free hinge.
Declared by the freedom it releases and the key of the spring across it (``RELEASES``);
derived from it (``descriptor.release``): ``q = [phi]``, ``Cz = e_M``, ``Cq = -kappa``,
``A = I``, ``B = e_theta`` (no special case at kappa = 0: the compound step is then the
constrained map M = 0); the count splits the node (its rotation left of the hinge is
eliminated with the pivot ``S_theta + kappa`` before the right piece is joined); a free
hinge lets a rigid-body motion kink there.
"""

from __future__ import annotations

from mstmm.catalog import Key

KIND = "hinge"
DOC = "internal hinge at x (0 < x < L) with a rotational spring k across it (0: free)"
KEYS = (
    Key("x", "m", check="interior", doc="position from the left end"),
    Key("k", "N m/rad", check="nonnegative", default=0.0, doc="stiffness across the hinge"),
)
#: The rotation jumps here, with the spring k across the jump.
RELEASES = ("theta", "k")
#: Its marker and colour in plots (matplotlib).
MARKER = ("o", "C1")
#: Name of its unknown in Z_all (the jump of the slope).
UNKNOWNS = "phi"

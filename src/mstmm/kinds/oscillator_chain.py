"""Oscillator chain: masses in series hanging from the beam (a multi-stage absorber).

``k = [k1, k2, ...]`` (beam -> m1, m1 -> m2, ...), ``m = [m1, m2, ...]``, optional
dashpots ``c`` parallel to the springs. Declared by the energy of one stage
(docs/components.md): stage ``j`` is a spring-mass hanging from node ``j - 1`` (node 0 the
beam point), so the chain's stiffness and mass over its nodes are tridiagonal. Everything
else is derived: the count adds the negative pivots of the nodes' dynamic stiffness (a
Sturm count), the stable step uses the chain condensed from its tip, free of poles
(``mstmm.numerics.chain``), and the mode shapes keep every mass's displacement.
SymPy is imported inside the function: the catalog reads this file's keys without it.
"""

from __future__ import annotations

from mstmm.catalog import Key

KIND = "oscillator_chain"
DOC = "masses m[i] in series hanging from the beam at x by springs k[i] (beam -> m1 -> m2 ...)"
KEYS = (
    Key("x", "m", check="position", doc="position from the left end"),
    Key("k", "N/m", shape="list", doc="spring stiffnesses, beam -> m1 first"),
    Key("m", "kg", shape="list", doc="masses, the one nearest the beam first"),
    Key(
        "c",
        "N s/m",
        shape="list",
        check="nonnegative",
        default=0.0,
        doc="dashpots parallel to the springs, beam -> m1 first (default none)",
        damping=True,
    ),
)
SAME_LENGTH = ("k", "m", "c")
#: Its marker and colour in plots (matplotlib).
MARKER = ("X", "C7")
#: Name of its unknowns in Z_all (the displacement of each mass).
UNKNOWNS = "Y_chain"


def stage(v: dict):
    """Stage j over ``[u_(j-1), theta, u_j]`` (its values the j-th entry of each list):
    the spring ``k (u_j - u_(j-1))^2 / 2``, its parallel dashpot and the mass
    ``m u_j'^2 / 2``; a rigid translation carries the mass."""
    import sympy as sp

    from mstmm.physics import Energy

    spring = sp.Matrix([[1, 0, -1], [0, 0, 0], [-1, 0, 1]])
    return Energy(
        K=v["k"] * spring, C=v.get("c", 0) * spring, M=sp.diag(0, 0, v["m"]), moves=("Y",)
    )

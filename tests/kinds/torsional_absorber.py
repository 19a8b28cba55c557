"""Torsional absorber: a rotary inertia J on a torsion spring k (and dashpot c) whose other
end turns with the beam at x.

The worked example of docs/components.md: a contributor adds it by dropping this one file
into ``src/mstmm/kinds/`` (tests/test_new_kind.py does exactly that in a copy of the
package and checks it against a finite-element model with its own degree of freedom).
Its physics is its energy over ``[Y, theta, theta_a]``; everything else is derived.
"""

from __future__ import annotations

from mstmm.catalog import Key

KIND = "torsional_absorber"
DOC = "rotary inertia J on a torsion spring k (dashpot c) turning with the beam at x"
KEYS = (
    Key("x", "m", check="position", doc="position from the left end"),
    Key("k", "N m/rad", doc="torsion spring stiffness"),
    Key("J", "kg m^2", doc="rotary inertia of the absorber"),
    Key(
        "c",
        "N m s/rad",
        check="nonnegative",
        default=0.0,
        doc="torsional dashpot parallel to the spring",
        damping=True,
    ),
)


def energy(v: dict):
    """The spring ``k (theta_a - theta)^2 / 2``, the dashpot ``c (theta_a' - theta')^2 / 2``
    and the inertia ``J theta_a'^2 / 2``; a rigid rotation of the beam carries theta_a."""
    import sympy as sp

    from mstmm.physics import Energy

    spring = sp.Matrix([[0, 0, 0], [0, 1, -1], [0, -1, 1]])
    return Energy(
        K=v["k"] * spring, C=v.get("c", 0) * spring, M=sp.diag(0, 0, v["J"]), moves=("theta",)
    )

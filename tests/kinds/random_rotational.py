"""A kind of the property test ``tests/test_random_kinds.py``: a rotary inertia ``J_q``
on a torsion spring ``k1`` (dashpot ``c``) and a rotational inerter ``b`` in parallel,
turning with the beam, a torsion spring ``k_theta`` to the ground and a lumped mass
``m_Y`` with rotary inertia ``J`` on the beam; every value but ``k1`` and ``J_q`` may be
0. Its mass matrix couples the beam's rotation to its unknown (``b``)."""

from __future__ import annotations

from mstmm.catalog import Key

KIND = "random_rotational"
DOC = "a rotary inertia on a torsion spring and an inerter, a grounded torsion spring"
KEYS = (
    Key("x", "m", check="position", doc="position from the left end"),
    Key("k1", "N m/rad", doc="torsion spring between the beam and the inertia"),
    Key("J_q", "kg m^2", doc="the turning inertia"),
    Key("b", "kg m^2", check="nonnegative", default=0.0, doc="inerter beside the spring"),
    Key("k_theta", "N m/rad", check="nonnegative", default=0.0, doc="spring to the ground"),
    Key("m_Y", "kg", check="nonnegative", default=0.0, doc="lumped mass on the beam"),
    Key("J", "kg m^2", check="nonnegative", default=0.0, doc="its rotary inertia"),
    Key("c", "N m s/rad", check="nonnegative", default=0.0, doc="dashpot beside k1", damping=True),
)


def energy(v: dict):
    import sympy as sp

    from mstmm.physics import Energy

    link = sp.Matrix([[0, 0, 0], [0, 1, -1], [0, -1, 1]])
    return Energy(
        K=v["k1"] * link + sp.diag(0, v["k_theta"], 0),
        C=v.get("c", 0) * link,
        M=v["b"] * link + sp.diag(v["m_Y"], v["J"], v["J_q"]),
        moves=("theta",),
    )

"""A kind of the property test ``tests/test_random_kinds.py``: a mass ``m_q`` on a spring
``k1`` (dashpot ``c``) and an inerter ``b`` in parallel, between the mass and the beam, a
spring ``k_Y`` to the ground and a lumped mass ``m_Y`` with rotary inertia ``J`` on the
beam; every value but ``k1`` and ``m_q`` may be 0. Its mass matrix couples the beam to
its unknown (``b``)."""

from __future__ import annotations

from mstmm.catalog import Key

KIND = "random_translational"
DOC = "a mass on a spring and an inerter, a grounded spring and a lumped mass"
KEYS = (
    Key("x", "m", check="position", doc="position from the left end"),
    Key("k1", "N/m", doc="spring between the beam and the mass"),
    Key("m_q", "kg", doc="the hanging mass"),
    Key("b", "kg", check="nonnegative", default=0.0, doc="inerter beside the spring"),
    Key("k_Y", "N/m", check="nonnegative", default=0.0, doc="spring to the ground"),
    Key("m_Y", "kg", check="nonnegative", default=0.0, doc="lumped mass on the beam"),
    Key("J", "kg m^2", check="nonnegative", default=0.0, doc="its rotary inertia"),
    Key("c", "N s/m", check="nonnegative", default=0.0, doc="dashpot beside k1", damping=True),
)


def energy(v: dict):
    import sympy as sp

    from mstmm.physics import Energy

    link = sp.Matrix([[1, 0, -1], [0, 0, 0], [-1, 0, 1]])
    return Energy(
        K=v["k1"] * link + sp.diag(v["k_Y"], 0, 0),
        C=v.get("c", 0) * link,
        M=v["b"] * link + sp.diag(v["m_Y"], v["J"], v["m_q"]),
        moves=("Y",),
    )

"""Point mass fixed to the beam, with rotary inertia.

At its node ``EI [W'''] = m w^2 W`` and ``EI [W''] = -J w^2 W'`` (``[.]`` the jump, right
minus left; issue 13's sign conventions). As a descriptor: no unknowns,
``A = I + mu b4 e_Q e_Y^T - j b4 e_M e_theta^T`` (paper Eq. (1), the lumped mass
``[[1, 0], [m w^2, 1]]`` on ``[Y, Q]`` and its rotary twin on ``[theta, M]``).
"""

from __future__ import annotations

from mstmm.catalog import Key

KIND = "mass"
DOC = "point mass m fixed to the beam at x, rotary inertia J"
KEYS = (
    Key("x", "m", check="position", doc="position from the left end"),
    Key("m", "kg", doc="mass"),
    Key(
        "J",
        "kg m^2",
        check="nonnegative",
        default=0.0,
        doc="rotary inertia about the beam axis normal",
    ),
)
#: Its marker and colour in plots (matplotlib).
MARKER = ("s", "C2")


def energy(v: dict):
    """Kinetic energy ``(mu Y'^2 + j theta'^2) / 2``: ``Q+ = Q + mu b4 Y``,
    ``M+ = M - j b4 theta`` (paper Eq. (1), lumped mass)."""
    import sympy as sp

    from mstmm.physics import Energy

    return Energy(K=sp.zeros(2, 2), C=sp.zeros(2, 2), M=sp.diag(v["m"], v["J"]))

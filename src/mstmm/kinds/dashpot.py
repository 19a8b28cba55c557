"""Viscous dashpot from the beam to the ground.

At its node ``EI [W'''] = -i w c W`` (time dependence exp(i w t): the force on the beam
is ``-c dW/dt``): a grounded ``spring`` whose stiffness is ``i w c``. As a descriptor: no
unknowns, ``A = I - i w1 gamma e_Q e_Y^T`` (``gamma = c L / sqrt(EI mbar)``, ``w1`` the
frequency in the kernel's units). A scene with a dashpot is damped: its kernel is
complex, and the kind is left out of its undamped twin.
"""

from __future__ import annotations

from mstmm.catalog import Key

KIND = "dashpot"
DOC = "viscous dashpot c from the beam at x to the ground"
KEYS = (
    Key("x", "m", check="position", doc="position from the left end"),
    Key("c", "N s/m", doc="damping coefficient", damping=True),
)
#: Its marker and colour in plots (matplotlib).
MARKER = ("*", "C8")


def energy(v: dict):
    """Dissipation ``gamma Y'^2 / 2``: ``Q+ = Q - i w1 gamma Y``."""
    import sympy as sp

    from mstmm.physics import Energy

    return Energy(K=sp.zeros(2, 2), C=sp.diag(v.get("c", 0), 0), M=sp.zeros(2, 2))

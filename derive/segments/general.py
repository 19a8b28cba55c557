"""A Timoshenko beam under an axial force on elastic foundations: the segment every term
of which is optional (issue 22), declared by its differential equation. Its terms are the
files of ``mstmm/physics/terms/`` (issue 42), each one of the roles this field carries
(``mstmm.physics.segment.ROLES``); ``t`` sums the tensions (an axial force P, a
Pasternak layer k_G), ``r`` the rotational foundations, ``k_w`` the Winkler ones.

From the energies per unit length (``psi`` the rotation of the section, ``w`` = Y)::

    potential  EI psi'^2 + kGA (w' - psi)^2 + t w'^2 + r psi^2 + k_w w^2      (halved)
    kinetic    mbar w'^2 + rhoI psi'^2                                        (halved)

the Euler-Lagrange equations at frequency omega, written for the state
``Z = [Y, psi, M, Q]`` with ``M = EI psi'`` and ``Q = -(kGA (w' - psi) + t w')``
(the signs of paper Eq. (1): ``M' = Q``, ``Q' = mbar omega^2 Y`` for Euler-Bernoulli),
are ``Z' = A Z`` with, for ``g = kGA + t``::

    Y'   = (kGA / g) psi - Q / g
    psi' = M / EI
    M'   = (kGA t / g + r - rhoI omega^2) psi + (kGA / g) Q
    Q'   = (mbar omega^2 - k_w) Y

``kGA -> oo`` gives Euler-Bernoulli with the tension and the foundations (``Y' = psi``,
``M' = Q + (t + r - rhoI omega^2) psi``); nothing else set gives paper Eq. (1).
The field transfer matrix is ``exp(A l)`` (``mstmm.numerics.field``): exact for every
branch, above the Timoshenko cut-off ``sqrt(kGA / rhoI)`` and on both sides of buckling.
``tests/test_field.py`` checks this matrix against the Euler-Lagrange equations SymPy
derives from the summed energies.
"""

from __future__ import annotations

import sympy as sp


def field(v: dict) -> sp.Matrix:
    """``A`` of ``Z' = A Z`` from the segment's values ``EI``, ``mbar``, ``w2`` (omega^2)
    and the optional role sums ``kGA`` (absent: no shear deformation), ``rhoI``, ``t``
    (tension positive), ``r``, ``k_w``."""
    EI, mbar, w2 = v["EI"], v["mbar"], v["w2"]
    t, r = v.get("t", 0), v.get("r", 0)
    rhoI, k_w = v.get("rhoI", 0), v.get("k_w", 0)
    if v.get("kGA") is None:
        a01, a03, a21, a23 = 1, 0, t + r - rhoI * w2, 1
    else:
        kGA = v["kGA"]
        g = kGA + t
        a01, a03, a21, a23 = kGA / g, -1 / g, kGA * t / g + r - rhoI * w2, kGA / g
    return sp.Matrix(
        [
            [0, a01, 0, a03],
            [0, 0, 1 / EI, 0],
            [0, a21, 0, a23],
            [mbar * w2 - k_w, 0, 0, 0],
        ]
    )

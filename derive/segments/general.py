"""A Timoshenko beam under an axial force on a Winkler-Pasternak foundation: the segment
kind every term of which is optional (issue 22), declared by its differential equation.

From the energies per unit length (``psi`` the rotation of the section, ``w`` = Y)::

    potential  EI psi'^2 + kGA (w' - psi)^2 + (P + k_G) w'^2 + k_w w^2      (halved)
    kinetic    mbar w'^2 + rhoI psi'^2                                       (halved)

the Euler-Lagrange equations at frequency omega, written for the state
``Z = [Y, psi, M, Q]`` with ``M = EI psi'`` and ``Q = -(kGA (w' - psi) + (P + k_G) w')``
(the signs of paper Eq. (1): ``M' = Q``, ``Q' = mbar omega^2 Y`` for Euler-Bernoulli),
are ``Z' = A Z`` with, for ``g = kGA + P + k_G``::

    Y'   = (kGA / g) psi - Q / g
    psi' = M / EI
    M'   = (kGA (P + k_G) / g - rhoI omega^2) psi + (kGA / g) Q
    Q'   = (mbar omega^2 - k_w) Y

``kGA -> oo`` gives Euler-Bernoulli with the axial force and the foundation
(``Y' = psi``, ``M' = Q + (P + k_G) psi``); nothing else set gives paper Eq. (1).
The field transfer matrix is ``exp(A l)`` (``mstmm.numerics.field``): exact for every
branch, above the Timoshenko cut-off ``sqrt(kGA / rhoI)`` and on both sides of buckling.
"""

from __future__ import annotations

import sympy as sp


def field(v: dict) -> sp.Matrix:
    """``A`` of ``Z' = A Z`` from the segment's values ``EI``, ``mbar``, ``w2`` (omega^2)
    and the optional ``kGA`` (absent: no shear deformation), ``rhoI``, ``P`` (tension
    positive), ``k_w``, ``k_G``."""
    EI, mbar, w2 = v["EI"], v["mbar"], v["w2"]
    t = v.get("P", 0) + v.get("k_G", 0)
    rhoI, k_w = v.get("rhoI", 0), v.get("k_w", 0)
    if v.get("kGA") is None:
        a01, a03, a21, a23 = 1, 0, t - rhoI * w2, 1
    else:
        kGA = v["kGA"]
        g = kGA + t
        a01, a03, a21, a23 = kGA / g, -1 / g, kGA * t / g - rhoI * w2, kGA / g
    return sp.Matrix(
        [
            [0, a01, 0, a03],
            [0, 0, 1 / EI, 0],
            [0, a21, 0, a23],
            [mbar * w2 - k_w, 0, 0, 0],
        ]
    )

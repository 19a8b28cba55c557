"""Spring-mass branch: paper Eq. (1) spring and lumped mass on ``[Y, Q]``.

The branch hangs from a massless rigid body on the beam; its tip (the free side
of the mass) is ``Z = [Y_m, 0]``.
"""

from __future__ import annotations

import sympy as sp

from ..compound import second_compound
from . import rigid_body


def spring(k: sp.Expr) -> sp.Matrix:
    """Linear translational spring, paper Eq. (1): ``[[1, -1/k], [0, 1]]``."""
    return sp.Matrix([[1, -1 / k], [0, 1]])


def mass(m: sp.Expr, omega: sp.Expr) -> sp.Matrix:
    """Lumped mass, paper Eq. (1): ``[[1, 0], [m w^2, 1]]``."""
    return sp.Matrix([[1, 0], [m * omega**2, 1]])


def branch(k: sp.Expr, m: sp.Expr, omega: sp.Expr) -> sp.Matrix:
    """Tip-to-beam transfer of the branch, ``U_spring U_mass`` (mass first, paper Eq. (2))."""
    return spring(k) * mass(m, omega)


def tip_column(k: sp.Expr, m: sp.Expr, omega: sp.Expr) -> sp.Matrix:
    """State delivered at the rigid body per unit tip displacement: ``B [1, 0]^T``."""
    return branch(k, m, omega)[:, 0]


def condensed_compound(k: sp.Expr, m: sp.Expr, omega: sp.Expr) -> tuple[sp.Matrix, sp.Expr]:
    """Pole-free second compound of the branch point, and the pole factor taken out.

    Eliminating the tip displacement with the geometric equation
    ``H_I1 Z_beam = H_I2 B [Y_m, 0]^T`` (paper Eq. (3)) gives the beam-to-beam
    matrix ``P = U_I1 + U_I2 [1, B10/B00]^T H_I1``, whose ``B10/B00 = k m w^2 / (k - m w^2)``
    has a pole at the oscillator frequency. ``C2(P)`` is linear in that ratio
    (``U_I2 H_I1`` has rank one), so ``B00 C2(P)`` is a polynomial: the pole is
    multiplied out exactly once, and the roots of the chain stay those of the
    paper's determinant, multiplicities included.
    """
    col = tip_column(k, m, omega)
    B00, B10 = col[0], col[1]
    ratio = sp.Symbol("ratio")
    # the branch delivers [Y_beam, ratio * Y_beam] to the rigid body's second input
    delivered = sp.Matrix([1, ratio]) * rigid_body.H_I1()
    P = rigid_body.U_I1() + rigid_body.U_I2() * delivered
    C = second_compound(P).applyfunc(sp.expand)
    if any(sp.degree(e, ratio) > 1 for e in C if e.has(ratio)):
        raise ValueError("compound of the branch point is not linear in the impedance")
    pole_free = C.applyfunc(lambda e: sp.expand(B00 * e.coeff(ratio, 0) + B10 * e.coeff(ratio, 1)))
    return pole_free, B00

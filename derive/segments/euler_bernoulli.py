"""Euler-Bernoulli beam segment: paper Eq. (1) and the forms derived from it.

State ``Z = [Y, theta, M, Q]``; ``Z_O = U Z_I`` with ``lam = (mbar w^2 / EI)^(1/4)``.
"""

from __future__ import annotations

import sympy as sp
from mstmm.derive.compound import second_compound, split_krylov_products


def field(v: dict) -> sp.Matrix:
    """``A`` of the segment's differential equation ``Z' = A Z`` (paper Eq. (1)'s signs:
    ``Y' = theta``, ``theta' = M / EI``, ``M' = Q``, ``Q' = mbar w^2 Y``), from the values
    ``EI``, ``mbar``, ``w2`` (omega^2): ``exp(A l)`` is :func:`transfer_matrix`
    (``tests/test_field.py``)."""
    return sp.Matrix(
        [[0, 1, 0, 0], [0, 0, 1 / v["EI"], 0], [0, 0, 0, 1], [v["mbar"] * v["w2"], 0, 0, 0]]
    )


def transfer_matrix(lam: sp.Expr, l: sp.Expr, EI: sp.Expr) -> sp.Matrix:
    """Beam transfer matrix exactly as printed in paper Eq. (1) (``a_1 .. a_16``)."""
    x = lam * l
    ch, sh, c, s = sp.cosh(x), sp.sinh(x), sp.cos(x), sp.sin(x)
    S, T, G, V = (ch + c) / 2, (sh + s) / 2, (ch - c) / 2, (sh - s) / 2
    return sp.Matrix(
        [
            [S, T / lam, G / (EI * lam**2), V / (EI * lam**3)],
            [lam * V, S, T / (EI * lam), G / (EI * lam**2)],
            [EI * lam**2 * G, EI * lam * V, S, T / lam],
            [EI * lam**3 * T, EI * lam**2 * G, lam * V, S],
        ]
    )


def transfer_matrix_reduced(lam: sp.Expr, l: sp.Expr, EI: sp.Expr, K) -> sp.Matrix:
    """Eq. (1) with ``T = x K1``, ``G = x^2 K2``, ``V = x^3 K3``, ``S = K0`` (``x = lam l``).

    ``K`` is a sequence of four symbols standing for :data:`special.KRYLOV`; the
    entries become monomials in ``lam, l, EI`` times one reduced function, so the
    matrix is exact for ``lam l -> 0`` (no ``1/lam`` left).
    """
    K0, K1, K2, K3 = K
    x = lam * l
    S, T, G, V = K0, x * K1, x**2 * K2, x**3 * K3
    U = sp.Matrix(
        [
            [S, T / lam, G / (EI * lam**2), V / (EI * lam**3)],
            [lam * V, S, T / (EI * lam), G / (EI * lam**2)],
            [EI * lam**2 * G, EI * lam * V, S, T / lam],
            [EI * lam**3 * T, EI * lam**2 * G, lam * V, S],
        ]
    )
    return U.applyfunc(lambda e: sp.powsimp(sp.expand(e)))


def compound_nondimensional(beta: sp.Symbol, rho: sp.Symbol, E, F) -> sp.Matrix:
    """Second compound of the beam matrix in units ``L = 1``, ``EI = 1`` (stable formulation).

    ``beta = lam L`` and ``rho = l / L``; ``x = beta rho``. Each 2x2 minor of
    Eq. (1) is reduced with ``ch^2 - sh^2 = 1`` and ``c^2 + s^2 = 1`` and written
    with the functions ``F1..F4`` of :mod:`..special` (symbols ``F``) and the
    scale ``E`` (``exp(-x)`` on the large-argument branch, 1 on the series branch).
    The result has no negative power of ``beta`` or ``rho``: it is exact at
    ``x -> 0`` and, with the scaled branch, bounded for ``x -> infinity``.
    """
    U = transfer_matrix(beta, rho, sp.Integer(1))
    C = second_compound(U)
    return C.applyfunc(lambda e: split_krylov_products(e, beta * rho, E, F))


def transfer_matrix_nondimensional(beta: sp.Expr, rho: sp.Expr, K) -> sp.Matrix:
    """Eq. (1) in units ``L = 1``, ``EI = 1`` (``beta = lam L``, ``rho = l / L``), reduced form."""
    return transfer_matrix_reduced(beta, rho, sp.Integer(1), K)


#: Nodal forces ``[F, M_theta]`` (work-conjugate to ``[Y, theta]``) -> internal ``[M, Q]``
#: at the left and at the right end of a segment. These are the only signs for which
#: the dynamic stiffness built from Eq. (1) is symmetric with the classical static limit
#: ``EI/l^3 [[12, 6l, -12, 6l], ...]`` (checked in tests/test_symbolic.py).
PI_LEFT = sp.Matrix([[0, -1], [1, 0]])
PI_RIGHT = sp.Matrix([[0, 1], [-1, 0]])


def blocks(U: sp.Matrix) -> tuple[sp.Matrix, sp.Matrix, sp.Matrix, sp.Matrix]:
    """``A, B, C, D`` of ``[d; f]_O = [[A, B], [C, D]] [d; f]_I`` with ``d = [Y, theta]``."""
    return U[:2, :2], U[:2, 2:], U[2:, :2], U[2:, 2:]


def dynamic_stiffness(U: sp.Matrix) -> sp.Matrix:
    """Segment dynamic stiffness ``[P_a; P_b] = K [d_a; d_b]`` from its transfer matrix."""
    A, B, C, D = blocks(U)
    k_ab = (B * PI_LEFT).inv()
    k_aa = -k_ab * A
    k_ba = PI_RIGHT.inv() * (C + D * PI_LEFT * k_aa)
    k_bb = PI_RIGHT.inv() * D * PI_LEFT * k_ab
    return sp.Matrix(sp.BlockMatrix([[k_aa, k_ab], [k_ba, k_bb]]))


def riccati_step(U: sp.Matrix, S: sp.Matrix) -> tuple[sp.Matrix, sp.Expr, sp.Expr, sp.Expr]:
    """Carry the condensed stiffness ``S`` of everything left of a node across one segment.

    With ``f_a = -PI_LEFT S d_a`` at the node, ``d_b = X d_a`` where
    ``X = A - B PI_LEFT S``, and the condensed stiffness at the far node is
    ``S_b = PI_RIGHT^-1 (C - D PI_LEFT S) X^-1`` (a Riccati transfer step, exact
    for any segment length: no ``EI/l^3`` appears). Eliminating the near node's
    degrees of freedom in the dynamic stiffness matrix has the pivot block
    ``S + k_aa = -(B PI_LEFT)^-1 X``: its inertia follows from the signs of
    ``det X``, ``det(B PI_LEFT)`` and ``m00 = -(adj(B PI_LEFT) X)[0, 0]``.
    Returns ``(S_b numerator over det X, det X, det(B PI_LEFT), m00)``.
    """
    A, B, C, D = blocks(U)
    BP = B * PI_LEFT
    X = A - BP * S
    S_num = PI_RIGHT.inv() * (C - D * PI_LEFT * S) * X.adjugate()
    return S_num, X.det(), BP.det(), -(BP.adjugate() * X)[0, 0]


def clamped_clamped_equation(x: sp.Expr) -> sp.Expr:
    """``1 - cos x cosh x``: zero at the natural frequencies of a segment clamped at both ends."""
    return 1 - sp.cos(x) * sp.cosh(x)

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


def clamped_clamped_equation(x: sp.Expr) -> sp.Expr:
    """``1 - cos x cosh x``: zero at the natural frequencies of a segment clamped at both ends."""
    return 1 - sp.cos(x) * sp.cosh(x)

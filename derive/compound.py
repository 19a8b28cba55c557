"""Second compound (2x2 minors) of a transfer matrix: the chain of the stable formulation.

For ``T = U_n ... U_1`` the Cauchy-Binet formula gives ``C2(T) = C2(U_n) ... C2(U_1)``;
the reduced determinant ``det(R T C)`` of a 4-state chain with two unknowns at
each end (paper Eq. (4) reduced by the boundary conditions) is one entry of
``C2(T)``. Working with ``C2`` lets the cancellation ``cosh^2 - sinh^2 = 1`` be
done symbolically, once, instead of in floating point at every evaluation.
"""

from __future__ import annotations

import sympy as sp

from mstmm.catalog import PAIRS


def pair_index(pair: tuple[int, int]) -> int:
    """Position of an ascending index pair in :data:`PAIRS`."""
    return PAIRS.index(tuple(sorted(pair)))


def second_compound(A: sp.Matrix) -> sp.Matrix:
    """``C2(A)[(i,j),(k,l)] = A[i,k] A[j,l] - A[i,l] A[j,k]`` for ``i<j``, ``k<l``."""
    n = len(PAIRS)
    return sp.Matrix(
        n,
        n,
        lambda a, b: (
            A[PAIRS[a][0], PAIRS[b][0]] * A[PAIRS[a][1], PAIRS[b][1]]
            - A[PAIRS[a][0], PAIRS[b][1]] * A[PAIRS[a][1], PAIRS[b][0]]
        ),
    )


def split_krylov_products(expr: sp.Expr, x: sp.Expr, E, F) -> sp.Expr:
    """Rewrite a minor of beam functions of ``x`` with ``E`` and ``F1..F4``.

    After ``ch^2 -> 1 + sh^2`` and ``c^2 -> 1 - s^2`` a minor is
    ``a0 + a1 c ch + a2 c sh + a3 ch s + a4 s sh`` (no other products survive:
    the exponents of ``C2`` are ``0`` and ``+-lam +- i lam``). With the
    definitions of :data:`special.COMPOUND`::

        a0 + a1 c ch            = (a0 + a1) - 2 a1 x^4 F4
        a2 c sh + a3 ch s       = (a2 + a3) x F1 + (a3 - a2) x^3 F3
        a4 s sh                 = 2 a4 x^2 F2

    and the constant ``(a0 + a1)`` takes the factor ``E``.
    """
    F1, F2, F3, F4 = F
    ch, sh, c, s = sp.symbols("ch sh c s")
    arg = x
    e = sp.expand(
        expr.subs(
            {sp.cosh(arg): ch, sp.sinh(arg): sh, sp.cos(arg): c, sp.sin(arg): s},
            simultaneous=True,
        )
    )
    e = sp.expand(e.subs({ch**2: 1 + sh**2, c**2: 1 - s**2}))
    poly = sp.Poly(e, ch, sh, c, s)
    allowed = {(0, 0, 0, 0), (1, 0, 1, 0), (0, 1, 1, 0), (1, 0, 0, 1), (0, 1, 0, 1)}
    extra = {m for m, v in poly.terms() if m not in allowed and sp.simplify(v) != 0}
    if extra:
        raise ValueError(f"unexpected products {extra} in a beam minor")
    a0 = poly.coeff_monomial(1)
    a1 = poly.coeff_monomial(ch * c)
    a2 = poly.coeff_monomial(sh * c)
    a3 = poly.coeff_monomial(ch * s)
    a4 = poly.coeff_monomial(sh * s)
    out = (
        sp.cancel(a0 + a1) * E
        - sp.cancel(2 * a1 * x**4) * F4
        + sp.cancel((a2 + a3) * x) * F1
        + sp.cancel((a3 - a2) * x**3) * F3
        + sp.cancel(2 * a4 * x**2) * F2
    )
    return sp.expand(out)

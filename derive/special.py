"""Reduced beam functions: the transcendental parts of the component matrices, free of cancellation.

The beam matrix of paper Eq. (1) contains ``T/lambda``, ``G/lambda^2``,
``V/lambda^3``; its second compound (the stable formulation) contains
``(1 - c ch)/x^4`` and kin. Printed as they stand these cancel catastrophically
for small ``x = lambda*l``. Every such quantity is written here as an entire
function of ``x^4``:

* ``K0..K3`` (Krylov-Duncan functions divided by ``x^k``)::

      K0 = S = (ch + c)/2          K1 = T/x = (sh + s)/(2x)
      K2 = G/x^2 = (ch - c)/(2x^2) K3 = V/x^3 = (sh - s)/(2x^3)

* ``F1..F4`` (the functions the 2x2 minors of the beam matrix reduce to once
  ``ch^2 - sh^2 = 1`` and ``c^2 + s^2 = 1`` are applied)::

      F1 = (c sh + ch s)/(2x)      F2 = s sh/(2x^2)
      F3 = (ch s - c sh)/(2x^3)    F4 = (1 - c ch)/(2x^4)

Below a threshold ``x0`` each is evaluated by its Taylor series in ``x^4``
(coefficients computed here exactly), above it by the closed form; the compound
functions are returned multiplied by ``exp(-x)`` above ``x0`` so that nothing
overflows at ``x = 1000``.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

x = sp.Symbol("x", positive=True)
ch, sh, c, s = sp.cosh(x), sp.sinh(x), sp.cos(x), sp.sin(x)

#: Below this argument the series is used; above it no closed form loses more
#: than about one digit to cancellation (checked in tests/symbolic).
SERIES_THRESHOLD = 1.5


@dataclass(frozen=True)
class Reduced:
    """An entire function of ``x^4`` given by its closed form."""

    name: str
    closed: sp.Expr

    def series(self, tol: float = 1e-18, x0: float = SERIES_THRESHOLD) -> list[sp.Rational]:
        """Coefficients ``a_n`` of ``f(x) = sum a_n x^(4n)``, enough terms for ``tol`` at ``x0``."""
        coeffs: list[sp.Rational] = []
        order = 8
        while True:
            ser = sp.series(self.closed, x, 0, order).removeO()
            poly = sp.Poly(sp.expand(ser), x)
            coeffs = [sp.Rational(poly.coeff_monomial(x ** (4 * n))) for n in range(order // 4)]
            if any(poly.coeff_monomial(x**j) != 0 for j in range(1, order) if j % 4):
                raise ValueError(f"{self.name} is not a function of x^4")
            last = abs(float(coeffs[-1])) * x0 ** (4 * (len(coeffs) - 1))
            if last < tol * abs(float(coeffs[0])) and len(coeffs) > 2:
                return coeffs[:-1]
            order += 4


KRYLOV = (
    Reduced("K0", (ch + c) / 2),
    Reduced("K1", (sh + s) / (2 * x)),
    Reduced("K2", (ch - c) / (2 * x**2)),
    Reduced("K3", (sh - s) / (2 * x**3)),
)

COMPOUND = (
    Reduced("F1", (c * sh + ch * s) / (2 * x)),
    Reduced("F2", s * sh / (2 * x**2)),
    Reduced("F3", (ch * s - c * sh) / (2 * x**3)),
    Reduced("F4", (1 - c * ch) / (2 * x**4)),
)


def scaled_closed_form(f: Reduced, E: sp.Symbol, chs: sp.Symbol, shs: sp.Symbol) -> sp.Expr:
    """``exp(-x) * f(x)`` with ``chs = exp(-x) cosh x``, ``shs = exp(-x) sinh x``, ``E = exp(-x)``.

    Every compound function is linear in ``(1, cosh, sinh)``, so multiplying by
    ``exp(-x)`` maps ``1 -> E``, ``cosh -> chs``, ``sinh -> shs`` exactly.
    """
    expr = sp.expand(f.closed)
    expr = expr.subs({ch: chs, sh: shs})
    # the terms free of chs and shs were the constants: they take the factor E
    expr = sp.expand(expr)
    free = sum(t for t in sp.Add.make_args(expr) if not t.has(chs) and not t.has(shs))
    return sp.expand(expr - free + E * free)

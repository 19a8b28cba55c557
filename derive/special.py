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
        coeffs = _taylor(self.closed)
        if any(c != 0 for j, c in enumerate(coeffs) if j % 4):
            raise ValueError(f"{self.name} is not a function of x^4")
        quartic = coeffs[::4]
        for n in range(2, len(quartic)):
            if abs(float(quartic[n])) * x0 ** (4 * n) < tol * abs(float(quartic[0])):
                return quartic[:n]
        raise ValueError(f"{self.name}: series too short for tol={tol} at x0={x0}")


#: Degree of the Taylor polynomials substituted for cos, sin, cosh, sinh.
_DEGREE = 64


def _taylor(expr: sp.Expr) -> list[sp.Rational]:
    """Exact Taylor coefficients of ``expr`` (a polynomial in cos, sin, cosh, sinh of x over x^k).

    The four functions are replaced by their Taylor polynomials and the
    numerator is expanded exactly; coefficients beyond what the truncation
    determines are dropped. Much faster than ``sympy.series`` on these products.
    """
    f = sp.factorial
    taylor = {
        sp.cos(x): sum((-1) ** (j // 2) * x**j / f(j) for j in range(0, _DEGREE + 1, 2)),
        sp.sin(x): sum((-1) ** (j // 2) * x**j / f(j) for j in range(1, _DEGREE + 1, 2)),
        sp.cosh(x): sum(x**j / f(j) for j in range(0, _DEGREE + 1, 2)),
        sp.sinh(x): sum(x**j / f(j) for j in range(1, _DEGREE + 1, 2)),
    }
    num, den = sp.fraction(sp.together(expr))
    den_poly = sp.Poly(den, x)
    if len(den_poly.terms()) != 1:
        raise ValueError(f"denominator {den} is not a monomial")
    ((k,), c) = den_poly.terms()[0]
    num_poly = sp.Poly(sp.expand(num.xreplace(taylor)), x)
    return [sp.Rational(num_poly.coeff_monomial(x ** (j + k))) / c for j in range(_DEGREE - k)]


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


#: Below ``leading_threshold`` the first neglected term of every series is under this
#: fraction of its constant term (under a quarter of its ulp: Horner's sum rounds to it).
LEADING_TOLERANCE = 2.0**-56


def leading_threshold(funcs: tuple[Reduced, ...]) -> float:
    """The argument below which every function of ``funcs`` is its constant term in double
    precision: ``|a_1 / a_0| x^4`` (the next term, the rest far smaller) under
    ``LEADING_TOLERANCE`` for each (the pieces between closely spaced components)."""
    ratio = max(abs(float(f.series()[1] / f.series()[0])) for f in funcs)
    return float((LEADING_TOLERANCE / ratio) ** 0.25)


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

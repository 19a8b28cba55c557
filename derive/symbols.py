"""Every name that appears in derived expressions and emitted code is decided here.

Symbols read like the paper: ``omega``, ``lam`` (lambda), ``EI``, ``mbar``,
segment lengths ``l_1..``, spring stiffnesses ``k_1..``, masses ``m_1..``; the
stable formulation works in units ``L = 1``, ``EI = 1`` with ``beta = lam L``,
``rho = l / L``, ``kappa = k L^3 / EI``, ``mu = m / (mbar L)``.
"""

from __future__ import annotations

import sympy as sp

omega = sp.Symbol("omega", positive=True)
lam = sp.Symbol("lam", positive=True)
EI = sp.Symbol("EI", positive=True)
mbar = sp.Symbol("mbar", positive=True)
L = sp.Symbol("L", positive=True)
l = sp.Symbol("l", nonnegative=True)
k = sp.Symbol("k", positive=True)
m = sp.Symbol("m", positive=True)

beta = sp.Symbol("beta", positive=True)
rho = sp.Symbol("rho", nonnegative=True)
kappa = sp.Symbol("kappa", positive=True)
mu = sp.Symbol("mu", positive=True)

#: Argument of the reduced beam functions, ``x = lam l``.
x = sp.Symbol("x", nonnegative=True)
#: Reduced Krylov functions ``K0..K3`` and compound functions ``F1..F4`` (see ``special``).
K = sp.symbols("K0:4")
F = sp.symbols("F1:5")
#: ``exp(-x)`` on the large-argument branch of the compound functions, 1 below it.
E = sp.Symbol("E")

#: Prefix of common-subexpression temporaries in emitted code (``t0, t1, ...``).
CSE_PREFIX = "t"


def lam_of_omega() -> sp.Expr:
    """``lam = (mbar omega^2 / EI)^(1/4)``, paper Eq. (1)."""
    return (mbar * omega**2 / EI) ** sp.Rational(1, 4)


def indexed(name: str, i: int) -> sp.Symbol:
    """The symbol of the ``i``-th (1-based) instance of a parameter, e.g. ``k_2``."""
    base = {"l": l, "k": k, "m": m}[name]
    return sp.Symbol(f"{name}_{i}", **base.assumptions0)

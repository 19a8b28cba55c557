"""Printer of numba source: scalar ``math`` calls, CSE temporaries, one statement per line."""

from __future__ import annotations

from collections.abc import Sequence

import sympy as sp
from sympy.printing.pycode import PythonCodePrinter

from . import symbols


class NumbaPrinter(PythonCodePrinter):
    """Python printer whose output numba compiles in nopython mode (``math.*`` scalars)."""

    def __init__(self) -> None:
        super().__init__({"fully_qualified_modules": True, "standard": "python3"})

    def _print_Rational(self, expr: sp.Rational) -> str:
        return repr(float(expr)) if expr.q != 1 else f"{expr.p}.0"

    def _print_Integer(self, expr: sp.Integer) -> str:
        return f"{int(expr)}.0"

    def _print_Pow(self, expr: sp.Pow, rational: bool = False) -> str:
        base, exp = expr.as_base_exp()
        if exp.is_Integer and 2 <= int(exp) <= 8:
            b = self.parenthesize(base, sp.printing.precedence.PRECEDENCE["Pow"])
            return f"{b}**{int(exp)}"
        if exp == -1:
            return f"1.0/{self.parenthesize(base, sp.printing.precedence.PRECEDENCE['Pow'])}"
        return super()._print_Pow(expr, rational=rational)


class ComplexNumbaPrinter(NumbaPrinter):
    """The same for complex arguments: ``cmath.*`` scalar calls (a damped kernel, and the
    complex beam functions of the frequency response), ``I`` as ``1j``."""

    def _module_format(self, fqn: str, register: bool = True) -> str:
        if fqn.startswith("math."):
            fqn = "c" + fqn
        return super()._module_format(fqn, register)

    def _print_ImaginaryUnit(self, expr: sp.Expr) -> str:
        return "1j"

    def _print_Pow(self, expr: sp.Pow, rational: bool = False) -> str:
        """Small integer powers as products: numba raises a complex number to an integer
        power through exp and log (about 35 ns, ten multiplications' worth)."""
        base, exp = expr.as_base_exp()
        if exp.is_Integer and 2 <= abs(int(exp)) <= 8:
            b = self.parenthesize(base, sp.printing.precedence.PRECEDENCE["Mul"])
            product = "*".join([b] * abs(int(exp)))
            return product if int(exp) > 0 else f"1.0/({product})"
        return super()._print_Pow(expr, rational=rational)


_PRINTER = NumbaPrinter()
_COMPLEX_PRINTER = ComplexNumbaPrinter()


def code(expr: sp.Expr, complex_: bool = False) -> str:
    """Source of one expression (``complex_``: for complex arguments, ``cmath``)."""
    return (_COMPLEX_PRINTER if complex_ else _PRINTER).doprint(expr)


def assignments(
    targets: Sequence[str],
    exprs: Sequence[sp.Expr],
    indent: str = "    ",
    complex_: bool = False,
) -> list[str]:
    """Lines ``t0 = ...`` (common subexpressions) then ``target = expr`` for each target.

    ``sympy.cse`` runs with ``order='none'``: the canonical order grows
    exponentially on nested chain expressions (DESIGN.md, tool-chain facts).
    """
    temps = sp.numbered_symbols(symbols.CSE_PREFIX)
    replacements, reduced = sp.cse(list(exprs), symbols=temps, order="none")
    lines = [f"{indent}{sym} = {code(val, complex_)}" for sym, val in replacements]
    lines += [f"{indent}{t} = {code(e, complex_)}" for t, e in zip(targets, reduced, strict=True)]
    return lines

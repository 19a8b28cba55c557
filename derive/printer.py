"""Printer of numba source: scalar ``math`` calls, CSE temporaries, one statement per line.

Whole functions are printed from SymPy's codegen AST (``sympy.codegen.ast``:
``FunctionDefinition``, ``Assignment``, ``AddAugmentedAssignment``, ``Return``, ``For``);
the AST has loops but no branch, so :class:`If` adds one, :class:`Unpack` assigns a
tuple to several names, and :func:`lit` writes a literal (an integer: the printer writes
SymPy's integers as floats, the expressions being floating point).
"""

from __future__ import annotations

from collections.abc import Sequence

import sympy as sp
from sympy.codegen.ast import Assignment, CodeBlock, Token
from sympy.printing.pycode import PythonCodePrinter

from . import symbols


def _block(statements) -> CodeBlock:
    return statements if isinstance(statements, CodeBlock) else CodeBlock(*statements)


class If(Token):
    """``if condition: body`` (``else: orelse`` when it has statements)."""

    __slots__ = _fields = ("condition", "body", "orelse")
    defaults = {"orelse": CodeBlock()}
    _construct_condition = staticmethod(sp.sympify)
    _construct_body = staticmethod(_block)
    _construct_orelse = staticmethod(_block)


class Unpack(Token):
    """``a, b, ... = value``: a call's tuple unpacked (SymPy's ``Assignment`` has one
    target)."""

    __slots__ = _fields = ("targets", "value")
    _construct_targets = staticmethod(lambda targets: sp.Tuple(*targets))
    _construct_value = staticmethod(sp.sympify)


def lit(k: int | str) -> sp.Symbol:
    """The literal ``k`` as written in code: an integer (an index, a count, a tag: the
    printer writes SymPy's integers as floats) or a typed zero (``"0.0"``, ``"0.0j"``)."""
    return sp.Symbol(str(k), integer=True) if isinstance(k, int) else sp.Symbol(k)


def array(name: str, *shape) -> sp.IndexedBase:
    """An array argument of a printed function (its element ``array(...)[i, j]``); the
    shape only lets an element be the target of an ``Assignment``."""
    return sp.IndexedBase(name, shape=shape or (sp.Symbol("n"),))


def _unwrapped(text: str) -> str:
    """``text`` without the parentheses around all of it (a condition's)."""
    if not (text.startswith("(") and text.endswith(")")):
        return text
    depth = 0
    for i, ch in enumerate(text):
        depth += {"(": 1, ")": -1}.get(ch, 0)
        if depth == 0 and i < len(text) - 1:
            return text  # the first parenthesis closes before the end
    return text[1:-1]


class NumbaPrinter(PythonCodePrinter):
    """Python printer whose output numba compiles in nopython mode (``math.*`` scalars)."""

    def __init__(self) -> None:
        super().__init__(
            {
                "fully_qualified_modules": True,
                "standard": "python3",
                "allow_unknown_functions": True,
            }
        )
        self._index_printer = PythonCodePrinter({"standard": "python3"})

    def _print_Indexed(self, expr) -> str:
        """``a[i, j]``: indices are integers."""
        return f"{expr.base}[{', '.join(self._index_printer.doprint(i) for i in expr.indices)}]"

    def _print_If(self, node: If) -> str:
        cond = _unwrapped(self._print(node.condition))
        out = [f"if {cond}:", self._indent_codestring(self._body(node.body))]
        if node.orelse.args:
            out += ["else:", self._indent_codestring(self._body(node.orelse))]
        return "\n".join(out)

    def _print_Unpack(self, node: Unpack) -> str:
        targets = ", ".join(self._print(t) for t in node.targets)
        return f"{targets} = {self._print(node.value)}"

    def _print_For(self, node) -> str:
        stop = node.iterable.args[1] if node.iterable.args[0] == 0 else node.iterable
        head = f"for {self._print(node.target)} in range({self._index_printer.doprint(stop)}):"
        return head + "\n" + self._indent_codestring(self._body(node.body))

    def _print_FunctionCall(self, node) -> str:
        return f"{node.name}({', '.join(self._print(a) for a in node.function_args)})"

    def _body(self, block: CodeBlock) -> str:
        return "\n".join(self._print(statement) for statement in block.args) or "pass"

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
    complex beam functions of the frequency response), ``I`` as ``1j``; a real target
    (a value loaded from the parameter vector, a count) keeps real arithmetic."""

    def _print_Assignment(self, expr) -> str:
        if isinstance(expr.lhs, sp.Symbol) and expr.lhs.is_real:
            return _PRINTER._print(expr)
        return super()._print_Assignment(expr)

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


def assignment_nodes(targets: Sequence, exprs: Sequence[sp.Expr]) -> list[Assignment]:
    """``t0 = ...`` (common subexpressions) then ``target = expr`` for each target, as
    SymPy's ``Assignment`` statements. ``sympy.cse`` runs with ``order='none'``: the
    canonical order grows exponentially on nested chain expressions (DESIGN.md, tool-chain
    facts)."""
    temps = sp.numbered_symbols(symbols.CSE_PREFIX)
    replacements, reduced = sp.cse(list(exprs), symbols=temps, order="none")
    out = [Assignment(sym, val) for sym, val in replacements]
    return out + [Assignment(t, e) for t, e in zip(targets, reduced, strict=True)]

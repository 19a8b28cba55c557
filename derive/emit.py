"""Emit the generated modules: build their functions as SymPy's codegen AST, print them,
sign them, write them.

``generated/euler_bernoulli.py``: the beam functions every kernel and the shared numerics
use (the reduced functions with their branches: constant terms, series, scaled closed
forms; the transfer matrix and compound step filled from them; the general segment's field
matrices), compiled by ``mstmm.numerics.beam``. A topology's kernel: its per-component
functions (``event_<what>``), one branch per kind present, printed from each kind's
descriptor (a bare beam gets no branch at all); its ends are data (every end pair), and
``lower`` makes its IR (``derive/ir.py``) that ``print_kernel`` prints. The numerics, the
characteristic functions' walk, the scan, the count, the marches, are ordinary code in
``mstmm.numerics``: a kernel binds ``mstmm.numerics.characteristic`` to its printed
functions. The templates (``templates/*.tmpl``) hold the modules' headers only.
"""

from __future__ import annotations

import importlib.metadata
import os
import tempfile
import textwrap
from pathlib import Path
from pprint import pformat
from string import Template

import sympy as sp
from sympy.codegen.ast import (
    AddAugmentedAssignment,
    Assignment,
    For,
    FunctionCall,
    FunctionDefinition,
    NoneToken,
    Return,
    Variable,
)

from mstmm import catalog
from mstmm.catalog import END_CODES, Topology
from mstmm.sign import derive_digest, numerics_digest, signature

from . import descriptor, ir, special
from . import symbols as S
from .printer import If, Unpack, array, assignment_nodes, code, lit
from .segments import euler_bernoulli as beam
from .segments import general

TEMPLATE = Path(__file__).with_name("templates") / "kernel.py.tmpl"
NUMERICS_TEMPLATE = TEMPLATE.with_name("euler_bernoulli.py.tmpl")
#: The characteristic functions a kernel binds (``mstmm.numerics.characteristic``).
FUNCTIONS = {False: "UNDAMPED", True: "DAMPED"}
#: What a kernel's characteristic functions are (the module docstring).
WHAT = {
    False: "``delta_stable`` (default) and ``delta_paper``, whose zeros are the natural"
    " frequencies, and ``count_below``, their number below omega",
    True: "``delta_damped``, whose zeros in the complex plane are the damped natural frequencies",
}


def _series(funcs: tuple[special.Reduced, ...], z: sp.Symbol) -> list:
    """``name = series`` of each reduced function: its Taylor coefficients (exact
    rationals, printed to the nearest double) in Horner form in ``z = x^4``."""
    lines = []
    for f in funcs:
        coeffs = f.series()
        expr = sp.Rational(coeffs[-1])
        for a in reversed(coeffs[:-1]):
            expr = sp.Add(sp.Rational(a), sp.Mul(z, expr, evaluate=False), evaluate=False)
        lines.append(Assignment(sp.Symbol(f.name), expr))
    return lines


def _closed(funcs, scaled: bool, complex_: bool = False) -> list:
    """``name = closed form`` of each beam function (``scaled``: times exp(-x), in terms
    of ``E = exp(-x)``, ``chs``, ``shs``); for a complex argument the negative powers of
    x through one reciprocal ``rx`` (a complex division costs as much as ten
    multiplications), and every sine, cosine and power once (CSE across the functions:
    numba calls ``cmath.sin`` again at each occurrence)."""
    rx = sp.Symbol("rx")
    out: list = [Assignment(rx, 1 / S.x)] if complex_ else []
    names, exprs = [], []
    for f in funcs:
        if scaled:
            E, chs, shs = sp.symbols("E chs shs")
            expr = special.scaled_closed_form(f, E, chs, shs)
        else:
            expr = f.closed
        if complex_:
            expr = expr.replace(
                lambda e: e.is_Pow and e.base == special.x and e.exp.is_negative,
                lambda e: rx ** (-e.exp),
            )
        names.append(sp.Symbol(f.name))
        exprs.append(expr.subs(special.x, S.x))
    return out + assignment_nodes(names, exprs)


def _returns(funcs) -> Return:
    return Return(sp.Tuple(*(sp.Symbol(f.name) for f in funcs)))


def _matrix_fill(M: sp.Matrix, name: str) -> list:
    U = array(name, M.rows, M.cols)
    targets = [U[i, j] for i in range(M.rows) for j in range(M.cols)]
    return assignment_nodes(targets, list(M))


def _compound_step(C: sp.Matrix) -> list:
    """``v <- C v`` for a 6x6 symbolic compound, through CSE'd scalars."""
    v = sp.symbols("v0:6")
    vv = array("v", 6)
    lines: list = [Assignment(v[a], vv[a]) for a in range(6)]
    return lines + assignment_nodes([vv[a] for a in range(6)], list(C * sp.Matrix(v)))


#: The symbols of a kernel's printed functions: the parameter vector ``p``, a component's
#: data block at ``o``, its tag, the units, the frequency (``b4``; complex ``w1``).
p_, o_, tag_ = sp.IndexedBase("p"), sp.Symbol("o", integer=True), sp.Symbol("tag", integer=True)
L_, EI_, mbar_ = sp.symbols("L EI mbar", positive=True)
b4_, w1_ = sp.Symbol("b4"), sp.Symbol("w1")
n_, j_ = sp.Symbol("n", integer=True), sp.Symbol("j", integer=True)
count_, pivot_, own_ = sp.Symbol("count", integer=True), sp.Symbol("pivot"), sp.Symbol("own")
st_ = array("st", 5, n_)


def _call(name: str, *args):
    """A call of a function of the shared numerics (or of another printed function)."""
    return sp.Function(name)(*args)


def _unit_factor(scale) -> sp.Expr:
    """The factor L^a EI^b mbar^c, ``scale = (a, b, c)``, that makes a value of that
    key's unit dimensionless, kept as one factor free of the value: the compiler computes
    it once, outside the event loop."""
    a, b, c = (sp.nsimplify(e) for e in scale)
    factor = L_**a * EI_**b * mbar_**c
    return sp.UnevaluatedExpr(factor) if factor != 1 else sp.Integer(1)


def _value_lines(module, damped: bool = False) -> tuple[list, dict]:
    """Statements loading a kind's scalar values from its data block (at ``o``) in units
    L = EI = mbar = 1 (exponents from each key's unit), and their symbols. Damping values
    (``Key.damping``) only in a damped kernel. For a kind of stages, the values of stage
    ``j`` (the j-th entry of each list; a list is stored after its length ``n``)."""
    lines: list = []
    values = {}
    staged = _staged(module)
    if staged:
        lines.append(Assignment(n_, _call("int", p_[o_])))
    for k, key in enumerate(module.KEYS[1:]):
        if (key.shape == "list") != staged:
            if staged:
                raise descriptor.refusal(module, "a kind of stages has only list keys")
            break
        if key.damping and not damped:
            continue
        name = sp.Symbol(f"val_{key.name}", real=True)
        at = o_ + k * (n_ + 1) + 1 + j_ if staged else o_ + k
        factor = _unit_factor(key.scale)
        lines.append(Assignment(name, p_[at] * factor if factor != 1 else p_[at]))
        values[key.name] = name
    return lines, values


def _staged(module) -> bool:
    """Whether a kind is made of stages in series (it declares ``stage``)."""
    return hasattr(module, "stage")


def _chain_lines(what: str, complex_: bool = False) -> list:
    """The stages of a kind of stages into ``st`` (the kernel's ``event_stages``, at the
    frequency, or at 0 for its own frequencies), then ``mstmm.numerics.chain``'s
    ``what``: the tip condensation, the full descriptor or the own frequencies."""
    w, suffix = (w1_, "_c") if complex_ else (b4_, "")
    if what == "internal":
        w = sp.Float(0.0)
    st = sp.Symbol("st")
    lines = [
        Assignment(st, _call(f"stage_array{suffix}", p_, o_)),
        FunctionCall(f"event_stages{suffix}", [tag_, p_, o_, w, L_, EI_, mbar_, st]),
    ]
    if what == "tip":
        names = sp.symbols("chain_u0 chain_g chain_log own")
        return lines + [Unpack(names, _call("chain_tip", st))]
    if what == "descriptor":
        args = [st] + [sp.Symbol(nm) for nm in ("Cz", "Cq", "A", "B", "qmass")]
        return lines + [Return(_call("chain_descriptor", *args))]
    out = sp.Symbol("out")
    return lines + [Return(_call("chain_internal", st, L_, EI_, mbar_, out, n_))]


def _symbolic_descriptor(module, damped: bool = False) -> tuple[list, descriptor.Descriptor]:
    lines, values = _value_lines(module, damped)
    return lines, descriptor.of(module, values)


def _step_lines(d: descriptor.Descriptor, name: str = "v") -> list:
    vs = sp.symbols("v0:6")
    v = array(name, 6)
    lines: list = [Assignment(vs[a], v[a]) for a in range(6)]
    step = descriptor.compound_step(d, sp.Matrix(vs))
    return lines + assignment_nodes([v[a] for a in range(6)], list(step))


def _tip_lines(complex_: bool = False) -> list:
    """A kind of stages condensed from its tip (``descriptor.chain_reduced``)."""
    return _chain_lines("tip", complex_)


def _stable_lines(module, d: descriptor.Descriptor) -> list:
    """v <- the component's pole-free compound step (docs/components.md); a kind of stages
    returns the log of the factor its condensation took out (dropped, it scaled Delta by a
    power of two that jumps with omega)."""
    if _staged(module):
        return _tip_lines() + _step_lines(d) + [Return(sp.Symbol("chain_log"))]
    return _value_lines(module)[0] + _step_lines(d)


def _damped_lines(module, d: descriptor.Descriptor) -> list:
    """The same in a damped kernel: complex, with the damping values (a kind of stages
    returns the log of the factor its condensation took out)."""
    if _staged(module):
        return _tip_lines(True) + _step_lines(d) + [Return(sp.Symbol("chain_log"))]
    return _value_lines(module, damped=True)[0] + _step_lines(d)


def _counted_lines(module, d: descriptor.Descriptor) -> list:
    """``_count_lines`` as a function's body: returns the negative pivots."""
    lines = _count_lines(module, d)
    if not any(isinstance(s, (If, AddAugmentedAssignment)) for s in lines):
        return lines
    return [Assignment(count_, lit(0))] + lines + [Return(count_)]


def _negative(pivot) -> If:
    """``count += 1`` where ``pivot`` is negative."""
    return If(pivot < 0, [AddAugmentedAssignment(count_, lit(1))])


def _count_lines(module, d: descriptor.Descriptor) -> list:
    """The negative pivots a component adds to the count (``count += ...``), and the
    minors Zc of the node's state subspace carried across it."""
    values = _value_lines(module)[0]
    rule = catalog.count_rule(module)
    if rule == "constraint":
        # the constrained freedoms as a stiffness PENALTY: exact for the inertia count
        A = sp.eye(4) - sp.Symbol("PENALTY") * d.B * d.Cz
        return _step_lines(descriptor.point(A), "Zc")
    step = _step_lines(d, "Zc")
    Zc = array("Zc", 6)
    if rule == "split":
        # a hinge: the rotation left of it is eliminated first, pivot S_theta + kappa
        if d.Cz != descriptor.unit(2).T or d.B != descriptor.unit(1):
            raise descriptor.refusal(module, "COUNT 'split' needs Cz = e_M and B = e_theta")
        pivot = [Assignment(pivot_, (Zc[1] - d.Cq[0, 0] * Zc[0]) * Zc[0])]
        return values + pivot + step + [_negative(pivot_)]
    if d.n_q == 0:
        descriptor.node_stiffness(d)  # checks that it is one
        return values + step
    if _staged(module):  # the negative pivots of its nodes' dynamic stiffness
        return _tip_lines() + step + [AddAugmentedAssignment(count_, own_)]
    _check_pivot(module, d)
    # the unknown's own dynamic stiffness (k - m w^2 for a spring-mass)
    return values + [Assignment(pivot_, -d.Cq[0, 0])] + step + [_negative(pivot_)]


def _check_pivot(module, d: descriptor.Descriptor) -> None:
    """A stiffness kind with unknowns is counted by the pivot ``-Cq``: one unknown, its
    row coupled to the beam's Y or theta alone, and ``-Cq`` of the sign of the unknown's
    own dynamic stiffness ``D_qq``. A kind declared by its energy has its row divided by
    its first stiffness coupling ``K_qb`` (``descriptor.from_energy``: ``qforce`` is
    minus its inverse), so that coupling must be a negative constant (``-k`` for a
    spring; an inerter beside the spring makes the row's ``Cz = 1 - b b4 / k``, which
    is not constant and need not be); a kind in descriptor form says it by a constant
    ``Cz > 0``. Anything else is refused, naming the kind's file and the term."""
    coupled = [j for j in range(4) if d.Cz[0, j] != 0] if d.n_q == 1 else []
    if len(coupled) != 1 or coupled[0] > 1:
        raise descriptor.refusal(
            module,
            f"a stiffness kind with unknowns needs n_q = 1 (it has {d.n_q}) and its row"
            f" coupled to Y or theta alone (Cz = {list(d.Cz)})",
        )
    if hasattr(module, "energy"):
        if not descriptor.positive(d.qforce[0]):
            raise descriptor.refusal(
                module,
                f"the count's pivot -Cq has the sign of the unknown's own dynamic stiffness"
                f" only when its row is divided by a negative constant: its row is divided by"
                f" {-1 / d.qforce[0]} (its first stiffness coupling to the beam,"
                f" K_q{'Y' if coupled[0] == 0 else 'theta'}, or 1 where K has none), which"
                f" is not (a spring gives -k)",
            )
        return
    c = sp.sympify(d.Cz[0, coupled[0]])
    if not (c.is_number and bool(c > 0)):
        raise descriptor.refusal(
            module,
            f"a kind in descriptor form with one unknown needs Cz = c e_Y or c e_theta with"
            f" a constant c > 0 (its row the unknown's equation of motion divided by its"
            f" coupling to the beam); Cz[0, {coupled[0]}] = {c}",
        )


#: The rows of a descriptor's ``qmass`` (``mstmm.numerics.characteristic.QMASS_ROWS``):
#: the mass of each q, its share in a rigid translation, the factor of a force on it, and
#: the mass it shares with the beam's Y and theta (always written: the arrays are reused
#: from one component to the next).
QMASS_ROWS = 5


def _fill_lines(d: descriptor.Descriptor) -> list:
    """Fill Cz, Cq, A, B, qmass from a descriptor; return (constraints, unknowns)."""
    A, Cz, Cq = array("A", 4, 4), array("Cz", 4, 4), array("Cq", 4, 4)
    B, qmass = array("B", 4, 4), array("qmass", QMASS_ROWS, 4)
    targets = [A[r, c] for r in range(4) for c in range(4)]
    exprs = list(d.A)
    for r in range(d.Cz.rows):
        targets += [Cz[r, c] for c in range(4)] + [Cq[r, j] for j in range(d.n_q)]
        exprs += list(d.Cz[r, :]) + list(d.Cq[r, :])
    for j in range(d.n_q):
        targets += [B[r, j] for r in range(4)]
        targets += [qmass[r, j] for r in range(QMASS_ROWS)]
        exprs += list(d.B[:, j]) + [d.qmass[j], d.qpart[j], d.qforce[j], *d.qcouple[j]]
    lines = assignment_nodes(targets, [sp.sympify(e) for e in exprs])
    return lines + [Return(sp.Tuple(lit(d.Cz.rows), lit(d.n_q)))]


def _descriptor_lines(module, d: descriptor.Descriptor) -> list:
    """Fill Cz, Cq, A, B, qmass (units L = EI = mbar = 1); return (constraints, unknowns)."""
    if _staged(module):
        return _chain_lines("descriptor")
    return _value_lines(module)[0] + _fill_lines(d)


def _descriptor_c_lines(damped: bool):
    """The complex descriptor at the complex frequency w1 (b4 = w1^2); with the damping
    values in a damped kernel (the frequency response and damped shapes of any kernel)."""

    def body(module, d: descriptor.Descriptor) -> list:
        if _staged(module):
            return _chain_lines("descriptor", complex_=True)
        values, symbols = _value_lines(module, damped)
        d = descriptor.of(module, symbols)
        return values + [Assignment(b4_, w1_ * w1_)] + _fill_lines(d)

    return body


def _internal_lines(module, d: descriptor.Descriptor) -> list:
    """Append the component's own frequencies (rad/s) to out[n:]; return n."""
    if _staged(module):
        return _chain_lines("internal")
    roots = descriptor.internal_b4(d)
    if not roots:
        return [Return(n_)]
    lines = _value_lines(module)[0]
    out = array("out", n_)
    for r in roots:
        # positive and finite (NaN fails both comparisons)
        lines += [
            Assignment(b4_, r),
            If(
                sp.And(b4_ > 0, b4_ < sp.oo),
                [
                    Assignment(out[n_], sp.sqrt(b4_ * EI_ / mbar_) / L_**2),
                    AddAugmentedAssignment(n_, lit(1)),
                ],
            ),
        ]
    return lines + [Return(n_)]


def _nq_lines(module, d: descriptor.Descriptor) -> list:
    return [Return(_call("int", p_[o_]) if _staged(module) else lit(d.n_q))]


def _inertia_lines(module, d: descriptor.Descriptor) -> list:
    """Fill Mp (3 x 2) with the mass matrix the component holds on [Y, theta] and the
    participation row of its couplings (``descriptor.inertia_rows``); return 1, or 0
    where it holds none."""
    if _staged(module):
        return [Return(lit(0))]
    M = descriptor.inertia_rows(d)
    if M == sp.zeros(3, 2):
        return [Return(lit(0))]
    Mp = array("Mp", 3, 2)
    lines = assignment_nodes([Mp[r, c] for r in range(3) for c in range(2)], list(M))
    return _value_lines(module)[0] + lines + [Return(lit(1))]


#: Flags of ``event_rigid``: the kinematic constraint a component puts on rigid motions.
RIGID_FLAGS = {"Y": 1, "theta": 2, "kink_if_free": 3}


def _rigid_lines(module, d: descriptor.Descriptor) -> list:
    rigid = descriptor.rigid_of(module, _value_lines(module)[1])
    if not rigid:
        return [Return(lit(0))]
    if len(rigid) != 1 or rigid[0] not in RIGID_FLAGS:
        raise descriptor.refusal(module, f"RIGID must be one of {tuple(RIGID_FLAGS)} or empty")
    if rigid[0] == "kink_if_free":  # the spring across the released rotation
        key = getattr(module, "RELEASES", ("theta", module.KEYS[1].name))[1]
        at = [k.name for k in module.KEYS[1:]].index(key)
        free = sp.Eq(p_[o_ + at], 0)
        return [Return(sp.Piecewise((lit(3), free), (lit(0), True)))]
    return [Return(lit(RIGID_FLAGS[rigid[0]]))]


def _damps_lines(module, d: descriptor.Descriptor) -> list:
    """A damper's constraint on rigid motions at w = 0 (a grounded dashpot dissipates
    unless Y = 0 there), derived from the kind's damping (``descriptor.damps_of``)."""
    damps = descriptor.damps_of(module, _value_lines(module, damped=True)[1])
    if not damps:
        return [Return(lit(0))]
    if damps not in (("Y",), ("theta",)):
        raise descriptor.refusal(module, "its damping holds ('Y',), ('theta',) or nothing")
    return [Return(lit(RIGID_FLAGS[damps[0]]))]


_DESCRIPTOR_ARGS = "p, o, b4, L, EI, mbar, Cz, Cq, A, B, qmass"
_DESCRIPTOR_C_ARGS = "p, o, w1, L, EI, mbar, Cz, Cq, A, B, qmass"
#: ``event_chain``'s arguments, the same in a real and in a damped kernel (one walk,
#: ``numerics.characteristic.delta_chain``, calls both).
CHAIN_ARGS = "p, o, v, w1, b4, L, EI, mbar"


def dispatch_table(damped: bool) -> tuple:
    """The kernel's dispatch functions ``event_<what>(tag, ...)`` (what each does:
    ``mstmm.numerics.characteristic``): arguments, the branch of each kind present
    (printed from its descriptor), the value for no branch, and whether complex. A
    damped kernel has no real descriptor and no own frequencies (its undamped twin's
    kernel has them)."""
    zero, zeros = lit(0), sp.Tuple(lit(0), lit(0))
    common = (
        ("descriptor_c", _DESCRIPTOR_C_ARGS, _descriptor_c_lines(damped), zeros, True),
        ("nq", "p, o", _nq_lines, zero, False),
        ("rigid", "p, o", _rigid_lines, zero, False),
        ("damps", "p, o", _damps_lines, zero, False),
    )
    if damped:
        return (("chain", CHAIN_ARGS, _damped_lines, lit("0.0j"), True), *common)
    return (
        ("chain", CHAIN_ARGS, _stable_lines, lit("0.0"), False),
        ("count", "p, o, Zc, b4, L, EI, mbar", _counted_lines, zero, False),
        (
            "descriptor",
            "p, o, b4, L, EI, mbar, Cz, Cq, A, B, qmass",
            _descriptor_lines,
            zeros,
            False,
        ),
        ("inertia", "p, o, L, EI, mbar, Mp", _inertia_lines, zero, False),
        ("internal", "p, o, L, EI, mbar, out, n", _internal_lines, n_, False),
        *common,
    )


def _parsed(kinds: tuple[str, ...], damped: bool = False) -> list:
    """``(kind, module, descriptor)`` of each kind present, in tag order (a damped
    kernel's descriptors carry the damping values; a kind of stages is condensed from
    its tip at run time, ``descriptor.chain_reduced``)."""
    out = []
    for k in kinds:
        module = catalog.kind(k)
        if _staged(module):
            out.append((k, module, descriptor.chain_reduced()))
        else:
            out.append((k, module, _symbolic_descriptor(module, damped)[1]))
    return out


def _stage_lines(damped: bool, complex_: bool):
    """The body of ``event_stages``: each stage j of a kind of stages into ``st[:, j]`` as
    ``(a, b, c, s1, m)`` (``descriptor.stage_parts`` of its declared ``stage``)."""

    def body(module, d: descriptor.Descriptor) -> list | None:
        if not _staged(module):
            return None
        values, symbols = _value_lines(module, damped)
        with sp.evaluate(True):
            parts = descriptor.stage_parts(module.stage(symbols))
        targets = [st_[r, j_] for r in range(5)]
        inner = values[1:] + assignment_nodes(targets, [sp.sympify(e) for e in parts])
        head = values[:1] + ([Assignment(b4_, w1_ * w1_)] if complex_ else [])
        return head + [For(j_, sp.Range(n_), inner)]

    return body


def _function(name: str, args: str, body: list, complex_: bool) -> str:
    """A printed function (SymPy's ``FunctionDefinition``), real or complex arithmetic."""
    params = [Variable(sp.Symbol(a.strip())) for a in args.split(",")]
    fd = FunctionDefinition(NoneToken(), name, params, body)
    return code(fd, complex_)


def _stage_functions(parsed: list, damped: bool) -> list[ir.FunctionIR]:
    """``event_stages`` (real; not in a damped kernel) and ``event_stages_c`` (complex):
    the stages of the kinds of stages present, what the chain numerics take; nothing for
    a topology without such a kind."""
    if not any(_staged(module) for _, module, _ in parsed):
        return []
    out = []
    for complex_ in (False, True) if not damped else (True,):
        suffix, w = ("_c", "w1") if complex_ else ("", "b4")
        branches = _branches(parsed, _stage_lines(damped, complex_))
        params = ("tag", "p", "o", w, "L", "EI", "mbar", "st")
        out.append(ir.FunctionIR(f"event_stages{suffix}", params, branches, None, complex_))
    return out


def _branches(parsed: list, body) -> tuple:
    """``(tag, statements)`` of each kind present (tags are its index in the kernel's
    ``KINDS``), its statements made from the kind's descriptor by ``body`` (none where
    ``body`` gives None)."""
    out = []
    for t, (_, module, d) in enumerate(parsed):
        body_lines = body(module, d)
        if body_lines is not None:
            out.append((t, tuple(body_lines)))
    return tuple(out)


def _functions(parsed: list, damped: bool = False) -> list[ir.FunctionIR]:
    """``event_<what>(tag, ...)``: one branch per kind present (none for a bare beam), each
    inline (one compiled function per entry, not per kind: compile time); the
    characteristic functions call them at each component (they compile them:
    ``mstmm.numerics.characteristic.bind_characteristic``)."""
    out = []
    for what, args, body, tail, complex_ in dispatch_table(damped):
        params = ("tag", *(a.strip() for a in args.split(",")))
        branches = _branches(parsed, body)
        out.append(ir.FunctionIR(f"event_{what}", params, branches, tail, complex_ or damped))
    return _stage_functions(parsed, damped) + out


def print_function(f: ir.FunctionIR) -> str:
    """A function of the IR printed: ``if tag == t:`` and its statements for each branch,
    then its tail returned (SymPy's ``FunctionDefinition``, real or complex arithmetic)."""
    body: list = [If(sp.Eq(tag_, lit(t)), list(lines)) for t, lines in f.branches]
    if f.tail is not None:
        body.append(Return(f.tail))
    return _function(f.name, ", ".join(f.params), body, f.complex_)


def _parameter_doc(topology: Topology) -> str:
    parts = [
        f"[L, EI_0, mbar_0, n_seg, n_ev, left end, right end (codes of {END_CODES}),"
        " (x_end, EI, mbar, eta, *terms) per segment (SEGMENT_COLUMNS), (tag, x, offset) per"
        " component sorted by x, data blocks (DATA_BLOCKS)]"
    ]
    for t, name in enumerate(topology.kinds):
        keys = ", ".join(
            f"{k.name}{'[]' if k.shape == 'list' else ''} ({k.unit})"
            for k in catalog.kind(name).KEYS[1:]
        )
        parts.append(f"tag {t} = {name}: {keys or 'no values'}")
    return "; ".join(parts)


def _tiny_series_closed(funcs, complex_: bool, scaled: bool, head: tuple) -> list:
    """The body of a beam function of ``funcs``: below ``*_TINY`` (real only) the
    constant terms, below ``SERIES_THRESHOLD`` (of |x| when complex) the series in
    z = x^4, above it the closed forms (``scaled``: times exp(-x), whose exponent is
    returned first as the shift); ``head`` what the tuple returned starts with below the
    threshold (the shift 0 and, for the compound functions, E = 1)."""
    x = sp.Symbol("x")
    z, x2 = sp.symbols("z x2")
    names = tuple(sp.Symbol(f.name) for f in funcs)
    prefix = "KRYLOV" if funcs is special.KRYLOV else "COMPOUND"
    body: list = []
    if not complex_:
        leading = [lit(repr(float(f.series()[0]))) for f in funcs]
        body.append(If(x < sp.Symbol(f"{prefix}_TINY"), [Return(sp.Tuple(*head, *leading))]))
        quartic = [Assignment(z, x**4)]
        small = x < sp.Symbol("SERIES_THRESHOLD")
    else:
        quartic = [Assignment(x2, x * x), Assignment(z, x2 * x2)]  # not through exp and log
        small = sp.Abs(x) < sp.Symbol("SERIES_THRESHOLD")
    series = quartic + _series(funcs, z) + [Return(sp.Tuple(*head, *names))]
    body.append(If(small, series))
    tail = []
    if scaled:
        E, chs, shs = sp.symbols("E chs shs")
        exp = sp.Function("cmath.exp" if complex_ else "math.exp")
        body += [
            Assignment(E, exp(-x)),
            Assignment(chs, sp.Rational(1, 2) + E * E / 2),
            Assignment(shs, sp.Rational(1, 2) - E * E / 2),
        ]
        tail = [x] + ([E] if len(head) > 1 else [])
    body += _closed(funcs, scaled, complex_)
    return body + [Return(sp.Tuple(*tail, *names))]


def _beam_functions() -> list[tuple[str, str, list, bool]]:
    """The printed beam functions: ``(name, arguments, body, complex)``. What composes
    the reduced functions (series, closed form, scaling) is printed with them; the count
    of a clamped piece and the general segment's switch are ordinary code
    (``mstmm.numerics.beam``, which compiles these)."""
    C_beam = beam.compound_nondimensional(S.beta, S.rho, S.E, S.F)
    U_paper = beam.transfer_matrix(S.lam, S.l, S.EI)
    U_nd = beam.transfer_matrix_nondimensional(S.beta, S.rho, S.K)
    K, F = special.KRYLOV, special.COMPOUND
    f = special.Reduced("f", beam.clamped_clamped_equation(special.x))
    fields = "e, m, w2, kGA, rhoI, t, r, k_w, A"
    zero, zero_c, one_c = lit("0.0"), lit("0.0j"), lit("1.0 + 0.0j")
    x, shift, E = sp.symbols("x shift E")
    Ks = [sp.Symbol(k.name) for k in K]
    Fs = [sp.Symbol(k.name) for k in F]
    out = [
        ("krylov", "x", _tiny_series_closed(K, False, False, ()), False),
        ("krylov_scaled", "x", _tiny_series_closed(K, False, True, (zero,)), False),
        ("compound_krylov", "x", _tiny_series_closed(F, False, True, (zero, lit("1.0"))), False),
        ("beam_transfer", "lam, l, EI, U", _matrix_fill(U_paper, "U"), False),
        ("krylov_c", "x", _tiny_series_closed(K, True, False, ()), True),
        ("krylov_scaled_c", "x", _tiny_series_closed(K, True, True, (zero_c,)), True),
        ("compound_krylov_c", "x", _tiny_series_closed(F, True, True, (zero_c, one_c)), True),
    ]
    fill, step = _matrix_fill(U_nd, "U"), _compound_step(C_beam)
    for c, suffix in ((False, ""), (True, "_c")):
        transfer = [Unpack([shift, *Ks], sp.Function(f"krylov_scaled{suffix}")(S.beta * S.rho))]
        compound = [
            Assignment(x, S.beta * S.rho),
            Unpack([shift, E, *Fs], sp.Function(f"compound_krylov{suffix}")(x)),
        ]
        out += [
            (f"beam_transfer_scaled{suffix}", "beta, rho, U", transfer + fill + [Return(shift)], c),
            (f"beam_compound_step{suffix}", "v, beta, rho", compound + step + [Return(shift)], c),
        ]
    kY, kT = sp.symbols("kY kT")
    A = sp.eye(4)
    A[3, 0] = -kY
    A[2, 1] = kT
    out += [
        ("clamped_clamped_sign", "x, E, chs, shs", _closed((f,), True) + [_returns((f,))], False),
        ("node_stiffness_step", "Zc, kY, kT", _step_lines(descriptor.point(A), "Zc"), False),
        ("general_field_rigid", fields, _general_field_lines(shear=False), False),
        ("general_field_shear", fields, _general_field_lines(shear=True), False),
    ]
    return out


def numerics_source() -> str:
    """The source of the printed beam functions every kernel and the shared numerics use
    (``generated/euler_bernoulli.py``; the numerics themselves, and what composes these
    functions, are ordinary code in ``mstmm.numerics``)."""
    K, F = special.KRYLOV, special.COMPOUND
    constants = [
        Assignment(sp.Symbol("SERIES_THRESHOLD"), sp.Float(special.SERIES_THRESHOLD)),
        Assignment(sp.Symbol("KRYLOV_TINY"), sp.Rational(special.leading_threshold(K))),
        Assignment(sp.Symbol("COMPOUND_TINY"), sp.Rational(special.leading_threshold(F))),
    ]
    printed = ["\n".join(code(c) for c in constants)]
    printed += [_function(*fn) for fn in _beam_functions()]
    values = dict(
        threshold=repr(special.SERIES_THRESHOLD),
        digest=derive_digest(),
        sympy_version=importlib.metadata.version("sympy"),
        printed="\n\n\n".join(printed),
    )
    return _clean(Template(NUMERICS_TEMPLATE.read_text()).substitute(values))


def _general_field_lines(shear: bool) -> list:
    """``A`` of the general segment's differential equation (``general.field``), filled
    entry by entry from its dimensionless values."""
    names = ("e", "m", "w2", "kGA", "rhoI", "t", "r", "k_w")
    v = dict(zip(names, sp.symbols(names)))
    values = {"EI": v["e"], "mbar": v["m"], **v, "kGA": v["kGA"] if shear else None}
    A = general.field(values)
    # the shared exponential (numerics.segment: field_prepare, field_exp) computes only the
    # entries a field of this zero pattern has: A where i + j is odd, A^2 where it is even
    even = [A[i, j] for i in range(4) for j in range(4) if (i + j) % 2 == 0]
    if any(sp.simplify(a) != 0 for a in even):
        raise ValueError("a segment's field matrix must vanish where i + j is even")
    return _matrix_fill(A, "A")


def _clean(text: str) -> str:
    return "\n".join(line.rstrip() for line in text.splitlines()) + "\n"


def regenerate_command(topology: Topology) -> str:
    """Shell command that writes this kernel again."""
    return f"python -m mstmm.derive --topology {topology.kernel_key} --out DIR"


def lower(topology: Topology) -> ir.KernelIR:
    """The IR of the kernel of ``topology`` (:mod:`mstmm.derive.ir`): every decision SymPy
    makes about it, nothing printed yet. Real for an undamped topology, complex for a
    damped one; the ends are not in it (they are data)."""
    kinds = topology.kinds
    damped = topology.damped
    parsed = _parsed(kinds, damped)
    functions = tuple(_functions(parsed, damped))  # first: what a kind cannot carry is refused
    blocks = catalog.data_blocks(kinds)
    kind_irs = []
    for t, (name, module, d) in enumerate(parsed):
        staged = _staged(module)
        inertia = sp.zeros(3, 2) if staged else descriptor.inertia_rows(d)
        values = _value_lines(module, damped=True)[1]
        damper = descriptor.damper_of(module, values)
        own = descriptor.own_masses_of(module, values)
        file = catalog.kind_file(name)
        kind_irs.append(ir.KindIR(name, t, file, staged, d, inertia, damper, own, blocks[name]))
    kinds_text = (
        "point components of the kinds " + ", ".join(kinds) if kinds else "no point components"
    )
    about = (
        f"A beam carrying {kinds_text}, at any end conditions (they are data: the parameter"
        " vector's head): each kind's branch of the events of"
        " ``mstmm.numerics.characteristic``, printed by SymPy from its declared physics"
        " (paper Eqs. (2)-(3)); the last line compiles them with the characteristic"
        f" functions ({WHAT[damped]})."
    )
    return ir.KernelIR(
        key=topology.kernel_key,
        signature=signature(topology),
        numerics=numerics_digest(),
        damped=damped,
        kinds=tuple(kind_irs),
        functions=functions,
        segment_columns=catalog.segment_columns(),
        data_blocks=blocks,
        end_codes=END_CODES,
        about=about,
        parameter_doc=_parameter_doc(topology),
        regenerate=regenerate_command(topology),
        bind=FUNCTIONS[damped],
    )


def print_kernel(kernel: ir.KernelIR) -> str:
    """The complete source of a kernel module printed from its IR (it imports the shared
    numerics, ``numerics_source``); nothing is decided here."""
    values = dict(
        key=kernel.key,
        about=textwrap.fill(kernel.about, 90, break_on_hyphens=False),
        kinds=repr(tuple(k.name for k in kernel.kinds)),
        dampers=repr(kernel.dampers),
        segment_columns=pformat(kernel.segment_columns, width=92),
        data_blocks=pformat(kernel.data_blocks, width=92),
        parameter_doc=kernel.parameter_doc,
        regenerate=kernel.regenerate,
        sympy_version=importlib.metadata.version("sympy"),
        signature=kernel.signature,
        digest=kernel.numerics,
        printed="\n\n\n".join(
            [*(print_function(f) for f in kernel.functions), print_own_masses(kernel)]
        ),
        functions=kernel.bind,
    )
    return _clean(Template(TEMPLATE.read_text()).substitute(values))


def print_own_masses(kernel: ir.KernelIR) -> str:
    """``own_masses(kind, v)``: the own masses (units L = EI_0 = mbar_0 = 1) of the unknowns
    a ``carried`` damper of ``kind`` moves, from its values ``v`` (key -> value in those
    units; a stage's for a kind of stages), as :attr:`ir.KernelIR.own_masses` holds them."""
    lines = [
        "def own_masses(kind, v):",
        '    """The own mass of each unknown a damper of ``kind`` moves (the Schur complement',
        "    of its mass matrix; units L = EI_0 = mbar_0 = 1) from its values ``v`` in those",
        '    units: the proved decay bound\'s m_a (``mstmm.decay_bound``)."""',
    ]
    for name, masses in kernel.own_masses.items():
        lines.append(f"    if kind == {name!r}:")
        used = sorted({s.name for m in masses for s in m.free_symbols})
        lines += [f"        {u} = v[{u.removeprefix('val_')!r}]" for u in used]
        codes = [sp.pycode(m) for m in masses]
        lines.append(f"        return ({', '.join(codes)}{',' if len(codes) == 1 else ''})")
    lines.append("    return ()")
    return "\n".join(lines)


def kernel_source(topology: Topology) -> str:
    """The complete source of the kernel module of ``topology``: its IR (:func:`lower`),
    printed (:func:`print_kernel`)."""
    return print_kernel(lower(topology))


def _write_atomically(source: str, path: Path) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".tmp-", suffix=".py")
    try:
        with os.fdopen(fd, "w") as fh:
            fh.write(source)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path


#: The printed module of the beam functions, in ``generated/``.
NUMERICS_MODULE = "euler_bernoulli.py"


def write_numerics(directory: Path) -> Path:
    """Write the printed beam functions (``euler_bernoulli.py``) into ``directory``."""
    return _write_atomically(numerics_source(), Path(directory) / NUMERICS_MODULE)


def write_kernel(topology: Topology, directory: Path, name: str | None = None) -> Path:
    """Derive the kernel of ``topology`` and write it atomically into ``directory`` (as
    ``name``, default ``<key>_<signature[:16]>.py``); returns its path."""
    directory = Path(directory)
    path = directory / (name or f"{topology.kernel_key}_{signature(topology)[:16]}.py")
    return _write_atomically(kernel_source(topology), path)

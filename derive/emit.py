"""Emit the numba kernel module of a topology: fill the template, sign it, write it.

Two templates: ``templates/euler_bernoulli.py.tmpl``, the beam functions every kernel and
the shared numerics use (printed once into ``generated/euler_bernoulli.py``); and
``templates/kernel.py.tmpl``, a topology's per-component functions (``event_<what>``) with
one branch per kind present, printed from each kind's descriptor (a bare beam gets no
branch at all). The numerics, the characteristic functions' walk, the scan, the count,
the marches, are ordinary code in ``mstmm.numerics``: a kernel binds
``mstmm.numerics.characteristic`` to its printed functions.
"""

from __future__ import annotations

import importlib.metadata
import os
import tempfile
from pathlib import Path
from string import Template

import sympy as sp

from mstmm import catalog
from mstmm.catalog import KNOWN_ZERO, Topology, unknown
from mstmm.sign import derive_digest, numerics_digest, signature

from . import descriptor, special
from . import symbols as S
from .compound import pair_index
from .printer import assignments, code
from .segments import euler_bernoulli as beam
from .segments import general

TEMPLATE = Path(__file__).with_name("templates") / "kernel.py.tmpl"
NUMERICS_TEMPLATE = TEMPLATE.with_name("euler_bernoulli.py.tmpl")
#: The characteristic functions a kernel binds (``mstmm.numerics.characteristic``).
FUNCTIONS = {False: "UNDAMPED", True: "DAMPED"}
#: What each kind of kernel's functions are (the module docstring).
WHAT = {
    False: """
* ``delta_paper``: det U_bar(omega), paper Eqs. (1)-(4): the tree algorithm with every
  component's unknowns and geometric equations (its descriptor), the boundary reduction,
  an LU determinant (units L = EI_0 = mbar_0 = 1);
* ``delta_stable`` (default): the same roots from the second-compound chain in
  units L = 1, EI_0 = 1, reduced beam functions (series below x = $threshold),
  every component's pole factor multiplied out exactly once, renormalised (by powers of
  two) whenever its largest minor leaves [2^-20, 2^20].

Both return ``(mantissa, log)`` with value ``mantissa * exp(log)``.
``count_below`` is the number of natural frequencies below omega (Wittrick-Williams:
clamped-piece counts plus the negative pivots of the dynamic stiffness, eliminated node
by node on the minors of the state subspace; each component adds its own), independent
of both.""",
    True: """
* ``delta_damped``: the second-compound chain of the undamped kernels in complex
  arithmetic at a complex frequency w = w_d + i sigma (time dependence exp(i w t)): the
  dashpots' forces i w c, each segment's loss factor as EI (1 + i eta), reduced beam
  functions (series below |x| = $threshold), pole factors multiplied out once; its
  ``(mantissa, log)`` are complex and mantissa * exp(log) is entire in w. The damped
  search counts its zeros by the argument principle (``mstmm.damped``).""",
}


def _indent(lines: list[str], n: int) -> str:
    pad = " " * n
    return "\n".join(pad + line if line.strip() else "" for line in lines)


def _series_lines(funcs: tuple[special.Reduced, ...]) -> list[str]:
    """Horner evaluation in ``z = x^4`` of each reduced function's Taylor series."""
    lines = []
    for f in funcs:
        coeffs = [repr(float(a)) for a in f.series()]
        expr = coeffs[-1]
        for a in reversed(coeffs[:-1]):
            expr = f"{a} + z * ({expr})"
        lines.append(f"{f.name} = {expr}")
    return lines


def _closed_lines(funcs, scaled: bool, complex_: bool = False) -> list[str]:
    """``name = closed form`` of each beam function; for a complex argument the negative
    powers of x through one reciprocal ``rx`` (a complex division costs as much as ten
    multiplications), and every sine, cosine and power once (CSE across the functions:
    numba calls ``cmath.sin`` again at each occurrence)."""
    out = ["rx = 1.0 / x"] if complex_ else []
    rx = sp.Symbol("rx")
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
        names.append(f.name)
        exprs.append(expr.subs(special.x, S.x))
    return out + assignments(names, exprs, indent="", complex_=complex_)


def _clamped_clamped_lines() -> list[str]:
    """``f = exp(-x) (1 - cos x cosh x)``, its sign is that of the equation."""
    E, chs, shs = sp.symbols("E chs shs")
    f = special.Reduced("f", beam.clamped_clamped_equation(special.x))
    expr = special.scaled_closed_form(f, E, chs, shs)
    return [f"f = {code(expr.subs(special.x, S.x))}"]


def _matrix_fill(M: sp.Matrix, name: str, complex_: bool = False) -> list[str]:
    targets = [f"{name}[{i}, {j}]" for i in range(M.rows) for j in range(M.cols)]
    return assignments(targets, list(M), indent="", complex_=complex_)


def _compound_step(C: sp.Matrix, complex_: bool = False) -> list[str]:
    """``v <- C v`` for a 6x6 symbolic compound, through CSE'd scalars."""
    v = sp.symbols("v0:6")
    lines = [f"v{a} = v[{a}]" for a in range(6)]
    products = list(C * sp.Matrix(v))
    lines += assignments([f"v[{a}]" for a in range(6)], products, indent="", complex_=complex_)
    return lines


def _unit_factor(scale) -> str:
    """`` * (L * L / EI)``-style factor making a value of unit exponents ``scale`` (of L,
    EI_0, mbar_0) dimensionless; half powers as ``math.sqrt`` (a dashpot's N s/m)."""
    num: list[str] = []
    den: list[str] = []
    roots_num: list[str] = []
    roots_den: list[str] = []
    for name, e in zip(("L", "EI", "mbar"), scale):
        whole, half = int(abs(e)), abs(e) - int(abs(e))
        (num if e > 0 else den).extend([name] * whole)
        if half:
            (roots_num if e > 0 else roots_den).append(name)
    if roots_num:
        num.append(f"math.sqrt({' * '.join(roots_num)})")
    if roots_den:
        den.append(f"math.sqrt({' * '.join(roots_den)})")
    # one factor, free of the value: the compiler computes it once, outside the event loop
    factor = " * ".join(num) if num else "1.0"
    if den:
        factor += " / " + (den[0] if len(den) == 1 else "(" + " * ".join(den) + ")")
    if factor == "1.0":
        return ""
    return f" * ({factor})" if " " in factor else f" * {factor}"


def _value_lines(module, damped: bool = False) -> tuple[list[str], dict]:
    """Lines loading a kind's scalar values from its data block (at ``o``) in units
    L = EI = mbar = 1 (exponents from each key's unit), and their symbols. Damping values
    (``Key.damping``) only in a damped kernel. For a kind of stages, the values of stage
    ``j`` (the j-th entry of each list; a list is stored after its length ``n``)."""
    lines = []
    values = {}
    staged = _staged(module)
    if staged:
        lines.append("n = int(p[o])")
    for j, key in enumerate(module.KEYS[1:]):
        if (key.shape == "list") != staged:
            if staged:
                raise ValueError(f"{module.KIND}: a kind of stages has only list keys")
            break
        if key.damping and not damped:
            continue
        name = f"val_{key.name}"
        at = f"o + {j} * (n + 1) + 1 + j" if staged else f"o + {j}"
        lines.append(f"{name} = p[{at}]{_unit_factor(key.scale)}")
        values[key.name] = sp.Symbol(name, real=True)
    return lines, values


def _staged(module) -> bool:
    """Whether a kind is made of stages in series (it declares ``stage``)."""
    return hasattr(module, "stage")


def _chain_lines(what: str, complex_: bool = False) -> list[str]:
    """The stages of a kind of stages into ``st`` (the kernel's ``event_stages``, at the
    frequency, or at 0 for its own frequencies), then ``mstmm.numerics.chain``'s
    ``what``: the tip condensation, the full descriptor or the own frequencies."""
    w, suffix, dtype = ("w1", "_c", "np.complex128") if complex_ else ("b4", "", "np.float64")
    if what == "internal":
        w = "0.0"
    lines = [
        f"st = np.empty((5, int(p[o])), dtype={dtype})",
        f"event_stages{suffix}(tag, p, o, {w}, L, EI, mbar, st)",
    ]
    call = {
        "tip": "chain_u0, chain_g, chain_log, own = chain_tip(st)",
        "descriptor": "return chain_descriptor(st, Cz, Cq, A, B, qmass)",
        "internal": "return chain_internal(st, L, EI, mbar, out, n)",
    }[what]
    return lines + [call]


def _symbolic_descriptor(module, damped: bool = False) -> tuple[list[str], descriptor.Descriptor]:
    lines, values = _value_lines(module, damped)
    return lines, descriptor.of(module, values)


def _step_lines(d: descriptor.Descriptor, name: str = "v", complex_: bool = False) -> list[str]:
    vs = sp.symbols("v0:6")
    lines = [f"v{a} = {name}[{a}]" for a in range(6)]
    step = descriptor.compound_step(d, sp.Matrix(vs))
    targets = [f"{name}[{a}]" for a in range(6)]
    lines += assignments(targets, list(step), indent="", complex_=complex_)
    return lines


def _tip_lines(complex_: bool = False) -> list[str]:
    """A kind of stages condensed from its tip (``descriptor.chain_reduced``)."""
    return _chain_lines("tip", complex_)


def _stable_lines(module, d: descriptor.Descriptor) -> list[str]:
    """v <- the component's pole-free compound step (docs/components.md)."""
    if _staged(module):
        return _tip_lines() + _step_lines(d)
    return _value_lines(module)[0] + _step_lines(d)


def _damped_lines(module, d: descriptor.Descriptor) -> list[str]:
    """The same in a damped kernel: complex, with the damping values (a kind of stages
    returns the log of the factor its condensation took out)."""
    if _staged(module):
        return _tip_lines(True) + _step_lines(d, complex_=True) + ["return chain_log"]
    return _value_lines(module, damped=True)[0] + _step_lines(d, complex_=True)


def _counted_lines(module, d: descriptor.Descriptor) -> list[str]:
    """``_count_lines`` as a function's body: returns the negative pivots."""
    lines = _count_lines(module, d)
    if not any("count +=" in line for line in lines):
        return lines
    return ["count = 0"] + lines + ["return count"]


def _count_lines(module, d: descriptor.Descriptor) -> list[str]:
    """The negative pivots a component adds to the count (``count += ...``), and the
    minors Zc of the node's state subspace carried across it."""
    values = _value_lines(module)[0]
    rule = catalog.count_rule(module)
    if rule == "constraint":
        # the constrained freedoms as a stiffness PENALTY: exact for the inertia count
        A = sp.eye(4) - sp.Symbol("PENALTY") * d.B * d.Cz
        return _step_lines(descriptor.point(A), "Zc")
    step = _step_lines(d, "Zc")
    if rule == "split":
        # a hinge: the rotation left of it is eliminated first, pivot S_theta + kappa
        if d.Cz != descriptor.unit(2).T or d.B != descriptor.unit(1):
            raise ValueError(f"{module.KIND}: COUNT 'split' needs Cz = e_M and B = e_theta")
        pivot = [f"pivot = (Zc[1] - ({code(d.Cq[0, 0])}) * Zc[0]) * Zc[0]"]
        return values + pivot + step + ["if pivot < 0.0:", "    count += 1"]
    if d.n_q == 0:
        descriptor.node_stiffness(d)  # checks that it is one
        return values + step
    if _staged(module):  # the negative pivots of its nodes' dynamic stiffness
        return _tip_lines() + step + ["count += own"]
    coupled = [j for j in range(4) if d.Cz[0, j] != 0] if d.n_q == 1 else []
    if len(coupled) != 1 or coupled[0] > 1 or not (d.Cz[0, coupled[0]] > 0):
        raise ValueError(
            f"{module.KIND}: a stiffness kind with unknowns needs n_q = 1 and Cz = c e_Y or"
            " c e_theta (its row the unknown's equation of motion divided by its coupling"
            " to the beam, c > 0)"
        )
    # the unknown's own dynamic stiffness (k - m w^2 for a spring-mass)
    pivot = [f"pivot = {code(-d.Cq[0, 0])}"]
    return values + pivot + step + ["if pivot < 0.0:", "    count += 1"]


def _fill_lines(d: descriptor.Descriptor, complex_: bool = False) -> list[str]:
    """Fill Cz, Cq, A, B, qmass from a descriptor; return (constraints, unknowns)."""
    targets = [f"A[{r}, {c}]" for r in range(4) for c in range(4)]
    exprs = list(d.A)
    for r in range(d.Cz.rows):
        targets += [f"Cz[{r}, {c}]" for c in range(4)] + [f"Cq[{r}, {j}]" for j in range(d.n_q)]
        exprs += list(d.Cz[r, :]) + list(d.Cq[r, :])
    for j in range(d.n_q):
        targets += [f"B[{r}, {j}]" for r in range(4)]
        targets += [f"qmass[0, {j}]", f"qmass[1, {j}]", f"qmass[2, {j}]"]
        exprs += list(d.B[:, j]) + [d.qmass[j], d.qpart[j], d.qforce[j]]
    lines = assignments(targets, [sp.sympify(e) for e in exprs], indent="", complex_=complex_)
    return lines + [f"return {d.Cz.rows}, {d.n_q}"]


def _descriptor_lines(module, d: descriptor.Descriptor) -> list[str]:
    """Fill Cz, Cq, A, B, qmass (units L = EI = mbar = 1); return (constraints, unknowns)."""
    if _staged(module):
        return _chain_lines("descriptor")
    return _value_lines(module)[0] + _fill_lines(d)


def _descriptor_c_lines(damped: bool):
    """The complex descriptor at the complex frequency w1 (b4 = w1^2); with the damping
    values in a damped kernel (the frequency response and damped shapes of any kernel)."""

    def body(module, d: descriptor.Descriptor) -> list[str]:
        if _staged(module):
            return _chain_lines("descriptor", complex_=True)
        values, symbols = _value_lines(module, damped)
        d = descriptor.of(module, symbols)
        return values + ["b4 = w1 * w1"] + _fill_lines(d, complex_=True)

    return body


def _internal_lines(module, d: descriptor.Descriptor) -> list[str]:
    """Append the component's own frequencies (rad/s) to out[n:]; return n."""
    if _staged(module):
        return _chain_lines("internal")
    roots = descriptor.internal_b4(d)
    if not roots:
        return ["return n"]
    lines = _value_lines(module)[0]
    for r in roots:
        lines += [
            f"b4 = {code(r)}",
            "if b4 > 0.0 and math.isfinite(b4):",
            "    out[n] = math.sqrt(b4 * EI / mbar) / (L * L)",
            "    n += 1",
        ]
    return lines + ["return n"]


def _nq_lines(module, d: descriptor.Descriptor) -> list[str]:
    return ["return int(p[o])" if _staged(module) else f"return {d.n_q}"]


def _inertia_lines(module, d: descriptor.Descriptor) -> list[str]:
    """Fill Mp (2 x 2) with the mass matrix the component holds on [Y, theta]
    (``descriptor.point_inertia``); return 1, or 0 where it holds none."""
    M = descriptor.point_inertia(d)
    if M == sp.zeros(2, 2) or _staged(module):
        return ["return 0"]
    targets = [f"Mp[{r}, {c}]" for r in range(2) for c in range(2)]
    lines = assignments(targets, list(M), indent="")
    return _value_lines(module)[0] + lines + ["return 1"]


#: Flags of ``event_rigid``: the kinematic constraint a component puts on rigid motions.
RIGID_FLAGS = {"Y": 1, "theta": 2, "kink_if_free": 3}


def _rigid_lines(module, d: descriptor.Descriptor) -> list[str]:
    rigid = descriptor.rigid_of(module, _value_lines(module)[1])
    if not rigid:
        return ["return 0"]
    if len(rigid) != 1 or rigid[0] not in RIGID_FLAGS:
        raise ValueError(f"{module.KIND}: RIGID must be one of {tuple(RIGID_FLAGS)} or empty")
    if rigid[0] == "kink_if_free":  # the spring across the released rotation
        key = getattr(module, "RELEASES", ("theta", module.KEYS[1].name))[1]
        at = [k.name for k in module.KEYS[1:]].index(key)
        return [f"return 3 if p[{f'o + {at}' if at else 'o'}] == 0.0 else 0"]
    return [f"return {RIGID_FLAGS[rigid[0]]}"]


def _damps_lines(module, d: descriptor.Descriptor) -> list[str]:
    """A damper's constraint on rigid motions at w = 0 (a grounded dashpot dissipates
    unless Y = 0 there), derived from the kind's damping (``descriptor.damps_of``)."""
    damps = descriptor.damps_of(module, _value_lines(module, damped=True)[1])
    if not damps:
        return ["return 0"]
    if damps not in (("Y",), ("theta",)):
        raise ValueError(f"{module.KIND}: its damping holds ('Y',), ('theta',) or nothing")
    return [f"return {RIGID_FLAGS[damps[0]]}"]


_DESCRIPTOR_C_ARGS = "p, o, w1, L, EI, mbar, Cz, Cq, A, B, qmass"
#: ``event_chain``'s arguments, the same in a real and in a damped kernel (one walk,
#: ``numerics.characteristic.delta_chain``, calls both).
CHAIN_ARGS = "p, o, v, w1, b4, L, EI, mbar"
_DESCRIPTOR_C_DOC = (
    "The component's descriptor in complex arithmetic at the complex frequency w1 (units\n"
    "    L = EI = mbar = 1, b4 = w1^2); returns (constraints, unknowns)."
)


def dispatch_table(damped: bool) -> tuple:
    """The kernel's dispatch functions ``event_<what>(tag, ...)``: arguments, the branch of
    each kind present (printed from its descriptor), the statement for no branch, and doc.
    A damped kernel has no real descriptor and no own frequencies (its undamped twin's
    kernel has them)."""
    common = (
        (
            "descriptor_c",
            _DESCRIPTOR_C_ARGS,
            _descriptor_c_lines(damped),
            "return 0, 0",
            _DESCRIPTOR_C_DOC,
        ),
        ("nq", "p, o", _nq_lines, "return 0", "Unknowns of the component (full descriptor)."),
        (
            "rigid",
            "p, o",
            _rigid_lines,
            "return 0",
            "Kinematic constraint on rigid motions: 0 none, 1 Y = 0, 2 theta = 0, 3 free kink.",
        ),
        (
            "damps",
            "p, o",
            _damps_lines,
            "return 0",
            "Constraint of a damper on rigid motions at w = 0: 0 none, 1 Y = 0, 2 theta = 0.",
        ),
    )
    if damped:
        return (
            (
                "chain",
                CHAIN_ARGS,
                _damped_lines,
                "return 0.0j",
                "v <- the component's pole-free compound step in complex arithmetic at the\n"
                "    complex frequency w1 (b4 = w1^2), its dashpots' forces i w c included (the\n"
                "    event of ``delta_damped``); returns the complex log of a factor taken out.",
            ),
            *common,
        )
    return (
        (
            "chain",
            CHAIN_ARGS,
            _stable_lines,
            "return 0.0",
            "v <- the component's pole-free compound step on the minors (the event of\n"
            "    ``delta_stable``; units L = EI = mbar = 1, w1 = (lam_0 L)^2, b4 = w1^2,\n"
            "    docs/components.md); returns the log of a factor taken out (none: 0).",
        ),
        (
            "count",
            "p, o, Zc, b4, L, EI, mbar",
            _counted_lines,
            "return 0",
            "Zc <- the minors of the node's state subspace past the component; returns the\n"
            "    negative pivots it adds to the Wittrick-Williams count (the event of\n"
            "    ``count_below``).",
        ),
        (
            "descriptor",
            "p, o, b4, L, EI, mbar, Cz, Cq, A, B, qmass",
            _descriptor_lines,
            "return 0, 0",
            "The component's descriptor: Cz Z + Cq q = 0, Z+ = A Z + B q, qmass[0] the mass\n"
            "    of each q, qmass[1] the share of it a rigid translation carries, qmass[2] what\n"
            "    a unit force on it adds to minus its row (units L = EI = mbar = 1; paper\n"
            "    Eqs. (2)-(3)); returns (constraints, unknowns).",
        ),
        (
            "inertia",
            "p, o, L, EI, mbar, Mp",
            _inertia_lines,
            "return 0",
            "Fill Mp with the mass matrix the component holds on [Y, theta] (units L = EI =\n"
            "    mbar = 1; the b4 part of its A); return 1, or 0 where it holds none.",
        ),
        (
            "internal",
            "p, o, L, EI, mbar, out, n",
            _internal_lines,
            "return n",
            "Append the component's own frequencies (rad/s; scan nodes) to out[n:]; return n.",
        ),
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

    def body(module, d: descriptor.Descriptor) -> list[str] | None:
        if not _staged(module):
            return None
        values, symbols = _value_lines(module, damped)
        with sp.evaluate(True):
            parts = descriptor.stage_parts(module.stage(symbols))
        targets = [f"st[{r}, j]" for r in range(5)]
        inner = values[1:] + assignments(
            targets, [sp.sympify(e) for e in parts], indent="", complex_=complex_
        )
        head = values[:1] + (["b4 = w1 * w1"] if complex_ else [])
        return head + ["for j in range(n):"] + ["    " + line for line in inner]

    return body


_STAGES_DOC = (
    "Fill st[:, j] with stage j of a kind of stages: its dynamic stiffness\n"
    "    [[a, b], [b, c]] over [u_(j-1), u_j], the inertia force s1 a common translation\n"
    "    leaves, its mass m (units L = EI = mbar = 1; ``mstmm.numerics.chain``)."
)


def _stage_dispatch(parsed: list, damped: bool) -> str:
    """``event_stages`` (real; not in a damped kernel) and ``event_stages_c`` (complex):
    the stages of the kinds of stages present, what the chain numerics take; nothing for
    a topology without such a kind."""
    if not any(_staged(module) for _, module, _ in parsed):
        return ""
    out = []
    for complex_ in (False, True) if not damped else (True,):
        suffix, w = ("_c", "w1") if complex_ else ("", "b4")
        lines = [
            "",
            "",
            "@njit(cache=True)",
            f"def event_stages{suffix}(tag, p, o, {w}, L, EI, mbar, st):",
            f'    """{_STAGES_DOC}"""',
        ]
        body = _stage_lines(damped, complex_)
        lines += ["    " + line if line else "" for line in _branch_lines(parsed, body)]
        out.append("\n".join(lines) + "\n")
    return "".join(out)


def _branch_lines(parsed: list, body) -> list[str]:
    """``if tag == 0: ... elif tag == 1: ...``: one branch per kind present, its body
    printed from the kind's descriptor by ``body`` (none where ``body`` gives None)."""
    lines: list[str] = []
    for t, (k, module, d) in enumerate(parsed):
        body_lines = body(module, d)
        if body_lines is None:
            continue
        lines.append(f"{'elif' if lines else 'if'} tag == {t}:  # {k}")
        lines += ["    " + line if line else "" for line in body_lines or ["pass"]]
    return lines


#: The events of the hot loops (``delta_stable`` and ``delta_damped``: the one chain,
#: ``count_below``): inlined into them by numba (a compiled call costs about 20 ns, a fifth
#: of a component's step; the walks hand them ``borrowed`` arrays, whose reference counts
#: cost nothing).
HOT = ("chain", "count")


def _dispatch(parsed: list, damped: bool = False) -> str:
    """``event_<what>(tag, ...)``: one branch per kind present (none for a bare beam), each
    printed inline (one compiled function per entry, not per kind: compile time); the
    characteristic functions call them at each component."""
    out = []
    for what, args, body, tail, doc in dispatch_table(damped):
        decorator = '@njit(cache=True, inline="always")' if what in HOT else "@njit(cache=True)"
        lines = ["", "", decorator, f"def event_{what}(tag, {args}):", f'    """{doc}"""']
        lines += ["    " + line if line else "" for line in _branch_lines(parsed, body)]
        lines.append(f"    {tail}")
        out.append("\n".join(lines) + "\n")
    return _stage_dispatch(parsed, damped) + "".join(out)


def _node_stiffness_lines() -> list[str]:
    """Zc <- C2(I - kY e_Q e_Y^T + kT e_M e_theta^T) Zc: a node stiffness on the minors."""
    kY, kT = sp.symbols("kY kT")
    A = sp.eye(4)
    A[3, 0] = -kY
    A[2, 1] = kT
    return _step_lines(descriptor.point(A), "Zc")


def _dampers(kinds: tuple[str, ...]) -> dict[str, str]:
    """``descriptor.damper_of`` of each kind present that has damping (read at run time by
    the proved decay bound, ``mstmm.decay_bound``: the runtime has no SymPy)."""
    out = {}
    for k in kinds:
        module = catalog.kind(k)
        what = descriptor.damper_of(module, _value_lines(module, damped=True)[1])
        if what != "none":
            out[k] = what
    return out


def _parameter_doc(topology: Topology) -> str:
    parts = [
        "[L, EI_0, mbar_0, n_seg, n_ev, (x_end, EI, mbar, eta) per segment,"
        " (tag, x, offset) per component sorted by x, data blocks]"
    ]
    for t, name in enumerate(topology.kinds):
        keys = ", ".join(
            f"{k.name}{'[]' if k.shape == 'list' else ''} ({k.unit})"
            for k in catalog.kind(name).KEYS[1:]
        )
        parts.append(f"tag {t} = {name}: {keys or 'no values'}")
    return "; ".join(parts)


def numerics_source() -> str:
    """The source of the printed beam functions every kernel and the shared numerics use
    (``generated/euler_bernoulli.py``; the numerics themselves are ordinary code in
    ``mstmm.numerics``)."""
    C_beam = beam.compound_nondimensional(S.beta, S.rho, S.E, S.F)
    U_paper = beam.transfer_matrix(S.lam, S.l, S.EI)
    U_nd = beam.transfer_matrix_nondimensional(S.beta, S.rho, S.K)
    values = dict(
        threshold=repr(special.SERIES_THRESHOLD),
        digest=derive_digest(),
        sympy_version=importlib.metadata.version("sympy"),
        krylov_tiny=repr(special.leading_threshold(special.KRYLOV)),
        krylov_leading=special.leading_terms(special.KRYLOV),
        compound_tiny=repr(special.leading_threshold(special.COMPOUND)),
        compound_leading=special.leading_terms(special.COMPOUND),
        krylov_series=_indent(_series_lines(special.KRYLOV), 8),
        krylov_closed=_indent(_closed_lines(special.KRYLOV, scaled=False), 8),
        compound_series=_indent(_series_lines(special.COMPOUND), 8),
        compound_closed=_indent(_closed_lines(special.COMPOUND, scaled=True), 8),
        beam_transfer=_indent(_matrix_fill(U_paper, "U"), 4),
        krylov_scaled=_indent(_closed_lines(special.KRYLOV, scaled=True), 4),
        beam_transfer_scaled=_indent(_matrix_fill(U_nd, "U"), 4),
        clamped_clamped=_indent(_clamped_clamped_lines(), 4),
        beam_compound=_indent(_compound_step(C_beam), 4),
        krylov_closed_c=_indent(_closed_lines(special.KRYLOV, False, complex_=True), 8),
        krylov_scaled_c=_indent(_closed_lines(special.KRYLOV, True, complex_=True), 4),
        compound_closed_c=_indent(_closed_lines(special.COMPOUND, True, complex_=True), 8),
        beam_transfer_scaled_c=_indent(_matrix_fill(U_nd, "U", complex_=True), 4),
        beam_compound_c=_indent(_compound_step(C_beam, complex_=True), 4),
        node_stiffness=_indent(_node_stiffness_lines(), 4),
        general_rigid=_indent(_general_field_lines(shear=False), 8),
        general_shear=_indent(_general_field_lines(shear=True), 8),
    )
    return _clean(Template(NUMERICS_TEMPLATE.read_text()).substitute(values))


def _general_field_lines(shear: bool) -> list[str]:
    """``A`` of the general segment's differential equation (``general.field``), filled
    entry by entry from its dimensionless values."""
    names = ("e", "m", "w2", "kGA", "rhoI", "P", "k_w", "k_G")
    v = dict(zip(names, sp.symbols(names)))
    values = {"EI": v["e"], "mbar": v["m"], **v, "kGA": v["kGA"] if shear else None}
    return _matrix_fill(general.field(values), "A")


def _clean(text: str) -> str:
    return "\n".join(line.rstrip() for line in text.splitlines()) + "\n"


def regenerate_command(topology: Topology) -> str:
    """Shell command that writes this kernel again."""
    return f"python -m mstmm.derive --topology {topology.key} --out DIR"


def kernel_source(topology: Topology) -> str:
    """The complete source of the kernel module of ``topology`` (it imports the shared
    numerics, ``numerics_source``): real for an undamped topology, complex for a damped
    one."""
    kinds = topology.kinds
    damped = topology.damped
    parsed = _parsed(kinds, damped)
    left_unknown = unknown(topology.left)
    right_unknown = unknown(topology.right)
    kinds_text = (
        "point components of the kinds " + ", ".join(kinds) if kinds else "no point components"
    )
    values = dict(
        key=topology.key,
        left=topology.left,
        right=topology.right,
        attachments_text=kinds_text,
        what=Template(WHAT[damped]).substitute(threshold=repr(special.SERIES_THRESHOLD)),
        kinds=repr(kinds),
        dampers=repr(_dampers(kinds)),
        parameter_doc=_parameter_doc(topology),
        regenerate=regenerate_command(topology),
        sympy_version=importlib.metadata.version("sympy"),
        signature=signature(topology),
        digest=numerics_digest(),
        left_unknown=repr(left_unknown),
        right_unknown=repr(right_unknown),
        left_known=repr(KNOWN_ZERO[topology.left]),
        right_known=repr(KNOWN_ZERO[topology.right]),
        start_pair=pair_index(left_unknown),
        end_pair=pair_index(KNOWN_ZERO[topology.right]),
        dispatch=_dispatch(parsed, damped),
        functions=FUNCTIONS[damped],
    )
    return _clean(Template(TEMPLATE.read_text()).substitute(values))


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
    path = directory / (name or f"{topology.key}_{signature(topology)[:16]}.py")
    return _write_atomically(kernel_source(topology), path)

"""Emit the numba kernel module of a topology: fill the template, sign it, write it.

The template (``templates/kernel.py.tmpl``) holds the generic numerics (scan
loop, Brent refinement, LU determinant, renormalisation); this module prints the
per-component expressions into it. Only the components of the topology's kinds
are printed, and the attachment loops are left out for a bare beam.
"""

from __future__ import annotations

import importlib.metadata
import os
import tempfile
from pathlib import Path
from string import Template

import sympy as sp

from . import special
from . import symbols as S
from .catalog import ATTACHMENT_PARAMETERS, BEAM_PARAMETERS, KNOWN_ZERO, Topology, unknown
from .components import beam, rigid_body, spring_mass
from .compound import pair_index
from .printer import assignments, code
from .sign import signature

TEMPLATE = Path(__file__).with_name("templates") / "kernel.py.tmpl"
FORMULATION_TEMPLATE = TEMPLATE.with_name("formulation.py.tmpl")
SHAPES_TEMPLATE = TEMPLATE.with_name("shapes.py.tmpl")
#: Gauss-Legendre points of the mode shapes' mass integrals.
GAUSS_POINTS = 8
#: Formulations emitted into every kernel (``delta_<name>`` in the kernel template).
FORMULATIONS = ("stable", "paper")


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


def _closed_lines(funcs, scaled: bool) -> list[str]:
    out = []
    for f in funcs:
        if scaled:
            E, chs, shs = sp.symbols("E chs shs")
            expr = special.scaled_closed_form(f, E, chs, shs)
        else:
            expr = f.closed
        out.append(f"{f.name} = {code(expr.subs(special.x, S.x))}")
    return out


def _clamped_clamped_lines() -> list[str]:
    """``f = exp(-x) (1 - cos x cosh x)``, its sign is that of the equation."""
    E, chs, shs = sp.symbols("E chs shs")
    f = special.Reduced("f", beam.clamped_clamped_equation(special.x))
    expr = special.scaled_closed_form(f, E, chs, shs)
    return [f"f = {code(expr.subs(special.x, S.x))}"]


def _matrix_fill(M: sp.Matrix, name: str) -> list[str]:
    targets = [f"{name}[{i}, {j}]" for i in range(M.rows) for j in range(M.cols)]
    return assignments(targets, list(M), indent="")


def _compound_step(C: sp.Matrix) -> list[str]:
    """``v <- C v`` for a 6x6 symbolic compound, through CSE'd scalars."""
    v = sp.symbols("v0:6")
    lines = [f"v{a} = v[{a}]" for a in range(6)]
    lines += assignments([f"v[{a}]" for a in range(6)], list(C * sp.Matrix(v)), indent="")
    return lines


SPRING_MASS_FUNCTIONS = '''

@njit(cache=True)
def spring_mass_compound_step(v, beta, kappa, mu):
    """v <- (1 - mu beta^4 / kappa) C2(P) v: the condensed spring-mass branch, pole-free."""
$step


@njit(cache=True)
def spring_mass_tip(k, m, omega):
    """Geometric (H_I2 B e_Y) and shear (U_I2 B e_Y) of a unit tip displacement, B = U_s U_m."""
$tip
    return geometric, shear
'''

SPRING_MASS_COUNT = '''

@njit(cache=True)
def spring_mass_stiffness(beta, kappa, mu):
    """Pivot of the mass degree of freedom (k - m w^2 over k) and the condensed stiffness
    it adds to the node's Y, -shear / pivot (units L = EI = 1, B = U_spring U_mass)."""
$stiffness
    if pivot == 0.0:
        return 0.0, PENALTY  # at the oscillator frequency the branch pins the node
    return pivot, -shear / pivot
'''

SPRING_MASS_COUNT_LOOP = """\
n = (p.shape[0] - 3) // ATTACHMENT_STRIDE
for i in range(n):
    q = 3 + ATTACHMENT_STRIDE * i
    rho = (p[q] - pos) / L
    paired = leave_pairing(Zc, S, pos, L, started, paired)
    if rho > MERGE_LENGTH or (rho > 0.0 and pos > 0.0):
        count += segment_count(S, Zc, U, beta, rho, started, paired)
        started = True
    pos = p[q]
    pivot, added = spring_mass_stiffness(beta, p[q + 1] * L**3 / EI, p[q + 2] / (mbar * L))
    if pivot < 0.0:
        count += 1
    S[0, 0] += added
    if paired:
        add_node_stiffness(Zc, added)"""

SPRING_MASS_STABLE_LOOP = """\
n = (p.shape[0] - 3) // ATTACHMENT_STRIDE
for i in range(n):
    q = 3 + ATTACHMENT_STRIDE * i
    rho = (p[q] - pos) / L
    pos = p[q]
    if rho > 0.0:
        log += beam_compound_step(v, beta, rho)
    kappa = p[q + 1] * L**3 / EI
    mu = p[q + 2] / (mbar * L)
    spring_mass_compound_step(v, beta, kappa, mu)
    log += renormalise(v)"""

#: Body of ``oscillator_frequencies(p)``: where the kernel's ``lowest`` puts extra scan nodes.
SPRING_MASS_OSCILLATORS = """\
n = (p.shape[0] - 3) // ATTACHMENT_STRIDE
out = np.empty(n)
for i in range(n):
    q = 3 + ATTACHMENT_STRIDE * i
    out[i] = math.sqrt(p[q + 1] / p[q + 2])
return np.sort(out)"""

SPRING_MASS_PAPER_LOOP = """\
for i in range(n):
    q = 3 + ATTACHMENT_STRIDE * i
    l = p[q] - pos
    pos = p[q]
    if l > 0.0:
        beam_transfer(lam, l, EI, U)
        apply_columns(U, W, ncols, col)
    geometric, shear = spring_mass_tip(p[q + 1], p[q + 2], omega)
    # geometric equation, paper Eq. (3): -H_I1 Z_I1 + H_I2 Z_I2 = 0
    for j in range(ncols):
        A[4 + i, j] = -W[H_I1_INDEX, j]
    A[4 + i, ncols] = geometric
    # rigid body output, paper Eq. (2): Z_O = U_I1 Z_I1 + U_I2 Z_I2
    W[U_I2_ROW, ncols] = shear
    ncols += 1"""


def _spring_mass_functions() -> str:
    C, _pole = spring_mass.condensed_compound(S.kappa, S.mu, S.beta**2)
    col = spring_mass.tip_column(S.k, S.m, S.omega)
    geometric = (rigid_body.H_I2() * col)[0, 0]
    shear = (rigid_body.U_I2() * col)[_u_i2_row(), 0]
    tip = assignments(["geometric", "shear"], [geometric, shear], indent="")
    # node stiffness of the condensed branch: F = -(B10 / B00) Y (paper Eq. (3) eliminated)
    col_nd = spring_mass.tip_column(S.kappa, S.mu, S.beta**2)
    stiffness = assignments(["pivot", "shear"], [col_nd[0], col_nd[1]], indent="")
    return Template(SPRING_MASS_FUNCTIONS + SPRING_MASS_COUNT).substitute(
        step=_indent(_compound_step(C), 4),
        tip=_indent(tip, 4),
        stiffness=_indent(stiffness, 4),
    )


SHAPE_EVENT = '''

@njit(cache=True)
def event_position(p, i):
    """x (SI) of the i-th point component, sorted by x."""
    return p[3 + ATTACHMENT_STRIDE * i]


@njit(cache=True)
def shape_event(p, i, beta, Cz, Cq, B, qmass):
    """The i-th point component in descriptor form for the mode-shape march (units
    L = EI = 1): its geometric equation H_I1 Z = B00 Y_m (paper Eq. (3), B00 = 1 - m w^2/k)
    as Cz Z + Cq q = 0, and the shear its mass puts into the beam, U_I2 B e_Y Y_m
    (paper Eq. (2)), as Z+ = Z + B q; q = [Y_m / L], of mass qmass = [mu] (units
    mbar L). Returns (constraints, unknowns)."""
    q = 3 + ATTACHMENT_STRIDE * i
    L = p[0]
    kappa = p[q + 1] * L**3 / p[1]
    mu = p[q + 2] / (p[2] * L)
    qmass[0] = mu
$descriptor
    return 1, 1
'''

NO_SHAPE_EVENT = '''

@njit(cache=True)
def event_position(p, i):
    """This topology has no point components."""
    return p[0]


@njit(cache=True)
def shape_event(p, i, beta, Cz, Cq, B, qmass):
    """This topology has no point components."""
    return 0, 0
'''


def _shape_event(has_sm: bool) -> str:
    """The per-kind descriptor functions of the mode-shape march."""
    if not has_sm:
        return NO_SHAPE_EVENT
    col = spring_mass.tip_column(S.kappa, S.mu, S.beta**2)
    B00, B10 = col[0], col[1]
    H = rigid_body.H_I1()
    jump = rigid_body.U_I2()[:, 1] * B10  # the branch's shear, per unit tip displacement
    targets = [f"Cz[0, {j}]" for j in range(4)] + ["Cq[0, 0]"] + [f"B[{r}, 0]" for r in range(4)]
    exprs = [H[0, j] for j in range(4)] + [-B00] + list(jump)
    lines = assignments(targets, exprs, indent="")
    return Template(SHAPE_EVENT).substitute(descriptor=_indent(lines, 4))


def _shape_functions(topology: Topology, has_sm: bool) -> str:
    import numpy as np

    gx, gw = np.polynomial.legendre.leggauss(GAUSS_POINTS)
    return _shape_event(has_sm) + Template(SHAPES_TEMPLATE.read_text()).substitute(
        max_q=1 if has_sm else 0,
        right_known=repr(KNOWN_ZERO[topology.right]),
        n_events="(p.shape[0] - 3) // ATTACHMENT_STRIDE" if has_sm else "0",
        gauss_x=repr([float(v) for v in 0.5 * (gx + 1.0)]),
        gauss_w=repr([float(v) for v in 0.5 * gw]),
    )


def _riccati_lines() -> list[str]:
    Us = sp.Matrix(4, 4, lambda i, j: sp.Symbol(f"U{i}{j}"))
    s00, s01, s11 = sp.symbols("s00 s01 s11")
    S_num, detX, detBP, m00 = beam.riccati_step(Us, sp.Matrix([[s00, s01], [s01, s11]]))
    lines = [f"U{i}{j} = U[{i}, {j}]" for i in range(4) for j in range(4)]
    targets = ["S00", "S01", "S10", "S11", "detX", "detBP", "m00"]
    return lines + assignments(targets, [*S_num, detX, detBP, m00], indent="")


def _penalty_lines(end: str) -> list[str]:
    """Constrained Y / theta of an end as a huge stiffness (exact for the inertia count)."""
    return [f"S[{d}, {d}] += PENALTY" for d in KNOWN_ZERO[end] if d < 2]


def _h_i1_index() -> int:
    (idx,) = [j for j in range(4) if rigid_body.H_I1()[0, j] != 0]
    return idx


def _u_i2_row() -> int:
    (row,) = [i for i in range(4) if rigid_body.U_I2()[i, 1] != 0]
    return row


def _parameter_doc(topology: Topology) -> str:
    names = list(BEAM_PARAMETERS)
    for kind in topology.kinds:
        fields = ", ".join(ATTACHMENT_PARAMETERS[kind])
        names.append(f"then per {kind} ({fields}), sorted by x")
    return "[" + ", ".join(names) + "]"


def regenerate_command(topology: Topology) -> str:
    """Shell command that writes this kernel again."""
    return f"python -m mstmm.derive --topology {topology.key} --out DIR"


def kernel_source(topology: Topology) -> str:
    """The complete source of the kernel module of ``topology``."""
    kinds = topology.kinds
    if kinds not in ((), ("spring_mass",)):
        raise NotImplementedError(f"no emitter for attachment kinds {kinds}")
    has_sm = "spring_mass" in kinds
    C_beam = beam.compound_nondimensional(S.beta, S.rho, S.E, S.F)
    U_paper = beam.transfer_matrix(S.lam, S.l, S.EI)
    U_nd = beam.transfer_matrix_nondimensional(S.beta, S.rho, S.K)
    left_unknown = unknown(topology.left)
    right_unknown = unknown(topology.right)
    rb_constants = (
        f"H_I1_INDEX = {_h_i1_index()}  # H_I1 = [1 0 0 0] picks Y (paper Eq. (3))\n"
        f"U_I2_ROW = {_u_i2_row()}  # U_I2 puts the branch shear into Q (paper Eq. (2))"
        if has_sm
        else ""
    )
    n_att = "any number of spring-mass branches" if has_sm else "no attachments"
    values = dict(
        key=topology.key,
        left=topology.left,
        right=topology.right,
        attachments_text=n_att,
        threshold=repr(special.SERIES_THRESHOLD),
        parameter_doc=_parameter_doc(topology),
        regenerate=regenerate_command(topology),
        sympy_version=importlib.metadata.version("sympy"),
        signature=signature(topology),
        left_unknown=repr(left_unknown),
        right_unknown=repr(right_unknown),
        start_pair=pair_index(left_unknown),
        end_pair=pair_index(KNOWN_ZERO[topology.right]),
        rigid_body_modes=topology.rigid_body_modes,
        stride=len(ATTACHMENT_PARAMETERS["spring_mass"]) if has_sm else 1,
        rigid_body_constants=rb_constants,
        formulation_functions="\n\n".join(
            Template(FORMULATION_TEMPLATE.read_text()).substitute(name=name).strip() + "\n"
            for name in FORMULATIONS
        ),
        krylov_series=_indent(_series_lines(special.KRYLOV), 8),
        krylov_closed=_indent(_closed_lines(special.KRYLOV, scaled=False), 8),
        compound_series=_indent(_series_lines(special.COMPOUND), 8),
        compound_closed=_indent(_closed_lines(special.COMPOUND, scaled=True), 8),
        beam_transfer=_indent(_matrix_fill(U_paper, "U"), 4),
        krylov_scaled=_indent(_closed_lines(special.KRYLOV, scaled=True), 4),
        beam_transfer_scaled=_indent(_matrix_fill(U_nd, "U"), 4),
        clamped_clamped=_indent(_clamped_clamped_lines(), 4),
        riccati=_indent(_riccati_lines(), 4),
        left_penalty=_indent(_penalty_lines(topology.left), 4),
        right_penalty=_indent(_penalty_lines(topology.right), 4),
        count_attachment_loop=_indent(SPRING_MASS_COUNT_LOOP.splitlines(), 4) if has_sm else "",
        oscillators=_indent(
            SPRING_MASS_OSCILLATORS.splitlines() if has_sm else ["return np.empty(0)"], 4
        ),
        beam_compound=_indent(_compound_step(C_beam), 4),
        attachment_functions=_spring_mass_functions() if has_sm else "",
        stable_attachment_loop=_indent(SPRING_MASS_STABLE_LOOP.splitlines(), 4) if has_sm else "",
        paper_attachment_loop=_indent(SPRING_MASS_PAPER_LOOP.splitlines(), 4) if has_sm else "",
        shape_functions=_shape_functions(topology, has_sm),
    )
    text = Template(TEMPLATE.read_text()).substitute(values)
    return "\n".join(line.rstrip() for line in text.splitlines()) + "\n"


def write_kernel(topology: Topology, directory: Path, name: str | None = None) -> Path:
    """Derive the kernel of ``topology`` and write it atomically into ``directory`` (as
    ``name``, default ``<key>_<signature[:16]>.py``); returns its path."""
    source = kernel_source(topology)
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    path = directory / (name or f"{topology.key}_{signature(topology)[:16]}.py")
    fd, tmp = tempfile.mkstemp(dir=directory, prefix=".tmp-", suffix=".py")
    try:
        with os.fdopen(fd, "w") as fh:
            fh.write(source)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path

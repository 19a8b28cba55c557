"""Overall transfer equation of a beam carrying any chain of components, paper Eqs. (2)-(4).

The main chain runs from the boundary ``Z_1`` at ``x = 0`` to the root at ``x = L``
(DESIGN.md, "Reading the paper correctly"): beam pieces (paper Eq. (1), one per stretch
between points, with its segment's EI and lam) alternate with point components. Each
component is its descriptor (``derive/descriptor.py``; its kind's file): it adds its
unknowns ``q`` as columns (paper Eq. (2): ``Z+ = A Z + B q``) and its geometric
equations ``Cz Z + Cq q = 0`` as rows (paper Eq. (3)). Walking the chain once gives
every transfer ``T_{j-root}`` and every geometric equation; ``U_all Z_all = 0`` is
paper Eq. (4). Values are SI symbols (``k_2``, ``m_2``, ``J_3``, ``l_1``; a chain's
``k_4_1``; a stepped beam's ``EI_1``, ``mbar_1``, ``lam_1``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import sympy as sp

from mstmm import catalog
from mstmm.physics import segment as segment_terms

from . import descriptor
from . import symbols as S
from .segments import euler_bernoulli as beam
from .segments import general


@dataclass
class OverallTransfer:
    """``U_all Z_all = 0`` of paper Eq. (4) and the pieces it is made of."""

    T_root: sp.Matrix  # T_{1-root}, 4x4
    T_q: sp.Matrix  # transfer of every component unknown to the root, 4 x n_q
    G_rows: list[sp.Matrix]  # geometric equations, one 1 x n_all row each
    U_all: sp.Matrix
    Z_all: sp.Matrix
    components: list[tuple[str, dict]]


def general_segments(scene) -> list[int]:
    """Indices (from 1) of the segments with a term beyond Euler-Bernoulli
    (``catalog.SEGMENT_PHYSICS``), whose transfer is ``exp(A l)`` of
    ``segments.general.field``."""
    b = scene.beam
    segments = getattr(b, "segments", ()) or (b,)
    keys = [key for key, _, _ in catalog.SEGMENT_PHYSICS]
    return [s for s, seg in enumerate(segments, 1) if any(getattr(seg, k, 0.0) for k in keys)]


#: The symbol of each role's sum in ``segments.general.field``.
ROLE_SYMBOLS = {"shear": "kGA", "rotary": "rhoI", "tension": "t", "rotational": "r"}
ROLE_SYMBOLS |= {"foundation": "k_w"}


def general_field(scene, s: int) -> sp.Matrix:
    """``A`` of segment s (from 1) with a symbol for each term it has (its ``SYMBOL``; paper
    symbols ``EI``, ``mbar``, ``omega`` for a uniform beam, indexed by the segment
    otherwise), summed by role (``physics.segment.ROLES``)."""
    b = scene.beam
    segments = getattr(b, "segments", ()) or ()
    seg = segments[s - 1] if segments else b
    tag = f"_{s}" if segments else ""
    v = {
        "EI": sp.Symbol(f"EI{tag}", positive=True),
        "mbar": sp.Symbol(f"mbar{tag}", positive=True),
        "w2": S.omega**2,
    }
    for term in segment_terms.terms():
        if getattr(seg, term.name, 0.0):
            name = ROLE_SYMBOLS[term.role]
            v[name] = v.get(name, 0) + sp.Symbol(f"{term.symbol}{tag}", real=True)
    return general.field(v)


def _segments(scene) -> list[tuple[float, sp.Expr, sp.Expr, sp.Expr]]:
    """``(x_end, EI, mbar, lam)`` symbols of each segment (the paper's for a uniform beam)."""
    b = scene.beam
    segments = getattr(b, "segments", ()) or ()
    if not segments:
        return [(float(b.length), S.EI, S.mbar, S.lam)]
    out = []
    end = 0.0
    for s, seg in enumerate(segments, start=1):
        end = float(b.length) if s == len(segments) else end + float(seg.length)
        out.append(
            (
                end,
                sp.Symbol(f"EI_{s}", positive=True),
                sp.Symbol(f"mbar_{s}", positive=True),
                sp.Symbol(f"lam_{s}", positive=True),
            )
        )
    return out


def value_symbol(name: str, i: int, j: int | None = None) -> sp.Symbol:
    """The symbol of value ``name`` of the i-th component (1-based, x order), e.g. ``k_2``."""
    return sp.Symbol(f"{name}_{i}" if j is None else f"{name}_{i}_{j}", positive=True)


def component_descriptor(kind: str, values: dict) -> descriptor.Descriptor:
    """A component's descriptor in SI (its kind's, with b4 -> omega^2 and w1 -> omega)."""
    module = catalog.kind(kind)
    d = descriptor.of(module, values)
    sub = {descriptor.b4: S.omega**2, descriptor.w1: S.omega}
    return descriptor.Descriptor(
        d.Cz.subs(sub),
        d.Cq.subs(sub),
        d.A.subs(sub),
        d.B.subs(sub),
        tuple(sp.sympify(m).subs(sub) for m in d.qmass),
        tuple(sp.sympify(m).subs(sub) for m in d.qpart),
        tuple(sp.sympify(m).subs(sub) for m in d.qforce),
    )


def _zero(e) -> bool:
    return e is sp.S.Zero or e == 0


def _matmul(A: sp.Matrix, B: sp.Matrix) -> sp.Matrix:
    """A B with structural zeros skipped: under ``sympy.evaluate(False)`` a product with a
    zero factor would stay as an unevaluated nonzero-looking term."""
    from sympy.core.parameters import global_parameters

    if global_parameters.evaluate:
        return A * B
    out = sp.zeros(A.rows, B.cols)
    for i in range(A.rows):
        for j in range(B.cols):
            terms = [
                A[i, k] * B[k, j] for k in range(A.cols) if not (_zero(A[i, k]) or _zero(B[k, j]))
            ]
            if len(terms) == 1:
                out[i, j] = terms[0]
            elif terms:
                out[i, j] = sp.Add(*terms)
    return out


def _add_into(M: sp.Matrix, i: int, j: int, e) -> None:
    if not _zero(e):
        M[i, j] = e if _zero(M[i, j]) else M[i, j] + e


def chain(scene) -> list[tuple[str, dict]]:
    """Components along the main chain in x order: ``("beam", {l, EI, lam})`` pieces
    and ``(kind, {index, values})`` points."""
    segments = _segments(scene)
    general_ = general_segments(scene)
    points = sorted(enumerate(scene.attachments), key=lambda t: t[1].x)
    out: list[tuple[str, dict]] = []
    pos = 0.0
    seg = 0
    piece = 0

    def advance(x: float) -> None:
        nonlocal pos, seg, piece
        while True:
            end, EI, _, lam = segments[seg]
            target = min(x, end) if seg < len(segments) - 1 else x
            if target > pos:
                piece += 1
                out.append(
                    (
                        "beam",
                        {
                            "l": S.indexed("l", piece),
                            "EI": EI,
                            "lam": lam,
                            "length": target - pos,
                            "general": seg + 1 if seg + 1 in general_ else 0,
                        },
                    )
                )
                pos = target
            if seg < len(segments) - 1 and end <= x:
                seg += 1
                continue
            break

    for i, (_, a) in enumerate(points, start=1):
        advance(float(a.x))
        module = catalog.kind(a.kind)
        values = {}
        for key in module.KEYS[1:]:
            v = catalog.value(a.kind, dict(a.values), key)
            # a damping value that is zero (or left out) is a structural zero, so an
            # undamped scene's matrices stay those of the undamped kinds
            undamped = key.damping and not any(float(e) for e in np.atleast_1d(v))
            if key.shape == "list":
                values[key.name] = [
                    sp.S.Zero if undamped else value_symbol(key.name, i, j + 1)
                    for j in range(len(v))
                ]
            else:
                values[key.name] = sp.S.Zero if undamped else value_symbol(key.name, i)
        out.append((a.kind, {"index": i, "values": values}))
    advance(float(scene.beam.length))
    return out


def unknown_names(kind: str, i: int, n: int) -> list[str]:
    """Names of a component's unknowns in Z_all (``Y_tip2``, ``R3``, ``phi1``, ``Y_4_1``)."""
    base = getattr(catalog.kind(kind), "UNKNOWNS", "q")
    return [f"{base}{i}"] if n == 1 else [f"{base}{i}_{j + 1}" for j in range(n)]


def overall_transfer(scene) -> OverallTransfer:
    """Eqs. (2)-(4) for the scene's chain of components."""
    components = chain(scene)
    points = [(k, par) for k, par in components if k != "beam"]
    descs = [component_descriptor(k, par["values"]) for k, par in points]
    n_q = sum(d.n_q for d in descs)
    n_all = 4 + n_q + 4
    W = sp.zeros(4, n_all)  # the state at the current point, as a combination of Z_all
    W[:, 0:4] = sp.eye(4)
    G_rows: list[sp.Matrix] = []
    col = 4
    names: list[str] = []
    d_iter = iter(descs)
    for kind, par in components:
        if kind == "beam" and par["general"]:  # exp(A_s l), A_s printed by ``show``
            name, l = f"E{par['general']}", par["l"]
            U = sp.Matrix([[sp.Function(f"{name}_{i}{j}")(l) for j in "1234"] for i in "1234"])
            W = _matmul(U, W)
            continue
        if kind == "beam":
            W = _matmul(beam.transfer_matrix(par["lam"], par["l"], par["EI"]), W)
            continue
        d = next(d_iter)
        # Eq. (3): Cz Z + Cq q = 0, one row per constraint
        for r in range(d.Cz.rows):
            row = _matmul(d.Cz[r, :], W)
            for j in range(d.n_q):
                _add_into(row, 0, col + j, d.Cq[r, j])
            G_rows.append(row)
        # Eq. (2): Z+ = A Z + B q
        W = _matmul(d.A, W)
        for i in range(4):
            for j in range(d.n_q):
                _add_into(W, i, col + j, d.B[i, j])
        names += unknown_names(kind, par["index"], d.n_q)
        col += d.n_q
    main = W.copy()
    main[:, n_all - 4 :] = -sp.eye(4)
    U_all = sp.Matrix.vstack(main, *G_rows) if G_rows else main
    Z_all = sp.Matrix(
        [sp.Symbol(f"{v}_1") for v in ("Y", "theta", "M", "Q")]
        + [sp.Symbol(n) for n in names]
        + [sp.Symbol(f"{v}_root") for v in ("Y", "theta", "M", "Q")]
    )
    return OverallTransfer(W[:, 0:4], W[:, 4 : 4 + n_q], G_rows, U_all, Z_all, components)

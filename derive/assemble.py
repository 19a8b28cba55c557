"""Overall transfer equation of a beam with any number of branches, paper Eqs. (2)-(4).

The main chain runs from the boundary ``Z_1`` at ``x = 0`` to the root at
``x = L`` (DESIGN.md, "Reading the paper correctly"): beam segments alternate
with massless rigid bodies, each carrying one spring-mass branch whose tip is a
boundary ``[Y_m, 0]``. Walking the chain once gives every transfer ``T_{j-root}``
of Eq. (2) and every geometric equation of Eq. (3).
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from . import symbols as S
from .components import beam, rigid_body, spring_mass


@dataclass
class OverallTransfer:
    """``U_all Z_all = 0`` of paper Eq. (4) and the pieces it is made of."""

    T_root: sp.Matrix  # T_{1-root}, 4x4
    T_tips: list[sp.Matrix]  # T_{tip i - root}, 4x2 each
    G_rows: list[sp.Matrix]  # geometric equations, one 1 x n_all row per rigid body
    U_all: sp.Matrix
    Z_all: sp.Matrix
    components: list[tuple[str, dict[str, sp.Expr]]]


def chain(n_attachments: int) -> list[tuple[str, dict[str, sp.Expr]]]:
    """Components along the main chain: segment, branch, segment, ..., segment."""
    out: list[tuple[str, dict[str, sp.Expr]]] = []
    for i in range(1, n_attachments + 1):
        out.append(("beam", {"l": S.indexed("l", i)}))
        out.append(("spring_mass", {"k": S.indexed("k", i), "m": S.indexed("m", i)}))
    out.append(("beam", {"l": S.indexed("l", n_attachments + 1)}))
    return out


def overall_transfer(n_attachments: int) -> OverallTransfer:
    """Eqs. (2)-(4) for a beam carrying ``n_attachments`` spring-mass branches."""
    components = chain(n_attachments)
    n_all = 4 + 2 * n_attachments + 4
    W_root = sp.eye(4)  # transfer of Z_1 to the current point
    W_tips: list[sp.Matrix] = []  # transfers of each tip to the current point
    G_rows: list[sp.Matrix] = []
    for kind, par in components:
        if kind == "beam":
            U = beam.transfer_matrix(S.lam, par["l"], S.EI)
            W_root = U * W_root
            W_tips = [U * W for W in W_tips]
        else:
            B = spring_mass.branch(par["k"], par["m"], S.omega)
            # Eq. (3): H_I1 Z_I1 = H_I2 Z_I2, written as G Z_all = 0
            row = sp.zeros(1, n_all)
            row[0, 0:4] = -rigid_body.H_I1() * W_root
            for i, W in enumerate(W_tips):
                row[0, 4 + 2 * i : 6 + 2 * i] = -rigid_body.H_I1() * W
            j = len(W_tips)
            row[0, 4 + 2 * j : 6 + 2 * j] = rigid_body.H_I2() * B
            G_rows.append(row)
            # Eq. (2): Z_O = U_I1 Z_I1 + U_I2 Z_I2
            W_root = rigid_body.U_I1() * W_root
            W_tips = [rigid_body.U_I1() * W for W in W_tips] + [rigid_body.U_I2() * B]
    main = sp.zeros(4, n_all)
    main[:, 0:4] = W_root
    for i, W in enumerate(W_tips):
        main[:, 4 + 2 * i : 6 + 2 * i] = W
    main[:, n_all - 4 :] = -sp.eye(4)
    U_all = sp.Matrix.vstack(main, *G_rows) if G_rows else main
    Z_all = sp.Matrix(
        [sp.Symbol(f"{v}_1") for v in ("Y", "theta", "M", "Q")]
        + [sp.Symbol(f"{v}_tip{i + 1}") for i in range(n_attachments) for v in ("Y", "Q")]
        + [sp.Symbol(f"{v}_root") for v in ("Y", "theta", "M", "Q")]
    )
    return OverallTransfer(W_root, W_tips, G_rows, U_all, Z_all, components)

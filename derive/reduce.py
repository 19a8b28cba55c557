"""Boundary reduction: ``U_all Z_all = 0`` -> square ``U_bar Z_bar = 0`` (paper, after Eq. (4)).

Half of the boundary state variables vanish (``Z_1`` by the left end condition,
each tip ``[Y_m, 0]``, the root by the right end condition); their columns are
deleted, leaving a square matrix whose determinant vanishes at the natural
frequencies.
"""

from __future__ import annotations

import sympy as sp

from .catalog import KNOWN_ZERO


def zero_columns(left: str, right: str, n_attachments: int) -> list[int]:
    """Columns of ``U_all`` whose state variable is zero at its boundary."""
    n_all = 8 + 2 * n_attachments
    cols = list(KNOWN_ZERO[left])
    cols += [4 + 2 * i + 1 for i in range(n_attachments)]  # tip shear Q = 0
    cols += [n_all - 4 + j for j in KNOWN_ZERO[right]]
    return cols


def reduce(
    U_all: sp.Matrix, Z_all: sp.Matrix, left: str, right: str, n_attachments: int
) -> tuple[sp.Matrix, sp.Matrix]:
    """``(U_bar, Z_bar)``: the columns and unknowns that survive the boundary conditions."""
    drop = set(zero_columns(left, right, n_attachments))
    keep = [j for j in range(U_all.shape[1]) if j not in drop]
    U_bar = U_all[:, keep]
    if U_bar.shape[0] != U_bar.shape[1]:
        raise ValueError(f"reduced matrix is not square: {U_bar.shape}")
    return U_bar, Z_all[keep, :]

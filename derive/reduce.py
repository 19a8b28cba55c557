"""Boundary reduction: ``U_all Z_all = 0`` -> square ``U_bar Z_bar = 0`` (paper, after Eq. (4)).

Half of the boundary state variables vanish (``Z_1`` by the left end condition, the
root by the right end condition); their columns are deleted, leaving a square matrix
whose determinant vanishes at the natural frequencies (the components' unknowns all
stay: each came with as many geometric equations).
"""

from __future__ import annotations

import sympy as sp

from mstmm.catalog import KNOWN_ZERO


def zero_columns(left: str, right: str, n_all: int) -> list[int]:
    """Columns of ``U_all`` whose state variable is zero at its boundary."""
    return list(KNOWN_ZERO[left]) + [n_all - 4 + j for j in KNOWN_ZERO[right]]


def reduce(
    U_all: sp.Matrix, Z_all: sp.Matrix, left: str, right: str
) -> tuple[sp.Matrix, sp.Matrix]:
    """``(U_bar, Z_bar)``: the columns and unknowns that survive the boundary conditions."""
    drop = set(zero_columns(left, right, U_all.shape[1]))
    keep = [j for j in range(U_all.shape[1]) if j not in drop]
    U_bar = U_all[:, keep]
    if U_bar.shape[0] != U_bar.shape[1]:
        raise ValueError(f"reduced matrix is not square: {U_bar.shape}")
    return U_bar, Z_all[keep, :]

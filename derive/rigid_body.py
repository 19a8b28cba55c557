"""Massless rigid body with two inputs (beam and branch) and one output, paper Eqs. (2)-(3)."""

from __future__ import annotations

import sympy as sp


def U_I1() -> sp.Matrix:
    """Transfer of the beam input: the identity (paper, after Eq. (2))."""
    return sp.eye(4)


def U_I2() -> sp.Matrix:
    """Transfer of the branch input ``[Y, Q]``: its shear enters ``Q`` of the beam."""
    return sp.Matrix([[0, 0], [0, 0], [0, 0], [0, 1]])


def H_I1() -> sp.Matrix:
    """Geometric equation, beam side: picks ``Y`` (paper Eq. (3))."""
    return sp.Matrix([[1, 0, 0, 0]])


def H_I2() -> sp.Matrix:
    """Geometric equation, branch side: picks ``Y`` of ``[Y, Q]`` (paper Eq. (3))."""
    return sp.Matrix([[1, 0]])

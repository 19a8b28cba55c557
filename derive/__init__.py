"""mstmm.derive: the symbolic stage (SymPy only; never imported on the solve path).

Stages, each a module, input -> output:

1. ``components/`` -- component kinds -> symbolic transfer matrices
   (beam segment Eq. (1), spring, lumped mass, massless rigid body, and the
   compound forms of the stable formulation); ``special`` the reduced beam
   functions that keep them exact at small arguments.
2. ``assemble`` -- a chain of components -> the overall transfer equation
   ``U_all Z_all = 0`` (paper Eqs. (2)-(4)).
3. ``reduce`` -- end conditions -> the square ``U_bar`` (paper, after Eq. (4)).
4. ``printer`` + ``emit`` -- a topology -> the numba kernel source (template
   ``templates/kernel.py.tmpl``), signed with a content hash.

Public entry points: :func:`symbolic` (inspect a scene's ``U_all``, ``U_bar``
and, when small, its determinant) and :func:`kernel_source`.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from . import symbols
from .assemble import OverallTransfer, overall_transfer
from .emit import kernel_source
from .reduce import reduce

__all__ = ["Derivation", "kernel_source", "symbolic", "symbols"]

#: Largest reduced matrix whose determinant :meth:`Derivation.determinant` expands.
MAX_DETERMINANT_SIZE = 6


@dataclass
class Derivation:
    """Symbolic objects of one scene: paper Eqs. (2)-(4) and the reduced matrix."""

    left: str
    right: str
    n_attachments: int
    overall: OverallTransfer
    U_bar: sp.Matrix
    Z_bar: sp.Matrix

    @property
    def U_all(self) -> sp.Matrix:
        """``U_all`` of paper Eq. (4)."""
        return self.overall.U_all

    @property
    def Z_all(self) -> sp.Matrix:
        """``Z_all`` of paper Eq. (4)."""
        return self.overall.Z_all

    def determinant(self, simplify: bool = True) -> sp.Expr:
        """``det U_bar`` in ``lam``, segment lengths, ``EI``, ``k_i``, ``m_i``, ``omega``."""
        if self.U_bar.rows > MAX_DETERMINANT_SIZE:
            raise ValueError(
                f"U_bar is {self.U_bar.rows}x{self.U_bar.rows}; symbolic determinants are "
                f"expanded up to {MAX_DETERMINANT_SIZE}x{MAX_DETERMINANT_SIZE}"
            )
        d = self.U_bar.det(method="berkowitz")
        return sp.simplify(d) if simplify else d

    def parameters(self, scene) -> dict[sp.Symbol, float]:
        """Numeric values of this derivation's symbols for ``scene`` (``lam`` excluded)."""
        beam = scene.beam
        values = {symbols.EI: beam.EI, symbols.mbar: beam.mass_per_length}
        pos = 0.0
        for i, a in enumerate(scene.attachments, start=1):
            values[symbols.indexed("l", i)] = a.x - pos
            values[symbols.indexed("k", i)] = a.k
            values[symbols.indexed("m", i)] = a.m
            pos = a.x
        values[symbols.indexed("l", len(scene.attachments) + 1)] = beam.length - pos
        return values


def symbolic(scene) -> Derivation:
    """Paper Eqs. (2)-(4) and the boundary reduction for a scene (any :class:`Scene`)."""
    n = len(scene.attachments)
    overall = overall_transfer(n)
    U_bar, Z_bar = reduce(overall.U_all, overall.Z_all, scene.beam.left, scene.beam.right, n)
    return Derivation(scene.beam.left, scene.beam.right, n, overall, U_bar, Z_bar)

"""Symbolic objects of a scene: paper Eqs. (2)-(4), the reduction, the component library."""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from mstmm import catalog
from mstmm.kinds import spring_mass

from . import rigid_body, symbols
from .assemble import OverallTransfer, overall_transfer
from .emit import kernel_source
from .reduce import reduce
from .segments import euler_bernoulli as beam

__all__ = ["Derivation", "component_matrices", "kernel_source", "symbolic", "symbols"]

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
        """``det U_bar`` in ``lam``, segment lengths, ``EI``, the components' values, ``omega``."""
        if self.U_bar.rows > MAX_DETERMINANT_SIZE:
            raise ValueError(
                f"U_bar is {self.U_bar.rows}x{self.U_bar.rows}; symbolic determinants are "
                f"expanded up to {MAX_DETERMINANT_SIZE}x{MAX_DETERMINANT_SIZE}"
            )
        d = self.U_bar.det(method="berkowitz")
        return sp.simplify(d) if simplify else d

    def chain(self) -> list[str]:
        """The components along the main chain, ``x = 0`` to ``L``, as short labels."""
        out = ["Z_1 (left end)"]
        for kind, par in self.overall.components:
            if kind == "beam":
                out.append(f"beam {par['l']}")
            else:
                values = ", ".join(
                    str(v) if not isinstance(v, list) else "[" + ", ".join(map(str, v)) + "]"
                    for v in par["values"].values()
                )
                out.append(f"{kind} {par['index']}" + (f" ({values})" if values else ""))
        return [*out, "Z_root (right end)"]

    def sparsity(self) -> list[str]:
        """The rows of ``U_bar``: ``X`` for a structurally nonzero entry, ``.`` for zero."""
        U = self.U_bar
        return [
            " ".join("X" if U[i, j] != 0 else "." for j in range(U.cols)) for i in range(U.rows)
        ]

    def parameters(self, scene) -> dict[sp.Symbol, float]:
        """Numeric values of this derivation's symbols for ``scene`` (the uniform beam's
        ``lam`` excluded; a stepped beam's ``lam_s`` as expressions of ``omega``)."""
        beam = scene.beam
        segments = getattr(beam, "segments", ()) or ()
        if segments:
            values = {}
            for s, seg in enumerate(segments, start=1):
                EI_s, mbar_s = (
                    sp.Symbol(f"EI_{s}", positive=True),
                    sp.Symbol(f"mbar_{s}", positive=True),
                )
                values[EI_s] = seg.EI
                values[mbar_s] = seg.mass_per_length
                lam = (seg.mass_per_length * symbols.omega**2 / seg.EI) ** sp.Rational(1, 4)
                values[sp.Symbol(f"lam_{s}", positive=True)] = lam
        else:
            values = {symbols.EI: beam.EI, symbols.mbar: beam.mass_per_length}
        points = sorted(scene.attachments, key=lambda a: a.x)
        for kind, par in self.overall.components:
            if kind == "beam":
                values[par["l"]] = par["length"]
                continue
            a = points[par["index"] - 1]
            module = catalog.kind(a.kind)
            given = {k.name: catalog.value(a.kind, dict(a.values), k) for k in module.KEYS[1:]}
            for name, sym in par["values"].items():
                pairs = (
                    zip(sym, given[name], strict=True)
                    if isinstance(sym, list)
                    else [(sym, given[name])]
                )
                values.update((s, v) for s, v in pairs if isinstance(s, sp.Symbol))
        return values


def symbolic(scene, evaluate: bool = True) -> Derivation:
    """Paper Eqs. (2)-(4) and the boundary reduction for a scene (any :class:`Scene`).

    ``evaluate=False`` leaves SymPy's products unevaluated (``sympy.evaluate(False)``):
    milliseconds instead of seconds for tens of attachments, with the same sizes,
    state vectors and zero pattern of ``U_bar`` (a test compares them), for showing
    the structure; its entries are not simplified and not meant to be printed.
    """
    n = len(scene.attachments)
    with sp.evaluate(evaluate):
        overall = overall_transfer(scene)
        U_bar, Z_bar = reduce(overall.U_all, overall.Z_all, scene.beam.left, scene.beam.right)
    return Derivation(scene.beam.left, scene.beam.right, n, overall, U_bar, Z_bar)


def _krylov_form(U: sp.Matrix, x: sp.Expr) -> sp.Matrix:
    """The beam matrix written with the Krylov functions ``S, T, G, V`` of ``x``, as printed."""
    ch, sh, c, s = sp.cosh(x), sp.sinh(x), sp.cos(x), sp.sin(x)
    S, T, G, V = (sp.Function(name)(x) for name in "STGV")
    short = U.subs({(ch + c) / 2: S, (sh + s) / 2: T, (ch - c) / 2: G, (sh - s) / 2: V})
    return U if short.has(sp.cosh, sp.cos) else short


def component_matrices() -> list[tuple[str, sp.Matrix]]:
    """The component library the chain is made of (paper Eqs. (1)-(3)), with generic symbols.

    Beam segment ``U_B(l)`` (state ``[Y, theta, M, Q]``), spring ``U_S(k)`` and lumped
    mass ``U_M(m)`` (on ``[Y, Q]``), the massless rigid body's transfer ``U_I1`` (beam
    input), ``U_I2`` (branch input) and its geometric equation ``H_I1 Z_I1 = H_I2 Z_I2``.
    """
    S = symbols
    return [
        (
            "beam segment U_B(l), Eq. (1), with lam = (mbar omega^2/EI)^(1/4), x = lam l,\n"
            "  S, T = (cosh x + cos x)/2, (sinh x + sin x)/2,"
            " G, V = (cosh x - cos x)/2, (sinh x - sin x)/2",
            _krylov_form(beam.transfer_matrix(S.lam, S.l, S.EI), S.lam * S.l),
        ),
        ("spring U_S(k), Eq. (1)", spring_mass.spring(S.k)),
        ("lumped mass U_M(m), Eq. (1)", spring_mass.mass(S.m, S.omega)),
        ("rigid body U_I1 (beam input), Eq. (2)", rigid_body.U_I1()),
        ("rigid body U_I2 (branch input [Y, Q]), Eq. (2)", rigid_body.U_I2()),
        ("rigid body H_I1 (geometric equation, beam side), Eq. (3)", rigid_body.H_I1()),
        ("rigid body H_I2 (geometric equation, branch side), Eq. (3)", rigid_body.H_I2()),
    ] + _kind_matrices()


def _kind_matrices() -> list[tuple[str, sp.Matrix]]:
    """Each kind's point matrix ``det(Cq) (A - B Cq^-1 Cz)`` on ``[Y, theta, M, Q]`` (its
    pole factor multiplied out; a constraint's is its constrained map), from its
    descriptor in SI with generic values ``k``, ``m``, ``J``; a chain's depends on its
    length (``symbolic`` shows it with every mass)."""
    from mstmm import catalog

    from . import descriptor
    from .assemble import component_descriptor

    out = []
    for name, module in catalog.kinds().items():
        if any(key.shape == "list" for key in module.KEYS):
            continue
        values = {key.name: sp.Symbol(key.name, positive=True) for key in module.KEYS[1:]}
        P, pole = descriptor.point_matrix(component_descriptor(name, values))
        factor = f" times its pole factor {pole}" if pole != 1 else ""
        out.append((f"{name} ({module.DOC}): point matrix{factor}, Eqs. (1)-(3)", P))
    return out

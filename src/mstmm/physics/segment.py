"""A segment term is one file: its key and the energy it adds per unit length.

A segment of the beam is Euler-Bernoulli (``EI``, ``mass_per_length``: paper Eq. (1)) plus
any of the *terms* declared in ``mstmm/physics/terms/`` (one module each, found by listing
the folder; docs/components.md, "A segment term"). A term declares plain data, no SymPy:

* its key: ``NAME``, ``UNIT`` (SI), ``CHECK`` (``"nonnegative"`` or ``"finite"``), ``DOC``,
  ``LIMIT = (form, least, most)`` (the range of its dimensionless form that the searches
  are built for, ``form`` how a message writes it), ``LOSS`` (whether the segment's loss
  factor multiplies it: a stiffness, not a load), ``ORDER`` (its column among the terms),
  ``SYMBOL`` (its name in formulas, ``mstmm show``; default ``NAME``);
* its energy per unit length as quadratic forms over the fields ``(w, w', psi, psi')``
  (``psi`` the rotation of the section): ``POTENTIAL`` and ``KINETIC``, dicts of
  ``(field, field) -> coefficient``, the energy being ``value * sum c f_a f_b / 2`` over
  the symmetric entries.

Everything else is derived here from the energy, once for every term (:func:`role`): a
term's energy is one of the :data:`ROLES` the field matrix carries (``derive/segments/
general.py`` writes ``A`` of ``Z' = A Z`` from them), and each role has its rules written
once below: its share of the field, of the count's clamped-clamped bound, of the rigid
motions it holds, of the wave-growth bound, and the shear limit. A term whose energy is
none of them is refused when the terms are loaded, naming its file.
"""

from __future__ import annotations

import functools
import importlib
import math
import pkgutil
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from types import ModuleType

from .scales import UNIT_SCALES

#: The fields a term's energy density is a quadratic form over.
FIELDS = ("w", "w'", "psi", "psi'")

#: What the field matrix carries, each a quadratic form times the term's value:
#: ``(potential, kinetic, sign)``; ``sign`` the values the role's rules are proved for.
ROLES: dict[str, tuple[dict, dict, str]] = {
    # a Timoshenko shear stiffness kappa G A: (w' - psi)^2
    "shear": ({("w'", "w'"): 1, ("w'", "psi"): -1, ("psi", "psi"): 1}, {}, "nonnegative"),
    # a rotary inertia per length rho I: psi'^2 kinetic
    "rotary": ({}, {("psi", "psi"): 1}, "nonnegative"),
    # an axial tension (or a Pasternak layer): w'^2; a compression is negative
    "tension": ({("w'", "w'"): 1}, {}, "finite"),
    # a rotational (Winkler) foundation: psi^2
    "rotational": ({("psi", "psi"): 1}, {}, "nonnegative"),
    # a Winkler foundation: w^2
    "foundation": ({("w", "w"): 1}, {}, "nonnegative"),
}
#: The role codes the numerics read (``mstmm.numerics.segment.segment_values``).
ROLE_CODES = {name: code for code, name in enumerate(ROLES)}

#: Where the terms live.
TERMS_PACKAGE = "mstmm.physics.terms"


class TermRefused(ValueError):
    """A segment term file the numerics cannot carry: one line naming the file and why."""


@dataclass(frozen=True)
class SegmentTerm:
    """One loaded term: its key's declarations and its :data:`ROLES` entry."""

    name: str
    unit: str
    check: str
    doc: str
    limit: tuple[str, float, float]
    loss: bool
    symbol: str
    role: str
    order: float
    file: str

    @property
    def scale(self) -> tuple[Fraction, Fraction, Fraction]:
        """Exponents of (L, EI_0, mbar_0) that make a value dimensionless."""
        return UNIT_SCALES[self.unit]


def _form(declared: dict, file: str, what: str) -> dict:
    """A declared quadratic form as ``{(a, b): c}`` with ``a <= b`` in FIELDS order."""
    out: dict = {}
    for pair, c in declared.items():
        if len(pair) != 2 or any(f not in FIELDS for f in pair):
            raise TermRefused(f"{file}: {what}: {pair!r} is not a pair of {FIELDS}")
        a, b = sorted(pair, key=FIELDS.index)
        out[(a, b)] = out.get((a, b), 0) + c
    return {k: v for k, v in out.items() if v != 0}


def role(module: ModuleType) -> str:
    """Which of :data:`ROLES` a term's declared energy is, or :class:`TermRefused`."""
    file = getattr(module, "__file__", None) or module.__name__
    potential = _form(getattr(module, "POTENTIAL", {}), file, "POTENTIAL")
    kinetic = _form(getattr(module, "KINETIC", {}), file, "KINETIC")
    for name, (p, k, sign) in ROLES.items():
        if potential == _form(p, file, name) and kinetic == _form(k, file, name):
            if sign == "nonnegative" and module.CHECK != "nonnegative":
                raise TermRefused(
                    f"{file}: {module.NAME}: a {name} term must be nonnegative (CHECK ="
                    " 'nonnegative'): the count's bound and the growth bound drop it"
                )
            return name
    raise TermRefused(
        f"{file}: {module.NAME}: its energy is none of what a segment's field carries"
        " (value times w^2, w'^2, psi^2 or (w' - psi)^2 potential, psi^2 kinetic):"
        f" POTENTIAL {potential!r}, KINETIC {kinetic!r}"
    )


def _load(module: ModuleType) -> SegmentTerm:
    file = getattr(module, "__file__", None) or module.__name__
    for attr in ("NAME", "UNIT", "CHECK", "DOC", "LIMIT"):
        if not hasattr(module, attr):
            raise TermRefused(f"{file}: a segment term declares {attr}")
    if module.UNIT not in UNIT_SCALES:
        raise TermRefused(f"{file}: {module.NAME}: unknown unit {module.UNIT!r}")
    if module.CHECK not in ("nonnegative", "finite"):
        raise TermRefused(f"{file}: {module.NAME}: CHECK is 'nonnegative' or 'finite'")
    return SegmentTerm(
        name=module.NAME,
        unit=module.UNIT,
        check=module.CHECK,
        doc=module.DOC,
        limit=tuple(module.LIMIT),  # type: ignore[arg-type]
        loss=bool(getattr(module, "LOSS", True)),
        symbol=str(getattr(module, "SYMBOL", module.NAME)),
        role=role(module),
        order=float(getattr(module, "ORDER", math.inf)),
        file=file,
    )


@functools.cache
def terms() -> tuple[SegmentTerm, ...]:
    """Every segment term, in column order (``ORDER``, then name): the folder's files."""
    package = importlib.import_module(TERMS_PACKAGE)
    found = []
    for info in pkgutil.iter_modules(package.__path__):
        if not info.name.startswith("_"):
            found.append(_load(importlib.import_module(f"{TERMS_PACKAGE}.{info.name}")))
    names = [t.name for t in found]
    if len(set(names)) != len(names):
        raise TermRefused(f"{package.__path__}: two segment terms share a NAME: {names}")
    return tuple(sorted(found, key=lambda t: (t.order, t.name)))


def names() -> tuple[str, ...]:
    """The scene keys of the terms, in column order."""
    return tuple(t.name for t in terms())


def of_role(name: str) -> tuple[SegmentTerm, ...]:
    return tuple(t for t in terms() if t.role == name)


def files() -> list[Path]:
    """The term files (the numerics' machine code depends on their content)."""
    return sorted({Path(t.file) for t in terms()})


# -- the rules, written once ---------------------------------------------------------------


def total(values, role_name: str):
    """The sum of the values of the terms of one role, in column order (``values``: key
    -> value, floats or arrays alike; a missing key 0)."""
    out = 0.0
    for t in of_role(role_name):
        out = out + values.get(t.name, 0.0)
    return out


def shear_stiffness(values):
    """``g = kappa_GA + tension``, a Timoshenko segment's ``w'^2`` coefficient (the
    ``g`` of ``derive/segments/general.py``); floats or arrays."""
    return total(values, "shear") + total(values, "tension")


def shear_limit_broken(values):
    """Where a segment with a shear term is compressed at or past its shear limit ``g <=
    0`` (no static equilibrium: it buckles in shear); floats or arrays. The one rule the
    scene file, the parameter studies and the buckling search all apply."""
    return (total(values, "shear") > 0.0) & (shear_stiffness(values) <= 0.0)


def shear_limit_message() -> str:
    """The one line that says a segment buckles in shear, naming the keys."""
    shear = [t.name for t in of_role("shear")]
    stiff = [t.name for t in of_role("tension") if t.check == "nonnegative"]
    every = shear + [t.name for t in of_role("tension")]
    return (
        f"a compression of {' + '.join(shear + stiff)} or more buckles the segment in shear"
        f" ({' + '.join(every)} must be > 0)"
    )


def row_values(rows, columns: dict) -> dict:
    """``{key: rows[..., column]}`` of every term: a mapping the rules above read, from
    segment rows of a parameter vector (``catalog.SEGMENT_COLUMNS``)."""
    return {t.name: rows[..., columns[t.name]] for t in terms()}


def compression_key() -> str:
    """The term a compression is given by (the signed tension term: an axial force)."""
    return next(t.name for t in of_role("tension") if t.check == "finite")


def wavenumber_bound(values, EI: float, mbar: float, w: float) -> float:
    """An upper bound of a segment's wavenumbers at omega = w (1/m), for the growth of
    its solutions along it: ``sqrt(T / EI) + ((mbar w^2 + k_w) / EI)^(1/4)``, T the sum
    of the positive tensions and rotational foundations, ``k_w`` the foundations'
    (shear deformation, rotary inertia and compression only lower it)."""
    T = sum(max(values.get(t.name, 0.0), 0.0) for t in of_role("tension"))
    T += sum(max(values.get(t.name, 0.0), 0.0) for t in of_role("rotational"))
    k_w = sum(abs(values.get(t.name, 0.0)) for t in of_role("foundation"))
    return math.sqrt(T / EI) + ((mbar * w * w + k_w) / EI) ** 0.25

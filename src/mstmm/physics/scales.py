"""Exponents (L, EI_0, mbar_0) that make a value of each SI unit dimensionless:
``value * L^a EI_0^b mbar_0^c`` (the kernels' units L = EI_0 = mbar_0 = 1; the time unit
is ``L^2 sqrt(mbar_0 / EI_0)``). The one table point kinds' keys and segment terms share."""

from __future__ import annotations

from fractions import Fraction

UNIT_SCALES: dict[str, tuple[Fraction, Fraction, Fraction]] = {
    unit: tuple(Fraction(e) for e in exponents)  # type: ignore[misc]
    for unit, exponents in {
        "m": (-1, 0, 0),
        "N/m": (3, -1, 0),
        "kg": (-1, 0, -1),
        "N m/rad": (1, -1, 0),
        "kg m^2": (-3, 0, -1),
        "N s/m": (1, Fraction(-1, 2), Fraction(-1, 2)),
        "N m s/rad": (-1, Fraction(-1, 2), Fraction(-1, 2)),
        # segment terms (per unit length)
        "N": (2, -1, 0),
        "kg m": (-2, 0, -1),
        "N/m^2": (4, -1, 0),
    }.items()
}

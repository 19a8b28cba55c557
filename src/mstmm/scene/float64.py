"""What float64 arithmetic can carry: the range every value and product of a scene must
lie in, the message for a value beyond it, and the check of a product of factors (each
factor a value with the field path that gave it)."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .errors import SceneError

#: Every value a scene gives, and every product the numerics form from them (the
#: frequency scale, the nondimensional value of each key, ...), must lie within
#: [REPRESENTABLE_MIN, REPRESENTABLE_MAX] (zero is allowed where a key allows it).
#: float64 is normal from 2.2e-308 to 1.8e308; the margin of 58 decades leaves room
#: for the powers of lam L up to the 4th that the root search forms on top of these.
REPRESENTABLE_MIN = 1e-250
REPRESENTABLE_MAX = 1e250
_LOG_MIN, _LOG_MAX = math.log10(REPRESENTABLE_MIN), math.log10(REPRESENTABLE_MAX)


@dataclass(frozen=True)
class _Factor:
    """One factor of a product: values (rows x elements, either may be 1 to broadcast),
    the field path of each element, its name in the product and its exponent."""

    label: str
    values: np.ndarray
    paths: Sequence[str]
    exponent: float = 1
    zero_ok: bool = False

    def __pow__(self, exponent: float) -> _Factor:
        return dataclasses.replace(self, exponent=exponent)


def _product_name(factors: Sequence[_Factor]) -> str:
    def term(f: _Factor) -> str:
        e = abs(f.exponent)
        return f.label if e == 1 else f"{f.label}^{e:g}"

    top = " ".join(term(f) for f in factors if f.exponent > 0) or "1"
    bottom = [term(f) for f in factors if f.exponent < 0]
    if not bottom:
        return top
    return f"{top}/{bottom[0]}" if len(bottom) == 1 else f"{top}/({' '.join(bottom)})"


def _range_problem(where: str) -> str:
    """What a value outside [REPRESENTABLE_MIN, REPRESENTABLE_MAX] is told."""
    return (
        f"{where}must lie in [{REPRESENTABLE_MIN:g}, {REPRESENTABLE_MAX:g}]"
        " (what float64 arithmetic can carry with room for the products formed)"
    )


def _check_product(name: str, factors: Sequence[_Factor], source: str, point: str) -> None:
    with np.errstate(divide="ignore", invalid="ignore"):
        logs = [f.exponent * np.log10(f.values) for f in factors]
        total = sum(logs[1:], logs[0])
        ok = (total >= _LOG_MIN) & (total <= _LOG_MAX)
        for f in factors:
            if f.zero_ok:
                ok = ok | (f.values == 0.0)
    if ok.all():
        return
    row, el = (int(i) for i in np.argwhere(~np.broadcast_to(ok, np.shape(total)))[0])

    def at(a: np.ndarray) -> float:
        return float(a[min(row, a.shape[0] - 1), min(el, a.shape[1] - 1)])

    size = np.nan_to_num(np.abs([at(g) for g in logs]), nan=np.inf)
    worst = factors[int(np.argmax(size))]
    where = f"at {point} {row}, " if point else ""
    value = at(np.broadcast_to(total, np.shape(total)))
    if len(factors) == 1 and factors[0].exponent == 1:
        problem = _range_problem(where)
    else:
        size_text = f"1e{value:+.0f}" if np.isfinite(value) else "0"
        problem = (
            f"{where}{name or _product_name(factors)} is about {size_text}, beyond what"
            f" float64 arithmetic can carry (every value and product must lie in"
            f" [{REPRESENTABLE_MIN:g}, {REPRESENTABLE_MAX:g}])"
        )
    path = worst.paths[min(el, len(worst.paths) - 1)]
    raise SceneError(source, path, problem, at(worst.values))

"""A solution at a glance: its short ``repr`` and its tables as pandas DataFrames.

:class:`mstmm.solve.Solution` and :class:`mstmm.damped.DampedSolution` call these for
``repr(sol)`` and ``sol.to_dataframe()`` (and share the end of ``to_dict``: the buckling
state and the mode shapes). pandas is optional: only ``to_dataframe`` needs it, and says
how to install it when it is missing.
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["UNITS", "Tabulated", "mode_columns", "shape_columns", "solution_repr", "to_dataframe"]

#: The unit of every column :func:`to_dataframe` writes (``DataFrame.attrs["units"]``).
UNITS = {
    "omega": "rad/s",
    "f": "Hz",
    "modal_mass": "kg m^2",
    "participation": "1/m",
    "effective_mass": "kg",
    "w_d": "rad/s",
    "sigma": "1/s",
    "abs_omega": "rad/s",
    "zeta": "-",
    "f_d": "Hz",
    "x": "m",
    "Y": "m",
    "theta": "rad",
    "M": "N m",
    "Q": "N",
}

#: At most this many frequencies are listed in a repr (the first ones, then the last).
REPR_FREQUENCIES = 6


def _damped(sol) -> bool:
    return bool(getattr(sol, "damped", False))


def _number(w: complex | float) -> str:
    if isinstance(w, complex | np.complexfloating):
        return f"{w.real:.6g}{w.imag:+.6g}j"
    return f"{float(w):.6g}"


def _listed(omega: np.ndarray) -> str:
    """The frequencies, shortened to the first few and the last."""
    values = [_number(w) for w in omega]
    if len(values) > REPR_FREQUENCIES:
        values = [*values[: REPR_FREQUENCIES - 1], "...", values[-1]]
    return ", ".join(values)


def solution_repr(sol) -> str:
    """One line: the scene, how many frequencies (rad/s) and the first of them, whether
    the count certified them, how many shapes, and what is not to be trusted."""
    omega = np.asarray(sol.omega)
    what = "damped natural frequencies w_d+i sigma" if _damped(sol) else "natural frequencies"
    parts = [f"{len(omega)} {what} [rad/s]: {_listed(omega)}" if len(omega) else f"no {what}"]
    parts.append("count checked" if sol.count_checked else "count NOT checked")
    untrusted = int(np.count_nonzero(~np.asarray(sol.converged, dtype=bool)))
    if untrusted:
        parts.append(f"{untrusted} NOT TRUSTED")
    if getattr(sol.buckling, "buckled", False):
        parts.append("buckled")
    if sol.shapes is not None:
        parts.append(f"{len(sol.shapes)} mode shapes")
    return f"{type(sol).__name__}({sol.scene.name!r}: {'; '.join(parts)})"


def mode_columns(sol) -> dict[str, np.ndarray]:
    """One value per mode: the frequency columns (and, undamped with shapes, the modal
    mass, participation and effective mass), as the CSV of ``mstmm solve`` has them."""
    if _damped(sol):
        columns = {
            "w_d": sol.w_d,
            "sigma": sol.sigma,
            "abs_omega": sol.magnitude,
            "zeta": sol.zeta,
            "f_d": sol.hz,
        }
    else:
        columns = {"omega": np.asarray(sol.omega, dtype=float), "f": sol.hz}
    columns |= {
        "multiplicity": np.asarray(sol.multiplicity, dtype=int),
        "converged": np.asarray(sol.converged, dtype=bool),
    }
    if sol.shapes is not None and not _damped(sol):
        for name in ("modal_mass", "participation", "effective_mass"):
            columns[name] = np.array([getattr(s, name) for s in sol.shapes], dtype=float)
    return columns


def shape_columns(sol) -> dict[str, np.ndarray]:
    """The mode shapes in long form: one row per mode and sample point, the columns
    ``mode``, ``x`` and the state ``Y``, ``theta``, ``M``, ``Q`` (complex when damped)."""
    if sol.shapes is None:
        raise ValueError("the solution carries no mode shapes: solve it with shapes=True")
    shapes = sol.shapes
    columns: dict[str, Any] = {
        "mode": np.concatenate([np.full(s.x.size, i) for i, s in enumerate(shapes, start=1)]),
        "x": np.concatenate([s.x for s in shapes]),
    }
    for name in ("Y", "theta", "M", "Q"):
        columns[name] = np.concatenate([getattr(s, name) for s in shapes])
    return columns


def _pandas():
    try:
        import pandas
    except ImportError:
        raise ImportError(
            "to_dataframe() needs pandas, an optional dependency of mstmm: pip install pandas"
        ) from None
    return pandas


def to_dataframe(sol, shapes: bool = False):
    """``sol`` as a pandas DataFrame: one row per mode indexed by mode number (from 1),
    the columns of :func:`mode_columns`; with ``shapes``, the mode shapes in long form
    (:func:`shape_columns`). ``attrs["units"]`` gives every column's unit. Raises
    ImportError, naming ``pip install pandas``, without pandas."""
    pd = _pandas()
    if shapes:
        frame = pd.DataFrame(shape_columns(sol))
    else:
        columns = mode_columns(sol)
        index = pd.RangeIndex(1, len(sol.omega) + 1, name="mode")
        frame = pd.DataFrame(columns, index=index)
    frame.attrs["units"] = {c: UNITS[c] for c in frame.columns if c in UNITS}
    frame.attrs["scene"] = sol.scene.name
    return frame


class Tabulated:
    """What a solution class gets from this module: a one-line ``repr``, ``to_dataframe``
    (its dataclass is declared with ``repr=False`` to keep this one) and the parts of
    ``to_dict`` an undamped and a damped solution share."""

    def __repr__(self) -> str:
        """One line: the scene, the frequencies (the first few), what to trust."""
        return solution_repr(self)

    def to_dataframe(self, shapes: bool = False):
        """A pandas DataFrame (pandas is optional): one row per mode, or with ``shapes``
        the mode shapes in long form; ``attrs["units"]`` the columns' units
        (:func:`to_dataframe`)."""
        return to_dataframe(self, shapes=shapes)

    def buckling_and_shapes(self, out: dict, shapes: bool) -> dict:
        """``out`` (a ``to_dict`` so far) with ``buckling`` (a scene with a segment in
        compression: buckled, load factor, unstable modes) and, with ``shapes``, each mode
        shape's own ``to_dict`` under ``mode_shapes``."""
        if self.buckling is not None:
            out["buckling"] = {
                "buckled": self.buckling.buckled,
                "load_factor": float(self.buckling.load_factor),
                "unstable_modes": self.buckling.unstable_modes,
            }
        if shapes and self.shapes is not None:
            out["mode_shapes"] = [s.to_dict() for s in self.shapes]
        return out

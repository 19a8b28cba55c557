"""What ``mstmm solve`` writes: JSON without NaN, the frequency table, CSV, mode shapes.

Every writer returns text; the command line prints it. JSON is strict
(``allow_nan=False``): a non-finite number becomes ``null`` and is reported.

Every CSV column with a unit is headed ``name [unit]`` (:mod:`mstmm.units`). The CSV of
``--shapes`` holds three blocks separated by one empty line, each with its own header
row, so that a spreadsheet shows them one under the other:

1. ``mode,omega [rad/s],f [Hz],multiplicity,converged,modal_mass [kg m^2],
   participation [1/m],effective_mass [kg]``: one row per natural frequency (rigid-body
   zeros included);
2. ``x [m],Y_1 [m],...,Y_n [m],theta_1 [rad],...,theta_n [rad],M_1 [N m],...,M_n [N m],
   Q_1 [N],...,Q_n [N]``: one row per sample point along the beam, the state vector
   ``[Y, theta, M, Q]`` of each mode (on a uniform Euler-Bernoulli piece theta = dY/dx,
   M = EI d2Y/dx2, Q = EI d3Y/dx3), the shape scaled to max |Y| = 1 m over the beam and
   the masses;
3. ``mass_x [m],Y_1 [m],...,Y_n [m]``: one row per carried mass, its position on the
   beam and its displacement in each mode (absent when the scene has no masses).

A damped scene's shapes are complex: ``Y_1_re [m],Y_1_im [m],...`` and so on.
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
import re
import stat
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np

from .solve import Solution
from .units import field_unit, frf_unit, header, split_header

__all__ = [
    "BANDS_HEADER",
    "DAMPED_HEADER",
    "FREQUENCY_HEADER",
    "SHAPE_SUMMARY_HEADER",
    "STATE",
    "damped_csv",
    "damped_shapes_csv",
    "damped_shapes_table",
    "damped_table",
    "CannotWrite",
    "NotAFile",
    "atomic_file",
    "check_out_file",
    "check_writable",
    "out_target",
    "frf_csv",
    "frf_csv_header",
    "frf_units",
    "frf_csv_rows",
    "frf_table",
    "frf_table_header",
    "frf_table_rows",
    "json_numbers",
    "write_atomically",
    "dumps",
    "finite",
    "frequencies_csv",
    "frequencies_table",
    "read_csv",
    "read_shapes_csv",
    "shapes_csv",
    "shapes_table",
    "solution_text",
    "sweep_csv",
    "total_mass",
]

FREQUENCY_HEADER = ("mode", "omega [rad/s]", "f [Hz]", "multiplicity", "converged")
SHAPE_SUMMARY_HEADER = (
    *FREQUENCY_HEADER,
    "modal_mass [kg m^2]",
    "participation [1/m]",
    "effective_mass [kg]",
)
#: The beam's state in a shape CSV: its names and units (a shape scaled to max |Y| = 1 m).
STATE = (("Y", "m"), ("theta", "rad"), ("M", "N m"), ("Q", "N"))


def finite(value: Any, where: str = "", found: list[str] | None = None) -> Any:
    """``value`` with every non-finite float replaced by None; their paths go into ``found``."""
    found = [] if found is None else found
    if isinstance(value, dict):
        return {k: finite(v, f"{where}.{k}" if where else str(k), found) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [finite(v, f"{where}[{i}]", found) for i, v in enumerate(value)]
    if isinstance(value, np.ndarray):
        return finite(value.tolist(), where, found)
    if isinstance(value, (float, np.floating)):
        if not math.isfinite(value):
            found.append(where or "<value>")
            return None
        return float(value) + 0.0  # + 0.0: never a negative zero
    if isinstance(value, np.generic):
        return value.item()
    return value


def dumps(data: Any) -> tuple[str, list[str]]:
    """Strict JSON of ``data`` and the paths of the non-finite numbers written as ``null``."""
    found: list[str] = []
    text = json.dumps(finite(data, found=found), allow_nan=False)
    return text, found


def _csv(rows: Sequence[Sequence[Any]]) -> str:
    buf = io.StringIO()
    csv.writer(buf, lineterminator="\n").writerows(rows)
    return buf.getvalue()


def _num(value: float) -> str:
    return repr(float(value) + 0.0)  # + 0.0: never "-0.0"


_NEGATIVE_ZERO = re.compile(r"-(?=0*(?:\.0*)?(?:e[+-]?\d+)?\s*$)")


def _fmt(value: float, spec: str) -> str:
    """``value`` formatted by ``spec``, without the sign of a number that prints as zero
    (``-0``, ``-0.0000``: a negative zero, or round-off below the printed digits)."""
    text = format(float(value) + 0.0, spec)
    return _NEGATIVE_ZERO.sub(" " if text[:1] == " " or spec[:1] == ">" else "", text, count=1)


def _phase_deg(h: complex) -> float:
    """The phase of ``h`` in degrees, (-180, 180]: a signed zero in ``h`` does not decide
    it (``-1 - 0j`` is 180, ``1 - 0j`` is 0)."""
    return math.degrees(math.atan2(h.imag + 0.0, h.real + 0.0)) + 0.0


DAMPED_HEADER = (
    "mode",
    "w_d [rad/s]",
    "sigma [1/s]",
    "abs_omega [rad/s]",
    "zeta [-]",
    "f_d [Hz]",
    "multiplicity",
    "converged",
)


def damped_csv(sol) -> str:
    """:data:`DAMPED_HEADER` (w_d, sigma, abs omega, zeta, f_d, multiplicity, converged),
    one row per damped natural frequency (:class:`mstmm.damped.DampedSolution`)."""
    rows: list[Sequence[Any]] = [list(DAMPED_HEADER)]
    for i in range(len(sol.omega)):
        rows.append(
            [
                i + 1,
                _num(sol.w_d[i]),
                _num(sol.sigma[i]),
                _num(sol.magnitude[i]),
                _num(sol.zeta[i]),
                _num(sol.hz[i]),
                int(sol.multiplicity[i]),
                bool(sol.converged[i]),
            ]
        )
    return _csv(rows)


def damped_rows(sol, title: str) -> list[str]:
    """The damped roots' table (w_d, sigma, |w|, damping ratio, f_d, multiplicity; an
    overdamped root and one not trusted marked) under its ``title``: a beam's
    (:func:`damped_table`) or a frame's (:mod:`mstmm.frame.report`)."""
    lines = [
        f"{title}{len(sol.omega)} damped natural frequencies w = w_d + i sigma"
        " (time dependence exp(i w t))",
        f"{'mode':>4}  {'w_d [rad/s]':>22}  {'sigma [1/s]':>22}  {'|w| [rad/s]':>22}"
        f"  {'zeta':>10}  {'f_d [Hz]':>12}  mult",
    ]
    for i in range(len(sol.omega)):
        flag = "" if sol.converged[i] else "  NOT TRUSTED"
        kind = "  overdamped" if sol.w_d[i] == 0.0 and sol.sigma[i] > 0.0 else ""
        lines.append(
            f"{i + 1:>4}  {_fmt(sol.w_d[i], '>22.16g')}  {_fmt(sol.sigma[i], '>22.16g')}"
            f"  {_fmt(sol.magnitude[i], '>22.16g')}  {_fmt(sol.zeta[i], '>10.4g')}"
            f"  {_fmt(sol.hz[i], '>12.6g')}  {sol.multiplicity[i]:>4}{kind}{flag}"
        )
    return lines


def damped_table(sol) -> str:
    """The table of ``mstmm solve`` for a damped scene: w_d, sigma, |w|, damping ratio."""
    x0, x1, y0, y1 = sol.rectangle
    lines = damped_rows(sol, f"{sol.scene.name}: ")
    t = sol.timings
    lines.append(
        f"time: load {t['load']:.3f} s, search {t['scan_refine'] * 1e3:.2f} ms; argument"
        f" principle checked: {sol.count_checked} (counted w_d < {x1:.6g} rad/s,"
        f" sigma < {y1:.6g} 1/s)"
    )
    return "\n".join(lines) + "\n"


def damped_shapes_table(sol) -> str:
    """Per damped mode shape (``mstmm solve --shapes`` of a damped scene): where on the beam
    |Y| peaks, the largest |Y| of a hanging mass, and the shape's complexity
    ``1 - |sum Y^2| / sum |Y|^2`` over the beam samples and the masses (0: a real shape,
    every point in phase, as an undamped mode; 1: a travelling wave). The shapes' samples
    are in ``--format json`` or ``csv``."""
    shapes = _shapes(sol)
    lines = [
        "damped mode shapes (complex, max |Y| = 1; samples with --format json or csv):",
        f"{'mode':>4}  {'w_d [rad/s]':>22}  {'sigma [1/s]':>22}  {'peak |Y| at x [m]':>17}"
        f"  {'max |mass Y|':>12}  {'complexity':>10}",
    ]
    for i, s in enumerate(shapes, start=1):
        y = np.concatenate([s.Y, s.mass_Y])
        power = float(np.sum(np.abs(y) ** 2))
        complexity = 1.0 - abs(complex(np.sum(y * y))) / power if power > 0.0 else 0.0
        peak = float(s.x[int(np.argmax(np.abs(s.Y)))]) if s.x.size else math.nan
        mass = float(np.max(np.abs(s.mass_Y))) if s.mass_Y.size else math.nan
        mass_text = f"{mass:>12.6g}" if s.mass_Y.size else f"{'-':>12}"
        lines.append(
            f"{i:>4}  {s.omega.real:>22.16g}  {s.omega.imag:>22.16g}  {peak:>17.6g}"
            f"  {mass_text}  {max(complexity, 0.0):>10.4g}"
        )
    return "\n".join(lines) + "\n"


def frequencies_csv(sol: Solution) -> str:
    """:data:`FREQUENCY_HEADER` (mode, omega, f, multiplicity, converged), one row per
    natural frequency."""
    rows: list[Sequence[Any]] = [list(FREQUENCY_HEADER)]
    for i, (w, f, m, c) in enumerate(
        zip(sol.omega, sol.hz, sol.multiplicity, sol.converged, strict=True), start=1
    ):
        rows.append([i, _num(w), _num(f), int(m), bool(c)])
    return _csv(rows)


def frequencies_table(sol: Solution) -> str:
    """The human-readable table of ``mstmm solve``, untrusted roots flagged."""
    lines = [
        f"{sol.scene.name}: {len(sol.omega)} natural frequencies ({sol.formulation} formulation)",
        f"{'mode':>4}  {'omega [rad/s]':>24}  {'f [Hz]':>24}  mult",
    ]
    for i, (w, f, m, c) in enumerate(
        zip(sol.omega, sol.hz, sol.multiplicity, sol.converged, strict=True), start=1
    ):
        flag = "" if c else "  NOT TRUSTED"
        lines.append(f"{i:>4}  {_fmt(w, '>24.17g')}  {_fmt(f, '>24.17g')}  {m:>4}{flag}")
    t = sol.timings
    machine = (
        "kernel run as Python (cheaper than loading machine code)"
        if sol.kernel_mode == "interpreted"
        else f"compile {t['compile']:.3f} s"
    )
    lines.append(
        f"time: load {t['load']:.3f} s, {machine}, "
        f"scan+refine {t['scan_refine'] * 1e3:.2f} ms, count checked: {sol.count_checked}"
    )
    if getattr(sol, "buckling", None) is not None:
        lines.append(sol.buckling.message())
    return "\n".join(lines) + "\n"


def solution_text(sol, fmt: str, shapes: bool) -> str:
    """What ``mstmm solve --format table|csv`` writes for ``sol`` (undamped or damped),
    with the shapes' CSV blocks or summary when ``shapes``."""
    damped = getattr(sol, "damped", False)
    if fmt == "csv" and damped:
        return damped_shapes_csv(sol) if shapes else damped_csv(sol)
    if fmt == "csv":
        return shapes_csv(sol) if shapes else frequencies_csv(sol)
    if damped:
        return damped_table(sol) + (damped_shapes_table(sol) if shapes else "")
    return frequencies_table(sol) + (shapes_table(sol) if shapes else "")


def _shapes(sol: Solution) -> list:
    if sol.shapes is None:
        raise ValueError("the solution carries no mode shapes: solve it with shapes=True")
    return sol.shapes


def total_mass(sol: Solution) -> float:
    """Mass of the beam (every segment) plus every mass the components carry (kg): the
    values of their keys in kg (a chain's every stage)."""
    from mstmm.catalog import kind

    beam = sol.scene.beam
    segments = beam.segments or (beam,)
    total = sum(s.mass_per_length * s.length for s in segments)
    for a in sol.scene.attachments:
        for key in kind(a.kind).KEYS:
            if key.unit == "kg":
                total += float(np.sum(getattr(a, key.name)))
    return total


def shapes_table(sol: Solution) -> str:
    """Per mode: modal mass, participation, effective mass; their sum against the total mass."""
    shapes = _shapes(sol)
    lines = [
        "mode shapes (base-translation participation; modal mass for max |Y| = 1 m):",
        f"{'mode':>4}  {'omega [rad/s]':>24}  {'modal mass [kg m^2]':>20}"
        f"  {'participation [1/m]':>20}"
        f"  {'effective mass [kg]':>20}",
    ]
    for i, s in enumerate(shapes, start=1):
        lines.append(
            f"{i:>4}  {_fmt(s.omega, '>24.17g')}  {_fmt(s.modal_mass, '>20.6g')}"
            f"  {_fmt(s.participation, '>20.6g')}  {_fmt(s.effective_mass, '>20.6g')}"
        )
    total = total_mass(sol)
    summed = float(sum(s.effective_mass for s in shapes))
    lines.append(
        f"sum of effective masses: {summed:.6g} kg of the total mass {total:.6g} kg"
        f" ({100.0 * summed / total:.4g} %; all modes together give 100 %)"
    )
    return "\n".join(lines) + "\n"


def _state_columns(shapes, names, complex_: bool, of=getattr) -> list[tuple[str, np.ndarray]]:
    """The columns of a shape block: per (name, unit) of ``names``, per mode, the values
    ``of(shape, name)`` headed ``name_i [unit]`` (``name_i_re [unit]``, ``name_i_im [unit]``
    when ``complex_``)."""
    columns = []
    for name, unit in names:
        for i, s in enumerate(shapes, start=1):
            values = np.asarray(of(s, name))
            if complex_:
                columns.append((header(f"{name}_{i}_re", unit), values.real))
                columns.append((header(f"{name}_{i}_im", unit), values.imag))
            else:
                columns.append((header(f"{name}_{i}", unit), values))
    return columns


def _point_rows(first: str, x: np.ndarray, columns) -> list[Sequence[Any]]:
    """A block: the header ``first`` and the columns' headers, then one row per point."""
    rows: list[Sequence[Any]] = [[first, *(h for h, _ in columns)]]
    rows += [[_num(xj), *(_num(v[j]) for _, v in columns)] for j, xj in enumerate(x)]
    return rows


def _shape_blocks(shapes, complex_: bool) -> str:
    """The blocks after the summary: the beam's state ``[Y, theta, M, Q]`` at every
    sample, then (when there are any) the displacement of every carried mass."""
    x = shapes[0].x if shapes else np.empty(0)
    mass_x = shapes[0].mass_x if shapes else np.empty(0)
    for s in shapes:
        if not (np.array_equal(s.x, x) and np.array_equal(s.mass_x, mass_x)):
            raise ValueError("mode shapes sampled at different points cannot share one CSV block")
    text = _csv(_point_rows("x [m]", x, _state_columns(shapes, STATE, complex_)))
    if len(mass_x):
        masses = _state_columns(shapes, STATE[:1], complex_, lambda s, _: s.mass_Y)
        text += "\n" + _csv(_point_rows("mass_x [m]", mass_x, masses))
    return text


def shapes_csv(sol: Solution) -> str:
    """The three-block CSV of ``mstmm solve --shapes --format csv`` (see the module doc)."""
    shapes = _shapes(sol)
    rows: list[Sequence[Any]] = [SHAPE_SUMMARY_HEADER]
    for i, (s, c) in enumerate(zip(shapes, sol.converged, strict=True), start=1):
        rows.append(
            [
                i,
                _num(s.omega),
                _num(s.omega / (2.0 * math.pi)),
                int(s.multiplicity),
                bool(c),
                _num(s.modal_mass),
                _num(s.participation),
                _num(s.effective_mass),
            ]
        )
    return _csv(rows) + "\n" + _shape_blocks(shapes, complex_=False)


def _blocks(text: str) -> list[list[list[str]]]:
    """The CSV's blocks (rows separated by an empty line), each a header and its rows."""
    blocks: list[list[list[str]]] = [[]]
    for row in csv.reader(io.StringIO(text)):
        if row:
            blocks[-1].append(row)
        elif blocks[-1]:
            blocks.append([])
    return [b for b in blocks if b]


def _column(values: list[str]) -> np.ndarray:
    """One CSV column as an array: booleans, integers, or floats (an empty cell is NaN)."""
    if values and all(v in ("True", "False") for v in values):
        return np.array([v == "True" for v in values], dtype=bool)
    try:
        return np.array([int(v) for v in values], dtype=int)
    except ValueError:
        return np.array([float(v) if v else math.nan for v in values], dtype=float)


#: Column names of CSVs written before the headers carried units (``omega_rad_s``):
#: read as today's (``omega [rad/s]``).
_LEGACY = {
    "omega_rad_s": "omega",
    "f_hz": "f",
    "modal_mass_kg": "modal_mass",
    "effective_mass_kg": "effective_mass",
    "w_d_rad_s": "w_d",
    "sigma_1_s": "sigma",
    "abs_omega_rad_s": "abs_omega",
    "f_d_hz": "f_d",
}


def _names(head: list[str]) -> tuple[list[str], dict[str, str]]:
    """A header row's column names without their units (older names as today's), and the
    units of those that have one."""
    names, units = [], {}
    for text in head:
        name, unit = split_header(text)
        name = _LEGACY.get(name, re.sub(r"_phase_deg$", "_phase", name))
        names.append(name)
        if unit is not None:
            units[name] = unit
    return names, units


_SHAPE_COLUMN = re.compile(r"(Y|theta|M|Q)_(\d+)(?:_(re|im))?")


def _points(block: list[list[str]], first: str) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """A block ``first,Y_1,...`` (then ``theta_i``, ``M_i``, ``Q_i`` when written; complex
    shapes as ``Y_1_re,Y_1_im,...``): the positions and, per quantity, the matrix (points x
    modes)."""
    names, _ = _names(block[0])
    if names[0] != first:
        raise ValueError(f"not a mode-shape block of mstmm: expected {first!r}, got {names[0]!r}")
    values = np.array([[float(v) for v in r] for r in block[1:]], dtype=float)
    values = values.reshape(len(block) - 1, len(names))
    parts: dict[str, dict[int, np.ndarray]] = {}
    for j, name in enumerate(names[1:], start=1):
        match = _SHAPE_COLUMN.fullmatch(name)
        if match is None:
            raise ValueError(f"not a mode-shape block of mstmm: column {name!r}")
        quantity, mode, part = match.group(1), int(match.group(2)), match.group(3)
        column = values[:, j] * 1j if part == "im" else values[:, j]
        slot = parts.setdefault(quantity, {})
        slot[mode] = slot[mode] + column if mode in slot else column
    matrices = {
        q: np.column_stack([cols[i] for i in sorted(cols)]).reshape(len(values), len(cols))
        for q, cols in parts.items()
    }
    matrices.setdefault("Y", np.empty((len(values), 0)))
    return values[:, 0], matrices


def _names_of(header_row) -> tuple[str, ...]:
    return tuple(_names(list(header_row))[0])


#: Which table a CSV's first header row starts: what :func:`read_csv` reports as ``kind``.
_KINDS = {
    _names_of(SHAPE_SUMMARY_HEADER): "shapes",
    _names_of(DAMPED_HEADER): "damped",
    _names_of(FREQUENCY_HEADER): "frequencies",
}
_BANDS_NAMES = ("omega", "f", "propagating", "re_k1", "im_k1", "re_k2", "im_k2")
_SWEEP_MODE = re.compile(r"(omega|w_d|sigma|zeta)_(\d+)")


def _frf_arrays(out: dict[str, Any], names: list[str], n: int) -> None:
    """``outputs`` (the labels) and ``H`` (frequencies x outputs) of an frf CSV."""
    labels = [h[: -len("_re")] for h in names[2::4]]
    if names[2:] != [f"{o}_{p}" for o in labels for p in _FRF_PARTS]:
        raise ValueError("not an frf CSV of mstmm: unexpected columns")
    out["outputs"] = labels
    out["H"] = np.column_stack([out[f"{o}_re"] + 1j * out[f"{o}_im"] for o in labels]).reshape(
        n, len(labels)
    )


def _sweep_arrays(out: dict[str, Any], names: list[str], n: int) -> None:
    """``omega`` (points x modes) of a sweep CSV: real, or ``w_d + i sigma`` when damped."""
    if any(re.fullmatch(r"w_d_\d+", h) for h in names):
        modes = [h[len("w_d_") :] for h in names if re.fullmatch(r"w_d_\d+", h)]
        omega = [out[f"w_d_{i}"] + 1j * out[f"sigma_{i}"] for i in modes]
    else:
        omega = [out[h] for h in names if re.fullmatch(r"omega_\d+", h)]
    out["omega"] = np.column_stack(omega).reshape(n, len(omega))


def _kind(names: list[str]) -> str:
    """What a first block with these column names is: a key of :func:`read_csv`."""
    kind = _KINDS.get(tuple(names))
    if kind is not None:
        return kind
    if tuple(names) == _BANDS_NAMES:
        return "bands"
    if names[:2] == ["omega", "f"]:
        return "frf"
    if any(_SWEEP_MODE.fullmatch(h) for h in names):
        return "sweep"
    raise ValueError(f"not a CSV of mstmm: unknown header {','.join(names)!r}")


def read_csv(text: str) -> dict[str, Any]:
    """Read any CSV mstmm writes back into arrays, recognising it by its header rows.

    Every first-block column is an array under its name without the unit (``omega`` for
    ``omega [rad/s]``; booleans, integers or floats); ``units`` maps those names to their
    units. CSVs written before the headers carried units (``omega_rad_s``) read the same.

    * ``solve --format csv``: ``kind`` ``"frequencies"`` (undamped) or ``"damped"``;
    * ``solve --shapes --format csv``: ``"shapes"`` or ``"damped_shapes"``, the summary's
      columns plus ``x``, ``Y``, ``theta``, ``M``, ``Q`` (points x modes; complex for a
      damped scene; the last three absent from an older CSV), ``mass_x``, ``mass_Y``
      (empty without hanging masses);
    * ``frf``: ``"frf"``, ``omega``, ``f`` and ``<output>_re``, ``_im``, ``_abs``,
      ``_phase`` (degrees) per output, plus ``H`` (frequencies x outputs, complex) and
      ``outputs`` (their labels);
    * ``sweep``: ``"sweep"``, a column per varied field and ``omega`` (points x modes;
      ``w_d + i sigma`` for a damped scene) beside the ``omega_<i>`` columns;
    * ``bands --format csv``: ``"bands"``, ``omega``, ``f``, ``propagating`` and ``k``
      (frequencies x 2, complex, 1/m) beside ``re_k1`` ... ``im_k2``.

    Raises ValueError on a text mstmm did not write.
    """
    blocks = _blocks(text)
    if not blocks:
        raise ValueError("not a CSV of mstmm: empty")
    (names, units), rows = _names(blocks[0][0]), blocks[0][1:]
    if len(set(names)) != len(names) or any(len(r) != len(names) for r in rows):
        raise ValueError("not a CSV of mstmm: rows of unequal length or repeated columns")
    out: dict[str, Any] = {name: _column([r[j] for r in rows]) for j, name in enumerate(names)}
    kind = _kind(names)
    if kind == "frf":
        _frf_arrays(out, names, len(rows))
    elif kind == "sweep":
        _sweep_arrays(out, names, len(rows))
    elif kind == "bands":
        out["k"] = np.column_stack(
            [out["re_k1"] + 1j * out["im_k1"], out["re_k2"] + 1j * out["im_k2"]]
        ).reshape(len(rows), 2)
    if len(blocks) > 1:
        if kind not in ("shapes", "damped"):
            raise ValueError("not a CSV of mstmm: a second block after a one-block table")
        kind = "shapes" if kind == "shapes" else "damped_shapes"
        out["x"], state = _points(blocks[1], "x")
        out.update(state)
        if len(blocks) > 2:
            out["mass_x"], masses = _points(blocks[2], "mass_x")
            out["mass_Y"] = masses["Y"]
        else:
            out["mass_x"], out["mass_Y"] = np.empty(0), out["Y"][:0]
    out["kind"], out["units"] = kind, units
    return out


#: What :func:`read_shapes_csv` passes on from :func:`read_csv`'s shape arrays.
_SHAPE_ARRAYS = ("multiplicity", "x", "Y", "theta", "M", "Q", "mass_x", "mass_Y")


def read_shapes_csv(text: str) -> dict[str, np.ndarray]:
    """Parse :func:`shapes_csv` or :func:`damped_shapes_csv` back: ``omega`` (complex,
    ``w_d + i sigma``, for a damped scene), ``multiplicity``, ``x``, ``Y``, ``theta``,
    ``M``, ``Q`` (samples x modes, complex when damped; the last three only from a CSV
    that has them), ``mass_x``, ``mass_Y`` (masses x modes); undamped also
    ``modal_mass``, ``participation``, ``effective_mass``; damped also ``w_d``, ``sigma``,
    ``zeta``, ``converged`` (see :func:`read_csv`)."""
    data = read_csv(text)
    arrays = {k: data[k] for k in _SHAPE_ARRAYS if k in data}
    if data["kind"] == "shapes":
        return {
            "omega": data["omega"].astype(float),
            "modal_mass": data["modal_mass"].astype(float),
            "participation": data["participation"].astype(float),
            "effective_mass": data["effective_mass"].astype(float),
            **arrays,
        }
    if data["kind"] == "damped_shapes":
        w_d, sigma = data["w_d"].astype(float), data["sigma"].astype(float)
        return {
            "omega": w_d + 1j * sigma,
            "w_d": w_d,
            "sigma": sigma,
            "zeta": data["zeta"].astype(float),
            "converged": data["converged"],
            **arrays,
        }
    raise ValueError("not a mode-shape CSV of mstmm")


_FRF_PARTS = ("re", "im", "abs", "phase")


def frf_units(quantity: str, source, outputs) -> list[str]:
    """The unit of each output's response to ``source`` (:class:`mstmm.response.Point`s):
    ``m/N`` for a displacement's receptance to a force, ``rad/s/(N m)`` for a rotation's
    mobility to a moment, ..."""
    return [frf_unit(quantity, d.quantity, source.quantity) for d in outputs]


def frf_csv_header(labels: Sequence[str], units: Sequence[str] | None = None) -> str:
    """The header row of :func:`frf_csv`: ``omega [rad/s],f [Hz]`` then per output
    ``<label>_re [unit]``, ``_im [unit]``, ``_abs [unit]``, ``_phase [deg]`` (no unit when
    ``units`` is None)."""
    row: list[str] = ["omega [rad/s]", "f [Hz]"]
    for label, unit in zip(labels, units or [None] * len(labels), strict=True):
        row += [header(f"{label}_{part}", unit) for part in _FRF_PARTS[:3]]
        row.append(header(f"{label}_phase", "deg"))
    return _csv([row])


def frf_csv_rows(omegas: np.ndarray, H: np.ndarray) -> str:
    """The rows of :func:`frf_csv` (no header), one per frequency."""
    rows: list[Sequence[Any]] = []
    for k, w in enumerate(omegas):
        row = [_num(w), _num(w / (2.0 * math.pi))]
        for j in range(H.shape[1]):
            h = complex(H[k, j])
            row += [_num(h.real), _num(h.imag), _num(abs(h)), _num(_phase_deg(h))]
        rows.append(row)
    return _csv(rows)


def frf_csv(
    omegas: np.ndarray, H: np.ndarray, labels: Sequence[str], units: Sequence[str] | None = None
) -> str:
    """``omega [rad/s],f [Hz]`` then per output ``<label>_re,_im,_abs`` (in ``units``) and
    ``<label>_phase [deg]``, one row per frequency (``mstmm frf``); H is (frequencies,
    outputs)."""
    return frf_csv_header(labels, units) + frf_csv_rows(omegas, H)


def frf_table_header(name: str, quantity: str, source: str, labels: Sequence[str]) -> str:
    """The two title lines of :func:`frf_table`."""
    head = f"{'omega [rad/s]':>16}"
    for label in labels:
        head += f"  {('|H| ' + label)[:28]:>28}  {'phase [deg]':>11}"
    return f"{name}: {quantity} to {source}\n{head}\n"


def frf_table_rows(omegas: np.ndarray, H: np.ndarray) -> str:
    """The lines of :func:`frf_table` (no title), one per frequency."""
    lines = []
    for k, w in enumerate(omegas):
        line = _fmt(w, ">16.8g")
        for j in range(H.shape[1]):
            h = complex(H[k, j])
            line += f"  {_fmt(abs(h), '>28.10g')}  {_fmt(_phase_deg(h), '>11.4f')}"
        lines.append(line + "\n")
    return "".join(lines)


def frf_table(
    name: str, quantity: str, source: str, omegas: np.ndarray, H: np.ndarray, labels
) -> str:
    """A readable table of ``mstmm frf``: |H| and its phase per output."""
    return frf_table_header(name, quantity, source, labels) + frf_table_rows(omegas, H)


def json_numbers(values: np.ndarray) -> tuple[str, int]:
    """``values`` (floats) as the comma-separated items of a JSON array, a non-finite one as
    ``null``, and how many were."""
    bad = ~np.isfinite(values)
    items = ["null" if b else repr(float(v)) for v, b in zip(values.tolist(), bad, strict=True)]
    return ", ".join(items), int(bad.sum())


class CannotWrite(OSError):
    """An output file's directory does not take a new file (``directory``, ``reason``)."""

    def __init__(self, directory, reason: str):
        super().__init__(f"cannot write to {directory} ({reason})")
        self.directory, self.reason = directory, reason


class NotAFile(CannotWrite):
    """An output path names something other than a regular file (a directory, a device, a
    FIFO, a socket): never replaced. ``problem`` says what it is, ``path`` the path given."""

    def __init__(self, path, problem: str):
        OSError.__init__(self, f"{path}: {problem}")
        self.directory, self.reason = _directory(path), problem
        self.path, self.problem = path, problem


#: What a path that is not a regular file is, by its ``stat`` type.
_NOT_FILES = (
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISFIFO, "a FIFO (named pipe)"),
    (stat.S_ISSOCK, "a socket"),
)


def out_target(path) -> Path:
    """The file that writing ``path`` replaces: ``path`` itself, or the file a symbolic link
    leads to (its final target: the link stays a link and its target gets the content).
    Raises :class:`NotAFile` when that is not a regular file (only a regular file, or
    nothing yet, is replaced) and :class:`CannotWrite` when it cannot be looked at."""
    path = Path(path)
    target = Path(os.path.realpath(path)) if path.is_symlink() else path
    try:
        mode = os.stat(target).st_mode
    except FileNotFoundError:
        return target
    except OSError as exc:  # a loop of links, a directory that cannot be searched
        raise CannotWrite(_directory(target), _reason(exc)) from None
    via = f" (the link leads to {target})" if target != path else ""
    if stat.S_ISDIR(mode):
        raise NotAFile(path, f"a directory{via}: give a file name inside it")
    for test, what in _NOT_FILES:
        if test(mode):
            raise NotAFile(path, f"{what}{via}, not a regular file: mstmm never replaces one")
    return target


def check_out_file(path) -> Path:
    """Before any work: the file writing ``path`` will replace (:func:`out_target`), after
    checking that its directory takes a new file (:func:`check_writable`)."""
    target = out_target(path)
    check_writable(target)
    return target


def _directory(path) -> Path:
    path = Path(path)
    return path.parent if str(path.parent) else Path(".")


def _reason(exc: OSError) -> str:
    return (exc.strerror or str(exc)).lower()


def check_writable(path) -> None:
    """Raise :class:`CannotWrite` unless a file can be created in ``path``'s directory (by
    creating one there and removing it: the permission bits alone do not tell, e.g. for
    root or on a read-only file system)."""
    import tempfile

    directory = _directory(path)
    if not directory.is_dir():
        reason = "not a directory" if directory.exists() else "directory does not exist"
        raise CannotWrite(directory, reason)
    try:
        with tempfile.TemporaryFile(dir=directory, prefix=".tmp-mstmm-"):
            pass
    except OSError as exc:
        raise CannotWrite(directory, _reason(exc)) from None


def _new_mode(target: Path) -> int:
    """The permissions of a file replacing ``target``: its own if it exists, else as
    ``open()`` would make a new one (mkstemp makes 0600)."""
    try:
        return stat.S_IMODE(os.stat(target).st_mode)
    except OSError:
        mask = os.umask(0o022)
        os.umask(mask)
        return 0o666 & ~mask


@contextmanager
def atomic_file(path) -> Iterator[Any]:
    """A text file to write ``path`` through: a temporary file beside it, put in place when
    the block ends, removed if it fails or is interrupted (never half written). Through a
    symbolic link to its target (:func:`out_target`). Raises :class:`NotAFile` when
    ``path`` is not a regular file, :class:`CannotWrite` when its directory takes no file."""
    import tempfile

    target = out_target(path)
    directory = _directory(target)
    try:
        fd, tmp = tempfile.mkstemp(dir=directory, prefix=".tmp-")
    except OSError as exc:
        raise CannotWrite(directory, _reason(exc)) from None
    try:
        with os.fdopen(fd, "w") as fh:
            yield fh
        os.chmod(tmp, _new_mode(target))
        os.replace(tmp, target)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def write_atomically(path, text: str) -> None:
    """Write ``text`` to ``path`` through a temporary file in its directory (never half
    written; :class:`CannotWrite` when the directory takes no new file)."""
    with atomic_file(path) as fh:
        fh.write(text)


def damped_shapes_csv(sol) -> str:
    """The damped summary (``damped_csv``), an empty line, ``x [m],Y_1_re [m],Y_1_im [m],
    ...`` then theta, M and Q likewise (one row per sample along the beam), and
    ``mass_x [m],Y_1_re [m],...`` (one row per hanging mass, when there are any): the
    complex shapes of ``mstmm solve --shapes``."""
    return damped_csv(sol) + "\n" + _shape_blocks(_shapes(sol), complex_=True)


# ------------------------------------------------------------------ periodic cells


def bands_table(b) -> str:
    """``mstmm bands``: every band edge and every stop band in the band asked for."""
    lo, hi = b.band
    lines = [
        f"{b.cell.name}: periodic cell of length {b.length:.17g} m,"
        f" band [{lo:.6g}, {hi:.6g}] rad/s",
    ]
    if b.damped:
        lines.append("damped cell: every wave decays; no sharp band edge (see --format csv)")
    else:
        lines.append(f"{'edge':>4}  {'omega [rad/s]':>24}  {'f [Hz]':>24}  {'k L':>12}  mult")
        for i, e in enumerate(b.edges, start=1):
            kL = {"periodic": "0", "antiperiodic": "pi"}.get(e.kind, "in (0, pi)")
            flag = "" if e.certified else "  NOT CERTIFIED"
            lines.append(
                f"{i:>4}  {_fmt(e.omega, '>24.17g')}  {_fmt(e.hz, '>24.17g')}  {kL:>12}"
                f"  {e.multiplicity:>4}{flag}"
            )
        lines.append(f"{len(b.gaps)} stop band(s):")
        for a, c in b.gaps:
            width = (c - a) / (0.5 * (a + c)) if a + c > 0 else 0.0
            lines.append(
                f"  [{a:.12g}, {c:.12g}] rad/s"
                f" = [{a / (2 * math.pi):.12g}, {c / (2 * math.pi):.12g}] Hz"
                f" (relative width {width:.4g})"
            )
    t = b.timings
    lines.append(
        f"time: dispersion at {b.omega.size} frequencies {t.get('dispersion', 0.0) * 1e3:.2f} ms,"
        f" edges {t.get('edges', 0.0) * 1e3:.2f} ms, count checked: {b.count_checked}"
    )
    return "\n".join(lines) + "\n"


BANDS_HEADER = "omega [rad/s],f [Hz],propagating,re_k1 [1/m],im_k1 [1/m],re_k2 [1/m],im_k2 [1/m]"


def bands_csv(b) -> str:
    """The dispersion: omega, f, propagating pairs, Re k and Im k (1/m) of both pairs (the
    more attenuated first)."""
    out = io.StringIO()
    out.write(BANDS_HEADER + "\n")
    for w, n, k in zip(b.omega, b.propagating, b.k):
        row = [w, w / (2 * math.pi), n, k[0].real, k[0].imag, k[1].real, k[1].imag]
        out.write(
            ",".join(
                repr(float(v)) if not isinstance(v, (int, np.integer)) else str(v) for v in row
            )
            + "\n"
        )
    return out.getvalue()


def bands_dict(b) -> dict:
    """``mstmm bands --format json``: the cell, the edges, the gaps and the dispersion."""
    return {
        "cell": b.cell.name,
        "length": b.length,
        "band": list(b.band),
        "damped": b.damped,
        "count_checked": b.count_checked,
        "edges": [
            {
                "omega": e.omega,
                "hz": e.hz,
                "kind": e.kind,
                "multiplicity": e.multiplicity,
                "certified": e.certified,
            }
            for e in b.edges
        ],
        "gaps": [list(g) for g in b.gaps],
        "omega": b.omega.tolist(),
        "propagating": b.propagating.tolist(),
        "k": [[[float(k.real), float(k.imag)] for k in row] for row in b.k],
        "notes": list(b.notes),
        "timings": dict(b.timings),
    }


# ------------------------------------------------------------------ parameter studies


def sweep_csv(
    scene, vary: dict[str, np.ndarray], omega: np.ndarray, units: Sequence[str] | None = None
) -> str:
    """``mstmm sweep``: one row per point, the varied fields (each with its unit: ``units``,
    or :func:`mstmm.units.field_unit` of the scene), then ``omega_<i> [rad/s]`` per mode,
    or for a damped scene ``w_d_<i> [rad/s]``, ``sigma_<i> [1/s]``, ``zeta_<i> [-]``."""
    modes = range(1, omega.shape[1] + 1)
    if units is None:
        units = [field_unit(scene, path) for path in vary]
    fields = [header(path, unit) for path, unit in zip(vary, units, strict=True)]
    if np.iscomplexobj(omega):  # damped: per mode w_d, sigma and the damping ratio
        names = (("w_d", "rad/s"), ("sigma", "1/s"), ("zeta", "-"))
        heads = [header(f"{q}_{i}", unit) for i in modes for q, unit in names]
        mag = np.abs(omega)
        zeta = np.divide(omega.imag, mag, out=np.zeros_like(mag), where=mag > 0)
        zeta[np.isnan(mag)] = np.nan
        cells = np.stack([omega.real, omega.imag, zeta], axis=2).reshape(len(omega), -1)
    else:
        heads = [header(f"omega_{i}", "rad/s") for i in modes]
        cells = omega
    rows: list[Sequence[Any]] = [[*fields, *heads]]
    for j in range(omega.shape[0]):
        rows.append([*(repr(float(v[j])) for v in vary.values()), *map(repr, cells[j].tolist())])
    return _csv(rows)

"""What ``mstmm solve`` writes: JSON without NaN, the frequency table, CSV, mode shapes.

Every writer returns text; the command line prints it. JSON is strict
(``allow_nan=False``): a non-finite number becomes ``null`` and is reported.

The CSV of ``--shapes`` holds three blocks separated by one empty line, each
with its own header row, so that a spreadsheet shows them one under the other:

1. ``mode,omega_rad_s,f_hz,multiplicity,converged,modal_mass_kg,participation,
   effective_mass_kg``: one row per natural frequency (rigid-body zeros included);
2. ``x,Y_1,...,Y_n``: one row per sample point along the beam (m), the displacement
   of each mode (max |Y| over beam and masses = 1);
3. ``mass_x,Y_1,...,Y_n``: one row per carried mass, its position on the beam and
   its displacement in each mode (absent when the scene has no masses).
"""

from __future__ import annotations

import csv
import io
import json
import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from .solve import Solution

__all__ = [
    "SHAPE_SUMMARY_HEADER",
    "dumps",
    "finite",
    "frequencies_csv",
    "frequencies_table",
    "read_shapes_csv",
    "shapes_csv",
    "shapes_table",
    "total_mass",
]

SHAPE_SUMMARY_HEADER = (
    "mode",
    "omega_rad_s",
    "f_hz",
    "multiplicity",
    "converged",
    "modal_mass_kg",
    "participation",
    "effective_mass_kg",
)


def finite(value: Any, where: str = "", found: list[str] | None = None) -> Any:
    """``value`` with every non-finite float replaced by None; their paths go into ``found``."""
    found = [] if found is None else found
    if isinstance(value, dict):
        return {k: finite(v, f"{where}.{k}" if where else str(k), found) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [finite(v, f"{where}[{i}]", found) for i, v in enumerate(value)]
    if isinstance(value, np.ndarray):
        return finite(value.tolist(), where, found)
    if isinstance(value, (float, np.floating)) and not math.isfinite(value):
        found.append(where or "<value>")
        return None
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
    return repr(float(value))


def frequencies_csv(sol: Solution) -> str:
    """``mode,omega_rad_s,f_hz,multiplicity,converged``, one row per natural frequency."""
    rows: list[Sequence[Any]] = [["mode", "omega_rad_s", "f_hz", "multiplicity", "converged"]]
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
        lines.append(f"{i:>4}  {w:>24.17g}  {f:>24.17g}  {m:>4}{flag}")
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
    return "\n".join(lines) + "\n"


def _shapes(sol: Solution) -> list:
    if sol.shapes is None:
        raise ValueError("the solution carries no mode shapes: solve it with shapes=True")
    return sol.shapes


def total_mass(sol: Solution) -> float:
    """Mass of the beam (every segment) plus every mass the components carry (kg): the
    values of their keys in kg (a chain's every stage)."""
    from mstmm.derive.catalog import kind

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
        "mode shapes (base-translation participation; modal mass for max |Y| = 1):",
        f"{'mode':>4}  {'omega [rad/s]':>24}  {'modal mass [kg]':>16}  {'participation':>14}"
        f"  {'effective mass [kg]':>20}",
    ]
    for i, s in enumerate(shapes, start=1):
        lines.append(
            f"{i:>4}  {s.omega:>24.17g}  {s.modal_mass:>16.6g}  {s.participation:>14.6g}"
            f"  {s.effective_mass:>20.6g}"
        )
    total = total_mass(sol)
    summed = float(sum(s.effective_mass for s in shapes))
    lines.append(
        f"sum of effective masses: {summed:.6g} kg of the total mass {total:.6g} kg"
        f" ({100.0 * summed / total:.4g} %; all modes together give 100 %)"
    )
    return "\n".join(lines) + "\n"


def shapes_csv(sol: Solution) -> str:
    """The three-block CSV of ``mstmm solve --shapes --format csv`` (see the module doc)."""
    shapes = _shapes(sol)
    n = len(shapes)
    x = shapes[0].x if shapes else np.empty(0)
    mass_x = shapes[0].mass_x if shapes else np.empty(0)
    for s in shapes:
        if not (np.array_equal(s.x, x) and np.array_equal(s.mass_x, mass_x)):
            raise ValueError("mode shapes sampled at different points cannot share one CSV block")
    labels = [f"Y_{i}" for i in range(1, n + 1)]
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
    rows.append([])
    rows.append(["x", *labels])
    rows += [[_num(xj), *(_num(s.Y[j]) for s in shapes)] for j, xj in enumerate(x)]
    if len(mass_x):
        rows.append([])
        rows.append(["mass_x", *labels])
        rows += [[_num(xj), *(_num(s.mass_Y[j]) for s in shapes)] for j, xj in enumerate(mass_x)]
    return _csv(rows)


def read_shapes_csv(text: str) -> dict[str, np.ndarray]:
    """Parse :func:`shapes_csv` back: ``omega``, ``modal_mass``, ``participation``,
    ``effective_mass``, ``multiplicity``, ``x``, ``Y`` (samples x modes), ``mass_x``,
    ``mass_Y`` (masses x modes)."""
    blocks: list[list[list[str]]] = [[]]
    for row in csv.reader(io.StringIO(text)):
        if row:
            blocks[-1].append(row)
        elif blocks[-1]:
            blocks.append([])
    summary, beam = blocks[0], blocks[1]
    masses = blocks[2] if len(blocks) > 2 else [["mass_x", *beam[0][1:]]]
    if tuple(summary[0]) != SHAPE_SUMMARY_HEADER or beam[0][0] != "x" or masses[0][0] != "mass_x":
        raise ValueError("not a mode-shape CSV of mstmm")
    n = len(beam[0]) - 1
    table = np.array([[float(v) for v in r[1:3] + r[5:8]] for r in summary[1:]]).reshape(-1, 5)
    beam_v = np.array([[float(v) for v in r] for r in beam[1:]]).reshape(-1, n + 1)
    mass_v = np.array([[float(v) for v in r] for r in masses[1:]]).reshape(-1, n + 1)
    return {
        "omega": table[:, 0],
        "modal_mass": table[:, 2],
        "participation": table[:, 3],
        "effective_mass": table[:, 4],
        "multiplicity": np.array([int(r[3]) for r in summary[1:]], dtype=int),
        "x": beam_v[:, 0],
        "Y": beam_v[:, 1:],
        "mass_x": mass_v[:, 0],
        "mass_Y": mass_v[:, 1:],
    }

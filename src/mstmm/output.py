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
import os
import re
import stat
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np

from .solve import Solution

__all__ = [
    "DAMPED_HEADER",
    "SHAPE_SUMMARY_HEADER",
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
    "w_d_rad_s",
    "sigma_1_s",
    "abs_omega_rad_s",
    "zeta",
    "f_d_hz",
    "multiplicity",
    "converged",
)


def damped_csv(sol) -> str:
    """``mode,w_d_rad_s,sigma_1_s,abs_omega_rad_s,zeta,f_d_hz,multiplicity,converged``, one
    row per damped natural frequency (:class:`mstmm.damped.DampedSolution`)."""
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


def damped_table(sol) -> str:
    """The table of ``mstmm solve`` for a damped scene: w_d, sigma, |w|, damping ratio."""
    x0, x1, y0, y1 = sol.rectangle
    lines = [
        f"{sol.scene.name}: {len(sol.omega)} damped natural frequencies w = w_d + i sigma"
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
        "mode shapes (base-translation participation; modal mass for max |Y| = 1):",
        f"{'mode':>4}  {'omega [rad/s]':>24}  {'modal mass [kg]':>16}  {'participation':>14}"
        f"  {'effective mass [kg]':>20}",
    ]
    for i, s in enumerate(shapes, start=1):
        lines.append(
            f"{i:>4}  {_fmt(s.omega, '>24.17g')}  {_fmt(s.modal_mass, '>16.6g')}"
            f"  {_fmt(s.participation, '>14.6g')}  {_fmt(s.effective_mass, '>20.6g')}"
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


def _points(block: list[list[str]], first: str) -> tuple[np.ndarray, np.ndarray]:
    """A block ``first,Y_1,...`` (real shapes) or ``first,Y_1_re,Y_1_im,...`` (complex):
    the positions and the matrix (points x modes)."""
    head = block[0]
    if head[0] != first:
        raise ValueError(f"not a mode-shape block of mstmm: expected {first!r}, got {head[0]!r}")
    values = np.array([[float(v) for v in r] for r in block[1:]], dtype=float)
    values = values.reshape(len(block) - 1, len(head))
    if len(head) > 1 and head[1].endswith("_re"):
        return values[:, 0], values[:, 1::2] + 1j * values[:, 2::2]
    return values[:, 0], values[:, 1:]


#: Which table a CSV's first header row starts: what :func:`read_csv` reports as ``kind``.
_KINDS = {
    SHAPE_SUMMARY_HEADER: "shapes",
    DAMPED_HEADER: "damped",
    ("mode", "omega_rad_s", "f_hz", "multiplicity", "converged"): "frequencies",
}


def read_csv(text: str) -> dict[str, Any]:
    """Read any CSV mstmm writes back into arrays, recognising it by its header rows.

    * ``solve --format csv``: ``kind`` ``"frequencies"`` (undamped) or ``"damped"``;
    * ``solve --shapes --format csv``: ``"shapes"`` or ``"damped_shapes"``, the summary's
      columns plus ``x``, ``Y`` (points x modes; complex for a damped scene), ``mass_x``,
      ``mass_Y`` (empty without hanging masses);
    * ``frf``: ``"frf"``, ``omega_rad_s``, ``f_hz`` and ``<output>_re``, ``_im``, ``_abs``,
      ``_phase_deg`` per output, plus ``H`` (frequencies x outputs, complex) and
      ``outputs`` (their labels);
    * ``sweep``: ``"sweep"``, a column per varied field and ``omega`` (points x modes)
      beside the ``omega_<i>`` columns.

    Every first-block column is an array under its header name (booleans, integers or
    floats). Raises ValueError on a text mstmm did not write.
    """
    blocks = _blocks(text)
    if not blocks:
        raise ValueError("not a CSV of mstmm: empty")
    head, rows = blocks[0][0], blocks[0][1:]
    if len(set(head)) != len(head) or any(len(r) != len(head) for r in rows):
        raise ValueError("not a CSV of mstmm: rows of unequal length or repeated columns")
    out: dict[str, Any] = {name: _column([r[j] for r in rows]) for j, name in enumerate(head)}
    kind = _KINDS.get(tuple(head))
    if kind is None and head[:2] == ["omega_rad_s", "f_hz"]:
        kind = "frf"
        labels = [h[: -len("_re")] for h in head[2::4]]
        if [h for h in head[2:]] != [f"{o}_{p}" for o in labels for p in _FRF_PARTS]:
            raise ValueError("not an frf CSV of mstmm: unexpected columns")
        out["outputs"] = labels
        out["H"] = np.column_stack([out[f"{o}_re"] + 1j * out[f"{o}_im"] for o in labels]).reshape(
            len(rows), len(labels)
        )
    elif kind is None and any(h.startswith("omega_") for h in head):
        kind = "sweep"
        modes = [h for h in head if re.fullmatch(r"omega_\d+", h)]
        out["omega"] = np.column_stack([out[h] for h in modes]).reshape(len(rows), len(modes))
    elif kind is None:
        raise ValueError(f"not a CSV of mstmm: unknown header {','.join(head)!r}")
    if len(blocks) > 1:
        if kind not in ("shapes", "damped"):
            raise ValueError("not a CSV of mstmm: a second block after a one-block table")
        kind = "shapes" if kind == "shapes" else "damped_shapes"
        out["x"], out["Y"] = _points(blocks[1], "x")
        if len(blocks) > 2:
            out["mass_x"], out["mass_Y"] = _points(blocks[2], "mass_x")
        else:
            out["mass_x"], out["mass_Y"] = np.empty(0), out["Y"][:0]
    out["kind"] = kind
    return out


def read_shapes_csv(text: str) -> dict[str, np.ndarray]:
    """Parse :func:`shapes_csv` or :func:`damped_shapes_csv` back: ``omega`` (complex,
    ``w_d + i sigma``, for a damped scene), ``multiplicity``, ``x``, ``Y`` (samples x
    modes, complex when damped), ``mass_x``, ``mass_Y`` (masses x modes); undamped also
    ``modal_mass``, ``participation``, ``effective_mass``; damped also ``w_d``, ``sigma``,
    ``zeta``, ``converged`` (see :func:`read_csv`)."""
    data = read_csv(text)
    if data["kind"] == "shapes":
        return {
            "omega": data["omega_rad_s"].astype(float),
            "modal_mass": data["modal_mass_kg"].astype(float),
            "participation": data["participation"].astype(float),
            "effective_mass": data["effective_mass_kg"].astype(float),
            "multiplicity": data["multiplicity"],
            "x": data["x"],
            "Y": data["Y"],
            "mass_x": data["mass_x"],
            "mass_Y": data["mass_Y"],
        }
    if data["kind"] == "damped_shapes":
        w_d, sigma = data["w_d_rad_s"].astype(float), data["sigma_1_s"].astype(float)
        return {
            "omega": w_d + 1j * sigma,
            "w_d": w_d,
            "sigma": sigma,
            "zeta": data["zeta"].astype(float),
            "multiplicity": data["multiplicity"],
            "converged": data["converged"],
            "x": data["x"],
            "Y": data["Y"],
            "mass_x": data["mass_x"],
            "mass_Y": data["mass_Y"],
        }
    raise ValueError("not a mode-shape CSV of mstmm")


_FRF_PARTS = ("re", "im", "abs", "phase_deg")


def frf_csv_header(labels: Sequence[str]) -> str:
    """The header row of :func:`frf_csv`."""
    header: list[str] = ["omega_rad_s", "f_hz"]
    for label in labels:
        header += [f"{label}_{part}" for part in _FRF_PARTS]
    return _csv([header])


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


def frf_csv(omegas: np.ndarray, H: np.ndarray, labels: Sequence[str]) -> str:
    """``omega_rad_s,f_hz`` then per output ``<label>_re,_im,_abs,_phase_deg``, one row per
    frequency (``mstmm frf``); H is (frequencies, outputs)."""
    return frf_csv_header(labels) + frf_csv_rows(omegas, H)


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
    """The damped summary (``damped_csv``), an empty line, ``x,Y_1_re,Y_1_im,...`` (one row
    per sample along the beam), and ``mass_x,Y_1_re,Y_1_im,...`` (one row per hanging
    mass, when there are any): the complex shapes of ``mstmm solve --shapes``."""
    shapes = _shapes(sol)
    out = damped_csv(sol) + "\n"
    head = ["x"]
    for i in range(len(shapes)):
        head += [f"Y_{i + 1}_re", f"Y_{i + 1}_im"]
    rows: list[Sequence[Any]] = [head]
    for k, x in enumerate(shapes[0].x):
        row = [_num(x)]
        for s in shapes:
            row += [_num(s.Y[k].real), _num(s.Y[k].imag)]
        rows.append(row)
    out += _csv(rows)
    if shapes[0].mass_x.size:
        rows = [["mass_x", *head[1:]]]
        for k, x in enumerate(shapes[0].mass_x):
            row = [_num(x)]
            for s in shapes:
                row += [_num(s.mass_Y[k].real), _num(s.mass_Y[k].imag)]
            rows.append(row)
        out += "\n" + _csv(rows)
    return out


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


def bands_csv(b) -> str:
    """The dispersion: omega, f, propagating pairs, Re k and Im k (1/m) of both pairs (the
    more attenuated first)."""
    out = io.StringIO()
    out.write("omega,f,propagating,re_k1,im_k1,re_k2,im_k2\n")
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

"""Command line: ``mstmm solve | sweep | plot | derive | show``.

Bad input prints one line ``mstmm: error: <file>: <field>: <problem> (got <value>)``
and exits with status 2, before anything is written. Exit statuses: see ``EPILOG``.
"""

from __future__ import annotations

import argparse
import math
import os
import re
import sys
import time
import warnings
from pathlib import Path
from typing import TYPE_CHECKING

from . import __version__, progress
from .signals import (
    EXIT_TERMINATED,
    Terminated,
    interrupts_kept,
    interrupts_not_lost,
    sigterm_as_interrupt,
)

if TYPE_CHECKING:
    from .scene import Scene


def _load() -> None:
    """Import the modules that load numpy, scipy and numba (a second or more on a busy
    machine): called by :func:`main` once Ctrl-C and SIGTERM are handled, so that an
    interrupt during the imports prints one line, not a traceback."""
    global FORMULATIONS, KernelError, CannotWrite, SceneError, check_band, load_scene, limits
    from . import limits
    from .kernels import FORMULATIONS, KernelError
    from .output import CannotWrite
    from .scene import SceneError, check_band, load_scene


EXIT_FAILURE = 1
EXIT_BAD_INPUT = 2
EXIT_UNTRUSTED = 3
EXIT_INTERRUPTED = 130
COMMAND_LINE = "<command line>"

EPILOG = """\
exit status:
  0    success
  1    failure: no natural frequency in the band, a kernel cache that cannot be
       written, a missing dependency, an unexpected error (one line; --debug
       shows the traceback)
  2    bad scene file or option, or an --out whose directory takes no file (one
       line naming the file or option, the field and the value; nothing is written)
  3    results written, but a root is NOT TRUSTED, the roots disagree with the
       Wittrick-Williams count, or (sweep) a point could not be certified (NaN)
  130  interrupted (Ctrl-C)
  143  terminated (SIGTERM); as with Ctrl-C, no temporary file is left behind
"""

SCENE_HELP = "scene file (TOML); default: the bundled paper example wu_chou_1998"
MODES_HELP = "the N lowest natural frequencies, counting every one, rigid-body zeros included"
BAND_HELP = (
    "every natural frequency in [LO, HI] rad/s (instead of --modes); both edges inclusive by"
    " 4 ulp: [LO (1 - 4 eps), HI (1 + 4 eps)], eps = 2.2e-16"
)
FORMULATION_HELP = (
    "characteristic function: 'stable' (second-compound chain, full precision) or 'paper'"
    " (det U_bar of the paper's Eq. (4) as printed; loses digits at higher modes)"
    " (default: %(default)s)"
)
RANGE_HELP = (
    "PATH=RANGE: a field (beam.length|EI|mass_per_length, beam.segments[s].EI|mass_per_length,"
    " a beam's or segment's kappa_GA|rho_I|axial_force|foundation_k|foundation_kG,"
    " attachments[i].x or any key of its kind, e.g. attachments[i].k, attachments[i].J,"
    " attachments[i].k[j] of a chain; i in x order)"
    " and its values: LOG:lo:hi:n, LIN:lo:hi:n or a list 1,2,3"
)


def _scene(path: str | None) -> Scene:
    """The scene at ``path``, or the bundled paper example."""
    if path is None:
        from . import example_path

        return load_scene(example_path("wu_chou_1998"))
    return load_scene(path)


OUT_HELP = (
    "write the --format output to this file instead of standard output, which then gets"
    " the file's name (a regular file or a new one; through a symbolic link to its target)"
)

#: ``--quantity`` of ``frf`` and ``plot --frf``.
_QUANTITY = {"choices": ("receptance", "mobility", "accelerance"), "default": "receptance"}
QUANTITY_HELP = "H (m/N, rad/N, ...), i w H or -w^2 H (default: %(default)s)"


def _positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}")
    return value


def _frequency(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a frequency in rad/s, got {text!r}") from None
    if not value >= 0.0 or value == float("inf"):
        raise argparse.ArgumentTypeError(f"expected a finite frequency >= 0, got {text!r}")
    return value


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # one line, status 2
        sys.stderr.write(f"mstmm: error: {message}\n")
        raise SystemExit(EXIT_BAD_INPUT)


class _Help(argparse.RawDescriptionHelpFormatter):
    """Keeps the epilog's layout."""


def build_parser() -> argparse.ArgumentParser:
    """The ``mstmm`` argument parser: every option has help text and shows its default."""
    _load()
    ap = _Parser(
        prog="mstmm",
        description="Natural frequencies and mode shapes of beams by MSTMM.",
        epilog=EPILOG,
        formatter_class=_Help,
    )
    ap.add_argument("--version", action="version", version=f"mstmm {__version__}")
    ap.add_argument("--debug", action="store_true", help="show tracebacks of unexpected errors")
    ap.add_argument(
        "--verbose", action="store_true", help="print where the time went (on standard error)"
    )
    sub = ap.add_subparsers(dest="command", required=True, parser_class=_Parser, metavar="COMMAND")

    def command(name: str, summary: str) -> argparse.ArgumentParser:
        return sub.add_parser(
            name, help=summary, description=summary, epilog=EPILOG, formatter_class=_Help
        )

    s = command("solve", "natural frequencies and mode shapes of a scene")
    s.add_argument("scene", nargs="?", metavar="SCENE", help=SCENE_HELP)
    g = s.add_mutually_exclusive_group()
    g.add_argument("--modes", type=_positive_int, metavar="N", help=MODES_HELP + " (default: 10)")
    g.add_argument("--band", nargs=2, type=_frequency, metavar=("LO", "HI"), help=BAND_HELP)
    s.add_argument(
        "--format",
        choices=("table", "json", "csv"),
        help="a table, one JSON object, or CSV (default: table; csv with --out)",
    )
    s.add_argument("--out", type=Path, help=OUT_HELP)
    s.add_argument("--formulation", choices=FORMULATIONS, default="stable", help=FORMULATION_HELP)
    s.add_argument(
        "--shapes",
        action="store_true",
        help="mode shapes too, one per natural frequency: with --format json every shape's"
        " samples (x, Y, theta, M, Q, mass_x, mass_Y) and its modal mass, participation and"
        " effective mass; with --format csv three blocks separated by an empty line: one row"
        " per mode (omega, f, multiplicity, modal mass, participation, effective mass), then"
        " x, Y_1..Y_n, theta_1..theta_n, M_1..M_n, Q_1..Q_n (one row per point along the"
        " beam; every header with its unit), then mass_x,Y_1..Y_n (one row per carried"
        " mass); with --format table a per-mode summary and the sum of effective"
        " masses against the total mass (a damped scene: w_d, sigma, where |Y| peaks and"
        " the shape's complexity) (default: off)",
    )
    f = command(
        "frf",
        "frequency response between two points: receptance, mobility or accelerance",
    )
    f.add_argument("scene", nargs="?", metavar="SCENE", help=SCENE_HELP)
    f.add_argument(
        "--input",
        required=True,
        metavar="LOAD:WHERE=VALUE",
        help="the unit harmonic load: force:x=X (N at X m), moment:x=X (N m), force:mass=J"
        " (on hanging mass J, numbered from 0 in x order as the mode shapes' mass_Y) or"
        " moment:inertia=J (on rotary inertia J, a torsional absorber's)",
    )
    f.add_argument(
        "--output",
        action="append",
        required=True,
        metavar="RESPONSE:WHERE=VALUE",
        help="displacement:x=X, rotation:x=X, displacement:mass=J or rotation:inertia=J; repeat for"
        " more columns",
    )
    f.add_argument(
        "--band",
        nargs=2,
        type=_frequency,
        required=True,
        metavar=("LO", "HI"),
        help="frequencies from LO to HI rad/s",
    )
    f.add_argument(
        "--points",
        type=_positive_int,
        default=1000,
        metavar="N",
        help="number of frequencies (default: %(default)s)",
    )
    f.add_argument(
        "--spacing",
        choices=("lin", "log"),
        default="lin",
        help="frequencies spaced linearly or logarithmically (default: %(default)s)",
    )
    f.add_argument("--quantity", **_QUANTITY, help=QUANTITY_HELP)
    f.add_argument(
        "--format",
        choices=("csv", "json", "table"),
        default="csv",
        help="CSV (omega, f, and per output re, im, abs, phase in degrees), one JSON object,"
        " or a table (default: %(default)s)",
    )
    f.add_argument("--out", type=Path, help="file to write (default: standard output)")
    b = command(
        "bands",
        "dispersion of a periodic beam (the scene is its unit cell) and certified band gaps",
    )
    b.add_argument(
        "scene",
        metavar="CELL",
        help="scene file (TOML): its beam and components make one cell (a scene with"
        " repeat = N: its cell); the end conditions play no part",
    )
    b.add_argument(
        "--band",
        nargs=2,
        type=_frequency,
        metavar=("LO", "HI"),
        help="frequencies from LO to HI rad/s (Hz with --hz) (default: 0 to where the bare"
        " beam's k L = 3 pi)",
    )
    b.add_argument(
        "--points",
        type=_positive_int,
        default=1000,
        metavar="N",
        help="frequencies of the dispersion curves (default: %(default)s)",
    )
    b.add_argument(
        "--format",
        choices=("table", "json", "csv"),
        help="the edges and gaps as a table, everything as one JSON object, or the"
        " dispersion curves as CSV (omega, f, propagating pairs, Re k and Im k of both pairs"
        " in 1/m) (default: table; csv with --out)",
    )
    b.add_argument("--out", type=Path, help=OUT_HELP)
    b.add_argument("--hz", action="store_true", help="--band in Hz (default: rad/s)")
    b.add_argument(
        "--plot",
        type=Path,
        metavar="FILE",
        help="also draw the dispersion (Re k, Im k) with the gaps shaded (needs matplotlib)",
    )
    d = command("derive", "write the kernel of a scene's topology, print where")
    d.add_argument("scene", metavar="SCENE", help="scene file (TOML)")
    d.add_argument("--out", type=Path, help="directory (default: the kernel cache)")
    v = command(
        "sweep",
        "lowest frequencies over a parameter study (all cores); damped: w_d, sigma, zeta",
    )
    v.add_argument("scene", metavar="SCENE", help="scene file (TOML)")
    v.add_argument(
        "--vary",
        action="append",
        required=True,
        metavar="PATH=RANGE",
        help=RANGE_HELP + "; several --vary (each field once) vary together, point by point",
    )
    v.add_argument(
        "--modes", type=_positive_int, default=5, metavar="N", help=MODES_HELP + " (default: 5)"
    )
    v.add_argument("--out", type=Path, help="CSV file (default: standard output)")
    v.add_argument(
        "--scheduler", help="Dask scheduler address, e.g. tcp://HOST:8786 (default: local cores)"
    )
    q = command("plot", "paper Fig. 2 (log|Delta| and mode shapes) or a veering diagram")
    q.add_argument("scene", nargs="?", metavar="SCENE", help=SCENE_HELP)
    q.add_argument(
        "-o", "--out", type=Path, required=True, help="image file; format from the suffix"
    )
    g = q.add_mutually_exclusive_group()
    g.add_argument(
        "--modes",
        type=_positive_int,
        metavar="N",
        help=MODES_HELP + "; the shape panel skips the zeros (default: 4; with --sweep 5)",
    )
    g.add_argument("--band", nargs=2, type=_frequency, metavar=("LO", "HI"), help=BAND_HELP)
    q.add_argument(
        "--sweep",
        metavar="PATH=RANGE",
        help="veering diagram instead of Fig. 2: " + RANGE_HELP,
    )
    q.add_argument("--formulation", choices=FORMULATIONS, default="stable", help=FORMULATION_HELP)
    q.add_argument(
        "--frf",
        action="store_true",
        help="frequency response instead of Fig. 2: magnitude (log) and phase of --output to"
        " --input over --band, the natural frequencies marked",
    )
    q.add_argument("--input", metavar="LOAD:WHERE=VALUE", help="with --frf: as mstmm frf --input")
    q.add_argument(
        "--output",
        action="append",
        metavar="RESPONSE:WHERE=VALUE",
        help="with --frf: as mstmm frf --output",
    )
    q.add_argument(
        "--points",
        type=_positive_int,
        default=2000,
        metavar="N",
        help="with --frf: number of frequencies (default: %(default)s)",
    )
    q.add_argument("--quantity", **_QUANTITY, help="with --frf: " + QUANTITY_HELP)
    q.add_argument(
        "--hz",
        action="store_true",
        help="with --frf: --band LO HI in Hz and the frequency axis in Hz (default: rad/s)",
    )
    w = command(
        "show",
        "print a scene's component matrices and structure (U_bar and det when small)",
    )
    w.add_argument("scene", metavar="SCENE", help="scene file (TOML)")
    w.add_argument(
        "--full",
        action="store_true",
        help="print the whole symbolic U_bar (and its determinant up to 6x6) whatever the size;"
        " can take minutes and megabytes beyond 2 attachments (default: only when small)",
    )
    w.add_argument("--latex", action="store_true", help="print LaTeX instead of pretty text")
    return ap


def _checked_band(args, scene: Scene) -> tuple[float, float] | None:
    """``--band`` as a tuple, checked against the scene (None without ``--band``)."""
    band = _band(args)
    if band is not None:
        check_band(scene, band, COMMAND_LINE, "--band")
    return band


def _band(args) -> tuple[float, float] | None:
    """``--band`` as a tuple, HI above LO (None without ``--band``)."""
    if args.band is None:
        return None
    band = (float(args.band[0]), float(args.band[1]))
    if band[1] <= band[0]:
        raise SceneError(COMMAND_LINE, "--band", "HI must exceed LO", list(band))
    return band


def _check_out_dir(path: Path, option: str = "--out") -> Path:
    """Before any work: an output file's directory must exist and take a new file, and the
    path must be a regular file or nothing yet (:func:`mstmm.output.check_out_file`).
    Returns the file to write (a symbolic link's target)."""
    from .output import CannotWrite, NotAFile, check_out_file

    try:
        return check_out_file(path)
    except NotAFile as exc:
        raise SceneError(COMMAND_LINE, option, exc.problem, Path(path)) from None
    except CannotWrite as exc:  # the path in full (a value's repr is cut at 80 characters)
        raise SceneError(COMMAND_LINE, option, str(exc)) from None


_NUMPY_SCALAR = re.compile(r"\bnp\.(?:float|int|uint|complex|bool_?)\d*\(([^()]*)\)")


def _plain_numbers(message: str) -> str:
    """``np.float64(0.5)`` in a message as ``0.5``: users read numbers, not numpy reprs."""
    return _NUMPY_SCALAR.sub(r"\1", message)


def _warn(message: str) -> None:
    print(f"mstmm: warning: {_plain_numbers(message)}", file=sys.stderr)


def _scene_or_frame(path: str | None):
    """The beam :class:`Scene` or the frame (``[[members]]``) at ``path``, its file read
    and parsed once (``mstmm.frame`` imported for a frame only); the bundled paper example
    without a path."""
    if path is None:
        return _scene(None)
    from .scene import scene_from_dict
    from .scene.reading import is_frame, read_table

    data, source = read_table(path)
    if is_frame(data):
        from .frame import frame_from_file

        return frame_from_file(data, source)
    return scene_from_dict(data, source=source)


def _solve_frame(args, frame) -> int:
    from .frame import solve_frame
    from .frame.report import frame_text

    if args.formulation != "stable":
        raise SceneError(
            COMMAND_LINE, "--formulation", "a frame is solved by its dynamic stiffness only",
            args.formulation,
        )  # fmt: skip
    band = _band(args)
    sol = solve_frame(frame, modes=args.modes, band=band, shapes=args.shapes)
    if band is not None and not sol.omega.size:
        raise NoRoots(
            f"no natural frequency in the band [{band[0]:.6g}, {band[1]:.6g}] rad/s"
            + (" (the count confirms it)" if sol.count_checked else "")
        )
    _emit(args, frame_text(sol, args.format, args.shapes))
    for warning in getattr(sol, "warnings", ()):  # a damped frame's
        _warn(warning)
    trusted = sol.count_checked and all(getattr(sol, "converged", ()))
    return 0 if trusted else EXIT_UNTRUSTED


def _solve(args) -> int:
    from . import output
    from .scene import Scene
    from .solve import solve
    from .topology import topology_of

    _out_format(args)
    scene = _scene_or_frame(args.scene)
    if not isinstance(scene, Scene):
        return _solve_frame(args, scene)
    band = _checked_band(args, scene)
    damped = topology_of(scene).damped
    if damped and args.formulation != "stable":
        raise SceneError(
            COMMAND_LINE,
            "--formulation",
            "a damped scene is solved by the complex stable chain only (the paper's det U_bar"
            " is real)",
            args.formulation,
        )
    sol = solve(
        scene, modes=args.modes, band=band, formulation=args.formulation, shapes=args.shapes
    )
    if sol.buckling is not None and sol.buckling.buckled:
        if args.format == "json":
            _emit(args, output.dumps(sol.to_dict())[0] + "\n")
        else:
            _emit(args, f"{scene.name}: {sol.buckling.message()}\n")
        return EXIT_UNTRUSTED
    if band is not None and not sol.omega.size:
        raise NoRoots(
            f"no natural frequency in the band [{band[0]:.6g}, {band[1]:.6g}] rad/s"
            + (" (the count confirms it)" if sol.count_checked else "")
        )
    _phase(args, "solve", **sol.timings)
    if args.format == "json":
        text, nulls = output.dumps(sol.to_dict(shapes=args.shapes))
        _emit(args, text + "\n")
        if nulls:
            _warn(
                f"{len(nulls)} non-finite number(s) written as null in the JSON output"
                f" (first: {nulls[0]}); they cannot be trusted"
            )
    else:
        _emit(args, output.solution_text(sol, args.format, args.shapes))
    for warning in sol.warnings:
        _warn(warning)
    trusted = bool(sol.count_checked) and bool(sol.converged.all())
    return 0 if trusted else EXIT_UNTRUSTED


def _out_format(args) -> None:
    """``--out`` of ``solve`` and ``bands`` checked before any work (a symbolic link: its
    target); ``--format`` unset: csv into a file, a table on standard output."""
    if args.out is not None:
        args.out_file = _check_out_dir(args.out)
    if args.format is None:
        args.format = "table" if args.out is None else "csv"


def _emit(args, text: str) -> None:
    """``text`` on standard output, or written atomically to ``--out`` (its name printed)."""
    if args.out is None:
        sys.stdout.write(text)
        return
    from .output import write_atomically

    write_atomically(args.out_file, text)
    print(args.out)


class NoRoots(RuntimeError):
    """A band asked for holds no natural frequency."""


def _seconds_since_process_start() -> float | None:
    """Wall time since this process started (Linux ``/proc``), for ``--verbose``."""
    try:
        with open("/proc/self/stat") as fh:
            start_ticks = float(fh.read().rsplit(")", 1)[1].split()[19])
        with open("/proc/uptime") as fh:
            uptime = float(fh.read().split()[0])
        return uptime - start_ticks / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError):
        return None


_LABELS = {
    "startup": "start-up (Python, numpy, numba, mstmm imports)",
    "load": "scene and kernel module",
    "derive": "of which SymPy derivation",
    "compile": "machine code (numba cache load or compile)",
    "scan_refine": "root search, refinement, count",
    "shapes": "mode shapes",
    "sweep": "parameter study",
    "output": "output",
    "total": "total",
}


def _phase(args, what: str, **seconds: float) -> None:
    """With ``--verbose``: one line per phase on standard error."""
    if not args.verbose:
        return
    for key, value in seconds.items():
        label = _LABELS.get(key, key)
        print(f"mstmm: time: {what}: {label}: {value:.6f} s", file=sys.stderr)


def _report_waits(args) -> None:
    """With ``--verbose``: each wait on a compile helper, how long and how it ended."""
    if args.verbose:
        from . import compiling

        for line in compiling.waits():
            print(f"mstmm: waited: {line}", file=sys.stderr)


def _sweep(args) -> int:
    from . import output
    from .study import sweep

    if args.out is not None:
        _check_out_dir(args.out)
    vary: dict[str, object] = {}
    for item in args.vary:
        path, values = _vary_item(item, "--vary")
        if path in vary:
            raise SceneError(COMMAND_LINE, f"--vary {path}", "the same field is varied twice", item)
        vary[path] = values
    from .scene import scene_from_dict
    from .scene.reading import is_frame, read_table

    data, source = read_table(args.scene)
    t0 = time.perf_counter()
    if is_frame(data):
        omega, text, notes = _sweep_frame(args, data, source, vary)
    else:
        scene = scene_from_dict(data, source=source)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            omega = sweep(
                scene, vary, modes=args.modes, scheduler=args.scheduler, progress=progress.enabled
            )
        text = output.sweep_csv(scene, vary, omega)
        notes = [str(w.message) for w in caught]
    _phase(args, "sweep", sweep=time.perf_counter() - t0)
    if args.out is None:
        sys.stdout.write(text)
    else:
        output.write_atomically(args.out, text)
        print(args.out)
    for note in notes:
        _warn(note)
    return EXIT_UNTRUSTED if _has_nan(omega) else 0


def _sweep_frame(args, data, source: str, vary: dict) -> tuple:
    """``mstmm sweep`` of a frame file (:func:`mstmm.frame.study.sweep_frame`): the
    frequencies, their CSV and what to warn of."""
    from . import output
    from .frame.study import field_unit, sweep_frame

    if args.scheduler is not None:
        raise SceneError(COMMAND_LINE, "--scheduler", "a frame's study runs on this machine")
    omega = sweep_frame(data, vary, modes=args.modes, source=source)
    units = [field_unit(data, path) for path in vary]
    notes = []
    if _has_nan(omega):
        notes.append("some points' roots could not be confirmed by the count: set to NaN")
    return omega, output.sweep_csv(None, vary, omega, units=units), notes


def _has_nan(values) -> bool:
    """Whether any value of an array is NaN (a point the sweep could not certify)."""
    import numpy as np

    return bool(np.isnan(values).any())


def _vary_item(item: str, option: str) -> tuple[str, object]:
    """``PATH=RANGE`` of --vary / --sweep."""
    from .study import parse_range

    path, sep, spec = item.partition("=")
    if not sep:
        raise SceneError(COMMAND_LINE, option, "expected PATH=RANGE", item)
    try:
        return path, parse_range(spec)
    except ValueError as exc:
        raise SceneError(COMMAND_LINE, f"{option} {path}", f"bad range: {exc}", spec) from None


def _plot(args) -> int:
    try:
        from . import plot
    except ModuleNotFoundError as exc:
        if (exc.name or "").split(".")[0] != "matplotlib":
            raise
        print(
            "mstmm: error: plotting needs matplotlib, mstmm's optional extra 'plot':"
            ' pip install "mstmm[plot]" (in a source tree: pip install ".[plot]")',
            file=sys.stderr,
        )
        return EXIT_FAILURE
    _check_image_format(plot, args.out, "--out")
    target = _check_out_dir(args.out)  # a symbolic link: its target
    from .scene import Scene

    scene = _scene_or_frame(args.scene)
    if not isinstance(scene, Scene):
        return _plot_frame(args, target, scene)
    if args.frf:
        if args.band is None or args.sweep is not None:
            raise SceneError(COMMAND_LINE, "--frf", "needs --band LO HI (and no --sweep)", None)
        omegas, src, dst = _frf_request(args, scene)
        if args.hz:
            omegas = omegas * (2.0 * math.pi)
        plot.frf_figure(scene, src, dst, omegas, path=target, quantity=args.quantity, hz=args.hz)
    elif args.hz:
        raise SceneError(COMMAND_LINE, "--hz", "only with --frf", None)
    elif args.sweep is not None:
        if args.band is not None:
            raise SceneError(COMMAND_LINE, "--band", "not with --sweep", list(args.band))
        path, values = _vary_item(args.sweep, "--sweep")
        plot.veering(scene, path, values, modes=args.modes or 5, path=target)
    else:
        if args.input is not None or args.output:
            option = "--input" if args.input is not None else "--output"
            raise SceneError(COMMAND_LINE, option, "needs --frf (a frequency response plot)")
        band = _checked_band(args, scene)
        try:
            plot.figure2(
                scene, target, modes=args.modes or 4, band=band, formulation=args.formulation
            )
        except plot.Buckled as exc:  # as solve says it
            print(f"{scene.name}: {exc}")
            return EXIT_UNTRUSTED
    print(args.out)
    return 0


def _plot_frame(args, target: Path, frame) -> int:
    """``mstmm plot`` of a frame: its lowest mode shapes drawn on the structure."""
    from .frame import solve_frame
    from .frame.plot import mode_shapes

    for option in ("frf", "sweep", "band", "input"):
        if getattr(args, option, None):
            raise SceneError(COMMAND_LINE, f"--{option}", "a frame plots its mode shapes only")
    if frame.motion == "out_of_plane":
        raise SceneError(
            frame.source, "motion", "plots of a grillage's modes (out of the plane) are not"
            " built yet: mstmm solve --shapes gives them", frame.motion,
        )  # fmt: skip
    modes = args.modes or 6
    mode_shapes(solve_frame(frame, modes), target, modes)
    print(args.out)
    return 0


def _check_image_format(plot, path: Path, option: str) -> None:
    """An image file's suffix must name a format matplotlib writes, before any work."""
    if path.suffix[1:].lower() not in plot.formats():
        raise SceneError(
            COMMAND_LINE,
            option,
            f"unknown image format; use one of {sorted(plot.formats())}",
            str(path),
        )


def _bands(args) -> int:
    from . import output
    from .bands import bands, cell_of

    if args.plot is not None:
        plot_to = _check_out_dir(args.plot, "--plot")
        try:
            from . import plot
        except ModuleNotFoundError as exc:
            if (exc.name or "").split(".")[0] != "matplotlib":
                raise
            raise SceneError(
                COMMAND_LINE, "--plot", 'needs matplotlib: pip install "mstmm[plot]"'
            ) from None
        _check_image_format(plot, args.plot, "--plot")
    _out_format(args)
    cell = cell_of(_scene(args.scene))
    band = None
    if args.band is not None:
        band = tuple(float(v) for v in args.band)
        if args.hz:
            band = tuple(v * 2.0 * math.pi for v in band)
        if band[1] <= band[0]:
            raise SceneError(COMMAND_LINE, "--band", "HI must exceed LO", list(args.band))
        limits.check_bands_band(cell, band, COMMAND_LINE, "--band")
    result = bands(cell, band=band, points=args.points)
    if result.buckling is not None:  # as solve: one line, no curves, exit 3
        print(f"{cell.name}: {result.buckling}")
        return EXIT_UNTRUSTED
    if args.format == "json":
        _emit(args, output.dumps(output.bands_dict(result))[0] + "\n")
    elif args.format == "csv":
        _emit(args, output.bands_csv(result))
    else:
        _emit(args, output.bands_table(result))
    if args.plot is not None:
        plot.dispersion(result, path=plot_to, hz=args.hz)
        print(args.plot, file=sys.stderr)
    _phase(args, "bands", **result.timings)
    for note in result.notes:
        _warn(note)
    return 0 if result.count_checked else EXIT_UNTRUSTED


def _frf_request(args, scene: Scene):
    """The frequencies and the parsed --input / --output of ``frf`` and ``plot --frf``,
    checked: the band as ``solve --band`` checks it, at most
    :data:`mstmm.response.MAX_RESPONSES` responses."""
    from .response import parse_point

    if args.input is None or not args.output:
        raise SceneError(COMMAND_LINE, "--input", "--frf needs --input and --output")
    src = parse_point(args.input, "input", COMMAND_LINE)
    dst = [parse_point(o, "output", COMMAND_LINE) for o in args.output]
    return _frequencies(args, *_checked_band(args, scene), len(dst)), src, dst


def _frequencies(args, lo: float, hi: float, outputs: int):
    """The ``--points`` frequencies of a frequency response from LO to HI, spaced as
    ``--spacing`` says, checked: LO > 0 for a log spacing, at most
    :data:`mstmm.response.MAX_RESPONSES` responses over ``outputs`` outputs."""
    import numpy as np

    from .response import MAX_RESPONSES

    if getattr(args, "spacing", "lin") == "log" and lo <= 0.0:
        raise SceneError(COMMAND_LINE, "--band", "a log spacing needs LO > 0", lo)
    if args.points * outputs > MAX_RESPONSES:
        raise SceneError(
            COMMAND_LINE,
            "--points",
            f"{args.points} frequencies x {outputs} output(s) is more than {MAX_RESPONSES:.0e}"
            " responses (16 bytes each): fewer points, or several runs over narrower bands",
            args.points,
        )
    space = np.geomspace if getattr(args, "spacing", "lin") == "log" else np.linspace
    return space(lo, hi, args.points)


def _frf(args) -> int:
    import contextlib

    import numpy as np

    from . import output
    from .response import frf_chunks
    from .scene import Scene

    if args.out is not None:
        _check_out_dir(args.out)
    scene = _scene_or_frame(args.scene)
    if not isinstance(scene, Scene):
        return _frf_frame(args, scene)
    omegas, src, dst = _frf_request(args, scene)
    labels, units = [str(d) for d in dst], output.frf_units(args.quantity, src, dst)
    t0 = time.perf_counter()
    chunks = frf_chunks(scene, [src], dst, omegas, quantity=args.quantity, source=COMMAND_LINE)
    with contextlib.ExitStack() as stack:
        fh = sys.stdout if args.out is None else stack.enter_context(output.atomic_file(args.out))
        if args.format == "json":
            H = np.empty((omegas.size, len(dst)), dtype=complex)
            for at, part in chunks:  # held (bounded by MAX_RESPONSES), written in pieces
                H[at] = part[:, 0, :]
            nulls = _frf_json(fh, scene, args.quantity, str(src), labels, omegas, H)
            if nulls:
                _warn(f"{nulls} non-finite value(s) written as null in the JSON output")
        else:
            header, rows = (
                (output.frf_csv_header(labels, units), output.frf_csv_rows)
                if args.format == "csv"
                else (
                    output.frf_table_header(scene.name, args.quantity, str(src), labels),
                    output.frf_table_rows,
                )
            )
            fh.write(header)
            for at, part in chunks:  # computed and written chunk by chunk
                fh.write(rows(omegas[at], part[:, 0, :]))
    _phase(args, "frf", frf=time.perf_counter() - t0)
    if args.out is not None:
        print(args.out)
    return 0


def _frf_frame(args, frame) -> int:
    """``mstmm frf`` of a frame: points ``QUANTITY:WHERE[=DIRECTION]`` at nodes or along
    members (:func:`mstmm.frame.response.parse_point`), the whole band in one call."""
    import contextlib

    from . import output
    from .frame.response import frf, parse_point
    from .response import as_quantity
    from .units import frf_unit

    src = parse_point(args.input, "--input", COMMAND_LINE)
    dst = [parse_point(o, "--output", COMMAND_LINE) for o in args.output]
    omegas = _frequencies(args, *_band(args), len(dst))
    t0 = time.perf_counter()
    H = as_quantity(args.quantity, omegas, frf(frame, src, dst, omegas))
    labels = [o.strip() for o in args.output]
    units = [frf_unit(args.quantity, d[0], src[0]) for d in dst]
    with contextlib.ExitStack() as stack:
        fh = sys.stdout if args.out is None else stack.enter_context(output.atomic_file(args.out))
        if args.format == "json":
            if _frf_json(fh, frame, args.quantity, args.input.strip(), labels, omegas, H):
                _warn("non-finite values (natural frequencies) written as null in the JSON output")
        elif args.format == "csv":
            fh.write(output.frf_csv_header(labels, units) + output.frf_csv_rows(omegas, H))
        else:
            head = output.frf_table_header(frame.name, args.quantity, args.input.strip(), labels)
            fh.write(head + output.frf_table_rows(omegas, H))
    _phase(args, "frf", frf=time.perf_counter() - t0)
    if args.out is not None:
        print(args.out)
    return 0


def _frf_json(fh, scene: Scene, quantity: str, src: str, labels, omegas, H) -> int:
    """``mstmm frf --format json`` written piece by piece: the keys of ``frf``'s JSON, each
    array in chunks of :data:`mstmm.chunks.MOST` numbers; returns the count of nulls."""
    import json

    import numpy as np

    from .chunks import MOST
    from .output import json_numbers

    head = {"scene": scene.name, "quantity": quantity, "input": src, "outputs": labels}
    fh.write(json.dumps(head)[:-1])
    nulls = 0

    def array(values) -> None:
        nonlocal nulls
        fh.write("[")
        for k in range(0, len(values), MOST):
            text, bad = json_numbers(values[k : k + MOST])
            fh.write((", " if k else "") + text)
            nulls += bad
        fh.write("]")

    for key, values in (("omega", omegas), ("hz", omegas / (2.0 * np.pi))):
        fh.write(f', "{key}": ')
        array(values)
    for key, part in (("re", H.real), ("im", H.imag)):
        fh.write(f', "{key}": [')
        for j in range(H.shape[1]):
            fh.write(", " if j else "")
            array(part[:, j])
        fh.write("]")
    fh.write("}\n")
    return nulls


def _derive(args) -> int:
    from .kernels import cache_dir, write_kernel
    from .topology import topology_of

    if args.out is not None:  # a directory, made if missing: its first existing ancestor
        existing = args.out
        while not existing.exists() and existing != existing.parent:
            existing = existing.parent
        _check_out_dir(existing / "kernel.py")
    scene = _scene(args.scene)
    topology = topology_of(scene)
    out = args.out if args.out is not None else cache_dir()
    try:
        path = write_kernel(topology, out)
    except OSError as exc:
        if args.out is not None:
            reason = (exc.strerror or str(exc)).lower()
            raise SceneError(COMMAND_LINE, "--out", f"cannot write to {out} ({reason})") from None
        raise KernelError(f"cannot write the kernel into {out}: {exc}") from exc
    print(path)
    return 0


#: ``mstmm show`` prints the whole symbolic U_bar (without --full) up to this many
#: attachments: its size grows about 16-fold per two attachments (count_ops: 631 with
#: one, 13355 with three, 219670 with five).
SHOW_FULL_MAX_ATTACHMENTS = 1
#: ``mstmm show`` draws U_bar's zero pattern up to this size (a line of 2 n characters).
SHOW_PATTERN_MAX = 60


def _show(args) -> int:
    import textwrap

    from .scene import Scene

    scene = _scene_or_frame(args.scene)
    if not isinstance(scene, Scene):
        from .frame.show import describe

        sys.stdout.write(describe(scene))
        return 0

    import sympy as sp

    from mstmm.derive import MAX_DETERMINANT_SIZE, component_matrices, symbolic

    from .structure import structure_of

    render = sp.latex if args.latex else (lambda e: sp.pretty(e, wrap_line=False))
    beam = scene.beam
    n = len(scene.attachments)
    print(f"{scene.name}: {beam.left} - {beam.right}, {n} point component(s)")
    print("component matrices (paper Eqs. (1)-(3)); beam state [Y, theta, M, Q]:")
    for title, matrix in component_matrices():
        print(f"{title} =")
        print(render(matrix))
    from mstmm.derive.assemble import general_field, general_segments

    for s in general_segments(scene):
        print(
            f"segment {s} (Timoshenko, axial force, foundation: derive/segments/general.py):"
            f" Z' = A Z, its transfer E{s}(l) = exp(A l) in place of U_B(l), A ="
        )
        print(render(general_field(scene, s)))
    der = structure_of(scene)  # sizes and zero pattern only, no SymPy product: fast for any n
    print("chain (x = 0 to L):")
    print(textwrap.fill(" -> ".join(der.chain), 100, subsequent_indent="  "))
    print(f"Z_all ({len(der.Z_all)}) =")
    print(textwrap.fill(", ".join(der.Z_all), 100, subsequent_indent="  "))
    print(f"Z_bar ({len(der.Z_bar)}, the unknowns left by the boundary conditions) =")
    print(textwrap.fill(", ".join(der.Z_bar), 100, subsequent_indent="  "))
    size = len(der.Z_bar)
    nonzero = int(der.pattern.sum())
    print(f"U_bar: {size}x{size}, {nonzero} of {size * size} entries nonzero (X):")
    if size > SHOW_PATTERN_MAX:
        print(f"  (the pattern is drawn up to {SHOW_PATTERN_MAX}x{SHOW_PATTERN_MAX})")
    for row in der.sparsity() if size <= SHOW_PATTERN_MAX else ():
        print("  " + row)
    if n > SHOW_FULL_MAX_ATTACHMENTS and not args.full:
        print(
            f"(the symbolic U_bar and its determinant are not printed for more than"
            f" {SHOW_FULL_MAX_ATTACHMENTS} attachment(s); to print U_bar, large and slow:)"
        )
        print(f"  mstmm show --full {args.scene}")
        return 0
    der = symbolic(scene)
    print("U_bar =")
    print(render(der.U_bar))
    if size <= MAX_DETERMINANT_SIZE - 1:
        print("det U_bar =")
        print(render(der.determinant()))
    else:
        print(f"(det U_bar not expanded: U_bar is {size}x{size})")
    return 0


def _one_line_warning(message, category, filename, lineno, file=None, line=None) -> None:
    """Any Python warning that reaches the command line: one ``mstmm: warning:`` line."""
    _warn(" ".join(str(message).split()))


#: BLAS thread pools the command keeps to one thread unless the user sets them: mstmm's
#: own linear algebra is on small matrices (the numerics are numba's), where OpenBLAS's
#: extra threads only spin: 0.2 s of a second core on a first solve, taken from other
#: work on a busy machine (benchmarks.busy), for no gain in time.
SINGLE_THREADED_BLAS = ("OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``mstmm`` command."""
    for name in SINGLE_THREADED_BLAS:  # before numpy loads
        os.environ.setdefault(name, "1")
    try:
        with sigterm_as_interrupt(), interrupts_not_lost():
            with interrupts_kept():
                _load()
            return _main(argv)
    except KeyboardInterrupt as exc:  # Ctrl-C or SIGTERM: one line, 128 + the signal
        if "--debug" in (sys.argv[1:] if argv is None else argv):
            raise
        if isinstance(exc, Terminated):
            print("mstmm: terminated", file=sys.stderr)
            return EXIT_TERMINATED
        print("mstmm: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED


def _main(argv: list[str] | None) -> int:
    started = _seconds_since_process_start() if argv is None else None
    t0 = time.perf_counter()
    args = build_parser().parse_args(argv)
    progress.enabled = sys.stderr.isatty() and getattr(args, "format", None) != "json"
    shown = warnings.showwarning
    warnings.showwarning = _one_line_warning
    try:
        limits.check_command_line(args, COMMAND_LINE)
        commands = {
            "solve": _solve,
            "frf": _frf,
            "bands": _bands,
            "sweep": _sweep,
            "plot": _plot,
            "derive": _derive,
            "show": _show,
        }
        status = commands[args.command](args)
        _report_waits(args)
        total = time.perf_counter() - t0
        if started is not None:
            _phase(args, args.command, startup=started, total=started + total)
        else:
            _phase(args, args.command, total=total)
        return status
    except NoRoots as exc:
        print(f"mstmm: error: {_plain_numbers(str(exc))}", file=sys.stderr)
        return EXIT_FAILURE
    except SceneError as exc:
        print(f"mstmm: error: {_plain_numbers(str(exc))}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except CannotWrite as exc:  # --out's directory changed since it was checked
        print(f"mstmm: error: {SceneError(COMMAND_LINE, '--out', str(exc))}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except KernelError as exc:
        print(f"mstmm: error: {_plain_numbers(str(exc))}", file=sys.stderr)
        return EXIT_FAILURE
    except ImportError as exc:
        if args.debug:
            raise
        name = (exc.name or "").split(".")[0]
        hint = f"the package {name!r} cannot be imported; reinstall it" if name else str(exc)
        print(f"mstmm: error: a dependency is missing: {hint} ({exc})", file=sys.stderr)
        return EXIT_FAILURE
    except BrokenPipeError:  # `mstmm solve | head`: the reader left, nothing to report
        sys.stdout = open(os.devnull, "w")  # noqa: SIM115 (keep the interpreter's flush quiet)
        return 0
    except Exception as exc:  # one line for the user, the traceback with --debug
        if args.debug:
            raise
        print(f"mstmm: error: {type(exc).__name__}: {exc} (--debug shows where)", file=sys.stderr)
        return EXIT_FAILURE
    finally:
        warnings.showwarning = shown

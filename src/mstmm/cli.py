"""Command line: ``mstmm solve | derive | show``.

Bad input prints one line ``mstmm: error: <file>: <field>: <problem> (got <value>)``
and exits with status 2, before anything is written.
"""

from __future__ import annotations

import argparse
import csv
import io
import json
import os
import sys
import time
from pathlib import Path

from . import progress
from .kernels import FORMULATIONS, KernelError
from .scene import Scene, SceneError, load_scene

EXIT_BAD_INPUT = 2
EXIT_FAILURE = 1


def _scene(path: str | None) -> Scene:
    if path is None:
        from . import example_path

        return load_scene(example_path("wu_chou_1998"))
    return load_scene(path)


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


def build_parser() -> argparse.ArgumentParser:
    ap = _Parser(prog="mstmm", description="Natural frequencies of beams by MSTMM.")
    ap.add_argument("--debug", action="store_true", help="show tracebacks of unexpected errors")
    ap.add_argument(
        "--verbose", action="store_true", help="print where the time went (on standard error)"
    )
    sub = ap.add_subparsers(dest="command", required=True, parser_class=_Parser)
    s = sub.add_parser("solve", help="natural frequencies and mode shapes of a scene")
    s.add_argument("scene", nargs="?", help="scene TOML (default: the bundled wu_chou_1998)")
    g = s.add_mutually_exclusive_group()
    g.add_argument("--modes", type=_positive_int, help="the N lowest frequencies (default 10)")
    g.add_argument(
        "--band",
        nargs=2,
        type=_frequency,
        metavar=("LO", "HI"),
        help="rad/s; both edges inclusive by 4 ulp: [LO (1 - 4 eps), HI (1 + 4 eps)], eps 2.2e-16",
    )
    s.add_argument("--format", choices=("table", "json", "csv"), default="table")
    s.add_argument("--formulation", choices=FORMULATIONS, default="stable")
    s.add_argument("--shapes", action="store_true", help="include mode shapes in JSON")
    d = sub.add_parser("derive", help="write the kernel of a scene's topology, print where")
    d.add_argument("scene")
    d.add_argument("--out", type=Path, help="directory (default: the kernel cache)")
    v = sub.add_parser("sweep", help="lowest frequencies over a parameter study (all cores)")
    v.add_argument("scene")
    v.add_argument(
        "--vary",
        action="append",
        required=True,
        metavar="PATH=RANGE",
        help="e.g. attachments[2].k=LOG:1e3:1e9:200, beam.EI=LIN:1e4:1e5:50 or a list 1,2,3",
    )
    v.add_argument("--modes", type=_positive_int, default=5)
    v.add_argument("--out", type=Path, help="CSV file (default: standard output)")
    v.add_argument("--scheduler", help="Dask scheduler address, e.g. tcp://HOST:8786")
    q = sub.add_parser(
        "plot", help="paper Fig. 2 (log|Delta| and mode shapes) or a veering diagram"
    )
    q.add_argument("scene", nargs="?", help="scene TOML (default: the bundled wu_chou_1998)")
    q.add_argument(
        "-o", "--out", type=Path, required=True, help="image file; format from the suffix"
    )
    g = q.add_mutually_exclusive_group()
    g.add_argument("--modes", type=_positive_int, help="elastic modes shown (default 4; sweep 5)")
    g.add_argument("--band", nargs=2, type=_frequency, metavar=("LO", "HI"), help="rad/s")
    q.add_argument(
        "--sweep",
        metavar="PATH=RANGE",
        help="veering diagram, e.g. attachments[2].k=LOG:1e3:1e9:200",
    )
    q.add_argument("--formulation", choices=FORMULATIONS, default="stable")
    w = sub.add_parser("show", help="print the symbolic U_bar of a scene (and det when small)")
    w.add_argument("scene")
    return ap


def _solve(args) -> int:
    from .solve import solve

    scene = _scene(args.scene)
    band = tuple(args.band) if args.band else None
    if band is not None and band[1] <= band[0]:
        raise SceneError("<command line>", "--band", "HI must exceed LO", list(band))
    sol = solve(
        scene,
        modes=args.modes,
        band=band,
        formulation=args.formulation,
        shapes=args.shapes and args.format == "json",
    )
    if band is not None and not sol.omega.size:
        raise NoRoots(
            f"no natural frequency in the band [{band[0]:.6g}, {band[1]:.6g}] rad/s"
            + (" (the count confirms it)" if sol.count_checked else "")
        )
    _phase(args, "solve", **sol.timings)
    if args.format == "json":
        print(json.dumps(sol.to_dict(shapes=args.shapes)))
    elif args.format == "csv":
        buf = io.StringIO()
        wr = csv.writer(buf, lineterminator="\n")
        wr.writerow(["mode", "omega_rad_s", "f_hz", "multiplicity", "converged"])
        for i, (w, f, m, c) in enumerate(
            zip(sol.omega, sol.hz, sol.multiplicity, sol.converged, strict=True), start=1
        ):
            wr.writerow([i, repr(float(w)), repr(float(f)), int(m), bool(c)])
        sys.stdout.write(buf.getvalue())
    else:
        print(f"{scene.name}: {len(sol.omega)} natural frequencies ({sol.formulation} formulation)")
        print(f"{'mode':>4}  {'omega [rad/s]':>24}  {'f [Hz]':>24}  mult")
        for i, (w, f, m, c) in enumerate(
            zip(sol.omega, sol.hz, sol.multiplicity, sol.converged, strict=True), start=1
        ):
            flag = "" if c else "  NOT TRUSTED"
            print(f"{i:>4}  {w:>24.17g}  {f:>24.17g}  {m:>4}{flag}")
        t = sol.timings
        machine = (
            "kernel run as Python (cheaper than loading machine code)"
            if sol.kernel_mode == "interpreted"
            else f"compile {t['compile']:.3f} s"
        )
        print(
            f"time: load {t['load']:.3f} s, {machine}, "
            f"scan+refine {t['scan_refine'] * 1e3:.2f} ms, count checked: {sol.count_checked}"
        )
    for warning in sol.warnings:
        print(f"mstmm: warning: {warning}", file=sys.stderr)
    return 0


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


def _sweep(args) -> int:
    import os
    import tempfile

    from .study import sweep

    scene = _scene(args.scene)
    vary = dict(_vary_item(item, "--vary") for item in args.vary)
    t0 = time.perf_counter()
    omega = sweep(
        scene, vary, modes=args.modes, scheduler=args.scheduler, progress=progress.enabled
    )
    _phase(args, "sweep", sweep=time.perf_counter() - t0)
    buf = io.StringIO()
    wr = csv.writer(buf, lineterminator="\n")
    wr.writerow([*vary, *(f"omega_{i + 1}" for i in range(args.modes))])
    for j in range(omega.shape[0]):
        wr.writerow([*(repr(float(v[j])) for v in vary.values()), *map(repr, omega[j].tolist())])
    if args.out is None:
        sys.stdout.write(buf.getvalue())
        return 0
    fd, tmp = tempfile.mkstemp(dir=args.out.parent or ".", prefix=".tmp-sweep-")
    with os.fdopen(fd, "w") as fh:
        fh.write(buf.getvalue())
    os.replace(tmp, args.out)
    print(args.out)
    return 0


def _vary_item(item: str, option: str) -> tuple[str, object]:
    """``PATH=RANGE`` of --vary / --sweep."""
    from .study import parse_range

    path, sep, spec = item.partition("=")
    if not sep:
        raise SceneError("<command line>", option, "expected PATH=RANGE", item)
    try:
        return path, parse_range(spec)
    except ValueError:
        raise SceneError("<command line>", f"{option} {path}", "bad range", spec) from None


def _plot(args) -> int:
    try:
        from . import plot
    except ModuleNotFoundError as exc:
        if (exc.name or "").split(".")[0] != "matplotlib":
            raise
        print("mstmm: error: plotting needs matplotlib: pip install 'mstmm[plot]'", file=sys.stderr)
        return EXIT_FAILURE
    where = "<command line>"
    if args.out.suffix[1:].lower() not in plot.formats():
        raise SceneError(
            where,
            "--out",
            f"unknown image format; use one of {sorted(plot.formats())}",
            str(args.out),
        )
    if not (args.out.parent if str(args.out.parent) else Path(".")).is_dir():
        raise SceneError(where, "--out", "directory does not exist", str(args.out.parent))
    scene = _scene(args.scene)
    if args.sweep is not None:
        if args.band is not None:
            raise SceneError(where, "--band", "not with --sweep", list(args.band))
        path, values = _vary_item(args.sweep, "--sweep")
        plot.veering(scene, path, values, modes=args.modes or 5, path=args.out)
    else:
        band = tuple(args.band) if args.band else None
        if band is not None and band[1] <= band[0]:
            raise SceneError(where, "--band", "HI must exceed LO", list(band))
        plot.figure2(
            scene, args.out, modes=args.modes or 4, band=band, formulation=args.formulation
        )
    print(args.out)
    return 0


def _derive(args) -> int:
    from .kernels import cache_dir, write_kernel
    from .topology import topology_of

    scene = _scene(args.scene)
    topology = topology_of(scene)
    out = args.out if args.out is not None else cache_dir()
    try:
        path = write_kernel(topology, out)
    except OSError as exc:
        raise KernelError(f"cannot write the kernel into {out}: {exc}") from exc
    print(path)
    return 0


def _show(args) -> int:
    import sympy as sp

    from mstmm.derive import MAX_DETERMINANT_SIZE, symbolic

    scene = _scene(args.scene)
    der = symbolic(scene)
    print(f"{scene.name}: Z_bar = {list(der.Z_bar)}")
    print("U_bar =")
    print(sp.pretty(der.U_bar, wrap_line=False))
    if der.U_bar.rows <= MAX_DETERMINANT_SIZE - 1:
        print("det U_bar =")
        print(sp.pretty(der.determinant(), wrap_line=False))
    else:
        print(f"(det U_bar not expanded: U_bar is {der.U_bar.rows}x{der.U_bar.rows})")
    return 0


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``mstmm`` command."""
    started = _seconds_since_process_start() if argv is None else None
    t0 = time.perf_counter()
    args = build_parser().parse_args(argv)
    progress.enabled = sys.stderr.isatty() and getattr(args, "format", None) != "json"
    try:
        commands = {
            "solve": _solve,
            "sweep": _sweep,
            "plot": _plot,
            "derive": _derive,
            "show": _show,
        }
        status = commands[args.command](args)
        total = time.perf_counter() - t0
        if started is not None:
            _phase(args, args.command, startup=started, total=started + total)
        else:
            _phase(args, args.command, total=total)
        return status
    except NoRoots as exc:
        print(f"mstmm: error: {exc}", file=sys.stderr)
        return EXIT_FAILURE
    except SceneError as exc:
        print(f"mstmm: error: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except KernelError as exc:
        print(f"mstmm: error: {exc}", file=sys.stderr)
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

"""Work-precision: wall time to the lowest 5 and 20 frequencies against their largest error.

The paper's example (``tests/data/wu_chou_1998.toml``); exact values: the ten
of ``tests/data/reference.json`` for the lowest 5, ``tests/reference_model.py``
``frequencies(scene, 20, dps=30)`` for the lowest 20 (both independent of
mstmm). Errors are computed in mpmath, so an error below 1e-16 is real.

Competitors, all on this machine in one run:

* mstmm warm (kernel compiled, ``kernel=mstmm.kernel_for(scene)`` reused):
  ``mstmm.solve(scene, modes=n, shapes=False, rtol=r, formulation=f)``,
  ``r`` in 1e-4, 1e-8, 1e-12, 0, both formulations;
* mstmm cold: a fresh ``python -m mstmm solve SCENE --modes n --format json``
  process with the kernel cached (numba's on-disk cache warm), and the first
  ever run of a topology that is not bundled (the example with a pinned left
  end) in an empty ``MSTMM_CACHE``: SymPy derivation, numba compilation, solve;
* the finite-element model ``tests/reference_fem.py`` (cubic Hermite elements,
  consistent mass) on meshes of 4 .. 1024 elements: ``dense`` (LAPACK on the
  shift-inverted problem), ``sparse`` (ARPACK shift-invert), the same with
  Richardson extrapolation (coarse mesh n and its bisection 2n, so n <= 512),
  and the textbook ``eigh(K, M)``;
* OpenSeesPy (``benchmarks/opensees_model.py``: ``elasticBeamColumn`` with
  ``-cMass``, ``zeroLength`` springs, ``eigen``), when it can be loaded;
* paper Table 1's times and frequencies (FEM, ANCM, MSTMM), quoted.

Each time is the median of repeated runs after one warm-up run (a run longer
than 2 s is measured once, everything having been loaded and compiled on a
small case before). A group of warm mstmm solves that does not finish within
its budget is stopped and reported as such.
"""

from __future__ import annotations

import json
import math
import multiprocessing
import os
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np
import reference_fem as fem  # tests/reference_fem.py
from mpmath import mp, mpf

import mstmm

from .machine import new_topology_env
from .table1 import QUOTED

ROOT = Path(__file__).resolve().parent.parent
SCENE = ROOT / "tests" / "data" / "wu_chou_1998.toml"
REFERENCE = ROOT / "tests" / "data" / "reference.json"
TESTS = ROOT / "tests"

RTOLS = (1e-4, 1e-8, 1e-12, 0.0)
MESHES = (4, 8, 16, 32, 64, 128, 256, 512, 1024)
MODES = (5, 20)
#: A single run longer than this (s) is measured once (no separate warm-up).
LONG = 2.0
#: Smallest error drawn (an exact result is drawn here).
ERROR_FLOOR = 1e-17


@dataclass
class Point:
    """One measured (or quoted) run: a method at one setting."""

    series: str  # legend label
    family: str  # mstmm-warm | mstmm-cold | mstmm-derive | fe | fe-richardson | opensees | quoted
    modes: int
    setting: str  # rtol=..., n=..., ...
    time: float  # seconds (median)
    error: float  # largest relative error over the modes (inf: failed)
    repeats: int = 1
    note: str = ""
    param: float = 0.0  # numeric setting (rtol or elements), for annotations


@dataclass
class Results:
    points: list[Point] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    opensees: str = ""  # why OpenSees is missing, or its version and solver
    cold_breakdown: dict[str, float] = field(default_factory=dict)
    profiles: dict[str, dict] = field(default_factory=dict)
    plateaus: dict[str, str] = field(default_factory=dict)
    #: ``mstmm.solve(scene, modes=5)`` as a user calls it (warm): seconds with the default
    #: ``shapes=True`` and with ``shapes=False``, and the number of runs.
    default_solve: dict[str, float] = field(default_factory=dict)
    quick: bool = False

    def to_json(self) -> dict:
        return asdict(self)

    @classmethod
    def from_json(cls, raw: dict) -> Results:
        raw = dict(raw)
        raw["points"] = [Point(**p) for p in raw["points"]]
        return cls(**raw)


# ------------------------------------------------------------------ helpers


def timed(fn, budget: float = 0.5, min_repeats: int = 5, max_repeats: int = 2000):
    """``(result, median seconds, repeats)``: one warm-up call, then repeats within ``budget``.

    A first call longer than :data:`LONG` seconds is taken as the measurement
    (repeats = 1): callers compile and load everything beforehand on a small case.
    """
    t = time.perf_counter()
    out = fn()
    first = time.perf_counter() - t
    if first > LONG:
        return out, first, 1
    times: list[float] = []
    spent = 0.0
    while len(times) < max_repeats:
        if len(times) >= min_repeats and spent >= budget:
            break
        t = time.perf_counter()
        fn()
        dt = time.perf_counter() - t
        times.append(dt)
        spent += dt
    return out, statistics.median(times), len(times)


def _reference_model():
    if str(TESTS) not in sys.path:
        sys.path.insert(0, str(TESTS))
    import reference_model  # tests/reference_model.py

    return reference_model


def exact(scene, modes: int) -> list:
    """Exact lowest ``modes`` frequencies (mpf): reference.json for <= 10, else the model."""
    with mp.workdps(40):
        if modes <= 10 and scene.name == "wu_chou_1998":
            data = json.loads(REFERENCE.read_text())[scene.name]["omega"]
            return [mpf(w) for w in data[:modes]]
        return list(_reference_model().frequencies(scene, modes, dps=30))


def max_rel_error(got, ref: list) -> float:
    """Largest ``|got - ref| / ref`` (mpmath); ``inf`` when too few values or not finite."""
    got = np.asarray(got, dtype=float)
    if got.size < len(ref) or not np.all(np.isfinite(got[: len(ref)])):
        return math.inf
    with mp.workdps(40):
        return max(_rel(float(g), r) for g, r in zip(got, ref))


def _rel(g: float, r) -> float:
    """Relative error; a zero (rigid-body) reference must be returned as exactly 0.0."""
    if r == 0:
        return 0.0 if g == 0.0 else math.inf
    return float(abs(mpf(g) - r) / abs(r))


def scene_toml(scene, name: str, left: str | None = None) -> str:
    """The TOML text of ``scene`` (optionally with another left end)."""
    b = scene.beam
    lines = [
        f'name = "{name}"',
        "[beam]",
        f"length = {b.length!r}",
        f"EI = {b.EI!r}",
        f"mass_per_length = {b.mass_per_length!r}",
        f'left = "{left or b.left}"',
        f'right = "{b.right}"',
    ]
    for a in scene.attachments:
        lines += ["[[attachments]]", 'type = "spring_mass"', f"x = {a.x!r}"]
        lines += [f"k = {a.k!r}", f"m = {a.m!r}"]
    return "\n".join(lines) + "\n"


def _cli(scene_path: Path, modes: int, env: dict | None = None) -> tuple[float, dict]:
    cmd = [sys.executable, "-m", "mstmm", "solve", str(scene_path), "--modes", str(modes)]
    cmd += ["--format", "json"]
    t = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env, check=False)
    dt = time.perf_counter() - t
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}: exit {proc.returncode}: {proc.stderr.strip()}")
    return dt, json.loads(proc.stdout)


def _python_c(code: str) -> float:
    t = time.perf_counter()
    subprocess.run([sys.executable, "-c", code], check=True, capture_output=True)
    return time.perf_counter() - t


def in_child(fn, budget: float) -> tuple[list, str]:
    """Run ``fn(emit)`` in a forked child for at most ``budget`` seconds.

    ``fn`` calls ``emit(item)`` for each result as it is ready (items must
    pickle). Returns the items received and ``""``, or the items received
    before the end and why it ended early (over budget, an exception). The
    child is ended by its own handle.
    """
    ctx = multiprocessing.get_context("fork")
    recv, send = ctx.Pipe(duplex=False)

    def target():
        try:
            fn(lambda item: send.send(("item", item)))
            send.send(("done", None))
        except BaseException as exc:  # report, never hang the parent
            send.send(("error", f"{type(exc).__name__}: {exc}"))
        finally:
            send.close()

    child = ctx.Process(target=target)
    child.start()
    send.close()
    items: list = []
    why = f"did not finish within {budget:.0f} s"
    deadline = time.perf_counter() + budget
    while True:
        left = deadline - time.perf_counter()
        if left <= 0 or not recv.poll(left):
            break
        try:
            kind, value = recv.recv()
        except EOFError:
            why = "the child process died"
            break
        if kind == "item":
            items.append(value)
        else:
            why = "" if kind == "done" else value
            break
    child.join(2.0)
    if child.is_alive():
        child.terminate()
        child.join()
    return items, why


# ------------------------------------------------------------------ profiling


class Probe:
    """A kernel that counts and times what the root search asks of it."""

    def __init__(self, kernel):
        self._kernel = kernel
        self.stats: dict[str, list[float]] = {}

    def __getattr__(self, name):
        return getattr(self._kernel, name)

    def _add(self, name: str, points: int, t0: float, its: int = 0) -> None:
        s = self.stats.setdefault(name, [0, 0, 0.0, 0])
        s[0] += 1
        s[1] += points
        s[2] += time.perf_counter() - t0
        s[3] += its

    def evaluate(self, omegas, p, formulation="stable"):
        t = time.perf_counter()
        out = self._kernel.evaluate(omegas, p, formulation)
        self._add("evaluate", int(np.size(omegas)), t)
        return out

    def delta(self, omega, p, formulation="stable"):
        t = time.perf_counter()
        out = self._kernel.delta(omega, p, formulation)
        self._add("delta", 1, t)
        return out

    def refine(self, a, b, p, formulation="stable", rtol=0.0, maxiter=200):
        t = time.perf_counter()
        out = self._kernel.refine(a, b, p, formulation, rtol, maxiter)
        self._add("refine", 1, t, its=out[1] + 2)
        return out

    def lowest(self, p, modes, certify=True, formulation="stable", rtol=0.0):
        t = time.perf_counter()
        out = self._kernel.lowest(p, modes, certify, formulation, rtol)
        self._add("lowest", int(modes), t, its=int(out.certified))
        return out

    def roots_in_band(self, p, lo, hi, from_bottom, formulation="stable", rtol=0.0):
        t = time.perf_counter()
        out = self._kernel.roots_in_band(p, lo, hi, from_bottom, formulation, rtol)
        self._add("lowest", len(out.omega), t, its=int(out.certified))
        return out

    def count_below(self, omegas, p):
        t = time.perf_counter()
        out = self._kernel.count_below(omegas, p)
        self._add("count_below", int(np.size(omegas)), t)
        return out


def profile_solve(
    scene, modes: int, formulation: str = "stable", kernel=None, runs: int = 3
) -> dict:
    """Where a warm ``mstmm.solve`` spends its time (fastest of ``runs`` instrumented runs):
    kernel calls, points, seconds."""
    kernel = kernel or mstmm.kernel_for(scene)
    if runs > 1:
        mstmm.solve(scene, modes=modes, shapes=False, formulation=formulation, kernel=kernel)
    best = None
    for _ in range(runs):
        probe = Probe(kernel)
        t = time.perf_counter()
        mstmm.solve(scene, modes=modes, shapes=False, formulation=formulation, kernel=probe)
        total = time.perf_counter() - t
        if best is None or total < best[0]:
            best = (total, probe.stats)
    total, stats = best
    out = {
        "modes": modes,
        "total": total,
        "calls": {
            k: {"calls": v[0], "points": v[1], "seconds": v[2], "its": v[3]}
            for k, v in stats.items()
        },
    }
    out["python"] = total - sum(v[2] for v in stats.values())
    if "lowest" in stats:  # the kernel's scan: its grid, costed by a timed evaluate
        out["lowest_grid"] = _lowest_grid(kernel, scene, modes)
    return out


def _lowest_grid(kernel, scene, modes: int) -> dict:
    """The kernel's ``lowest`` scan replayed with ``evaluate``: its grid (uniform in beta up to
    ``(modes + 1.5) pi``), the nodes it visits before the ``modes``-th sign change (where it
    stops), what those evaluations cost, and what one count costs."""
    per_mode = getattr(kernel.module, "NODES_PER_MODE", 24)
    b_hi = (modes + 1.5) * math.pi
    nodes = int(math.ceil((b_hi - 1e-3) / math.pi * per_mode)) + 1
    b = scene.beam
    beta = np.linspace(1e-3, b_hi, nodes)
    w = beta**2 * math.sqrt(b.EI / b.mass_per_length) / b.length**2
    p = mstmm.parameter_vector(scene)
    (mant, _), t, _ = timed(lambda: kernel.evaluate(w, p), 0.05, min_repeats=3)
    changes = np.nonzero(np.sign(mant[1:]) != np.sign(mant[:-1]))[0]
    want = modes - kernel.rigid_body_modes(p)
    visited = int(changes[want - 1]) + 2 if 0 < want <= changes.size else nodes
    sub = w[:: max(1, nodes // 16)]
    _, tc, _ = timed(lambda: kernel.count_below(sub, p), 0.05, min_repeats=3)
    return {
        "nodes": nodes,
        "per_mode": per_mode,
        "visited": visited,
        "beta_stop": float(beta[visited - 1]),
        "scan_seconds": t * visited / nodes,
        "count_seconds_per_point": tc / sub.size,
    }


# ------------------------------------------------------------------ measurements


def measure_mstmm_warm(
    res: Results, scene, refs: dict, rtols, budget: float, group_budget: float
) -> None:
    """Warm solves; each (formulation, modes) group in a forked child within ``group_budget``."""
    kernel = mstmm.kernel_for(scene)
    mstmm.solve(scene, modes=5, shapes=False, kernel=kernel)  # compile before forking
    for formulation in ("stable", "paper"):
        for modes in MODES:

            def group(emit, f=formulation, m=modes):
                for rtol in rtols:
                    sol, t, n = timed(
                        lambda r=rtol: mstmm.solve(
                            scene, modes=m, shapes=False, rtol=r, formulation=f, kernel=kernel
                        ),
                        budget,
                    )
                    flagged = int(np.count_nonzero(~sol.converged))
                    note = (
                        f"{flagged} of {sol.omega.size} roots flagged NOT TRUSTED by the solver"
                        if flagged
                        else ""
                    )
                    emit((rtol, t, max_rel_error(sol.omega, refs[m]), n, note))

            items, why = in_child(group, group_budget)
            series = f"mstmm warm, {formulation}"
            for rtol, t, err, n, note in items:
                res.points.append(
                    Point(series, "mstmm-warm", modes, f"rtol={rtol:g}", t, err, n, note, rtol)
                )
            if why:
                rtol = rtols[len(items)]
                res.points.append(
                    Point(
                        series,
                        "mstmm-warm",
                        modes,
                        f"rtol={rtol:g}",
                        math.nan,
                        math.inf,
                        0,
                        f"solve {why}",
                        rtol,
                    )
                )
                res.notes.append(
                    f"{series}, lowest {modes}, rtol={rtol:g}: the solve {why} (stopped; "
                    "the remaining tolerances were not run)"
                )
    for modes in MODES:
        res.profiles[f"paper example, lowest {modes}, stable, rtol=0"] = profile_solve(
            scene, modes, kernel=kernel
        )


def measure_default_solve(res: Results, scene, budget: float) -> None:
    """The default call, ``mstmm.solve(scene, modes=5)`` (mode shapes on), warm, against the
    same without shapes; median of many runs, the two interleaved in rounds."""
    mstmm.solve(scene, modes=5)  # load, compile, warm every path both calls take
    mstmm.solve(scene, modes=5, shapes=False)
    runs = {"shapes": [], "no_shapes": []}
    spent, rounds = 0.0, 0
    while rounds < 50 or (spent < 4 * budget and rounds < 2000):
        for key, shapes in (("shapes", True), ("no_shapes", False)):
            t = time.perf_counter()
            mstmm.solve(scene, modes=5, shapes=shapes)
            dt = time.perf_counter() - t
            runs[key].append(dt)
            spent += dt
        rounds += 1
    res.default_solve = {k: statistics.median(v) for k, v in runs.items()}
    res.default_solve["repeats"] = rounds


#: Fresh-process series: label, family, ``MSTMM_INTERPRET_BUDGET`` (None: the default).
COLD_SERIES = (
    ("mstmm cold: fresh process, kernel cached", "mstmm-cold", None),
    ("mstmm cold, compiled only (MSTMM_INTERPRET_BUDGET=0)", "mstmm-cold-jit", "0"),
)


def _env(budget: str | None) -> dict:
    """This environment with ``MSTMM_INTERPRET_BUDGET`` set to ``budget`` (None: unset)."""
    env = {k: v for k, v in os.environ.items() if k != "MSTMM_INTERPRET_BUDGET"}
    if budget is not None:
        env["MSTMM_INTERPRET_BUDGET"] = budget
    return env


def measure_mstmm_cold(res: Results, refs: dict, repeats: int, breakdown: bool) -> None:
    """Fresh ``python -m mstmm solve`` processes, the bundled kernel in numba's cache.

    By default such a small solve runs the kernel as Python (``mstmm.interpret``);
    the second series forces the compiled kernel, as before that tier existed.
    """
    for label, family, budget in COLD_SERIES:
        for modes in MODES:
            _cli(SCENE, modes, _env("0"))  # warm numba's on-disk cache
            runs = [_cli(SCENE, modes, _env(budget)) for _ in range(repeats)]
            t = statistics.median(r[0] for r in runs)
            out = runs[0][1]
            res.points.append(
                Point(
                    label,
                    family,
                    modes,
                    f"python -m mstmm solve ({out['kernel_mode']})",
                    t,
                    max_rel_error(out["omega"], refs[modes]),
                    repeats,
                    note=f"in-process load {out['timings']['load']:.3f} s, "
                    f"scan+refine {out['timings']['scan_refine'] * 1e3:.2f} ms",
                )
            )
    if breakdown:
        parts = {
            "python -c pass": "pass",
            "import numpy": "import numpy",
            "import numba": "import numba",
            "import mstmm": "import mstmm",
            "+ load_scene, kernel_for (module, no machine code yet)": (
                "import mstmm; s = mstmm.load_scene(mstmm.example_path()); k = mstmm.kernel_for(s)"
            ),
            "+ mstmm.solve(s, modes=5, shapes=False) (default: run as Python)": (
                "import mstmm; s = mstmm.load_scene(mstmm.example_path()); "
                "k = mstmm.kernel_for(s); mstmm.solve(s, modes=5, shapes=False)"
            ),
            "+ the same compiled only (numba cache load + solve)": (
                "import mstmm; mstmm.interpret.set_budget(0); "
                "s = mstmm.load_scene(mstmm.example_path()); "
                "k = mstmm.kernel_for(s); mstmm.solve(s, modes=5, shapes=False)"
            ),
        }
        with tempfile.TemporaryDirectory(prefix="mstmm-bench-numba-") as tmp:
            # numba's fixed price of a first call from its on-disk cache, on any function
            Path(tmp, "nb_trivial.py").write_text(
                "from numba import njit\n\n\n@njit(cache=True)\ndef f(x):\n    return x + 1.0\n"
            )
            parts["import numba; first call of a trivial cached @njit function (numba's floor)"] = (
                f"import sys; sys.path.insert(0, {tmp!r}); import nb_trivial; nb_trivial.f(1.0)"
            )
            for label, code in parts.items():
                _python_c(code)
                res.cold_breakdown[label] = statistics.median(
                    _python_c(code) for _ in range(repeats)
                )


def measure_first_derive(res: Results, scene, repeats: int) -> None:
    """First-ever run of a topology that is not bundled: derive + compile + solve, empty cache."""
    name = "wu_chou_1998_pinned"
    with tempfile.TemporaryDirectory(prefix="mstmm-bench-") as tmp:
        path = Path(tmp) / f"{name}.toml"
        path.write_text(scene_toml(scene, name, left="pinned"))
        variant = mstmm.load_scene(path)
        for modes in MODES:
            ref = exact(variant, modes)
            runs = []
            for i in range(repeats if modes == 5 else 1):
                env = _env("0")  # compiled: what this point measures
                env.update(new_topology_env(Path(tmp) / f"cache-{modes}-{i}"))
                env["MSTMM_INTERPRET_BUDGET"] = "0"
                env["MSTMM_COMPILE_HELPERS"] = "1"  # as a user's process compiles
                runs.append(_cli(path, modes, env))
            t = statistics.median(r[0] for r in runs)
            out = runs[0][1]
            res.points.append(
                Point(
                    "mstmm cold: first run of a new topology (derive + compile)",
                    "mstmm-derive",
                    modes,
                    "pinned-free, empty MSTMM_CACHE",
                    t,
                    max_rel_error(out["omega"], ref),
                    len(runs),
                    note="the paper's example with a pinned left end (error against its own "
                    f"reference); in-process load {out['timings']['load']:.2f} s",
                )
            )


def measure_fe(res: Results, scene, refs: dict, meshes, budget: float) -> None:
    for solver in ("sparse", "dense", "eigh"):
        for modes in MODES:
            for n in meshes:
                _fe_point(res, scene, refs, modes, n, solver, False, budget)
                if solver != "eigh" and 2 * n <= meshes[-1]:
                    _fe_point(res, scene, refs, modes, n, solver, True, budget)


def _fe_point(res, scene, refs, modes, n, solver, rich, budget) -> None:
    fn = fem.richardson if rich else fem.frequencies
    ndof = 2 * n + len(scene.attachments)
    if modes > ndof - 3:
        return
    label = {
        "dense": "FE dense (eigh, shift-inverted)",
        "sparse": "FE sparse (eigsh shift-invert)",
        "eigh": "FE textbook eigh(K, M)",
    }[solver] + (" + Richardson" if rich else "")
    try:
        w, t, reps = timed(lambda: fn(scene, modes, n, solver), budget, min_repeats=3)
        err, note = max_rel_error(w, refs[modes]), ""
    except Exception as exc:  # a failing mesh is a result too
        t, reps, err = math.nan, 0, math.inf
        note = f"{type(exc).__name__}: {exc}"
    setting = f"n={n}" + (f"+{2 * n}" if rich else "")
    family = "fe-richardson" if rich else "fe"
    res.points.append(Point(label, family, modes, setting, t, err, reps, note, param=n))


def opensees_series(solver: str) -> str:
    """Legend label of OpenSeesPy with one eigen solver."""
    return f"OpenSeesPy {solver}"


def measure_opensees(res: Results, refs: dict, meshes, budget: float) -> None:
    """OpenSeesPy with each eigen solver it offers (:data:`opensees_model.SOLVERS`)."""
    from . import opensees_model

    out = opensees_model.run(
        {"scene": str(SCENE), "modes": list(MODES), "meshes": list(meshes), "budget": budget}
    )
    if "error" in out:
        res.opensees = f"OpenSeesPy could not be run: {out['error']}"
        return
    solvers = ", ".join(f"`{s}`" for s in out["solvers"])
    res.opensees = f"OpenSeesPy {out['version']}, `eigen(solver, n)` with each of {solvers}"
    for row in out["rows"]:
        modes, n = row["modes"], row["n"]
        series = opensees_series(row["solver"])
        if "error" in row:
            point = Point(
                series, "opensees", modes, f"n={n}", math.nan, math.inf, 0, row["error"], n
            )
        else:
            err = max_rel_error(row["omega"], refs[modes])
            point = Point(
                series, "opensees", modes, f"n={n}", row["time"], err, row["repeats"], param=n
            )
        res.points.append(point)


def opensees_best(res: Results, modes: int) -> dict[str, Point]:
    """Per OpenSeesPy eigen solver: its most accurate point (a failed point if all failed)."""
    out: dict[str, Point] = {}
    for p in res.points:
        if p.family != "opensees" or p.modes != modes:
            continue
        best = out.get(p.series)
        if best is None or p.error < best.error:
            out[p.series] = p
    return out


def opensees_summary(res: Results, modes: int) -> str:
    """Each solver's best error (or its failure), one clause each."""
    parts = []
    for series, p in opensees_best(res, modes).items():
        solver = series.replace("OpenSeesPy ", "")
        if math.isfinite(p.error):
            parts.append(f"`{solver}` {fmt_err(p.error)} ({p.setting}, {fmt_time(p.time)})")
        else:
            from .opensees_model import KNOWN_FAILURES

            note = p.note.splitlines()[0][:80] if p.note else "?"
            parts.append(f"`{solver}` " + KNOWN_FAILURES.get(solver, f"failed ({note})"))
    return "; ".join(parts)


def add_quoted(res: Results, refs: dict) -> None:
    for label, (omega, cpu) in QUOTED.items():
        seconds = float(cpu.split()[0])
        res.points.append(
            Point(
                f"paper Table 1: {label.replace(' (quoted)', '')} (quoted, not measured)",
                "quoted",
                5,
                "as printed",
                seconds,
                max_rel_error(omega, refs[5]),
                0,
                note="frequencies and CPU time as printed in the paper (other machine)",
            )
        )


def plateau_of(pts: list[Point]):
    """``(best, worst after best, slope of log error on log n)`` of a mesh series, or None."""
    pts = sorted(pts, key=lambda p: p.param)
    ok = [p for p in pts if math.isfinite(p.error)]
    if not ok:
        return None
    best = min(ok, key=lambda p: p.error)
    after = [p for p in pts if p.param > best.param]
    if not after:
        return best, None, None
    worst = max(after, key=lambda p: p.error)
    slope = None
    if math.isfinite(worst.error) and best.error > 1e-14 and worst.error > 4 * best.error:
        slope = math.log(worst.error / best.error) / math.log(worst.param / best.param)
    return best, worst, slope


def plateaus(res: Results) -> None:
    """Where each mesh-refined series stops improving: its best mesh and what follows."""
    for key in sorted(
        {(p.series, p.modes) for p in res.points if p.family in ("fe", "fe-richardson", "opensees")}
    ):
        pts = [p for p in res.points if (p.series, p.modes) == key]
        pts.sort(key=lambda p: p.param)
        ok = [p for p in pts if math.isfinite(p.error)]
        if not ok:
            continue
        best = min(ok, key=lambda p: p.error)
        after = [p for p in pts if p.param > best.param]
        if not after:
            text = f"still improving at the finest mesh ({best.setting}: {best.error:.1e})"
        else:
            worst = max(after, key=lambda p: p.error)
            if not math.isfinite(worst.error):
                tail = f"fails at {worst.setting} ({worst.note.split(':')[0] or 'no result'})"
            elif best.error < 1e-14:
                tail = f"{worst.error:.1e} at {worst.setting}: at round-off level already"
            else:
                tail = f"{worst.error:.1e} at {worst.setting}"
                fin = [p for p in after if math.isfinite(p.error) and p.error > 0]
                if len(fin) >= 1 and worst.error > 4 * best.error:
                    slope = math.log(worst.error / best.error) / math.log(worst.param / best.param)
                    tail += f" (error ~ n^{slope:.1f}: round-off)"
            text = f"best {best.error:.1e} at {best.setting}; finer meshes do not help: {tail}"
        res.plateaus[f"{key[0]}, lowest {key[1]}"] = text


def stage(res, name: str, log, fn, *args, **kwargs) -> None:
    """Run one measurement stage; a failure is recorded in ``res.notes``, not raised."""
    log(name)
    try:
        fn(*args, **kwargs)
    except Exception as exc:
        res.notes.append(f"{name} failed: {type(exc).__name__}: {exc}")
        log(f"  FAILED: {type(exc).__name__}: {exc}")


def run(quick: bool = False, log=print) -> Results:
    """All the measurements (``quick``: a few seconds' smoke run)."""
    res = Results(quick=quick)
    scene = mstmm.load_scene(SCENE)
    refs = {m: exact(scene, m) for m in MODES}
    budget = 0.05 if quick else 0.5
    rtols = (1e-8, 0.0) if quick else RTOLS
    group_budget = 3.0 if quick else 30.0
    stage(
        res,
        "work-precision: mstmm warm",
        log,
        measure_mstmm_warm,
        res,
        scene,
        refs,
        rtols,
        budget,
        group_budget,
    )
    stage(
        res,
        "work-precision: default solve (shapes on)",
        log,
        measure_default_solve,
        res,
        scene,
        budget,
    )
    stage(
        res,
        "work-precision: mstmm cold (fresh processes)",
        log,
        measure_mstmm_cold,
        res,
        refs,
        1 if quick else 5,
        breakdown=not quick,
    )
    if quick:
        res.notes.append("--quick: first-ever derive + compile not measured")
    else:
        stage(
            res,
            "work-precision: first-ever derive + compile",
            log,
            measure_first_derive,
            res,
            scene,
            3,
        )
    stage(
        res,
        "work-precision: finite elements",
        log,
        measure_fe,
        res,
        scene,
        refs,
        MESHES[:4] if quick else MESHES,
        budget,
    )
    if quick:
        res.opensees = "OpenSeesPy not run (--quick)"
    else:
        stage(res, "work-precision: OpenSeesPy", log, measure_opensees, res, refs, MESHES, budget)
    add_quoted(res, refs)
    plateaus(res)
    return res


# ------------------------------------------------------------------ report

STYLE = {
    "mstmm warm, stable": dict(color="C0", marker="o", lw=2),
    "mstmm warm, paper": dict(color="C1", marker="s", lw=2),
    "mstmm cold: fresh process, kernel cached": dict(color="C0", marker="P", ms=10, ls=""),
    "mstmm cold, compiled only (MSTMM_INTERPRET_BUDGET=0)": dict(
        color="C9", marker="P", ms=10, ls=""
    ),
    "mstmm cold: first run of a new topology (derive + compile)": dict(
        color="C0", marker="X", ms=10, ls=""
    ),
    "FE dense (eigh, shift-inverted)": dict(color="C2", marker="^"),
    "FE sparse (eigsh shift-invert)": dict(color="C3", marker="v"),
    "FE dense (eigh, shift-inverted) + Richardson": dict(color="C2", marker="^", ls="--"),
    "FE sparse (eigsh shift-invert) + Richardson": dict(color="C3", marker="v", ls="--"),
    "FE textbook eigh(K, M)": dict(color="C7", marker=".", ls=":"),
    "OpenSeesPy -genBandArpack": dict(color="C4", marker="D"),
    "OpenSeesPy -fullGenLapack": dict(color="C6", marker="d", ls="--"),
    "OpenSeesPy -symmBandLapack": dict(color="C5", marker="d", ls=":"),
}


def plot(res: Results, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(14, 6.2))
    for ax, modes in zip(axes, MODES):
        pts = [p for p in res.points if p.modes == modes and math.isfinite(p.time)]
        for series in dict.fromkeys(p.series for p in pts):
            sp = [p for p in pts if p.series == series and math.isfinite(p.error)]
            if not sp:
                continue
            sp.sort(key=lambda p: p.param if p.family != "mstmm-warm" else -p.param)
            x = [max(p.error, ERROR_FLOOR) for p in sp]
            y = [p.time for p in sp]
            if series.startswith("paper Table 1"):
                ax.plot(x, y, marker="*", ms=13, ls="", label=series)
                continue
            style = dict(STYLE.get(series, {}))
            ax.plot(x, y, label=series, **style)
            if sp[0].family in ("fe", "fe-richardson", "opensees"):
                for p, xi, yi in zip(sp, x, y):
                    if p.param in (sp[0].param, sp[-1].param) or p.param == 64:
                        ax.annotate(
                            f"{int(p.param)}",
                            (xi, yi),
                            fontsize=7,
                            xytext=(3, 3),
                            textcoords="offset points",
                            color=style.get("color", "k"),
                        )
            if sp[0].family == "mstmm-warm" and series.endswith("stable"):
                for p, xi, yi in zip(sp, x, y):
                    ax.annotate(
                        p.setting,
                        (xi, yi),
                        fontsize=7,
                        xytext=(0, -12),
                        textcoords="offset points",
                        color="C0",
                        ha="center",
                    )
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.invert_xaxis()
        ax.axvline(1e-10, color="0.6", lw=0.8, ls=":")
        ax.set_xlabel(f"largest relative error of the lowest {modes} frequencies")
        ax.set_ylabel("wall time [s] (median)")
        ax.set_title(f"lowest {modes} frequencies, paper example (Wu & Chou 1998)")
        ax.grid(True, which="major", alpha=0.3)
        notes = panel_notes(res, modes)
        if notes:
            ax.text(
                0.99,
                0.99,
                "\n".join(notes),
                transform=ax.transAxes,
                fontsize=7,
                va="top",
                ha="right",
                bbox=dict(boxstyle="round", fc="white", ec="0.7", alpha=0.9),
            )
        ax.text(
            0.01,
            0.01,
            "numbers: FE elements (Richardson: coarse mesh)\n"
            f"errors below {ERROR_FLOOR:.0e} drawn at {ERROR_FLOOR:.0e}; right = more accurate",
            transform=ax.transAxes,
            fontsize=7,
            va="bottom",
        )
    handles, labels = [], []
    for ax in axes:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            if lab not in labels:
                handles.append(h)
                labels.append(lab)
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.14, 1, 1))
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def lowest_split(seconds: float, g: dict) -> str:
    """What the kernel's ``lowest`` spent: its scan (replayed) and the rest (Brent, counts)."""
    rest = max(seconds - g["scan_seconds"], 0.0)
    return (
        f"scan {g['visited']} of {g['nodes']} grid nodes ({g['per_mode']} per pi of lambda L, "
        f"stops at the last root's sign change, lambda L = {g['beta_stop']:.3g}): "
        f"~{fmt_time(g['scan_seconds'])}; the other ~{fmt_time(rest)} go to Brent and the "
        f"counts (one count {fmt_time(g['count_seconds_per_point'])}: at most "
        f"~{rest / g['count_seconds_per_point']:.0f} counts)"
    )


def panel_notes(res: Results, modes: int) -> list[str]:
    """Short notes for a plot panel: where refinement stops helping, runs that failed."""
    out = []
    for series in dict.fromkeys(
        p.series for p in res.points if p.modes == modes and p.family in ("fe", "opensees")
    ):
        pl = plateau_of([p for p in res.points if p.series == series and p.modes == modes])
        if not pl or pl[1] is None:
            continue
        best, worst, slope = pl
        name = series.split(" (")[0]
        if not math.isfinite(worst.error):
            out.append(
                f"{name}: best {best.error:.0e} at n={int(best.param)}, fails at "
                f"n={int(worst.param)}"
            )
        elif slope is not None:
            out.append(
                f"{name}: stops improving at n={int(best.param)} ({best.error:.0e}); "
                f"then error ~ n^{slope:.1f} (round-off)"
            )
    for p in res.points:
        if p.modes == modes and p.family == "mstmm-warm" and not math.isfinite(p.error):
            out.append(f"{p.series}: {p.note}")
    return out


def fmt_time(t: float) -> str:
    if not math.isfinite(t):
        return "-"
    if t >= 1.0:
        return f"{t:.2f} s"
    if t >= 1e-3:
        return f"{t * 1e3:.2f} ms"
    if t >= 1e-5:
        return f"{t * 1e6:.0f} us"
    if t >= 1e-6:
        return f"{t * 1e6:.2f} us"
    return f"{t * 1e9:.0f} ns"


def fmt_err(e: float) -> str:
    if not math.isfinite(e):
        return "failed"
    return "0" if e == 0 else f"{e:.1e}"


THRESHOLDS = (1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14)


def fastest(res: Results, modes: int, tol: float, family_prefix: str, series: str | None = None):
    """The fastest measured point of a family (or series) with error <= tol."""
    pts = [
        p
        for p in res.points
        if p.modes == modes
        and p.family == family_prefix
        and (series is None or p.series == series)
        and p.error <= tol
        and math.isfinite(p.time)
    ]
    return min(pts, key=lambda p: p.time) if pts else None


def markdown(res: Results, img: str | None) -> str:
    out = []
    if img:
        out.append(f"![work-precision]({img})\n")
    else:
        out.append("(plot skipped: matplotlib is not installed)\n")
    out.append(f"OpenSees: {res.opensees}.\n")
    for modes in MODES:
        summary = opensees_summary(res, modes)
        if summary:
            out.append(f"OpenSeesPy, lowest {modes}, best per eigen solver: {summary}.\n")
    if res.default_solve:
        d = res.default_solve
        out.append(
            f"The default call `mstmm.solve(scene, modes=5)` (mode shapes on), warm: "
            f"{fmt_time(d['shapes'])}; with `shapes=False`: {fmt_time(d['no_shapes'])} "
            f"(medians of {int(d['repeats'])} interleaved runs each).\n"
        )
    for note in res.notes:
        out.append(f"Note: {note}.\n")
    # time to accuracy
    groups = [
        ("mstmm warm", "mstmm-warm", None),
        ("mstmm cold, kernel cached", "mstmm-cold", None),
        ("mstmm cold, compiled only", "mstmm-cold-jit", None),
        ("FE (dense or sparse)", "fe", None),
        ("FE + Richardson", "fe-richardson", None),
        ("OpenSeesPy", "opensees", None),
    ]
    for modes in MODES:
        out.append(f"\n**Time to reach an accuracy, lowest {modes}** (fastest measured setting):\n")
        out.append("| largest rel. error <= | " + " | ".join(g[0] for g in groups) + " |")
        out.append("|---|" + "---|" * len(groups))
        for tol in THRESHOLDS:
            cells = []
            for _, fam, ser in groups:
                p = fastest(res, modes, tol, fam, ser)
                cells.append(f"{fmt_time(p.time)} ({p.setting})" if p else "not reached")
            out.append(f"| {tol:.0e} | " + " | ".join(cells) + " |")
    out.append("\n**Where refinement stops helping** (mesh of the smallest error):\n")
    for key, text in res.plateaus.items():
        out.append(f"* {key}: {text}")
    out.append("\n<details><summary>All measured points</summary>\n")
    out.append("| lowest | method | setting | max rel. error | time | repeats | note |")
    out.append("|---|---|---|---|---|---|---|")
    for p in res.points:
        out.append(
            f"| {p.modes} | {p.series} | {p.setting} | {fmt_err(p.error)} | {fmt_time(p.time)} "
            f"| {p.repeats} | {p.note} |"
        )
    out.append("\n</details>\n")
    if res.cold_breakdown:
        out.append("**A fresh process, piece by piece** (median wall time of `python -c ...`):\n")
        out.append("| what | wall |")
        out.append("|---|---|")
        for k, v in res.cold_breakdown.items():
            out.append(f"| `{k}` | {fmt_time(v)} |")
        out.append("")
    if res.profiles:
        out.append("**Where a warm solve spends its time** (one instrumented run):\n")
        out.append(profile_table(res.profiles))
    return "\n".join(out) + "\n"


def profile_table(profiles: dict) -> str:
    lines = [
        "| case | total | kernel `lowest` (certified scan in numba): calls / time "
        "| evaluate: calls / points / time | refine: calls / evals / time "
        "| count_below: calls / points / time | Python (scan, merge, ...) |",
        "|---|---|---|---|---|---|---|",
    ]
    for case, prof in profiles.items():
        c = prof["calls"]

        def cell(name, use_its=False, c=c):
            if name not in c:
                return "-"
            v = c[name]
            mid = v["its"] if use_its else v["points"]
            return f"{v['calls']} / {mid} / {fmt_time(v['seconds'])}"

        ev = c.get("evaluate", {"calls": 0, "points": 0, "seconds": 0.0})
        de = c.get("delta", {"calls": 0, "points": 0, "seconds": 0.0})
        merged = {
            "calls": ev["calls"] + de["calls"],
            "points": ev["points"] + de["points"],
            "seconds": ev["seconds"] + de["seconds"],
            "its": 0,
        }
        c = dict(c, evaluate=merged)
        low = "-"
        if "lowest" in c:
            v = c["lowest"]
            low = f"{v['calls']} / {fmt_time(v['seconds'])}"
            low += " (certified)" if v["its"] else " (not certified: full search follows)"
            g = prof.get("lowest_grid")
            if g:
                low += "; " + lowest_split(v["seconds"], g)
        lines.append(
            f"| {case} | {fmt_time(prof['total'])} | {low} | {cell('evaluate')} "
            f"| {cell('refine', True)} | {cell('count_below')} | {fmt_time(prof['python'])} |"
        )
    return "\n".join(lines) + "\n"

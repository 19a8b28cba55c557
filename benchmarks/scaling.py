"""Scaling with the number of attachments N: evaluation, solve, derive and compile.

Scenes: the paper's beam (L, EI, mbar of ``tests/data/wu_chou_1998.toml``),
clamped-free, carrying N spring-masses with random positions ``x ~ U(0, L)``,
masses ``m ~ U(0.5, 1.5) mbar L / (2 N)`` (the attached mass stays half the
beam's whatever N) and stiffnesses ``k = m w_i^2``, fixed seed, in two families:

``in band``
    oscillator frequencies ``w_i = sqrt(k_i/m_i)`` log-uniform between the first
    and the 20th natural frequency of the bare cantilever: the attachments
    interact with the modes asked for (and most of the lowest 20 modes are
    oscillator modes);
``stiff mounts``
    ``w_i`` log-uniform in 10..100 times the 20th bare-beam frequency: the
    attachments load the beam like masses, and no oscillator frequency lies in
    the band searched.

Measured per N:

* the characteristic function: ``kernel.evaluate(omegas, p, formulation)`` on
  a grid across the band, time per omega (``paper`` only up to N = 300:
  its ``det U_bar`` is an ``(N + 4)``-square LU, O(N^3)); the Wittrick-Williams
  count ``kernel.count_below`` likewise;
* a warm ``mstmm.solve(scene, modes=20, shapes=False)`` (the root search and
  its certification), with a profile of the kernel calls it makes;
* derive time, generated source size and numba compile time: a fresh process
  per N with an empty ``MSTMM_CACHE`` and the pinned-free topology (not
  bundled, so ``mstmm.kernel_for`` derives it): they do not depend on N,
  because the kernel is generated per topology and loops over the attachments.

Log-log slopes are least-squares fits of ``log(time)`` on ``log(N)`` over N >= 100.
"""

from __future__ import annotations

import json
import math
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

import mstmm

from .machine import new_topology_env
from .workprecision import fmt_time, in_child, profile_solve, stage, timed

ROOT = Path(__file__).resolve().parent.parent
BASE = ROOT / "tests" / "data" / "wu_chou_1998.toml"
NS = (1, 3, 10, 100, 1000, 10000)
PAPER_MAX_N = 300
PAPER_NS = (1, 3, 10, 100, 300)
MODES = 20
SEED = 20240611
FAMILIES = ("in band", "stiff mounts")
#: Cantilever eigenvalues beta_1 and beta_20 (beta_n ~ (n - 1/2) pi).
BETA_1, BETA_20 = 1.8751040687119611, 19.5 * math.pi
#: Scan points per evaluate call when timing the characteristic function.
GRID = 256
#: Wall-clock budget of one solve measurement (s); a solve over it is reported as such.
SOLVE_BUDGET = 400.0
#: The same for the paper formulation (its search can wander on a noisy determinant).
PAPER_BUDGET = 15.0


@dataclass
class Results:
    evaluate: list[dict] = field(default_factory=list)  # N, family, formulation, seconds/omega
    count: list[dict] = field(default_factory=list)  # N, family, seconds/omega
    solve: list[dict] = field(default_factory=list)  # N, family, formulation, seconds, profile
    derive: list[dict] = field(default_factory=list)  # N, derive, compile, size, lines
    slopes: dict[str, float] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    quick: bool = False

    def to_json(self) -> dict:
        return asdict(self)


def random_scene(n: int, family: str = "in band", left: str = "clamped", seed: int = SEED):
    """The paper's beam with ``n`` random spring-masses (see the module docstring)."""
    base = mstmm.load_scene(BASE).beam
    L, EI, mbar = base.length, base.EI, base.mass_per_length
    scale = math.sqrt(EI / mbar) / L**2  # omega = scale * beta^2
    w1, w20 = scale * BETA_1**2, scale * BETA_20**2
    lo, hi = (w1, w20) if family == "in band" else (10 * w20, 100 * w20)
    rng = np.random.default_rng([seed, n, FAMILIES.index(family)])
    x = rng.uniform(0.0, L, n)
    m = rng.uniform(0.5, 1.5, n) * mbar * L / (2 * n)
    w = np.exp(rng.uniform(math.log(lo), math.log(hi), n))
    k = m * w**2
    beam = {"length": L, "EI": EI, "mass_per_length": mbar, "left": left, "right": "free"}
    atts = [
        {"type": "spring_mass", "x": float(a), "k": float(b), "m": float(c)}
        for a, b, c in zip(x, k, m)
    ]
    name = f"random_{n}_{family.replace(' ', '_')}_{left}"
    return mstmm.scene_from_dict({"name": name, "beam": beam, "attachments": atts})


def band_grid(scene, points: int) -> np.ndarray:
    """``points`` omegas uniform in beta over (0, 1.1 beta_20]: the band a 20-mode solve scans."""
    b = scene.beam
    beta = np.linspace(0.02, 1.1 * BETA_20, points)
    return beta**2 * math.sqrt(b.EI / b.mass_per_length) / b.length**2


# ------------------------------------------------------------------ measurements


def measure_evaluate(res: Results, ns, budget: float) -> None:
    """Time per omega of both characteristic functions (paper: N <= 300) and of the count."""
    for family in FAMILIES:
        for n in sorted(set(ns) | {m for m in PAPER_NS if m <= max(ns) or m == PAPER_MAX_N}):
            scene = random_scene(n, family)
            kernel = mstmm.kernel_for(scene)
            p = mstmm.parameter_vector(scene)
            for formulation in ("stable", "paper"):
                if formulation == "paper" and n > PAPER_MAX_N:
                    continue
                if formulation == "stable" and n not in ns:
                    continue
                pts = GRID if formulation == "stable" or n < 100 else 32
                w = band_grid(scene, pts)
                _, t, reps = timed(
                    lambda w=w, f=formulation, k=kernel, p=p: k.evaluate(w, p, f), budget
                )
                res.evaluate.append(
                    {
                        "N": n,
                        "family": family,
                        "formulation": formulation,
                        "seconds": t / pts,
                        "repeats": reps,
                    }
                )
            if n in ns:
                w = band_grid(scene, 64)
                _, t, reps = timed(lambda w=w, k=kernel, p=p: k.count_below(w, p), budget)
                res.count.append({"N": n, "family": family, "seconds": t / 64, "repeats": reps})


def _solve_group(scene, formulation: str, emit) -> None:
    kernel = mstmm.kernel_for(scene)
    sol, t, reps = timed(
        lambda: mstmm.solve(
            scene, modes=MODES, shapes=False, formulation=formulation, kernel=kernel
        ),
        0.5,
        min_repeats=3,
    )
    out = {
        "seconds": t,
        "repeats": reps,
        "checked": bool(sol.count_checked),
        "omega_20": float(sol.omega[-1]),
        "profile": None,
    }
    if t < 10.0:  # one instrumented run where it is affordable
        out["profile"] = profile_solve(scene, MODES, formulation, kernel, runs=1)
    emit(out)


def measure_solve(res: Results, ns, budget: float, log, paper: bool = True) -> None:
    for family in FAMILIES:
        for n in ns:
            for formulation in ("stable", "paper"):
                if formulation == "paper" and (n > 100 or not paper):
                    continue
                scene = random_scene(n, family)
                # compile before forking
                mstmm.solve(random_scene(1, family), modes=3, shapes=False, formulation=formulation)
                t0 = time.perf_counter()
                limit = budget if formulation == "stable" else min(budget, PAPER_BUDGET)
                items, why = in_child(
                    lambda emit, s=scene, f=formulation: _solve_group(s, f, emit), limit
                )
                out = items[0] if items else {"error": f"solve {why}"}
                log(
                    f"  solve N={n} {family} {formulation}: "
                    f"{out.get('seconds', out.get('error'))} ({time.perf_counter() - t0:.1f} s)"
                )
                res.solve.append({"N": n, "family": family, "formulation": formulation, **out})


_DERIVE_CODE = r"""
import json, os, sys, time
t0 = time.perf_counter()
import mstmm
from mstmm.kernels import cache_dir
t1 = time.perf_counter()
scene = mstmm.load_scene(sys.argv[1])
kernel = mstmm.kernel_for(scene)
t2 = time.perf_counter()
mstmm.solve(scene, modes=5, shapes=False)
t3 = time.perf_counter()
ts = []
for _ in range(3):
    t = time.perf_counter()
    mstmm.solve(scene, modes=5, shapes=False)
    ts.append(time.perf_counter() - t)
warm = sorted(ts)[1]
src = kernel.origin
text = open(src).read() if os.path.exists(src) else ""
print(json.dumps({"import": t1 - t0, "derive": t2 - t1, "first_solve": t3 - t2, "warm": warm,
                  "compile": t3 - t2 - warm, "bytes": len(text.encode()),
                  "lines": text.count("\n"), "origin": src,
                  "derived": str(cache_dir()) in src}))
"""


def measure_derive(res: Results, ns, log) -> None:
    """Fresh process per N, empty cache, pinned-free (not bundled): derive + compile."""
    from .workprecision import scene_toml

    with tempfile.TemporaryDirectory(prefix="mstmm-derive-") as tmp:
        for n in ns:
            scene = random_scene(n, "in band", left="pinned")
            path = Path(tmp) / f"{scene.name}.toml"
            path.write_text(scene_toml(scene, scene.name))
            env = new_topology_env(Path(tmp) / f"cache-{n}")
            env["MSTMM_INTERPRET_BUDGET"] = "0"  # compiled: what is measured here
            env["MSTMM_COMPILE_HELPERS"] = "1"  # as a user's process compiles
            t = time.perf_counter()
            proc = subprocess.run(
                [sys.executable, "-c", _DERIVE_CODE, str(path)],
                capture_output=True,
                text=True,
                env=env,
                check=False,
            )
            wall = time.perf_counter() - t
            if proc.returncode != 0:
                tail = (proc.stderr.strip().splitlines() or ["?"])[-1]
                res.derive.append({"N": n, "error": tail, "wall": wall})
                continue
            out = json.loads(proc.stdout.strip().splitlines()[-1])
            out.update({"N": n, "wall": wall})
            log(f"  derive N={n}: derive {out['derive']:.2f} s, compile {out['compile']:.2f} s")
            res.derive.append(out)


def slope(ns, ts, n_min: int = 100) -> float:
    """Least-squares slope of log(t) on log(N) over N >= n_min (nan with < 2 points)."""
    pts = [(n, t) for n, t in zip(ns, ts) if n >= n_min and t and math.isfinite(t) and t > 0]
    if len(pts) < 2:
        return math.nan
    x = np.log([p[0] for p in pts])
    y = np.log([p[1] for p in pts])
    return float(np.polyfit(x, y, 1)[0])


def fit_slopes(res: Results) -> None:
    for family in FAMILIES:
        for formulation in ("stable", "paper"):
            rows = [
                r for r in res.evaluate if r["family"] == family and r["formulation"] == formulation
            ]
            rows.sort(key=lambda r: r["N"])
            if rows:
                res.slopes[f"evaluate, {formulation}, {family}"] = slope(
                    [r["N"] for r in rows], [r["seconds"] for r in rows]
                )
            rows = [
                r
                for r in res.solve
                if r["family"] == family and r["formulation"] == formulation and "seconds" in r
            ]
            if rows:
                res.slopes[f"solve (lowest 20), {formulation}, {family}"] = slope(
                    [r["N"] for r in rows], [r["seconds"] for r in rows]
                )
        rows = [r for r in res.count if r["family"] == family]
        if rows:
            res.slopes[f"count_below, {family}"] = slope(
                [r["N"] for r in rows], [r["seconds"] for r in rows]
            )
    ok = [r for r in res.derive if "derive" in r]
    for key in ("derive", "compile", "bytes"):
        if len(ok) >= 2:
            res.slopes[f"{key} (all N)"] = slope(
                [r["N"] for r in ok], [r[key] for r in ok], n_min=1
            )


def run(quick: bool = False, log=print) -> Results:
    res = Results(quick=quick)
    ns = (1, 3, 10, 100) if quick else NS
    budget = 0.05 if quick else 0.3
    stage(res, "scaling: characteristic function and count", log, measure_evaluate, res, ns, budget)
    stage(
        res,
        "scaling: solves (lowest 20)",
        log,
        measure_solve,
        res,
        ns,
        60.0 if quick else SOLVE_BUDGET,
        log,
        paper=not quick,
    )
    if quick:
        res.notes.append("--quick: solves of the paper formulation not run")
        res.notes.append("--quick: derive and compile against N not measured")
    else:
        stage(
            res,
            "scaling: derive + compile against N (fresh processes)",
            log,
            measure_derive,
            res,
            ns,
            log,
        )
    fit_slopes(res)
    return res


# ------------------------------------------------------------------ report


def _line(ax, rows: list[dict], ls: str, color: str, marker: str, label: str) -> None:
    """One curve of seconds against N (nothing when there are no rows)."""
    if rows:
        ax.plot(
            [r["N"] for r in rows],
            [r["seconds"] for r in rows],
            ls=ls,
            color=color,
            marker=marker,
            label=label,
        )


def plot(res: Results, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(16, 5.2))
    ax = axes[0]
    for family, ls in zip(FAMILIES, ("-", "--")):
        for formulation, color in (("stable", "C0"), ("paper", "C1")):
            rows = sorted(
                (
                    r
                    for r in res.evaluate
                    if r["family"] == family and r["formulation"] == formulation
                ),
                key=lambda r: r["N"],
            )
            _line(ax, rows, ls, color, "o", f"evaluate, {formulation}, {family}")
        rows = sorted((r for r in res.count if r["family"] == family), key=lambda r: r["N"])
        _line(ax, rows, ls, "C2", "s", f"count_below, {family}")
    ax.set_title("one characteristic-function / count evaluation")
    ax.set_ylabel("time per omega [s]")
    ax = axes[1]
    for family, ls in zip(FAMILIES, ("-", "--")):
        for formulation, color in (("stable", "C0"), ("paper", "C1")):
            rows = sorted(
                (
                    r
                    for r in res.solve
                    if r["family"] == family and r["formulation"] == formulation and "seconds" in r
                ),
                key=lambda r: r["N"],
            )
            _line(ax, rows, ls, color, "o", f"solve, {formulation}, {family}")
    failed = [r for r in res.solve if "seconds" not in r]
    if failed:
        ax.text(
            0.99,
            0.01,
            "did not finish:\n"
            + "\n".join(f"{r['formulation']}, {r['family']}, N={r['N']}" for r in failed),
            transform=ax.transAxes,
            fontsize=6,
            ha="right",
            va="bottom",
            color="C1",
        )
    ax.axhline(0.05, color="0.5", lw=0.8, ls=":")
    ax.text(1, 0.05, " target at N = 1000: 50 ms", fontsize=7, va="bottom", color="0.4")
    ax.set_title(f"warm solve, lowest {MODES} modes")
    ax.set_ylabel("wall time [s] (median)")
    ax = axes[2]
    ok = sorted((r for r in res.derive if "derive" in r), key=lambda r: r["N"])
    if ok:
        ax.plot([r["N"] for r in ok], [r["derive"] for r in ok], marker="o", label="derive (SymPy)")
        ax.plot([r["N"] for r in ok], [r["compile"] for r in ok], marker="s", label="numba compile")
        ax.set_ylabel("seconds")
        ax2 = ax.twinx()
        ax2.plot(
            [r["N"] for r in ok],
            [r["bytes"] / 1e3 for r in ok],
            color="C3",
            marker="^",
            label="generated source [kB]",
        )
        ax2.set_ylabel("generated source [kB]")
        ax2.set_ylim(0, max(r["bytes"] for r in ok) / 1e3 * 1.3)
        ax2.legend(loc="upper right", fontsize=8)
        ax.set_ylim(0, max(max(r["derive"], r["compile"]) for r in ok) * 1.3)
    else:
        ax.text(0.5, 0.5, "not measured (--quick)", ha="center", transform=ax.transAxes)
    ax.set_title("derive, compile, source size (per topology)")
    for i, a in enumerate(axes):
        a.set_xscale("log")
        if i < 2:
            a.set_yscale("log")
        a.set_xlabel("number of attachments N")
        a.grid(True, alpha=0.3)
        if a.get_legend_handles_labels()[0]:
            a.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def markdown(res: Results, img: str | None) -> str:
    out = [f"![scaling]({img})\n" if img else "(plot skipped: matplotlib is not installed)\n"]
    for note in res.notes:
        out.append(f"Note: {note}.\n")
    ns = sorted({r["N"] for r in res.evaluate} | {r["N"] for r in res.solve})
    out.append("**Time per omega of the characteristic function and of the count**:\n")
    cols = [(fam, f) for fam in FAMILIES for f in ("stable", "paper")]
    out.append(
        "| N | "
        + " | ".join(f"evaluate {f}, {fam}" for fam, f in cols)
        + " | "
        + " | ".join(f"count, {fam}" for fam in FAMILIES)
        + " |"
    )
    out.append("|---|" + "---|" * (len(cols) + len(FAMILIES)))
    for n in ns:
        cells = []
        for fam, f in cols:
            r = [
                x
                for x in res.evaluate
                if x["N"] == n and x["family"] == fam and x["formulation"] == f
            ]
            cells.append(fmt_time(r[0]["seconds"]) if r else "-")
        for fam in FAMILIES:
            r = [x for x in res.count if x["N"] == n and x["family"] == fam]
            cells.append(fmt_time(r[0]["seconds"]) if r else "-")
        out.append(f"| {n} | " + " | ".join(cells) + " |")
    out.append(
        f"\n**Warm solve, lowest {MODES} modes** (median; `checked`: the count confirmed "
        "every root):\n"
    )
    out.append("| N | family | formulation | time | repeats | omega_20 [rad/s] | checked |")
    out.append("|---|---|---|---|---|---|---|")
    for r in sorted(res.solve, key=lambda r: (r["family"], r["formulation"], r["N"])):
        if "seconds" in r:
            out.append(
                f"| {r['N']} | {r['family']} | {r['formulation']} | {fmt_time(r['seconds'])} "
                f"| {r['repeats']} | {r['omega_20']:.6g} | {r['checked']} |"
            )
        else:
            out.append(f"| {r['N']} | {r['family']} | {r['formulation']} | {r['error']} | | | |")
    if res.derive:
        out.append(
            "\n**Derive and compile against N** (fresh process, empty `MSTMM_CACHE`, "
            "pinned-free topology):\n"
        )
        out.append(
            "| N | import mstmm | derive + write | first solve (compile) | compile only "
            "| warm solve | source | kernel from the cache dir |"
        )
        out.append("|---|---|---|---|---|---|---|---|")
        for r in res.derive:
            if "error" in r:
                out.append(f"| {r['N']} | failed: {r['error']} | | | | | | |")
                continue
            out.append(
                f"| {r['N']} | {fmt_time(r['import'])} | {fmt_time(r['derive'])} "
                f"| {fmt_time(r['first_solve'])} | {fmt_time(r['compile'])} "
                f"| {fmt_time(r['warm'])} "
                f"| {r['bytes']} B, {r['lines']} lines | {r['derived']} |"
            )
    out.append(
        "\n**Log-log slopes** (least squares over N >= 100; derive/compile/source over all N):\n"
    )
    out.append("| quantity | slope |")
    out.append("|---|---|")
    for k, v in res.slopes.items():
        if math.isfinite(v):  # a quantity with fewer than two points at N >= 100 has none
            out.append(f"| {k} | {v:.2f} |")
    profiled = [r for r in res.solve if r.get("profile")]
    if profiled:
        from .workprecision import profile_table

        profs = {
            f"N = {r['N']}, {r['family']}, {r['formulation']}": r["profile"]
            for r in profiled
            if r["N"] >= 100
        }
        if profs:
            out.append("\n**Where a warm solve spends its time** (one instrumented run):\n")
            out.append(profile_table(profs))
    return "\n".join(out) + "\n"


def median_or_nan(xs) -> float:
    xs = [x for x in xs if math.isfinite(x)]
    return statistics.median(xs) if xs else math.nan

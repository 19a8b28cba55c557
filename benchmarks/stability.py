"""Numerical-stability report: ``python -m benchmarks.stability`` (writes ``docs/stability.md``).

1. Every extreme case of :mod:`benchmarks.cases` (the cases ``tests/test_extremes.py``
   asserts, scored by the same :func:`benchmarks.cases.compare`): the largest
   relative error of the ``stable`` (default) and ``paper`` formulations against
   the independent reference model, the condition exercised, the tolerance and
   pass/fail of the default formulation.  The paper's formulation runs in a
   forked child with a wall-clock budget (:data:`PAPER_BUDGET`): on noisy
   determinants its root search can take very long, and its ``det U_bar`` is an
   ``(N + 4)``-square LU per evaluation; a run over budget is reported as such.
2. The evaluation cost of the stable characteristic function (median time per
   ``kernel.evaluate`` call on a 64-point grid, divided by 64) against the number
   of attachments N = 1 .. 10000, with the fitted log-log slope.
"""

from __future__ import annotations

import math
import multiprocessing
import os
import platform
import statistics
import sys
import time
from pathlib import Path

import numba
import numpy as np

import mstmm

from . import figures
from .cases import CASES, ROOT, Case, bracketed_root_errors, compare, make_scene, reference

OUT = ROOT / "docs" / "stability.md"
COMMAND = "python -m benchmarks.stability"
#: Wall-clock budget of one paper-formulation solve (s).
PAPER_BUDGET = 30.0
#: Paper-formulation solves run side by side (forked children).
WORKERS = 2
#: Attachment counts of the cost table.
COST_N = (1, 10, 100, 1000, 10000)
COST_GRID = 64


# ------------------------------------------------------------------ accuracy


def _summary(comp) -> dict:
    return {
        "max_rel_error": comp.max_rel_error,
        "first_beyond": comp.first_mode_beyond(comp.case.tol),
        "n_roots": len(comp.omega),
        "zeros_exact": comp.zeros_exact,
        "passed": comp.passed,
        "problems": list(comp.problems),
        "seconds": comp.seconds,
        "max_trusted_error": comp.max_trusted_error,
    }


def _child(case: Case, formulation: str, conn) -> None:
    try:
        conn.send(_summary(compare(case, formulation)))
    except BaseException as exc:  # report, never hang the parent
        conn.send({"error": f"{type(exc).__name__}: {exc}"})
    finally:
        conn.close()


def run_budgeted(cases: list[Case], formulation: str, budget: float) -> dict[str, dict]:
    """``compare(case, formulation)`` of each case in forked children, each within ``budget`` s.

    References must already be computed (they are inherited by the children).
    A child over budget is terminated (by its own handle) and reported as such.
    """
    ctx = multiprocessing.get_context("fork")
    pending = list(cases)
    active: dict[str, tuple] = {}
    out: dict[str, dict] = {}
    while pending or active:
        while pending and len(active) < WORKERS:
            case = pending.pop(0)
            recv, send = ctx.Pipe(duplex=False)
            proc = ctx.Process(target=_child, args=(case, formulation, send), daemon=True)
            proc.start()
            send.close()
            active[case.name] = (proc, recv, time.perf_counter())
        time.sleep(0.05)
        for name, (proc, recv, start) in list(active.items()):
            elapsed = time.perf_counter() - start
            if recv.poll():
                try:
                    out[name] = recv.recv()
                except EOFError:
                    out[name] = {"error": "child exited without a result"}
            elif not proc.is_alive():
                out[name] = {"error": f"child exited with status {proc.exitcode}"}
            elif elapsed > budget:
                proc.terminate()
                out[name] = {"timeout": budget}
            else:
                continue
            proc.join()
            recv.close()
            del active[name]
            print(f"  {formulation} {name}: {_fmt_result(out[name])}", flush=True)
    return out


def _fmt_err(err: float) -> str:
    return "inf" if math.isinf(err) else f"{err:.1e}"


def _fmt_result(res: dict) -> str:
    if "timeout" in res:
        return f"no result in {res['timeout']:.0f} s"
    if "error" in res:
        return "error: " + res["error"]
    text = _fmt_err(res["max_rel_error"])
    if res["problems"]:
        text += " (" + "; ".join(res["problems"]) + ")"
    return text


def _first_beyond(res: dict) -> str:
    if "timeout" in res or "error" in res:
        return "-"
    first = res["first_beyond"]
    return "none" if first is None else f"mode {first}"


def _diagnostic(case: Case) -> tuple[str, str]:
    """Max error and first mode beyond tol of the paper det's own roots, bracketed."""
    err = bracketed_root_errors(case, "paper")
    known = ~np.isnan(err)
    if not known.any():
        return "-", "-"
    bad = np.nonzero(known & ~(err <= case.tol))[0]
    return _fmt_err(float(err[known].max())), "none" if not bad.size else f"mode {bad[0] + 1}"


def accuracy() -> tuple[list[str], list[str], str, dict]:
    """Markdown rows of the case table, the failures of the default formulation, a summary,
    and the figures the README quotes."""
    stable: dict[str, dict] = {}
    diag: dict[str, tuple[str, str]] = {}
    for case in CASES:
        t = time.perf_counter()
        reference(case)
        comp = compare(case, "stable")
        stable[case.name] = _summary(comp)
        print(
            f"  stable {case.name}: {_fmt_result(stable[case.name])} "
            f"({time.perf_counter() - t:.1f} s with the reference)",
            flush=True,
        )
    for case in CASES:
        diag[case.name] = _diagnostic(case)
        print(f"  paper det {case.name}: {diag[case.name]}", flush=True)
    paper = run_budgeted(CASES, "paper", PAPER_BUDGET)
    rows, failures = [], []
    for case in CASES:
        s, p = stable[case.name], paper[case.name]
        ok = s["passed"]
        if not ok:
            failures.append(f"{case.name}: {_fmt_result(s)}")
        if "timeout" in p or "error" in p:
            p_text = _fmt_result(p)
        else:
            p_text = _fmt_err(p["max_rel_error"])
            if p["first_beyond"] is not None:
                p_text += f" (> tol from {_first_beyond(p)})"
            if p["problems"]:
                p_text += " (" + "; ".join(p["problems"]) + ")"
                p_text += f"; not flagged: max {_fmt_err(p['max_trusted_error'])}"
        rows.append(
            f"| {case.name} | {case.modes} | {_fmt_err(s['max_rel_error'])} | {p_text} | "
            f"{diag[case.name][0]} | {diag[case.name][1]} | {case.condition} | "
            f"{case.tol:.0e} | {'pass' if ok else '**FAIL**'} |"
        )
    done = [p for p in paper.values() if "max_rel_error" in p]
    within = [p for p in done if p["passed"]]
    firsts = sorted(int(d[1].split()[1]) for d in diag.values() if d[1].startswith("mode "))
    summary = (
        f"Paper formulation: the root search returned within {PAPER_BUDGET:.0f} s on "
        f"{len(done)} of {len(CASES)} cases, {len(within)} of them within tolerance; "
        f"its determinant's own roots leave the tolerance on {len(firsts)} of {len(CASES)} "
        + (f"cases, from mode {firsts[0]} to mode {firsts[-1]}." if firsts else "cases.")
    )
    worst = max(CASES, key=lambda c: stable[c.name]["max_rel_error"])
    figs = {
        "cases": len(CASES),
        "passed": len(CASES) - len(failures),
        "worst_error": stable[worst.name]["max_rel_error"],
        "worst_case": worst.name,
        "worst_condition": worst.condition,
        "paper_det_first_beyond": [firsts[0], firsts[-1]] if firsts else None,
        "paper_det_cases_beyond": len(firsts),
    }
    return rows, failures, summary, figs


# ---------------------------------------------------------------------- cost


def _cost_scene(n: int) -> mstmm.Scene:
    atts = tuple(
        ((i + 0.5) / n, (20.0 + 1980.0 * i / max(n - 1, 1)) ** 2 / n, 1.0 / n) for i in range(n)
    )
    return mstmm.scene_from_dict(make_scene(f"cost_{n}", "clamped", "free", atts))


def evaluation_cost() -> tuple[list[tuple[int, float, int]], float, float]:
    """(N, median seconds per evaluation, repeats) per N, and the log-log slopes (all N, N>=100)."""
    rows = []
    for n in COST_N:
        scene = _cost_scene(n)
        kernel = mstmm.kernel_for(scene)
        p = mstmm.parameter_vector(scene)
        w = np.linspace(10.0, 5e4, COST_GRID)
        kernel.evaluate(w, p, "stable")  # compiled / loaded
        times: list[float] = []
        start = time.perf_counter()
        while len(times) < 7 or time.perf_counter() - start < 0.5:
            t = time.perf_counter()
            kernel.evaluate(w, p, "stable")
            times.append(time.perf_counter() - t)
        rows.append((n, statistics.median(times) / COST_GRID, len(times)))
        print(f"  N = {n}: {rows[-1][1] * 1e6:.3g} us per evaluation", flush=True)
    logn = np.log([r[0] for r in rows])
    logt = np.log([r[1] for r in rows])
    slope_all = float(np.polyfit(logn, logt, 1)[0])
    big = logn >= math.log(100)
    slope_big = float(np.polyfit(logn[big], logt[big], 1)[0])
    return rows, slope_all, slope_big


# -------------------------------------------------------------------- report


def _cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def machine() -> str:
    return (
        f"{platform.platform()}, {_cpu_model()}, {os.cpu_count()} CPUs; "
        f"Python {platform.python_version()}, numpy {np.__version__}, numba {numba.__version__}, "
        f"mstmm {mstmm.__version__}"
    )


def main() -> None:
    t0 = time.perf_counter()
    print("accuracy (stable in process, then paper in forked children):", flush=True)
    rows, failures, paper_summary, figs = accuracy()
    print("evaluation cost:", flush=True)
    cost, slope_all, slope_big = evaluation_cost()
    elapsed = time.perf_counter() - t0
    n_pass = len(CASES) - len(failures)
    lines = [
        "# Numerical stability",
        "",
        f"Generated by `{COMMAND}` (from the repository root) on {machine()}. "
        f"Run time {elapsed / 60:.1f} min.",
        "",
        "## Accuracy on extreme cases",
        "",
        "Each case is a scene of `benchmarks/cases.py`; `tests/test_extremes.py` asserts the "
        "same numbers (`benchmarks.cases.compare`). *solve*: largest relative error "
        "`|omega_i - ref_i| / ref_i` over the lowest *modes* frequencies returned by "
        "`mstmm.solve(scene, modes=n, formulation=..., shapes=False)`, against the independent "
        "reference model `tests/reference_model.py` (global assembly of exact segment "
        "solutions and a Wittrick-Williams count in mpmath, 30 digits; 20 digits for "
        "`many_1000`, whose reference polishes each stable root in a bracket of relative "
        "half-width 1e-8 with the reference's own count and global determinant, and proves "
        "with `count_below` at the top that no root lies outside the brackets). Zero "
        "(rigid-body) frequencies count as exact only when returned as exactly 0; a missing "
        "root is an infinite error. *default*: pass when the default (stable) formulation "
        "is within the case's tolerance, returns all modes, converged, with exact zeros.",
        "",
        f"The paper's formulation is solved in a forked child with {PAPER_BUDGET:.0f} s of "
        "wall time per case (two side by side); *no result* means the root search had not "
        "returned by then (`many_1000`: each evaluation of the paper's determinant is an LU "
        "of a 1004-square matrix). The solver checks every root it returns against the "
        "count (a root within 1e-8) and the stable function (a sign change within 1e-12) "
        "and flags those that fail; *not flagged* is the largest error over the roots it "
        "let through, which is what a user who heeds the flags gets. "
        "*paper det U_bar*: independent of the root search, Brent's "
        "method on the paper's determinant in the bracket between each simple reference "
        "root's neighbours (geometric means): largest relative error of those roots, and "
        "the first mode beyond the case's tolerance (inf: no sign change in the bracket).",
        "",
        "| case | modes | stable: solve | paper: solve | paper det U_bar: roots | "
        "paper det: first mode > tol | condition | tol | default |",
        "|---|---|---|---|---|---|---|---|---|",
        *rows,
        "",
        f"Default formulation: {n_pass} of {len(CASES)} cases within tolerance"
        + ("." if not failures else "; failing: " + "; ".join(failures) + "."),
        paper_summary,
        "",
        "## Evaluation cost of the stable characteristic function",
        "",
        f"Median wall time of one `kernel.evaluate(omegas, p, 'stable')` call on a "
        f"{COST_GRID}-point grid, divided by {COST_GRID}; clamped-free beam with N "
        "spring-masses (the topology `clamped_free__spring_mass`, kernel `beam__spring_mass`),"
        " one thread.",
        "",
        "| N attachments | time per evaluation | repeats |",
        "|---|---|---|",
        *[f"| {n} | {t * 1e6:.3g} us | {r} |" for n, t, r in cost],
        "",
        f"Fitted slope of log(time) against log(N): {slope_all:.2f} over all N "
        f"(the fixed per-call cost dominates at N = 1), {slope_big:.2f} over N >= 100: "
        "linear in the number of attachments.",
        "",
    ]
    text = "\n".join(lines)
    print()
    print(text)
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.write_text(text)
    print(f"written {OUT.relative_to(ROOT)}", file=sys.stderr)
    figs["cost_seconds"] = {str(n): t for n, t, _ in cost}
    figs["cost_slope_all"] = slope_all
    figs["cost_slope_big"] = slope_big
    print(f"recorded in {figures.record('stability', figs, command=COMMAND)}", file=sys.stderr)


if __name__ == "__main__":
    main()

"""``python -m benchmarks``: error against run time, and scaling with N; writes docs/benchmarks.md.

Options: ``--quick`` (a smoke run of about half a minute, used by
``tests/test_benchmarks.py``), ``--only workprecision|scaling``, ``--out DIR``
(default ``docs/``; the plots go to ``DIR/img/``), ``--json FILE`` (raw results).

BLAS runs single-threaded (``OPENBLAS_NUM_THREADS=1`` unless set): on this
2-core machine a multi-threaded OpenBLAS made the dense FE solver up to 60
times slower, and mstmm is single-threaded too.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SECTIONS = ("workprecision", "scaling", "study")


def _log(msg: str) -> None:
    print(f"[benchmarks {time.strftime('%H:%M:%S')}] {msg}", file=sys.stderr, flush=True)


def try_plot(fn, results, path: Path) -> tuple[str | None, str]:
    """Draw with ``fn`` into ``path``; ``(relative image path or None, why not)``."""
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        return None, "matplotlib is not installed: plots skipped"
    try:
        fn(results, path)
    except Exception as exc:  # a broken plot must not lose the numbers
        return None, f"plot failed: {type(exc).__name__}: {exc}"
    return f"img/{path.name}", ""


# ------------------------------------------------------------------ targets


def _first_run_remark(first: dict, key: str) -> str:
    """What a first run's time is made of (``benchmarks.components``)."""
    from .workprecision import fmt_time

    remark = (
        "the process compiles the topology's characteristic function; a helper the rest of"
        " its kernel (count, own frequencies, rigid-body count, mode-shape functions), run as"
        " Python until it has them (mstmm.compiling)"
    )
    alone = first.get("nothing_compiled_one_process")
    if key == "nothing_compiled" and alone:
        remark += (
            "; the shared numerics once per machine, in two more helpers (nice 10), the drivers"
            " run as Python until they are compiled;"
            f" in one process (`MSTMM_COMPILE_HELPERS=0`) {fmt_time(alone['wall_seconds'])}"
            f" ({'-'.join(alone['ends'])} ends, same run)"
        )
    return remark


def _status(ok: bool | None) -> str:
    return {True: "**met**", False: "**missed**", None: "not measured"}[ok]


def targets(wp, sc, st=None) -> list[tuple[str, str, str, str, str]]:
    """(target, goal, measured, status, what limits it / remark) rows."""
    from .workprecision import fastest, fmt_err, fmt_time, opensees_summary

    rows = []
    if st is not None:
        from .study import speedup

        one, every = st.threads.values()
        rows.append(
            (
                f"parameter study: {st.points} points of the paper example, lowest {st.modes}",
                "uses both cores",
                f"{fmt_time(every)} on {st.cores} threads vs {fmt_time(one)} on one "
                f"({speedup(st):.2f}x); {st.uncertified} uncertified; error "
                f"{st.max_error:.1e} on {st.checked} points checked",
                _status(st.cores >= 2 and speedup(st) > 1.3),
                "numba prange over the points; the kernel's lowest per point",
            )
        )
    # 1. paper example, lowest 5 to 1e-13, warm
    if wp is not None:
        p = fastest(wp, 5, 1e-13, "mstmm-warm")
        default = [
            q
            for q in wp.points
            if q.family == "mstmm-warm"
            and q.modes == 5
            and q.setting == "rtol=0"
            and q.series.endswith("stable")
        ]
        if p:
            extra = ""
            if default:
                d = default[0]
                extra = f"; default (stable, rtol=0): {fmt_time(d.time)}, error {fmt_err(d.error)}"
            prof = wp.profiles.get("paper example, lowest 5, stable, rtol=0")
            remark = _profile_remark(prof) if prof else ""
            rows.append(
                (
                    "paper example, lowest 5 to 1e-13 relative, warm",
                    "<= 0.5 ms",
                    f"{fmt_time(p.time)} ({p.series.split(', ')[-1]}, {p.setting}, "
                    f"error {fmt_err(p.error)}){extra}",
                    _status(p.time <= 0.5e-3),
                    remark,
                )
            )
        else:
            rows.append(
                (
                    "paper example, lowest 5 to 1e-13, warm",
                    "<= 0.5 ms",
                    "1e-13 not reached",
                    _status(False),
                    "",
                )
            )
        if wp.default_solve:
            d = wp.default_solve
            rows.append(
                (
                    "default `mstmm.solve(scene, modes=5)` of the paper example (mode shapes "
                    "on), warm",
                    "<= 1 ms",
                    f"{fmt_time(d['shapes'])} (median of {int(d['repeats'])}); without shapes "
                    f"{fmt_time(d['no_shapes'])}",
                    _status(d["shapes"] <= 1e-3),
                    f"mode shapes cost {fmt_time(d['shapes'] - d['no_shapes'])} of it",
                )
            )
        # 2. fresh process, kernel cached
        cold = [q for q in wp.points if q.family == "mstmm-cold" and q.modes == 5]
        if cold:
            c = cold[0]
            br = wp.cold_breakdown
            remark = ""
            if br:
                remark = "; ".join(f"`{k}` {fmt_time(v)}" for k, v in br.items())
                remark = "fresh-process costs: " + remark
            jit = [q for q in wp.points if q.family == "mstmm-cold-jit" and q.modes == 5]
            if jit and c.setting.endswith("(interpreted)"):
                remark = (
                    "the kernel runs as Python for so small a first solve (mstmm.interpret); "
                    f"forced compiled it takes {fmt_time(jit[0].time)}. " + remark
                )
            rows.append(
                (
                    "`mstmm solve --modes 5` in a fresh process, kernel cached",
                    "<= 1.0 s wall",
                    f"{fmt_time(c.time)} (median of {c.repeats}; {c.note})",
                    _status(c.time <= 1.0),
                    remark,
                )
            )
        # 3. equal accuracy 1e-10 on the lowest 5
        m = fastest(wp, 5, 1e-10, "mstmm-warm")
        fe = fastest(wp, 5, 1e-10, "fe-richardson")
        os_ = fastest(wp, 5, 1e-10, "opensees")
        if m and fe:
            ratio = fe.time / m.time
            rows.append(
                (
                    "lowest 5 to 1e-10: mstmm (warm) vs the best FE + Richardson",
                    ">= 20x faster",
                    f"{ratio:.0f}x: mstmm {fmt_time(m.time)} "
                    f"({m.setting}, {m.series.split(', ')[-1]}) "
                    f"vs {fe.series} {fe.setting} {fmt_time(fe.time)} (error {fmt_err(fe.error)})",
                    _status(ratio >= 20),
                    "FE timed warm in-process too; a fresh mstmm process (cold) is slower than a "
                    "warm FE solve, see the work-precision table",
                )
            )
        elif m:
            best = [q for q in wp.points if q.family == "fe-richardson" and q.modes == 5]
            best = min(best, key=lambda q: q.error) if best else None
            rows.append(
                (
                    "lowest 5 to 1e-10: mstmm (warm) vs the best FE + Richardson",
                    ">= 20x faster",
                    "FE + Richardson did not reach 1e-10 on the meshes run"
                    + (f" (best {fmt_err(best.error)} at {best.setting})" if best else ""),
                    _status(None),
                    "",
                )
            )
        os_pts = [q for q in wp.points if q.family == "opensees" and math.isfinite(q.error)]
        if m and os_:
            ratio = os_.time / m.time
            rows.append(
                (
                    "lowest 5 to 1e-10: mstmm (warm) vs OpenSeesPy",
                    ">= 20x faster",
                    f"{ratio:.0f}x: OpenSeesPy {os_.setting} {fmt_time(os_.time)}",
                    _status(ratio >= 20),
                    "",
                )
            )
        elif m and os_pts:
            best = min(os_pts, key=lambda q: q.error)
            rows.append(
                (
                    "lowest 5 to 1e-10: mstmm (warm) vs OpenSeesPy",
                    ">= 20x faster",
                    f"OpenSeesPy never reaches 1e-10 with any eigen solver: its best is "
                    f"{fmt_err(best.error)} ({best.series}, {best.setting}, "
                    f"{fmt_time(best.time)} = {best.time / m.time:.0f}x mstmm's "
                    f"{fmt_time(m.time)})",
                    _status(True),
                    "each solver's best: "
                    + opensees_summary(wp, 5)
                    + ". The error stops falling, then grows with n (round-off, eps cond(K) "
                    "~ n^4)",
                )
            )
        else:
            rows.append(
                (
                    "lowest 5 to 1e-10: mstmm vs OpenSeesPy",
                    ">= 20x faster",
                    wp.opensees or "not measured",
                    _status(None),
                    "",
                )
            )
        # 5. derive + compile
        der = [q for q in wp.points if q.family == "mstmm-derive" and q.modes == 5]
        if der:
            d = der[0]
            split = ""
            if sc is not None and sc.derive:
                ok = [r for r in sc.derive if "derive" in r]
                if ok:
                    split = (
                        f"; split (scaling runs, median over N): derive "
                        f"{fmt_time(_median([r['derive'] for r in ok]))}, compile "
                        f"{fmt_time(_median([r['compile'] for r in ok]))}"
                    )
            rows.append(
                (
                    "first run of a new topology: derive + compile (+ solve)",
                    "<= 30 s",
                    f"{fmt_time(d.time)} wall, whole `mstmm solve` process (median of {d.repeats})"
                    + split,
                    _status(d.time <= 30.0),
                    "numba compiles the characteristic function here, a helper the rest of the"
                    " kernel (run as Python meanwhile: mstmm.compiling); the SymPy derivation"
                    " is the smaller part",
                )
            )
    # 4. N = 1000
    if sc is not None:
        for family in ("in band", "stiff mounts"):
            r = [
                x
                for x in sc.solve
                if x["N"] == 1000 and x["family"] == family and x["formulation"] == "stable"
            ]
            if not r:
                continue
            r = r[0]
            if "seconds" not in r:
                rows.append(
                    (
                        f"N = 1000 ({family}): lowest 20 modes, warm",
                        "<= 50 ms",
                        r.get("error", "?"),
                        _status(False),
                        "",
                    )
                )
                continue
            remark = (
                _profile_remark(r["profile"], n=1000, family=family) if r.get("profile") else ""
            )
            rows.append(
                (
                    f"N = 1000 random spring-masses ({family}): lowest 20 modes, warm",
                    "<= 50 ms",
                    f"{fmt_time(r['seconds'])} (median of {r['repeats']})",
                    _status(r["seconds"] <= 0.05),
                    remark,
                )
            )
    return rows


def _median(xs):
    xs = sorted(xs)
    return xs[len(xs) // 2] if xs else math.nan


def _profile_remark(prof: dict, n: int | None = None, family: str | None = None) -> str:
    """Where a solve's time went: the kernel's root search, the checks after it, Python."""
    from .workprecision import fmt_time

    c = prof["calls"]
    parts = []
    if "lowest" in c:
        v = c["lowest"]
        g = prof.get("lowest_grid") or {}
        text = (
            f"kernel search {fmt_time(v['seconds'])} "
            f"({'certified' if v['its'] else 'NOT certified by the count'})"
        )
        if g:
            from .workprecision import lowest_split

            text += ": " + lowest_split(v["seconds"], g)
        parts.append(text)
    ev = c.get("evaluate", {"points": 0, "seconds": 0.0})
    ct = c.get("count_below", {"points": 0, "seconds": 0.0})
    if ev["points"] or ct["points"]:
        parts.append(
            f"checks after it: count {ct['points']} points {fmt_time(ct['seconds'])}, "
            f"function {ev['points']} points {fmt_time(ev['seconds'])}"
        )
    parts.append(f"Python around it {fmt_time(prof['python'])}")
    return "profile: " + "; ".join(parts)


def findings(wp, sc) -> list[str]:
    """Observations drawn from the numbers (what limits performance, where methods stop)."""
    from .workprecision import fmt_err, fmt_time, plateau_of

    out = []
    if wp is not None:
        for modes in (5, 20):
            warm = [
                p
                for p in wp.points
                if p.family == "mstmm-warm"
                and p.modes == modes
                and p.series.endswith("stable")
                and math.isfinite(p.time)
            ]
            zero = [p for p in warm if p.param == 0.0]
            other = [p for p in warm if p.param != 0.0]
            if zero and other and min(p.time for p in other) > 1.5 * zero[0].time:
                out.append(
                    f"Lowest {modes}, stable: asking for less accuracy is slower. rtol = 0 takes "
                    f"{fmt_time(zero[0].time)}, rtol = 1e-4 .. 1e-12 take "
                    f"{fmt_time(min(p.time for p in other))} .. "
                    f"{fmt_time(max(p.time for p in other))}."
                )
        failed = [p for p in wp.points if p.family == "mstmm-warm" and not math.isfinite(p.error)]
        for p in failed:
            out.append(
                f"{p.series}, lowest {p.modes} ({p.setting}): {p.note}. The paper's det U_bar "
                "loses about one digit per pi of lambda L, so above about the 10th mode it is "
                "noise: its sign changes are spurious, the count drops them and bisects to each "
                "root, but a root taken from the noise is flagged NOT TRUSTED, not corrected."
            )
        for series in dict.fromkeys(p.series for p in wp.points if p.family in ("fe", "opensees")):
            for modes in (5, 20):
                pl = plateau_of([p for p in wp.points if p.series == series and p.modes == modes])
                if not pl:
                    continue
                best, worst, slope = pl
                if worst is None:
                    out.append(
                        f"{series}, lowest {modes}: still improving at the finest mesh "
                        f"(n = {int(best.param)}: {fmt_err(best.error)}, {fmt_time(best.time)})."
                    )
                elif slope is not None:
                    out.append(
                        f"{series}, lowest {modes}: stops improving at n = {int(best.param)} "
                        f"({fmt_err(best.error)}); beyond, the error grows like n^{slope:.1f} "
                        "(round-off, eps cond(K) with cond(K) ~ n^4)."
                    )
                elif not math.isfinite(worst.error):
                    out.append(
                        f"{series}, lowest {modes}: best {fmt_err(best.error)} at n = "
                        f"{int(best.param)}; fails at n = {int(worst.param)} ({worst.note})."
                    )
        br = wp.cold_breakdown
        if br:
            keys = list(br)
            steps = [f"{k} {fmt_time(br[k])}" for k in keys]
            out.append(
                "A fresh process (cumulative wall times): " + "; ".join(steps) + ". "
                "Most of it is Python, numpy and numba start-up and loading the cached machine "
                "code, not the solve."
            )
    if sc is not None:
        import math as _m

        from .scaling import MODES, random_scene
        from .workprecision import lowest_split

        for r in sc.solve:
            if r.get("formulation") != "stable" or r["N"] not in (1000, 10000):
                continue
            prof = r.get("profile") or {}
            g = prof.get("lowest_grid")
            low = prof.get("calls", {}).get("lowest")
            if not g or not low or "omega_20" not in r:
                continue
            b = random_scene(1).beam
            beta = b.length * (b.mass_per_length * r["omega_20"] ** 2 / b.EI) ** 0.25
            scan_share = g["scan_seconds"] / max(low["seconds"], 1e-300)
            text = (
                f"N = {r['N']}, {r['family']}: the kernel's `lowest` takes "
                f"{fmt_time(low['seconds'])}; the {MODES}th root is at lambda L = {beta:.3g}. "
                + lowest_split(low["seconds"], g)
                + ". "
            )
            if scan_share < 0.5:
                text += (
                    "The count dominates: the oscillator roots crowd into a few grid cells "
                    f"(the {MODES} lowest lie below lambda L = {beta:.3g}, the grid step is "
                    f"pi/{g['per_mode']}), the scan sees few of them as sign changes, and "
                    "bisection on the O(N) count separates them one by one."
                )
            else:
                text += (
                    "The scan dominates: every node is an O(N) evaluation, "
                    f"{g['per_mode']} nodes per pi of lambda L up to the {MODES}th root."
                )
            out.append(text)
        slopes = {k: v for k, v in sc.slopes.items() if _m.isfinite(v)}
        if slopes:
            out.append(
                "Log-log slopes against N: "
                + "; ".join(f"{k} {v:.2f}" for k, v in slopes.items())
                + "."
            )
    return out


def component_rows(figs: dict) -> list[tuple[str, str, str, str, str]]:
    """Issue 13's targets, from what ``benchmarks.components`` and ``benchmarks.against``
    recorded in docs/figures.json (each with its own date and command)."""
    from .workprecision import fmt_time

    rows = []
    co, ag = figs.get("components"), figs.get("against")
    if ag:
        rows.append(
            (
                f"paper example, lowest {ag['modes']}, warm, frequencies only: not slower than"
                f" before the component library ({ag['other_label']})",
                "ratio <= 1",
                f"{fmt_time(ag['this_seconds'])} vs {fmt_time(ag['other_seconds'])} (ratio"
                f" {ag['ratio']:.2f}, {ag['rounds']} interleaved rounds; frequencies agree to"
                f" {ag['largest_difference']:.1e})",
                _status(ag["ratio"] <= 1.0),
                f"`{ag['measured']['command']}`, {ag['measured']['date']}",
            )
        )
    if co:
        m, first = co["mixed"], co["first_run"]
        rows.append(
            (
                f"{m['components']} components of every kind on a 3-segment beam: lowest 20, warm",
                "<= 50 ms",
                f"{fmt_time(m['lowest20_seconds'])} (`Kernel.lowest`); `solve(shapes=False)`"
                f" {fmt_time(m['solve20_seconds'])}, with mode shapes"
                f" {fmt_time(m['solve20_shapes_seconds'])}; error against the mpmath reference"
                f" {m['error_against_reference']:.1e}, certified {m['certified']}",
                _status(m["lowest20_seconds"] <= 0.05 and m["certified"]),
                f"`{co['measured']['command']}`, {co['measured']['date']}",
            )
        )
        for label, key, goal in (
            ("the shared numerics already compiled on the machine", "numerics_compiled", 5.0),
            ("nothing compiled yet (the first run after installing)", "nothing_compiled", 15.0),
        ):
            r = first[key]
            rows.append(
                (
                    "first run of a new topology with every kind (derive + compile + solve,"
                    f" fresh process, compiled forced): {label}",
                    f"<= {goal:g} s",
                    f"{fmt_time(r['wall_seconds'])} ({'-'.join(r['ends'])} ends)",
                    _status(r["wall_seconds"] <= goal and r["certified"]),
                    _first_run_remark(first, key),
                )
            )
        d = first.get("default")
        if d:
            rows.append(
                (
                    "first run of a new topology with every kind, default settings (a small"
                    " first solve runs as Python)",
                    "<= 15 s",
                    f"{fmt_time(d['wall_seconds'])} ({'-'.join(d['ends'])} ends)",
                    _status(d["wall_seconds"] <= 15.0 and d["certified"]),
                    "SymPy derives the kernel; nothing is compiled (mstmm.interpret)",
                )
            )
    return rows


def damping_rows(figs: dict) -> list[tuple[str, str, str, str, str]]:
    """Issue 14's targets, from what ``benchmarks.damping`` recorded in docs/figures.json."""
    from .workprecision import fmt_err, fmt_time

    d = figs.get("damping")
    if not d:
        return []
    r, f = d["roots"], d["frf"]
    best = r["fe_equal_accuracy"]
    where = f"`{d['measured']['command']}`, {d['measured']['date']}"
    return [
        (
            f"damped paper example (dashpots at 5 % of critical, loss factor 0.01): lowest"
            f" {r['modes']} complex roots, warm, against the damped FE model",
            "faster at equal accuracy",
            f"mstmm {fmt_time(r['mstmm_seconds'])} (error {fmt_err(r['mstmm_error'])}, count"
            f" checked {r['count_checked']}); FE + Richardson {best['elements']} elements"
            f" {fmt_time(best['seconds'])} (error {fmt_err(best['error'])}"
            f"{'' if r['fe_reaches_1e-10'] else ', its best: short of 1e-10'})"
            f" = {r['ratio']:.0f}x",
            _status(r["ratio"] > 1.0 and r["count_checked"]),
            where,
        ),
        (
            f"frequency response: {f['points']} frequencies of the paper example, warm, both cores",
            "<= 50 ms",
            f"{fmt_time(f['seconds_all_cores'])} on {f['threads']} threads"
            f" ({fmt_time(f['seconds_one_core'])} on one); error at 20 points"
            f" {fmt_err(f['error_at_20_points'])}",
            _status(f["seconds_all_cores"] <= 0.05),
            where,
        ),
    ]


def damped_large_rows(figs: dict) -> list[tuple[str, str, str, str, str]]:
    """Issue 20 item 11's target, from what ``benchmarks.damped_large`` recorded."""
    from .workprecision import fmt_err, fmt_time

    d = figs.get("damped_large")
    if not d:
        return []
    w, c, r = d["in_process"], d["command_line"], d["reference"]
    return [
        (
            f"damped scene of {w['components']} mixed components (dashpots at 5 % of critical"
            " in every absorber, loss factor 0.01): lowest 20, warm, against the same scene"
            " undamped",
            "<= 10x",
            f"{fmt_time(w['damped_seconds'])} vs {fmt_time(w['undamped_seconds'])} ="
            f" {w['ratio']:.1f}x (`solve(shapes=False)`); with mode shapes"
            f" {fmt_time(w['damped_shapes_seconds'])} vs"
            f" {fmt_time(w['undamped_shapes_seconds'])} = {w['ratio_shapes']:.1f}x; `mstmm"
            f" solve --modes 20` (fresh process, kernels cached) {fmt_time(c['damped_seconds'])}"
            f" vs {fmt_time(c['undamped_seconds'])} = {c['ratio']:.1f}x; count checked"
            f" {w['count_checked']}; {r['components']} components against the mpmath reference:"
            f" error {fmt_err(r['error'])}",
            _status(
                max(w["ratio"], w["ratio_shapes"]) <= 10.0
                and w["count_checked"]
                and r["error"] <= 1e-10
            ),
            f"`{d['measured']['command']}`, {d['measured']['date']}; the counted rectangle is"
            f" {w['rectangle'][3]:.3g} rad/s tall (the proved decay bound) and each point of"
            " its contour costs one damped chain over every component",
        )
    ]


def codebase_rows(figs: dict) -> list[tuple[str, str, str, str, str]]:
    """Issue 21's code figures, from what ``benchmarks.codebase`` recorded."""
    c = figs.get("codebase")
    if not c:
        return []
    g, n = c["generated"], c["numerics"]
    every = g["every_kind"]
    share = g["printed"] / g["lines"]

    def of(r: dict) -> str:
        return f"{r['printed'] / r['lines']:.0%} ({r['printed'] / r.get('code', r['lines']):.0%})"

    u, d = every["undamped"], every["damped"]
    code_share = g["printed"] / g.get("code", g["lines"])
    return [
        (
            "lines of `generated/` printed by SymPy",
            ">= 90 %",
            f"{g['printed']} of {g['lines']} = {share:.0%} of its lines, {code_share:.0%} of"
            f" its lines of code (a kernel of every kind: {of(u)} undamped, {of(d)} damped)",
            _status(share >= 0.9),
            f"`{c['measured']['command']}`, {c['measured']['date']}; every function and"
            " constant is printed from SymPy's codegen AST; what is not is each module's"
            " header (docstring, imports, the hashes and kinds it was printed with) and a"
            " kernel's last line, `bind_characteristic`; what composes the printed functions"
            " is ordinary code (`mstmm/numerics/beam.py`, `characteristic.py`)",
        ),
        (
            "hand-written numba in `src/mstmm/numerics/` (ordinary, linted code)",
            "measured",
            f"{n['lines']} lines of code (statements; no blank lines, comments, docstrings)",
            "",
            f"`{c['measured']['command']}`",
        ),
        (
            "files touched to add a point kind",
            "1",
            f"{c['files_to_add_a_kind']} (the kind's file)",
            _status(c["files_to_add_a_kind"] == 1),
            f"{c['files_to_add_a_kind_checked_by']} adds one to a copy of the package",
        ),
    ]


def segment_rows(figs: dict) -> list[tuple[str, str, str, str, str]]:
    """Issue 22's targets, from what ``benchmarks.segments`` recorded."""
    g = figs.get("segments")
    if not g:
        return []
    when = f"`{g['measured']['command']}`, {g['measured']['date']}"
    closed = g["closed_forms"]
    worst = max(r["error"] for r in closed.values())
    w, m, f = g["warm_solve"], g["many_modes"], g["first_run"]
    rows = [
        (
            "segment terms against closed forms (simply supported, 8 combinations, 16 modes)",
            "<= 1e-12",
            f"worst {worst:.1e}, every count checked",
            _status(worst <= 1e-12 and all(r["count_checked"] for r in closed.values())),
            when + "; Timoshenko's two spectra and the thickness-shear mode included",
        ),
        (
            "paper example with every segment term, warm (frequencies only)",
            "<= 2x Euler-Bernoulli",
            f"{w['every_term'] * 1e3:.3f} ms against {w['euler_bernoulli'] * 1e3:.3f} ms"
            f" ({w['ratio']:.2f}x)",
            _status(w["ratio"] <= 2.0),
            when + "; one exp(A h) (a Cayley-Hamilton series) and its minors per piece"
            " between components, against the printed closed forms",
        ),
        (
            f"Timoshenko, lowest {m['modes']} ({m['above_cut_off']} above the cut-off)",
            "stable, <= 1e-10",
            f"worst {m['error']:.1e} in {m['seconds']:.2f} s",
            _status(m["error"] <= 1e-10 and m["count_checked"]),
            when,
        ),
        (
            "first run of a new topology with segment terms (shared numerics compiled)",
            "<= 5 s",
            f"{f['default']['process']:.2f} s as run (kernel as Python); derive + compile"
            f" {f['compiled']['process']:.2f} s",
            _status(f["default"]["process"] <= 5.0),
            when + "; a fresh process with an empty kernel cache",
        ),
    ]
    if "fem" in g:
        e = g["fem"]
        rows.append(
            (
                "against the finite-element model with these terms (tests/reference_fem.py)",
                "converging to mstmm",
                f"{e['error']:.1e} after Richardson ({e['elements']} elements)",
                _status(e["error"] <= 1e-8),
                when + "; " + e["scene"],
            )
        )
    return rows


def periodic_rows(figs: dict) -> list[tuple[str, str, str, str, str]]:
    """Issue 23's targets on periodic cells, from what ``benchmarks.periodic`` recorded
    (the clusters' from ``benchmarks.clusters``)."""
    g = figs.get("periodic")
    if not g:
        return []
    when = f"`{g['measured']['command']}`, {g['measured']['date']}"
    d, e, a = g["dispersion"], g["edges"], g["attenuation"]
    return [
        (
            f"dispersion of a cell at {d['frequencies']} frequencies, warm",
            "<= 20 ms",
            f"{d['seconds'] * 1e3:.2f} ms ({d['cell']}; its {d['edges']} edges with the count"
            f" {d['edges_seconds'] * 1e3:.2f} ms)",
            _status(d["seconds"] <= 0.020),
            when + "; the cell's end-state subspace re-orthonormalised per piece, real"
            " arithmetic for an undamped cell (complex for a damped one), numba prange over"
            " the frequencies",
        ),
        (
            "band edges against an mpmath reference",
            "<= 1e-12, none missed",
            f"worst {e['worst']:.1e} over {e['edges']} edges of {e['cells']} cells,"
            f" {e['missed_or_spurious']} missed or spurious; every stretch proved"
            f" ({e['count_checked']}), {e['meetings_confirmed']} of {e['meetings']} proved"
            " band ends inside the zone confirmed by mpmath",
            _status(
                e["worst"] <= 1e-12
                and e["missed_or_spurious"] == 0
                and e["count_checked"]
                and e["meetings_confirmed"] == e["meetings"]
            ),
            when + "; tests/reference_bloch.py (its own count of the closed ring)",
        ),
        (
            "a finite beam's attenuation in a gap against N Im k",
            "agrees",
            f"decay per cell within {a['error']:.1e} of Im k L = {a['im_k_L']:.4f}"
            f" ({a['cells']} cells)",
            _status(a["error"] <= 1e-6),
            when + "; mstmm.frf along the beam",
        ),
    ]


def cluster_rows(figs: dict) -> list[tuple[str, str, str, str, str]]:
    """Issue 23's targets on clusters of roots, from what ``benchmarks.clusters``
    recorded."""
    g = figs.get("clusters")
    if not g:
        return []
    when = f"`{g['measured']['command']}`, {g['measured']['date']}"
    rows = []
    for r in g["in_band"]:
        goal = 0.050 if r["n"] <= 10_000 else 0.500
        rows.append(
            (
                f"N = {r['n']} spring-masses in band, lowest 20 certified, warm",
                f"<= {goal * 1e3:.0f} ms",
                f"{r['solve'] * 1e3:.1f} ms; {r['missed']} missed ({r['missed_by']})",
                _status(r["solve"] <= goal and r["count_checked"] and r["missed"] == 0),
                when + "; one count per block, Brent only on roots reported, the roots refined"
                " on both cores after the search (docs/clusters.md)",
            )
        )
    one, spaced, slopes = g["one_point"], g["spaced"], g["slopes"]
    big = one[-1]
    rows.append(
        (
            f"N identical resonators at one point: the whole cluster (N = {big['n']})",
            "N - 1 roots, exact multiplicity, linear in N",
            f"multiplicity {big['multiplicity']} at the own frequency, {big['missed']} missed,"
            f" {big['seconds'] * 1e3:.1f} ms; log-log slope {slopes['one_point']:.2f}",
            _status(big["multiplicity"] == big["n"] - 1 and slopes["one_point"] <= 1.15),
            when,
        )
    )
    s = spaced[-1]
    ten = next((r for r in spaced if r["n"] == 10_000), s)
    rows.append(
        (
            f"N identical resonators at spaced points: every root (N = {s['n']})",
            "linear in N, none missed",
            f"{s['seconds']:.2f} s (N = {ten['n']}: {ten['seconds'] * 1e3:.1f} ms),"
            f" {sum(r['missed'] for r in spaced)} missed; log-log slope"
            f" {slopes['spaced']:.2f} from N = {spaced[0]['n']}",
            _status(slopes["spaced"] <= 1.15 and all(r["missed"] == 0 for r in spaced)),
            when + "; N cells (repeat = N): count and characteristic function in O(log N)"
            " (mstmm.repeated); roots closer than round-off come out as one root of their"
            " count's multiplicity (docs/clusters.md)",
        )
    )
    meta = g.get("metamaterial")
    if meta:
        m = meta[-1]
        rows.append(
            (
                f"metamaterial beam of N cells: every root below the gap (N = {m['n']})",
                "linear in N, none missed",
                f"{m['modes']} roots in {m['seconds']:.2f} s; log-log slope"
                f" {slopes['metamaterial']:.2f}; missed {sum(r['missed'] for r in meta)}"
                f" ({meta[0]['missed_by']} at N = {meta[0]['n']})",
                _status(slopes["metamaterial"] <= 1.15 and all(r["missed"] == 0 for r in meta)),
                when + "; mstmm.repeated",
            )
        )
    return rows


def targets_markdown(rows) -> str:
    out = [
        "| target | goal | measured | status | what limits it / remark |",
        "|---|---|---|---|---|",
    ]
    for r in rows:
        out.append("| " + " | ".join(x.replace("|", "/") for x in r) + " |")
    return "\n".join(out) + "\n"


# ------------------------------------------------------------------ figures


def _point(p) -> dict | None:
    if p is None:
        return None
    return {"series": p.series, "setting": p.setting, "time": p.time, "error": p.error}


def figures_of(wp, sc, st) -> dict[str, dict]:
    """What the README quotes from this run, per section (``docs/figures.json``)."""
    from .workprecision import fastest, opensees_best

    out: dict[str, dict] = {}
    if wp is not None:
        default = [
            q
            for q in wp.points
            if q.family == "mstmm-warm" and q.modes == 5 and q.setting == "rtol=0"
        ]
        default = [q for q in default if q.series.endswith("stable")]
        m = fastest(wp, 5, 1e-10, "mstmm-warm")
        fe = fastest(wp, 5, 1e-10, "fe-richardson")
        first = {
            fam: [q for q in wp.points if q.family == fam and q.modes == 5]
            for fam in ("mstmm-cold", "mstmm-cold-jit", "mstmm-derive")
        }
        out["workprecision"] = {
            "quick": wp.quick,
            "warm_default_lowest5": _point(default[0] if default else None),
            "warm_lowest5_1e-10": _point(m),
            "fe_richardson_1e-10": _point(fe),
            "fe_ratio": fe.time / m.time if (m and fe) else None,
            "opensees": wp.opensees,
            "opensees_best": {k: _point(v) for k, v in opensees_best(wp, 5).items()},
            "fresh_process": {k: _point(v[0] if v else None) for k, v in first.items()},
            "fresh_process_breakdown": wp.cold_breakdown,
            "default_solve": wp.default_solve,
        }
    if sc is not None:
        n1000 = {
            r["family"]: r.get("seconds")
            for r in sc.solve
            if r["N"] == 1000 and r["formulation"] == "stable"
        }
        ok = [r for r in sc.derive if "derive" in r]
        out["scaling"] = {
            "quick": sc.quick,
            "lowest20_n1000": n1000,
            "derive_median": _median([r["derive"] for r in ok]) if ok else None,
            "compile_median": _median([r["compile"] for r in ok]) if ok else None,
            "slopes": sc.slopes,
        }
    if st is not None:
        out["study"] = {**st.to_json(), "quick": st.points < 10_000}
    return out


# ------------------------------------------------------------------ report

INTRO = """# Benchmarks: error against run time

Generated by `{command}` (do not edit by hand; `--quick` is a smoke run whose
numbers mean little). One run, one machine; every time is the **median** of
repeated runs after a warm-up run (a run longer than 2 s is measured once, after
everything was compiled on a small case), wall clock by `time.perf_counter`.
"Warm" means in-process with the kernel loaded and compiled
(`kernel=mstmm.kernel_for(scene)` reused); "cold" means a fresh Python process.
Errors are the largest relative error over the modes, against exact values
independent of mstmm (`tests/data/reference.json`, `tests/reference_model.py` in
mpmath), computed in mpmath. BLAS is single-threaded for everything
(`OPENBLAS_NUM_THREADS=1`): with two threads on this 2-core machine the dense FE
solver was up to 60x slower. Other processes may have been running: the load
average is recorded below.
"""


def report(out_dir: Path, wp, sc, start: dict, end: dict, elapsed: float, st=None) -> Path:
    """Write ``out_dir/benchmarks.md`` (and the plots under ``out_dir/img``)."""
    from . import figures, machine, scaling, study, workprecision

    out_dir.mkdir(parents=True, exist_ok=True)
    parts = [INTRO.format(command=start["command"])]
    skipped = []
    wp_img = sc_img = None
    if wp is not None:
        wp_img, why = try_plot(workprecision.plot, wp, out_dir / "img" / "workprecision.png")
        if why:
            skipped.append(why)
    if sc is not None:
        sc_img, why = try_plot(scaling.plot, sc, out_dir / "img" / "scaling.png")
        if why and why not in skipped:
            skipped.append(why)
    if skipped:
        parts.append("**Plots:** " + "; ".join(skipped) + ".\n")
    parts.append("## Machine\n")
    parts.append(machine.markdown(start, end, elapsed) + "\n")
    parts.append("## Targets\n")
    parts.append("Goals of the benchmark (not timed unit tests), each with the measured figure.\n")
    recorded = figures.load()
    rows = (
        targets(wp, sc, st)
        + component_rows(recorded)
        + damping_rows(recorded)
        + damped_large_rows(recorded)
        + codebase_rows(recorded)
        + segment_rows(recorded)
        + periodic_rows(recorded)
        + cluster_rows(recorded)
    )
    parts.append(targets_markdown(rows))
    notes = findings(wp, sc)
    if notes:
        parts.append("## Findings\n")
        parts.append("\n".join(f"* {n}" for n in notes) + "\n")
    if wp is not None:
        parts.append("## 1. Work-precision: paper example (Wu & Chou 1998)\n")
        parts.append(_doc(workprecision))
        parts.append(workprecision.markdown(wp, wp_img))
    if sc is not None:
        parts.append("## 2. Scaling with the number of attachments N\n")
        parts.append(_doc(scaling))
        parts.append(scaling.markdown(sc, sc_img))
    if st is not None:
        parts.append("## 3. Parameter study on all cores\n")
        parts.append(_doc(study))
        parts.append(study.markdown(st))
    path = out_dir / "benchmarks.md"
    path.write_text("\n".join(parts))
    return path


def _doc(module) -> str:
    """The module docstring minus its first line: the method, in the report."""
    lines = (module.__doc__ or "").strip().splitlines()[1:]
    return "\n".join(lines).strip() + "\n"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m benchmarks", description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="smoke run (~30 s)")
    ap.add_argument("--only", choices=SECTIONS, help="run one section")
    ap.add_argument("--out", type=Path, default=ROOT / "docs", help="report directory")
    ap.add_argument("--json", type=Path, help="also write the raw results here")
    ap.add_argument("--render", type=Path, help="only re-render the report from a --json file")
    args = ap.parse_args(argv)
    # before numpy is imported (by the modules below)
    for var in ("OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "OMP_NUM_THREADS"):
        os.environ.setdefault(var, "1")

    from . import figures, machine, scaling, study, workprecision

    if args.render:
        raw = json.loads(args.render.read_text())
        wp = workprecision.Results.from_json(raw["workprecision"]) if raw["workprecision"] else None
        sc = scaling.Results(**raw["scaling"]) if raw["scaling"] else None
        st = study.Results(**raw["study"]) if raw.get("study") else None
        path = report(args.out, wp, sc, raw["machine"], raw.get("machine_end"), raw["elapsed"], st)
        _log(f"re-rendered {path}")
        return 0
    start = machine.info(sys.argv if argv is None else ["benchmarks", *argv])
    t0 = time.perf_counter()
    wp = sc = st = None
    if args.only in (None, "workprecision"):
        wp = workprecision.run(quick=args.quick, log=_log)
    if args.only in (None, "scaling"):
        sc = scaling.run(quick=args.quick, log=_log)
    if args.only in (None, "study"):
        _log("parameter study")
        st = study.run(quick=args.quick, log=_log)
    elapsed = time.perf_counter() - t0
    end = machine.info()
    path = report(args.out, wp, sc, start, end, elapsed, st)
    for section, values in figures_of(wp, sc, st).items():
        figures.record(section, values, args.out / "figures.json", start["command"])
    if args.json:
        raw = {
            "machine": start,
            "machine_end": end,
            "elapsed": elapsed,
            "workprecision": wp.to_json() if wp else None,
            "scaling": sc.to_json() if sc else None,
            "study": st.to_json() if st else None,
        }
        args.json.write_text(json.dumps(raw, indent=1, default=str))
    _log(f"wrote {path} ({elapsed:.0f} s)")
    for row in targets(wp, sc, st):
        _log(f"target: {row[0]}: {row[2]} -> {row[3]}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

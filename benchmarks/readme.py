"""Write the measured figures of README.md and docs/*.md from ``docs/figures.json``.

Run: ``python -m benchmarks.readme``. The pages (README.md and every ``docs/*.md``,
:func:`pages`) mark every measured figure with a block::

    <!-- figures:NAME -->...<!-- /figures:NAME -->

and this script rewrites each block's content, wherever it stands, from the figures the
benchmarks recorded (:mod:`benchmarks.figures`; ``docs/certification.json`` of
``python -m benchmarks.certification`` too, when it exists). Every block of
:data:`BLOCKS` occurs exactly once over all the pages, so a block moves with its text
from one page to another and is still rewritten. A link a block writes is relative to
the repository root (``docs/many_modes.md``) and is made relative to the page that holds
it. ``--check`` only reports whether the pages are up to date (exit status 1 if not);
``tests/test_readme_figures.py`` runs the same check, so a figure typed into a page
fails CI. Which benchmark feeds which block:

* ``example``: ``python -m benchmarks.example`` (the output of ``mstmm solve``);
* ``front-damped``, ``front-frf``, ``front-bands``, ``front-sweep``, ``front-frame``:
  ``python -m benchmarks.example --front-page`` (the README's other examples, each
  command's output);
* ``first-solve``: ``example``, ``python -m benchmarks`` (fresh-process and
  first-derive times, the scaling run's SymPy time);
* ``table1``: ``python -m benchmarks.table1`` and ``python -m benchmarks``
  (the fresh-process line);
* ``certification``: ``python -m benchmarks.certification`` (docs/certification.json);
* ``accuracy``: ``python -m benchmarks.stability`` and ``python -m benchmarks``;
* ``many-modes``: ``python -m benchmarks.many_modes``;
* ``components``: ``python -m benchmarks.components --record``;
* ``segments``: ``python -m benchmarks.segments --record``.
* ``periodic``: ``python -m benchmarks.periodic --record``.
* ``clusters``: ``python -m benchmarks.clusters --record``.
"""

from __future__ import annotations

import argparse
import json
import posixpath
import re
import sys
import textwrap
from pathlib import Path

from mstmm.interpret import DEFAULT_BUDGET

from . import figures
from .opensees_model import KNOWN_FAILURES
from .workprecision import fmt_err, fmt_time

README = figures.ROOT / "README.md"
DOCS = figures.ROOT / "docs"
CERTIFICATION = figures.ROOT / "docs" / "certification.json"

BLOCK = re.compile(
    r"<!-- figures:(?P<name>[a-z0-9-]+) -->(?P<body>.*?)<!-- /figures:(?P=name) -->", re.S
)

#: The producing command of each section of docs/figures.json.
PRODUCERS = {
    "example": "python -m benchmarks.example",
    "front_page": "python -m benchmarks.example --front-page",
    "table1": "python -m benchmarks.table1",
    "stability": "python -m benchmarks.stability",
    "workprecision": "python -m benchmarks",
    "scaling": "python -m benchmarks",
    "study": "python -m benchmarks",
    "many_modes": "python -m benchmarks.many_modes",
    "components": "python -m benchmarks.components --record",
    "segments": "python -m benchmarks.segments --record",
    "periodic": "python -m benchmarks.periodic --record",
    "clusters": "python -m benchmarks.clusters --record",
    "busy": "python -m benchmarks.busy --record",
    "frames": "python -m benchmarks.frames --rounds 5 --accuracy --fem 64 --record",
}

WIDTH = 88


class MissingFigures(LookupError):
    """A block needs a section that no benchmark has recorded (or only a --quick run)."""


def _section(figs: dict, name: str) -> dict:
    sec = figs.get(name)
    if sec is None:
        raise MissingFigures(f"docs/figures.json has no '{name}': run {PRODUCERS[name]}")
    if sec.get("quick"):
        raise MissingFigures(
            f"docs/figures.json '{name}' comes from a --quick run: run {PRODUCERS[name]}"
        )
    return sec


def _para(text: str) -> str:
    return textwrap.fill(" ".join(text.split()), WIDTH)


def _bullet(text: str) -> str:
    return textwrap.fill(" ".join(text.split()), WIDTH, initial_indent="* ", subsequent_indent="  ")


def _fresh(figs: dict) -> dict:
    return _section(figs, "workprecision")["fresh_process"]


# ------------------------------------------------------------------ blocks


def example(figs: dict, cert: dict | None) -> str:
    ex = _section(figs, "example")
    return f"\n```\n$ {ex['command']}\n{ex['output'].rstrip()}\n```\n"


#: Lines of a front-page example's output shown before "...".
FRONT_LINES = {"front-sweep": 3}


def _front(name: str):
    def block(figs: dict, cert: dict | None) -> str:
        ex = _section(figs, "front_page")[name.removeprefix("front-")]
        lines = ex["output"].rstrip().splitlines()
        keep = FRONT_LINES.get(name)
        if keep is not None and len(lines) > keep:
            lines = [*lines[:keep], "..."]
        return f"\n```\n$ {ex['command']}\n" + "\n".join(lines) + "\n```\n"

    block.__name__ = name.replace("-", "_")
    return block


def first_solve(figs: dict, cert: dict | None) -> str:
    wp = _section(figs, "workprecision")
    sc = _section(figs, "scaling")
    fresh = wp["fresh_process"]
    br = wp.get("fresh_process_breakdown") or {}
    floor_key = "import numba; first call of a trivial cached @njit function (numba's floor)"
    floor = ""
    if floor_key in br and "import numba" in br:
        floor = (
            f" numba charges a fresh process {fmt_time(br[floor_key] - br['import numba'])} "
            "to load even cached machine code, whatever the function (a trivial function's "
            "first call after `import numba`)."
        )
    text = (
        "A small first solve runs the kernel's own functions as plain Python "
        "(`scan+refine` in the time line of `mstmm solve`); a fresh `mstmm solve --modes 5` "
        f"process takes {fmt_time(fresh['mstmm-cold']['time'])} that way, against "
        f"{fmt_time(fresh['mstmm-cold-jit']['time'])} when forced to load the compiled "
        f"kernel.{floor} Bigger or repeated work in a process loads the compiled kernel "
        '("compile" in the time line) once the Python time would have paid for it '
        f"(`MSTMM_INTERPRET_BUDGET`, seconds, default {DEFAULT_BUDGET:g}; `0` means always "
        "compiled; see "
        "`src/mstmm/interpret.py`). The first run of a new topology derives its kernel with "
        f"SymPy and compiles it: {fmt_time(fresh['mstmm-derive']['time'])} once, for the "
        f"whole process ({fmt_time(sc['derive_median'])} of it SymPy)."
    )
    return "\n" + _para(text) + "\n"


def table1(figs: dict, cert: dict | None) -> str:
    from .table1 import markdown

    t1 = _section(figs, "table1")
    cold = _fresh(figs)["mstmm-cold"]
    intro = (
        "Lowest five frequencies (rad/s) of the paper's example, each line's largest relative "
        "error against the exact reference (`tests/data/reference.json`, computed "
        "independently by global assembly in 50-digit arithmetic). Quoted lines are the "
        "paper's numbers and CPU times; mstmm's lines are measured on this machine "
        f"({t1['measured']['machine']}), median of {t1['repeats']} warm solves. Reproduce "
        "with `python -m benchmarks.table1`."
    )
    line = (
        f"`mstmm solve --modes 5` in a fresh process, kernel cached: {fmt_time(cold['time'])} "
        "wall (`python -m benchmarks`)."
    )
    return f"\n{_para(intro)}\n\n{markdown(t1)}\n{line}\n"


def certification(figs: dict, cert: dict | None) -> str:
    if not cert:
        return "What the check costs is measured by `python -m benchmarks.certification`."
    rows = cert.get("rows") or []
    row = min(rows, key=lambda r: r.get("modes", 0)) if rows else None
    if row is None:
        return "What the check costs is measured by `python -m benchmarks.certification`."
    return (
        f"The check's cost: the lowest {row['modes']} of the paper's example take "
        f"{fmt_time(row['certified_s'])} certified against {fmt_time(row['unchecked_s'])} "
        f"for the same search with the count switched off ({row['ratio']:.2f}x; "
        "`python -m benchmarks.certification`)."
    )


def many_modes(figs: dict, cert: dict | None) -> str:
    mm = _section(figs, "many_modes")
    times = mm["times"]
    n, t = times[-1]
    return (
        "\n"
        + _bullet(
            f"**Many modes**: the cost of `--modes N` is linear in N: {n:,} modes of the paper's "
            f"example in {fmt_time(t)} warm, {fmt_time(t / n)} per mode (log-log slope "
            f"{mm['slope']:.2f} over N = {times[0][0]:,} .. {n:,}; `python -m "
            "benchmarks.many_modes`, [docs/many_modes.md](docs/many_modes.md))."
        )
        + "\n"
    )


def accuracy(figs: dict, cert: dict | None) -> str:
    stab = _section(figs, "stability")
    wp = _section(figs, "workprecision")
    sc = _section(figs, "scaling")
    st = _section(figs, "study")
    fresh = wp["fresh_process"]
    bullets = []
    first = stab.get("paper_det_first_beyond")
    paper = (
        f"The paper's determinant leaves the tolerance between its {first[0]}th and "
        f"{first[1]}th mode on {stab['paper_det_cases_beyond']} of them."
        if first
        else "The paper's determinant stays within the tolerance on every one."
    )
    bullets.append(
        f"**Extreme cases** ({stab['cases']} scenes: springs 1e-6 .. 1e12 EI/L^3, masses 1e-6 "
        ".. 1e6 mbar L, attachments at the ends, 1e-9 L apart and at one x, 1000 attachments, "
        "the paper's example up to its 100th mode, all 16 end pairs, free-free, beams from "
        "0.01 m to 100 m and EI from 1 to 1e9): the default formulation is within the case's "
        "tolerance (1e-12, or 1e-10 for the hardest) of an independent 30-digit reference on "
        f"{stab['passed']} of {stab['cases']} (worst {fmt_err(stab['worst_error'])}, "
        f"`{stab['worst_case']}`); `tests/test_extremes.py` asserts it. {paper}"
    )
    cost = stab["cost_seconds"]
    bullets.append(
        "**Cost per evaluation** of the stable function grows linearly with the number of "
        f"attachments (slope {stab['cost_slope_big']:.2f} for N >= 100; "
        f"{fmt_time(cost['1000'])} at N = 1000)."
    )
    warm = wp["warm_default_lowest5"]
    fe = wp["fe_richardson_1e-10"]
    fe_text = (
        f"a finite-element model with Richardson extrapolation needs {fmt_time(fe['time'])} for "
        f"1e-10 ({wp['fe_ratio']:.0f}x)"
        if fe
        else "a finite-element model with Richardson extrapolation does not reach 1e-10"
    )
    bullets.append(
        f"**Work-precision** (lowest 5 of the paper's example): mstmm reaches "
        f"{fmt_err(warm['error'])} in {fmt_time(warm['time'])} warm; {fe_text}; "
        + _opensees(wp)
        + _default_solve(wp)
        + f" A fresh `mstmm solve` process with the kernel cached takes "
        f"{fmt_time(fresh['mstmm-cold']['time'])}, mostly starting Python, numpy and numba "
        f"({fmt_time(fresh['mstmm-cold-jit']['time'])} if forced to load the compiled kernel); "
        f"the first run of a new topology (derive + compile) "
        f"{fmt_time(fresh['mstmm-derive']['time'])}, of which SymPy is "
        f"{fmt_time(sc['derive_median'])}."
    )
    n1000 = [t for t in sc["lowest20_n1000"].values() if t is not None]
    slopes = sc.get("slopes") or {}
    flat = [slopes.get(k) for k in ("derive (all N)", "bytes (all N)", "compile (all N)")]
    flat_text = (
        " (log-log slopes against N: " + ", ".join(f"{s:.2f}" for s in flat) + ")"
        if all(s is not None for s in flat)
        else ""
    )
    bullets.append(
        f"**Scale**: lowest 20 modes of a beam with 1000 spring-masses in "
        f"{_span(n1000)} warm; derive time, kernel size and compile time do not depend on "
        f"N{flat_text}."
    )
    one, every = st["threads"].values()
    certified = (
        "every point certified by the count"
        if not st["uncertified"]
        else f"{st['uncertified']} points not certified by the count (NaN)"
    )
    bullets.append(
        f"**Parameter studies**: {st['points']:,} points of the paper's example (lowest "
        f"{st['modes']}) take {fmt_time(every)} on {st['cores']} threads against "
        f"{fmt_time(one)} on one (speed-up {one / every:.2f}x, with whatever else the machine "
        f"was running: see docs/benchmarks.md), {certified} (largest error "
        f"{fmt_err(st['max_error'])} on {st['checked']} "
        "points checked against the mpmath reference)."
    )
    return "\n" + "\n".join(_bullet(b) for b in bullets) + "\n"


def _span(times: list[float]) -> str:
    if not times:
        return "(not measured)"
    lo, hi = min(times), max(times)
    return fmt_time(lo) if lo == hi else f"{fmt_time(lo)} - {fmt_time(hi)}"


def _opensees(wp: dict) -> str:
    best = wp.get("opensees_best") or {}
    if not best:
        return f"OpenSeesPy was not measured ({wp.get('opensees', '')}). "
    ok = {k: v for k, v in best.items() if v and v["error"] is not None}
    parts = []
    for series, p in best.items():
        solver = series.replace("OpenSeesPy ", "")
        if p and p["error"] is not None:
            parts.append(f"`{solver}` {fmt_err(p['error'])} at {p['setting']}")
        else:
            why = KNOWN_FAILURES.get(solver, "fails")
            parts.append(f"`{solver}` {why}")
    top = min(ok.values(), key=lambda p: p["error"]) if ok else None
    lead = (
        f"OpenSeesPy gets no lower than {fmt_err(top['error'])} with any of its eigen solvers"
        if top
        else "OpenSeesPy fails with every eigen solver"
    )
    return f"{lead} ({'; '.join(parts)})."


def _default_solve(wp: dict) -> str:
    d = wp.get("default_solve") or {}
    if not d:
        return ""
    return (
        f" The default call `mstmm.solve(scene, modes=5)`, mode shapes included, takes "
        f"{fmt_time(d['shapes'])} warm ({fmt_time(d['no_shapes'])} with `shapes=False`)."
    )


def components(figs: dict, cert: dict | None) -> str:
    co = _section(figs, "components")
    m, first = co["mixed"], co["first_run"]
    warm, cold = first["numerics_compiled"], first["nothing_compiled"]
    text = (
        f"A 3-segment beam carrying {m['components']} components of every kind: its lowest 20"
        f" frequencies in {fmt_time(m['lowest20_seconds'])} warm (`Kernel.lowest`;"
        f" `mstmm.solve(..., shapes=False)` {fmt_time(m['solve20_seconds'])}, with mode"
        f" shapes {fmt_time(m['solve20_shapes_seconds'])}), certified by the count and"
        f" within {fmt_err(m['error_against_reference'])} of the independent mpmath reference"
        " (`tests/reference_model.py`, whose own count proves that no root was missed). The"
        " first run of a topology with every kind present (derive with SymPy, compile,"
        f" solve; a fresh process) takes {fmt_time(warm['wall_seconds'])} once the shared"
        " numerics are compiled on the machine (any earlier run compiled them), and"
        f" {fmt_time(cold['wall_seconds'])} on a machine where nothing is compiled yet."
        " Reproduce with `python -m benchmarks.components`."
    )
    return "\n" + _para(text) + "\n"


def damping(figs: dict, cert: dict | None) -> str:
    d = _section(figs, "damping")
    r, f = d["roots"], d["frf"]
    best = r["fe_equal_accuracy"]
    fe = (
        f"the damped finite-element model (first-order form, `scipy.linalg.eig`, Richardson)"
        f" needs {best['elements']} elements and {fmt_time(best['seconds'])} to reach 1e-10"
        if r["fe_reaches_1e-10"]
        else "the damped finite-element model (first-order form, `scipy.linalg.eig`,"
        f" Richardson) gets no closer than {fmt_err(best['error'])}, with {best['elements']}"
        f" elements in {fmt_time(best['seconds'])}"
    )
    text = (
        f"The paper's example with a dashpot beside each spring (5 % of critical) and a beam"
        f" loss factor of 0.01: its lowest {r['modes']} damped roots in"
        f" {fmt_time(r['mstmm_seconds'])} warm (with mode shapes"
        f" {fmt_time(r['mstmm_shapes_seconds'])}), within {fmt_err(r['mstmm_error'])} of the"
        f" mpmath reference, the argument-principle count checked; {fe}"
        f" ({r['ratio']:.0f}x). The tip receptance at {f['points']} frequencies up to"
        f" {f['band'][1]:.0f} rad/s (its first {r['modes']} modes):"
        f" {fmt_time(f['seconds_all_cores'])} warm on {f['threads']} cores"
        f" ({fmt_time(f['seconds_one_core'])} on one), within"
        f" {fmt_err(f['error_at_20_points'])} of the reference's direct solve. Reproduce with"
        " `python -m benchmarks.damping`."
    )
    return "\n" + _para(text) + "\n"


def segments(figs: dict, cert: dict | None) -> str:
    g = _section(figs, "segments")
    worst = max(r["error"] for r in g["closed_forms"].values())
    w, m, f, e = g["warm_solve"], g["many_modes"], g["first_run"], g["fem"]
    text = (
        f"A simply supported beam with every combination of these terms, against the closed"
        f" form (both Timoshenko spectra): worst {fmt_err(worst)} over the lowest 16, the"
        f" count checked. The lowest {m['modes']} of a Timoshenko beam, {m['above_cut_off']}"
        f" of them above its cut-off: {fmt_err(m['error'])} in {fmt_time(m['seconds'])}."
        f" {e['scene'].capitalize()}: within {fmt_err(e['error'])} of the finite-element"
        f" model with Timoshenko elements after Richardson extrapolation. The paper's example"
        f" with every term on solves (lowest 10, frequencies only) in"
        f" {fmt_time(w['every_term'])} warm, {w['ratio']:.2f}x its Euler-Bernoulli"
        f" {fmt_time(w['euler_bernoulli'])}; a first run of a new topology with these"
        f" terms takes {fmt_time(f['default']['process'])} in a fresh process"
        f" ({fmt_time(f['compiled']['process'])} when compiled). Reproduce with"
        " `python -m benchmarks.segments`."
    )
    return "\n" + _para(text) + "\n"


def periodic(figs: dict, cert: dict | None) -> str:
    g = _section(figs, "periodic")
    d, e, a = g["dispersion"], g["edges"], g["attenuation"]
    text = (
        f"The dispersion of the metamaterial cell at {d['frequencies']} frequencies takes"
        f" {fmt_time(d['seconds'])} warm (both cores), its {d['edges']} edges with their"
        f" count {fmt_time(d['edges_seconds'])}. Against an independent mpmath model with"
        f" its own count, {e['edges']} edges of {e['cells']} cells (every kind, supports,"
        f" segment physics, random cells): worst {fmt_err(e['worst'])},"
        f" {e['missed_or_spurious']} missed or spurious; every stretch between them proved,"
        f" and of the {e['meetings']} band ends inside the zone it proved (two pairs meet"
        f" and turn complex, {e['above_cut_off']} of the cells taken to three times their"
        f" Timoshenko cut-off), {e['meetings_confirmed']} confirmed by mpmath's waves 1e-9"
        f" on either side. A free-free beam of {a['cells']}"
        f" cells driven at one end in the gap: its response decays per cell as the cell's"
        f" Im k L = {a['im_k_L']:.4f} predicts, within {fmt_err(a['error'])}. Reproduce with"
        " `python -m benchmarks.periodic`."
    )
    return "\n" + _para(text) + "\n"


def clusters(figs: dict, cert: dict | None) -> str:
    g = _section(figs, "clusters")
    sp, mm, sl = g["spaced"], g["metamaterial"], g["slopes"]
    small = next(r for r in sp if "general_seconds" in r)
    big = sp[-1]
    m = mm[-1]
    text = (
        f"Such a structure is solved as what it is: the count and the characteristic"
        f" function of N identical cells cost O(log N) each (the cell's transfer squared,"
        f" its dynamic stiffness doubled; `mstmm.repeated`), so every root of a cluster"
        f" costs about the same whatever N. {big['n']} cells of the paper's beam, each"
        f" carrying a resonator whose own frequency lies between the beam's 2nd and 3rd:"
        f" all {big['modes']} roots, crowding below that frequency, in"
        f" {fmt_time(big['seconds'])} (as {big['distinct']} values: the"
        f" {big['largest_multiplicity']} closest to it lie closer together than double"
        f" precision resolves and come as one value with the count's multiplicity;"
        f" {small['n']}: {fmt_time(small['seconds'])}, where"
        f" the same beam written out as {small['n']} attachments takes"
        f" {fmt_time(small['general_seconds'])} in the general search; log-log slope"
        f" {sl['spaced']:.2f}); the metamaterial beam of {m['n']} cells: its"
        f" {m['modes']} roots below the gap in {fmt_time(m['seconds'])} (log-log slope"
        f" {sl['metamaterial']:.2f}). Every root is certified by the count, and the mpmath"
        f" reference's count finds none missed up to {mm[0]['n']} cells. Reproduce with"
        " `python -m benchmarks.clusters`."
    )
    return "\n" + _para(text) + "\n"


def busy(figs: dict, cert: dict | None) -> str:
    from .busy import report

    g = _section(figs, "busy")
    result = {k: g[k] for k in ("solve", "plot")}
    text = (
        "A machine's first `mstmm solve` and `mstmm plot` (nothing compiled: an empty"
        " `MSTMM_CACHE`), idle and beside two CPU-bound processes at the same priority (a"
        " core each), median of interleaved runs. The compile helpers such a run starts are"
        " never waited on while they are starved, and a first run's small work runs as"
        " Python rather than compiling. Reproduce with `python -m benchmarks.busy`."
    )
    return "\n" + _para(text) + "\n\n" + report(result) + "\n"


def frames(figs: dict, cert: dict | None) -> str:
    g = _section(figs, "frames")
    rows = [*g["sizes"], g["distinct"]]
    big_rounds = g["sizes"][-1].get("rounds", 5)
    lines = [
        "| frame | members | lowest | warm | with shapes | first call in the process |",
        "|---|---:|---:|---:|---:|---:|",
    ]
    for r in rows:
        each = ", every member its own section" if r["distinct"] else ""
        lines.append(
            f"| {r['storeys']} storeys x {r['bays']} bays{each} | {r['members']} | {r['modes']}"
            f" | {fmt_time(r['warm_s'])} | {fmt_time(r['with_shapes_s'])}"
            f" | {fmt_time(r['cold_s'])} |"
        )
    big = g["sizes"][-1]
    fem = big.get("fem", [])
    text = (
        "Regular building frames (steel columns and floor beams, fixed feet, two roof TMDs"
        " tuned by Den Hartog's rule), the lowest natural frequencies certified by the count,"
        f" the median of {big_rounds} runs, with shapes and without them in turn; the first call in"
        " a process loads the compiled member functions from the user cache (a frame has no"
        " kernel of its own to derive)."
    )
    out = "\n" + _para(text) + "\n\n" + "\n".join(lines) + "\n"
    if fem:
        best = {}
        for r in fem:
            for key, s_key in (("error", "s"), ("richardson2", "richardson2_s"),
                               ("richardson3", "richardson3_s")):  # fmt: skip
                if key in r and r[key] <= 1e-8 and (not best or r[s_key] < best["s"]):
                    best = {"s": r[s_key], "error": r[key], "elements": r["elements"], "how": key}
        last = fem[-1]
        text = (
            f"The same {big['storeys']}-storey frame by the finite-element model a user would"
            " write instead (rod and Hermite beam elements with consistent masses, assembled"
            " sparse, shift-invert Lanczos for the lowest"
            f" {big['modes']}): {last['elements']} elements a member err {fmt_err(last['error'])}"
            f" in {fmt_time(last['s'])}"
        )
        if best:
            how = {"error": "on its own", "richardson2": "Richardson over two meshes",
                   "richardson3": "Richardson over three meshes"}[best["how"]]  # fmt: skip
            text += (
                f"; it first reaches 1e-8 ({fmt_err(best['error'])}) with {best['elements']}"
                f" elements a member, {how}, in {fmt_time(best['s'])}:"
                f" {best['s'] / big['warm_s']:.0f} times mstmm's warm time"
            )
        out += "\n" + _para(text + ".") + "\n"
    if g.get("accuracy"):
        acc = ", ".join(
            f"{a['frame']} {fmt_err(a['worst'])}" + ("" if a["multiplicities"] else " (WRONG)")
            for a in g["accuracy"]
        )
        text = (
            "Worst relative error of the lowest 12 (FV2: 16) against the 30-digit reference"
            f" model's roots, multiplicities all exact: {acc}."
        )
        out += "\n" + _para(text) + "\n"
    return out + "\nReproduce with `" + PRODUCERS["frames"] + "`.\n"


BLOCKS = {
    "example": example,
    "front-damped": _front("front-damped"),
    "front-frf": _front("front-frf"),
    "front-bands": _front("front-bands"),
    "front-sweep": _front("front-sweep"),
    "front-frame": _front("front-frame"),
    "first-solve": first_solve,
    "table1": table1,
    "certification": certification,
    "many-modes": many_modes,
    "components": components,
    "damping": damping,
    "accuracy": accuracy,
    "segments": segments,
    "periodic": periodic,
    "clusters": clusters,
    "busy": busy,
    "frames": frames,
}


# ------------------------------------------------------------------ rewrite


def pages() -> list[Path]:
    """Every page that may hold figure blocks: README.md and docs/*.md."""
    return [README, *sorted(DOCS.glob("*.md"))]


def read_pages(paths: list[Path] | None = None) -> dict[Path, str]:
    """``{page: its text}`` of :func:`pages` (or of ``paths``)."""
    return {p: p.read_text() for p in (pages() if paths is None else paths)}


def _name(page: Path) -> str:
    try:
        return page.resolve().relative_to(figures.ROOT).as_posix()
    except ValueError:
        return str(page)


def _relink(body: str, page: Path) -> str:
    """``body`` with every Markdown link to a repository path (``](docs/x.md)``) made
    relative to ``page``'s folder."""
    here = posixpath.dirname(_name(page)) or "."
    if here == ".":
        return body

    def link(m: re.Match) -> str:
        target = m.group(1)
        if "://" in target or target.startswith(("#", "/")):
            return m.group(0)
        return f"]({posixpath.relpath(target, here)})"

    return re.sub(r"\]\(([^)\s]+)\)", link, body)


def render_pages(texts: dict[Path, str], figs: dict, cert: dict | None) -> dict[Path, str]:
    """``texts`` (``{page: text}``) with every figure block rewritten; every block of
    :data:`BLOCKS` must occur exactly once over all the pages, and no other."""
    where: dict[str, list[str]] = {}
    for page, text in texts.items():
        for m in BLOCK.finditer(text):
            where.setdefault(m.group("name"), []).append(_name(page))
    unknown = sorted(set(where) - set(BLOCKS))
    if unknown:
        found = "; ".join(f"{n} in {', '.join(where[n])}" for n in unknown)
        raise ValueError(f"unknown figure block(s) {unknown} ({found})")
    missing = sorted(set(BLOCKS) - set(where))
    if missing:
        raise ValueError(
            f"figure block(s) {missing} missing from {', '.join(_name(p) for p in texts)}"
        )
    twice = sorted(n for n, at in where.items() if len(at) > 1)
    if twice:
        found = "; ".join(f"{n} in {', '.join(where[n])}" for n in twice)
        raise ValueError(f"figure block(s) {twice} occur more than once ({found})")

    def rewrite(page: Path, text: str) -> str:
        def body(m: re.Match) -> str:
            name = m.group("name")
            content = _relink(BLOCKS[name](figs, cert), page)
            return f"<!-- figures:{name} -->{content}<!-- /figures:{name} -->"

        return BLOCK.sub(body, text)

    return {page: rewrite(page, text) for page, text in texts.items()}


def render(text: str, figs: dict, cert: dict | None, page: Path = README) -> str:
    """One page's ``text`` that holds every block (:func:`render_pages` of that page)."""
    return render_pages({page: text}, figs, cert)[page]


def load_certification(path: Path = CERTIFICATION) -> dict | None:
    return json.loads(path.read_text()) if path.exists() else None


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m benchmarks.readme", description=__doc__)
    ap.add_argument(
        "--check", action="store_true", help="exit 1 if a page's figures are not current"
    )
    args = ap.parse_args(argv)
    texts = read_pages()
    try:
        new = render_pages(texts, figures.load(), load_certification())
    except (MissingFigures, ValueError) as exc:
        print(f"benchmarks.readme: error: {exc}", file=sys.stderr)
        return 2
    stale = [page for page in texts if new[page] != texts[page]]
    if args.check:
        for page in stale:
            print(f"{_name(page)}: figures are not current: run python -m benchmarks.readme")
        return 1 if stale else 0
    for page in stale:
        page.write_text(new[page])
        print(f"{_name(page)}: figures rewritten from docs/figures.json")
    if not stale:
        print("README.md, docs/*.md: figures already current")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

"""Clusters of roots (issue 23, item 3): many components whose own frequencies crowd.

Run: ``python -m benchmarks.clusters [--record] [--quick]`` (a few minutes; ``--quick``:
the small sizes only, nothing recorded).

* **in band**: ``benchmarks.scaling.random_scene(N, "in band")`` (the paper's cantilever,
  N random spring-masses, own frequencies log-uniform between its first and 20th natural
  frequency), N = 10,000 and 100,000: the lowest 20, warm, ``mstmm.solve(shapes=False)``
  and the kernel's ``Kernel.lowest`` (median of repeated runs); what the search did (the
  kernel's search run as Python around its compiled functions, each call counted): scan
  nodes, Brent's evaluations, counts; missed roots: the independent reference count
  (``tests/reference_model.py``, mpmath) below the midpoint of the 20th and 21st root
  minus 20 (N = 10,000; at 100,000 the reference takes minutes a count: the kernel's own
  count is reported instead, marked so);
* **identical, one point**: N identical spring-masses at x = 0.37 L, own frequency w0
  between the beam's 2nd and 3rd: every root up to the cluster's end (``--modes`` N + 4);
  the multiplicity at w0 (exactly N - 1) and the other roots against the beam with ONE
  spring-mass (N k, N m) at that point (the same, by ``tests/test_clusters.py``'s proof):
  missed = the roots that differ;
* **identical, evenly spaced**: the same N spring-masses at x = (i + 1/2) L / N, written
  as what they are, N cells of L / N with one at the middle (``repeat = N``: the count and
  characteristic function in O(log N), ``mstmm.repeated``): every root of the cluster
  (``--modes`` up to w0 (1 + 1e-6), plus 2), N = 1,000, 10,000 and 100,000; missed: the
  reference count in windows w0 (1 -+ d) against the roots found there (N = 1,000; at
  10,000 one window, the reference count costing about 10 s; at 100,000 none). The same
  N = 1,000 written out as N attachments goes through the general search, for comparison;
* **metamaterial**: ``examples/metamaterial.toml``'s cell repeated N = 10,000 and 100,000
  times: every root of the pass band below the gap (the count below 3141 rad/s); missed:
  the reference count there (N = 10,000).

The time of a whole cluster against N: log-log slope between the two N.
"""

from __future__ import annotations

import argparse
import math
import platform
import sys
import time
from pathlib import Path

import numpy as np

import mstmm
from mstmm import interpret, repeated
from mstmm.scene import scene_to_dict

from . import figures
from .cases import rm as ref
from .scaling import random_scene
from .workprecision import fmt_time, timed

BASE = mstmm.example_path("wu_chou_1998")
#: Own frequency of the identical spring-masses: beta = 7 on the paper's beam.
BETA0 = 7.0
#: The identical spring-masses carry half the beam's mass between them.
MASS_RATIO = 0.5
#: Windows w0 (1 -+ d) of the spaced cluster checked against the reference count.
WINDOWS = (1e-3, 1e-5, 1e-7)
TARGETS = {10_000: 0.050, 100_000: 0.500}


def spring_masses(atts: list[tuple[float, float, float]], name: str):
    """The paper's cantilever carrying spring-masses ``(x, k, m)``."""
    beam = mstmm.load_scene(BASE).beam
    b = {
        "length": beam.length,
        "EI": beam.EI,
        "mass_per_length": beam.mass_per_length,
        "left": "clamped",
        "right": "free",
    }
    rows = [{"type": "spring_mass", "x": x, "k": k, "m": m} for x, k, m in atts]
    return mstmm.scene_from_dict({"name": name, "beam": b, "attachments": rows})


def identical(n: int, where: str):
    """N identical spring-masses on the paper's cantilever: at one point (0.37 L) or at
    evenly spaced points; returns (scene, w0, k, m)."""
    beam = mstmm.load_scene(BASE).beam
    L, EI, mbar = beam.length, beam.EI, beam.mass_per_length
    w0 = math.sqrt(EI / mbar) / L**2 * BETA0**2
    m = MASS_RATIO * mbar * L / n
    k = m * w0**2
    name = f"identical_{n}_{where.replace(' ', '_')}"
    if where == "cells":  # the spaced ones as N cells, each with one at its middle
        cell = {"length": L / n, "EI": EI, "mass_per_length": mbar}
        cell |= {"left": "clamped", "right": "free"}
        sm = {"type": "spring_mass", "x": 0.5 * L / n, "k": k, "m": m}
        d = {"name": name, "repeat": n, "beam": cell, "attachments": [sm]}
        return mstmm.scene_from_dict(d), w0, k, m
    xs = [0.37 * L] * n if where == "one point" else [(i + 0.5) * L / n for i in range(n)]
    return spring_masses([(x, k, m) for x in xs], name), w0, k, m


def counted(scene, modes: int) -> dict:
    """The kernel's search run as Python around its compiled characteristic function and
    count, each call counted by the search function that made it."""
    kernel = mstmm.kernel_for(scene)
    p = mstmm.parameter_vector(scene)
    mod = kernel.module
    ns = interpret.python_copy(mod)
    calls: dict[str, int] = {}

    def tally(kind: str):
        caller = sys._getframe(2).f_code.co_name
        key = f"{kind} ({'Brent' if caller in ('divided', 'scaled') else caller})"
        calls[key] = calls.get(key, 0) + 1

    def delta(w, p):
        tally("delta")
        return mod.delta_stable(w, p)

    def count(w, p):
        tally("count")
        return mod.count_below(w, p)

    out = np.zeros(modes)
    flags = np.zeros(modes, dtype=np.int64)
    state = np.zeros(mod.STATE_SIZE)
    ns["lowest"](
        delta, count, mod.oscillator_frequencies, mod.rigid_body_modes, p, modes, out, flags,
        state, True, 0.0,
    )  # fmt: skip
    _, t_delta, _ = timed(lambda: mod.delta_stable(float(out[-1]), p), 0.2, 3)
    _, t_count, _ = timed(lambda: mod.count_below(float(out[-1]), p), 0.2, 3)
    return {"calls": calls, "delta_seconds": t_delta, "count_seconds": t_count}


def in_band(n: int, reference: bool) -> dict:
    scene = random_scene(n, "in band")
    kernel = mstmm.kernel_for(scene)
    p = mstmm.parameter_vector(scene)
    w21 = mstmm.solve(scene, modes=21, shapes=False, kernel=kernel).omega[20]
    sol, t_solve, runs = timed(
        lambda: mstmm.solve(scene, modes=20, shapes=False, kernel=kernel), 2.0, 3
    )
    _, t_lowest, _ = timed(lambda: kernel.lowest(p, 20), 2.0, 3)
    mid = 0.5 * (sol.omega[-1] + w21)
    if reference:
        below, how = ref.count_below(scene, mid, dps=30), "reference (mpmath)"
    else:
        below, how = int(kernel.count_below(np.array([mid]), p)[0]), "the kernel's count"
    return {
        "n": n,
        "solve": t_solve,
        "lowest": t_lowest,
        "runs": runs,
        "count_checked": bool(sol.count_checked),
        "converged": bool(sol.converged.all()),
        "missed": int(below) - 20,
        "missed_by": how,
        "profile": counted(scene, 20),
    }


def one_point(n: int) -> dict:
    scene, w0, k, m = identical(n, "one point")
    single = spring_masses([(0.37 * scene.beam.length, n * k, n * m)], "single")
    modes = n + 4
    kernel = mstmm.kernel_for(scene)
    sol, t, runs = timed(
        lambda: mstmm.solve(scene, modes=modes, shapes=False, kernel=kernel), 2.0, 3
    )
    own = float(kernel.oscillator_frequencies(mstmm.parameter_vector(scene))[0])
    at = sol.omega == own
    rest = sol.omega[~at]
    other = mstmm.solve(single, modes=len(rest), shapes=False).omega
    same = np.abs(rest - other) <= 1e-12 * other
    return {
        "n": n,
        "modes": modes,
        "seconds": t,
        "runs": runs,
        "multiplicity": int(np.count_nonzero(at)),
        "at_own_frequency": bool(at.any()),
        "others_error": float(np.max(np.abs(rest - other) / other)),
        "missed": int(np.count_nonzero(~same)) + abs(int(np.count_nonzero(at)) - (n - 1)),
        "count_checked": bool(sol.count_checked),
    }


def spaced(n: int, windows, general: bool = False) -> dict:
    scene, w0, _, _ = identical(n, "cells")
    kernel = mstmm.kernel_for(scene)
    chain = repeated.chain_of(scene)
    modes = int(chain.count_below(np.array([w0 * (1.0 + 1e-6)]))[0]) + 2
    sol, t, runs = timed(
        lambda: mstmm.solve(scene, modes=modes, shapes=False, kernel=kernel), 2.0, 3
    )
    missed = 0
    checked = []
    for d in windows:
        lo, hi = w0 * (1.0 - d), w0 * (1.0 + d)
        got = int(np.count_nonzero((sol.omega > lo) & (sol.omega < hi)))
        want = ref.count_below(scene, hi, dps=30) - ref.count_below(scene, lo, dps=30)
        missed += abs(want - got)
        checked.append([d, got, want])
    distinct, counts = np.unique(sol.omega, return_counts=True)
    out = {
        "n": n,
        "modes": modes,
        "seconds": t,
        "runs": runs,
        "path": sol.kernel_mode,
        "distinct": int(distinct.size),
        "largest_multiplicity": int(counts.max()),
        "windows": checked,
        "missed": missed,
        "count_checked": bool(sol.count_checked),
    }
    if general:  # the same structure written out: the general search
        explicit, _, _, _ = identical(n, "spaced")
        k2 = mstmm.kernel_for(explicit)
        other, t2, _ = timed(
            lambda: mstmm.solve(explicit, modes=modes, shapes=False, kernel=k2), 2.0, 3
        )
        out["general_seconds"] = t2
        out["general_max_difference"] = float(np.max(np.abs(other.omega - sol.omega) / sol.omega))
    return out


def metamaterial(n: int, reference: bool) -> dict:
    scene = mstmm.load_scene(Path(__file__).resolve().parents[1] / "examples" / "metamaterial.toml")
    d = scene_to_dict(scene.cell) | {"repeat": n, "name": f"metamaterial_{n}"}
    scene = mstmm.scene_from_dict(d)
    kernel = mstmm.kernel_for(scene)
    below = 3141.0  # in the pass band just below the gap (3141.41 to 3847.63 rad/s)
    modes = int(repeated.chain_of(scene).count_below(np.array([below]))[0])
    sol, t, runs = timed(
        lambda: mstmm.solve(scene, modes=modes, shapes=False, kernel=kernel), 2.0, 3
    )
    missed = ref.count_below(scene, below, dps=30) - modes if reference else 0
    return {
        "n": n,
        "modes": modes,
        "seconds": t,
        "runs": runs,
        "path": sol.kernel_mode,
        "missed": int(missed),
        "missed_by": "reference (mpmath)" if reference else "the count",
        "count_checked": bool(sol.count_checked),
    }


def slope(rows: list[dict], key: str = "seconds") -> float:
    (a, b) = rows[0], rows[-1]
    return math.log(b[key] / a[key]) / math.log(b["n"] / a["n"])


def measure(quick: bool) -> dict:
    interpret.set_budget(0.0)  # compiled throughout
    warm, _, _, _ = identical(50, "spaced")
    mstmm.solve(warm, modes=300, shapes=False)  # compiles every entry point the runs use
    warm, _, _, _ = identical(50, "cells")
    mstmm.solve(warm, modes=60, shapes=False)  # and those of repeated cells
    sizes = (1_000, 3_000) if quick else (10_000, 100_000)
    band = [in_band(n, reference=not quick and n <= 10_000) for n in sizes]
    ns = (300, 1_000) if quick else (1_000, 10_000)
    one = [one_point(n) for n in ns]
    cells = (1_000, 3_000) if quick else (1_000, 10_000, 100_000)
    spread = [
        spaced(n, WINDOWS if n <= 1_000 else WINDOWS[:1] if n <= 10_000 else (), n == cells[0])
        for n in cells
    ]
    meta = [metamaterial(n, not quick and n <= 10_000) for n in cells[-2:]]
    return {
        "in_band": band,
        "one_point": one,
        "spaced": spread,
        "metamaterial": meta,
        "slopes": {
            "one_point": slope(one),
            "spaced": slope(spread),
            "metamaterial": slope(meta),
        },
    }


def report(fig: dict) -> None:
    print(
        f"clusters of roots; {platform.machine()}, Python {platform.python_version()},"
        " warm, compiled, median of repeated runs"
    )
    print("\nin band, lowest 20:")
    for r in fig["in_band"]:
        target = TARGETS.get(r["n"])
        verdict = (
            f" (target {fmt_time(target)}: {'met' if r['solve'] <= target else 'NOT met'})"
            if target
            else ""
        )
        c = r["profile"]["calls"]
        print(
            f"  N = {r['n']:>7}: solve {fmt_time(r['solve'])}, Kernel.lowest"
            f" {fmt_time(r['lowest'])}{verdict}; certified {r['count_checked']}; missed"
            f" {r['missed']} ({r['missed_by']})"
        )
        print(
            "             "
            + ", ".join(f"{k}: {v}" for k, v in sorted(c.items()))
            + f"; one delta {fmt_time(r['profile']['delta_seconds'])},"
            f" one count {fmt_time(r['profile']['count_seconds'])}"
        )
    print("\nidentical spring-masses at one point, every root up to the cluster's end:")
    for r in fig["one_point"]:
        print(
            f"  N = {r['n']:>6}: {r['modes']} modes in {fmt_time(r['seconds'])};"
            f" multiplicity {r['multiplicity']} at their own frequency; the others against"
            f" one spring-mass (N k, N m): {r['others_error']:.1e}; missed {r['missed']};"
            f" certified {r['count_checked']}"
        )
    print(f"  log-log slope: {fig['slopes']['one_point']:.2f}")
    print(
        "\nidentical spring-masses at evenly spaced points (N cells, repeat = N), every root"
        " of the cluster:"
    )
    for r in fig["spaced"]:
        windows = "; ".join(f"{d:.0e}: {g} (reference {w})" for d, g, w in r["windows"])
        print(
            f"  N = {r['n']:>6}: {r['modes']} modes in {fmt_time(r['seconds'])} ({r['path']});"
            f" {r['distinct']} distinct values (largest multiplicity"
            f" {r['largest_multiplicity']}); roots within w0 (1 -+ d): {windows or 'not checked'};"
            f" missed {r['missed']}; certified {r['count_checked']}"
        )
        if "general_seconds" in r:
            print(
                f"             the same written out as {r['n']} attachments, general search:"
                f" {fmt_time(r['general_seconds'])}; largest difference"
                f" {r['general_max_difference']:.1e}"
            )
    print(f"  log-log slope: {fig['slopes']['spaced']:.2f}")
    print("\nmetamaterial (examples/metamaterial.toml's cell), every root below the gap:")
    for r in fig["metamaterial"]:
        print(
            f"  N = {r['n']:>6}: {r['modes']} modes in {fmt_time(r['seconds'])} ({r['path']});"
            f" missed {r['missed']} ({r['missed_by']}); certified {r['count_checked']}"
        )
    print(f"  log-log slope: {fig['slopes']['metamaterial']:.2f}")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m benchmarks.clusters", description=__doc__)
    ap.add_argument("--record", action="store_true", help="write docs/figures.json")
    ap.add_argument("--quick", action="store_true", help="small sizes only, nothing recorded")
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    fig = measure(args.quick)
    report(fig)
    print(f"\n({time.perf_counter() - t0:.0f} s)")
    kinds = ("in_band", "one_point", "spaced", "metamaterial")
    ok = all(r["missed"] == 0 and r["count_checked"] for k in kinds for r in fig[k])
    if args.record and not args.quick:
        path = figures.record("clusters", fig, command="python -m benchmarks.clusters --record")
        print(f"recorded in {path}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())

"""How the cost of ``--modes N`` grows with N: the paper's example, up to 100,000 modes.

Run: ``python -m benchmarks.many_modes`` (N = 1e3, 1e4, 1e5; ``--quick``: 300,
1000, 3000). Warm (kernel compiled first on a small case), one process, the
stable formulation, ``mstmm.solve(scene, modes=N, shapes=False)``, median of
repeated runs within about 3 s (one run when it takes longer). Prints the
time and cost per mode of each N and the log-log slope between them (1 is
linear), and checks each run: N ascending values, all converged, the count
check held, and at sample modes the reference model's own Wittrick-Williams
count (``tests/reference_model.py``, mpmath, independent of mstmm) jumps across
the value reported: ``N_ref(w (1 - 1e-9)) <= i`` and ``N_ref(w (1 + 1e-9)) >= i + 1``
for mode ``i + 1``. The target of issue 12: 100,000 modes in at most 60 s.
"""

from __future__ import annotations

import argparse
import math
import platform
import sys

import numpy as np

import mstmm
from mstmm import interpret

from . import figures
from .cases import rm as ref
from .workprecision import timed

FULL = (1_000, 10_000, 100_000)
QUICK = (300, 1_000, 3_000)
#: Relative half-width of the reference count's window around a root.
WINDOW = 1e-9
TARGET_SECONDS = 60.0


def samples(n: int) -> list[int]:
    """Mode indices (from 0) checked against the reference: the first, spread, the last."""
    return sorted({0, n // 10, n // 2, (9 * n) // 10, n - 1})


def check(scene, omega: np.ndarray, n: int) -> list[str]:
    """Failures of one run (empty when every check holds)."""
    bad = []
    if len(omega) != n:
        bad.append(f"{len(omega)} values for {n} modes")
    if np.any(np.diff(omega) < 0.0):
        bad.append("not ascending")
    for i in samples(len(omega)):
        w = float(omega[i])
        below = ref.count_below(scene, w * (1.0 - WINDOW), dps=30)
        above = ref.count_below(scene, w * (1.0 + WINDOW), dps=30)
        if not (below <= i and above >= i + 1):
            bad.append(f"mode {i + 1}: w = {w!r}, reference count {below} .. {above}")
    return bad


def run(ns: tuple[int, ...], record: bool = False) -> bool:
    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    kernel = mstmm.kernel_for(scene)
    interpret.set_budget(0.0)  # compiled throughout
    mstmm.solve(scene, modes=400, shapes=False, kernel=kernel)  # loads every entry point
    print(
        f"--modes N of the paper's example (wu_chou_1998), stable formulation, warm; "
        f"{platform.machine()}, Python {platform.python_version()}"
    )
    print(f"{'N':>8}  {'time [s]':>10}  {'per mode [us]':>13}  {'slope':>6}  check")
    times, ok = [], True
    for n in ns:
        sol, dt, _ = timed(
            lambda n=n: mstmm.solve(scene, modes=n, shapes=False, kernel=kernel), 3.0
        )
        bad = check(scene, sol.omega, n)
        if not sol.count_checked:
            bad.append("count check failed")
        if not sol.converged.all():
            bad.append(f"{int((~sol.converged).sum())} not converged")
        slope = (
            f"{math.log(dt / times[-1][1]) / math.log(n / times[-1][0]):6.2f}" if times else " " * 6
        )
        times.append((n, dt))
        verdict = "ok" if not bad else "FAILED: " + "; ".join(bad)
        ok &= not bad
        print(f"{n:>8}  {dt:>10.3f}  {dt / n * 1e6:>13.1f}  {slope}  {verdict}")
    ln = np.log(np.array(times))
    fit = float(np.polyfit(ln[:, 0], ln[:, 1], 1)[0])
    print(f"log-log slope over all N (least squares): {fit:.2f}")
    print(f"sample modes checked against the reference count: {samples(ns[-1])[:]} (+1)")
    n_last, t_last = times[-1]
    if n_last >= 100_000:
        met = "met" if t_last <= TARGET_SECONDS else "NOT met"
        print(f"target: 100,000 modes in <= {TARGET_SECONDS:.0f} s: {met} ({t_last:.1f} s)")
    if record and ok:
        figures.record(
            "many_modes",
            {"times": [[n, t] for n, t in times], "slope": fit},
            command="python -m benchmarks.many_modes",
        )
    return ok


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m benchmarks.many_modes", description=__doc__)
    ap.add_argument("--quick", action="store_true", help=f"N = {QUICK} instead of {FULL}")
    args = ap.parse_args(argv)
    return 0 if run(QUICK if args.quick else FULL, record=not args.quick) else 1


if __name__ == "__main__":
    sys.exit(main())

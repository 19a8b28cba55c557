"""Paper Table 1 against the exact reference, with this package's line.

Run: ``python -m benchmarks.table1``.

Prints a Markdown table: the frequencies the paper quotes (FEM, ANCM of Wu &
Chou 1998, the paper's MSTMM), each with its largest relative error against
``tests/data/reference.json``, and mstmm's own line with its measured time
(median of repeated warm solves of the lowest five modes, kernel compiled).
"""

from __future__ import annotations

import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import mstmm

REFERENCE = Path(__file__).resolve().parent.parent / "tests" / "data" / "reference.json"

#: Paper Table 1, quoted (rad/s) with the CPU times the paper reports (s).
QUOTED = {
    "FEM [5] (quoted)": ([102.79, 188.73, 248.66, 349.11, 1428.03], "19.18 s"),
    "ANCM [5] (quoted)": ([102.71, 188.76, 248.51, 349.14, 1427.97], "5.05 s"),
    "MSTMM, paper (quoted)": ([102.79, 188.73, 248.64, 349.11, 1427.96], "2.25 s"),
}


def warm_time(scene, formulation: str, repeats: int = 200) -> float:
    kernel = mstmm.kernel_for(scene)
    mstmm.solve(scene, modes=5, shapes=False, formulation=formulation, kernel=kernel)
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        mstmm.solve(scene, modes=5, shapes=False, formulation=formulation, kernel=kernel)
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def cold_time() -> float:
    """Wall time of a fresh ``mstmm solve --modes 5`` process with the kernel cached."""
    cmd = [sys.executable, "-m", "mstmm", "solve", "--modes", "5", "--format", "json"]
    subprocess.run(cmd, check=True, capture_output=True)  # warm numba's on-disk cache
    times = []
    for _ in range(5):
        t = time.perf_counter()
        subprocess.run(cmd, check=True, capture_output=True)
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def main() -> None:
    exact = np.array([float(w) for w in json.loads(REFERENCE.read_text())["wu_chou_1998"]["omega"]])
    exact = exact[:5]
    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    rows = []
    for label, (omega, cpu) in QUOTED.items():
        err = np.max(np.abs(np.array(omega) - exact) / exact)
        rows.append((label, [f"{w:.2f}" for w in omega], f"{err:.1e}", cpu))
    for formulation in ("stable", "paper"):
        sol = mstmm.solve(scene, modes=5, shapes=False, formulation=formulation)
        err = np.max(np.abs(sol.omega - exact) / exact)
        t = warm_time(scene, formulation)
        rows.append(
            (
                f"mstmm, {formulation} (measured)",
                [f"{w:.10g}" for w in sol.omega],
                f"{err:.1e}",
                f"{t * 1e3:.2f} ms warm",
            )
        )
    rows.append(("exact (reference.json)", [f"{w:.10g}" for w in exact], "0", ""))
    print("| method | w1 | w2 | w3 | w4 | w5 | max rel. error | time |")
    print("|---|---|---|---|---|---|---|---|")
    for label, omega, err, t in rows:
        print(f"| {label} | " + " | ".join(omega) + f" | {err} | {t} |")
    print(f"\n`mstmm solve --modes 5` in a fresh process, kernel cached: {cold_time():.2f} s wall.")


if __name__ == "__main__":
    main()

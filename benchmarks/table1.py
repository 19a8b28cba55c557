"""Paper Table 1 against the exact reference, with this package's line.

Run: ``python -m benchmarks.table1``.

Prints a Markdown table: the frequencies the paper quotes (FEM, ANCM of Wu &
Chou 1998, the paper's MSTMM), each with its largest relative error against
``tests/data/reference.json``, and mstmm's own line with its measured time
(median of repeated warm solves of the lowest five modes, kernel compiled).
The figures go to ``docs/figures.json`` (key ``table1``), whence the README's
table is written (``python -m benchmarks.readme``).
"""

from __future__ import annotations

import json
import statistics
import time
from pathlib import Path

import numpy as np

import mstmm

from . import figures

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


def measure(repeats: int = 200) -> dict:
    """Table 1's rows: label, the five frequencies, largest relative error, time (s or quoted)."""
    exact = np.array([float(w) for w in json.loads(REFERENCE.read_text())["wu_chou_1998"]["omega"]])
    exact = exact[:5]
    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    rows = []
    for label, (omega, cpu) in QUOTED.items():
        err = float(np.max(np.abs(np.array(omega) - exact) / exact))
        rows.append({"label": label, "omega": omega, "error": err, "quoted_time": cpu})
    for formulation in ("stable", "paper"):
        sol = mstmm.solve(scene, modes=5, shapes=False, formulation=formulation)
        err = float(np.max(np.abs(sol.omega - exact) / exact))
        rows.append(
            {
                "label": f"mstmm, {formulation} (measured)",
                "omega": [float(w) for w in sol.omega],
                "error": err,
                "seconds": warm_time(scene, formulation, repeats),
            }
        )
    rows.append({"label": "exact (reference.json)", "omega": exact.tolist(), "error": 0.0})
    return {"rows": rows, "repeats": repeats}


def markdown(fig: dict) -> str:
    """The Markdown table of :func:`measure`'s figures."""
    from .workprecision import fmt_time  # (workprecision imports this module)

    out = [
        "| method | w1 | w2 | w3 | w4 | w5 | max rel. error | time |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for row in fig["rows"]:
        quoted = "quoted_time" in row
        omega = [f"{w:.2f}" if quoted else f"{w:.10g}" for w in row["omega"]]
        err = f"{row['error']:.1e}" if row["error"] else "0"
        if quoted:
            t = row["quoted_time"]
        elif "seconds" in row:
            t = f"{fmt_time(row['seconds'])} warm"
        else:
            t = ""
        out.append(f"| {row['label']} | " + " | ".join(omega) + f" | {err} | {t} |")
    return "\n".join(out) + "\n"


def main() -> None:
    fig = measure()
    print(markdown(fig))
    print(f"recorded in {figures.record('table1', fig, command='python -m benchmarks.table1')}")


if __name__ == "__main__":
    main()

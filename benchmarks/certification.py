"""What certification costs: the kernel's search of the lowest N with and without the count.

Run: ``python -m benchmarks.certification`` (writes ``docs/certification.json``).

Both sides are the same compiled kernel call, ``kernel.lowest(p, N, certify)``,
on the paper's example: a scan of the stable characteristic function on 8 nodes
per pi of lambda L plus a node at each oscillator frequency, and Brent on each
sign change. *unchecked* (``certify=False``) stops there: it returns the
sign-change roots as they are, and misses a double root or two roots in one
cell. *certified* (the default, what ``mstmm solve`` runs) also counts the roots
below the top of the scan with the Wittrick-Williams count, once per block when
the sign changes account for every root, and bisects on the count where they do
not. Warm (kernel compiled), one process, the two run in turn round after round
(median of each). The ratio is the price of the proof; whether the unchecked
roots are right is reported too.
"""

from __future__ import annotations

import json
import platform
import statistics
import time
from pathlib import Path

import numpy as np

import mstmm
from mstmm import interpret

from .workprecision import fmt_time

#: Numbers of lowest modes timed.
MODES = (10, 1000)
OUT = Path(__file__).resolve().parent.parent / "docs" / "certification.json"


def interleaved(fns, budget: float = 2.0, min_rounds: int = 5) -> tuple[list[float], int]:
    """Median seconds of each of ``fns``, run in turn round after round (so that the
    load of a shared machine falls on all alike), and the number of rounds."""
    times: list[list[float]] = [[] for _ in fns]
    spent = 0.0
    while len(times[0]) < min_rounds or spent < budget:
        for fn, ts in zip(fns, times):
            t = time.perf_counter()
            fn()
            ts.append(time.perf_counter() - t)
            spent += ts[-1]
    return [statistics.median(ts) for ts in times], len(times[0])


def measure(kernel, p: np.ndarray, modes: int) -> dict:
    """Times (s) of the certified and unchecked search of the lowest ``modes``."""
    found = kernel.lowest(p, modes, True)
    cert, plain = found.omega, kernel.lowest(p, modes, False).omega
    (t_cert, t_plain), rounds = interleaved(
        [lambda: kernel.lowest(p, modes, True), lambda: kernel.lowest(p, modes, False)]
    )
    return {
        "modes": modes,
        "certified_s": t_cert,
        "unchecked_s": t_plain,
        "ratio": t_cert / t_plain,
        "rounds": rounds,
        "certified_ok": bool(found.certified),
        "unchecked_equals_certified": bool(np.array_equal(cert, plain)),
        "unchecked_max_rel_difference": float(np.max(np.abs(plain - cert) / cert)),
    }


def main() -> None:
    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    kernel = mstmm.kernel_for(scene)
    p = mstmm.parameter_vector(scene)
    interpret.set_budget(0.0)  # compiled
    kernel.lowest(p, 10, True), kernel.lowest(p, 10, False)
    rows = [measure(kernel, p, n) for n in MODES]
    print("kernel.lowest on the paper's example, warm, median of interleaved runs")
    for r in rows:
        diff = r["unchecked_max_rel_difference"]
        same = (
            "identical roots"
            if r["unchecked_equals_certified"]
            else f"unchecked roots WRONG: max rel. difference {diff:.1e}"
        )
        print(
            f"  lowest {r['modes']:>5}: certified {fmt_time(r['certified_s'])},"
            f" unchecked {fmt_time(r['unchecked_s'])}, ratio {r['ratio']:.2f} ({same})"
        )
    record = {
        "benchmark": "python -m benchmarks.certification",
        "scene": scene.name,
        "machine": f"{platform.machine()}, Python {platform.python_version()}",
        "rows": rows,
    }
    OUT.write_text(json.dumps(record, indent=2) + "\n")
    print(f"written: {OUT.relative_to(OUT.parent.parent)}")


if __name__ == "__main__":
    main()

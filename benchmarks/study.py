"""Parameter study: 1e4 parameter sets of the paper's example on one core and on all.

``mstmm.sweep(scene, {"attachments[2].k": k}, modes=5)`` with the stiffness of
the third spring-mass log-spaced over 1e3 .. 1e9 N/m (the veering study of the
README: its oscillator frequency crosses the beam's first modes), 1e4 points,
warm (kernel compiled by a small sweep first). Timed with numba's thread pool
limited to one thread, then with every core (``numba.set_num_threads``); the
median of a few runs each. Accuracy: a handful of the points against the
independent mpmath reference (``tests/reference_model.py``).
"""

from __future__ import annotations

import statistics
import sys
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

import mstmm

ROOT = Path(__file__).resolve().parent.parent
POINTS = 10_000
MODES = 5
PATH = "attachments[2].k"
#: Points checked against the mpmath reference (indices into the study).
CHECKED = (0, 2_500, 5_000, 7_500, POINTS - 1)


@dataclass
class Results:
    points: int = POINTS
    modes: int = MODES
    threads: dict[str, float] = field(default_factory=dict)  # "1", "all (n)": seconds
    cores: int = 1
    uncertified: int = 0
    max_error: float = float("nan")
    checked: int = 0

    def to_json(self) -> dict:
        return asdict(self)


def _stiffnesses(points: int) -> np.ndarray:
    return np.logspace(3.0, 9.0, points)


def run(quick: bool = False, log=print) -> Results:
    import numba

    points = 500 if quick else POINTS
    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    kernel = mstmm.kernel_for(scene)
    k = _stiffnesses(points)
    mstmm.sweep(scene, {PATH: k[:4]}, modes=MODES, kernel=kernel)  # compile
    res = Results(points=points, cores=numba.config.NUMBA_NUM_THREADS)
    omega = None
    for label, n in (("1 thread", 1), (f"all {res.cores} threads", res.cores)):
        numba.set_num_threads(n)
        times = []
        for _ in range(3):
            t0 = time.perf_counter()
            omega = mstmm.sweep(scene, {PATH: k}, modes=MODES, kernel=kernel)
            times.append(time.perf_counter() - t0)
        res.threads[label] = statistics.median(times)
        log(f"  sweep of {points} points, {label}: {res.threads[label]:.3f} s")
    numba.set_num_threads(res.cores)
    res.uncertified = int(np.isnan(omega).any(axis=1).sum())
    sys.path.insert(0, str(ROOT / "tests"))
    import reference_model as ref

    errors = []
    for i in CHECKED if not quick else (0, points - 1):
        point = mstmm.scene_from_dict(_with_k(scene, float(k[i])))
        exact = np.array([float(w) for w in ref.frequencies(point, MODES, dps=30)])
        errors.append(float(np.max(np.abs(omega[i] - exact) / exact)))
    res.max_error = max(errors)
    res.checked = len(errors)
    return res


def _with_k(scene, k: float) -> dict:
    """The scene as a dict, the third attachment (in x order) with stiffness ``k``."""
    b = scene.beam
    atts = sorted(scene.attachments, key=lambda a: a.x)
    rows = [{"type": "spring_mass", "x": a.x, "k": a.k, "m": a.m} for a in atts]
    rows[2]["k"] = k
    beam = {
        "length": b.length,
        "EI": b.EI,
        "mass_per_length": b.mass_per_length,
        "left": b.left,
        "right": b.right,
    }
    return {"name": scene.name, "beam": beam, "attachments": rows}


def speedup(res: Results) -> float:
    one, every = (res.threads[k] for k in res.threads)
    return one / every


def markdown(res: Results) -> str:
    from .workprecision import fmt_time

    out = ["| threads | wall time | per point |", "|---|---|---|"]
    for label, t in res.threads.items():
        out.append(f"| {label} | {fmt_time(t)} | {fmt_time(t / res.points)} |")
    out.append(
        f"\nSpeed-up on all cores: {speedup(res):.2f}x. Points the count could not certify "
        f"(NaN): {res.uncertified}. Largest relative error of the {res.checked} points "
        f"checked against the mpmath reference: {res.max_error:.1e}.\n"
    )
    return "\n".join(out)


if __name__ == "__main__":
    r = run(quick="--quick" in sys.argv)
    print(markdown(r))

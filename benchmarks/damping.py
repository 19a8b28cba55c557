"""Damping and frequency response (issue 14): ``python -m benchmarks.damping [--record]``.

* ``roots``: the paper example with a dashpot beside each spring (c = 2 zeta sqrt(k m),
  zeta = 0.05) and a loss factor of 0.01 on the beam, its lowest 10 complex natural
  frequencies: ``mstmm.solve`` warm (median of repeats) and its largest relative error
  against the independent mpmath reference (``tests/reference_model.py``:
  ``damped_frequencies``), against the damped finite-element model (``tests/reference_fem.py``:
  eigenvalues of the first-order form by ``scipy.linalg.eig``, then Richardson
  extrapolation from a mesh and its bisection) on meshes of 8 to 256 elements: the time
  each mesh takes and its error. "At equal accuracy" compares mstmm with the cheapest FE
  run that reaches 1e-10, or with the FE's best when none does.
* ``frf``: the paper example's tip receptance (force and displacement at x = L) at 10,000
  frequencies from 1 to 30,000 rad/s (its lowest 10 modes), warm, on all cores and on one
  (numba's thread count), and its agreement with the reference model's direct solve at
  20 of the points.

``--record`` stores the figures under ``damping`` in docs/figures.json.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import numpy as np

import mstmm
from mstmm.response import frf

from . import figures

ROOT = Path(__file__).resolve().parent.parent
if str(ROOT / "tests") not in sys.path:
    sys.path.insert(0, str(ROOT / "tests"))

import reference_fem as fem  # noqa: E402
import reference_model as rm  # noqa: E402

ZETA = 0.05
ETA = 0.01
MODES = 10


def damped_paper_example() -> dict:
    """The paper example with a dashpot beside each spring and a beam loss factor."""
    scene = mstmm.scene.scene_to_dict(mstmm.load_scene(mstmm.example_path("wu_chou_1998")))
    for a in scene["attachments"]:
        a["c"] = 2.0 * ZETA * float(np.sqrt(a["k"] * a["m"]))
    scene["beam"]["loss_factor"] = ETA
    scene["name"] = "wu_chou_1998_damped"
    return scene


def _median_time(fn, repeats: int) -> float:
    fn()
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def _rel(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.abs(a - b) / np.where(b == 0, 1.0, np.abs(b))))


def roots(repeats: int, meshes: tuple[int, ...]) -> dict:
    sc = damped_paper_example()
    scene = mstmm.scene_from_dict(sc)
    exact = np.array([complex(w) for w in rm.damped_frequencies(sc, MODES, dps=25)])
    sol = mstmm.solve(scene, modes=MODES, shapes=False)
    t_mstmm = _median_time(lambda: mstmm.solve(scene, modes=MODES, shapes=False), repeats)
    t_shapes = _median_time(lambda: mstmm.solve(scene, modes=MODES), max(3, repeats // 5))
    fe = []
    for n in meshes:
        t0 = time.perf_counter()
        try:
            w = fem.damped_richardson(sc, MODES, n)
            err = _rel(w, exact)
        except (ValueError, FloatingPointError) as exc:
            err, w = float("inf"), str(exc)
        fe.append({"elements": n, "seconds": time.perf_counter() - t0, "error": err})
    reached = [r for r in fe if r["error"] <= 1e-10]
    if reached:
        best = min(reached, key=lambda r: r["seconds"])
    else:
        best = min(fe, key=lambda r: r["error"])
    return {
        "scene": sc["name"],
        "modes": MODES,
        "mstmm_seconds": t_mstmm,
        "mstmm_shapes_seconds": t_shapes,
        "mstmm_error": _rel(sol.omega, exact),
        "count_checked": bool(sol.count_checked),
        "fe": fe,
        "fe_equal_accuracy": best,
        "fe_reaches_1e-10": bool(reached),
        "ratio": best["seconds"] / t_mstmm,
    }


def frequency_response(points: int, repeats: int) -> dict:
    import numba

    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    w = np.linspace(1.0, 30000.0, points)
    args = ("force:x=1.0", "displacement:x=1.0")
    kernel = mstmm.kernel_for(scene)
    H = frf(scene, *args, w, kernel=kernel)
    threads = numba.get_num_threads()
    t_all = _median_time(lambda: frf(scene, *args, w, kernel=kernel), repeats)
    numba.set_num_threads(1)
    try:
        t_one = _median_time(lambda: frf(scene, *args, w, kernel=kernel), repeats)
    finally:
        numba.set_num_threads(threads)
    sc = mstmm.scene.scene_to_dict(scene)
    pick = np.linspace(0, points - 1, 20).astype(int)
    tip = (("force", "x", 1.0), ("displacement", "x", 1.0))
    exact = np.array([complex(h) for h in rm.frf(sc, *tip, list(w[pick]), dps=30)])
    return {
        "points": points,
        "band": [float(w[0]), float(w[-1])],
        "seconds_all_cores": t_all,
        "seconds_one_core": t_one,
        "threads": threads,
        "error_at_20_points": _rel(H[pick], exact),
    }


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--record", action="store_true", help="store in docs/figures.json")
    ap.add_argument("--quick", action="store_true", help="fewer meshes and repeats")
    args = ap.parse_args(argv)
    meshes = (8, 16, 32) if args.quick else (8, 16, 32, 64, 128, 256)
    repeats = 3 if args.quick else 30
    out = {"roots": roots(repeats, meshes), "frf": frequency_response(10_000, repeats)}
    out["quick"] = bool(args.quick)
    r, f = out["roots"], out["frf"]
    print(
        f"damped paper example, lowest {r['modes']}: mstmm {r['mstmm_seconds'] * 1e3:.2f} ms"
        f" (error {r['mstmm_error']:.1e}, count checked {r['count_checked']}; with mode shapes"
        f" {r['mstmm_shapes_seconds'] * 1e3:.2f} ms)"
    )
    for row in r["fe"]:
        print(
            f"  FE + Richardson, {row['elements']:>4} elements: {row['seconds'] * 1e3:9.2f} ms,"
            f" error {row['error']:.1e}"
        )
    best = r["fe_equal_accuracy"]
    reach = "reaches" if r["fe_reaches_1e-10"] else "best, short of"
    print(
        f"  at equal accuracy: FE {best['elements']} elements {best['seconds'] * 1e3:.2f} ms"
        f" ({reach} 1e-10), {r['ratio']:.0f}x mstmm"
    )
    print(
        f"tip receptance, {f['points']} frequencies: {f['seconds_all_cores'] * 1e3:.2f} ms on"
        f" {f['threads']} threads, {f['seconds_one_core'] * 1e3:.2f} ms on one; error at 20"
        f" points {f['error_at_20_points']:.1e}"
    )
    if args.record and not args.quick:
        figures.record("damping", out, command="python -m benchmarks.damping")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

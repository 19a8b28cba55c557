"""A damped scene of 1000 components (issue 20 item 11): ``python -m benchmarks.damped_large
[--record] [--quick]``.

The scene is ``benchmarks.components.mixed_scene(1000)`` (every kind, random positions on
a 3-segment clamped-free beam) with a dashpot beside every spring of its spring-masses and
oscillator chains (``c = 2 zeta sqrt(k m)``, zeta = 0.05) and a loss factor of 0.01 on
each segment; "undamped" is the same scene without them. Measured, in one run:

* warm, in-process (kernels loaded and compiled, median of repeats): ``mstmm.solve(scene,
  modes=20)`` with and without mode shapes, damped and undamped, and their ratios;
* the command line, a fresh process with every kernel cached (``mstmm solve FILE --modes
  20``, the way the issue timed it), damped and undamped, median wall time;
* correctness: the damped count is checked (``count_checked``), and the same construction
  with ``SMALL`` components matches the independent mpmath reference
  (``tests/reference_model.py``: ``damped_frequencies``), largest relative error.

``--record`` stores the figures under ``damped_large`` in docs/figures.json.
"""

from __future__ import annotations

import argparse
import math
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import mstmm

from . import figures
from .components import mixed_scene
from .damping import ETA, ZETA, rm
from .damping import _median_time as _median

MODES = 20
#: Components of the scene checked against the mpmath reference (its global determinant
#: grows with the components).
SMALL = 30


def damped_mixed(n: int = 1000, zeta: float = ZETA, eta: float = ETA) -> dict:
    """``mixed_scene(n)`` with a dashpot beside every spring of its absorbers (zeta of
    critical) and the loss factor eta on every segment."""
    d = mixed_scene(n)
    d["name"] = f"damped_mixed_{n}"
    for s in d["beam"]["segments"]:
        s["loss_factor"] = eta
    for a in d["attachments"]:
        if a["type"] == "spring_mass":
            a["c"] = 2.0 * zeta * math.sqrt(a["k"] * a["m"])
        elif a["type"] == "oscillator_chain":
            a["c"] = [2.0 * zeta * math.sqrt(k * m) for k, m in zip(a["k"], a["m"])]
    return d


def _toml_value(v) -> str:
    if isinstance(v, str):
        return '"' + v + '"'
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    return repr(float(v))


def to_toml(d: dict) -> str:
    """The scene dictionary as a scene file (tables of scalars and lists only)."""
    lines = [f'name = "{d["name"]}"', "", "[beam]"]
    beam = dict(d["beam"])
    segments = beam.pop("segments", [])
    lines += [f"{k} = {_toml_value(v)}" for k, v in beam.items()]
    for s in segments:
        lines += ["", "[[beam.segments]]"] + [f"{k} = {_toml_value(v)}" for k, v in s.items()]
    for a in d["attachments"]:
        lines += ["", "[[attachments]]"] + [f"{k} = {_toml_value(v)}" for k, v in a.items()]
    return "\n".join(lines) + "\n"


def in_process(n: int, repeats: int) -> dict:
    damped = mstmm.scene_from_dict(damped_mixed(n))
    undamped = mstmm.scene_from_dict(mixed_scene(n))
    sol = mstmm.solve(damped, modes=MODES)  # compiles everything
    mstmm.solve(undamped, modes=MODES)
    out = {
        "components": n,
        "count_checked": bool(sol.count_checked),
        "rectangle": [float(x) for x in sol.rectangle],
        "warnings": list(sol.warnings),
    }
    for name, scene in (("damped", damped), ("undamped", undamped)):
        out[f"{name}_seconds"] = _median(
            lambda s=scene: mstmm.solve(s, modes=MODES, shapes=False), repeats
        )
        out[f"{name}_shapes_seconds"] = _median(
            lambda s=scene: mstmm.solve(s, modes=MODES), max(3, repeats // 3)
        )
    out["ratio"] = out["damped_seconds"] / out["undamped_seconds"]
    out["ratio_shapes"] = out["damped_shapes_seconds"] / out["undamped_shapes_seconds"]
    return out


def command_line(n: int, repeats: int) -> dict:
    """``mstmm solve FILE --modes 20`` in a fresh process, every kernel cached: median wall
    time, damped and undamped."""
    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name, d in (("damped", damped_mixed(n)), ("undamped", mixed_scene(n))):
            path = Path(tmp) / f"{name}.toml"
            path.write_text(to_toml(d))
            cmd = [sys.executable, "-m", "mstmm", "solve", str(path), "--modes", str(MODES)]
            subprocess.run(cmd, check=True, capture_output=True)  # caches the kernels
            times = []
            for _ in range(repeats):
                t = time.perf_counter()
                subprocess.run(cmd, check=True, capture_output=True)
                times.append(time.perf_counter() - t)
            out[f"{name}_seconds"] = statistics.median(times)
    out["ratio"] = out["damped_seconds"] / out["undamped_seconds"]
    return out


def against_reference(n: int) -> dict:
    d = damped_mixed(n)
    t = time.perf_counter()
    exact = np.array([complex(w) for w in rm.damped_frequencies(d, MODES, dps=20)])
    t_ref = time.perf_counter() - t
    sol = mstmm.solve(mstmm.scene_from_dict(d), modes=MODES, shapes=False)
    err = float(np.max(np.abs(sol.omega - exact) / np.abs(exact)))
    return {
        "components": n,
        "error": err,
        "count_checked": bool(sol.count_checked),
        "reference_seconds": t_ref,
    }


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--record", action="store_true", help="store in docs/figures.json")
    ap.add_argument("--quick", action="store_true", help="100 components, fewer repeats")
    args = ap.parse_args(argv)
    n, repeats = (100, 3) if args.quick else (1000, 9)
    out = {
        "in_process": in_process(n, repeats),
        "command_line": command_line(n, 3),
        "reference": against_reference(SMALL if not args.quick else 10),
        "quick": bool(args.quick),
    }
    w, c, r = out["in_process"], out["command_line"], out["reference"]
    print(
        f"{n} damped components, lowest {MODES}, warm: {w['damped_seconds'] * 1e3:.1f} ms vs"
        f" {w['undamped_seconds'] * 1e3:.1f} ms undamped ({w['ratio']:.1f}x); with mode shapes"
        f" {w['damped_shapes_seconds'] * 1e3:.1f} ms vs {w['undamped_shapes_seconds'] * 1e3:.1f}"
        f" ms ({w['ratio_shapes']:.1f}x); count checked {w['count_checked']}"
    )
    print(
        f"  command line (fresh process, kernels cached): {c['damped_seconds']:.2f} s vs"
        f" {c['undamped_seconds']:.2f} s undamped ({c['ratio']:.1f}x)"
    )
    print(
        f"  {r['components']} components against the mpmath reference: error {r['error']:.1e},"
        f" count checked {r['count_checked']}"
    )
    if args.record and not args.quick:
        figures.record("damped_large", out, command="python -m benchmarks.damped_large")
    return 0 if w["count_checked"] and r["count_checked"] and r["error"] <= 1e-10 else 1


if __name__ == "__main__":
    raise SystemExit(main())

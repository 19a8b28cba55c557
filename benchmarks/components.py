"""The component library's speed (issue 13): ``python -m benchmarks.components [--record]``.

* ``mixed``: a 1000-component scene mixing every kind on a 3-segment beam, its lowest 20
  natural frequencies by the kernel's certified scan (``Kernel.lowest``), warm (compiled,
  best of repeats), and the default solve with mode shapes; the result is checked against
  the independent mpmath reference (``tests/reference_model.py``): each root polished in
  a bracket of 1e-8 around it, and the reference's own count at the top of the last
  bracket proves that no root lies outside them (``benchmarks.cases``, "brackets").
* ``first_run``: a new topology with every kind present, in a fresh process with an
  empty kernel cache: derive (SymPy) + compile + solve, wall time. Twice: with the shared
  numerics already compiled (numba's caches in ``src/mstmm/numerics/__pycache__`` and
  ``generated/__pycache__``, as after any earlier run on the machine) and without (the
  first run after installing).
* ``paper_example``: the paper example's lowest 5 frequencies, warm (frequencies only),
  for the "does not get slower" check against ``docs/figures.json``'s ``workprecision``.

``--record`` stores the figures under ``components`` in docs/figures.json.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import mstmm
from mstmm import compiling

from . import figures
from .cases import Case, _rel_errors, reference
from .machine import new_topology_env

KINDS = (
    "spring_mass",
    "mass",
    "spring",
    "rotational_spring",
    "support",
    "hinge",
    "oscillator_chain",
)


def mixed_scene(n: int = 1000, seed: int = 13) -> dict:
    """``n`` components of every kind, cycling, at random positions on a 3-segment
    clamped-free beam of 20 m; values a few decades around the beam's own scales."""
    rng = np.random.default_rng(seed)
    segments = [(8.0, 2.0e7, 40.0), (7.0, 1.0e7, 30.0), (5.0, 4.0e6, 20.0)]
    L = sum(s[0] for s in segments)
    EI, mbar = segments[0][1], segments[0][2]
    k0, m0 = EI / L**3, mbar * L
    atts: list[dict] = []
    used: set[float] = set()
    for i in range(n):
        kind = KINDS[i % len(KINDS)]
        x = float(np.round(rng.uniform(0.02, 0.98) * L, 6))
        if kind in ("support", "hinge"):
            while x in used:
                x = float(np.round(rng.uniform(0.02, 0.98) * L, 6))
        used.add(x)
        a: dict = {"type": kind, "x": x}
        if kind == "spring_mass":
            a.update(k=k0 * 10 ** rng.uniform(0, 3), m=m0 * 10 ** rng.uniform(-4, -2))
        elif kind == "mass":
            a.update(m=m0 * 10 ** rng.uniform(-4, -2), J=m0 * L**2 * 10 ** rng.uniform(-7, -5))
        elif kind == "spring":
            a.update(k=k0 * 10 ** rng.uniform(-2, 1))
        elif kind == "rotational_spring":
            a.update(k=EI / L * 10 ** rng.uniform(-3, -1))
        elif kind == "support":
            pass
        elif kind == "hinge":
            a.update(k=EI / L * 10 ** rng.uniform(1, 3))
        else:
            a.update(
                k=[k0 * 10 ** rng.uniform(0, 3) for _ in range(2)],
                m=[m0 * 10 ** rng.uniform(-4, -2) for _ in range(2)],
            )
        atts.append(a)
    beam = {
        "left": "clamped",
        "right": "free",
        "segments": [{"length": a, "EI": b, "mass_per_length": c} for a, b, c in segments],
    }
    return {"name": "mixed_1000", "beam": beam, "attachments": atts}


def best_of(fn, repeats: int) -> float:
    best = float("inf")
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def mixed(n: int, repeats: int) -> dict:
    scene = mstmm.scene_from_dict(mixed_scene(n))
    kernel = mstmm.kernel_for(scene)
    p = mstmm.parameter_vector(scene)
    w = kernel.lowest(p, 20)  # compile
    mstmm.solve(scene, modes=20)
    compiling.wait_all()  # no helper of this process compiles while it is timed
    t_lowest = best_of(lambda: kernel.lowest(p, 20), repeats)
    t_solve = best_of(lambda: mstmm.solve(scene, modes=20, shapes=False), repeats)
    t_shapes = best_of(lambda: mstmm.solve(scene, modes=20), max(1, repeats // 3))
    ref = reference(Case(f"mixed_{n}", mixed_scene(n), 20, "every kind", 1e-12, "brackets", 20))
    err = float(np.max(_rel_errors(w.omega, ref.omega)))
    return {
        "components": n,
        "lowest20_seconds": t_lowest,
        "solve20_seconds": t_solve,
        "solve20_shapes_seconds": t_shapes,
        "certified": bool(w.certified),
        "reference_complete": bool(ref.complete),
        "reference_seconds": ref.seconds,
        "error_against_reference": err,
    }


FIRST_RUN = """
import time, sys
import mstmm
sc = mstmm.scene_from_dict({scene!r})
sol = mstmm.solve(sc, modes=10)
print(time.time(), sol.count_checked)
from mstmm import compiling
compiling.wait_all()  # no helper of this run outlives it into the next measurement
"""


def _every_kind_scene(left: str, right: str) -> dict:
    atts = [
        {"type": "spring_mass", "x": 0.3, "k": 2000.0, "m": 0.4},
        {"type": "mass", "x": 0.7, "m": 0.5, "J": 0.02},
        {"type": "spring", "x": 0.45, "k": 500.0},
        {"type": "rotational_spring", "x": 0.2, "k": 50.0},
        {"type": "support", "x": 1.2},
        {"type": "hinge", "x": 0.35, "k": 20.0},
        {"type": "oscillator_chain", "x": 1.8, "k": [3000.0, 1000.0], "m": [0.3, 0.2]},
    ]
    beam = {"length": 2.0, "EI": 1000.0, "mass_per_length": 3.0, "left": left, "right": right}
    return {"beam": beam, "attachments": atts}


def first_run(
    ends: tuple[str, str], cold_numerics: bool, compiled: bool = True, helpers: bool = True
) -> dict:
    """Wall time of a fresh process solving a topology never derived before (``compiled``:
    forced to compile, ``MSTMM_INTERPRET_BUDGET=0``; else the default settings; without
    ``helpers``, ``MSTMM_COMPILE_HELPERS=0``: everything compiles in that process)."""
    with tempfile.TemporaryDirectory(prefix="mstmm-first-") as cache:
        # numba's machine code of the shared numerics: where this process has it, or (a
        # cold run) a folder of its own, empty
        env = new_topology_env(cache, MSTMM_COMPILE_HELPERS="1" if helpers else "0")
        if cold_numerics:
            env["NUMBA_CACHE_DIR"] = str(Path(cache) / "numba")
        if compiled:
            env["MSTMM_INTERPRET_BUDGET"] = "0"
        code = FIRST_RUN.format(scene=_every_kind_scene(*ends))
        t0 = time.time()
        out = subprocess.run(
            [sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True
        )
    done, ok = out.stdout.split()
    wall = float(done) - t0  # the process up to its answer, not its helpers' end
    return {"ends": list(ends), "wall_seconds": wall, "certified": ok == "True"}


def paper_example(repeats: int) -> dict:
    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    kernel = mstmm.kernel_for(scene)
    p = mstmm.parameter_vector(scene)
    kernel.lowest(p, 5)
    kernel.warmed.add("lowest")
    return {"lowest5_seconds": best_of(lambda: kernel.lowest(p, 5), repeats)}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--record", action="store_true", help="store in docs/figures.json")
    ap.add_argument("--quick", action="store_true", help="100 components, fewer repeats")
    args = ap.parse_args(argv)
    n, repeats = (100, 3) if args.quick else (1000, 15)
    from mstmm import interpret

    interpret.set_budget(0.0)
    out = {"mixed": mixed(n, repeats), "paper_example": paper_example(repeats * 20)}
    warm = first_run(("sliding", "pinned"), cold_numerics=False)
    cold = first_run(("pinned", "sliding"), cold_numerics=True)
    alone = first_run(("sliding", "sliding"), cold_numerics=True, helpers=False)
    default = first_run(("clamped", "sliding"), cold_numerics=False, compiled=False)
    out["first_run"] = {
        "numerics_compiled": warm,
        "nothing_compiled": cold,
        "nothing_compiled_one_process": alone,
        "default": default,
    }
    out["quick"] = bool(args.quick)
    m = out["mixed"]
    print(
        f"{m['components']} mixed components, lowest 20: {m['lowest20_seconds'] * 1e3:.1f} ms"
        f" (solve {m['solve20_seconds'] * 1e3:.1f} ms, with mode shapes"
        f" {m['solve20_shapes_seconds'] * 1e3:.1f} ms), certified {m['certified']},"
        f" error against the reference {m['error_against_reference']:.1e}"
        f" (reference complete: {m['reference_complete']})"
    )
    print(f"paper example, lowest 5 warm: {out['paper_example']['lowest5_seconds'] * 1e6:.0f} us")
    print(
        f"first run of a new topology with every kind: {warm['wall_seconds']:.1f} s"
        f" (numerics compiled before), {cold['wall_seconds']:.1f} s (nothing compiled;"
        f" {alone['wall_seconds']:.1f} s in one process, without helpers),"
        f" {default['wall_seconds']:.1f} s with the default settings (run as Python)"
    )
    if args.record:
        figures.record("components", out, command="python -m benchmarks.components")
    ok = m["certified"] and m["reference_complete"] and m["error_against_reference"] <= 1e-12
    firsts = (warm, cold, alone, default)
    return 0 if ok and all(r["certified"] for r in firsts) else 1


if __name__ == "__main__":
    raise SystemExit(main())

"""A process that forks after a parallel solve: its children solve too.

mstmm's parallel loops (the search refines a long beam's roots on all cores, sweeps, the
frequency response, dispersion) run on numba's threads. With GNU OpenMP (numba's "omp"
layer, its first choice where libgomp is found) a child forked after one of them dies at
its first parallel loop ("Terminating: fork() called from a process already using GNU
OpenMP"): a ``multiprocessing`` pool of solves after one solve of 1,000 spring-masses
hung on its dead workers. ``mstmm.jit`` picks a fork-safe layer unless the user set
``NUMBA_THREADING_LAYER``. Checked in a fresh interpreter: the children's roots against
the parent's (the same scene solved before the fork).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

_SCRIPT = r"""
import json, multiprocessing as mp
import mstmm
from mstmm.numerics import PARALLEL_EVENTS

n = 2 * PARALLEL_EVENTS  # the search refines its roots on all cores
atts = [
    {"type": "spring_mass", "x": (i + 0.5) / n, "k": 50.0 + i, "m": 1e-3}
    for i in range(n)
]
beam = dict(length=1.0, EI=100.0, mass_per_length=5.0, left="clamped", right="free")
scene = mstmm.scene_from_dict({"beam": beam, "attachments": atts})

def solve(_):
    return mstmm.solve(scene, modes=12, shapes=False).omega.tolist()

parent = solve(0)
with mp.get_context("fork").Pool(2) as pool:
    children = pool.map(solve, [0, 1])
import numba
print(json.dumps({"parent": parent, "children": children, "layer": numba.threading_layer()}))
"""


def test_children_forked_after_a_parallel_solve_solve_too():
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_THREADING_LAYER"}
    env["MSTMM_INTERPRET_BUDGET"] = "0"  # compiled: the parallel loops run
    done = subprocess.run(
        [sys.executable, "-c", _SCRIPT],
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    out = json.loads(done.stdout.splitlines()[-1])
    assert len(out["parent"]) == 12
    assert out["children"] == [out["parent"], out["parent"]]

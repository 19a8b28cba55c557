"""A process that forks after a parallel loop: its children solve and sweep too.

mstmm's parallel loops (sweeps, the frequency response, dispersion, damped contours) run
on numba's threads. With GNU OpenMP (numba's "omp" layer, its first choice where libgomp
is found) a child forked after one of them dies at its first parallel loop
("Terminating: fork() called from a process already using GNU OpenMP"): a
``multiprocessing`` pool after a parameter sweep hung on its dead workers. ``mstmm.jit``
picks a fork-safe layer unless the user set ``NUMBA_THREADING_LAYER``. Checked in a
fresh interpreter: the children's sweeps and roots against the parent's.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

_SCRIPT = r"""
import json, multiprocessing as mp
import numpy as np
import mstmm

scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
ks = np.logspace(3, 9, 64)

def work(_):
    swept = mstmm.sweep(scene, {"attachments[2].k": ks}, modes=3)  # numba prange
    return [np.asarray(swept).tolist(), mstmm.solve(scene, modes=5).omega.tolist()]

parent = work(0)
with mp.get_context("fork").Pool(2) as pool:
    children = pool.map(work, [0, 1])
import numba
print(json.dumps({"parent": parent, "children": children, "layer": numba.threading_layer()}))
"""


def test_children_forked_after_a_parallel_sweep_solve_too():
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
    assert out["layer"] != "omp"
    assert len(out["parent"][1]) == 5
    assert out["children"] == [out["parent"], out["parent"]]

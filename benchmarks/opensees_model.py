"""The beam with spring-masses in OpenSeesPy: a third-party finite-element competitor.

Model (2-D, 3 DOFs per node: ``ux``, ``uy``, ``rz``):

* the beam is cut at the nodes of ``mesh`` of tests/reference_fem.py (uniform, with a
  node at every attachment) into ``elasticBeamColumn`` elements with
  ``E = EI``, ``Iz = 1``, ``A = 1``, distributed mass ``-mass mbar`` and the
  consistent mass matrix (``-cMass``); ``ux`` is fixed at every node (no axial
  modes);
* every spring-mass is a node at the same place carrying ``mass(0, m, 0)``,
  joined to its beam node by a ``zeroLength`` element with an ``Elastic``
  material of stiffness ``k`` in direction 2; its ``ux`` and ``rz`` are fixed;
* end conditions fix ``uy`` / ``rz`` of the end nodes: clamped both, pinned
  ``uy``, sliding ``rz``, free neither;
* ``eigen(solver, n_modes)`` returns ``omega**2``.

Loading.  The ``openseespylinux`` wheel ships its own ``libblas.so.3``,
``liblapack.so.3``, ``libgfortran`` ... in ``openseespylinux/lib`` but does not
put them on the loader path, so ``import openseespy.opensees`` fails with
``libblas.so.3: cannot open shared object file``.  :func:`load` retries after
loading them with ``ctypes.CDLL(..., RTLD_GLOBAL)``; :func:`loader_env` is the
environment (``LD_LIBRARY_PATH``) for a subprocess.  The benchmark runs
OpenSees in a subprocess (``python -m benchmarks.opensees_model``, JSON on
stdin and stdout), so that its BLAS never shares a process with numpy's.
"""

from __future__ import annotations

import ctypes
import importlib
import importlib.util
import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np

#: The shared libraries of the wheel, in dependency order.
_LIBS = ("libquadmath.so.0", "libgfortran.so.4", "libgomp.so.1", "libblas.so.3", "liblapack.so.3")

#: ``fix`` flags (ux, uy, rz) of an end node.
_END_FIX = {
    "clamped": (1, 1, 1),
    "pinned": (1, 1, 0),
    "sliding": (1, 0, 1),
    "free": (1, 0, 0),
}

#: The eigen solver used unless told otherwise (OpenSees' default).
SOLVER = "-genBandArpack"

#: Every eigen solver OpenSeesPy's ``eigen`` offers, each run by the benchmark, with the
#: largest mesh it is run on: ``-fullGenLapack`` is dense LAPACK (O(n^3): 45 s at 512
#: elements on the 2-core machine measured), the band solvers go to the finest mesh.
#: ``-symmBandLapack`` solves only the standard problem (OpenSees: "only does standard
#: problem"), so it fails on this model's consistent (non-diagonal) mass matrix; it is run
#: all the same and its failure reported.
SOLVERS = {"-genBandArpack": None, "-fullGenLapack": 256, "-symmBandLapack": None}

#: Why a solver fails on this model, in OpenSees' words (its Python error says only
#: "See stderr output"; the reason is printed on stderr).
KNOWN_FAILURES = {
    "-symmBandLapack": "fails: it solves only the standard eigenproblem "
    "(SymBandEigenSolver: 'only does standard problem'), and this model's consistent mass "
    "matrix is not diagonal",
}


def lib_dir() -> Path | None:
    """``openseespylinux/lib`` of the installed wheel (found without importing it)."""
    try:
        spec = importlib.util.find_spec("openseespylinux")
    except (ImportError, ValueError):
        return None
    if spec is None or not spec.submodule_search_locations:
        return None
    path = Path(next(iter(spec.submodule_search_locations))) / "lib"
    return path if path.is_dir() else None


def loader_env(env: dict[str, str] | None = None) -> dict[str, str]:
    """A copy of ``env`` (default ``os.environ``) with the wheel's libraries on the loader path."""
    env = dict(os.environ if env is None else env)
    d = lib_dir()
    if d is not None:
        old = env.get("LD_LIBRARY_PATH", "")
        env["LD_LIBRARY_PATH"] = str(d) + (os.pathsep + old if old else "")
    return env


def _forget() -> None:
    for name in list(sys.modules):
        if name.startswith(("openseespy", "openseespylinux")):
            del sys.modules[name]


def load() -> Any:
    """The ``openseespy.opensees`` module; raises ``ImportError`` with the reason."""
    try:
        return importlib.import_module("openseespy.opensees")
    except ModuleNotFoundError:
        raise
    except (ImportError, RuntimeError) as first:
        _forget()
        d = lib_dir()
        if d is None:
            raise ImportError(f"openseespy: {first} (no openseespylinux/lib to preload)") from first
        for name in _LIBS:
            path = d / name
            if path.exists():
                ctypes.CDLL(str(path), mode=ctypes.RTLD_GLOBAL)
        try:
            return importlib.import_module("openseespy.opensees")
        except (ImportError, RuntimeError) as second:
            _forget()
            raise ImportError(
                f"openseespy: {second} (after preloading {d}: first error {first})"
            ) from second


def build(ops: Any, scene: Any, n_elements: int) -> int:
    """Build the model of ``scene`` on the mesh of ``n_elements`` elements; returns the DOFs."""
    from reference_fem import mesh

    beam = scene.beam
    nodes = mesh(scene, n_elements)
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    for i, x in enumerate(nodes, start=1):
        ops.node(i, float(x), 0.0)
    n = len(nodes)
    for i in range(1, n + 1):
        if i == 1:
            ops.fix(i, *_END_FIX[beam.left])
        elif i == n:
            ops.fix(i, *_END_FIX[beam.right])
        else:
            ops.fix(i, 1, 0, 0)
    ops.geomTransf("Linear", 1)
    for e in range(1, n):
        ops.element(
            "elasticBeamColumn",
            e,
            e,
            e + 1,
            1.0,
            float(beam.EI),
            1.0,
            1,
            "-mass",
            float(beam.mass_per_length),
            "-cMass",
        )
    index = {float(x): i for i, x in enumerate(nodes, start=1)}
    for j, a in enumerate(scene.attachments, start=1):
        tag = n + j
        ops.node(tag, float(a.x), 0.0)
        ops.fix(tag, 1, 0, 1)
        ops.mass(tag, 0.0, float(a.m), 0.0)
        ops.uniaxialMaterial("Elastic", j, float(a.k))
        ops.element("zeroLength", n + j, index[float(a.x)], tag, "-mat", j, "-dir", 2)
    free = {"clamped": 0, "pinned": 1, "sliding": 1, "free": 2}
    return 2 * (n - 2) + free[beam.left] + free[beam.right] + len(scene.attachments)


def frequencies(
    ops: Any, scene: Any, n_modes: int, n_elements: int, solver: str = SOLVER
) -> np.ndarray:
    """Lowest ``n_modes`` OpenSees frequencies (rad/s) of ``scene`` on ``n_elements`` elements."""
    build(ops, scene, n_elements)
    lam = ops.eigen(solver, int(n_modes))
    return np.sqrt(np.sort(np.asarray(lam, dtype=float)))


def _worker(spec: dict) -> dict:
    """Time OpenSees on ``spec``: ``scene`` (path), ``modes`` (list), ``meshes``, ``budget``,
    ``solvers`` (``{solver: largest mesh or None}``, default :data:`SOLVERS`)."""
    import mstmm

    from .workprecision import timed

    ops = load()
    scene = mstmm.load_scene(spec["scene"])
    solvers = spec.get("solvers", SOLVERS)
    rows = []
    for solver, largest in solvers.items():
        for modes in spec["modes"]:
            for n in spec["meshes"]:
                ndof = build(ops, scene, n)
                if modes >= ndof - 1 or (largest is not None and n > largest):
                    continue
                row = {"solver": solver, "modes": modes, "n": n}
                try:
                    w, t, reps = timed(
                        lambda m=modes, n=n, s=solver: frequencies(ops, scene, m, n, s),
                        spec["budget"],
                        min_repeats=3,
                        max_repeats=100,
                    )
                except Exception as exc:  # report the failure of one mesh, keep the others
                    rows.append({**row, "error": f"{type(exc).__name__}: {exc}"})
                    continue
                rows.append({**row, "omega": w.tolist(), "time": t, "repeats": reps})
    ops.wipe()
    version = ops.version() if hasattr(ops, "version") else "?"
    return {"rows": rows, "solvers": list(solvers), "version": str(version)}


def run(spec: dict, timeout: float = 600.0) -> dict:
    """:func:`_worker` in a fresh subprocess; ``{"error": ...}`` when OpenSees cannot run."""
    cmd = [sys.executable, "-m", "benchmarks.opensees_model"]
    root = Path(__file__).resolve().parent.parent
    env = loader_env()
    env["PYTHONPATH"] = str(root) + (os.pathsep + env["PYTHONPATH"] if "PYTHONPATH" in env else "")
    try:
        proc = subprocess.run(
            cmd,
            input=json.dumps(spec),
            capture_output=True,
            text=True,
            timeout=timeout,
            cwd=root,
            env=env,
        )
    except subprocess.TimeoutExpired:
        return {"error": f"the OpenSees run did not finish within {timeout:.0f} s"}
    lines = [ln for ln in proc.stdout.splitlines() if ln.startswith("{")]
    if not lines:
        tail = (proc.stderr.strip().splitlines() or ["no output"])[-1]
        return {"error": f"exit status {proc.returncode}: {tail}"}
    return json.loads(lines[-1])


def main() -> None:
    spec = json.loads(sys.stdin.read())
    try:
        out = _worker(spec)
    except Exception as exc:
        out = {"error": f"{type(exc).__name__}: {exc}"}
    sys.stdout.write(json.dumps(out) + "\n")
    sys.stdout.flush()


if __name__ == "__main__":
    main()

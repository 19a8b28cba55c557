"""Segments beyond Euler-Bernoulli (issue 22): accuracy against closed forms, the cost of
the matrix-exponential walk, Timoshenko at 1000 modes, the first run of such a scene.

Run: ``python -m benchmarks.segments [--record]`` (about a minute).

* **closed forms**: the simply supported beam with every combination of the terms
  (:func:`simply_supported`: both Timoshenko spectra and the thickness-shear mode), the
  lowest 16 through ``mstmm.solve`` (default path, shapes on): worst relative error;
* **warm solve**: the paper's example (the lowest 10, frequencies only) as printed, and
  with every segment term on (shear, rotary inertia, tension, Winkler, Pasternak), in one
  process, median of rounds: the ratio is what the matrix exponentials cost;
* **Timoshenko at 1000 modes**: a simply supported beam whose cut-off frequency lies
  near its 30th mode, the lowest 1000 against the closed form;
* **first run**: a fresh process with an empty kernel cache solving a scene of a topology
  no bundled kernel has, with every term on (derive + compile of the kernel; the shared
  numerics already compiled on the machine).
"""

from __future__ import annotations

import argparse
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

from . import figures
from .machine import new_topology_env


def simply_supported(L, EI, mbar, kGA=0.0, rhoI=0.0, t=0.0, kw=0.0, n_max=400):
    """Every natural frequency squared (ascending) of a simply supported uniform beam with
    n <= n_max half waves, with its mode number and amplitude ratio ``Psi / W``:
    ``w = W sin(k x)``, ``psi = Psi cos(k x)``, ``k = n pi / L`` solve the Euler-Lagrange
    equations of ``EI psi'^2 + kGA (w' - psi)^2 + t w'^2 + k_w w^2`` (t = P + k_G) and
    ``mbar w^2 + rhoI psi^2`` when ``det [[kGA k^2 + t k^2 + k_w - mbar w^2, -kGA k],
    [-kGA k, EI k^2 + kGA - rhoI w^2]] = 0`` (both roots: Timoshenko's two spectra); n = 0
    is the thickness-shear mode ``w^2 = kGA / rhoI`` (``w = 0``, ``psi`` constant). Without
    shear deformation (kGA = 0): ``w^2 = (EI k^4 + t k^2 + k_w) / (mbar + rhoI k^2)``.
    Returns ``(w2, n, Psi / W)`` tuples."""
    out = []
    if kGA > 0.0 and rhoI > 0.0:
        out.append((kGA / rhoI, 0, math.inf))
    for n in range(1, n_max + 1):
        k = n * math.pi / L
        if kGA == 0.0:
            out.append(((EI * k**4 + t * k**2 + kw) / (mbar + rhoI * k**2), n, k))
            continue
        X = kGA * k**2 + t * k**2 + kw
        Y = EI * k**2 + kGA
        a, b, c = mbar * rhoI, -(mbar * Y + rhoI * X), X * Y - kGA**2 * k**2
        if a == 0.0:
            roots = [-c / b]
        else:  # the two roots without cancellation
            q = -0.5 * (b - math.sqrt(b * b - 4.0 * a * c))
            roots = [c / q, q / a]
        out += [(w2, n, (X - mbar * w2) / (kGA * k)) for w2 in roots]
    return sorted(out)


#: Combinations of the terms on a beam L = 2, EI = 3, mbar = 1.5 (SI).
CASES = {
    "tension": dict(axial_force=5.0),
    "compression": dict(axial_force=-5.0),
    "Winkler": dict(foundation_k=40.0),
    "Pasternak": dict(foundation_kG=7.0),
    "Rayleigh": dict(rho_I=0.05),
    "shear beam": dict(kappa_GA=30.0),
    "Timoshenko": dict(kappa_GA=30.0, rho_I=0.02),
    "everything": dict(
        kappa_GA=300.0, rho_I=0.01, axial_force=-3.0, foundation_k=20.0, foundation_kG=2.0
    ),
}
BEAM = dict(length=2.0, EI=3.0, mass_per_length=1.5)


def terms(extra: dict) -> dict:
    """The closed form's arguments from a beam's scene keys."""
    return dict(
        kGA=extra.get("kappa_GA", 0.0),
        rhoI=extra.get("rho_I", 0.0),
        t=extra.get("axial_force", 0.0) + extra.get("foundation_kG", 0.0),
        kw=extra.get("foundation_k", 0.0),
    )


def _scene(extra: dict, beam: dict = BEAM, attachments=()):
    from mstmm.scene import scene_from_dict

    b = dict(beam, left="pinned", right="pinned", **extra)
    return scene_from_dict({"name": "segments", "beam": b, "attachments": list(attachments)})


def closed_forms(modes: int = 16) -> dict:
    import mstmm

    out = {}
    for name, extra in CASES.items():
        sol = mstmm.solve(_scene(extra), modes=modes)
        exact = np.sqrt([m[0] for m in simply_supported(2.0, 3.0, 1.5, **terms(extra))][:modes])
        out[name] = {
            "error": float(np.max(np.abs(sol.omega - exact) / exact)),
            "count_checked": bool(sol.count_checked),
        }
    return out


def _paper_with_every_term():
    import mstmm
    from mstmm.scene import scene_to_dict

    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    b = scene.beam
    EI, L, mbar = b.EI, b.length, b.mass_per_length
    extra = dict(
        kappa_GA=50.0 * EI / L**2,
        rho_I=mbar * 0.05**2,
        axial_force=2.0 * EI / L**2,
        foundation_k=10.0 * EI / L**4,
        foundation_kG=0.5 * EI / L**2,
    )
    data = scene_to_dict(scene)
    data["beam"].update(extra)
    return scene, mstmm.scene_from_dict(data)


def warm_solve(rounds: int = 15) -> dict:
    import mstmm
    from mstmm import compiling

    plain, every = _paper_with_every_term()
    times = {}
    for label, scene in (("euler_bernoulli", plain), ("every_term", every)):
        mstmm.solve(scene, modes=10, shapes=False)
        mstmm.solve(scene, modes=10, shapes=False)
        compiling.wait_all()  # no helper of this process compiles while it is timed
        runs = []
        for _ in range(rounds):
            t0 = time.perf_counter()
            mstmm.solve(scene, modes=10, shapes=False)
            runs.append(time.perf_counter() - t0)
        times[label] = float(np.median(runs))
    return {**times, "ratio": times["every_term"] / times["euler_bernoulli"], "rounds": rounds}


def many_modes(modes: int = 1000) -> dict:
    import mstmm

    beam = dict(length=1.0, EI=1.0, mass_per_length=1.0)
    extra = dict(kappa_GA=1e4, rho_I=1e-5)
    scene = _scene(extra, beam)
    mstmm.solve(scene, modes=5, shapes=False)
    t0 = time.perf_counter()
    sol = mstmm.solve(scene, modes=modes, shapes=False)
    seconds = time.perf_counter() - t0
    exact = np.sqrt([m[0] for m in simply_supported(1.0, 1.0, 1.0, 1e4, 1e-5, n_max=modes)])
    exact = exact[:modes]
    cut = math.sqrt(1e4 / 1e-5)
    return {
        "modes": modes,
        "error": float(np.max(np.abs(sol.omega - exact) / exact)),
        "count_checked": bool(sol.count_checked),
        "above_cut_off": int(np.count_nonzero(exact > cut)),
        "cut_off": cut,
        "seconds": seconds,
    }


FIRST_RUN = """
import time
t0 = time.perf_counter()
import mstmm
from mstmm.scene import scene_from_dict
beam = dict(length=3.0, EI=2.0e4, mass_per_length=12.0, left="sliding", right="pinned",
            kappa_GA=4.0e6, rho_I=0.02, axial_force=1.0e4, foundation_k=5.0e4,
            foundation_kG=1.0e3)
atts = [dict(type="mass", x=1.0, m=3.0, J=0.1), dict(type="spring", x=2.0, k=1.0e5)]
sol = mstmm.solve(scene_from_dict(dict(name="first", beam=beam, attachments=atts)), modes=5)
assert sol.count_checked
print(time.perf_counter() - t0, sol.timings.get("derive", 0.0))
"""


def first_run() -> dict:
    """A fresh process, an empty kernel cache, a topology no bundled kernel has (the shared
    numerics compiled on the machine by the runs before): as a user runs it (a small
    first solve runs the kernel as Python, ``mstmm.interpret``), and compiled
    (``MSTMM_INTERPRET_BUDGET=0``: derive + compile)."""
    out = {}
    for label, budget in (("default", None), ("compiled", "0")):
        with tempfile.TemporaryDirectory() as cache:
            env = new_topology_env(cache, MSTMM_COMPILE_HELPERS="1")  # a user's
            if budget is not None:
                env["MSTMM_INTERPRET_BUDGET"] = budget
            t0 = time.perf_counter()
            run = subprocess.run(
                [sys.executable, "-c", FIRST_RUN],
                env=env,
                capture_output=True,
                text=True,
                check=True,
            )
            wall = time.perf_counter() - t0
        inside, derive = (float(v) for v in run.stdout.split())
        out[label] = {"process": wall, "solve": inside, "derive": derive}
    return out


def fem(elements: int = 64) -> dict:
    """The example ``deep_beam_tmd`` with a tension and a foundation added, against the
    finite-element model (Timoshenko elements, geometric and foundation stiffness) after
    Richardson extrapolation: the lowest 8."""
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    import reference_fem as fe

    import mstmm
    from mstmm.scene import scene_to_dict

    path = figures.ROOT / "examples" / "deep_beam_tmd.toml"
    data = scene_to_dict(mstmm.load_scene(path))
    data["beam"].update(axial_force=2.0e7, foundation_k=5.0e6, foundation_kG=1.0e6)
    scene = mstmm.scene_from_dict(data)
    got = mstmm.solve(scene, modes=8, shapes=False).omega
    ref = fe.richardson(scene, 8, elements, "sparse")
    return {
        "error": float(np.max(np.abs(got - ref) / ref)),
        "elements": elements,
        "scene": "examples/deep_beam_tmd.toml with a tension, a Winkler and a Pasternak foundation",
    }


def measure() -> dict:
    return {
        "fem": fem(),
        "closed_forms": closed_forms(),
        "warm_solve": warm_solve(),
        "many_modes": many_modes(),
        "first_run": first_run(),
    }


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--record", action="store_true", help="write docs/figures.json")
    args = ap.parse_args(argv)
    fig = measure()
    for name, r in fig["closed_forms"].items():
        print(f"simply supported, {name}: worst error {r['error']:.1e}, count {r['count_checked']}")
    w = fig["warm_solve"]
    print(
        f"paper example, lowest 10: {w['euler_bernoulli'] * 1e3:.3f} ms as printed,"
        f" {w['every_term'] * 1e3:.3f} ms with every segment term ({w['ratio']:.2f}x)"
    )
    m = fig["many_modes"]
    print(
        f"Timoshenko, lowest {m['modes']} ({m['above_cut_off']} above the cut-off):"
        f" worst error {m['error']:.1e} in {m['seconds']:.2f} s, count {m['count_checked']}"
    )
    e = fig["fem"]
    print(f"against the FE model ({e['scene']}): {e['error']:.1e} after Richardson")
    for label, f in fig["first_run"].items():
        print(
            f"first run of a new topology ({label}): {f['process']:.2f} s"
            f" ({f['derive']:.2f} s SymPy)"
        )
    if args.record:
        path = figures.record("segments", fig, command="python -m benchmarks.segments --record")
        print(f"recorded in {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

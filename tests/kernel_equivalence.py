"""Two printings of one kernel compute the same numbers: the check behind a SymPy range.

The committed kernels in ``generated/`` are printed by one SymPy version (the
header says which: ``Derived by mstmm.derive with SymPy X.``). Another SymPy
may order or factor the printed expressions differently, so under it the text
comparison of ``tests/test_kernels.py`` means nothing; what must hold is that
the freshly printed kernel computes what the committed one computes. This
module loads two kernel sources side by side, as plain Python (each numba
dispatcher's ``py_func``, rebound by :func:`mstmm.interpret.python_copy`, so
nothing is compiled), and compares their public functions at random parameter
vectors and frequencies:

* a kernel: ``delta_stable``, ``delta_paper`` (the value ``mantissa * exp(log)``),
  ``u_bar_paper``, and the shared drivers run with each printing's functions
  (``evaluate``, ``refine``, ``lowest``, ``mode_shapes``); the shared numerics:
  ``beam_transfer``, ``beam_transfer_scaled``, ``beam_compound_step``, ``krylov``:
  relative difference at most :data:`RTOL` (next to a root, where the
  characteristic function cancels, relative to the size of its terms: see
  :func:`close`);
* ``count_below``, ``rigid_body_modes``, ``shape_sizes``: exactly equal;
* the module constants (all upper-case names but ``SIGNATURE``) and the set of
  functions: equal.

Run as a script in another environment to print the kernels there::

    python tests/kernel_equivalence.py derive OUT_DIR   # every end pair, bare and spring-mass
    python tests/kernel_equivalence.py solve            # the paper example vs reference.json

(used by ``tests/test_sympy_range.py`` in a venv holding the oldest SymPy supported).
"""

from __future__ import annotations

import importlib.util
import itertools
import json
import math
import sys
import tempfile
from pathlib import Path

import numpy as np

#: Largest relative difference allowed between the two printings.
RTOL = 1e-13

#: A kernel's functions compared one by one (the shared drivers are run with each).
PUBLIC = (
    "delta_stable",
    "delta_paper",
    "count_below",
    "u_bar_paper",
    "oscillator_frequencies",
    "rigid_body_modes",
    "shape_event",
    "shape_inertia",
    "shape_sizes",
)
#: The shared numerics' printed functions compared one by one.
NUMERICS_PUBLIC = ("beam_transfer", "beam_transfer_scaled", "beam_compound_step", "krylov")

HEADER = "Derived by mstmm.derive with SymPy "

_LOADED = itertools.count()


def printed_by(source: str) -> str | None:
    """The SymPy version a kernel source says it was printed with (None if it does not say)."""
    for line in source.splitlines():
        if line.startswith(HEADER):
            return line[len(HEADER) :].strip().rstrip(".")
    return None


def all_topologies() -> list:
    """A kernel of each: bare, with spring-masses, with every kind of an undamped scene (a
    dashpot makes a scene damped: its kernel is complex). The ends are data: ``compare``
    draws an end pair at each point."""
    from mstmm.catalog import builtin_kinds, damping_only
    from mstmm.topology import Topology

    every = tuple(sorted(k for k in builtin_kinds() if not damping_only(k)))
    return [Topology("clamped", "free", kinds) for kinds in ((), ("spring_mass",), every)]


def python_kernel(source: str) -> dict:
    """The kernel printed in ``source`` as a namespace of plain-Python functions."""
    from mstmm.interpret import python_copy

    name = f"mstmm_equivalence_{next(_LOADED)}"
    with tempfile.TemporaryDirectory(prefix="mstmm-equivalence-") as tmp:
        path = Path(tmp) / f"{name}.py"
        path.write_text(source)
        spec = importlib.util.spec_from_file_location(name, path)
        assert spec is not None and spec.loader is not None
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        try:
            spec.loader.exec_module(module)
        finally:
            del sys.modules[name]
    return python_copy(module)


def _functions(ns: dict) -> set[str]:
    return {
        k for k, v in ns.items() if callable(v) and getattr(v, "__module__", "") == ns["__name__"]
    }


def _constants(ns: dict) -> dict:
    """Module constants, arrays as tuples (so that two printings compare with ``==``)."""
    return {
        k: tuple(np.ravel(v).tolist()) if isinstance(v, np.ndarray) else v
        for k, v in ns.items()
        if k.isupper() and k != "SIGNATURE"
    }


def random_parameters(rng: np.random.Generator, kinds: tuple, left: str, right: str) -> np.ndarray:
    """A parameter vector over several decades: 1..3 segments, 1..5 components of each
    kind (attachments at the ends and two at one x included), as ``catalog.layout``."""
    from mstmm.catalog import Component, Topology, layout

    L = 10 ** rng.uniform(-1, 1)
    EI = 10 ** rng.uniform(0, 6)
    mbar = 10 ** rng.uniform(-1, 2)
    n_seg = int(rng.integers(1, 4))
    cuts = np.sort(rng.uniform(0.1, 0.9, n_seg - 1)) * L
    lengths = np.diff(np.concatenate([[0.0], cuts, [L]]))
    segments = [(float(lengths[0]), EI, mbar)] + [
        (float(ln), EI * 10 ** rng.uniform(-1, 1), mbar * 10 ** rng.uniform(-0.5, 0.5))
        for ln in lengths[1:]
    ]
    k_scale, m_scale = EI / L**3, mbar * L
    comps = []
    for kind in kinds:
        n = int(rng.integers(1, 4)) if kind not in ("support", "hinge") else 1
        for _ in range(n):
            x = float(rng.uniform(0.05, 0.95) * L)
            if kind == "spring_mass":
                values = {
                    "k": k_scale * 10 ** rng.uniform(-1, 2),
                    "m": m_scale * 10 ** rng.uniform(-1, 0),
                }
            elif kind == "mass":
                values = {"m": m_scale * 10 ** rng.uniform(-1, 0), "J": m_scale * L**2 * 0.01}
            elif kind == "spring":
                values = {"k": k_scale * 10 ** rng.uniform(-1, 2)}
            elif kind in ("rotational_spring", "hinge"):
                values = {"k": EI / L * 10 ** rng.uniform(-1, 1)}
            elif kind == "oscillator_chain":
                stages = int(rng.integers(1, 4))
                values = {
                    "k": [k_scale * 10 ** rng.uniform(-1, 2) for _ in range(stages)],
                    "m": [m_scale * 10 ** rng.uniform(-1, 0) for _ in range(stages)],
                }
            else:
                values = {}
            comps.append(Component(kind, x, values))
    return layout(segments, comps, Topology(left, right, kinds))[0]


def _shape_ends(p: np.ndarray) -> np.ndarray:
    """The mode-shape march's ends of ``p``: its left end's unknowns, its right end's knowns."""
    from mstmm.catalog import march_ends

    return np.array(march_ends(p), dtype=np.int64)


def _topology(ns: dict) -> tuple:
    from mstmm.catalog import Topology

    return Topology.from_key(ns["TOPOLOGY"])
    """The kernel's topology."""


def omega_of(p: np.ndarray, beta: float) -> float:
    """Frequency at ``beta = lambda L``."""
    return math.sqrt(p[1] / p[2]) / p[0] ** 2 * beta**2


def close(a, b, rtol: float = RTOL, scale=None) -> bool:
    """|a - b| <= rtol * max(|a|, |b|, scale) elementwise (``scale``: size of the terms)."""
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    ref = np.maximum(np.abs(a), np.abs(b))
    if scale is not None:
        ref = np.maximum(ref, scale)
    return bool(np.all(np.abs(a - b) <= rtol * ref) and np.array_equal(np.isnan(a), np.isnan(b)))


def _value_pair(ref, new, fn, omega, p, h):
    """Both printings' value of ``fn`` (a (mantissa, log) function), on one scale, and the
    size of the function's variation over ``omega * (1 +- h)`` (a root's cancellation)."""
    ma, la = ref[fn](omega, p)
    mb, lb = new[fn](omega, p)
    top = max(la, lb)
    va, vb = ma * math.exp(la - top), mb * math.exp(lb - top)
    near = []
    for w in (omega * (1 - h), omega * (1 + h)):
        m, lg = ref[fn](w, p)
        near.append(abs(m) * math.exp(lg - top))
    return va, vb, max(near)


def compare(reference_source: str, candidate_source: str, points: int = 40, seed: int = 0) -> list:
    """What differs between two printings of one kernel, or of the shared numerics (an
    empty list: nothing)."""
    ref = python_kernel(reference_source)
    new = python_kernel(candidate_source)
    problems = []
    if _functions(ref) != _functions(new):
        problems.append(f"functions differ: {sorted(_functions(ref) ^ _functions(new))}")
    cr, cn = _constants(ref), _constants(new)
    if cr != cn:
        problems.append(f"constants differ: {cr} != {cn}")
    numerics = "TOPOLOGY" not in ref
    public = NUMERICS_PUBLIC if numerics else PUBLIC
    missing = [f for f in public if f not in ref]
    if missing:
        problems.append(f"public functions missing: {missing}")
        return problems
    rng = np.random.default_rng(seed)
    for i in range(points):
        if numerics:
            problems += _compare_numerics_at(ref, new, rng, i)
        else:
            from mstmm.scene import BOUNDARY_KINDS

            t = _topology(ref)
            left, right = (str(e) for e in rng.choice(BOUNDARY_KINDS, 2))
            p = random_parameters(rng, t.kinds, left, right)
            problems += _compare_at(ref, new, p, rng, i)
        if len(problems) > 10:
            break
    return problems


def _compare_numerics_at(ref: dict, new: dict, rng: np.random.Generator, i: int) -> list:
    out = []
    for beta in np.concatenate([10 ** rng.uniform(-3, 0.3, 3), rng.uniform(2, 45, 3)]):
        rho = rng.uniform(0.01, 1.0)
        Ua, Ub = np.empty((4, 4)), np.empty((4, 4))
        ref["beam_transfer_scaled"](beta, rho, Ua)
        new["beam_transfer_scaled"](beta, rho, Ub)
        if not close(Ua, Ub, scale=np.abs(Ua).max()):
            out.append(f"beam_transfer_scaled({beta}, {rho}) point {i}: {Ua} vs {Ub}")
        lam, l, EI = beta, rho, 10 ** rng.uniform(0, 4)
        ref["beam_transfer"](lam, l, EI, Ua)
        new["beam_transfer"](lam, l, EI, Ub)
        if not close(Ua, Ub, scale=np.abs(Ua).max()):
            out.append(f"beam_transfer({lam}, {l}, {EI}) point {i}: {Ua} vs {Ub}")
        va, vb = rng.normal(size=6), None
        vb = va.copy()
        sa, sb = ref["beam_compound_step"](va, beta, rho), new["beam_compound_step"](vb, beta, rho)
        if sa != sb or not close(va, vb, scale=np.abs(va).max()):
            out.append(f"beam_compound_step({beta}, {rho}) point {i}: {va} vs {vb}")
        ka, kb = ref["krylov"](beta * rho), new["krylov"](beta * rho)
        if not close(ka, kb):
            out.append(f"krylov({beta * rho}) point {i}: {ka} vs {kb}")
    return out


def _search(ns: dict) -> tuple:
    return tuple(
        ns[n] for n in ("delta_stable", "count_below", "oscillator_frequencies", "rigid_body_modes")
    )


def _compare_at(ref: dict, new: dict, p: np.ndarray, rng: np.random.Generator, i: int) -> list:
    out = []
    where = f"point {i} p={p.tolist()}"
    betas = np.concatenate([10 ** rng.uniform(-2, 0.3, 3), rng.uniform(2, 45, 5)])
    omegas = np.array([omega_of(p, b) for b in betas])
    for fn in ("delta_stable", "delta_paper"):
        for w in omegas:
            # the paper's determinant loses a digit per pi of lambda L: compare it where
            # both printings still hold digits, with the same cancellation allowance
            va, vb, scale = _value_pair(ref, new, fn, w, p, 1e-6)
            if not close(va, vb, scale=scale):
                out.append(f"{fn}({w!r}) {where}: {va!r} vs {vb!r} (scale {scale:.3g})")
        mant_a, logs_a = np.empty_like(omegas), np.empty_like(omegas)
        mant_b, logs_b = np.empty_like(omegas), np.empty_like(omegas)
        ref["evaluate"](ref[fn], omegas, p, mant_a, logs_a)
        new["evaluate"](new[fn], omegas, p, mant_b, logs_b)
        single = np.array([ref[fn](w, p) for w in omegas])
        if not (np.array_equal(mant_a, single[:, 0]) and np.array_equal(logs_a, single[:, 1])):
            out.append(f"evaluate({fn}) of the reference printing is not {fn} pointwise")
        signs = [
            k
            for k in range(len(omegas))
            if np.sign(mant_a[k]) != np.sign(mant_b[k])
            and abs(mant_a[k]) > 1e-12
            and abs(mant_b[k]) > 1e-12
        ]
        if signs:
            out.append(f"evaluate({fn}) signs differ at {omegas[signs]} {where}")
    for w in omegas:
        a, b = ref["count_below"](w, p), new["count_below"](w, p)
        if a != b:
            out.append(f"count_below({w!r}) {where}: {a} vs {b}")
    for fn in ("rigid_body_modes", "shape_sizes"):
        if ref[fn](p) != new[fn](p):
            out.append(f"{fn} {where}: {ref[fn](p)} vs {new[fn](p)}")
    if not close(ref["oscillator_frequencies"](p), new["oscillator_frequencies"](p)):
        out.append(f"oscillator_frequencies {where}")
    for w in omegas[:4]:
        Ua, Ub = ref["u_bar_paper"](w, p), new["u_bar_paper"](w, p)
        if not close(Ua, Ub, scale=np.abs(Ua).max()):
            out.append(f"u_bar_paper({w!r}) {where}: {Ua} vs {Ub}")
    modes = 6
    oa, ob = np.zeros(modes), np.zeros(modes)
    found = []
    for ns, o in ((ref, oa), (new, ob)):
        flags, state = np.zeros(modes, dtype=np.int64), np.zeros(ns["STATE_SIZE"])
        k = ns["lowest"](*_search(ns), p, modes, o, flags, state, True, 0.0)
        found.append((k, state[ns["STATE_CERTIFIED"]], tuple(flags)))
    ok_a, ok_b = found
    if ok_a != ok_b or not close(oa, ob):
        out.append(f"lowest {where}: {oa} ({ok_a}) vs {ob} ({ok_b})")
    xs = np.linspace(0.0, p[0], 11)
    nq = ref["shape_sizes"](p)[0]
    for r in oa[oa > 0][:2]:
        shapes = []
        for k in (ref, new):
            Z, q = np.zeros((1, len(xs), 4)), np.zeros((1, nq))
            q_x, q_mass = np.zeros(nq), np.zeros((2, nq))
            gram, part, ratio = np.zeros((1, 1)), np.zeros(1), np.zeros(1)
            k["mode_shapes"](
                k["shape_event"],
                k["shape_inertia"],
                k["shape_sizes"],
                _shape_ends(p),
                r,
                p,
                1,
                xs,
                Z,
                q,
                q_x,
                q_mass,
                gram,
                part,
                ratio,
            )
            v = np.concatenate([Z.ravel(), q.ravel()])
            shapes.append(v / v[np.argmax(np.abs(v))] / np.sqrt(gram[0, 0]) * np.abs(v).max())
        if not close(shapes[0], shapes[1], scale=np.abs(shapes[0]).max()):
            out.append(f"mode_shapes({r!r}) {where}: {shapes[0]} vs {shapes[1]}")
    for fn in ("delta_stable", "delta_paper"):
        roots = oa[(oa > 0)][:2] if fn == "delta_stable" else oa[(oa > 0)][:1]
        for r in roots:
            a, b = r * (1 - 1e-3), r * (1 + 1e-3)
            ra = ref["refine"](ref[fn], a, b, p, 0.0, 200)
            rb = new["refine"](new[fn], a, b, p, 0.0, 200)
            if ra[2] != rb[2] or not close(ra[0], rb[0], rtol=1e-12):
                out.append(f"refine({fn}, {a!r}, {b!r}) {where}: {ra} vs {rb}")
    return out


def derive_all(out_dir: Path) -> list[Path]:
    """Print every topology's kernel with the SymPy of this environment into ``out_dir``."""
    from mstmm.derive.emit import kernel_source, numerics_source

    out_dir.mkdir(parents=True, exist_ok=True)
    paths = [out_dir / "euler_bernoulli.py"]
    paths[0].write_text(numerics_source())
    for topology in all_topologies():
        path = out_dir / f"{topology.kernel_key}.py"
        path.write_text(kernel_source(topology))
        paths.append(path)
    return paths


def solve_paper_example() -> dict:
    """The paper example's lowest 10 against reference.json: largest relative error, and
    where the kernel came from."""
    import mstmm

    data = Path(__file__).resolve().parent / "data"
    raw = json.loads((data / "reference.json").read_text())
    exact = np.array([float(w) for w in raw["wu_chou_1998"]["omega"]])
    scene = mstmm.load_scene(data / "wu_chou_1998.toml")
    sol = mstmm.solve(scene, modes=len(exact), shapes=False)
    if not (sol.count_checked and all(sol.converged)):
        raise SystemExit("the solve was not certified")
    error = float(np.max(np.abs(sol.omega - exact) / exact))
    return {"error": error, "kernel_origin": sol.kernel_origin}


def main(argv: list[str]) -> int:
    if argv[:1] == ["derive"] and len(argv) == 2:
        import sympy

        paths = derive_all(Path(argv[1]))
        print(json.dumps({"sympy": sympy.__version__, "kernels": [str(p) for p in paths]}))
        return 0
    if argv == ["solve"]:
        import sympy

        print(json.dumps({"sympy": sympy.__version__, **solve_paper_example()}))
        return 0
    print("usage: kernel_equivalence.py derive OUT_DIR | solve", file=sys.stderr)
    return 2


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))

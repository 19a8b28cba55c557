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

* ``delta_stable``, ``delta_paper`` (the value ``mantissa * exp(log)``),
  ``u_bar_paper``, ``beam_transfer``, ``beam_transfer_reduced``,
  ``beam_transfer_scaled``, ``evaluate_*``, ``refine_*`` and ``lowest``:
  relative difference at most :data:`RTOL` (next to a root, where the
  characteristic function cancels, relative to the size of its terms: see
  :func:`close`);
* ``count_below`` / ``counts``: exactly equal;
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

#: Functions compared one by one (others are helpers reached through these).
PUBLIC = (
    "delta_stable",
    "delta_paper",
    "count_below",
    "counts",
    "u_bar_paper",
    "beam_transfer",
    "beam_transfer_scaled",
    "evaluate_stable",
    "evaluate_paper",
    "refine_stable",
    "refine_paper",
    "lowest",
    "mode_shapes",
)

HEADER = "Derived by mstmm.derive with SymPy "

_LOADED = itertools.count()


def printed_by(source: str) -> str | None:
    """The SymPy version a kernel source says it was printed with (None if it does not say)."""
    for line in source.splitlines():
        if line.startswith(HEADER):
            return line[len(HEADER) :].strip().rstrip(".")
    return None


def all_topologies() -> list:
    """Every end pair, bare and with spring-masses (32 topologies)."""
    from mstmm.scene import BOUNDARY_KINDS
    from mstmm.topology import Topology

    return [
        Topology(left, right, kinds)
        for left in BOUNDARY_KINDS
        for right in BOUNDARY_KINDS
        for kinds in ((), ("spring_mass",))
    ]


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


def random_parameters(rng: np.random.Generator, spring_mass: bool) -> np.ndarray:
    """[L, EI, mbar, (x, k, m)...] over several decades, attachments anywhere (ends included)."""
    L = 10 ** rng.uniform(-1, 1)
    EI = 10 ** rng.uniform(0, 6)
    mbar = 10 ** rng.uniform(-1, 2)
    p = [L, EI, mbar]
    if spring_mass:
        n = int(rng.integers(1, 6))
        xs = rng.uniform(0, L, n)
        if n > 2:
            xs[0], xs[1] = 0.0, L  # at both ends
            xs[2] = xs[-1]  # two at one x
        for x in np.sort(xs):
            p += [
                float(x),
                EI / L**3 * 10 ** rng.uniform(-2, 3),
                mbar * L * 10 ** rng.uniform(-2, 1),
            ]
    return np.array(p, dtype=float)


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
    """What differs between two printings of one kernel (an empty list: nothing)."""
    ref = python_kernel(reference_source)
    new = python_kernel(candidate_source)
    problems = []
    if _functions(ref) != _functions(new):
        problems.append(f"functions differ: {sorted(_functions(ref) ^ _functions(new))}")
    cr, cn = _constants(ref), _constants(new)
    if cr != cn:
        problems.append(f"constants differ: {cr} != {cn}")
    missing = [f for f in PUBLIC if f not in ref]
    if missing:
        problems.append(f"public functions missing: {missing}")
        return problems
    rng = np.random.default_rng(seed)
    spring_mass = ref["ATTACHMENT_STRIDE"] > 1 or "spring_mass_compound_step" in ref
    for i in range(points):
        p = random_parameters(rng, spring_mass)
        problems += _compare_at(ref, new, p, rng, i)
        if len(problems) > 10:
            break
    return problems


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
        kind = fn.split("_")[1]
        ref[f"evaluate_{kind}"](omegas, p, mant_a, logs_a)
        new[f"evaluate_{kind}"](omegas, p, mant_b, logs_b)
        single = np.array([ref[fn](w, p) for w in omegas])
        if not (np.array_equal(mant_a, single[:, 0]) and np.array_equal(logs_a, single[:, 1])):
            out.append(f"evaluate_{kind} of the reference printing is not {fn} pointwise")
        if not (np.array_equal(np.sign(mant_a), np.sign(mant_b))):
            signs = [
                k
                for k in range(len(omegas))
                if np.sign(mant_a[k]) != np.sign(mant_b[k])
                and abs(mant_a[k]) > 1e-12
                and abs(mant_b[k]) > 1e-12
            ]
            if signs:
                out.append(f"evaluate_{kind} signs differ at {omegas[signs]} {where}")
    for w in omegas:
        a, b = ref["count_below"](w, p), new["count_below"](w, p)
        if a != b:
            out.append(f"count_below({w!r}) {where}: {a} vs {b}")
    ca, cb = np.empty(len(omegas), np.int64), np.empty(len(omegas), np.int64)
    ref["counts"](omegas, p, ca)
    new["counts"](omegas, p, cb)
    if not np.array_equal(ca, cb):
        out.append(f"counts {where}: {ca} vs {cb}")
    for w in omegas[:4]:
        Ua, Ub = ref["u_bar_paper"](w, p), new["u_bar_paper"](w, p)
        if not close(Ua, Ub, scale=np.abs(Ua).max()):
            out.append(f"u_bar_paper({w!r}) {where}: {Ua} vs {Ub}")
    for beta in betas:
        lam = beta / p[0]
        l = p[0] * rng.uniform(0.01, 1.0)
        for fn, args in (
            ("beam_transfer", (lam, l, p[1])),
            ("beam_transfer_scaled", (beta, l / p[0])),
        ):
            Ua, Ub = np.empty((4, 4)), np.empty((4, 4))
            ref[fn](*args, Ua)
            new[fn](*args, Ub)
            if not close(Ua, Ub, scale=np.abs(Ua).max()):
                out.append(f"{fn}{args} {where}: {Ua} vs {Ub}")
    modes = 6
    oa, ob = np.zeros(modes), np.zeros(modes)
    ok_a, ok_b = ref["lowest"](p, modes, oa), new["lowest"](p, modes, ob)
    if ok_a != ok_b or not close(oa, ob):
        out.append(f"lowest {where}: {oa} ({ok_a}) vs {ob} ({ok_b})")
    xs = np.linspace(0.0, p[0], 11)
    nq = (len(p) - 3) // ref["ATTACHMENT_STRIDE"] * ref["MAX_Q"]
    for r in oa[oa > 0][:2]:
        shapes = []
        for k in (ref, new):
            Z, q = np.zeros((1, len(xs), 4)), np.zeros((1, nq))
            gram, part, ratio = np.zeros((1, 1)), np.zeros(1), np.zeros(1)
            k["mode_shapes"](r, p, 1, xs, Z, q, gram, part, ratio)
            v = np.concatenate([Z.ravel(), q.ravel()])
            shapes.append(v / v[np.argmax(np.abs(v))] / np.sqrt(gram[0, 0]) * np.abs(v).max())
        if not close(shapes[0], shapes[1], scale=np.abs(shapes[0]).max()):
            out.append(f"mode_shapes({r!r}) {where}: {shapes[0]} vs {shapes[1]}")
    for kind in ("stable", "paper"):
        roots = oa[(oa > 0)][:2] if kind == "stable" else oa[(oa > 0)][:1]
        for r in roots:
            a, b = r * (1 - 1e-3), r * (1 + 1e-3)
            ra = ref[f"refine_{kind}"](a, b, p, 0.0, 200)
            rb = new[f"refine_{kind}"](a, b, p, 0.0, 200)
            if ra[2] != rb[2] or not close(ra[0], rb[0], rtol=1e-12):
                out.append(f"refine_{kind}({a!r}, {b!r}) {where}: {ra} vs {rb}")
    return out


def derive_all(out_dir: Path) -> list[Path]:
    """Print every topology's kernel with the SymPy of this environment into ``out_dir``."""
    from mstmm.derive.emit import kernel_source

    out_dir.mkdir(parents=True, exist_ok=True)
    paths = []
    for topology in all_topologies():
        path = out_dir / f"{topology.key}.py"
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

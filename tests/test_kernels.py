"""Generated kernels against the SymPy objects they were derived from, and their regeneration."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from kernel_equivalence import compare, printed_by
from mstmm.derive import symbolic
from mstmm.derive import symbols as S
from mstmm.derive.bundled import BUNDLED_TOPOLOGIES, generated_dir
from mstmm.derive.emit import kernel_source, numerics_source

import mstmm.catalog
from mstmm.kernels import load_kernel
from mstmm.scene import BOUNDARY_KINDS, scene_from_dict
from mstmm.topology import parameter_vector, topology_of

PAIRS = [(a, b) for a in BOUNDARY_KINDS for b in BOUNDARY_KINDS]


def scene(left: str, right: str, n: int = 2, L: float = 1.3, EI: float = 2.5, mbar: float = 0.7):
    rng = np.random.default_rng(len(left) * 7 + len(right) + n)
    atts = [
        {"type": "spring_mass", "x": float(x), "k": float(k), "m": float(m)}
        for x, k, m in zip(
            rng.uniform(0, L, n),
            EI / L**3 * 10 ** rng.uniform(-1, 2, n),
            mbar * L * 10 ** rng.uniform(-1, 0, n),
        )
    ]
    beam = {"length": L, "EI": EI, "mass_per_length": mbar, "left": left, "right": right}
    return scene_from_dict({"beam": beam, "attachments": atts})


@pytest.mark.parametrize(
    "topology", [None, *BUNDLED_TOPOLOGIES], ids=lambda t: t.kernel_key if t else "euler_bernoulli"
)
def test_regenerated_kernel_is_identical_to_committed(topology):
    """Text under the SymPy that printed the committed kernel, numbers under any other.

    The printed expressions depend on the SymPy version (mstmm accepts a range):
    under another version the fresh kernel must compute what the committed one
    computes (tests/kernel_equivalence.py: every public function at random
    parameters and frequencies, 1e-13 relative, counts exactly).
    """
    name = topology.kernel_key if topology else "euler_bernoulli"
    committed = (generated_dir() / f"{name}.py").read_text()
    fresh = kernel_source(topology) if topology else numerics_source()
    stale = f"generated/{name}.py is stale: run python -m mstmm.derive --bundled"
    printed_with = printed_by(committed)
    assert printed_with is not None, f"generated/{name}.py names no SymPy version"
    if printed_with == sp.__version__:
        assert fresh == committed, stale
    else:
        problems = compare(committed, fresh)
        assert not problems, stale + "\n" + "\n".join(problems)


def test_numeric_comparison_catches_a_changed_coefficient():
    """The check used under other SymPy versions sees a change in the 13th digit."""
    committed = (generated_dir() / "euler_bernoulli.py").read_text()
    target = "(0.5)*t2"
    assert target in committed
    changed = committed.replace(target, "(0.5000000000001)*t2", 1)
    assert compare(committed, changed, points=10)


@pytest.mark.parametrize(
    "left,right", [("clamped", "free"), ("pinned", "sliding"), ("free", "free")]
)
def test_paper_kernel_equals_lambdified_symbolic_u_bar(left, right):
    """u_bar_paper(omega) of the kernel == the SymPy U_bar of paper Eq. (4), lambdified
    (the kernel works in units L = EI = mbar = 1: a beam with those values compares
    entry by entry)."""
    sc = scene(left, right, n=2, L=1.0, EI=1.0, mbar=1.0)
    der = symbolic(sc)
    values = der.parameters(sc)
    lam = S.lam_of_omega().subs(values)
    U_bar = der.U_bar.subs(values).subs(S.lam, lam)
    f = sp.lambdify(S.omega, U_bar, "mpmath")
    kernel = load_kernel(topology_of(sc))
    p = parameter_vector(sc)
    for omega in (0.3, 2.0, 7.5):
        exact = np.array(f(omega).tolist(), dtype=float)
        got = kernel.u_bar(omega, p)
        assert np.allclose(got, exact, rtol=1e-12, atol=1e-12 * np.abs(exact).max())


def _value(pair):
    mant, log = pair
    return mant * np.exp(log)


@pytest.mark.parametrize("left,right", PAIRS)
def test_stable_and_paper_determinants_differ_by_a_constant(left, right):
    """Same roots, no poles: delta_stable / delta_paper is +-1 at every omega.

    Both work on [Y/L, theta, M L/EI, Q L^2/EI], and each spring-mass's pole factor
    B00 is the paper's geometric-equation entry (Cq), multiplied out once in the chain.
    """
    sc = scene(left, right, n=3)
    kernel = load_kernel(topology_of(sc))
    p = parameter_vector(sc)
    L, EI = p[0], p[1]
    expected = 1.0
    ratios = []
    for omega in np.linspace(0.05, 3.0, 13) * np.sqrt(EI / (p[2] * L**4)) * 10:
        a = _value(kernel.delta(omega, p, "stable"))
        b = _value(kernel.delta(omega, p, "paper"))
        ratios.append(a / b)
    ratios = np.array(ratios)
    assert np.allclose(np.abs(ratios), expected, rtol=1e-9)
    assert np.all(np.sign(ratios) == np.sign(ratios[0]))


def test_solve_path_does_not_import_sympy():
    """Nor SciPy's optimize (0.35 s of every fresh process when ``mstmm.bands`` imported
    it at the top)."""
    code = (
        "import sys, mstmm\n"
        "s = mstmm.load_scene(mstmm.example_path('wu_chou_1998'))\n"
        "sol = mstmm.solve(s, modes=3)\n"
        "assert 'sympy' not in sys.modules, 'sympy imported'\n"
        "assert 'scipy.optimize' not in sys.modules, 'scipy.optimize imported'\n"
        "print(len(sol.omega))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "3"


def test_kernel_carries_only_what_the_scene_needs():
    bare = kernel_source(BUNDLED_TOPOLOGIES[1])
    with_sm = kernel_source(BUNDLED_TOPOLOGIES[0])
    assert "spring_mass" not in bare.split('"""', 2)[2]
    assert "KINDS = ('spring_mass',)" in with_sm
    assert "if tag == 0:" in with_sm and "if tag ==" not in bare


def test_stages_run_in_one_direction():
    """derive prints, signs and writes kernels; the runtime finds and loads them. Both stand
    on the SymPy-free ground floor (``mstmm.catalog``, ``mstmm.sign``, the kinds'
    declarations in ``mstmm.kinds``, the physics declarations in ``mstmm.physics``): no
    module of mstmm.derive imports any other part of
    the runtime, and the ground floor imports nothing of mstmm.derive at import time
    (a kind's energy imports SymPy and derive's descriptor inside its function)."""
    import ast

    from mstmm.derive.bundled import generated_dir

    ground = {"mstmm.catalog", "mstmm.sign", "mstmm.kinds", "mstmm.physics"}

    def imported(path):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                if node.module == "mstmm":
                    yield from (f"mstmm.{a.name}" for a in node.names)
                else:
                    yield node.module
            elif isinstance(node, ast.Import):
                yield from (a.name for a in node.names)

    root = generated_dir().parent / "derive"
    for path in root.rglob("*.py"):
        for name in imported(path):
            if name == "mstmm" or name.startswith("mstmm."):
                top = ".".join(name.split(".")[:2])
                assert top == "mstmm.derive" or top in ground, f"{path.name} imports {name}"
    src = Path(mstmm.catalog.__file__).resolve().parent
    ground_files = [src / "catalog.py", src / "sign.py", *sorted((src / "kinds").glob("*.py"))]
    ground_files += sorted((src / "physics").rglob("*.py"))
    for path in ground_files:
        tree = ast.parse(path.read_text())
        for node in tree.body:  # module level only
            if isinstance(node, ast.ImportFrom) and node.module:
                assert not node.module.startswith("mstmm.derive"), f"{path.name}: {node.module}"

"""The field transfer matrix of a segment from its differential equation
(``mstmm.numerics.field``; issue 21 item 2, the base of issue 22's segment kinds).

Independent checks: Euler-Bernoulli's ``exp(A h)`` against the closed form of paper
Eq. (1) (SymPy's cosh/cos, evaluated by mpmath at 30 digits); the general field matrix
(Timoshenko, axial force, foundation, both signs of every branch: below and above the
Timoshenko cut-off, tension and compression) against mpmath's ``expm`` at 30 digits; the
second compound ``exp(A2 h)`` against the 2 x 2 minors of mpmath's ``exp(A h)``; the
clamped-clamped bound below the first clamped-clamped frequency found by mpmath (the
first sign change of the determinant of the clamped-clamped block of ``exp(A h)``), and
not far below it.
"""

from __future__ import annotations

import itertools
import math

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mstmm.numerics import field

mpmath.mp.dps = 30
PAIRS = list(itertools.combinations(range(4), 2))


def general_A(EI, kGA, rhoI, mbar, P, kw, kG, w2, mp=False):
    """``Z' = A Z`` over ``[Y, psi, M, Q]`` (paper signs: ``M' = Q`` and
    ``Q' = mbar w^2 Y`` for Euler-Bernoulli) of a Timoshenko beam under the axial force P
    (tension positive) on a Winkler (kw) and Pasternak (kG) foundation; written here from
    the energies, independently of ``derive/segments``."""
    one = mpmath.mpf(1) if mp else 1.0
    t = P + kG
    if math.isinf(kGA):
        a01, a03, a21, a23 = one, 0 * one, t * one, one
    else:
        g = kGA + t
        a01, a03 = kGA * one / g, -one / g
        a21, a23 = kGA * t * one / g - rhoI * w2, kGA * one / g
    rows = [
        [0, a01, 0, a03],
        [0, 0, one / EI, 0],
        [0, a21, 0, a23],
        [(mbar * w2 - kw) * one, 0, 0, 0],
    ]
    return mpmath.matrix(rows) if mp else np.array(rows, dtype=float)


def _expm(A, h, complex_=False):
    U = np.zeros(A.shape, dtype=A.dtype)
    field.expm_short(A, h, field.wavenumber(A) if A.shape[0] == 4 else 1.0, U)
    return U


def _rel(got, want) -> float:
    """Entry-wise error relative to the row and column scale (the state's units differ)."""
    want = np.array(want.tolist(), dtype=complex).reshape(got.shape)
    scale = np.sqrt(np.outer(np.max(abs(want), axis=1), np.max(abs(want), axis=0)))
    return float(np.max(abs(got - want) / scale))


@pytest.mark.parametrize("beta_h", [1e-6, 0.01, 0.5, 1.0, 2.0, 4.0])
def test_euler_bernoulli_against_paper_eq_1(beta_h):
    import sympy as sp
    from mstmm.derive.segments import euler_bernoulli as eb

    beta = 3.7
    h = beta_h / beta
    U = _expm(general_A(1.0, math.inf, 0.0, 1.0, 0.0, 0.0, 0.0, beta**4), h)
    closed = eb.transfer_matrix(sp.Float(beta, 40), sp.Float(h, 40), 1)  # paper Eq. (1)
    want = np.array([[complex(e.evalf(40)) for e in row] for row in closed.tolist()])
    assert _rel(U, want) < 5e-15


CASES = {
    # EI, kGA, rhoI, mbar, P, kw, kG, omega^2 (kernel-like units)
    "timoshenko below cut-off": (1.0, 400.0, 2e-3, 1.0, 0.0, 0.0, 0.0, 5.0e3),
    "timoshenko above cut-off": (1.0, 400.0, 2e-3, 1.0, 0.0, 0.0, 0.0, 4.0e5),
    "tension": (1.0, math.inf, 0.0, 1.0, 50.0, 0.0, 0.0, 800.0),
    "compression": (1.0, math.inf, 0.0, 1.0, -5.0, 0.0, 0.0, 800.0),
    "compression beyond buckling": (1.0, math.inf, 0.0, 1.0, -60.0, 0.0, 0.0, 0.5),
    "winkler below its cut-off": (1.0, math.inf, 0.0, 1.0, 0.0, 900.0, 0.0, 100.0),
    "pasternak and winkler": (1.0, math.inf, 0.0, 1.0, 0.0, 300.0, 20.0, 1000.0),
    "everything": (2.0, 300.0, 1e-3, 1.5, -3.0, 50.0, 4.0, 2.0e5),
}


@pytest.mark.parametrize("name", sorted(CASES))
@pytest.mark.parametrize("kh", [0.05, 1.0, 2.5])
def test_general_field_against_mpmath(name, kh):
    args = CASES[name]
    A = general_A(*args)
    h = kh / field.wavenumber(A)
    want = mpmath.expm(general_A(*args, mp=True) * h)
    assert _rel(_expm(A, h), want) < 1e-13
    # the second compound: exp(A2 h) against the minors of mpmath's exp(A h)
    A2 = np.zeros((6, 6))
    field.additive_compound(A, A2)
    C = np.zeros((6, 6))
    k = field.wavenumber(A)
    field.expm_short(A2, h, k, C)
    minors = mpmath.matrix(6, 6)
    for a, (i, j) in enumerate(PAIRS):
        for b, (r, s) in enumerate(PAIRS):
            minors[a, b] = want[i, r] * want[j, s] - want[i, s] * want[j, r]
    assert _rel(C, minors) < 1e-13


def test_complex_field_is_the_same_code():
    args = CASES["everything"]
    A = general_A(*args).astype(complex)
    A[1, 2] = 1.0 / (args[0] * (1.0 + 0.02j))  # a loss factor on the bending stiffness
    h = 1.5 / field.wavenumber(A)
    want = mpmath.expm(mpmath.matrix(A.tolist()) * h)
    assert _rel(_expm(A, h), want) < 1e-13


def _field_exp(A, h):
    """``segment.field_exp`` (the Cayley-Hamilton series the walks use) of A over h."""
    from mstmm.numerics import segment

    F = np.zeros((4, 4, 4), dtype=A.dtype)
    F[0] = A
    F[1] = A @ A
    F[2] = F[1] @ A
    a = -0.5 * np.trace(F[1])
    b = np.linalg.det(A)
    F[3, 0, :3] = a, b, max(math.sqrt(abs(a) + math.sqrt(abs(b))), 1.0)
    U = np.zeros((4, 4), dtype=A.dtype)
    segment.field_exp(F, h, U)
    E = np.zeros((6, 6), dtype=A.dtype)
    segment.second_compound(U, E)
    return U, E


@pytest.mark.parametrize("name", sorted(CASES))
@pytest.mark.parametrize("kh", [1e-7, 0.05, 0.5, 1.0])
def test_walk_exponential_against_mpmath(name, kh):
    """The walks' ``exp(A h)`` (``segment.field_exp``: no eigenvalue, no squaring) and its
    second compound against mpmath's ``expm`` and its minors, on every branch, for the
    pieces the walks form (k h <= 1)."""
    args = CASES[name]
    A = general_A(*args)
    h = kh / max(field.wavenumber(A), 1.0)
    want = mpmath.expm(general_A(*args, mp=True) * h)
    U, E = _field_exp(A, h)
    assert _rel(U, want) < 1e-14
    minors = mpmath.matrix(6, 6)
    for a, (i, j) in enumerate(PAIRS):
        for b, (r, s) in enumerate(PAIRS):
            minors[a, b] = want[i, r] * want[j, s] - want[i, s] * want[j, r]
    assert _rel(E, minors) < 1e-14


def test_walk_exponential_complex():
    args = CASES["everything"]
    A = general_A(*args).astype(complex)
    A[1, 2] = 1.0 / (args[0] * (1.0 + 0.02j))  # a loss factor on the bending stiffness
    h = 0.9 / field.wavenumber(A)
    want = mpmath.expm(mpmath.matrix(A.tolist()) * h)
    assert _rel(_field_exp(A, h)[0], want) < 1e-14


def _first_clamped_clamped(args, h) -> float:
    """The lowest omega^2 at which the piece clamped at both ends has a mode: the first
    sign change (real part) of det of exp(A h)'s block from [M, Q] to [Y, psi], bracketed
    on a fine grid in omega and refined by bisection (mpmath, 30 digits)."""

    def f(w2):
        U = mpmath.expm(general_A(*args[:-1], w2, mp=True) * h)
        return U[0, 2] * U[1, 3] - U[0, 3] * U[1, 2]

    grid = np.geomspace(1e-3, 1e12, 700)
    prev = f(grid[0])
    for lo, hi in zip(grid[:-1], grid[1:]):
        cur = f(hi)
        if mpmath.sign(cur) != mpmath.sign(prev):
            a, b = mpmath.mpf(lo), mpmath.mpf(hi)
            for _ in range(60):
                m = (a + b) / 2
                if mpmath.sign(f(m)) == mpmath.sign(prev):
                    a = m
                else:
                    b = m
            return float(a)
        prev = cur
    raise AssertionError("no clamped-clamped frequency below 1e12")


@pytest.mark.parametrize(
    "name", ["timoshenko below cut-off", "tension", "compression", "everything"]
)
@pytest.mark.parametrize("h", [0.05, 0.2])
def test_clamped_clamped_bound_is_a_lower_bound(name, h):
    EI, kGA, rhoI, mbar, P, kw, kG, _ = CASES[name]
    bound = field.clamped_clamped_bound(EI, kGA, rhoI, mbar, P + kG, h)
    exact = _first_clamped_clamped(CASES[name], h)
    assert 0.0 < bound <= exact
    assert bound >= 0.02 * exact  # a bound, but not a useless one


@settings(max_examples=15, deadline=None)
@given(
    st.floats(0.5, 4.0),
    st.floats(50.0, 5e4),
    st.floats(1e-5, 1e-2),
    st.floats(0.5, 3.0),
    st.floats(-3.0, 30.0),
    st.floats(0.02, 0.3),
)
def test_clamped_clamped_bound_random(EI, kGA, rhoI, mbar, P, h):
    """No clamped-clamped mode below the bound: the determinant keeps its sign on a fine
    grid up to it (what J0 = 0 needs)."""
    bound = field.clamped_clamped_bound(EI, kGA, rhoI, mbar, P, h)
    if not bound > 0.0:
        return
    A = general_A(EI, kGA, rhoI, mbar, P, 0.0, 0.0, 0.0, mp=True)

    def f(w2):
        A[2, 1] = general_A(EI, kGA, rhoI, mbar, P, 0.0, 0.0, w2, mp=True)[2, 1]
        A[3, 0] = mbar * w2
        U = mpmath.expm(A * h)
        return mpmath.sign(U[0, 2] * U[1, 3] - U[0, 3] * U[1, 2])

    signs = {f(w2) for w2 in np.geomspace(1e-6 * bound, bound, 120)}
    assert len(signs) == 1


def test_declared_fields_are_the_equations_written_here():
    """``derive/segments``' declared differential equations (SymPy) equal the ones written
    above from the energies, at random values; the general one reduces to
    Euler-Bernoulli's with its optional terms left out."""
    import sympy as sp
    from mstmm.derive.segments import euler_bernoulli, general

    rng = np.random.default_rng(3)
    for _ in range(20):
        EI, kGA, rhoI, mbar, w2 = rng.uniform(0.5, 3.0, 5) * [1, 300, 1e-3, 1, 1e3]
        P, kw, kG = rng.uniform(-5.0, 50.0), rng.uniform(0, 100), rng.uniform(0, 10)
        values = dict(EI=EI, kGA=kGA, rhoI=rhoI, mbar=mbar, t=P + kG, k_w=kw, w2=w2)
        got = np.array(general.field(values).evalf(), dtype=float)
        np.testing.assert_allclose(got, general_A(EI, kGA, rhoI, mbar, P, kw, kG, w2), rtol=1e-14)
        plain = dict(EI=EI, mbar=mbar, w2=w2)
        assert (general.field(plain) - euler_bernoulli.field(plain)).is_zero_matrix
    symbols = {name: sp.Symbol(name, positive=True) for name in ("EI", "mbar", "w2")}
    assert sp.simplify(general.field(symbols) - euler_bernoulli.field(symbols)) == sp.zeros(4, 4)


def _euler_lagrange_field(terms, shear: bool):
    """``A`` of ``Z' = A Z`` (Z = [w, psi, M, Q]) derived here by SymPy from the energies
    per length the term files declare (their POTENTIAL and KINETIC quadratic forms, each
    times a symbol), plus bending ``EI psi'^2`` and ``mbar w^2`` kinetic: with shear the
    canonical (Hamiltonian) form of L(w, psi, w', psi'), M = dL/dpsi', Q = -dL/dw';
    without, psi = w' and Ostrogradsky's form of L(w, w', w''), M = dL/dw'',
    Q = M' - dL/dw' (the signs of paper Eq. (1))."""
    import sympy as sp

    w, w1, psi, psi1, w2, EI, mbar = sp.symbols("w w1 psi psi1 w2 EI mbar")
    field = {"w": w, "w'": w1, "psi": psi, "psi'": psi1}
    values = {t.name: sp.Symbol(t.name) for t in terms}
    V = EI * psi1**2 / 2
    T = mbar * w**2 / 2
    for t in terms:
        module = __import__(f"mstmm.physics.terms.{t.file.split('/')[-1][:-3]}", fromlist=["x"])
        for (a, b), c in getattr(module, "POTENTIAL", {}).items():
            V += values[t.name] * c * field[a] * field[b] * (1 if a == b else 2) / 2
        for (a, b), c in getattr(module, "KINETIC", {}).items():
            T += values[t.name] * c * field[a] * field[b] * (1 if a == b else 2) / 2
    L = V - w2 * T  # the amplitude equations at omega^2 = w2
    Y, th, M, Q = sp.symbols("Y th M Q")
    if shear:
        pw, pp = sp.diff(L, w1), sp.diff(L, psi1)
        sol = sp.solve([sp.Eq(pw, -Q), sp.Eq(pp, M)], [w1, psi1], dict=True)[0]
        dM = sp.diff(L, psi).subs(sol)
        dQ = -sp.diff(L, w).subs(sol)
        rows = [sol[w1], sol[psi1], dM, dQ]
    else:
        L = L.subs(psi, w1).subs(psi1, sp.Symbol("w2dd"))
        w2dd = sp.Symbol("w2dd")
        # M = dL/dw'', M' = Q + dL/dw', Q' = dL/dw (amplitudes: -omega^2 terms in L)
        sol = sp.solve(sp.Eq(sp.diff(L, w2dd), M), w2dd, dict=True)[0]
        rows = [w1, sol[w2dd], Q + sp.diff(L, w1), -sp.diff(L, w)]
    sub = {w: Y, psi: th}
    if not shear:
        sub = {w: Y, w1: th}
    rows = [sp.expand(sp.sympify(r).subs(sub)) for r in rows]
    A = sp.Matrix([[sp.diff(r, z) for z in (Y, th, M, Q)] for r in rows])
    return A, values, EI, mbar, w2


@pytest.mark.parametrize("shear", [True, False])
def test_the_field_is_the_euler_lagrange_equations_of_the_declared_terms(shear):
    """``derive/segments/general.py`` writes A from the role sums; SymPy's Euler-Lagrange
    equations of the summed energies the term files declare give the same A, term by
    term (every file of ``mstmm/physics/terms/``, and a rotational foundation psi^2 that
    no built-in term has, through its role)."""
    import sympy as sp
    from mstmm.derive.segments import general

    from mstmm.physics import segment as segment_terms

    terms = [t for t in segment_terms.terms() if shear or t.role != "shear"]
    A, values, EI, mbar, w2 = _euler_lagrange_field(terms, shear)
    sums: dict = {}
    symbol = {"shear": "kGA", "rotary": "rhoI", "tension": "t", "rotational": "r"}
    symbol["foundation"] = "k_w"
    for t in terms:
        sums[symbol[t.role]] = sums.get(symbol[t.role], 0) + values[t.name]
    declared = general.field({"EI": EI, "mbar": mbar, "w2": w2, **sums})
    assert sp.simplify(A - declared) == sp.zeros(4, 4)
    r = sp.Symbol("r")
    with_r = general.field({"EI": EI, "mbar": mbar, "w2": w2, **sums, "r": r})
    assert sp.simplify(with_r - declared)[2, 1] == r  # psi^2 stiffness: M' gains r psi


def test_a_field_with_the_other_zero_pattern_is_refused(monkeypatch):
    """``numerics.segment`` computes A^2, A^3 and exp(A h) only where a field of the
    pattern A[i, j] = 0 for i + j even has them; a segment kind whose field breaks it is
    refused when its functions are printed, not computed wrongly."""
    import sympy as sp
    from mstmm.derive import emit

    emit._general_field_lines(shear=True)  # the built-in field: accepted
    declared = emit.general.field

    def broken(values):
        A = declared(values)
        A[0, 0] = values["w2"]  # a term on the diagonal
        return A

    monkeypatch.setattr(emit.general, "field", broken)
    with pytest.raises(ValueError, match="i \\+ j is even"):
        emit._general_field_lines(shear=True)
    assert isinstance(declared({"EI": 1, "mbar": 1, "w2": sp.Symbol("w2")}), sp.Matrix)

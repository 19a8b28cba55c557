"""Symbolic checks of the derivation: closed-form frequency equations and matrix identities."""

from __future__ import annotations

import random

import mpmath
import pytest
import sympy as sp
from mstmm.derive import special, symbolic
from mstmm.derive import symbols as S
from mstmm.derive.compound import second_compound
from mstmm.derive.segments import euler_bernoulli as beam

from mstmm.kinds import spring_mass
from mstmm.scene import scene_from_dict

b = sp.Symbol("b", positive=True)


def bare(left: str, right: str):
    beam_ = {"length": 1.0, "EI": 1.0, "mass_per_length": 1.0, "left": left, "right": right}
    return scene_from_dict({"beam": beam_})


def det_in_b(left: str, right: str) -> sp.Expr:
    """det U_bar of a bare beam of length l_1 with lam * l_1 = b."""
    d = symbolic(bare(left, right)).determinant()
    l1 = S.indexed("l", 1)
    return sp.simplify(d.subs(l1, b / S.lam))


def test_cantilever_determinant_is_multiple_of_frequency_equation():
    """Clamped-free: det U_bar = c (1 + cos b cosh b), b = lam L, c a non-zero constant."""
    ratio = sp.simplify(det_in_b("clamped", "free") / (1 + sp.cos(b) * sp.cosh(b)))
    assert not ratio.has(b)
    assert ratio != 0


def test_pinned_pinned_determinant_is_sin_family():
    """Pinned-pinned: det U_bar = c(lam) sin b sinh b, zero exactly at b = n pi."""
    d = det_in_b("pinned", "pinned")
    ratio = sp.simplify(d / (sp.sin(b) * sp.sinh(b)))
    assert not ratio.has(b)
    assert ratio != 0


def test_clamped_clamped_determinant():
    """Clamped-clamped: proportional to 1 - cos b cosh b."""
    ratio = sp.simplify(det_in_b("clamped", "clamped") / (1 - sp.cos(b) * sp.cosh(b)))
    assert not ratio.has(b) and ratio != 0


def test_beam_matrix_group_property_and_unit_determinant():
    """U(l1) U(l2) = U(l1 + l2) and det U = 1 (numerically at random points, 30 digits)."""
    l1, l2 = sp.symbols("l1 l2", positive=True)
    U = lambda l: beam.transfer_matrix(S.lam, l, S.EI)  # noqa: E731
    rng = random.Random(1)
    for _ in range(5):
        vals = {
            S.lam: sp.Rational(rng.randint(10, 500), 100),
            l1: sp.Rational(rng.randint(10, 200), 100),
            l2: sp.Rational(rng.randint(10, 200), 100),
            S.EI: sp.Rational(rng.randint(50, 500), 100),
        }
        lhs = (U(l1) * U(l2)).subs(vals).evalf(40)
        rhs = U(l1 + l2).subs(vals).evalf(40)
        assert max(abs(x) for x in (lhs - rhs)) < 1e-25 * max(abs(x) for x in rhs)
        assert abs(U(l1).subs(vals).evalf(40).det() - 1) < 1e-25


def test_reduced_beam_matrix_equals_printed_one():
    """Eq. (1) with K0..K3 substituted back is Eq. (1) as printed."""
    x = S.lam * S.l
    back = {K: f.closed.subs(special.x, x) for K, f in zip(S.K, special.KRYLOV, strict=True)}
    red = beam.transfer_matrix_reduced(S.lam, S.l, S.EI, S.K).subs(back)
    diff = (red - beam.transfer_matrix(S.lam, S.l, S.EI)).applyfunc(sp.simplify)
    assert diff == sp.zeros(4, 4)


def test_compound_of_beam_matches_minors():
    """The rewritten compound (E, F1..F4) equals C2 of Eq. (1) in units L = EI = 1."""
    C = beam.compound_nondimensional(S.beta, S.rho, S.E, S.F)
    direct = second_compound(beam.transfer_matrix(S.beta, S.rho, sp.Integer(1)))
    rng = random.Random(2)
    for _ in range(4):
        beta = sp.Rational(rng.randint(20, 600), 100)
        rho = sp.Rational(rng.randint(5, 100), 100)
        x = beta * rho
        vals = {S.beta: beta, S.rho: rho, S.E: 1}
        vals.update({F: f.closed.subs(special.x, x) for F, f in zip(S.F, special.COMPOUND)})
        a = C.subs(vals).evalf(40)
        d = direct.subs({S.beta: beta, S.rho: rho}).evalf(40)
        assert max(abs(u - v) for u, v in zip(a, d)) < 1e-18 * max(abs(v) for v in d)


def test_series_of_reduced_functions_match_closed_forms_at_threshold():
    """Truncated series vs the closed form evaluated with 50 digits, below the threshold."""
    mpmath.mp.dps = 50
    for f in special.KRYLOV + special.COMPOUND:
        coeffs = f.series()
        closed = sp.lambdify(special.x, f.closed, "mpmath")
        for x in (1e-6, 0.3, 1.0, special.SERIES_THRESHOLD):
            z = mpmath.mpf(x) ** 4
            ser = sum(mpmath.mpf(a.p) / a.q * z**n for n, a in enumerate(coeffs))
            exact = closed(mpmath.mpf(x))
            assert abs(ser - exact) <= 1e-17 * abs(exact), (f.name, x)


def test_spring_mass_compound_is_pole_free_and_exact():
    """B00 C2(P) is polynomial in omega and equals C2 of the condensed matrix times B00."""
    C, pole = spring_mass.condensed_compound(S.k, S.m, S.omega)
    assert all(sp.denom(sp.together(e)).free_symbols <= {S.k} for e in C)
    impedance = S.k * S.m * S.omega**2 / (S.k - S.m * S.omega**2)
    P = sp.eye(4)
    P[3, 0] = impedance
    diff = (pole * second_compound(P) - C).applyfunc(sp.simplify)
    assert diff == sp.zeros(6, 6)


def test_paper_example_structure():
    """Three branches: U_all is 7x11 (one unknown per branch) and U_bar 7x7 (paper Eq. (4))."""
    scene = scene_from_dict(
        {
            "beam": {
                "length": 1,
                "EI": 1,
                "mass_per_length": 1,
                "left": "clamped",
                "right": "free",
            },
            "attachments": [
                {"type": "spring_mass", "x": x, "k": 1, "m": 1} for x in (0.1, 0.4, 0.8)
            ],
        }
    )
    der = symbolic(scene)
    assert der.U_all.shape == (7, 11)
    assert der.U_bar.shape == (7, 7)
    assert [str(z) for z in der.Z_bar] == [
        "M_1",
        "Q_1",
        "Y_tip1",
        "Y_tip2",
        "Y_tip3",
        "Y_root",
        "theta_root",
    ]


KIND_SCENES = {
    "mass": [{"type": "mass", "x": 0.6, "m": 0.4, "J": 0.02}],
    "spring": [{"type": "spring", "x": 0.3, "k": 40.0}],
    "rotational_spring": [{"type": "rotational_spring", "x": 0.3, "k": 4.0}],
    "support": [{"type": "support", "x": 0.45}],
    "hinge": [{"type": "hinge", "x": 0.45, "k": 2.0}],
    "oscillator_chain": [
        {"type": "oscillator_chain", "x": 0.7, "k": [300.0, 90.0], "m": [0.2, 0.1]}
    ],
    "stepped": [],
}


@pytest.mark.parametrize("kind", sorted(KIND_SCENES))
def test_symbolic_u_bar_of_every_kind_vanishes_at_the_reference_frequencies(kind):
    """``symbolic(scene)`` (paper Eqs. (2)-(4) for any chain of kinds): det U_bar, evaluated
    in mpmath, is zero at the reference model's frequencies and not 1e-6 away."""
    import reference_model as ref

    beam = {"left": "clamped", "right": "pinned"}
    if kind == "stepped":
        beam["segments"] = [
            {"length": 0.4, "EI": 2.0, "mass_per_length": 1.5},
            {"length": 0.6, "EI": 0.7, "mass_per_length": 0.8},
        ]
    else:
        beam.update(length=1.0, EI=1.0, mass_per_length=1.0)
    data = {"beam": beam, "attachments": KIND_SCENES[kind]}
    der = symbolic(scene_from_dict(data))
    values = der.parameters(scene_from_dict(data))
    U = der.U_bar.subs(values)
    if kind != "stepped":
        U = U.subs(S.lam, S.lam_of_omega().subs(values))
    f = sp.lambdify(S.omega, U, "mpmath")
    with mpmath.workdps(40):
        for w in ref.frequencies(data, 3, dps=40):
            at = abs(mpmath.det(mpmath.matrix(f(w))))
            near = min(
                abs(mpmath.det(mpmath.matrix(f(w * (1 + s * mpmath.mpf("1e-6")))))) for s in (-1, 1)
            )
            # the root within ~1e-12 relative (the scene values are doubles)
            assert at < mpmath.mpf("1e-6") * near, (kind, w, at, near)

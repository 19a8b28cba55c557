"""Checks of the damped references of tests/reference_model.py (damped_frequencies,
damped_count, damped_zero_count, damped_global_determinant, frf) against closed forms
solved here with mpmath, physical limits and exact properties.  Not tests of mstmm.

Closed forms used (time dependence exp(i w t), w = w_d + i sigma, sigma > 0 decays):

* Loss factor on a uniform beam with no attachments: EI -> EI (1 + i eta) scales the
  whole stiffness, so every root is ``w_n sqrt(1 + i eta)`` (principal root), w_n the
  undamped one; pinned-pinned: ``w_n = (n pi / L)^2 sqrt(EI / mbar)``.
* A spring-dashpot-mass (k, c, m) at a clamped or pinned end sees W = 0: it is a decoupled
  oscillator, ``k + i w c - m w^2 = 0``: ``w = i c / (2m) + sqrt(k/m - (c/2m)^2)``; if
  ``c^2 > 4 k m`` (overdamped) two roots on the imaginary axis,
  ``w = i (c +- sqrt(c^2 - 4 k m)) / (2 m)``.  At the middle of a clamped-clamped beam the
  root tends to the same as EI -> infinity, the gap falling like k / k_beam ~ 1 / EI.
* n identical absorbers at one point: their differences leave the beam at rest, a root
  of ``k + i w c - m w^2 = 0`` of multiplicity n - 1.
* A grounded dashpot c at the middle of a free-free beam (length 2a): the modes
  antisymmetric about it do not move it (the undamped free-free roots, real); the
  symmetric ones solve ``2 K_h(w) + i w c = 0`` with the dynamic stiffness of a half
  beam, free at one end and sliding at the other, at its sliding end
  ``K_h = -EI lam^3 (sinh x cos x + sin x cosh x) / (1 + cosh x cos x)``, ``x = lam a``,
  ``lam^4 = mbar w^2 / EI`` (a function of lam^4: any root).  The rigid translation
  becomes an overdamped root, ``~ i c / (mbar L)`` for c small, ``i c^2 / (8 sqrt(EI)
  mbar^(3/2))`` for c large (the dashpot pins its point); the rigid rotation stays at 0.
  Off the centre (distance d, small c): ``sigma = c (1 / m + d^2 / I)``.
* A two-stage chain with dashpots at a clamped end: a quartic in w (in its test).
* The characteristic function is entire: Cauchy-Riemann holds across w_d = 0, where
  z = W^2 crosses the branch cut of the principal fourth root.
* The zero of the characteristic function at w = 0 has order ``2 n_rigid - r``, r the
  number of rigid motions the grounded dashpots restrain (a Jordan chain of length 2 per
  free rigid mode, 1 per restrained one).
* Cantilever tip receptance (EI -> EI (1 + i eta) with a loss factor, b^4 = mbar w^2 / EI):
  ``H = W(L) / F = (sin bL cosh bL - cos bL sinh bL) / (EI b^3 (1 + cos bL cosh bL))``,
  static limit ``L^3 / (3 EI)`` (derived in test_cantilever_tip_receptance).  Statics:
  a tip force gives ``W = F x^2 (3L - x) / (6 EI)``, ``W' = F x (2L - x) / (2 EI)``; a
  tip couple ``W = C x^2 / (2 EI)``, ``W' = C x / EI``.  An absorber (k* = k + i w c, m)
  at the tip, forced on its mass: ``u / F = (1 + k* H) / (k* - m w^2 - m w^2 k* H)``,
  ``W(L) / F = k* H / (k* - m w^2 - m w^2 k* H)``.
* Reciprocity (K*, C, M symmetric): ``H_YF(a, b) = H_YF(b, a)``,
  ``H_thetaF(a, b) = H_YM(b, a)``, and likewise between a beam point and a hanging mass.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # the FE seeds' small dense eigvals

import sys  # noqa: E402
from pathlib import Path  # noqa: E402

import mpmath  # noqa: E402
import pytest  # noqa: E402
from hypothesis import HealthCheck, Phase, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402
from mpmath import mp, mpc, mpf  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))

import reference_model as ref  # noqa: E402
from reference_model import (  # noqa: E402
    damped_count,
    damped_frequencies,
    damped_global_determinant,
    damped_zero_count,
    frequencies,
    frf,
)


@pytest.fixture(autouse=True)
def _precise_arithmetic():
    """Expected values and tolerances at 50 digits (the default 15 would hide 1e-30)."""
    with mp.workdps(50):
        yield


def beam(left, right, attachments=(), length=1.0, ei=1.0, mbar=1.0, **extra):
    values = {"length": length, "EI": ei, "mass_per_length": mbar, "left": left, "right": right}
    return {"beam": values | extra, "attachments": list(attachments)}


def absorber(x, k, m, c=0.0):
    return {"type": "spring_mass", "x": x, "k": k, "m": m, "c": c}


def rel(a, b):
    return abs(mpc(a) - mpc(b)) / abs(mpc(b))


def sdof_roots(k, m, c):
    """Roots of k + i w c - m w^2 = 0 with w_d >= 0 (one if underdamped, else two)."""
    k, m, c = mpf(k), mpf(m), mpf(c)  # the floats exactly
    disc = c * c - 4 * k * m
    if disc < 0:
        return [mpc(mpmath.sqrt(-disc) / (2 * m), c / (2 * m))]
    return [mpc(0, (c - mpmath.sqrt(disc)) / (2 * m)), mpc(0, (c + mpmath.sqrt(disc)) / (2 * m))]


def stepped(left, right, segments, attachments=()):
    return {
        "beam": {
            "left": left,
            "right": right,
            "segments": [
                dict(zip(("length", "EI", "mass_per_length"), s[:3])) | s[3] for s in segments
            ],
        },
        "attachments": list(attachments),
    }


# ------------------------------------------------------------------- the basis


def test_krylov_functions_are_entire_in_lam4():
    """The four Krylov functions equal their closed forms with each of the four fourth
    roots of z (no branch matters), on both sides of the switch from the power series
    (|lam x| <= 2) to the closed forms."""
    switch = [mpf(y) * mpc(0, 1) ** q / 2 for y in ("31.99", "32.01") for q in range(4)]
    with mp.workdps(40):
        for z in [mpc(3, 1), mpc(-50, 7), mpc(0, -200), mpf(-90), mpf(1000)] + switch:
            for x in (mpf("0.3"), mpf("0.9"), mpf(1), mpf(2)):
                got = ref._krylov(z, x)
                for q in range(4):
                    lam = mpmath.root(z, 4) * mpc(0, 1) ** q
                    t = lam * x
                    ch, sh, c, s = mpmath.cosh(t), mpmath.sinh(t), mpmath.cos(t), mpmath.sin(t)
                    closed = [(ch + c) / 2, (sh + s) / (2 * lam), (ch - c) / (2 * lam**2)]
                    closed.append((sh - s) / (2 * lam**3))
                    for a, b in zip(got, closed, strict=True):
                        assert abs(a - b) <= mpf(10) ** -32 * max(1, abs(b))


# ------------------------------------------------------------------- closed forms


@pytest.mark.parametrize("eta", [0.03, 0.4])
def test_loss_factor_pinned_pinned_closed_form(eta):
    length, ei, mbar = 1.25, 2.5, 0.75
    sc = beam("pinned", "pinned", length=length, ei=ei, mbar=mbar, loss_factor=eta)
    got = damped_frequencies(sc, 5, dps=30)
    for n, w in enumerate(got, 1):
        wn = (n * mp.pi / mpf(length)) ** 2 * mpmath.sqrt(mpf(ei) / mpf(mbar))
        assert rel(w, wn * mpmath.sqrt(1 + mpc(0, mpf(eta)))) < 1e-28
        assert w.real > 0 and w.imag > 0


def test_loss_factor_on_every_segment_of_a_cantilever():
    """Two segments of one material, both with the same eta: w_n sqrt(1 + i eta)."""
    eta = 0.0625
    sc = stepped(
        "clamped",
        "free",
        [(0.375, 2.0, 3.0, {"loss_factor": eta}), (0.625, 2.0, 3.0, {"loss_factor": eta})],
    )
    undamped = frequencies(beam("clamped", "free", ei=2.0, mbar=3.0), 4, dps=30)
    got = damped_frequencies(sc, 4, dps=30)
    for w, wn in zip(got, undamped, strict=True):
        assert rel(w, wn * mpmath.sqrt(1 + mpc(0, eta))) < 1e-28


UNDAMPED = {
    "cantilever_c0": beam("clamped", "free", [absorber(0.6, 40.0, 0.2, 0.0)], loss_factor=0.0),
    "free_free_dashpot_c0": beam(
        "free", "free", [{"type": "dashpot", "x": 0.3, "c": 0.0}, absorber(0.8, 30.0, 0.1)]
    ),
    "stepped_kinds": stepped(
        "pinned",
        "free",
        [(0.5, 2.0, 1.5, {"loss_factor": 0.0}), (0.75, 1.0, 1.0, {})],
        [
            {"type": "hinge", "x": 0.9, "k": 3.0},
            {"type": "oscillator_chain", "x": 1.25, "k": [50.0, 20.0], "m": [0.1, 0.1]},
            {"type": "mass", "x": 0.25, "m": 0.2, "J": 0.003},
            {"type": "rotational_spring", "x": 0.5, "k": 2.0},
            absorber(0.5, 25.0, 0.1, 0.0),
        ],
    ),
    "three_oscillators": beam("clamped", "free", [absorber(0.5, 20.0, 0.1)] * 3),
}


@pytest.mark.parametrize("name", sorted(UNDAMPED))
def test_undamped_limit_is_the_real_model(name):
    """c = 0, eta = 0: the damped roots are frequencies(), real (sigma exactly 0), the
    characteristic function real on the real axis with zeros there, the receptance real."""
    sc = UNDAMPED[name]
    expected = frequencies(sc, 7, dps=30)
    got = damped_frequencies(sc, 7, dps=30)
    for w, e in zip(got, expected, strict=True):
        assert w.imag == 0
        assert (w.real == 0) == (e == 0)
        if e:
            assert rel(w, e) < 1e-28
    w = expected[-1]
    f0 = damped_global_determinant(sc, w, dps=30)
    f1 = damped_global_determinant(sc, w * (1 + mpf("1e-6")), dps=30)
    assert f0.imag == 0 and f1.imag == 0
    assert abs(f0) < mpf("1e-20") * abs(f1)
    h = frf(sc, ("force", "x", 1.0), ("displacement", "x", 0.4), [0.37 * float(w)], dps=20)[0]
    assert h.imag == 0


def test_undamped_functions_refuse_a_damped_scene():
    for sc in (
        beam("clamped", "free", [absorber(0.5, 10.0, 1.0, 0.5)]),
        beam("clamped", "free", [{"type": "dashpot", "x": 0.5, "c": 0.1}]),
        beam("clamped", "free", loss_factor=0.01),
    ):
        with pytest.raises(ValueError, match="damping"):
            frequencies(sc, 1, dps=15)


@pytest.mark.parametrize("end", ["clamped", "pinned"])
def test_absorber_at_a_fixed_end_is_the_sdof_oscillator(end):
    """Underdamped: its root exactly, the beam's roots untouched (real)."""
    k, m, c = 100.0, 1.5, 2.5
    sc = beam(end, "free" if end == "clamped" else "pinned", [absorber(0.0, k, m, c)])
    (exact,) = sdof_roots(k, m, c)
    bare = frequencies(beam(end, "free" if end == "clamped" else "pinned"), 4, dps=30)
    got = damped_frequencies(sc, 5, dps=30)
    assert sum(rel(w, exact) < 1e-28 for w in got) == 1
    for w, b in zip([w for w in got if rel(w, exact) > 1e-10], bare, strict=True):
        assert rel(w, b) < 1e-28 and abs(w.imag) < mpf(10) ** -30 * abs(b)


def test_overdamped_absorber_gives_two_roots_on_the_imaginary_axis():
    k, m, c = 40.0, 0.5, 12.0  # c^2 = 144 > 4 k m = 80
    sc = beam("pinned", "pinned", [absorber(1.0, k, m, c), absorber(0.5, 30.0, 0.1, 0.2)])
    got = damped_frequencies(sc, 4, dps=30)
    for w, e in zip(got[:2], sdof_roots(k, m, c), strict=True):  # overdamped first
        assert w.real == 0 and rel(w, e) < 1e-28
    assert got[2].real > 0 and got[3].real > got[2].real


def test_absorber_on_a_stiff_beam_tends_to_the_sdof_root():
    k, m, c = 100.0, 1.0, 4.0
    (exact,) = sdof_roots(k, m, c)
    gaps = []
    for ei in (1e3, 1e5, 1e7):
        sc = beam("clamped", "clamped", [absorber(0.5, k, m, c)], ei=ei)
        gaps.append(rel(damped_frequencies(sc, 1, dps=25)[0], exact))
    assert gaps[2] < 1e-7
    for a, b in zip(gaps, gaps[1:]):
        assert 90 < a / b < 110  # ~ k / k_beam ~ 1 / EI


@pytest.mark.parametrize("count", [2, 3])
def test_identical_absorbers_at_one_point(count):
    """n identical damped absorbers: k + i w c - m w^2 = 0 is a root of multiplicity
    n - 1 (the beam at rest), listed n - 1 times and counted n - 1 times by the argument
    principle around it."""
    k, m, c = 50.0, 0.1, 0.2
    sc = beam("clamped", "free", [absorber(0.7, k, m, c)] * count)
    (exact,) = sdof_roots(k, m, c)
    got = damped_frequencies(sc, 5, dps=30)
    assert sum(rel(w, exact) < 1e-28 for w in got) == count - 1
    r = mpf(10) ** -3 * abs(exact)
    n = damped_zero_count(sc, exact.real - r, exact.real + r, exact.imag - r, exact.imag + r)
    assert n == count - 1


def test_damped_chain_at_a_clamped_end_is_its_own_quartic():
    """A two-stage chain with dashpots at a clamped end (W = 0): a_i = k_i + i w c_i,
    (a1 + a2 - m1 w^2)(a2 - m2 w^2) - a2^2 = m1 m2 w^4 - i (m2 c1 + (m1 + m2) c2) w^3
    - (c1 c2 + m2 k1 + (m1 + m2) k2) w^2 + i (k1 c2 + k2 c1) w + k1 k2 = 0."""
    k1, k2, m1, m2, c1, c2 = (mpf(v) for v in (60.0, 20.0, 0.15, 0.1, 0.25, 0.125))
    chain = {"type": "oscillator_chain", "x": 0.0, "k": [60.0, 20.0], "m": [0.15, 0.1]}
    sc = beam("clamped", "free", [chain | {"c": [0.25, 0.125]}])
    i = mpc(0, 1)
    coefficients = [
        m1 * m2,
        -i * (m2 * c1 + (m1 + m2) * c2),
        -(c1 * c2 + m2 * k1 + (m1 + m2) * k2),
        i * (k1 * c2 + k2 * c1),
        k1 * k2,
    ]
    exact = [r for r in mpmath.polyroots(coefficients, maxsteps=200, extraprec=200) if r.real > 0]
    assert len(exact) == 2
    got = damped_frequencies(sc, 4, dps=30)
    for r in exact:
        assert sum(rel(w, r) < 1e-28 for w in got) == 1


def test_characteristic_function_is_analytic_across_the_imaginary_axis():
    """Where z = W^2 crosses the branch cut of the principal fourth root (w_d = 0) the
    function is continuous and satisfies Cauchy-Riemann: dF/dw_d = -i dF/dsigma."""
    sc = stepped(
        "clamped",
        "free",
        [(0.5, 2.0, 1.5, {"loss_factor": 0.05}), (0.5, 1.0, 1.0, {})],
        [{"type": "dashpot", "x": 0.75, "c": 0.2}, absorber(0.3, 30.0, 0.1, 0.1)],
    )
    h = mpf(10) ** -12
    for w in (mpc(0, 3), mpc(0, 40), mpc("1e-15", 7), mpc(-2, 30)):

        def f(z):
            return damped_global_determinant(sc, z, dps=40)

        along = (f(w + h) - f(w - h)) / (2 * h)
        across = (f(w + mpc(0, h)) - f(w - mpc(0, h))) / (2 * h)
        assert abs(along + mpc(0, 1) * across) < mpf(10) ** -20 * abs(along)
        assert abs(f(w + h) - f(w - h)) < mpf(10) ** -10 * abs(f(w))


def _half_beam_stiffness(w, ei, mbar, a):
    lam = mpmath.root(mbar * w**2 / ei, 4)
    x = lam * a
    num = mpmath.sinh(x) * mpmath.cos(x) + mpmath.sin(x) * mpmath.cosh(x)
    return -ei * lam**3 * num / (1 + mpmath.cosh(x) * mpmath.cos(x))


def test_grounded_dashpot_on_a_free_free_beam():
    c, ei, mbar, length = 0.375, 2.0, 1.5, 1.0
    sc = beam("free", "free", [{"type": "dashpot", "x": 0.5, "c": c}], ei=ei, mbar=mbar)
    got = damped_frequencies(sc, 6, dps=30)
    assert got[0] == 0 and got[1] == 0  # two rigid-body modes reported as zeros
    with mp.workdps(45):

        def f(w):
            return 2 * _half_beam_stiffness(w, mpf(ei), mpf(mbar), mpf(length) / 2) + mpc(0, c) * w

        overdamped = mpmath.findroot(f, mpc(0, c / (mbar * length)))
        scale = mpmath.sqrt(mpf(ei) / mpf(mbar))
        symmetric = mpmath.findroot(f, mpc(mpf("4.730040744862704") ** 2 * scale, 0.1))
    assert got[2].real == 0 and rel(got[2], mpc(0, overdamped.imag)) < 1e-28
    assert rel(got[3], symmetric) < 1e-28
    antisymmetric = frequencies(beam("free", "free", ei=ei, mbar=mbar), 4, dps=30)[3]
    assert rel(got[4], antisymmetric) < 1e-28
    # the zero at w = 0: order 2 * 2 - 1 (the dashpot restrains the translation)
    assert damped_zero_count(sc, -0.1, 0.1, -0.1, 0.1) == 3


def test_strong_dashpot_pins_its_point():
    """A large dashpot c at the middle of a free-free beam: the overdamped root relaxes
    the nearly pinned point, 2 K_h(i sigma) = sigma c with K_h -> sqrt(2) EI kappa^3,
    kappa^4 = mbar sigma^2 / EI (a half beam much longer than 1 / kappa): sigma ->
    c^2 / (8 sqrt(EI) mbar^(3/2)), the gap falling like exp(-kappa L / 2)."""
    gaps = []
    for c, ei, mbar in ((50.0, 1.0, 1.0), (100.0, 2.0, 1.5), (200.0, 1.0, 1.0)):
        sc = beam("free", "free", [{"type": "dashpot", "x": 0.5, "c": c}], ei=ei, mbar=mbar)
        w = damped_frequencies(sc, 3, dps=25)[2]
        assert w.real == 0
        gaps.append(rel(w.imag, mpf(c) ** 2 / (8 * mpf(ei) ** 0.5 * mpf(mbar) ** 1.5)))
    assert gaps[0] < 1e-4 and gaps[1] < 1e-5 and gaps[2] < 1e-18  # 4.6e-5, 1.6e-6, 2.5e-21


def test_small_dashpot_damps_the_rigid_motion_it_restrains():
    """A free-free beam (mass m = mbar L, inertia I = m L^2 / 12 about its centre) with a
    small grounded dashpot c at distance d from the centre: the rigid rotation about the
    dashpot stays at 0, the other rigid motion decays at sigma = c (1 / m + d^2 / I) (the
    rigid-body limit of s M_r + c v v^T = 0, v = (1, d)); the elastic modes correct it at
    second order: the relative gap falls like c^2."""
    mbar, length, x = mpf(2), mpf(1.5), mpf(0.3)
    m, inertia, d = mbar * length, mbar * length**3 / 12, x - length / 2
    gaps = []
    for c in (1e-2, 1e-3):
        sc = beam("free", "free", [{"type": "dashpot", "x": 0.3, "c": c}], mbar=2.0, length=1.5)
        w = damped_frequencies(sc, 3, dps=25)
        assert w[:2] == [0, 0] and w[2].real == 0
        gaps.append(rel(w[2].imag, mpf(c) * (1 / m + d * d / inertia)))
    assert gaps[0] < 1e-6 and 90 < gaps[0] / gaps[1] < 110


def test_order_of_the_zero_at_the_origin():
    """2 n_rigid - (rigid motions restrained by grounded dashpots): a free-free beam with a
    free hinge has 3 rigid-body modes; one dashpot restrains 1, two restrain 2."""
    hinge = {"type": "hinge", "x": 0.4}
    for dashpots, order in (([0.7], 5), ([0.7, 0.1], 4), ([], 6)):
        atts = [hinge] + [{"type": "dashpot", "x": x, "c": 0.5} for x in dashpots]
        sc = beam("free", "free", atts)
        assert damped_zero_count(sc, -0.05, 0.05, -0.05, 0.05, dps=20) == order
        assert ref._DampedSolver(sc, 20).a0 == order
    sc = beam("free", "free", [hinge, {"type": "dashpot", "x": 0.7, "c": 0.5}])
    roots = damped_frequencies(sc, 5, dps=20)
    assert roots[:3] == [0, 0, 0] and roots[3].real == 0 and roots[4].real > 0


# --------------------------------------------------------------- the counts


COUNTED = {
    "viscous": beam(
        "clamped",
        "pinned",
        [absorber(0.5, 40.0, 0.1, 5.0), {"type": "dashpot", "x": 0.25, "c": 0.3}],
    ),
    "loss_and_dashpot": stepped(
        "free",
        "free",
        [(0.5, 2.0, 1.5, {"loss_factor": 0.05}), (0.5, 1.0, 1.0, {"loss_factor": 0.01})],
        [{"type": "dashpot", "x": 0.75, "c": 0.2}, absorber(0.3, 30.0, 0.1, 0.1)],
    ),
}


@pytest.mark.parametrize("name", sorted(COUNTED))
def test_count_equals_the_roots_returned_and_one_more_root_adds_one(name):
    sc = COUNTED[name]
    roots = damped_frequencies(sc, 7, dps=20)
    top = 2 * max(w.imag for w in roots) + 1
    for n in (5, 6):  # w_d halfway between root n and root n + 1
        a, b = roots[n - 1].real, roots[n].real
        assert b > a
        assert damped_count(sc, (a + b) / 2, -1, top, dps=20) == n
    # the rectangle's top just below the highest overdamped root leaves that one out
    axis = [w for w in roots if w.real == 0 and w != 0]
    if axis:
        width = (roots[5].real + roots[4].real) / 2
        assert damped_count(sc, width, -1, axis[-1].imag * mpf("0.99"), dps=20) == 4


def test_count_splits_an_overdamped_pair_and_a_loss_factor_root():
    k, m, c = 40.0, 0.5, 12.0
    sc = beam("pinned", "pinned", [absorber(1.0, k, m, c)])
    low, high = sdof_roots(k, m, c)
    width = mpf(5)  # below the first beam root (9.87)
    assert damped_count(sc, width, -1, (low.imag + high.imag) / 2) == 1
    assert damped_count(sc, width, -1, high.imag + 1) == 2
    assert damped_count(sc, width, (low.imag + high.imag) / 2, high.imag + 1) == 1
    assert damped_count(sc, width, low.imag / 2, high.imag + 1) == 2
    eta = 0.1
    sc = beam("pinned", "pinned", loss_factor=eta)
    first = mp.pi**2 * mpmath.sqrt(1 + mpc(0, eta))
    assert damped_count(sc, 20, -1, 5) == 1
    assert damped_count(sc, 20, first.imag * 1.01, 5) == 0
    assert damped_count(sc, 45, -1, 5) == 2


@pytest.mark.parametrize("loss", [0.0, 0.04])
def test_the_count_catches_a_withheld_seed(loss):
    """The certificate has teeth: with any one seed withheld (a root of the 5 lowest, one
    of a double root's two) the argument principle finds more zeros than were polished;
    a double root whose two seeds were split apart, or spurious seeds, still give the
    right roots."""
    sc = beam(
        "clamped",
        "free",
        [absorber(0.7, 50.0, 0.1, 0.2)] * 3 + [{"type": "dashpot", "x": 0.3, "c": 2.0}],
        loss_factor=loss,
    )
    seeds = [mpc(complex(w)) for w in ref._fem().damped_spectrum(sc, 40).roots]
    with mp.workdps(40):
        good = ref._DampedSolver(sc, 20)._certified(5, seeds)
        double = [i for i in range(len(seeds) - 1) if rel(seeds[i], seeds[i + 1]) < 1e-9]
        assert len(double) == 1 and rel(good[2], good[3]) == 0
        for drop in (0, double[0], 4) if loss == 0 else (double[0],):  # ~2 s each
            with pytest.raises(ref._Uncertified, match="zeros in the rectangle"):
                ref._DampedSolver(sc, 20)._certified(5, seeds[:drop] + seeds[drop + 1 :])
        split = list(seeds)
        split[double[0] + 1] *= 1 + mpf("1e-7")
        spurious = sorted(seeds + [mpc(0, 7.5), mpc(5, 3)], key=ref._order_key)
        for bent in (split, spurious):
            got = ref._DampedSolver(sc, 20)._certified(5, bent)
            assert all(rel(a, b) < 1e-18 for a, b in zip(got, good, strict=True))


# ------------------------------------------------------------------ receptance


def _tip_receptance(w, ei, mbar, length, eta=0.0):
    ei_c = mpf(ei) * (1 + mpc(0, eta))
    if w == 0:
        return mpf(length) ** 3 / (3 * ei_c)
    b = mpmath.root(mbar * mpc(w) ** 2 / ei_c, 4)
    x = b * length
    num = mpmath.sin(x) * mpmath.cosh(x) - mpmath.cos(x) * mpmath.sinh(x)
    return num / (ei_c * b**3 * (1 + mpmath.cos(x) * mpmath.cosh(x)))


def test_cantilever_tip_receptance():
    """The closed form: W = A(cosh - cos) + B(sinh - sin) of b x (clamped at 0); free end
    W'' = 0 gives B = -A (cosh + cos) / (sinh + sin) at bL, and the tip force
    EI W'''(L) = -F; then W(L) / F = (sin cosh - cos sinh) / (EI b^3 (1 + cos cosh)),
    which tends to L^3 / (3 EI) (sin cosh - cos sinh ~ 2 (bL)^3 / 3).  Undamped and with a
    loss factor (EI -> EI (1 + i eta), same formula, b^4 = mbar w^2 / EI*)."""
    ei, mbar, length = 2.0, 3.0, 1.5
    for eta in (0.0, 0.05):
        sc = beam("clamped", "free", length=length, ei=ei, mbar=mbar, loss_factor=eta)
        omegas = [0.0, 0.3, 2.0, 5.0, 11.0 + 0.5j]
        got = frf(sc, ("force", "x", length), ("displacement", "x", length), omegas, dps=30)
        for w, h in zip(omegas, got, strict=True):
            assert rel(h, _tip_receptance(w, ei, mbar, length, eta)) < 1e-27
    assert _tip_receptance(1e-6, ei, mbar, length) == pytest.approx(length**3 / (3 * ei))


def test_static_shapes_fix_the_signs():
    ei, length = 2.0, 1.5
    sc = beam("clamped", "free", length=length, ei=ei)
    tip = length
    for x in (0.5, 1.0, 1.5):
        xm = mpf(x)
        cases = [
            (("force", "x", tip), ("displacement", "x", x), xm**2 * (3 * tip - xm) / (6 * ei)),
            (("force", "x", tip), ("rotation", "x", x), xm * (2 * tip - xm) / (2 * ei)),
            (("moment", "x", tip), ("displacement", "x", x), xm**2 / (2 * ei)),
            (("moment", "x", tip), ("rotation", "x", x), xm / ei),
        ]
        for src, dst, exact in cases:
            assert rel(frf(sc, src, dst, [0.0], dps=30)[0], exact) < 1e-28


def test_absorber_at_the_tip_forced_on_its_mass():
    ei, mbar, length, eta = 2.0, 3.0, 1.5, 0.02
    k, m, c = 30.0, 0.25, 0.5
    sc = beam("clamped", "free", [absorber(length, k, m, c)], length, ei, mbar, loss_factor=eta)
    omegas = [0.0, 1.7, 6.0, 13.0]
    u = frf(sc, ("force", "mass", 0), ("displacement", "mass", 0), omegas, dps=30)
    tip = frf(sc, ("force", "mass", 0), ("displacement", "x", length), omegas, dps=30)
    for w, gu, gw in zip(omegas, u, tip, strict=True):
        w = mpf(w)
        h = _tip_receptance(w, ei, mbar, length, eta)
        ks = mpf(k) + mpc(0, w) * mpf(c)
        den = ks - mpf(m) * w**2 - mpf(m) * w**2 * ks * h
        assert rel(gu, (1 + ks * h) / den) < 1e-27
        assert rel(gw, ks * h / den) < 1e-27


def test_absorber_at_a_clamped_end_is_its_own_receptance():
    k, m, c = 30.0, 0.25, 0.5
    sc = beam("clamped", "free", [absorber(0.0, k, m, c), absorber(0.6, 20.0, 0.1, 0.3)])
    for w in (0.5, 9.0 + 1j):
        h = frf(sc, ("force", "mass", 0), ("displacement", "mass", 0), [w], dps=30)[0]
        w = mpc(w)
        assert rel(h, 1 / (mpf(k) + mpc(0, 1) * w * mpf(c) - mpf(m) * w**2)) < 1e-28
        # the hanging masses in x order: the one at 0.6 is number 1
        assert frf(sc, ("force", "mass", 1), ("displacement", "x", 0.0), [w], dps=20)[0] == 0


RECIPROCAL = stepped(
    "clamped",
    "free",
    [(0.4, 3.0, 2.0, {"loss_factor": 0.02}), (0.6, 1.0, 1.0, {"loss_factor": 0.05})],
    [
        {"type": "mass", "x": 1.0, "m": 0.2, "J": 0.01},
        absorber(0.7, 40.0, 0.1, 0.1),
        {"type": "dashpot", "x": 0.25, "c": 0.2},
        {"type": "oscillator_chain", "x": 0.4, "k": [30.0, 20.0], "m": [0.1, 0.05]}
        | {"c": [0.05, 0.0]},
        {"type": "spring", "x": 0.55, "k": 5.0},
    ],
)


@settings(
    max_examples=6,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow],
    phases=[Phase.explicit, Phase.reuse, Phase.generate],  # ~1 s an example: no shrinking
)
@given(
    a=st.floats(0.0, 1.0),
    b=st.floats(0.0, 1.0),
    w=st.floats(0.5, 40.0),
    j=st.integers(0, 2),
)
def test_property_receptance_reciprocity(a, b, w, j):
    def h(src, dst):
        return frf(RECIPROCAL, src, dst, [w], dps=20)[0]

    tol = mpf(10) ** -17
    pairs = [
        (("force", "x", a), ("displacement", "x", b), ("force", "x", b), ("displacement", "x", a)),
        (("force", "x", a), ("rotation", "x", b), ("moment", "x", b), ("displacement", "x", a)),
        (("moment", "x", a), ("rotation", "x", b), ("moment", "x", b), ("rotation", "x", a)),
        (
            ("force", "mass", j),
            ("rotation", "x", a),
            ("moment", "x", a),
            ("displacement", "mass", j),
        ),
        (
            ("force", "mass", j),
            ("displacement", "mass", (j + 1) % 3),
            ("force", "mass", (j + 1) % 3),
        )
        + (("displacement", "mass", j),),
    ]
    for s1, d1, s2, d2 in pairs:
        one, two = h(s1, d1), h(s2, d2)
        assert abs(one - two) <= tol * max(abs(one), abs(two)), (s1, d1)


def test_hinge_and_bad_inputs():
    sc = beam("pinned", "pinned", [{"type": "hinge", "x": 0.5, "k": 2.0}, absorber(0.3, 9.0, 0.1)])
    # a force at a hinge is fine (W continuous), a moment or rotation there is not
    assert frf(sc, ("force", "x", 0.5), ("displacement", "x", 0.5), [1.0], dps=15)[0] != 0
    for src, dst in (
        (("moment", "x", 0.5), ("displacement", "x", 0.2)),
        (("force", "x", 0.2), ("rotation", "x", 0.5)),
        (("force", "mass", 1), ("displacement", "x", 0.2)),
        (("torque", "x", 0.2), ("displacement", "x", 0.2)),
        (("force", "x", 0.2), ("velocity", "x", 0.2)),
        (("force", "x", 2.0), ("displacement", "x", 0.2)),
    ):
        with pytest.raises(ValueError):
            frf(sc, src, dst, [1.0], dps=15)
    for bad in (
        beam("clamped", "free", [absorber(0.5, 1.0, 1.0, -0.1)]),
        beam("clamped", "free", [{"type": "dashpot", "x": 0.5, "c": -1.0}]),
        beam(
            "clamped",
            "free",
            [{"type": "oscillator_chain", "x": 0.5, "k": [1, 2]} | {"m": [1, 1], "c": [0.1]}],
        ),
        beam("clamped", "free", loss_factor=-0.01),
        stepped("clamped", "free", [(1.0, 1.0, 1.0, {})]) | {},
    ):
        if "segments" in bad["beam"]:
            bad["beam"]["loss_factor"] = 0.1  # beside segments: ambiguous
        with pytest.raises(ValueError):
            damped_global_determinant(bad, 1.0, dps=15)


def test_precision_is_converged():
    """dps = 25 and dps = 40 agree to ~1e-25 on a damped scene with every kind."""
    sc = RECIPROCAL | {
        "attachments": RECIPROCAL["attachments"] + [{"type": "hinge", "x": 0.85, "k": 4.0}]
    }
    low = damped_frequencies(sc, 6, dps=25)
    high = damped_frequencies(sc, 6, dps=40)
    for a, b in zip(low, high, strict=True):
        assert rel(a, b) < 1e-24
    h = [
        frf(sc, ("force", "x", 0.2), ("displacement", "mass", 2), [7.0], dps=d)[0] for d in (25, 40)
    ]
    assert rel(h[0], h[1]) < 1e-24

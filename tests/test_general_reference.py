"""General segments (issue 22: ``kappa_GA``, ``rho_I``, ``axial_force``, ``foundation_k``,
``foundation_kG``) against the independent reference (``tests/reference_model.py``).

* The reference itself: its field matrix ``A`` satisfies the Euler-Lagrange equations and
  the force definitions of the energies (derived here with SymPy, not taken from mstmm);
  its exp(A h) agrees with ``mpmath.expm``; its piece stiffness is symmetric and, without
  the new terms, the Euler-Bernoulli closed form.
* The reference against closed forms: simply supported uniform beams, both roots of
  ``det [[kGA k^2 + t k^2 + k_w - mbar w^2, -kGA k], [-kGA k, EI k^2 + kGA - rhoI w^2]]``
  per ``k = n pi / L`` and the shear mode ``w^2 = kGA / rhoI``, to 1e-20; with a loss factor
  (complex stiffnesses, P undamped) too.
* Rigid-body modes: the reference's exact count equals its Wittrick-Williams count at 0+
  and mstmm's number of zero roots (foundations hold both rigid motions, an axial force or
  Pasternak layer the rotation, of the segment they lie on).
* mstmm against the reference: every end, every undamped kind, stepped beams with other
  terms per segment, compression below buckling, a Timoshenko beam far above its cut-off
  ``sqrt(kappa_GA / rho_I)``, ``modes=`` and ``band=``, a damped scene.
* Random scenes (hypothesis): the lowest roots, none missed or spurious.
* Simply supported Timoshenko beams, 1000 modes, against the closed form.

``test_random_compressed_timoshenko_scenes`` found that a stable compressed Timoshenko
segment made ``mstmm.solve`` raise ZeroDivisionError, the buckling check's load factor
overshooting ``kappa_GA + lam P + k_G = 0`` (:data:`SHEAR_LIMIT_OVERSHOOT`, kept as an
explicit example; ``mstmm.buckling.shear_limit`` caps the search now).

mstmm runs interpreted here unless a test asks for ``compiled`` (see ``_interpreted``).
"""

from __future__ import annotations

import functools
import math

import mpmath
import numpy as np
import pytest
import reference_model as ref
import sympy as sp
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st
from mpmath import mp, mpf

import mstmm
from mstmm import interpret

DPS = 16  # reference digits for the comparisons with mstmm (its roots to ~1e-16)
RTOL = 1e-10


@pytest.fixture(autouse=True)
def _interpreted(request, monkeypatch):
    """mstmm's kernels as plain Python, as in a fresh process whose budget is not spent
    (:mod:`mstmm.interpret`: the same generated functions in the same IEEE arithmetic),
    unless the test asks for ``compiled``: machine code costs seconds per topology to
    build.  (A compressed scene's buckling check, ``band=`` and damped scenes load machine
    code anyway, so those run compiled too.)"""
    if "compiled" in request.fixturenames:
        return
    request.getfixturevalue("fresh_process")
    monkeypatch.setattr(interpret._Process, "budget", math.inf)


@pytest.fixture
def compiled(monkeypatch):
    """Run the test's solves compiled (numba)."""
    monkeypatch.setattr(interpret._Process, "compiled", True)


def scene(left, right, attachments=(), segments=None, **beam):
    """A scene dict: a uniform ``beam`` (keys as in the TOML) or ``segments``."""
    beam = {"left": left, "right": right} | beam
    if segments is not None:
        beam["segments"] = [dict(s) for s in segments]
    return {"name": "general", "beam": beam, "attachments": [dict(a) for a in attachments]}


def solve(sc, **kw):
    sol = mstmm.solve(mstmm.scene_from_dict(sc), shapes=kw.pop("shapes", False), **kw)
    assert sol.count_checked, sol.warnings
    assert np.all(sol.converged), sol.warnings
    assert sol.buckling is None or not sol.buckling.buckled, sol.buckling
    return sol


def rel(got, exact) -> np.ndarray:
    got, exact = np.asarray(got), np.asarray(exact)
    return np.abs(got - exact) / np.where(exact == 0, 1.0, np.abs(exact))


def check(got, exact, what, rtol=RTOL) -> float:
    """Same length, rigid-body zeros exactly where the reference has them, the rest within
    ``rtol`` relative; returns the worst relative error."""
    got = np.asarray(got)
    exact = np.asarray([complex(w) if isinstance(w, mpmath.mpc) else float(w) for w in exact])
    assert got.shape == exact.shape, (what, got, exact)
    zero = exact == 0
    assert np.all(got[zero] == 0), (what, got, exact)
    err = rel(got, exact)
    assert err.max() <= rtol, (what, float(err.max()), got, exact)
    return float(err.max())


# ------------------------------------------------------------ the reference's own pieces


def _euler_lagrange_residuals(par: dict, A, om2):
    """The residuals, linear in the state (Y, psi, M, Q), of the Euler-Lagrange equations and
    force definitions of the energies when the state's derivatives are A times it
    (physical units, L = 1; A already converted from the reference's scaled state)."""
    x = sp.Symbol("x")
    Z = sp.Matrix(sp.symbols("Y psi M Q"))
    EI, kGA, rhoI = par["EI"], par["kappa_GA"], par["rho_I"]
    t, kw, mbar = par["axial_force"] + par["foundation_kG"], par["foundation_k"], par["mbar"]
    derivs = [Z]
    for _ in range(4):
        derivs.append(A * derivs[-1])
    out = []
    if kGA != 0:
        w, psi = sp.Function("w")(x), sp.Function("psi")(x)
        lag = (
            EI * psi.diff(x) ** 2 + kGA * (w.diff(x) - psi) ** 2 + t * w.diff(x) ** 2 + kw * w**2
        ) / 2 - om2 * (mbar * w**2 + rhoI * psi**2) / 2
        eqs = sp.calculus.euler.euler_equations(lag, [w, psi], x)
        # force definitions: M = dL/dpsi', -Q = dL/dw' (boundary terms [M dpsi - Q dw])
        eqs = [e.lhs for e in eqs] + [
            lag.diff(psi.diff(x)) - sp.Symbol("M"),
            lag.diff(w.diff(x)) + sp.Symbol("Q"),
        ]
        funcs = (w, psi)
    else:  # no shear deformation: psi = w'
        w = sp.Function("w")(x)
        lag = (EI * w.diff(x, 2) ** 2 + t * w.diff(x) ** 2 + kw * w**2) / 2 - om2 * (
            mbar * w**2 + rhoI * w.diff(x) ** 2
        ) / 2
        (eq,) = sp.calculus.euler.euler_equations(lag, [w], x)
        # boundary terms [dL/dw'' dw' + (dL/dw' - (dL/dw'')') dw]: M = dL/dw'', -Q = the rest
        eqs = [
            eq.lhs,
            lag.diff(w.diff(x, 2)) - sp.Symbol("M"),
            lag.diff(w.diff(x)) - lag.diff(w.diff(x, 2)).diff(x) + sp.Symbol("Q"),
            w.diff(x) - sp.Symbol("psi"),
        ]
        funcs = (w,)
    for e in eqs:
        for k in range(4, -1, -1):  # highest derivatives first
            for i, f in enumerate(funcs):
                e = e.subs(f.diff(x, k) if k else f, derivs[k][i])
        out.append(sp.expand(e))
    return out, Z


PARAMETER_SETS = [
    dict(EI=2, mbar=3, kappa_GA=50, rho_I=0.02, axial_force=7, foundation_k=11, foundation_kG=2),
    dict(EI=1, mbar=1, kappa_GA=40, rho_I=0, axial_force=-9, foundation_k=0, foundation_kG=1),
    dict(EI=3, mbar=2, kappa_GA=0, rho_I=0.05, axial_force=-4, foundation_k=5, foundation_kG=0),
    dict(EI=1, mbar=2, kappa_GA=0, rho_I=0, axial_force=0, foundation_k=0, foundation_kG=3),
]


@pytest.mark.parametrize("par", PARAMETER_SETS)
def test_field_matrix_solves_the_euler_lagrange_equations(par):
    """The reference's A (state (Y / L, psi, M L / EI, Q L^2 / EI), here L = 1) turned into
    physical units satisfies the Euler-Lagrange equations of the energies per length
    1/2 [EI psi'^2 + kGA (w' - psi)^2 + (P + k_G) w'^2 + k_w w^2] - w^2/2 [mbar w^2 + rhoI
    psi^2] and M = EI psi', Q = -(kGA (w' - psi) + (P + k_G) w') identically in the state.
    Four independent conditions on four derivatives: they fix A, so this is its derivation."""
    om2 = sp.Rational(37, 3)
    # decimal strings: the reference reads them at its precision, SymPy takes them exactly
    segment = {k: str(v) for k, v in par.items() if k != "mbar"} | {
        "mass_per_length": str(par["mbar"])
    }
    with mp.workdps(50):
        A_ref = ref.field_matrix(segment, mpf(37) / 3)  # beta^4 = w^2 with mbar0 = EI0 = 1
        # Z_ref = D Z with D = diag(1, 1, 1 / EI, 1 / EI): A = D^-1 A_ref D
        d = [1, 1, 1 / mpf(par["EI"]), 1 / mpf(par["EI"])]
        A = sp.Matrix(4, 4, lambda i, j: sp.Float(mpmath.nstr(A_ref[i][j] * d[j] / d[i], 45), 45))
    exact = {k: sp.nsimplify(v) for k, v in par.items()}
    residuals, Z = _euler_lagrange_residuals(exact, A, om2)
    for r in residuals:
        coeffs = [abs(float(r.coeff(z))) for z in Z]
        assert max(coeffs) < 1e-35, (par, r)


def test_exp_field_matrix_agrees_with_mpmath_expm():
    gen = {"EI": 2, "mass_per_length": 0.7, "kappa_GA": 300, "rho_I": 0.002}
    cases = [
        (gen | {"axial_force": 3, "foundation_kG": 0.5, "foundation_k": 10}, 1e4, "0.05", 0),
        (gen | {"axial_force": -30}, 1e7, "0.01", 0),
        ({"EI": 1, "rho_I": 0.01, "axial_force": 50, "foundation_k": 3}, 100, "0.3", "0.05"),
        (gen | {"foundation_k": 1e3}, mpmath.mpc(1e5, 3e3), "0.02", "0.1"),
    ]
    with mp.workdps(60):
        for segment, b4, h, eta in cases:
            A = mpmath.matrix(ref.field_matrix(segment, b4, mpf(eta)))
            got = ref._expm(A, mpf(h))
            with mp.workdps(120):
                want = mpmath.expm(A * mpf(h))
            for i in range(4):
                scale = max(abs(want[i, j]) for j in range(4))
                assert max(abs(got[i][j] - want[i, j]) for j in range(4)) < 1e-55 * scale


def test_piece_stiffness_is_symmetric_and_reduces_to_euler_bernoulli():
    with mp.workdps(40):
        beta, ell = mpf("2.7"), mpf("0.6")
        eb = ref.segment_stiffness_matrix(beta, ell)
        gen = ref.general_segment_stiffness_matrix({}, beta, ell)
        for i in range(4):
            for j in range(4):
                assert abs(gen[i][j] - eb[i][j]) < mpf(10) ** -30 * abs(eb[0][0])
        full = {"kappa_GA": 80, "rho_I": 0.01, "axial_force": -5, "foundation_k": 30}
        K = ref.general_segment_stiffness_matrix(full | {"foundation_kG": 2}, beta, ell)
        for i in range(4):
            for j in range(4):
                assert abs(K[i][j] - K[j][i]) < mpf(10) ** -30 * abs(K[0][0])
        # reflection symmetry of a uniform piece (y -> y, psi -> -psi, ends swapped)
        assert abs(K[2][2] - K[0][0]) < mpf(10) ** -30 * abs(K[0][0])
        assert abs(K[3][3] - K[1][1]) < mpf(10) ** -30 * abs(K[1][1])
        assert abs(K[2][3] + K[0][1]) < mpf(10) ** -30 * abs(K[0][0])


# ------------------------------------------------------------------ closed forms


def simply_supported(L, EI, mbar, kGA=0, rhoI=0, P=0, kw=0, kG=0, eta=0, n_max=20) -> list:
    """Natural frequencies of a uniform simply supported beam (mpmath, current precision):
    w^2 the roots of the 2x2 determinant for each k = n pi / L, n = 1..n_max (one root
    without shear), and w^2 = kGA / rhoI (n = 0: psi constant, Y = 0) when both are > 0.
    A loss factor multiplies EI, kGA, k_w, k_G (complex roots, Re w > 0).  Sorted by Re."""
    c = 1 if eta == 0 else mpmath.mpc(1, eta)
    L, mbar, rhoI = mpf(L), mpf(mbar), mpf(rhoI)
    EI, kGA, kw = mpf(EI) * c, mpf(kGA) * c, mpf(kw) * c
    t = mpf(P) + mpf(kG) * c
    out = []
    if kGA != 0 and rhoI != 0:
        out.append(mpmath.sqrt(kGA / rhoI))
    for n in range(1, n_max + 1):
        k = n * mp.pi / L
        if kGA == 0:
            out.append(mpmath.sqrt((EI * k**4 + t * k**2 + kw) / (mbar + rhoI * k**2)))
            continue
        a, b, d = (kGA + t) * k**2 + kw, kGA * k, EI * k**2 + kGA
        if rhoI == 0:  # linear in w^2
            out.append(mpmath.sqrt((a * d - b * b) / (mbar * d)))
            continue
        # mbar rhoI x^2 - (a rhoI + d mbar) x + (a d - b^2) = 0, small root without cancellation
        p2, p1, p0 = mbar * rhoI, a * rhoI + d * mbar, a * d - b * b
        big = (p1 + mpmath.sqrt(p1 * p1 - 4 * p2 * p0)) / (2 * p2)
        out += [mpmath.sqrt(p0 / (p2 * big)), mpmath.sqrt(big)]
    return sorted(out, key=lambda w: (mpmath.re(w), mpmath.im(w)))


SS_CASES = {
    "everything": dict(
        length=1.0, EI=1.0, mass_per_length=1.0, kappa_GA=400.0, rho_I=0.002, axial_force=5.0
    )
    | dict(foundation_k=10.0, foundation_kG=0.5),
    # cut-off sqrt(50 / 0.01) = 70.7 among the lowest modes: both branches interleave
    "thick_timoshenko": dict(length=1.0, EI=1.0, mass_per_length=1.0, kappa_GA=50.0, rho_I=0.01),
    "shear_no_rotary_inertia_compressed": dict(
        length=2.0, EI=3.0, mass_per_length=0.5, kappa_GA=30.0, axial_force=-4.0
    ),  # buckling load P_E / (1 + P_E / kGA) = 5.94 N
    # above the bare beam's Euler load (8.77 N), held by the foundation: every
    # EI k^4 - 10 k^2 + 20 > 0
    "rayleigh_compressed_on_foundation": dict(
        length=1.5, EI=2.0, mass_per_length=1.2, rho_I=0.03, axial_force=-10.0
    )
    | dict(foundation_k=20.0),
    "pasternak_only": dict(length=1.0, EI=1.0, mass_per_length=1.0, foundation_kG=25.0),
}


@pytest.mark.parametrize("name", sorted(SS_CASES))
def test_reference_simply_supported_closed_form(name):
    beam = SS_CASES[name]
    sc = scene("pinned", "pinned", **beam)
    n = 10
    with mp.workdps(40):
        got = ref.frequencies(sc, n, dps=25)
        exact = simply_supported(
            beam["length"],
            beam["EI"],
            beam["mass_per_length"],
            beam.get("kappa_GA", 0),
            beam.get("rho_I", 0),
            beam.get("axial_force", 0),
            beam.get("foundation_k", 0),
            beam.get("foundation_kG", 0),
        )[:n]
        worst = max(abs(g - e) / e for g, e in zip(got, exact, strict=True))
    assert worst < mpf(10) ** -20, (name, worst)


def test_reference_damped_simply_supported_closed_form():
    """A loss factor on a Timoshenko beam with every term: complex EI, kGA, k_w, k_G."""
    beam = SS_CASES["everything"] | {"loss_factor": 0.03}
    sc = scene("pinned", "pinned", **beam)
    n = 5
    with mp.workdps(40):
        got = ref.damped_frequencies(sc, n, dps=20)
        exact = simply_supported(1, 1, 1, 400, 0.002, 5, 10, 0.5, eta=0.03)[:n]
        worst = max(abs(g - e) / abs(e) for g, e in zip(got, exact, strict=True))
    assert worst < mpf(10) ** -18, worst


def test_reference_static_receptance_and_mode_shape_closed_form():
    """The reference's forced solve and eigenspace through a Timoshenko segment: the
    receptance of a simply supported beam at a tiny frequency is the static deflection,
    bending plus shear, ``F a x' (L^2 - a^2 - x'^2) / (6 L EI) + F a x' / (L kGA)`` (load at
    a from the left, deflection at x' from the right, x' <= L - a); its second mode shape is
    sin(2 pi x / L)."""
    length, ei, kga = 2.0, 3.0, 40.0
    sc = scene("pinned", "pinned", length=length, EI=ei, mass_per_length=1.5, kappa_GA=kga)
    sc["beam"]["rho_I"] = 0.01
    a, x = 0.7, 1.3
    xp = length - x
    static = a * xp * (length**2 - a**2 - xp**2) / (6 * length * ei) + a * xp / (length * kga)
    (h,) = ref.frf(sc, ("force", "x", a), ("displacement", "x", x), [1e-6], dps=30)
    assert abs(complex(h) - static) < 1e-12 * static  # (w / w_1)^2 = 1e-13
    with mp.workdps(30):
        w2 = ref.frequencies(sc, 2, dps=20)[1]
    xs = np.linspace(0.0, length, 21)
    (shape,) = ref.eigenspace(sc, w2, 1, xs.tolist(), dps=20)
    shape = np.asarray(shape) / shape[5]  # the crest at x = L / 4
    assert np.abs(shape - np.sin(2 * np.pi * xs / length)).max() < 1e-12


# -------------------------------------------------------------- rigid-body modes

RIGID = {
    # free-free beams: shear and rotary inertia hold nothing, a foundation everything, an
    # axial force or Pasternak layer the rotation (P + k_G = 0 nothing)
    "shear_rotary": (scene("free", "free", length=1.0, EI=1.0, mass_per_length=1.0,
                           kappa_GA=30.0, rho_I=0.01), 2),
    "winkler": (scene("free", "free", length=1.0, EI=1.0, mass_per_length=1.0,
                      foundation_k=5.0), 0),
    "tension": (scene("free", "free", length=1.0, EI=1.0, mass_per_length=1.0,
                      axial_force=3.0), 1),
    "pasternak_cancelled": (scene("free", "free", length=1.0, EI=1.0, mass_per_length=1.0,
                                  axial_force=-2.0, foundation_kG=2.0, rho_I=0.01), 2),
    "sliding_free_tension": (scene("sliding", "free", length=1.0, EI=1.0, mass_per_length=1.0,
                                   axial_force=3.0), 1),
    # a free hinge: the plain part may still turn about it (the spring to ground sits where
    # the beam is held anyway, the hanging mass holds nothing)
    "pinned_free_hinge_pasternak": (
        scene(
            "pinned",
            "free",
            [
                {"type": "hinge", "x": 1.4},
                {"type": "spring", "x": 0.5, "k": 30.0},
                {"type": "spring_mass", "x": 1.8, "k": 40.0, "m": 0.1},
            ],
            segments=[
                dict(length=1.0, EI=1.0, mass_per_length=1.0, foundation_kG=4.0),
                dict(length=1.0, EI=1.0, mass_per_length=1.0, kappa_GA=60.0),
            ],
        ),
        1,
    ),
    "free_hinge_winkler_left": (
        scene(
            "free",
            "free",
            [
                {"type": "hinge", "x": 1.0},
                {"type": "mass", "x": 1.5, "m": 0.2},
                {"type": "spring_mass", "x": 2.0, "k": 40.0, "m": 0.1},
            ],
            segments=[
                dict(length=1.0, EI=1.0, mass_per_length=1.0, foundation_k=9.0),
                dict(length=1.0, EI=2.0, mass_per_length=1.0, rho_I=0.02),
            ],
        ),
        1,
    ),
}  # fmt: skip


@pytest.mark.parametrize("name", sorted(RIGID))
def test_rigid_body_modes(name):
    sc, expected = RIGID[name]
    assert ref.rigid_body_mode_count(sc) == expected
    assert ref.count_below(sc, 1e-3, dps=16) == expected  # Wittrick-Williams at 0+
    sol = solve(sc, modes=expected + 2)
    assert int(np.sum(sol.omega == 0)) == expected, (name, sol.omega)
    assert np.all(sol.omega[expected:] > 1e-3)


# ------------------------------------------------------------------ mstmm vs reference

SCENES = {
    "cantilever_timoshenko_tension": scene(
        "clamped",
        "free",
        [
            {"type": "spring_mass", "x": 0.7, "k": 2.0e4, "m": 1.5},
            {"type": "mass", "x": 1.2, "m": 2.0, "J": 0.05},
        ],
        length=1.2,
        EI=3.0e4,
        mass_per_length=8.0,
        kappa_GA=2.0e6,
        rho_I=0.01,
        axial_force=5.0e3,
    ),
    # buckling of the pinned-sliding beam: pi^2 EI / (2 L)^2 = 6169 N, 6131 N with the shear
    # (springs only stiffen); 4 times the compression is far below kappa_GA (see
    # test_random_compressed_timoshenko_scenes)
    "pinned_sliding_compressed": scene(
        "pinned",
        "sliding",
        [
            {"type": "spring", "x": 1.1, "k": 5.0e3},
            {"type": "rotational_spring", "x": 0.6, "k": 2.0e3},
            {"type": "spring_mass", "x": 1.7, "k": 3.0e4, "m": 0.8},
        ],
        length=2.0,
        EI=1.0e4,
        mass_per_length=5.0,
        kappa_GA=1.0e6,
        rho_I=0.05,
        axial_force=-2.4e3,
    ),
    "free_free_winkler_pasternak_hinge": scene(
        "free",
        "free",
        [
            {"type": "hinge", "x": 1.3, "k": 800.0},
            {"type": "spring_mass", "x": 2.5, "k": 6.0e4, "m": 2.0},
            {"type": "mass", "x": 0.0, "m": 3.0},
        ],
        length=3.0,
        EI=2.0e4,
        mass_per_length=10.0,
        kappa_GA=5.0e5,
        rho_I=0.02,
        foundation_k=4.0e4,
        foundation_kG=3.0e3,
    ),
    "stepped_mixed_terms": scene(
        "clamped",
        "pinned",
        [
            {"type": "support", "x": 1.1},
            {"type": "spring_mass", "x": 0.3, "k": 1.0e5, "m": 2.0},
            {"type": "hinge", "x": 1.5, "k": 1.0e3},
            {"type": "rotational_spring", "x": 0.8, "k": 5.0e3},
        ],
        segments=[
            dict(length=0.6, EI=5.0e4, mass_per_length=12.0, kappa_GA=1.0e6, rho_I=0.03),
            dict(length=0.5, EI=3.0e4, mass_per_length=9.0),
            dict(length=0.9, EI=4.0e4, mass_per_length=10.0, rho_I=0.01, axial_force=8.0e3)
            | dict(foundation_k=2.0e5),
        ],
    ),
    "sliding_clamped_support": scene(
        "sliding",
        "clamped",
        [
            {"type": "support", "x": 0.45},
            {"type": "spring_mass", "x": 0.2, "k": 500.0, "m": 0.3},
            {"type": "mass", "x": 0.8, "m": 0.5, "J": 0.02},
        ],
        length=1.0,
        EI=1.0e3,
        mass_per_length=2.0,
        kappa_GA=8.0e4,
        rho_I=0.005,
        axial_force=300.0,
        foundation_kG=100.0,
    ),
    "pinned_free_free_hinge_stepped": scene(
        "pinned",
        "free",
        [
            {"type": "hinge", "x": 1.4},
            {"type": "spring_mass", "x": 1.8, "k": 40.0, "m": 0.1},
            {"type": "spring", "x": 0.5, "k": 30.0},
        ],
        segments=[
            dict(length=1.0, EI=1.0, mass_per_length=1.0, foundation_kG=4.0),
            dict(length=1.0, EI=2.0, mass_per_length=1.5, kappa_GA=60.0, rho_I=0.004),
        ],
    ),
}

# Timoshenko far above its cut-off: G L^2 / EI = 20, cut-off sqrt(2e5 / 0.05) = 2000 rad/s
ABOVE_CUTOFF = scene(
    "clamped",
    "pinned",
    [{"type": "spring_mass", "x": 0.35, "k": 4.0e5, "m": 0.5}],
    length=1.0,
    EI=1.0e4,
    mass_per_length=10.0,
    kappa_GA=2.0e5,
    rho_I=0.05,
)
CUTOFF = math.sqrt(2.0e5 / 0.05)

MODES = 10


@functools.cache
def reference(name: str, modes: int = MODES) -> tuple:
    sc = ABOVE_CUTOFF if name == "above_cutoff" else SCENES[name]
    return tuple(ref.frequencies(sc, modes, dps=DPS))


@pytest.mark.parametrize("name", sorted(SCENES))
def test_mstmm_matches_reference(name):
    sol = solve(SCENES[name], modes=MODES)
    check(sol.omega, reference(name), name)


def test_timoshenko_far_above_cutoff():
    n = 24
    exact = reference("above_cutoff", n)
    assert sum(1 for w in exact if w > CUTOFF) >= 8  # several modes beyond the cut-off
    sol = solve(ABOVE_CUTOFF, modes=n)
    check(sol.omega, exact, "above_cutoff")


def test_band_matches_reference():
    """``band=`` between two reference roots: the same roots, the same count (on the scene
    whose buckling check has compiled its kernel already)."""
    name = "pinned_sliding_compressed"
    exact = reference(name)
    lo = float(exact[2] + exact[3]) / 2
    hi = float(exact[8] + exact[9]) / 2
    sol = solve(SCENES[name], band=(lo, hi))
    check(sol.omega, exact[3:9], "band")
    with mp.workdps(30):
        assert [float(w) for w in ref.band(SCENES[name], lo, hi, dps=DPS)] == pytest.approx(
            [float(w) for w in exact[3:9]], rel=1e-14
        )


def test_scene_objects_and_shapes():
    """The reference reads a Scene too; mstmm with its mode shapes on (the default): the
    ratio of the beam's deflection under the hanging mass to the mass's, against the
    reference's null vector (:func:`reference_model.mode_at_attachments`)."""
    sc = SCENES["cantilever_timoshenko_tension"]
    obj = mstmm.scene_from_dict(sc)
    exact = reference("cantilever_timoshenko_tension")
    got = ref.frequencies(obj, 4, dps=DPS)
    assert [float(w) for w in got] == pytest.approx([float(w) for w in exact[:4]], rel=1e-15)
    sol = mstmm.solve(obj, modes=MODES)
    assert sol.count_checked and sol.shapes is not None and len(sol.shapes) == MODES
    check(sol.omega, exact, "with shapes")
    x = sc["attachments"][0]["x"]
    for i in (0, 1, 3):
        shape = sol.shapes[i]
        (beam,), (mass,) = ref.mode_at_attachments(sc, exact[i], dps=DPS)
        ratio = float(np.interp(x, shape.x, shape.Y)) / shape.mass_Y[0]  # x is a grid point
        assert ratio == pytest.approx(beam / mass, rel=1e-9, abs=1e-12), (i, ratio, beam / mass)


# Loss factors on a stepped beam, Timoshenko on the left, the other terms on the right (a
# dashpot beside a Timoshenko segment leaves mstmm without a proved decay bound, by design:
# mstmm.decay_bound; the count then says which roots it did not count).
DAMPED = scene(
    "clamped",
    "free",
    [{"type": "spring_mass", "x": 0.75, "k": 50.0, "m": 0.2}],
    segments=[
        dict(length=0.5, EI=1.0, mass_per_length=1.0, kappa_GA=300.0, rho_I=0.002)
        | dict(loss_factor=0.02),
        dict(length=0.5, EI=0.8, mass_per_length=0.9, rho_I=0.001, axial_force=3.0)
        | dict(foundation_k=20.0, foundation_kG=0.5, loss_factor=0.01),
    ],
)


def test_damped_general_scene():
    exact = ref.damped_frequencies(DAMPED, 6, dps=DPS)
    sol = mstmm.solve(mstmm.scene_from_dict(DAMPED), modes=6, shapes=False)
    assert sol.count_checked and not sol.warnings, sol.warnings
    assert np.all(sol.omega.imag > 0)
    check(sol.omega, exact, "damped")


# ------------------------------------------------------------------ random scenes

# The topologies (ends, kinds) of the scenes above: the random scenes vary everything else
# (terms, segments, counts, positions and values of the attachments) without a new kernel
# to compile for each example (seconds each).
TEMPLATES = sorted(
    {
        (
            sc["beam"]["left"],
            sc["beam"]["right"],
            tuple(sorted({a["type"] for a in sc["attachments"]})),
        )
        for sc in [*SCENES.values(), ABOVE_CUTOFF]
    }
    | {("pinned", "pinned", ())}
)


@st.composite
def random_scenes(draw, timoshenko_compression: bool = False):
    """One or two segments with random general terms, one or two attachments of each kind of
    a topology of :data:`TEMPLATES`.  A compression only where it cannot buckle the beam
    (both ends held, no hinge: a third of the pinned-pinned Timoshenko buckling load of the
    weakest segment), else a tension; on segments without shear deformation, or with
    ``timoshenko_compression`` on a Timoshenko segment at least (both ends then held)."""
    templates = TEMPLATES
    if timoshenko_compression:
        templates = [t for t in TEMPLATES if {t[0], t[1]} <= {"clamped", "pinned"}]
        templates = [t for t in templates if "hinge" not in t[2]]
    left, right, kinds = draw(st.sampled_from(templates))
    kinds = list(kinds) + draw(st.lists(st.sampled_from(kinds), max_size=1)) if kinds else []
    nseg = draw(st.integers(1, 2))
    slots = draw(
        st.lists(st.integers(1, 19), min_size=len(kinds), max_size=len(kinds), unique=True)
    )
    held = left in ("clamped", "pinned") and right in ("clamped", "pinned") and "hinge" not in kinds
    segments = []
    for i in range(nseg):
        seg = {
            "length": 1.0 / nseg,
            "EI": draw(st.sampled_from([0.5, 1.0, 2.0])),
            "mass_per_length": draw(st.sampled_from([0.5, 1.0, 1.5])),
        }
        forced = timoshenko_compression and i == 0
        if forced or draw(st.booleans()):
            seg["kappa_GA"] = draw(st.sampled_from([20.0, 100.0, 1000.0]))
        if draw(st.booleans()):
            seg["rho_I"] = draw(st.sampled_from([0.001, 0.01, 0.03]))
        if draw(st.booleans()):
            seg["foundation_k"] = draw(st.sampled_from([5.0, 50.0, 500.0]))
        if draw(st.booleans()):
            seg["foundation_kG"] = draw(st.sampled_from([0.5, 5.0]))
        if forced:
            seg["axial_force"] = -1.0
        elif draw(st.booleans()):
            seg["axial_force"] = draw(st.sampled_from([2.0, 20.0, -1.0]))
        segments.append(seg)
    ei = min(s["EI"] for s in segments)
    kga = min((s.get("kappa_GA") or math.inf) for s in segments)
    p_cr = math.pi**2 * ei / (1 + math.pi**2 * ei / kga)
    for s in segments:
        if s.get("axial_force", 0) < 0:
            allowed = held and (timoshenko_compression or "kappa_GA" not in s)
            s["axial_force"] = -p_cr / 3 if allowed else -s["axial_force"]
    atts = []
    for kind, slot in zip(kinds, slots, strict=True):
        x = slot / 20  # distinct points: no rotational spring or rotary inertia at a hinge
        if kind == "spring_mass":
            atts.append({"type": kind, "x": x, "k": draw(st.sampled_from([10.0, 300.0])), "m": 0.2})
        elif kind == "mass":
            atts.append({"type": kind, "x": x, "m": 0.3, "J": draw(st.sampled_from([0.0, 0.002]))})
        elif kind in ("spring", "rotational_spring"):
            atts.append({"type": kind, "x": x, "k": draw(st.sampled_from([5.0, 200.0]))})
        elif kind == "support":
            atts.append({"type": kind, "x": x})
        else:
            atts.append({"type": kind, "x": x, "k": draw(st.sampled_from([0.0, 3.0]))})
    if nseg == 1:
        return scene(left, right, atts, **segments[0])
    return scene(left, right, atts, segments=segments)


def _random_check(sc, n=6):
    interpret._Process.compiled = False  # each example as a fresh process (undone after)
    exact = ref.frequencies(sc, n, dps=DPS)
    sol = solve(sc, modes=n)
    check(sol.omega, exact, sc)


@settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(sc=random_scenes())
def test_random_general_scenes(sc):
    _random_check(sc)


# mstmm's buckling check (mstmm.buckling.buckling) doubles the load factor on the axial
# forces until the count finds a negative stiffness; for a Timoshenko segment it may step
# past kappa_GA + lam * axial_force + foundation_kG = 0 (where no count exists, however
# stable the scene: the Timoshenko buckling load is below kappa_GA + foundation_kG) and the
# count divides by zero.  Here: buckling load 19.60 N, compression 3 N, load factors 2, 4
# stable, 8 gives kappa_GA - 24 < 0: ZeroDivisionError out of mstmm.solve.  Expected (closed
# form, reference): 12.800887540805, 25.829310121806, 38.807969020050, 51.773907103360 rad/s.
SHEAR_LIMIT_OVERSHOOT = scene(
    "pinned",
    "pinned",
    length=1.0,
    EI=100.0,
    mass_per_length=1.0,
    kappa_GA=20.0,
    axial_force=-3.0,
)


@settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(sc=random_scenes(timoshenko_compression=True))
@example(sc=SHEAR_LIMIT_OVERSHOOT)
def test_random_compressed_timoshenko_scenes(sc):
    _random_check(sc, 4)


# ------------------------------------------------------------------ 1000 modes

HIGH = {
    "timoshenko": dict(length=2.0, EI=2.0e5, mass_per_length=15.0, kappa_GA=4.0e7, rho_I=0.02),
    "every_term": dict(length=2.0, EI=2.0e5, mass_per_length=15.0, kappa_GA=4.0e7, rho_I=0.02)
    | dict(axial_force=-5.0e4, foundation_k=3.0e6, foundation_kG=2.0e4),
}


@pytest.mark.parametrize("name", sorted(HIGH))
def test_thousand_modes_simply_supported_timoshenko(name, compiled):
    beam = HIGH[name]
    n = 1000
    sol = solve(scene("pinned", "pinned", **beam), modes=n)
    with mp.workdps(30):
        exact = simply_supported(
            beam["length"],
            beam["EI"],
            beam["mass_per_length"],
            beam["kappa_GA"],
            beam["rho_I"],
            beam.get("axial_force", 0),
            beam.get("foundation_k", 0),
            beam.get("foundation_kG", 0),
            n_max=n,
        )[:n]
    exact = np.array([float(w) for w in exact])
    assert int(np.sum(exact > math.sqrt(beam["kappa_GA"] / beam["rho_I"]))) > 900
    check(sol.omega, exact, name)

"""Checks of the Bloch-Floquet reference (tests/reference_bloch.py) against closed forms
(bare, tensioned / founded / Timoshenko and damped beams; Mead's periodically pinned beam;
Sugino's locally resonant gap and its first-order correction), against the independent
global-determinant model of tests/reference_model.py (symmetric cells split into half cells)
and against itself (det T = 1, palindromic polynomials, edges where mu = +-2, dps)."""

from __future__ import annotations

import sys
from pathlib import Path

import mpmath
import pytest
from mpmath import mp, mpf

sys.path.insert(0, str(Path(__file__).resolve().parent))

import reference_bloch as rb  # noqa: E402
import reference_model as rm  # noqa: E402
from reference_bloch import (  # noqa: E402
    band_edges,
    bloch_k,
    bloch_mu,
    cell_pencil,
    cell_transfer,
    characteristic,
    edge_count,
)


@pytest.fixture(autouse=True)
def _precise():
    with mp.workdps(60):
        yield


def bare(EI=2.0, mbar=3.0, L=1.5, **extra):
    return {"beam": {"length": L, "EI": EI, "mass_per_length": mbar, **extra}, "attachments": []}


def close(a, b, tol):
    return abs(a - b) <= tol * max(1, abs(b))


# ------------------------------------------------------------------ (a) bare beam


@pytest.mark.parametrize("omega", [1e-3, 0.5, 7.0, 40.0, 400.0, 3000.0])
def test_bare_beam_mu_and_k(omega):
    EI, mbar, L = 2.0, 3.0, 1.5
    kL = mpmath.root(mbar * mpf(omega) ** 2 / EI, 4) * L
    mu1, mu2 = bloch_mu(bare(EI, mbar, L), omega)
    assert close(mu1, 2 * mpmath.cosh(kL), mpf(10) ** -38)
    assert close(mu2, 2 * mpmath.cos(kL), mpf(10) ** -38)
    k1, k2 = bloch_k(bare(EI, mbar, L), omega)
    assert close(k1 * L, mpmath.mpc(0, kL), mpf(10) ** -30)
    folded = abs(kL - 2 * mp.pi * mpmath.nint(kL / (2 * mp.pi)))  # kL folded into [0, pi]
    assert close(k2 * L, folded, mpf(10) ** -30)


def test_bare_beam_as_segments_and_scene():
    """The same beam as three equal segments, and as an mstmm Scene object."""
    from mstmm.scene import scene_from_dict

    seg = {"length": 0.5, "EI": 2.0, "mass_per_length": 3.0}
    cell = {"beam": {"segments": [seg, seg, seg]}, "attachments": []}
    scene = scene_from_dict(
        {
            "beam": {
                "length": 1.5,
                "EI": 2.0,
                "mass_per_length": 3.0,
                "left": "free",
                "right": "free",
            }
        }
    )
    for omega in (3.0, 90.0):
        ref = bloch_mu(bare(), omega)
        for other in (cell, scene):
            got = bloch_mu(other, omega)
            assert all(close(a, b, mpf(10) ** -37) for a, b in zip(got, ref))


def test_bare_beam_edges_are_double():
    EI, mbar, L = 2.0, 3.0, 1.5
    scale = mpmath.sqrt(mpf(EI) / mbar) / mpf(L) ** 2
    w_hi = float((5.5 * mp.pi) ** 2 * scale)
    edges = band_edges(bare(EI, mbar, L), 0, w_hi, dps=40)
    assert [m for _w, _k, m in edges] == [2] * 5
    for n, (w, kind, _m) in enumerate(edges, start=1):
        assert kind == ("antiperiodic" if n % 2 else "periodic")
        assert close(w, (n * mp.pi) ** 2 * scale, mpf(10) ** -38)
    # the count: 1 rigid translation + 2 per periodic edge below w_hi
    assert edge_count(bare(EI, mbar, L), w_hi, "periodic") == 1 + 4
    assert edge_count(bare(EI, mbar, L), w_hi, "antiperiodic") == 6


# ----------------------------------------------------------- general segments, damping


def _general_mus(p: dict, omega, L):
    """2 cos(k L) of the two roots s = k^2 of the plane-wave determinant of
    kGA (W'' - psi') + t W'' + (m w^2 - kw) W = 0, EI psi'' + kGA (W' - psi) + rho_I w^2 psi = 0
    (t = P + kG): g EI s^2 + (g (G - R) - Mw EI - G^2) s - Mw (G - R) = 0, g = G + t."""
    EI, m = mpf(p["EI"]), mpf(p["mass_per_length"])
    G, rho, P = mpf(p.get("kappa_GA", 0)), mpf(p.get("rho_I", 0)), mpf(p.get("axial_force", 0))
    kw, kG = mpf(p.get("foundation_k", 0)), mpf(p.get("foundation_kG", 0))
    w = mpmath.mpmathify(omega)
    t, Mw, R = P + kG, m * w**2 - kw, rho * w**2
    if G == 0:  # Euler-Bernoulli: EI s^2 + t s - Mw = 0
        A, B, C = EI, t, -Mw
    else:
        g = G + t
        A, B, C = g * EI, g * (G - R) - Mw * EI - G**2, -Mw * (G - R)
    d = mpmath.sqrt(B * B - 4 * A * C)
    return [2 * mpmath.cos(mpmath.sqrt(s) * L) for s in ((-B + d) / (2 * A), (-B - d) / (2 * A))]


def _same_set(got, want, tol):
    a, b = list(got), list(want)
    return (close(a[0], b[0], tol) and close(a[1], b[1], tol)) or (
        close(a[0], b[1], tol) and close(a[1], b[0], tol)
    )


@pytest.mark.parametrize(
    "extra",
    [
        {"axial_force": 30.0, "foundation_k": 50.0},
        {"axial_force": -2.0, "foundation_kG": 0.5},
        {"kappa_GA": 400.0, "rho_I": 0.002},
        {"kappa_GA": 400.0, "rho_I": 0.002, "axial_force": 3.0, "foundation_k": 50.0},
    ],
)
def test_general_segment_closed_form(extra):
    p = {"EI": 2.0, "mass_per_length": 3.0, **extra}
    for omega in (1.0, 20.0, 150.0):
        got = bloch_mu(bare(**extra), omega)
        assert _same_set(got, _general_mus(p, omega, mpf(1.5)), mpf(10) ** -36)


@pytest.mark.parametrize(
    "b4, eta", [(mpf(2000), 0), (mpf(9e4), 0.03), (mpmath.mpc(1e4, 300), 0), (mpf(1e-6), 0)]
)
def test_general_piece_against_reference_model_and_expm(b4, eta):
    """The general A (state m, q scaled by EI0) is reference_model's (scaled by the
    segment's EI) under diag(1, 1, e, e); the piece transfer is mpmath.expm(A h)."""
    seg = {
        "EI": 0.7,
        "mass_per_length": 1.2,
        "kappa_GA": 300.0,
        "rho_I": 0.01,
        "axial_force": -2.0,
        "foundation_k": 30.0,
        "foundation_kG": 0.5,
    }
    theirs = rm.field_matrix(seg, b4, eta)
    gen = rm._General(
        *(mpf(seg[k]) for k in ("kappa_GA", "rho_I", "axial_force")), mpf(0.5), mpf(30)
    )
    piece = rb._Seg(mpf(0.7), mpf(1.2), mpf(eta), gen)
    mine = rb._field_a(piece, b4)
    e = [1, 1, mpf(0.7), mpf(0.7)]
    for i in range(4):
        for j in range(4):
            assert close(mine[i][j], e[i] * theirs[i][j] / e[j], mpf(10) ** -50)
    lam = rb._wavenumber_bound(gen, piece.e, piece.mu, piece.eta, b4)
    for h in (mpf(3) / lam if lam > 3 else mpf(1), mpf("0.01")):
        got = rb._general_transfer(piece, b4, h)
        want = mpmath.expm(mpmath.matrix(mine) * h)
        assert max(abs(got[i][j] - want[i, j]) for i in range(4) for j in range(4)) < mpf(
            10
        ) ** -50 * mpmath.mnorm(want, 1)


@pytest.mark.parametrize("omega", [2.0, 20.0, mpmath.mpc(5, 0.3), mpmath.mpc(30, -1)])
def test_damped_closed_form(omega):
    """Loss factor (EI -> EI (1 + i eta)) and complex omega: mu = 2 cos(kL), 2 cosh(kL)."""
    eta, L = 0.05, 1.5
    kL = mpmath.root(3 * mpmath.mpmathify(omega) ** 2 / (2 * mpmath.mpc(1, eta)), 4) * L
    got = bloch_mu(bare(loss_factor=eta), omega)
    assert _same_set(got, [2 * mpmath.cos(kL), 2 * mpmath.cosh(kL)], mpf(10) ** -36)
    k1, k2 = bloch_k(bare(loss_factor=eta), omega)
    for k, mu in zip((k1, k2), got):
        assert close(2 * mpmath.cos(k * L), mu, mpf(10) ** -30)
        assert 0 <= k.real * L <= mp.pi


# ---------------------------------------------------------- (d) det T = 1, palindromic

MIXED = {
    "beam": {
        "segments": [
            {"length": 0.4, "EI": 2.0, "mass_per_length": 3.0},
            {
                "length": 0.35,
                "EI": 0.7,
                "mass_per_length": 1.2,
                "kappa_GA": 300.0,
                "rho_I": 0.01,
                "axial_force": 4.0,
                "foundation_k": 20.0,
            },
            {"length": 0.5, "EI": 1.5, "mass_per_length": 2.0},
        ]
    },
    "attachments": [
        {"type": "spring_mass", "x": 0.0, "k": 40.0, "m": 0.05},
        {"type": "mass", "x": 0.2, "m": 0.3, "J": 0.002},
        {"type": "rotational_spring", "x": 0.75, "k": 3.0},
        {"type": "spring", "x": 0.9, "k": 20.0},
        {"type": "oscillator_chain", "x": 1.0, "k": [30.0, 80.0], "m": [0.04, 0.02]},
    ],
}


def _damped(cell):
    out = {"beam": dict(cell["beam"]), "attachments": [dict(a) for a in cell["attachments"]]}
    out["beam"]["segments"] = [dict(s, loss_factor=0.02) for s in cell["beam"]["segments"]]
    out["attachments"][0]["c"] = 0.3
    out["attachments"].append({"type": "dashpot", "x": 0.7, "c": 0.5})
    return out


@pytest.mark.parametrize("omega", [0.7, 13.0, 95.0, mpmath.mpc(40, 2)])
def test_det_one_and_palindromic(omega):
    for cell in (MIXED, _damped(MIXED)):
        T = cell_transfer(cell, omega, dps=60)
        assert close(mpmath.det(T), 1, mpf(10) ** -35)
        c = characteristic(cell, omega)
        assert close(c[0], c[4], mpf(10) ** -35) and close(c[1], c[3], mpf(10) ** -35)
        mu1, mu2 = bloch_mu(cell, omega)  # the pairs lam, 1/lam of the eigenvalues of T
        lams = mpmath.eig(T, left=False, right=False)
        mus = sorted((lam + 1 / lam for lam in lams), key=lambda v: -abs(v))
        assert _same_set((mus[0], mus[-1]), (mu1, mu2), mpf(10) ** -25)
        assert abs(mu1) >= abs(mu2)


def test_support_cell_pencil_and_polynomial():
    cell = {**MIXED, "attachments": MIXED["attachments"] + [{"type": "support", "x": 0.6}]}
    with pytest.raises(ValueError):
        cell_transfer(cell, 10.0)
    for omega in (3.0, 60.0):
        c = characteristic(cell, omega)
        assert c[4] == 0 and abs(c[0]) < mpf(10) ** -35 and close(c[1], c[3], mpf(10) ** -35)
        mu1, mu2 = bloch_mu(cell, omega)
        assert mu1 is None
        # the pencil: P v = lam R v has the eigenvalue lam with lam + 1/lam = mu2
        P, R = cell_pencil(cell, omega)
        lam = (mu2 + mpmath.sqrt(mu2 * mu2 - 4)) / 2
        det = mpmath.det(P - lam * R)
        assert abs(det) < mpf(10) ** -30 * max(abs(v) for v in P)


# ------------------------------------------------------- (b) Mead: periodically pinned


def _pinned(L, xs):
    return {
        "beam": {"length": L, "EI": 2.0, "mass_per_length": 3.0},
        "attachments": [{"type": "support", "x": x} for x in xs],
    }


def test_pinned_mu_mead():
    """cos(k L) = (sinh x cos x - cosh x sin x) / (sinh x - sin x), x = lam L (Mead 1970),
    wherever the support sits in the cell; two supports per cell of 2L: mu -> mu^2 - 2."""
    L = 1.5
    for omega in (0.3, 7.7, 30.0, 400.0):
        x = mpmath.root(3 * mpf(omega) ** 2 / 2, 4) * L
        sh, ch, s, c = mpmath.sinh(x), mpmath.cosh(x), mpmath.sin(x), mpmath.cos(x)
        mead = 2 * (sh * c - ch * s) / (sh - s)
        for xs in ([0.0], [0.37 * L]):
            mu1, mu2 = bloch_mu(_pinned(L, xs), omega)
            assert mu1 is None and close(mu2, mead, mpf(10) ** -37)
        _n, mu = bloch_mu(_pinned(2 * L, [0.125, 0.125 + L]), omega)
        assert close(mu, mead**2 - 2, mpf(10) ** -35)


def test_pinned_band_edges():
    """Pass bands bounded by the bay's pinned-pinned (x = n pi) and clamped-clamped
    (cos x cosh x = 1) frequencies: x = n pi periodic for even n, the clamped-clamped ones
    alternately periodic (symmetric modes) and antiperiodic."""
    L = 1.5
    scale = mpmath.sqrt(mpf(2) / 3) / mpf(L) ** 2
    x_hi = 5.2 * mp.pi
    pp = [(n * mp.pi, "periodic" if n % 2 == 0 else "antiperiodic") for n in range(1, 6)]
    cc = []
    for n in range(1, 5):
        guess = (n + mpf(1) / 2) * mp.pi
        root = mpmath.findroot(lambda x: mpmath.cos(x) - 1 / mpmath.cosh(x), guess)
        cc.append((root, "periodic" if n % 2 else "antiperiodic"))
    want = sorted(pp + cc)
    for xs in ([0.0], [0.2]):
        edges = band_edges(_pinned(L, xs), 0, float(x_hi**2 * scale), dps=40)
        assert len(edges) == len(want)
        for (w, kind, m), (x, wkind) in zip(edges, want):
            assert m == 1 and kind == wkind
            assert close(w, x**2 * scale, mpf(10) ** -37)


def test_resonator_on_a_support_is_a_flat_band():
    """A spring_mass hung on a support does not couple: sqrt(k/m) is an eigenvalue of both
    closed cells (a flat band); the Bloch wave does not see it."""
    cell = _pinned(1.0, [0.0])
    cell["attachments"].append({"type": "spring_mass", "x": 0.0, "k": 400.0, "m": 1.0})
    edges = band_edges(cell, 19.0, 21.0, dps=30)
    assert [(float(w), k, m) for w, k, m in edges] == [
        (20.0, "antiperiodic", 1),
        (20.0, "periodic", 1),
    ]
    assert bloch_mu(cell, 21.0)[1] == bloch_mu(_pinned(1.0, [0.0]), 21.0)[1]


def test_compressed_cell():
    """EI W'''' - P W'' = mbar w^2 W with P < 0: w^2 = (EI k^4 + P k^2) / mbar at k L = n pi
    (double); buckled (ValueError) when that is negative for n = 1."""
    cell = bare(EI=1.0, mbar=1.0, L=1.0, axial_force=-5.0)
    edges = band_edges(cell, 0, 100.0, dps=30)
    assert [(k, m) for _w, k, m in edges] == [
        ("antiperiodic", 2),
        ("periodic", 2),
        ("antiperiodic", 2),
    ]
    for n, (w, _k, _m) in enumerate(edges, start=1):
        k = n * mp.pi
        assert close(w, mpmath.sqrt(k**4 - 5 * k**2), mpf(10) ** -28)
    with pytest.raises(ValueError, match="buckled"):
        band_edges(bare(EI=1.0, mbar=1.0, L=1.0, axial_force=-30.0), 0, 100.0)


# -------------------------------------------------------------- (c) Sugino's asymptote


@pytest.mark.parametrize("r", [0.1, 0.03, 0.01])
@pytest.mark.parametrize("mu", [1e-2, 1e-3, 1e-4])
def test_sugino_gap(r, mu):
    """Resonators (m = mu mbar L, tuned to w_t = r w_B, w_B = pi^2 sqrt(EI / mbar) / L^2 the
    first Bragg frequency): the gap [w_lo (antiperiodic), w_hi (periodic)] tends to Sugino's
    [w_t, w_t sqrt(1 + mu)].  First order in mu r^2, from the ring's point receptance
    (antiperiodic L^3 / (48 EI), periodic flexible part L^3 / (720 EI)):
    w_lo = w_t (1 - pi^4 mu r^2 / 96), w_hi = w_t sqrt(1 + mu) (1 - pi^4 mu r^2 / 1440)."""
    wt = r * mp.pi**2
    cell = {
        "beam": {"length": 1.0, "EI": 1.0, "mass_per_length": 1.0},
        "attachments": [{"type": "spring_mass", "x": 0.3, "k": float(mu * wt**2), "m": mu}],
    }
    edges = band_edges(cell, float(wt / 2), float(2 * wt), dps=30)
    assert [k for _w, k, _m in edges] == ["antiperiodic", "periodic"]
    wt = mpmath.sqrt(mpf(float(mu * wt**2)) / mpf(mu))  # the tuning as the floats state it
    e_lo = 1 - edges[0][0] / wt
    e_hi = edges[1][0] / (wt * mpmath.sqrt(1 + mpf(mu))) - 1
    eps = mu * r * r
    assert 0 < e_lo < 1.03 * eps and -0.07 * eps < e_hi < 0
    assert close(e_lo / eps, mp.pi**4 / 96, 1.5 * r**2 + 2 * mu)
    assert close(e_hi / eps, -(mp.pi**4) / 1440, 1.5 * r**2 + 2 * mu)


# ------------------------------- symmetric cells against the global-determinant reference

# A cell symmetric about x = L/2 (and so about its ends): its periodic modes are those of
# the half cell [0, L/2] sliding-sliding (symmetric) and pinned-pinned (antisymmetric), its
# antiperiodic ones sliding-pinned and pinned-sliding; an attachment on a symmetry point
# goes into a sliding end's half cell with half its k and m (dropped at a pinned end: it
# does not move).


def _symmetric(general: dict):
    beam = {"length": 1.0, "EI": 1.0, "mass_per_length": 1.0, **general}
    atts = [
        {"type": "spring_mass", "x": 0.5, "k": 40.0, "m": 0.2},
        {"type": "oscillator_chain", "x": 0.0, "k": [300.0, 900.0], "m": [0.3, 0.1]},
        {"type": "mass", "x": 0.25, "m": 0.1, "J": 0.001},
        {"type": "mass", "x": 0.75, "m": 0.1, "J": 0.001},
        {"type": "rotational_spring", "x": 0.125, "k": 2.0},
        {"type": "rotational_spring", "x": 0.875, "k": 2.0},
    ]
    return {"beam": beam, "attachments": atts}


def _half(general: dict, left: str, right: str):
    beam = {"length": 0.5, "EI": 1.0, "mass_per_length": 1.0, "left": left, "right": right}
    atts = [
        {"type": "mass", "x": 0.25, "m": 0.1, "J": 0.001},
        {"type": "rotational_spring", "x": 0.125, "k": 2.0},
    ]
    if left == "sliding":
        atts.append({"type": "oscillator_chain", "x": 0.0, "k": [150.0, 450.0], "m": [0.15, 0.05]})
    if right == "sliding":
        atts.append({"type": "spring_mass", "x": 0.5, "k": 20.0, "m": 0.1})
    return {"beam": {**beam, **general}, "attachments": atts}


@pytest.mark.parametrize("general", [{}, {"axial_force": 5.0, "foundation_k": 30.0}])
def test_symmetric_cell_against_reference_model(general):
    w_hi = 420.0
    edges = band_edges(_symmetric(general), 0, w_hi, dps=30)
    for kind, halves in (
        ("periodic", [("sliding", "sliding"), ("pinned", "pinned")]),
        ("antiperiodic", [("sliding", "pinned"), ("pinned", "sliding")]),
    ):
        want = sorted(w for h in halves for w in rm.band(_half(general, *h), 0, w_hi, dps=30))
        want = [w for w in want if w > 0]  # the rigid translation of the periodic ring
        got = [w for w, k, m in edges if k == kind for _ in range(m)]
        assert len(got) == len(want) > 5
        assert all(close(a, b, mpf(10) ** -27) for a, b in zip(got, want))


# ---------------------------------------------- edges against the transfer formulation


def test_edges_are_where_mu_is_pm2_and_none_missed():
    """An asymmetric cell (segments, general physics, every kind, a support): each edge has
    a mu within 1e-25 of +-2 (the count and the transfer matrix are separate formulations),
    and a scan of det(P -+ R) finds no sign change that band_edges lacks."""
    cell = {**MIXED, "attachments": MIXED["attachments"] + [{"type": "support", "x": 0.95}]}
    w_hi = 260.0
    edges = band_edges(cell, 0, w_hi, dps=30)
    assert len(edges) >= 20
    for w, kind, m in edges:
        target = 2 if kind == "periodic" else -2
        assert m == 1
        _n, mu = bloch_mu(cell, w, dps=30)
        assert abs(mu - target) < mpf(10) ** -25
    for kind, lam in (("periodic", 1), ("antiperiodic", -1)):
        found = [w for w, k, _m in edges if k == kind]
        grid = [mpf(w_hi) * i / 150 for i in range(1, 151)]
        vals = [_entire_det(cell, w, lam) for w in grid]
        for a, b, fa, fb in zip(grid, grid[1:], vals, vals[1:]):
            inside = sum(1 for w in found if a <= w < b)
            if (fa > 0) != (fb > 0):
                assert inside % 2 == 1
        assert edge_count(cell, w_hi, kind) == len(found)


def _entire_det(cell, w, lam):
    """det(P - lam R) times the attachments' pole factors (k - m w^2 of the spring_mass, the
    chain's det(K - w^2 M) with its base held): free of poles in w."""
    P, R = cell_pencil(cell, w, dps=20)
    value = mpmath.det(P - lam * R)
    for a in cell["attachments"]:
        if a["type"] == "spring_mass":
            value *= a["k"] - a["m"] * w**2
        elif a["type"] == "oscillator_chain":
            (k1, k2), (m1, m2) = a["k"], a["m"]
            value *= (k1 + k2 - m1 * w**2) * (k2 - m2 * w**2) - k2 * k2
    return value


def test_edges_stable_in_dps_and_band():
    a = band_edges(MIXED, 0, 150.0, dps=30)
    b = band_edges(MIXED, 0, 150.0, dps=45)
    assert [(k, m) for _w, k, m in a] == [(k, m) for _w, k, m in b]
    assert all(close(x[0], y[0], mpf(10) ** -31) for x, y in zip(a, b))
    part = band_edges(MIXED, 40.0, 120.0, dps=30)
    assert [(w, k, m) for w, k, m in a if 40 <= w < 120] == part and len(part) >= 6


def test_band_edges_refuses_damping():
    with pytest.raises(ValueError):
        band_edges(_damped(MIXED), 0, 10.0)

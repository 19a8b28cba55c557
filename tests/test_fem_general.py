"""Checks of the finite-element model (tests/reference_fem.py) with the optional segment terms
``kappa_GA``, ``rho_I``, ``axial_force``, ``foundation_k``, ``foundation_kG``, against
closed forms only (not against mstmm).  Closed forms used:

* Pinned-pinned uniform beam, mode n, ``k = n pi / L``, ``t = P + k_G``: the roots
  ``omega^2`` of ``det [[kGA k^2 + t k^2 + k_w - mbar w^2, -kGA k], [-kGA k, EI k^2 + kGA
  - rho_I w^2]] = 0`` (both per n), with ``kGA > 0`` and ``rho_I > 0`` the thickness-shear
  mode ``w = 0``, ``psi`` constant at ``omega^2 = kGA / rho_I``; without shear
  ``omega^2 = (EI k^4 + t k^2 + k_w) / (mbar + rho_I k^2)``.  A loss factor multiplies
  EI, kGA, k_w, k_G by ``1 + i eta`` (not P).
* Its buckling load ``P_cr = -P_E / (1 + P_E / kGA)``, ``P_E = pi^2 EI / L^2``.
* Free-free beam on a Winkler foundation: ``omega^2 = k_w / mbar`` twice (the former
  rigid modes), then ``omega_n^2 + k_w / mbar``, ``beta_n L`` the roots of
  ``cos x cosh x = 1``.
* Symmetry about the middle of a pinned-pinned beam: the modes with ``w(L/2) = 0`` (even
  n, and the thickness-shear mode) ignore a translational attachment there, those with
  ``psi(L/2) = 0`` (odd n) a rotational one; a hinge with a support there cuts the beam
  into two independent pinned-pinned spans of length ``L/2``.
* A static central force on a pinned-pinned Timoshenko beam: ``L^3 / (48 EI) + L / (4
  kGA)`` (the exact static solution lies in the element's space: exact on any mesh).

The measured errors (Richardson of 64 and 128 elements, six modes) are <= 9.3e-10; the
tolerances below sit about 2x above the largest measured value.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # small dense eigenproblems: threads hurt

import sys  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
import pytest  # noqa: E402
import scipy.optimize  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))

import reference_fem as fem  # noqa: E402

L, EI, MBAR = 2.0, 3.0, 1.5
P_E = np.pi**2 * EI / L**2  # Euler buckling load of the pinned-pinned beam
KEYS = ("kappa_GA", "rho_I", "axial_force", "foundation_k", "foundation_kG")

CASES = {
    "tension": {"axial_force": 40.0},
    "compression": {"axial_force": -0.6 * P_E},
    "winkler": {"foundation_k": 200.0},
    "pasternak": {"foundation_kG": 15.0},
    "rayleigh": {"rho_I": 0.02},
    "timoshenko": {"kappa_GA": 60.0},
    "timoshenko_rotary": {"kappa_GA": 60.0, "rho_I": 0.02},
    "combined": {
        "kappa_GA": 60.0,
        "rho_I": 0.02,
        "axial_force": -5.0,
        "foundation_k": 200.0,
        "foundation_kG": 15.0,
    },
}
COMBINED = CASES["combined"]


def uniform(left="pinned", right="pinned", length=L, attachments=(), **physics) -> dict:
    beam = {"length": length, "EI": EI, "mass_per_length": MBAR, "left": left, "right": right}
    return {"beam": beam | physics, "attachments": list(attachments)}


def pinned_modes(count: int, length=L, loss_factor=0.0, **physics) -> list[tuple[int, complex]]:
    """``(n, omega)`` of the lowest ``count`` modes of the pinned-pinned uniform beam (n = 0:
    the thickness-shear mode), ascending; complex with a loss factor."""
    kga, rhoi, p, kw, kg = (float(physics.get(key, 0.0)) for key in KEYS)
    f = 1.0 + 1j * loss_factor
    out = []
    for n in range(1, count + 1):
        k = n * np.pi / length
        if kga == 0:
            out.append((n, ((EI * k**4 + kg * k**2 + kw) * f + p * k**2) / (MBAR + rhoi * k**2)))
            continue
        a11 = (kga + kg) * k**2 * f + kw * f + p * k**2
        a12, a22 = -kga * k * f, (EI * k**2 + kga) * f
        # (a11 - mbar w^2) (a22 - rho_I w^2) - a12^2 = 0, a polynomial in w^2
        c = [MBAR * rhoi, -(a11 * rhoi + a22 * MBAR), a11 * a22 - a12**2]
        out += [(n, r) for r in (np.roots(c) if rhoi > 0 else [-c[2] / c[1]])]
    if kga > 0 and rhoi > 0:
        out.append((0, kga * f / rhoi))
    modes = sorted(((n, np.sqrt(complex(w2))) for n, w2 in out), key=lambda m: m[1].real)
    modes = modes[:count]
    return modes if loss_factor else [(n, w.real) for n, w in modes]


def exact(count: int, **physics) -> np.ndarray:
    return np.array([w for _, w in pinned_modes(count, **physics)])


def rel(a, b) -> np.ndarray:
    return np.abs(np.asarray(a) / np.asarray(b) - 1.0)


# --- pinned-pinned closed forms -------------------------------------------------------------


@pytest.mark.parametrize("name", sorted(CASES))
def test_pinned_pinned_closed_form(name):
    """Richardson(64 -> 128 elements) within 2e-9 of the closed form (measured <= 9.3e-10,
    Rayleigh's sixth mode), the plain FE frequencies upper bounds converging as h^4 (error
    ratio 15.36 - 16.05 between 16, 32 and 64 elements), dense and sparse alike."""
    physics = CASES[name]
    scene, ref = uniform(**physics), exact(6, **physics)
    rich = fem.richardson(scene, 6, 64, "sparse")
    assert np.all(rel(rich, ref) < 2e-9), rel(rich, ref)
    plain = {n: fem.frequencies(scene, 6, n, "sparse") for n in (16, 32, 64)}
    assert np.all(rel(fem.frequencies(scene, 6, 32, "dense"), plain[32]) < 1e-12)
    for w in plain.values():
        assert np.all(w >= ref * (1 - 1e-13))  # Rayleigh-Ritz: upper bounds
    err = {n: w / ref - 1 for n, w in plain.items()}
    elastic = err[16] > 1e-12  # the thickness-shear mode is exact on any mesh
    for coarse, fine in ((16, 32), (32, 64)):
        ratio = err[coarse][elastic] / err[fine][elastic]
        assert np.all((ratio > 15.0) & (ratio < 16.5)), ratio


def test_thickness_shear_mode_exact():
    """w = 0, psi constant is in the FE space: omega^2 = kGA / rho_I on any mesh."""
    physics = CASES["timoshenko_rotary"]
    w = fem.frequencies(uniform(**physics), 12, 4)
    assert np.min(rel(w, np.sqrt(60.0 / 0.02))) < 1e-13


def test_solvers_agree():
    """dense, sparse, svd and eigh agree where each applies; svd refuses a compression and
    both svd and eigh a Timoshenko segment without rho_I (singular mass)."""
    for physics in (CASES["tension"], CASES["winkler"], CASES["timoshenko_rotary"]):
        scene = uniform(**physics)
        dense = fem.frequencies(scene, 5, 16)
        assert np.all(rel(fem.frequencies(scene, 5, 16, "svd"), dense) < 1e-11)
        assert np.all(rel(fem.frequencies(scene, 5, 16, "eigh"), dense) < 1e-8)
        assert np.all(rel(fem.frequencies(scene, 5, 16, "sparse"), dense) < 1e-12)
    for physics, refused in (
        (CASES["compression"], ("svd",)),
        (CASES["timoshenko"], ("svd", "eigh")),
    ):
        scene = uniform(**physics)
        dense = fem.frequencies(scene, 5, 16)
        assert np.all(rel(fem.frequencies(scene, 5, 16, "sparse"), dense) < 1e-12)
        for solver in refused:
            with pytest.raises(ValueError, match="svd|eigh"):
                fem.frequencies(scene, 5, 16, solver)


# --- other closed forms ----------------------------------------------------------------------


def test_free_free_on_winkler_foundation():
    """The former rigid modes at sqrt(k_w / mbar), then sqrt(omega_n^2 + k_w / mbar)."""
    kw = 200.0
    roots = [
        scipy.optimize.brentq(lambda x: np.cos(x) * np.cosh(x) - 1.0, a, a + 1.5)
        for a in (4.0, 7.0, 10.5, 13.7)
    ]
    ref = np.sqrt(
        np.array([kw, kw] + [(r / L) ** 4 * EI + kw for r in roots]) / MBAR
    )  # omega_n^2 = (beta_n L)^4 EI / (mbar L^4)
    scene = uniform("free", "free", foundation_k=kw)
    assert np.all(rel(fem.frequencies(scene, 6, 8)[:2], ref[:2]) < 1e-13)  # rigid: exact
    rich = fem.richardson(scene, 6, 64, "sparse")
    assert np.all(rel(rich, ref) < 1e-9), rel(rich, ref)  # measured 2.7e-10


def test_buckling():
    """Pinned-pinned: 1.01 P_E (and far beyond, where the Cholesky factorization of
    K - sigma M fails) buckled in every function, 0.99 P_E gives the closed form."""
    for factor in (1.01, 5.0):
        scene = uniform(axial_force=-factor * P_E)
        for call in (
            lambda s=scene: fem.frequencies(s, 2, 16),
            lambda s=scene: fem.frequencies(s, 2, 16, "sparse"),
            lambda s=scene: fem.richardson(s, 2, 16),
            lambda s=scene: fem.count_below(s, 5.0, 16),
            lambda s=scene: fem.damped_frequencies(s, 2, 16),
            lambda s=scene: fem.frf(s, ("force", "x", 0.5), ("displacement", "x", 1.0), [1.0], 8),
        ):
            with pytest.raises(ValueError, match="buckled"):
                call()
    p = -0.99 * P_E
    k = np.pi / L
    w1 = np.sqrt(((k**4) * EI + p * k**2) / MBAR)
    scene = uniform(axial_force=p)
    # near buckling omega_1 is a small difference (measured error 2.5e-12)
    assert rel(fem.richardson(scene, 1, 64, "sparse")[0], w1) < 1e-10
    assert fem.count_below(scene, 1.001 * w1, 32) == 1
    assert fem.count_below(scene, 0.999 * w1, 32) == 0


def test_timoshenko_buckling_load():
    """P_cr = -P_E / (1 + P_E / kGA): 0.99 of it is stable, 1.01 buckled; a compression
    beyond kGA + k_G buckles in shear."""
    kga = 60.0
    p_cr = -P_E / (1 + P_E / kga)
    k = np.pi / L
    stable = uniform(kappa_GA=kga, axial_force=0.99 * p_cr)
    w = fem.richardson(stable, 1, 64, "sparse")[0]
    assert rel(w, exact(1, kappa_GA=kga, axial_force=0.99 * p_cr)[0]) < 1e-10  # 2.1e-12
    assert w < 0.2 * np.sqrt(EI * k**4 / MBAR)
    for p in (1.01 * p_cr, -1.5 * kga):
        with pytest.raises(ValueError, match="buckled"):
            fem.frequencies(uniform(kappa_GA=kga, axial_force=p), 1, 32)


def test_count_below():
    """Between consecutive closed-form frequencies of each case the inertia count is their
    index (the FE ones are upper bounds within 1e-5 at 32 elements)."""
    for physics in CASES.values():
        ref = exact(8, **physics)
        scene = uniform(**physics)
        mids = 0.5 * (ref[:-1] + ref[1:])
        assert [fem.count_below(scene, w, 32) for w in mids] == list(range(1, 8))
        assert fem.count_below(scene, 0.5 * ref[0], 32) == 0


# --- attachments on beams with these terms ---------------------------------------------------

MIDDLE = L / 2


@pytest.mark.parametrize(
    "attachment,unaffected",
    [
        ({"type": "spring", "k": 400.0}, "w"),
        ({"type": "spring_mass", "k": 400.0, "m": 0.3}, "w"),
        ({"type": "mass", "m": 0.4}, "w"),
        ({"type": "support"}, "w"),
        ({"type": "rotational_spring", "k": 30.0}, "psi"),
        ({"type": "mass", "m": 0.0, "J": 0.05}, "psi"),
    ],
    ids=lambda v: v["type"] + ("_J" if v.get("J") else "") if isinstance(v, dict) else v,
)
@pytest.mark.parametrize("physics", ["combined", "rayleigh"])
def test_attachment_at_the_middle(attachment, unaffected, physics):
    """A translational attachment at L/2 leaves the modes with w(L/2) = 0 (even n, the
    thickness-shear mode n = 0), a rotational one those with psi(L/2) = 0 (odd n): each
    still an FE frequency within 2e-9 after Richardson(64) (the six lowest closed-form
    modes; measured <= 9e-10), the others moved."""
    terms = CASES[physics]
    scene = uniform(attachments=[attachment | {"x": MIDDLE}], **terms)
    rich = fem.richardson(scene, 12, 64, "sparse")
    modes = pinned_modes(6, **terms)
    kept = [w for n, w in modes if (n % 2 == 0) == (unaffected == "w")]
    moved = [w for n, w in modes if (n % 2 == 0) != (unaffected == "w")]
    assert len(kept) >= 2 and len(moved) >= 3
    for w in kept:
        assert np.min(rel(rich, w)) < 2e-9, (w, np.min(rel(rich, w)))
    for w in moved:
        assert np.min(rel(rich, w)) > 1e-4


def test_hinge_and_support_split_the_beam():
    """A hinge (k = 0) with a support at L/2: two independent pinned-pinned spans of length
    L/2, every frequency twice (the thickness-shear one too: the hinge splits psi)."""
    scene = uniform(
        attachments=[{"type": "hinge", "x": MIDDLE}, {"type": "support", "x": MIDDLE}],
        **COMBINED,
    )
    ref = np.repeat(exact(4, length=L / 2, **COMBINED), 2)
    rich = fem.richardson(scene, 8, 64, "sparse")
    assert np.all(rel(rich, ref) < 2e-9), rel(rich, ref)  # measured 6.3e-11


def test_static_timoshenko_receptance_exact():
    """frf at w = 0, central force on a pinned-pinned Timoshenko beam: L^3 / (48 EI) +
    L / (4 kGA) on any mesh (round-off only); reciprocity with a rotation."""
    kga = 60.0
    scene = uniform(kappa_GA=kga)
    mid = ("displacement", "x", MIDDLE)
    for n in (2, 6):
        h = fem.frf(scene, ("force", "x", MIDDLE), mid, [0.0], n)[0]
        assert rel(h, L**3 / (48 * EI) + L / (4 * kga)) < 1e-13
    scene = uniform("clamped", "free", **COMBINED)
    w = [2.0, 7.0 + 0.5j]
    one = fem.frf(scene, ("force", "x", 0.5), ("rotation", "x", 1.7), w, 16)
    two = fem.frf(scene, ("moment", "x", 1.7), ("displacement", "x", 0.5), w, 16)
    assert np.all(rel(one, two) < 1e-11)


# --- damping ---------------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["timoshenko", "timoshenko_rotary", "combined", "tension"])
def test_loss_factor_closed_form(name):
    """The loss factor on EI, kGA, k_w, k_G but not on P: damped_richardson(16 -> 32
    elements, dense state-space eigenvalues: a modest mesh) against the complex closed
    form within 3e-7 (measured <= 1.3e-7; a loss factor on P too would be off by ~1e-2)."""
    physics = CASES[name]
    eta = 0.04
    ref = np.array([w for _, w in pinned_modes(4, loss_factor=eta, **physics)])
    scene = uniform(loss_factor=eta, **physics)
    got = fem.damped_richardson(scene, 4, 16)
    assert np.all(np.abs(got - ref) < 3e-7 * np.abs(ref)), np.abs(got / ref - 1)


def test_loss_factor_without_axial_force_scales_every_root():
    """P = 0: K* = (1 + i eta) K exactly, every FE root is the undamped one times
    sqrt(1 + i eta), the massless rotations (rho_I = 0) dropped from the spectrum."""
    eta = 0.05
    for physics in (CASES["timoshenko"], COMBINED | {"axial_force": 0.0}):
        scene = uniform("clamped", "free", **physics)
        undamped = fem.frequencies(scene, 8, 12)
        damped = fem.damped_frequencies(
            uniform("clamped", "free", loss_factor=eta, **physics), 8, 12
        )
        assert np.all(np.abs(damped / (undamped * np.sqrt(1 + 1j * eta)) - 1) < 1e-12)
        spectrum = fem.damped_spectrum(scene, 12)
        K, M = fem.assemble(scene, 12)
        finite = int(np.count_nonzero(M.diagonal() > 0))
        assert len(spectrum.roots) == finite and spectrum.n_rigid == 0
        assert np.all(rel(np.sort(spectrum.roots.real)[:8], undamped) < 1e-12)


def test_damped_rigid_modes():
    """Free-free: two rigid modes (Timoshenko w = a + b x, psi = b), one under a tension
    (the rotation is held), none on a foundation."""
    for physics, rigid in (
        ({"kappa_GA": 60.0}, 2),
        ({"kappa_GA": 60.0, "axial_force": 5.0}, 1),
        ({"foundation_k": 10.0, "rho_I": 0.01}, 0),
    ):
        scene = uniform("free", "free", **physics)
        assert fem.damped_spectrum(scene, 8).n_rigid == rigid
        assert np.count_nonzero(fem.frequencies(scene, 4, 8) == 0) == rigid


# --- stepped beams: self-convergence ---------------------------------------------------------


def stepped(left, right, segments, attachments=()) -> dict:
    keys = ("length", "EI", "mass_per_length")
    rows = [dict(zip(keys, s[:3], strict=True)) | s[3] for s in segments]
    return {"beam": {"left": left, "right": right, "segments": rows}, "attachments": attachments}


STEPPED = {
    "eb_terms": stepped(
        "clamped",
        "pinned",
        [
            (0.75, 3.0, 1.5, {"axial_force": 20.0, "foundation_k": 150.0}),
            (1.25, 1.5, 1.0, {"rho_I": 0.01, "foundation_kG": 8.0, "axial_force": 20.0}),
        ],
    ),
    "eb_timoshenko": stepped(
        "free",
        "free",
        [
            (1.0, 3.0, 1.5, {"axial_force": -1.0, "foundation_k": 100.0}),
            (1.0, 2.0, 1.2, {"kappa_GA": 40.0, "rho_I": 0.02, "axial_force": -1.0}),
        ],
        [{"type": "spring_mass", "x": 1.25, "k": 200.0, "m": 0.2}],
    ),
    "timoshenko_timoshenko": stepped(
        "clamped",
        "free",
        [
            (1.25, 3.0, 1.5, {"kappa_GA": 80.0, "foundation_kG": 5.0}),
            (0.75, 1.0, 0.8, {"kappa_GA": 30.0, "rho_I": 0.005}),
        ],
        [
            {"type": "mass", "x": 2.0, "m": 0.3, "J": 0.01},
            {"type": "hinge", "x": 0.625, "k": 20.0},
            {"type": "rotational_spring", "x": 1.5, "k": 10.0},
        ],
    ),
}


@pytest.mark.parametrize("name", sorted(STEPPED))
def test_stepped_self_convergence(name):
    """Two segments with different terms (Euler-Bernoulli or Timoshenko on either side),
    meshes 16, 32, 64 (nested: the boundaries and attachments on the 16-element nodes):
    the plain frequencies decrease (upper bounds), their differences fall as h^4 (measured
    ratio 15.1 - 16.0), those of Richardson as h^6 (measured 50 - 67), and the error of
    Richardson(64) estimated from them, ``(R32 - R64) / 63``, is below 2e-9 (measured
    <= 1.4e-9)."""
    scene = STEPPED[name]
    w = {n: fem.frequencies(scene, 6, n, "sparse") for n in (16, 32, 64)}
    assert np.all(w[16] >= w[32]) and np.all(w[32] >= w[64])
    ratio = (w[16] - w[32]) / (w[32] - w[64])
    assert np.all((ratio > 14.5) & (ratio < 16.5)), ratio
    r = {n: fem.richardson(scene, 6, n, "sparse") for n in (16, 32, 64)}
    ratio = (r[16] - r[32]) / (r[32] - r[64])
    assert np.all((ratio > 45.0) & (ratio < 75.0)), ratio
    assert np.all(rel(r[32], r[64]) / 63 < 2e-9), rel(r[32], r[64]) / 63


def test_large_shear_stiffness_tends_to_euler_bernoulli():
    """Same mesh, every attachment kind: the Timoshenko element's space holds the Hermite
    one, so its frequencies lie below, by O(EI / (kGA L^2))."""
    base = STEPPED["timoshenko_timoshenko"]
    plain = stepped(
        "free",
        "sliding",
        [(1.25, 3.0, 1.5, {}), (0.75, 1.0, 0.8, {"rho_I": 0.005})],
        base["attachments"] + [{"type": "oscillator_chain", "x": 1.0, "k": [90.0, 60.0]}],
    )
    plain["attachments"][-1]["m"] = [0.1, 0.05]
    eb = fem.frequencies(plain, 6, 16)
    gaps = []
    for kga in (1e5, 1e6):
        timo = stepped(
            "free",
            "sliding",
            [(s["length"], s["EI"], s["mass_per_length"], s | {"kappa_GA": kga})
             for s in plain["beam"]["segments"]],
            plain["attachments"],
        )  # fmt: skip
        w = fem.frequencies(timo, 6, 16)
        assert np.all(w <= eb * (1 + 1e-13))
        gaps.append(rel(w[eb > 0], eb[eb > 0]))
    assert np.all(gaps[0] < 1e-3) and np.all(gaps[1] < 1e-4)
    assert np.all((gaps[0] / gaps[1] > 8) & (gaps[0] / gaps[1] < 12))  # O(1 / kGA)


# --- input checks --------------------------------------------------------------------------


def test_bad_physics():
    for bad in ({"kappa_GA": -1.0}, {"rho_I": -0.1}, {"foundation_k": -1.0}):
        with pytest.raises(ValueError):
            fem.frequencies(uniform(**bad), 1, 8)
    scene = STEPPED["eb_terms"]
    scene = scene | {"beam": scene["beam"] | {"axial_force": 3.0}}
    with pytest.raises(ValueError, match="segment"):
        fem.frequencies(scene, 1, 8)

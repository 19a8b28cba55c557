"""Checks of the damped finite-element model (tests/reference_fem.py: damped_spectrum,
damped_frequencies, damped_richardson, damped_assemble, frf) against the mpmath reference
(tests/reference_model.py) and closed forms.  Not tests of mstmm.

Closed forms and exact properties used:

* A loss factor eta on every element: ``K* = (1 + i eta) K``, so every FE root is the
  undamped FE root times ``sqrt(1 + i eta)`` (exact for the discrete model).
* n identical absorbers (k, c, m) at one node: their differences leave the beam at rest,
  ``k + i w c - m w^2 = 0`` exactly, whatever the mesh (multiplicity n - 1).
* The zero eigenvalue's algebraic multiplicity: ``2 dim null K - rank(V^T C V)``, V the
  rigid motions (the order of the reference's characteristic function at w = 0).
* c = 0, eta = 0: the state-space roots are the undamped FE frequencies.
* Static receptances: Hermite cubic elements are exact at the nodes for nodal loads, so at
  w = 0 the FE receptance equals the exact one (the reference's).
* Reciprocity: K*, C and M are symmetric, so ``H(a, b) = H(b, a)`` for work-conjugate
  pairs (force / displacement, moment / rotation, across).
* Convergence: the damped roots' error is ``O(h^4)`` (error ratio 16 between a mesh and
  its bisection), ``O(h^6)`` after Richardson (ratio 64), measured here.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # small dense eigvals: threads only hurt

import functools  # noqa: E402
import sys  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
import pytest  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))

import reference_fem as fem  # noqa: E402
import reference_model as ref  # noqa: E402


def beam(left, right, attachments=(), length=1.0, ei=1.0, mbar=1.0, **extra):
    values = {"length": length, "EI": ei, "mass_per_length": mbar, "left": left, "right": right}
    return {"beam": values | extra, "attachments": list(attachments)}


def absorber(x, k, m, c=0.0):
    return {"type": "spring_mass", "x": x, "k": k, "m": m, "c": c}


def stepped(left, right, segments, attachments=()):
    keys = ("length", "EI", "mass_per_length")
    return {
        "beam": {
            "left": left,
            "right": right,
            "segments": [dict(zip(keys, s[:3], strict=True)) | s[3] for s in segments],
        },
        "attachments": list(attachments),
    }


def rel(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return np.abs(a - b) / np.where(b == 0, 1.0, np.abs(b))


def bisect(nodes):
    return np.sort(np.concatenate([nodes, 0.5 * (nodes[:-1] + nodes[1:])]))


SCENES = {
    "spring_dashpot_mass": beam(
        "clamped", "free", [absorber(0.9, 30.0, 0.2, 0.4)], length=1.2, ei=2.0, mbar=1.5
    ),
    "two_absorbers_at_one_point": beam("pinned", "pinned", [absorber(0.4, 80.0, 0.1, 0.3)] * 2),
    "grounded_dashpot": beam("free", "free", [{"type": "dashpot", "x": 0.3, "c": 0.5}]),
    "overdamped_absorber": beam("clamped", "pinned", [absorber(0.5, 40.0, 0.1, 5.0)]),
    "loss_factor_stepped": stepped(
        "clamped",
        "free",
        [(0.4, 3.0, 2.0, {"loss_factor": 0.02}), (0.6, 1.0, 1.0, {"loss_factor": 0.08})],
        [{"type": "mass", "x": 1.0, "m": 0.2, "J": 0.01}],
    ),
    "damped_chain": beam(
        "clamped",
        "free",
        [
            {"type": "oscillator_chain", "x": 0.8, "k": [60.0, 20.0], "m": [0.15, 0.1]}
            | {"c": [0.2, 0.05]}
        ],
    ),
    "every_kind": stepped(
        "free",
        "sliding",
        [(0.5, 2.0, 1.5, {"loss_factor": 0.03}), (0.75, 1.0, 1.0, {})],
        [
            {"type": "hinge", "x": 0.5, "k": 3.0},
            absorber(0.5, 250.0, 0.1, 0.2),
            {"type": "mass", "x": 0.25, "m": 0.2, "J": 0.003},
            {"type": "oscillator_chain", "x": 1.25, "k": [100.0, 80.0], "m": [0.1, 0.1]}
            | {"c": [0.0, 0.3]},
            {"type": "spring", "x": 0.875, "k": 20.0},
            {"type": "rotational_spring", "x": 0.3, "k": 2.0},
            {"type": "dashpot", "x": 1.0, "c": 0.4},
        ],
    ),
}


@functools.cache
def exact_roots(name, n=6):
    return np.array([complex(w) for w in ref.damped_frequencies(SCENES[name], n, dps=20)])


def fe_roots(model, nodes, n):
    spectrum = fem._spectrum(model, nodes)
    return np.concatenate([np.zeros(spectrum.n_rigid, complex), spectrum.roots])[:n]


@pytest.mark.parametrize("name", sorted(SCENES))
def test_damped_roots_against_the_reference(name):
    """6 roots: Richardson(64 -> 128) within 1e-9 of the mpmath roots (measured <= 2e-10),
    the plain error falling as h^4 (ratio 16) and Richardson's as h^6 (ratio 64), the same
    rigid-body zeros and overdamped roots (exactly on the imaginary axis)."""
    exact = exact_roots(name)
    model = fem._model(SCENES[name])
    meshes = [fem._nodes(model, 32)]
    meshes += [bisect(meshes[0]), bisect(bisect(meshes[0]))]
    w = [fe_roots(model, nodes, 6) for nodes in meshes]
    for x in w:
        assert np.array_equal(x == 0, exact == 0)
        assert np.array_equal(x.real == 0, exact.real == 0)
    err = [rel(x, exact) for x in w]
    rich = [rel(w[i + 1] + (w[i + 1] - w[i]) / 15, exact) for i in range(2)]
    assert np.all(rich[1] < 1e-9), rich[1]
    assert np.all(err[2] < 2e-7)
    moving = err[1] > 1e-12  # exact zeros and the absorbers' mesh-free root do not move
    ratio = err[1][moving] / err[2][moving]
    assert np.all(ratio > 15.5) and np.all(ratio < 16.5), ratio
    above = rich[0] > 1e-11  # well above round-off
    assert np.count_nonzero(above) >= 3
    ratio = rich[0][above] / rich[1][above]
    assert np.all(ratio > 55) and np.all(ratio < 75), ratio
    assert np.all(rel(fem.damped_richardson(SCENES[name], 6, 64), exact) < 1e-9)


def test_zero_eigenvalue_multiplicity_matches_the_reference():
    cases = {
        "free_free_dashpot": (SCENES["grounded_dashpot"], 2, 3),
        "free_hinge_one_dashpot": (
            beam("free", "free", [{"type": "hinge", "x": 0.4}, {"type": "dashpot", "x": 0.7}]) | {},
            3,
            5,
        ),
        "free_free": (beam("free", "free", [absorber(0.2, 5.0, 0.1, 0.1)]), 2, 4),
    }
    cases["free_hinge_one_dashpot"][0]["attachments"][1]["c"] = 0.5
    for sc, n_rigid, order in cases.values():
        spectrum = fem.damped_spectrum(sc, 24)
        assert spectrum.n_rigid == n_rigid == ref.rigid_body_mode_count(sc)
        assert spectrum.n_zero == order == ref._DampedSolver(sc, 15).a0


@pytest.mark.parametrize("count", [2, 3])
def test_identical_absorbers_root_is_exact_on_any_mesh(count):
    k, m, c = 80.0, 0.1, 0.3
    sc = beam("pinned", "pinned", [absorber(0.4, k, m, c)] * count)
    exact = 1j * c / (2 * m) + np.sqrt(k / m - (c / (2 * m)) ** 2)
    w = fem.damped_frequencies(sc, 6, 16)
    assert np.count_nonzero(rel(w, exact) < 1e-12) == count - 1


def test_undamped_limit_and_loss_factor_scaling():
    """c = 0: the state-space roots are frequencies() (real up to round-off); a loss
    factor on a uniform beam multiplies every FE root by sqrt(1 + i eta) exactly."""
    plain = beam("free", "free", [absorber(0.3, 30.0, 0.1, 0.0), {"type": "dashpot", "x": 0.6}])
    plain["attachments"][1]["c"] = 0.0
    w = fem.damped_frequencies(plain, 8, 32)
    undamped = fem.frequencies(plain, 8, 32)  # accepts c = 0
    assert np.array_equal(w == 0, undamped == 0)
    assert np.all(rel(w.real, undamped) < 1e-11)  # measured 1.8e-12
    assert np.all(np.abs(w.imag) < 1e-11 * np.abs(w).max())
    eta = 0.07
    sc = beam("clamped", "free", [{"type": "mass", "x": 0.6, "m": 0.3}], loss_factor=eta)
    lossless = fem.frequencies(
        beam("clamped", "free", [{"type": "mass", "x": 0.6, "m": 0.3}]), 6, 32
    )
    assert np.all(rel(fem.damped_frequencies(sc, 6, 32), lossless * np.sqrt(1 + 1j * eta)) < 1e-11)


def test_undamped_functions_refuse_damped_scenes_and_bad_values():
    damped = beam("clamped", "free", [absorber(0.5, 10.0, 1.0, 0.5)])
    for call in (
        lambda: fem.frequencies(damped, 2, 8),
        lambda: fem.richardson(damped, 2, 8),
        lambda: fem.count_below(damped, 1.0, 8),
        lambda: fem.assemble(damped, 8),
    ):
        with pytest.raises(ValueError, match="damping"):
            call()
    for bad in (
        beam("clamped", "free", [absorber(0.5, 1.0, 1.0, -0.1)]),
        beam("clamped", "free", [{"type": "dashpot", "x": 0.5, "c": -1.0}]),
        beam("clamped", "free", [{"type": "oscillator_chain", "x": 0.5, "k": [1.0, 2.0]}]),
        beam("clamped", "free", loss_factor=-0.1),
    ):
        if bad["attachments"] and bad["attachments"][0]["type"] == "oscillator_chain":
            bad["attachments"][0] |= {"m": [1.0, 1.0], "c": [0.1]}
        with pytest.raises(ValueError):
            fem.damped_frequencies(bad, 1, 8)


def test_damped_matrices():
    """K* = sum (1 + i eta_e) K_e is complex symmetric, C symmetric positive semidefinite
    (the dashpots between their DOFs), K* = (1 + i eta) K for one loss factor."""
    sc = SCENES["every_kind"]
    K, C, M = fem.damped_assemble(sc, 16)
    assert abs(K - K.T).max() <= 1e-15 * abs(K).max() and abs(C - C.T).max() == 0
    assert np.linalg.eigvalsh(C.toarray()).min() > -1e-12
    assert abs(K.imag).max() > 0
    eta = 0.05
    K1, C1, _ = fem.damped_assemble(beam("pinned", "free", loss_factor=eta), 8)
    K0 = fem.assemble(beam("pinned", "free"), 8)[0]
    assert abs(K1 - (1 + 1j * eta) * K0).max() <= 1e-13 * abs(K0).max()
    assert C1.nnz == 0


FRF_SCENE = stepped(
    "clamped",
    "free",
    [(0.4, 3.0, 2.0, {"loss_factor": 0.02}), (0.6, 1.0, 1.0, {})],
    [
        {"type": "mass", "x": 1.0, "m": 0.2, "J": 0.01},
        absorber(0.7, 40.0, 0.1, 0.1),
        {"type": "dashpot", "x": 0.25, "c": 0.2},
        {"type": "oscillator_chain", "x": 0.4, "k": [30.0, 20.0], "m": [0.1, 0.05]}
        | {"c": [0.05, 0.0]},
    ],
)
FRF_PAIRS = [
    (("force", "x", 0.55), ("displacement", "x", 0.85)),
    (("moment", "x", 0.55), ("rotation", "x", 0.85)),
    (("force", "x", 0.55), ("rotation", "x", 1.0)),
    (("force", "mass", 1), ("displacement", "mass", 2)),
    (("force", "mass", 0), ("displacement", "x", 0.25)),
]


@pytest.mark.parametrize("pair", FRF_PAIRS, ids=lambda p: f"{p[0][0]}-{p[1][0]}")
def test_frf_against_the_reference(pair):
    """Away from resonance (the roots: 3.67, 11.8, 15.0, 22.1, 27.0 rad/s): 128 elements
    within 5e-8 (measured, over the five pairs: <= 1.2e-9 at 8 rad/s, 4.8e-9 at 19 rad/s,
    1.2e-10 at 6 + 2i rad/s), exact at w = 0 (5e-16)."""
    src, dst = pair
    omegas = [0.0, 8.0, 19.0, 6.0 + 2.0j]
    exact = np.array([complex(h) for h in ref.frf(FRF_SCENE, src, dst, omegas, dps=20)])
    got = fem.frf(FRF_SCENE, src, dst, omegas, 128)
    assert rel(got[0], exact[0]) < 1e-12
    assert np.all(rel(got, exact) < 5e-8), rel(got, exact)


def test_frf_reciprocity_and_hinge():
    w = [3.0, 9.0 + 0.5j]
    n = 24

    def h(src, dst):
        return fem.frf(FRF_SCENE, src, dst, w, n)

    for one, two in (
        (
            h(("force", "x", 0.3), ("displacement", "x", 0.8)),
            h(("force", "x", 0.8), ("displacement", "x", 0.3)),
        ),
        (
            h(("force", "x", 0.3), ("rotation", "x", 0.8)),
            h(("moment", "x", 0.8), ("displacement", "x", 0.3)),
        ),
        (
            h(("force", "mass", 2), ("rotation", "x", 0.6)),
            h(("moment", "x", 0.6), ("displacement", "mass", 2)),
        ),
    ):
        assert np.all(rel(one, two) < 1e-11)
    hinged = beam("pinned", "pinned", [{"type": "hinge", "x": 0.5, "k": 2.0}])
    assert fem.frf(hinged, ("force", "x", 0.5), ("displacement", "x", 0.5), [1.0], 8)[0] != 0
    for src, dst in (
        (("moment", "x", 0.5), ("displacement", "x", 0.2)),
        (("force", "x", 0.2), ("rotation", "x", 0.5)),
        (("force", "mass", 0), ("displacement", "x", 0.2)),
    ):
        with pytest.raises(ValueError):
            fem.frf(hinged, src, dst, [1.0], 8)

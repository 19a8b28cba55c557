"""Mode shapes (paper Eq. (5)) on the default path, against independent references.

References: the null space of the global matrix of ``tests/reference_model.py``
(exact segment solutions, mpmath, no transfer matrix), the closed-form cantilever
modes, and physics (the effective modal masses of all modes sum to the mass a
translation of the supports moves). Compared by the sine of the largest principal
angle between our shapes and the reference's null space, sampled at the same
points (beam deflection and every hanging mass).
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
import reference_model as ref
from eigenspaces import check_against_reference, sin_angle, vectors

import mstmm
from mstmm.scene import scene_from_dict


def make(left, right, atts, L=1.0, EI=1.0, mbar=1.0):
    beam = {"length": L, "EI": EI, "mass_per_length": mbar, "left": left, "right": right}
    return scene_from_dict(
        {
            "beam": beam,
            "attachments": [{"type": "spring_mass", "x": x, "k": k, "m": m} for x, k, m in atts],
        }
    )


def test_paper_example_shapes_up_to_mode_40_span_the_reference_null_space(tier):
    """The issue's acceptance: sine of the largest principal angle <= 1e-9 to the 40th mode."""
    sc = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    sol = mstmm.solve(sc, modes=40)
    assert len(sol.shapes) == 40
    check_against_reference(sc, sol, 1e-9)


def test_spring_mass_at_a_clamped_end():
    """sqrt(k/m) is a root with the beam at rest and the mass moving (B00 = 0 exactly)."""
    sc = make("clamped", "free", [(0.0, 100.0, 1.0), (0.6, 300.0, 0.2)])
    sol = mstmm.solve(sc, modes=5)
    i = int(np.argmin(np.abs(sol.omega - 10.0)))
    s = sol.shapes[i]
    assert abs(s.mass_Y[0]) == pytest.approx(1.0)
    assert np.max(np.abs(s.Y)) < 1e-12 and np.max(np.abs(s.mass_Y[1:])) < 1e-12
    check_against_reference(sc, sol, 1e-9)


@pytest.mark.parametrize("n, rest", [(2, 1), (3, 2)])
def test_identical_spring_masses_at_one_point(n, rest):
    """n identical spring-masses at one point: sqrt(k/m) has n - 1 shapes, the beam at rest,
    the masses moving against each other (their displacements sum to zero)."""
    sc = make("clamped", "free", [(0.5, 100.0, 1.0)] * n)
    sol = mstmm.solve(sc, modes=5)
    at = [s for s in sol.shapes if abs(s.omega - 10.0) < 1e-12]
    assert len(at) == rest and all(s.multiplicity == rest for s in at)
    for s in at:
        assert np.max(np.abs(s.Y)) < 1e-12
        assert abs(np.sum(s.mass_Y)) < 1e-12
    mass = np.array([[a.m for a in sc.attachments]])
    gram = np.array([[np.sum(mass * u.mass_Y * v.mass_Y) for v in at] for u in at])
    assert np.allclose(gram / np.sqrt(np.outer(np.diag(gram), np.diag(gram))), np.eye(rest))
    check_against_reference(sc, sol, 1e-9)


def test_close_pair_gets_two_different_shapes():
    """One spring-mass 1e-6 L from a clamped end, two identical ones 1e-7 L apart: two
    roots about 6e-13 apart (relative), which no refinement separates. They share one
    two-dimensional eigenspace, so they get two mass-orthonormal shapes spanning it (the
    seed gave the same shape twice)."""
    sc = make("clamped", "free", [(1e-6, 100.0, 1.0), (0.5, 100.0, 1.0), (0.5 + 1e-7, 100.0, 1.0)])
    sol = mstmm.solve(sc, modes=6)
    exact = ref.frequencies(sc, 6, dps=40)
    pair = [i for i, w in enumerate(exact) if abs(float(w) - 10.0) < 1e-9]
    assert len(pair) == 2 and float(exact[pair[1]] - exact[pair[0]]) < 1e-11
    a, b = (sol.shapes[i] for i in pair)
    assert a.multiplicity == b.multiplicity == 2
    assert sin_angle([np.concatenate([a.Y, a.mass_Y])], [np.concatenate([b.Y, b.mass_Y])]) > 0.5
    # near-coincident roots next to the masses' own frequency: the eigenspace is as good as
    # a float64 frequency allows: B00 = 1 - m w^2/k ~ 1e-12 there, so the 1e-16 error of w
    # is a 1e-4 error of the beam's motion relative to the masses' (2.5e-5 of it): ~1e-8
    check_against_reference(sc, sol, 1e-7, exact)


def test_rigid_body_modes_are_rigid_motions():
    """Free-free with a hanging mass: the two zero frequencies span {1, x}, the mass moving
    with the beam."""
    sc = make("free", "free", [(0.3, 100.0, 1.0)], L=2.0, EI=3.0, mbar=0.5)
    sol = mstmm.solve(sc, modes=4)
    assert list(sol.omega[:2]) == [0.0, 0.0]
    xs, ours = vectors(sol.shapes[:2])
    theirs = ref.eigenspace(sc, 0, 2, xs)
    assert sin_angle(ours, theirs) < 1e-12
    check_against_reference(sc, sol, 1e-9)


@pytest.mark.parametrize("left,right", [("pinned", "pinned"), ("sliding", "free")])
def test_spring_mass_at_the_right_end(left, right):
    """The new user's pinned-pinned beam with a spring-mass at x = L (NaN mass displacement
    and a zero beam shape before): finite shapes matching the reference."""
    sc = make(left, right, [(1.0, 100.0, 1.0)])
    sol = mstmm.solve(sc, modes=4)
    check_against_reference(sc, sol, 1e-9)


def _cantilever(beta):
    """Closed-form cantilever mode phi(xi) and its derivatives, 50 digits."""
    s = (mpmath.cosh(beta) + mpmath.cos(beta)) / (mpmath.sinh(beta) + mpmath.sin(beta))

    def d(xi, k):
        z = beta * xi
        f = (
            (mpmath.cosh(z), mpmath.sinh(z), mpmath.cosh(z), mpmath.sinh(z))[k]
            - (mpmath.cos(z), -mpmath.sin(z), -mpmath.cos(z), mpmath.sin(z))[k]
            - s
            * (
                (mpmath.sinh(z), mpmath.cosh(z), mpmath.sinh(z), mpmath.cosh(z))[k]
                - (mpmath.sin(z), mpmath.cos(z), -mpmath.sin(z), -mpmath.cos(z))[k]
            )
        )
        return beta**k * f

    return d


def test_cantilever_slope_moment_shear_and_modal_mass_match_closed_form():
    """Y, theta = Y', M = EI Y'', Q = EI Y''' (the signs of paper Eq. (1)), modal mass
    int mbar Y^2 and participation int mbar Y / modal mass of the closed-form cantilever
    modes phi = cosh - cos - sigma (sinh - sin)."""
    L, EI, mbar = 1.7, 3.0e3, 2.5
    sc = make("clamped", "free", [], L=L, EI=EI, mbar=mbar)
    sol = mstmm.solve(sc, modes=8)
    mpmath.mp.dps = 50
    for s in sol.shapes:
        b = mpmath.findroot(
            lambda z: 1 + mpmath.cos(z) * mpmath.cosh(z),
            mpmath.mpf(L * (mbar * s.omega**2 / EI) ** 0.25),
        )
        d = _cantilever(b)
        xi = s.x / L
        exact = [np.array([float(d(mpmath.mpf(float(v)), k)) for v in xi]) for k in range(4)]
        scale = exact[0][np.argmax(np.abs(exact[0]))]
        for k, (got, unit) in enumerate(
            zip((s.Y, s.theta, s.M, s.Q), (1.0, 1 / L, EI / L**2, EI / L**3), strict=True)
        ):
            want = exact[k] * unit / scale
            assert np.max(np.abs(got - want)) <= 1e-9 * np.max(np.abs(want)), k
        norm2 = mpmath.quad(lambda z, d=d: d(z, 0) ** 2, [0, 1])
        integral = mpmath.quad(lambda z, d=d: d(z, 0), [0, 1])
        modal = mbar * L * float(norm2) / float(scale) ** 2
        assert s.modal_mass == pytest.approx(modal, rel=1e-11)
        part = mbar * L * float(integral) / float(scale) / modal
        assert s.participation == pytest.approx(part, rel=1e-9)
        n = s.mass_normalised()
        assert n.modal_mass == pytest.approx(1.0, rel=1e-14)
        assert n.effective_mass == pytest.approx(s.effective_mass, rel=1e-12)


@pytest.mark.parametrize("name", ["bare_cantilever", "wu_chou_1998"])
def test_effective_modal_masses_sum_to_the_total_mass(name):
    """Base translation of a clamped beam: sum over all modes of the effective modal masses
    = beam mass + hanging masses. The tail of the sum falls like 1/N (cantilever:
    ~8/(pi^2 N) of the beam mass), so the partial sums at N, 2N, 4N are extrapolated
    (Richardson in 1/N, two steps) to 1e-6."""
    sc = mstmm.load_scene(mstmm.example_path(name))
    total = sc.beam.mass_per_length * sc.beam.length + sum(a.m for a in sc.attachments)
    n = 100
    sol = mstmm.solve(sc, modes=4 * n)
    meff = np.cumsum([s.effective_mass for s in sol.shapes]) / total
    s1, s2, s4 = meff[n - 1], meff[2 * n - 1], meff[4 * n - 1]
    r1, r2 = 2 * s2 - s1, 2 * s4 - s2  # error O(1/N^2)
    limit = (4 * r2 - r1) / 3  # error O(1/N^3)
    assert s4 < 1.0
    assert abs(limit - 1.0) < 1e-6, (s4, limit)


def test_mode_shapes_are_mass_orthogonal():
    """Distinct modes are orthogonal in the mass inner product, computed here independently
    of the kernel's quadrature: Simpson on a fine sampling (L/2000) plus the masses."""
    sc = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    sol = mstmm.solve(sc, modes=8)
    kernel = mstmm.kernel_for(sc)
    from mstmm.modes import mode_shapes

    shapes = mode_shapes(kernel, mstmm.parameter_vector(sc), sol.omega, n_points=2001)
    x = shapes[0].x
    w = np.zeros_like(x)
    h = np.diff(x)
    w[:-1] += h / 2
    w[1:] += h / 2  # trapezoid on the (slightly non-uniform) samples
    mbar = sc.beam.mass_per_length
    m = np.array([a.m for a in sc.attachments])
    G = np.array(
        [
            [np.sum(mbar * w * u.Y * v.Y) + np.sum(m * u.mass_Y * v.mass_Y) for v in shapes]
            for u in shapes
        ]
    )
    d = np.sqrt(np.diag(G))
    off = G / np.outer(d, d) - np.eye(len(shapes))
    assert np.max(np.abs(off)) < 1e-5  # trapezoid error at L/2000
    assert np.allclose(np.diag(G), [s.modal_mass for s in shapes], rtol=1e-5)


def test_hanging_masses_obey_their_equation_of_motion_on_every_example():
    """Every hanging mass (a spring-mass's, each stage of a chain) obeys its equation of
    motion in every mode of every undamped example (``eigenspaces.check_shapes``; the
    damped example's complex shapes: ``tests/test_damped.py``, ``tests/test_examples.py``)."""
    import glob
    from pathlib import Path

    from eigenspaces import check_shapes

    root = Path(__file__).resolve().parent.parent
    for path in sorted(glob.glob(str(root / "examples" / "*.toml"))):
        sc = mstmm.load_scene(path)
        if mstmm.topology_of(sc).damped:
            continue
        sol = mstmm.solve(sc, modes=12)
        check_shapes(sc, sol)

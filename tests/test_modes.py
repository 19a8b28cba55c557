"""Mode shapes (paper Eq. (5)) against the closed-form cantilever modes and the mass equation."""

from __future__ import annotations

import mpmath
import numpy as np

import mstmm


def cantilever_mode(omega: float, beam, xi: np.ndarray) -> np.ndarray:
    """phi = cosh - cos - sigma (sinh - sin), sigma = (cosh b + cos b)/(sinh b + sin b),
    b the root of 1 + cos b cosh b nearest lam L, all in 60-digit arithmetic."""
    mpmath.mp.dps = 60
    guess = beam.length * (beam.mass_per_length * omega**2 / beam.EI) ** 0.25
    b = mpmath.findroot(lambda z: 1 + mpmath.cos(z) * mpmath.cosh(z), mpmath.mpf(guess))
    s = (mpmath.cosh(b) + mpmath.cos(b)) / (mpmath.sinh(b) + mpmath.sin(b))
    phi = [
        mpmath.cosh(b * z) - mpmath.cos(b * z) - s * (mpmath.sinh(b * z) - mpmath.sin(b * z))
        for z in (mpmath.mpf(float(v)) for v in xi)
    ]
    return np.array([float(v) for v in phi])


def normalised(y: np.ndarray) -> np.ndarray:
    k = np.argmax(np.abs(y))
    return y / y[k]


def test_bare_cantilever_shapes_match_closed_form_up_to_mode_20():
    """The paper's SVD of U_bar loses a digit per pi of lam L; the march keeps ~1e-10."""
    scene = mstmm.load_scene(mstmm.example_path("bare_cantilever"))
    sol = mstmm.solve(scene, modes=20)
    for n, shape in enumerate(sol.shapes, start=1):
        exact = normalised(cantilever_mode(shape.omega, scene.beam, shape.x / scene.beam.length))
        err = np.max(np.abs(normalised(shape.Y) - exact))
        assert err < (1e-12 if n <= 4 else 1e-9), (n, err)
        assert shape.singular_ratio < 1e-6  # the end matrix is singular at omega_n


def test_hanging_masses_obey_their_equation_of_motion():
    """(k - m w^2) Y_m = k Y_beam(x_i): the spring force accelerates the mass."""
    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    sol = mstmm.solve(scene, modes=5)
    for shape in sol.shapes:
        for a, ym in zip(scene.attachments, shape.mass_Y, strict=True):
            yb = np.interp(a.x, shape.x, shape.Y)
            lhs = (a.k - a.m * shape.omega**2) * ym
            assert abs(lhs - a.k * yb) < 1e-8 * a.k
        assert shape.Y[0] == 0.0 or abs(shape.Y[0]) < 1e-12  # clamped end
        # the beam is continuous across every attachment (201 samples on L = 1)
        assert np.max(np.abs(np.diff(shape.Y))) < 0.05


def test_paper_example_shapes_match_reference_global_assembly(tier):
    """Mode shapes of the paper's example against the null vector of the reference model's
    global matrix (exact segment solutions, 40 digits): displacement at the attachments.
    Both tiers: after an interpreted solve the march uses the Python beam matrix."""
    import reference_model as ref

    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    sol = mstmm.solve(scene, modes=5)
    assert sol.kernel_mode == tier
    for shape in sol.shapes:
        beam_at, masses = ref.mode_at_attachments(scene, shape.omega, dps=40)
        ours = np.concatenate(
            [[np.interp(a.x, shape.x, shape.Y) for a in scene.attachments], shape.mass_Y]
        )
        theirs = np.concatenate([beam_at, masses])
        theirs = theirs / theirs[np.argmax(np.abs(theirs))]
        ours = ours / ours[np.argmax(np.abs(theirs))]
        assert np.max(np.abs(ours - theirs)) < 1e-10

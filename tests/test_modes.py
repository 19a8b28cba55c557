"""Mode shapes (paper Eq. (5)) against the closed-form cantilever modes and the mass equation."""

from __future__ import annotations

import math

import numpy as np

import mstmm


def cantilever_mode(beta_L: float, xi: np.ndarray) -> np.ndarray:
    """phi = cosh - cos - sigma (sinh - sin), sigma = (cosh b + cos b)/(sinh b + sin b)."""
    b = beta_L
    s = (math.cosh(b) + math.cos(b)) / (math.sinh(b) + math.sin(b))
    z = b * xi
    return np.cosh(z) - np.cos(z) - s * (np.sinh(z) - np.sin(z))


def normalised(y: np.ndarray) -> np.ndarray:
    k = np.argmax(np.abs(y))
    return y / y[k]


def test_bare_cantilever_shapes_match_closed_form():
    scene = mstmm.load_scene(mstmm.example_path("bare_cantilever"))
    sol = mstmm.solve(scene, modes=4)
    beam = scene.beam
    for shape in sol.shapes:
        b = beam.length * (beam.mass_per_length * shape.omega**2 / beam.EI) ** 0.25
        exact = normalised(cantilever_mode(b, shape.x / beam.length))
        assert np.max(np.abs(normalised(shape.Y) - exact)) < 1e-9
        assert shape.singular_ratio < 1e-12


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

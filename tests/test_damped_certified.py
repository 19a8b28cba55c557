"""The damped count certifies what it says (issue 20, items 1, 2 and 6).

Each case is checked against a closed form, through the default path (``mstmm.solve``
with mode shapes):

* **Overdamped roots far above any heuristic height.** A dashpot ``c`` at a beam's free
  end pins an overdamped root at ``w = i sigma`` with ``sigma = 2 c^2 / (sqrt(EI)
  mbar^1.5)`` (the semi-infinite beam's end stiffness ``EI kappa^3 / sqrt 2``, ``kappa^4
  = mbar sigma^2 / EI``, against the dashpot's ``c sigma``; the finite beam's correction
  is of order ``exp(-2 kappa L / sqrt 2)``, below 1e-30 here), 4x above what the old
  heuristic counted. At a sliding end (``theta = 0``) the end stiffness is ``sqrt 2 EI
  kappa^3`` (half an infinite beam's point stiffness) and the root is at ``sigma = c^2 /
  (2 sqrt(EI) mbar^1.5)``. The counted rectangle's
  height is a proved bound (:mod:`mstmm.decay_bound`) and holds every root.
* **A critically damped pair.** A spring-dashpot-mass (k = 4, m = 1, c = 4) at a
  clamped end does not move the beam: its roots solve ``m w^2 - i c w - k = 0``, the
  double root ``w = 2 i`` exactly. Reported once with multiplicity 2 (twice in the list)
  to full accuracy; near-critical damping gives two roots, each to full accuracy.
* **Huge loss factors.** A pinned-pinned beam with ``EI (1 + i eta)``:
  ``w_n = sqrt(1 + i eta) (n pi / L)^2 sqrt(EI / mbar)``, eta up to 1e4.
"""

from __future__ import annotations

import cmath
import math

import numpy as np
import pytest

import mstmm
from mstmm.decay_bound import sigma_max
from mstmm.scene import scene_from_dict


def _beam(left: str, right: str, **extra) -> dict:
    return {"length": 1.0, "EI": 1.0, "mass_per_length": 1.0, "left": left, "right": right} | extra


def _scene(beam: dict, *attachments: dict):
    return scene_from_dict({"name": "case", "beam": beam, "attachments": list(attachments)})


def _cantilever_roots(n: int) -> list[float]:
    """Clamped-free: cos b cosh b = -1, w = b^2 (EI = mbar = L = 1)."""
    out = []
    for k in range(n):
        a = (k + 0.5) * math.pi
        b = a
        for _ in range(60):
            g = math.cos(b) * math.cosh(b) + 1.0
            dg = -math.sin(b) * math.cosh(b) + math.cos(b) * math.sinh(b)
            b -= g / dg
        out.append(b * b)
    return out


def _axis_roots(sol) -> np.ndarray:
    w = np.asarray(sol.omega)
    return np.sort(w[(w.real == 0.0) & (w.imag > 0.0)].imag)


@pytest.mark.parametrize(
    ("right", "c", "sigma"),
    [("free", 50.0, 2.0 * 50.0**2), ("free", 40.0, 2.0 * 40.0**2), ("sliding", 80.0, 80.0**2 / 2)],
)
def test_the_overdamped_root_of_an_end_dashpot_is_found(right, c, sigma):
    scene = _scene(_beam("clamped", right), {"type": "dashpot", "x": 1.0, "c": c})
    sol = mstmm.solve(scene, modes=8)
    assert sol.count_checked
    axis = _axis_roots(sol)
    assert np.any(np.abs(axis - sigma) <= 1e-12 * sigma), axis
    assert sol.rectangle[3] > sigma  # the counted rectangle holds it
    assert len(sol.shapes) == len(sol.omega)


def test_two_end_dashpots_give_a_double_overdamped_root():
    c = 30.0
    scene = _scene(
        _beam("free", "free"),
        {"type": "dashpot", "x": 0.0, "c": c},
        {"type": "dashpot", "x": 1.0, "c": c},
    )
    sol = mstmm.solve(scene, modes=8)
    assert sol.count_checked
    sigma = 2.0 * c * c
    hits = [i for i, w in enumerate(sol.omega) if abs(w - 1j * sigma) <= 1e-12 * sigma]
    assert len(hits) == 2  # both ends' roots, exponentially close: one double root
    assert all(sol.multiplicity[i] == 2 for i in hits)


def test_the_bound_is_above_every_root_found():
    """The proved height against roots of a cantilever with dashpots and a damped
    absorber (every root the count found lies below it)."""
    scene = _scene(
        _beam("clamped", "free", loss_factor=0.2),
        {"type": "dashpot", "x": 0.5, "c": 3.0},
        {"type": "dashpot", "x": 1.0, "c": 7.0},
        {"type": "spring_mass", "x": 0.7, "k": 50.0, "m": 0.1, "c": 2.0},
    )
    sol = mstmm.solve(scene, modes=12)
    assert sol.count_checked
    bound = sigma_max(scene, sol.rectangle[1])
    assert bound is not None
    assert np.all(np.asarray(sol.omega).imag < bound.sigma)
    assert sol.rectangle[3] >= bound.sigma


def test_critical_damping_is_one_double_root_to_full_accuracy():
    scene = _scene(
        _beam("clamped", "free"), {"type": "spring_mass", "x": 0.0, "k": 4.0, "m": 1.0, "c": 4.0}
    )
    sol = mstmm.solve(scene, modes=6)
    assert sol.count_checked
    w = np.asarray(sol.omega)
    double = [i for i in range(w.size) if abs(w[i] - 2j) <= 1e-6]
    assert len(double) == 2
    for i in double:
        assert w[i].real == 0.0
        assert abs(w[i] - 2j) <= 1e-14 * 2
        assert sol.multiplicity[i] == 2
    # the beam's own roots: the clamped end holds it, the absorber does not move it
    beam = np.sort(w[np.abs(w - 2j) > 1e-6].real)
    assert np.allclose(beam, _cantilever_roots(beam.size), rtol=1e-12, atol=0)


@pytest.mark.parametrize("c", [4.0 * (1 + 1e-6), 4.0 * (1 - 1e-6)])
def test_near_critical_damping_gives_two_roots(c):
    scene = _scene(
        _beam("clamped", "free"), {"type": "spring_mass", "x": 0.0, "k": 4.0, "m": 1.0, "c": c}
    )
    sol = mstmm.solve(scene, modes=6)
    assert sol.count_checked
    # m w^2 - i c w - k = 0: w = (i c +- sqrt(4 k m - c^2)) / (2 m)
    disc = cmath.sqrt(4.0 * 4.0 - c * c)
    exact = [(1j * c + disc) / 2.0, (1j * c - disc) / 2.0]
    if c < 4.0:
        exact = [exact[0]]  # the mirror image -conj(w) is the same mode
    for z in exact:
        got = min(sol.omega, key=lambda w, z=z: abs(w - z))
        assert abs(got - z) <= 1e-11 * abs(z), (got, z)


@pytest.mark.parametrize("eta", [10.0, 1e3, 1e4])
def test_huge_loss_factors_against_the_closed_form(eta):
    L = 10.0
    scene = _scene(_beam("pinned", "pinned", length=L, loss_factor=eta))
    sol = mstmm.solve(scene, modes=4)
    assert sol.count_checked
    exact = [cmath.sqrt(1.0 + 1j * eta) * (n * math.pi / L) ** 2 for n in range(1, 5)]
    assert np.all(sol.converged)
    assert np.allclose(sol.omega, exact, rtol=1e-10, atol=0)

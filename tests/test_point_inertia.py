"""Modal and effective masses count the inertia a component holds on the beam (issue 20,
item 4): a ``mass``'s m on Y and its rotary inertia J on theta (the b4 part of its A,
``derive/descriptor.point_inertia``) enter the mode shapes' mass matrix and the base
translation's participation.

References: the classical cantilever with a tip mass and rotary inertia (shape
``cosh - cos - s (sinh - sin)``, its integrals in mpmath) at the roots of the mpmath
global assembly (``tests/reference_model.py``), whose null vectors also give the shapes of
a free-free beam with an interior mass; and physics: the effective masses of all modes sum
to the total translational mass (beam + every m), extrapolated as in ``tests/test_shapes.py``.
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
import reference_model as ref

import mstmm
from mstmm.output import total_mass

L, EI, MBAR, M_TIP = 1.0, 1.0, 2.0, 3.0  # a 2 kg beam, a 3 kg tip mass


def cantilever(J: float) -> dict:
    beam = {"length": L, "EI": EI, "mass_per_length": MBAR, "left": "clamped", "right": "free"}
    return {"beam": beam, "attachments": [{"type": "mass", "x": L, "m": M_TIP, "J": J}]}


def tip_mass_mode(w, J: float):
    """Closed form at a root w: W(x) = cosh bx - cos bx - s (sinh bx - sin bx) with s from
    the tip's shear condition EI W''' = -m w^2 W; returns (W(L), modal mass, base-translation
    integral int mbar W + m W(L), residual of the moment condition EI W'' = J w^2 W')."""
    with mpmath.workdps(40):
        w = mpmath.mpf(w)
        b = (MBAR * w**2 / EI) ** mpmath.mpf(0.25)
        bl = b * L
        ch, c, sh, s_ = mpmath.cosh(bl), mpmath.cos(bl), mpmath.sinh(bl), mpmath.sin(bl)
        mw2 = M_TIP * w**2
        sig = (EI * b**3 * (sh - s_) + mw2 * (ch - c)) / (EI * b**3 * (ch + c) + mw2 * (sh - s_))

        def W(x):
            return (
                mpmath.cosh(b * x)
                - mpmath.cos(b * x)
                - sig * (mpmath.sinh(b * x) - mpmath.sin(b * x))
            )

        WL = W(L)
        dWL = b * ((sh + s_) - sig * (ch - c))
        d2WL = b**2 * ((ch + c) - sig * (sh + s_))
        modal = MBAR * mpmath.quad(lambda x: W(x) ** 2, [0, L / 2, L]) + M_TIP * WL**2 + J * dWL**2
        part = MBAR * ((sh - s_) - sig * (ch + c - 2)) / b + M_TIP * WL
        residual = (EI * d2WL - J * w**2 * dWL) / (EI * b**2 * (abs(ch) + abs(sig * sh)))
        return WL, modal, part, residual


@pytest.mark.parametrize("J", [0.0, 0.05])
def test_cantilever_with_tip_mass_modal_and_effective_masses(J):
    """Each of the lowest 8 modes: modal mass (of the shape as scaled) and effective mass
    against the closed form, 1e-9."""
    sc = cantilever(J)
    sol = mstmm.solve(mstmm.scene_from_dict(sc), modes=8)
    exact = [mpmath.mpf(w) for w in ref.frequencies(sc, 8)]
    assert sol.count_checked
    for s, w in zip(sol.shapes, exact, strict=True):
        assert s.omega == pytest.approx(float(w), rel=1e-11)
        WL, modal, part, residual = tip_mass_mode(w, J)
        assert abs(residual) < 1e-14  # the closed form holds at the reference root
        assert s.x[-1] == L
        scale = s.Y[-1] / float(WL)
        assert s.modal_mass == pytest.approx(float(modal) * scale**2, rel=1e-9)
        assert s.effective_mass == pytest.approx(float(part**2 / modal), rel=1e-9)


def richardson_limit(meff: np.ndarray, n: int) -> float:
    """Partial sums at n, 2n, 4n extrapolated in 1/N (two steps; the tail falls like 1/N)."""
    s1, s2, s4 = meff[n - 1], meff[2 * n - 1], meff[4 * n - 1]
    r1, r2 = 2 * s2 - s1, 2 * s4 - s2
    return (4 * r2 - r1) / 3


@pytest.mark.parametrize("J", [0.0, 0.05])
def test_cantilever_with_tip_mass_effective_masses_sum_to_the_total_mass(J):
    """Sum over all modes = 2 kg beam + 3 kg tip mass (J adds no translational mass)."""
    sol = mstmm.solve(mstmm.scene_from_dict(cantilever(J)), modes=400)
    total = total_mass(sol)
    assert total == pytest.approx(MBAR * L + M_TIP, rel=1e-15)
    meff = np.cumsum([s.effective_mass for s in sol.shapes]) / total
    limit = richardson_limit(meff, 100)
    assert meff[-1] < 1.0
    assert abs(limit - 1.0) < 1e-6, (meff[-1], limit)


FREE = {
    "beam": {"length": 1.0, "EI": 1.0, "mass_per_length": 1.0, "left": "free", "right": "free"},
    "attachments": [{"type": "mass", "x": 0.3, "m": 0.5, "J": 0.02}],
}
XM = 0.3


def reference_modal_mass(w: float, xj: float):
    """Modal mass of the mpmath reference's null vector at w, scaled to 1 at xj: Simpson on
    [0, xm] and [xm, L] (2000 intervals each) + m W(xm)^2 + J W'(xm)^2 (W' by the
    one-sided second-order difference from the left, h = 1e-5: W'' jumps at the mass)."""
    h = 1e-5
    left, right = np.linspace(0.0, XM, 2001), np.linspace(XM, 1.0, 2001)
    xs = list(left) + list(right) + [XM - h, XM - 2 * h, xj]
    W = np.array(ref.eigenspace(FREE, w, 1, xs)[0])
    wl, wr = W[:2001], W[2001:4002]
    simpson = np.ones(2001)
    simpson[1:-1:2], simpson[2:-1:2] = 4.0, 2.0
    integral = (simpson @ wl**2) * XM / 6000 + (simpson @ wr**2) * (1.0 - XM) / 6000
    dW = (3 * wl[-1] - 4 * W[4002] + W[4003]) / (2 * h)
    modal = integral + 0.5 * wl[-1] ** 2 + 0.02 * dW**2
    return modal / W[4004] ** 2


def test_free_free_beam_with_an_interior_mass_and_rotary_inertia():
    """Two rigid-body modes and the elastic ones: modal masses against the reference's
    shapes (1e-8); elastic modes carry no effective mass (they are mass-orthogonal to the
    translation, m included), so the rigid modes carry it all: beam 1 kg + 0.5 kg."""
    sc = mstmm.scene_from_dict(FREE)
    sol = mstmm.solve(sc, modes=6)
    exact = [float(w) for w in ref.frequencies(FREE, 6)]
    assert sol.count_checked
    np.testing.assert_allclose(sol.omega, exact, rtol=1e-11)
    total = total_mass(sol)
    assert total == pytest.approx(1.5, rel=1e-15)
    assert sum(s.effective_mass for s in sol.shapes[:2]) == pytest.approx(total, rel=1e-12)
    for s in sol.shapes[2:]:
        assert s.effective_mass < 1e-12 * total
        j = int(np.argmax(np.abs(s.Y)))
        want = reference_modal_mass(s.omega, float(s.x[j]))
        assert s.modal_mass == pytest.approx(want * s.Y[j] ** 2, rel=1e-8)

"""The plane-frame reference model (``tests/reference_frame.py``) against closed forms.

The frame solver of issue 43 will be checked against this model, so it is checked first
against what is known without it:

* a cantilever cut into two collinear members, turned by any angle: its bending
  frequencies are the roots of ``1 + cos b cosh b = 0`` and its axial ones
  ``(2k - 1) pi / 2 sqrt(EA / mbar) / L``, each simple;
* NAFEMS FV2 (the pin-ended double cross) with its centre held: the arms vibrate pinned
  at the far end, either all with the centre's rotation (``sum of the eight end moments =
  0``: pinned-pinned, ``b = n pi``, simple) or with it at rest (clamped-pinned, ``tan b =
  tanh b``, seven-fold: eight arms, one equation), which are NAFEMS's published 11.336,
  17.709, 45.345 and 57.390 Hz;
* FV2 with the centre free and the arms axially elastic: the modes that leave the centre
  at rest need the moments and both force components at the centre to balance (eight
  arms, three equations), so five of each seven stay exactly at the clamped-pinned
  frequency; the other two move;
* and against another method: the finite-element model of ``tests/reference_frame_fem.py``
  (an L-frame, a portal frame with a node mass, a tree with a pinned member end), to
  which it converges.
"""

from __future__ import annotations

import sys
from pathlib import Path

import mpmath
import pytest
from mpmath import mp

sys.path.insert(0, str(Path(__file__).resolve().parent))
from reference_frame import (  # noqa: E402
    Frame,
    Member,
    count_below,
    frequencies,
    nafems_fv2,
    sample_frames,
)

DPS = 30


def _cantilever_roots(n: int) -> list:
    """The lowest n roots of 1 + cos b cosh b = 0 (one in each (k - 1/2) pi +- 1)."""
    f = lambda b: 1 + mpmath.cos(b) * mpmath.cosh(b)  # noqa: E731
    return [mpmath.findroot(f, (k - mpmath.mpf(0.5)) * mp.pi) for k in range(1, n + 1)]


@pytest.mark.parametrize("angle", [0.0, 30.0, 135.0])
def test_two_collinear_members_are_a_cantilever(angle):
    """Clamped at A, free at C, a node B at 0.37 L: bending and axial frequencies of the
    cantilever, whatever the direction it points in."""
    with mp.workdps(DPS):
        L, EI, EA, mbar = 2.0, 3.0e3, 4.0e5, 7.0
        c, s = mpmath.cos(mpmath.radians(angle)), mpmath.sin(mpmath.radians(angle))
        nodes = {"A": (0.0, 0.0), "B": (0.37 * L * c, 0.37 * L * s), "C": (L * c, L * s)}
        members = (Member("A", "B", EI, EA, mbar), Member("B", "C", EI, EA, mbar))
        frame = Frame(nodes, members, held={"A": "xyt"})
        scale = mpmath.sqrt(mpmath.mpf(EI) / mbar) / L**2
        bending = [b**2 * scale for b in _cantilever_roots(6)]
        axial_speed = mpmath.sqrt(mpmath.mpf(EA) / mbar)
        axial = [(2 * k - 1) * mp.pi / 2 * axial_speed / L for k in range(1, 4)]
        exact = sorted(bending + axial)[:7]
        found = frequencies(frame, 7, DPS)
        assert [m for _, m in found] == [1] * 7
        for (w, _), e in zip(found, exact):
            assert abs(w - e) <= mpmath.mpf(10) ** (10 - DPS) * e


def _fv2_exact() -> dict:
    """The held-centre FV2's frequencies (Hz) from the arm's closed forms, with their
    multiplicities."""
    E, rho, side, arm = mpmath.mpf(200e9), mpmath.mpf(8000), mpmath.mpf(0.125), 5
    scale = mpmath.sqrt(E * side**2 / 12 / rho) / arm**2 / (2 * mp.pi)
    pinned = [(n * mp.pi) ** 2 * scale for n in (1, 2)]
    g = lambda b: mpmath.tan(b) - mpmath.tanh(b)  # noqa: E731
    clamped_pinned = [mpmath.findroot(g, x) ** 2 * scale for x in (3.9266, 7.0686)]
    return {pinned[0]: 1, clamped_pinned[0]: 7, pinned[1]: 1, clamped_pinned[1]: 7}


def test_fv2_with_its_centre_held_has_nafems_values_and_two_sevenfold_roots():
    with mp.workdps(DPS):
        found = frequencies(nafems_fv2(held_centre=True), 16, DPS)
        exact = _fv2_exact()
        assert [m for _, m in found] == list(exact.values())
        for (w, _), e in zip(found, exact):
            assert abs(w / (2 * mp.pi) - e) <= mpmath.mpf(10) ** (10 - DPS) * e
        published = [11.336, 17.709, 45.345, 57.390]
        assert [round(float(w / (2 * mp.pi)), 3) for w, _ in found] == published


def test_fv2_with_a_free_centre_keeps_five_of_each_seven():
    """Axially elastic arms, the centre free: exactly five modes stay at each
    clamped-pinned frequency (count jumps of 5 across it, within 1e-20), and the
    first pinned-pinned mode (the centre turning, no arm stretched) stays too."""
    frame = nafems_fv2()
    with mp.workdps(DPS):
        exact = list(_fv2_exact())
        for e, jump in ((exact[0], 1), (exact[1], 5), (exact[3], 5)):
            w = 2 * mp.pi * e
            eps = mpmath.mpf(10) ** -20
            below, above = (
                count_below(frame, w * (1 - eps), DPS),
                count_below(frame, w * (1 + eps), DPS),
            )
            assert above - below == jump


@pytest.mark.parametrize("name", ["L", "portal", "tree"])
def test_frames_against_finite_elements(name):
    """The exact model against the finite-element one (``tests/reference_frame_fem.py``,
    another method: textbook rod and Hermite elements, turned and assembled): the lowest
    six frequencies of 64 elements a member within 2e-5 of the exact ones, and eight
    times closer than those of 16 elements wherever these are off by more than 1e-5 (the
    elements converge to the exact model, as h^2 where the rod's linear elements matter:
    sixteen times closer; below ~1e-6 the dense eigensolver's round-off is what is
    left)."""
    import numpy as np
    import reference_frame_fem as fem

    frame = sample_frames()[name]
    with mp.workdps(20):
        exact = np.array([float(w) for w, m in frequencies(frame, 6, 20) for _ in range(m)])[:6]
    coarse = np.abs(fem.frequencies(frame, 6, 16) / exact - 1)
    fine = np.abs(fem.frequencies(frame, 6, 64) / exact - 1)
    assert np.all(fine <= 2e-5), fine
    assert np.all((coarse <= 1e-5) | (fine <= coarse / 8)), (coarse, fine)

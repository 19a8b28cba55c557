"""The top of a locally resonant gap where the two complex wave pairs turn real a hair
before one of them reaches k L = 0 (issue 45): the gap ends at the meeting, not at the
k L = 0 edge, and the meeting is listed; against the independent mpmath model
(tests/reference_bloch.py: its own characteristic polynomial, 40 digits), whose
discriminant changes sign at the meeting.

The cells put a spring-mass of mass ratio mu (to the cell's beam) tuned low in the first
Bragg zone, where the meeting and the edge lie close: mu = 0.5 at 0.045 of the Bragg
frequency (the reported gap top was 1.2e-10 off), mu = 2 at 0.033 (2.9e-10), and
examples/metamaterial.toml (2.3e-14).
"""

from __future__ import annotations

from pathlib import Path

import pytest
import reference_bloch as ref
from mpmath import mp, mpf
from test_bands import W_BRAGG, cell, resonator

import mstmm
from mstmm.bands import bands, cell_of

METAMATERIAL = Path(__file__).resolve().parent.parent / "examples" / "metamaterial.toml"
DPS = 40


def _cells() -> dict:
    out = {}
    for mu, ratio in ((0.5, 0.045), (2.0, 0.033)):
        w_t = ratio * W_BRAGG
        out[f"mu_{mu}"] = (cell(resonator(0.35, mu, w_t)), (0.5 * w_t, 2.5 * w_t))
    meta = cell_of(mstmm.load_scene(METAMATERIAL))
    w_t = (5329.586 / 0.00054) ** 0.5
    out["metamaterial"] = (meta, (0.5 * w_t, 2.0 * w_t))
    return out


CELLS = _cells()


def _discriminant(c, w):
    """The discriminant of the model's P(mu) = c4 mu^2 + c3 mu + (c2 - 2 c4): negative
    where the two pairs' mu are a complex conjugate pair."""
    co = ref.characteristic(c, w, dps=DPS)
    with mp.workdps(DPS):
        return co[3] ** 2 - 4 * co[4] * (co[2] - 2 * co[4])


def _model_gap_top(c, edge: float) -> tuple[mpf, bool]:
    """The model's top of the gap that its k L = 0 edge ``edge`` closes: where its
    discriminant turns positive below the edge, if it does within 1e-3 of it, with the
    double root inside [-2, 2] (the pairs propagate from there); else the edge. Returns
    (top, whether it is a meeting)."""
    with mp.workdps(DPS):
        lo, hi = mpf(edge) * (1 - mpf("1e-3")), mpf(edge)
        if _discriminant(c, lo) >= 0:
            return hi, False
        for _ in range(120):
            m = (lo + hi) / 2
            if _discriminant(c, m) < 0:
                lo = m
            else:
                hi = m
        co = ref.characteristic(c, hi, dps=DPS)
        mu = -co[3] / (2 * co[4])  # the double root
        return (hi, True) if abs(mu) <= 2 else (mpf(edge), False)


@pytest.mark.parametrize("name", sorted(CELLS))
def test_the_gap_ends_where_the_pairs_meet(name):
    c, band = CELLS[name]
    b = bands(c, band=band, points=50)
    assert b.gaps, b.notes
    top = b.gaps[0][1]
    periodic = [e.omega for e in b.edges if e.kind == "periodic" and e.omega >= top * 0.999]
    edge = min(periodic)
    want, meeting = _model_gap_top(c, edge)
    assert abs(top - float(want)) <= 1e-12 * float(want), (top, want, b.edges, b.notes)
    if meeting and abs(float(want) - edge) > 1e-13 * edge:
        assert any(
            e.kind == "coalescence" and abs(e.omega - float(want)) <= 1e-12 * float(want)
            for e in b.edges
        ), b.edges
        assert b.count_checked, b.notes

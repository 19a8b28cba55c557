"""Bloch wavenumbers from omega -> 0 to past the third Bragg gap, against the independent
mpmath model (tests/reference_bloch.py, 30 digits: its own transfer matrices and
characteristic polynomial), and the documented branch everywhere (issue 45).

As omega -> 0 both roots mu = 2 cos(k L) of the cell's quadratic crowd at 2 (k L -> 0 and
the evanescent pair's i k L -> 0): solved for mu, the quadratic kept about the square root
of the working precision of mu - 2, and k L was 15 % off at omega = 1e-3 rad/s on the
metamaterial cell, with no word. The roots are now taken about +-2 (``numerics.bloch``:
``bloch_mu``, ``bloch_slope``) and k L from mu - 2 itself.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import reference_bloch as ref
from test_bands_reference import CELLS as REFERENCE_CELLS

import mstmm
from mstmm.bands import bands, cell_of, default_band

DPS = 30
METAMATERIAL = Path(__file__).resolve().parent.parent / "examples" / "metamaterial.toml"

CELLS = {
    "metamaterial": lambda: cell_of(mstmm.load_scene(METAMATERIAL)),
    # tests/test_bands_reference.py's stepped cell: a tensioned Euler-Bernoulli piece, a
    # Timoshenko piece on a foundation, a resonator and a mass
    "stepped_general": lambda: mstmm.scene_from_dict(REFERENCE_CELLS["stepped_general"]),
}

#: Relative error allowed on k: where the propagating pair's |k L| < LOW (omega ->
#: 0: k L is about 6e-6 at omega = 1e-6 rad/s on the metamaterial cell, mu - 2 about
#: 4e-11), and elsewhere across the bands.
LOW, LOW_TOL = 1e-4, 1e-10
TOL = 1e-12


def _frequencies(cell) -> np.ndarray:
    top = 1.05 * default_band(cell)[1]  # past the third Bragg frequency of the bare beam
    low = np.logspace(-6, 1, 8)
    return np.concatenate([low, np.linspace(0.01 * top, top, 24)])


def _matched(got, want) -> float:
    """Worst relative error of the two wavenumbers, each pair matched to its nearest."""
    (a, b), (c, d) = got, want
    straight = max(abs(a - c) / abs(c), abs(b - d) / abs(d))
    crossed = max(abs(a - d) / abs(d), abs(b - c) / abs(c))
    return min(straight, crossed)


@pytest.mark.parametrize("name", sorted(CELLS))
def test_wavenumbers_from_omega_1e_minus_6_past_the_third_gap(name):
    cell = CELLS[name]()
    ws = _frequencies(cell)
    out = bands(cell, omegas=ws, edges=False)
    length = cell.beam.length
    for i, w in enumerate(ws):
        want = [complex(k) for k in ref.bloch_k(cell, float(w), dps=DPS)]
        low = min(abs(k) for k in want) * length < LOW
        err = _matched(out.k[i], want)
        assert err < (LOW_TOL if low else TOL), (w, out.k[i], want)


def test_the_branch_is_the_documented_one_in_the_stop_bands_too():
    """Undamped: 0 <= Re k L <= pi and Im k >= 0 at every frequency (inside a locally
    resonant gap the two pairs are a complex conjugate pair of mu; 1,177 of 20,000
    wavenumbers had Re k < 0 there), and mu = 2 cos(k L) for each pair."""
    cell = CELLS["metamaterial"]()
    out = bands(cell, band=default_band(cell), points=20_000, edges=False)
    kL = out.k * cell.beam.length
    assert np.all(kL.real >= 0.0) and np.all(kL.real <= math.pi)
    assert np.all(kL.imag >= 0.0)
    mu = 2.0 * np.cos(kL)
    # mu of each pair, or its conjugate (the folded wave -conj(k) of the other pair)
    near = np.minimum(abs(mu - out.mu), abs(mu - np.conj(out.mu)))
    assert np.all(near <= 1e-9 * np.maximum(1.0, abs(out.mu)))
    assert np.any(abs(out.mu.imag) > 1e-3)  # the gap where mu is complex is sampled

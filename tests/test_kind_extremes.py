"""Stiff and extreme cases of the component library (issue 13), against the reference.

Springs from 1e-6 to 1e12 EI/L^3 (nearly a support), rotary inertia up to 1e3 mbar L^3,
segments whose EI differ by 1e6, a hinge 1e-9 L from a support, 20 identical chains at
one point (eigenvalues of multiplicity 19). Every case goes through the default path
(``mstmm.solve`` with mode shapes): its frequencies are within 1e-12 of the reference
model (tests/reference_model.py, mpmath at 40 digits), or the solution says it cannot be
trusted (``count_checked`` False or a warning): never a silent wrong frequency.
"""

from __future__ import annotations

import numpy as np
import pytest
import reference_model as ref
from eigenspaces import check_shapes

import mstmm

MODES = 8
RTOL = 1e-12


def _beam(left, right, length=1.0, EI=1.0, mbar=1.0, segments=None):
    beam = {"left": left, "right": right}
    if segments:
        beam["segments"] = [{"length": a, "EI": b, "mass_per_length": c} for a, b, c in segments]
    else:
        beam.update(length=length, EI=EI, mass_per_length=mbar)
    return beam


def _chain(x):
    return {"type": "oscillator_chain", "x": x, "k": [400.0, 150.0], "m": [0.05, 0.02]}


CASES = {
    "spring_nearly_a_support": (
        _beam("pinned", "free"),
        [{"type": "spring", "x": 0.5, "k": 1e12}, {"type": "spring", "x": 0.8, "k": 1e-6}],
    ),
    "soft_spring_on_free_free": (
        _beam("free", "free"),
        [{"type": "spring", "x": 0.3, "k": 1e-6}, {"type": "spring", "x": 0.9, "k": 1e12}],
    ),
    "rotary_inertia_1e3": (
        _beam("clamped", "free"),
        [{"type": "mass", "x": 1.0, "m": 1.0, "J": 1e3}, {"type": "mass", "x": 0.5, "m": 1e-3}],
    ),
    "ei_ratio_1e6": (
        _beam("clamped", "free", segments=[(0.3, 1.0, 1.0), (0.4, 1e6, 10.0), (0.3, 1.0, 1.0)]),
        [],
    ),
    "hinge_1e-9_from_a_support": (
        _beam("pinned", "pinned"),
        [{"type": "support", "x": 0.5}, {"type": "hinge", "x": 0.5 + 1e-9}],
    ),
    "twenty_identical_chains": (
        _beam("clamped", "free"),
        [_chain(0.7) for _ in range(20)],
    ),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_extreme_case_matches_the_reference_or_says_so(name):
    beam, atts = CASES[name]
    scene = {"beam": beam, "attachments": atts}
    modes = MODES if name != "twenty_identical_chains" else 45
    sol = mstmm.solve(mstmm.scene_from_dict(scene), modes=modes)
    exact = np.array([float(w) for w in ref.frequencies(scene, modes, dps=40)])
    trusted = sol.count_checked and not sol.warnings and bool(np.all(sol.converged))
    assert trusted, (name, sol.warnings)  # flagged would be allowed; every case here is exact
    zero = exact == 0.0
    np.testing.assert_array_equal(sol.omega[zero], 0.0)
    rel = np.abs(sol.omega[~zero] - exact[~zero]) / exact[~zero]
    assert rel.max() <= RTOL, (name, rel.max(), sol.omega, exact)
    check_shapes(scene, sol)

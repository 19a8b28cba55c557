"""The damped search's fast path (issue 20 item 11) finds what the slow one found.

* **The leap** (:func:`mstmm.secant.newton_many` from every undamped root at once): on a
  pinned-pinned beam with a loss factor the roots are ``sqrt(1 + i eta) (n pi / L)^2
  sqrt(EI / mbar)`` exactly.
* **A root reached twice** (two close undamped roots whose paths arrive at one damped
  root) is listed once: adding it again, moved by round-off, adds nothing (that "new"
  root once sent the search into a tall rectangle's quarters one after another).
* **Many absorbers**: a scene of every kind with a dashpot beside each absorber's spring
  and a loss factor on each segment, through the default path (mode shapes on), against
  the mpmath reference model.
* **The proved decay bound** takes each damper over its own hinge-free piece: it still
  lies above every root (the closed form of an end dashpot).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

import mstmm
from mstmm import damped, secant
from mstmm.decay_bound import sigma_max
from mstmm.scene import scene_from_dict

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import reference_model as rm  # noqa: E402

from benchmarks.damped_large import damped_mixed  # noqa: E402


def _pinned(eta: float):
    beam = {
        "length": 2.0,
        "EI": 3.0,
        "mass_per_length": 1.5,
        "left": "pinned",
        "right": "pinned",
        "loss_factor": eta,
    }
    return scene_from_dict({"name": "pp", "beam": beam, "attachments": []})


def _problem(scene):
    from mstmm.topology import parameter_vector

    kernel = mstmm.kernel_for(scene)
    p = np.ascontiguousarray(parameter_vector(scene), dtype=np.float64)
    f = damped._Function(kernel, p)
    unit = math.sqrt(p[1] / p[2]) / p[0] ** 2
    columns = np.zeros(0, dtype=np.int64)
    return damped._Problem(kernel, p, f, columns, unit, False, 0, 0), unit


@pytest.mark.parametrize("eta", [0.01, 0.3])
def test_the_leap_lands_on_the_closed_form(eta):
    scene = _pinned(eta)
    problem, unit = _problem(scene)
    n = np.arange(1, 9)
    w0 = (n * math.pi / 2.0) ** 2 * math.sqrt(3.0 / 1.5)
    exact = np.sqrt(1.0 + 1j * eta) * w0
    w, ok = secant.newton_many(problem.f, w0 * (1.0 + 0.3j * eta), scale=unit)
    assert ok.all()
    assert np.max(np.abs(w - exact) / np.abs(exact)) < 1e-13


def test_a_root_added_twice_is_listed_once():
    scene = _pinned(0.05)
    problem, unit = _problem(scene)
    w0 = (math.pi / 2.0) ** 2 * math.sqrt(3.0 / 1.5)
    exact = complex(np.sqrt(1.0 + 0.05j) * w0)
    assert problem.add(exact, 1, "continuation")
    again = exact * (1.0 + 3e-16) + 1e-15j * abs(exact)
    assert not problem.add(again, 1, "continuation")
    assert len(problem.roots) == 1
    assert abs(problem.roots[0].omega - exact) < 1e-13 * abs(exact)


def test_many_damped_absorbers_match_the_reference():
    d = damped_mixed(14)
    exact = np.array([complex(w) for w in rm.damped_frequencies(d, 12, dps=20)])
    sol = mstmm.solve(scene_from_dict(d), modes=12)
    assert sol.count_checked, sol.warnings
    assert np.max(np.abs(sol.omega - exact) / np.abs(exact)) < 1e-10
    assert len(sol.shapes) == 12


def test_the_per_damper_bound_still_holds_an_end_dashpot():
    """A dashpot c at a cantilever's free end: the overdamped root sits at
    sigma = 2 c^2 / (sqrt(EI) mbar^1.5) (the semi-infinite beam's end stiffness), with a
    hinge close by (a short hinge-free piece elsewhere no longer shrinks the bound for
    every damper)."""
    c = 50.0
    beam = {"length": 1.0, "EI": 1.0, "mass_per_length": 1.0, "left": "clamped", "right": "free"}
    atts = [
        {"type": "dashpot", "x": 1.0, "c": c},
        {"type": "hinge", "x": 0.3, "k": 1e3},
        {"type": "dashpot", "x": 0.31, "c": 1e-3},
    ]
    scene = scene_from_dict({"name": "end", "beam": beam, "attachments": atts})
    bound = sigma_max(scene, 100.0)
    assert bound is not None and bound.sigma > 2.0 * c**2
    sol = mstmm.solve(scene, modes=4)
    assert sol.count_checked, sol.warnings
    top = max(w.imag for w in sol.omega)
    assert top == pytest.approx(2.0 * c**2, rel=1e-6)

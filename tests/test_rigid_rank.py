"""The rigid-body count is exact: constraints however close never fake a zero frequency.

Issue 20, item 3: two supports 1e-9 L apart on a free-free beam (or a support and a stiff
spring) were counted as one constraint by a thresholded SVD; the search then took the
true lowest root for a rigid-body mode. ``rigid_dimension`` (``mstmm.numerics.search``)
decides the rank from the positions by exact comparisons. References: the mpmath global
assembly of ``tests/reference_model.py`` (frequencies, damped frequencies, and the exact
rational rank ``rigid_body_mode_count``).
"""

from __future__ import annotations

import json

import numpy as np
import pytest
import reference_model as ref
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import mstmm
from mstmm.cli import main
from mstmm.scene import SceneError

RTOL = 1e-10
SPACINGS = (1e-3, 1e-6, 1e-9, 1e-12)


def scene(atts: list, left: str = "free", right: str = "free") -> dict:
    beam = {"length": 1.0, "EI": 1.0, "mass_per_length": 1.0, "left": left, "right": right}
    return {"beam": beam, "attachments": atts}


def support(x: float) -> dict:
    return {"type": "support", "x": x}


def check(sc: dict, modes: int = 4, shapes: bool = True):
    """Solve on the default path and compare with the reference: the same list (rigid-body
    zeros exactly zero, none spurious), certified, one finite shape per root."""
    sol = mstmm.solve(mstmm.scene_from_dict(sc), modes=modes, shapes=shapes)
    exact = np.array([float(w) for w in ref.frequencies(sc, modes)])
    assert sol.count_checked, sol.warnings
    assert np.array_equal(sol.omega == 0.0, exact == 0.0), (sol.omega, exact)
    assert np.allclose(sol.omega, exact, rtol=RTOL, atol=0.0), (sol.omega, exact)
    if shapes:
        assert len(sol.shapes) == modes
        assert all(np.isfinite(s.Y).all() for s in sol.shapes)
    return sol, exact


@pytest.mark.parametrize("d", SPACINGS)
def test_two_supports_close_together_on_a_free_free_beam(d):
    """No rigid-body mode: the lowest root is elastic (8.3219 rad/s for 1e-9 L)."""
    sc = scene([support(0.35), support(0.35 + d)])
    assert ref.rigid_body_mode_count(sc) == 0
    sol, exact = check(sc)
    assert sol.omega[0] > 8.0


@pytest.mark.parametrize("d", SPACINGS)
def test_two_supports_close_to_an_end(d):
    """At the free end: the pair acts as a clamp there."""
    check(scene([support(0.0), support(d)]))
    check(scene([support(1.0 - d), support(1.0)], left="sliding"))


@pytest.mark.parametrize("d", SPACINGS)
def test_two_supports_close_across_a_free_hinge(d):
    """The two sides of a free hinge each get one support: the pieces still turn about
    them (two rigid-body modes), and a third support takes one of them away."""
    hinge = {"type": "hinge", "x": 0.5, "k": 0.0}
    sc = scene([support(0.5 - d / 2), hinge, support(0.5 + d / 2)])
    assert ref.rigid_body_mode_count(sc) == 1
    check(sc)
    check(scene([support(0.5 - d / 2), hinge, support(0.5 + d / 2), support(0.9)]))


@pytest.mark.parametrize("x", [0.35, 0.5])
def test_support_and_a_stiff_spring_close_together(x):
    """k = 1e12 N/m 1e-9 L from a support: a rocking root sqrt(k d^2 / I_x), I_x the beam's
    moment of inertia about the support (0.0034641 rad/s about the middle), not a zero."""
    sc = scene([support(x), {"type": "spring", "x": x + 1e-9, "k": 1e12}])
    sol, exact = check(sc)
    inertia = ((1.0 - x) ** 3 + x**3) / 3.0
    assert sol.omega[0] == pytest.approx(np.sqrt(1e12 * 1e-18 / inertia), rel=1e-6)


def test_cli_json_reports_the_elastic_root(tmp_path, capsys):
    """The same through ``mstmm solve SCENE.toml --format json``."""
    path = tmp_path / "pair.toml"
    path.write_text(
        "[beam]\nlength = 1.0\nEI = 1.0\nmass_per_length = 1.0\n"
        'left = "free"\nright = "free"\n'
        '[[attachments]]\ntype = "support"\nx = 0.35\n'
        '[[attachments]]\ntype = "support"\nx = 0.350000001\n'
    )
    assert main(["solve", str(path), "--modes", "3", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    exact = [float(w) for w in ref.frequencies(mstmm.load_scene(path), 3)]
    assert data["count_checked"] is True
    assert np.allclose(data["omega"], exact, rtol=RTOL, atol=0.0), (data["omega"], exact)
    assert exact[0] == pytest.approx(8.3219, rel=1e-4)


def test_damped_scene_with_two_close_supports():
    """The damped search's rigid count (``rigid_motions``, with and without dampers): no
    zero and no overdamped root from a rotation the two supports forbid."""
    sc = scene([support(0.35), support(0.35 + 1e-9), {"type": "dashpot", "x": 0.8, "c": 1.0}])
    sol = mstmm.solve(mstmm.scene_from_dict(sc), modes=3)
    exact = np.array([complex(w) for w in ref.damped_frequencies(sc, 3, dps=20)])
    assert sol.count_checked, sol.warnings
    assert np.all(np.abs(sol.omega - exact) <= RTOL * np.abs(exact)), (sol.omega, exact)


def test_damped_dashpot_close_to_a_support():
    """A dashpot 1e-3 L from the only support restrains its rotation: an overdamped root
    (sigma ~ c d^2 / I_x = 9.4e-6 rad/s), not a second zero."""
    sc = scene([support(0.35), {"type": "dashpot", "x": 0.351, "c": 1.0}])
    sol = mstmm.solve(mstmm.scene_from_dict(sc), modes=3)
    exact = np.array([complex(w) for w in ref.damped_frequencies(sc, 3, dps=20)])
    assert sol.count_checked, sol.warnings
    assert np.count_nonzero(sol.omega == 0) == 1
    assert np.all(np.abs(sol.omega - exact) <= RTOL * np.abs(exact)), (sol.omega, exact)


# ------------------------------------------------------------ property: the exact rank

#: Positions: the ends, and pairs 1e-9 and 1e-12 apart.
POSITIONS = (0.0, 0.1, 0.2, 0.35, 0.35 + 1e-12, 0.35 + 1e-9, 0.5, 0.5 + 1e-9, 0.65, 0.8, 0.9, 1.0)
ENDS = ("clamped", "pinned", "free", "sliding")


@st.composite
def constrained_scenes(draw):
    """Beams with supports, springs, a rotational spring and free (mostly) or elastic
    hinges, each at its own position above, hinges and supports inside the span (every
    kind present: one kernel per end pair)."""
    counts = {
        "support": draw(st.integers(1, 2)),
        "spring": draw(st.integers(1, 2)),
        "rotational_spring": 1,
        "hinge": draw(st.integers(1, 3)),
    }
    inner = draw(st.permutations(POSITIONS[1:-1]))  # hinges and supports: not at an end
    k = counts["hinge"] + counts["support"]
    outer = iter(inner[:k] + draw(st.permutations(inner[k:] + [0.0, 1.0])))
    atts = []
    for kind in ("hinge", "support", "spring", "rotational_spring"):
        for _ in range(counts[kind]):
            a = {"type": kind, "x": next(outer)}
            if kind in ("spring", "rotational_spring"):
                a["k"] = draw(st.sampled_from((1.0, 1e12)))
            elif kind == "hinge":
                a["k"] = draw(st.sampled_from((0.0, 0.0, 0.0, 5.0)))
            atts.append(a)
    return scene(atts, draw(st.sampled_from(ENDS)), draw(st.sampled_from(ENDS)))


@settings(
    max_examples=80,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)
@given(constrained_scenes())
def test_property_exact_rank_equals_the_reference(sc):
    try:
        s = mstmm.scene_from_dict(sc)
    except SceneError:
        return  # a placement the scene refuses (two constraints at one x, ...)
    kernel = mstmm.kernel_for(s)
    assert kernel.rigid_body_modes(mstmm.parameter_vector(s)) == ref.rigid_body_mode_count(sc)

"""Every scene in examples/ solves, certified, and matches the independent reference model."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from eigenspaces import check_against_reference, check_shapes
from reference_model import frequencies, rigid_body_mode_count

import mstmm

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
SCENES = sorted(EXAMPLES.glob("*.toml"))
#: The damped examples (complex roots: the damped reference); the rest are undamped.
DAMPED = [p for p in SCENES if mstmm.topology_of(mstmm.load_scene(p)).damped]
UNDAMPED = [p for p in SCENES if p not in DAMPED]
MODES = 10


def test_the_examples_are_there_and_described():
    names = {p.name for p in SCENES}
    assert {"wu_chou_1998.toml", "launch_vehicle.toml", "absorbers.toml"} <= names
    readme = (EXAMPLES / "README.md").read_text()
    for name in names:
        assert f"`{name}`" in readme, name


def test_the_paper_example_is_the_bundled_scene():
    copy = mstmm.load_scene(EXAMPLES / "wu_chou_1998.toml")
    assert copy == mstmm.load_scene(mstmm.example_path("wu_chou_1998"))


@pytest.mark.parametrize("path", UNDAMPED, ids=[p.stem for p in UNDAMPED])
def test_example_matches_reference(path):
    scene = mstmm.load_scene(path)
    sol = mstmm.solve(scene, modes=MODES)
    assert sol.count_checked, sol.warnings
    assert not sol.warnings
    assert sol.converged.all()
    assert len(sol.omega) == MODES
    exact = np.array(frequencies(scene, MODES, dps=30), dtype=float)
    zero = exact == 0.0
    assert zero.sum() == rigid_body_mode_count(scene)
    np.testing.assert_array_equal(sol.omega[zero], 0.0)
    rel = np.abs(sol.omega[~zero] - exact[~zero]) / exact[~zero]
    assert rel.max() < 1e-12, (path.stem, rel.max())
    # the default path: a shape per frequency; each spans the reference null space (an
    # mpmath SVD of the global matrix: affordable up to a handful of attachments)
    check_shapes(scene, sol)
    if len(scene.attachments) <= 6:
        check_against_reference(scene, sol, 1e-9, list(exact))


@pytest.mark.parametrize("path", DAMPED, ids=[p.stem for p in DAMPED])
def test_damped_example_matches_reference(path):
    """The damped roots (default path, mode shapes on) against the reference model's
    (``damped_frequencies``: complex global assembly, its own argument-principle count)."""
    from reference_model import damped_frequencies

    from mstmm.scene import scene_to_dict

    scene = mstmm.load_scene(path)
    sol = mstmm.solve(scene, modes=MODES)
    assert sol.count_checked and not sol.warnings and sol.converged.all(), sol.warnings
    exact = np.array([complex(w) for w in damped_frequencies(scene_to_dict(scene), MODES)])
    rel = np.abs(sol.omega - exact) / np.where(exact == 0, 1.0, np.abs(exact))
    assert rel.max() < 1e-10, (path.stem, rel.max())
    assert len(sol.shapes) == MODES
    assert all(np.isfinite(s.Y).all() and s.singular_ratio < 1e-8 for s in sol.shapes)


def test_absorbers_scene_is_a_tight_cluster():
    """36 TMDs: the lowest ten frequencies all sit within 15 % of the bare first mode."""
    scene = mstmm.load_scene(EXAMPLES / "absorbers.toml")
    assert len(scene.attachments) == 36
    beam = scene.beam
    bare = np.pi**2 * np.sqrt(beam.EI / beam.mass_per_length) / beam.length**2
    sol = mstmm.solve(scene, modes=MODES)
    check_shapes(scene, sol)
    omega = sol.omega
    assert np.all(np.abs(omega / bare - 1.0) < 0.15)
    assert np.all(np.diff(omega) > 0)

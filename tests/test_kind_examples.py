"""The three example scenes of issue 13 against the independent reference model.

``examples/deck_three_span.toml`` (supports, tuned spring-masses), ``stepped_tower.toml``
(three segments, an elastically restrained end, a top mass with rotary inertia) and
``hinged_absorber.toml`` (a hinge with a rotational spring, a two-stage oscillator chain):
the lowest 6 frequencies of ``mstmm.solve(mstmm.load_scene(path), modes=6)`` within 1e-10
of ``reference_model.frequencies`` of the same file, with the default path's shapes. The
reference checks (name contains ``reference``) confirm the numbers the files' comments
state (bare-structure frequencies, tunings) with the reference model and closed forms.
The TOML snippets of the "Component kinds" section of ``docs/scenes.md`` are scenes too:
the reference model accepts them and the solver matches it.
"""

from __future__ import annotations

import copy
import math
import tomllib
from pathlib import Path

import mpmath
import numpy as np
import pytest
import reference_model as ref
from eigenspaces import check_shapes
from test_kinds import (
    chain_held_frequencies,
    check_frequencies,
    reference,
)

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
NAMES = ["deck_three_span", "stepped_tower", "hinged_absorber"]
MODES = 6


def scene(name: str) -> dict:
    """The example as a plain dict (what the reference model reads)."""
    with open(EXAMPLES / f"{name}.toml", "rb") as fh:
        return tomllib.load(fh)


def hz(sc: dict, modes: int) -> list[float]:
    return [float(w) / (2 * math.pi) for w in reference(sc, modes)]


@pytest.fixture(scope="module")
def mstmm():
    """The package under test (imported here, so that the reference checks run alone)."""
    import mstmm as package

    return package


@pytest.mark.parametrize("name", NAMES)
def test_example_lowest_modes(mstmm, name):
    sol = mstmm.solve(mstmm.load_scene(EXAMPLES / f"{name}.toml"), modes=MODES)
    assert sol.count_checked, sol.warnings
    assert not sol.warnings, sol.warnings
    assert np.all(sol.converged)
    check_frequencies(sol.omega, reference(scene(name), MODES))
    check_shapes(scene(name), sol)


def test_reference_deck_three_span():
    """The bare deck's modes and the dampers' tuning the comments state."""
    sc = scene("deck_three_span")
    bare = copy.deepcopy(sc)
    bare["attachments"] = [a for a in sc["attachments"] if a["type"] == "support"]
    f = hz(bare, 3)
    assert [f"{v:.3f}" for v in f] == ["2.908", "4.760", "5.710"]
    # the mode each damper is tuned to moves its span most (largest |W| at its midspan)
    mids = [15.0, 50.0, 85.0]
    target = {}
    for i, w in enumerate(reference(bare, 3)[:2]):
        shape = [abs(v) for v in ref.eigenspace(bare, w, 1, mids, dps=30)[0]]
        target.update({x: f[i] for x, v in zip(mids, shape) if v > 0.99 * max(shape)})
    assert target == {15.0: f[1], 50.0: f[0], 85.0: f[1]}
    spans = {15.0: 30.0, 50.0: 40.0, 85.0: 30.0}
    mbar = sc["beam"]["mass_per_length"]
    for a in sc["attachments"]:
        if a["type"] == "spring_mass":
            assert a["m"] == 0.01 * spans[a["x"]] * mbar
            tuned = math.sqrt(a["k"] / a["m"]) / (2 * math.pi)
            assert abs(tuned * 1.02 / target[a["x"]] - 1) < 1e-3, (a, tuned)
            assert f"{tuned:.3f}" == {15.0: "4.667", 50.0: "2.851", 85.0: "4.667"}[a["x"]]


def test_reference_stepped_tower():
    """First frequency on the foundation springs and on a clamped base; 327 t of tower."""
    sc = scene("stepped_tower")
    assert sum(s["length"] * s["mass_per_length"] for s in sc["beam"]["segments"]) == 327e3
    assert f"{hz(sc, 1)[0]:.3f}" == "0.408"
    clamped = copy.deepcopy(sc)
    clamped["beam"]["left"] = "clamped"
    clamped["attachments"] = [a for a in sc["attachments"] if a["type"] == "mass"]
    assert f"{hz(clamped, 1)[0]:.3f}" == "0.420"
    assert ref.rigid_body_mode_count(sc) == 0


def test_reference_hinged_absorber():
    """The bare girder with and without the splice's flexibility, and the absorber's own
    frequencies with its attachment point held (closed form), just below modes 1 and 2."""
    sc = scene("hinged_absorber")
    hinge = [a for a in sc["attachments"] if a["type"] == "hinge"]
    chain = next(a for a in sc["attachments"] if a["type"] == "oscillator_chain")
    bare = dict(sc, attachments=hinge)
    f = hz(bare, 2)
    assert [f"{v:.3f}" for v in f] == ["3.229", "9.840"]
    assert f"{hz(dict(sc, attachments=[]), 1)[0]:.3f}" == "3.478"
    with mpmath.mp.workdps(30):
        held = [
            float(w) / (2 * math.pi)
            for w in chain_held_frequencies(*(mpmath.mpf(v) for v in (*chain["k"], *chain["m"])))
        ]
    assert [f"{v:.3f}" for v in held] == ["3.152", "9.602"]
    assert all(0.95 < h / g < 1 for h, g in zip(held, f, strict=True))
    assert sc["beam"]["length"] * sc["beam"]["mass_per_length"] == 14.4e3


# ------------------------------------------- the kind snippets of docs/scenes.md

DOCS = Path(__file__).resolve().parent.parent / "docs" / "scenes.md"


def doc_scenes() -> list[dict]:
    """The TOML snippets of the "Component kinds" section of ``docs/scenes.md`` as scenes:
    a snippet without ``[beam]`` is put on a 4 m free-free beam."""
    text = DOCS.read_text().split("\n## Component kinds", 1)[1].split("\n## ", 1)[0]
    blocks = [b.split("```", 1)[0] for b in text.split("```toml\n")[1:]]
    out = []
    for block in blocks:
        data = tomllib.loads(block)
        if "beam" not in data:
            data["beam"] = {
                "left": "free",
                "right": "free",
                "length": 4.0,
                "EI": 5.0e5,
                "mass_per_length": 20.0,
            }
        elif "attachments" not in data and "segments" in data["beam"]:
            data["attachments"] = []
        out.append(data)
    return out


def test_reference_doc_snippets_are_scenes_of_every_kind():
    scenes = doc_scenes()
    assert len(scenes) == 3
    kinds = {a["type"] for sc in scenes for a in sc.get("attachments", [])}
    assert kinds == set(ref.KINDS)
    for sc in scenes:
        roots = reference(sc, 4)
        assert len(roots) == 4 and roots == sorted(roots)


@pytest.mark.parametrize("index", range(3))
def test_doc_snippets_solve(mstmm, index):
    sc = doc_scenes()[index]
    sol = mstmm.solve(mstmm.scene_from_dict(sc), modes=4)
    assert sol.count_checked, sol.warnings
    check_frequencies(sol.omega, reference(sc, 4))

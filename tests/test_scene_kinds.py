"""Scene files for every component kind (issue 13, section 2): reading, the parameter
layout, round trips and every error, through ``load_scene`` and through the command line.

Nothing here solves: the command line reports a bad scene before it loads any kernel.
"""

from __future__ import annotations

import types
from pathlib import Path

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from test_scene import run_cli_solve

import mstmm
from mstmm import catalog
from mstmm import scene as scene_module
from mstmm.scene import (
    ATTACHMENT_TYPES,
    BOUNDARY_KINDS,
    Attachment,
    Beam,
    SceneError,
    Segment,
    load_scene,
    scene_from_dict,
    scene_to_dict,
)

UNIFORM = """\
[beam]
left = "{left}"
right = "{right}"
length = 2.0
EI = 100.0
mass_per_length = 3.0
"""

STEPPED = """\
[beam]
left = "clamped"
right = "free"
[[beam.segments]]
length = 0.4
EI = 2.0e4
mass_per_length = 12.0
[[beam.segments]]
length = 0.6
EI = 1.0e4
mass_per_length = 8.0
"""

#: One of each kind on the stepped beam, deliberately not in x order.
EVERY_KIND = """
[[attachments]]
type = "mass"
x = 1.0
m = 2.0
J = 0.1
[[attachments]]
type = "oscillator_chain"
x = 0.5
k = [1.0e4, 2.0e4]
m = [1.0, 2.0]
[[attachments]]
type = "hinge"
x = 0.3
[[attachments]]
type = "support"
x = 0.7
[[attachments]]
type = "spring"
x = 0.0
k = 5.0
[[attachments]]
type = "rotational_spring"
x = 1.0
k = 3.0
"""


def uniform(left: str = "clamped", right: str = "free") -> str:
    return UNIFORM.format(left=left, right=right)


def attachment(kind: str, **values: object) -> str:
    lines = ["", "[[attachments]]", f'type = "{kind}"']
    lines += [f"{key} = {value}" for key, value in values.items()]
    return "\n".join(lines) + "\n"


def write(tmp_path: Path, text: str, name: str = "scene.toml") -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


# ---------------------------------------------------------------------------
# Reading every kind


def test_every_kind_reads_with_its_defaults(tmp_path):
    scene = load_scene(write(tmp_path, STEPPED + EVERY_KIND))
    assert scene.beam == Beam(
        1.0,
        2.0e4,
        12.0,
        "clamped",
        "free",
        (Segment(0.4, 2.0e4, 12.0), Segment(0.6, 1.0e4, 8.0)),
    )
    # sorted by x, stable: the mass stays before the rotational spring at x = 1
    assert scene.attachments == (
        Attachment("spring", 0.0, (("k", 5.0),)),
        Attachment("hinge", 0.3, (("k", 0.0),)),  # k defaults to 0: a free hinge
        Attachment("oscillator_chain", 0.5, (("k", (1.0e4, 2.0e4)), ("m", (1.0, 2.0)))),
        Attachment("support", 0.7, ()),
        Attachment("mass", 1.0, (("m", 2.0), ("J", 0.1))),
        Attachment("rotational_spring", 1.0, (("k", 3.0),)),
    )
    spring, hinge, chain, support, mass, rotational = scene.attachments
    assert (spring.k, hinge.k, chain.k, chain.m, mass.m, mass.J) == (
        5.0,
        0.0,
        (1.0e4, 2.0e4),
        (1.0, 2.0),
        2.0,
        0.1,
    )
    assert [a.kind for a in scene.attachments] == [
        "spring",
        "hinge",
        "oscillator_chain",
        "support",
        "mass",
        "rotational_spring",
    ]
    with pytest.raises(AttributeError, match="support attachment has no value 'k'"):
        _ = support.k
    assert type(chain.k) is tuple and all(type(v) is float for v in chain.k)


def test_mass_without_rotary_inertia_defaults_to_zero(tmp_path):
    scene = load_scene(write(tmp_path, uniform() + attachment("mass", x=1, m=2)))
    assert scene.attachments == (Attachment("mass", 1.0, (("m", 2.0), ("J", 0.0))),)


def test_parameter_vector_of_every_kind_by_hand(tmp_path):
    """The layout of docs/components.md section 4, written out from the scene above."""
    scene = load_scene(write(tmp_path, STEPPED + EVERY_KIND))
    # tags: the kinds present, sorted: hinge 0, mass 1, oscillator_chain 2,
    # rotational_spring 3, spring 4, support 5
    # [L, EI_0, mbar_0, n_seg, n_ev, left end, right end] (codes of catalog.END_CODES:
    # clamped 0, free 2)
    head = [1.0, 2.0e4, 12.0, 2.0, 6.0, 0.0, 2.0]
    # segment rows (x_end, EI, mbar, eta, kappa_GA, rho_I, P, k_w, k_G): Euler-Bernoulli
    segments = [0.4, 2.0e4, 12.0, 0.0, 0, 0, 0, 0, 0, 1.0, 1.0e4, 8.0, 0.0, 0, 0, 0, 0, 0]
    # data from 7 + 2 * 9 + 6 * 3 = 43, one block per attachment in x order:
    # spring [5] at 43, hinge [0] at 44, chain [2, 1e4, 2e4, 2, 1, 2, 2, 0, 0] at 45 (its
    # dashpots, none given, as zeros), support [] at 54, mass [2, 0.1] at 54, rotational
    # spring [3] at 56
    events = [4, 0.0, 43, 0, 0.3, 44, 2, 0.5, 45, 5, 0.7, 54, 1, 1.0, 54, 3, 1.0, 56]
    data = [5.0, 0.0, 2, 1.0e4, 2.0e4, 2, 1.0, 2.0, 2, 0.0, 0.0, 2.0, 0.1, 3.0]
    expected = head + segments + events + data
    assert mstmm.parameter_vector(scene).tolist() == [float(v) for v in expected]


def test_uniform_beam_dict_is_unchanged(tmp_path):
    scene = load_scene(write(tmp_path, uniform("pinned", "sliding")))
    assert scene.beam.segments == ()
    assert scene_to_dict(scene)["beam"] == {
        "length": 2.0,
        "EI": 100.0,
        "mass_per_length": 3.0,
        "left": "pinned",
        "right": "sliding",
    }


def test_one_segment_is_a_stepped_beam(tmp_path):
    text = STEPPED.split("[[beam.segments]]")
    scene = load_scene(write(tmp_path, text[0] + "[[beam.segments]]" + text[1]))
    assert scene.beam == Beam(0.4, 2.0e4, 12.0, "clamped", "free", (Segment(0.4, 2.0e4, 12.0),))


@pytest.mark.parametrize(
    "kind, values, data",
    [
        ("mass", {"m": 2.0, "J": 0.5}, {"m": 2.0, "J": 0.5}),
        ("mass", {"m": 2.0}, {"m": 2.0, "J": 0.0}),
        ("spring", {"k": 7.0}, {"k": 7.0}),
        ("rotational_spring", {"k": 7.0}, {"k": 7.0}),
        ("support", {}, {}),
        ("hinge", {}, {"k": 0.0}),
        ("hinge", {"k": 4.0}, {"k": 4.0}),
        ("spring_mass", {"k": 7.0, "m": 2.0}, {"k": 7.0, "m": 2.0}),
        ("oscillator_chain", {"k": [1.0, 2.0, 3.0], "m": [4.0, 5.0, 6.0]}, None),
    ],
)
def test_every_kind_round_trips(kind, values, data):
    beam = {"length": 2.0, "EI": 1e4, "mass_per_length": 5.0, "left": "free", "right": "free"}
    given_dict = {"name": "d", "beam": beam, "attachments": [{"type": kind, "x": 0.5, **values}]}
    scene = scene_from_dict(given_dict)
    expected = dict(given_dict["attachments"][0]) if data is None else {"type": kind, "x": 0.5}
    if data is not None:
        expected |= data
    assert scene_to_dict(scene) == {"name": "d", "beam": beam, "attachments": [expected]}
    assert scene_from_dict(scene_to_dict(scene)) == scene


def test_stepped_beam_round_trips(tmp_path):
    scene = load_scene(write(tmp_path, STEPPED + EVERY_KIND))
    data = scene_to_dict(scene)
    assert data["beam"] == {
        "left": "clamped",
        "right": "free",
        "segments": [
            {"length": 0.4, "EI": 2.0e4, "mass_per_length": 12.0},
            {"length": 0.6, "EI": 1.0e4, "mass_per_length": 8.0},
        ],
    }
    assert data["attachments"][2] == {
        "type": "oscillator_chain",
        "x": 0.5,
        "k": [1.0e4, 2.0e4],
        "m": [1.0, 2.0],
    }
    again = scene_from_dict(data, source=scene.source)
    assert again == scene
    assert scene_to_dict(again) == data


def test_replace_with_a_stepped_beam_revalidates():
    beam = {"length": 1.0, "EI": 1.0, "mass_per_length": 1.0, "left": "free", "right": "free"}
    scene = scene_from_dict({"beam": beam, "attachments": [{"type": "hinge", "x": 0.5}]})
    stepped = Beam(3.0, 1.0, 1.0, "free", "free", (Segment(1.0, 1.0, 1.0), Segment(2.0, 2.0, 2.0)))
    assert scene.replace(beam=stepped).beam == stepped
    short = Beam(0.5, 1.0, 1.0, "free", "free", (Segment(0.5, 1.0, 1.0),))
    with pytest.raises(SceneError, match=r"attachments\[0\]\.x: must lie inside the beam"):
        scene.replace(beam=short)
    with pytest.raises(SceneError, match=r"beam\.segments\[0\]\.EI: must be > 0"):
        scene.replace(beam=Beam(1.0, 0.0, 1.0, "free", "free", (Segment(1.0, 0.0, 1.0),)))


def test_attachment_pickles_and_hashes():
    import copy
    import pickle

    a = Attachment("oscillator_chain", 0.5, (("k", (1.0, 2.0)), ("m", (3.0, 4.0))))
    assert pickle.loads(pickle.dumps(a)) == a
    assert copy.deepcopy(a) == a and hash(copy.copy(a)) == hash(a)
    assert pickle.loads(pickle.dumps(a)).m == (3.0, 4.0)


# ---------------------------------------------------------------------------
# Placements that are valid


@pytest.mark.parametrize(
    "text",
    [
        uniform("free", "free") + attachment("support", x=0.0),  # a free end: now pinned
        uniform("sliding", "free") + attachment("support", x=0.0),
        uniform("clamped", "free") + attachment("support", x=2.0),
        uniform() + attachment("hinge", x=1) + attachment("support", x=1),
        uniform() + attachment("hinge", x=1) + attachment("spring", x=1, k=2),
        uniform() + attachment("hinge", x=1) + attachment("mass", x=1, m=2),  # J = 0
        uniform() + attachment("hinge", x=1) + attachment("mass", x=1, m=2, J=0.0),
        uniform() + attachment("hinge", x=1) + attachment("hinge", x=1.2, k=3),
        uniform() + attachment("hinge", x=1) + attachment("rotational_spring", x=1.5, k=3),
        uniform() + attachment("rotational_spring", x=0, k=3) + attachment("spring", x=0, k=1),
        uniform() + attachment("oscillator_chain", x=2, k=[1], m=[2]),
    ],
)
def test_valid_placements(tmp_path, text):
    load_scene(write(tmp_path, text))


# ---------------------------------------------------------------------------
# Every error: one line naming the file, the field and the value

ERRORS = {
    # stepped beams
    "segment_length_zero": (
        STEPPED.replace("length = 0.6", "length = 0.0"),
        "beam.segments[1].length",
        "0.0",
        "must be > 0",
    ),
    "segment_length_negative": (
        STEPPED.replace("length = 0.4", "length = -0.4"),
        "beam.segments[0].length",
        "-0.4",
        "must be > 0",
    ),
    "segment_EI_nan": (
        STEPPED.replace("EI = 1.0e4", "EI = nan"),
        "beam.segments[1].EI",
        "nan",
        "must be finite",
    ),
    "length_and_segments": (
        STEPPED.replace('right = "free"\n', 'right = "free"\nlength = 1.0\n'),
        "beam.length",
        "1.0",
        "not with [[beam.segments]]",
    ),
    "EI_and_segments": (
        STEPPED.replace('right = "free"\n', 'right = "free"\nEI = 5.0\n'),
        "beam.EI",
        "5.0",
        "not with [[beam.segments]]",
    ),
    "empty_segments": (
        '[beam]\nleft = "clamped"\nright = "free"\nsegments = []\n',
        "beam.segments",
        "[]",
        "at least one segment",
    ),
    "segments_not_tables": (
        '[beam]\nleft = "clamped"\nright = "free"\nsegments = 3\n',
        "beam.segments",
        "3",
        "array of tables",
    ),
    "segment_unknown_key": (
        STEPPED.replace("EI = 1.0e4", "EI = 1.0e4\ndensity = 7800.0"),
        "beam.segments[1].density",
        "7800.0",
        "unknown key (allowed: length, EI, mass_per_length, loss_factor, kappa_GA, rho_I,"
        " axial_force, foundation_k, foundation_kG)",
    ),
    "segment_missing_EI": (
        STEPPED.replace("EI = 2.0e4\n", ""),
        "beam.segments[0].EI",
        None,
        "missing",
    ),
    "segment_EI_beyond_float64": (
        STEPPED.replace("EI = 1.0e4", "EI = 1e300"),
        "beam.segments[1].EI",
        "1e+300",
        "float64",
    ),
    # hinges
    "hinge_at_left_end": (
        uniform("free", "free") + attachment("hinge", x=0.0),
        "attachments[0].x",
        "0.0",
        "must lie inside the beam",
    ),
    "hinge_at_right_end": (
        uniform() + attachment("spring", x=1, k=1) + attachment("hinge", x=2.0),
        "attachments[1].x",
        "2.0",
        "must lie inside the beam",
    ),
    "hinge_negative_k": (
        uniform() + attachment("hinge", x=1, k=-1.0),
        "attachments[0].k",
        "-1.0",
        "must be >= 0",
    ),
    # supports where the end already fixes Y
    "support_at_clamped_left": (
        uniform("clamped", "free") + attachment("support", x=0),
        "attachments[0].x",
        "0",
        "already fixes Y",
    ),
    "support_at_pinned_left": (
        uniform("pinned", "free") + attachment("support", x=0.0),
        "attachments[0].x",
        "0.0",
        "already fixes Y",
    ),
    "support_at_clamped_right": (
        uniform("free", "clamped") + attachment("support", x=2.0),
        "attachments[0].x",
        "2.0",
        "already fixes Y",
    ),
    "support_at_pinned_right": (
        uniform("free", "pinned") + attachment("mass", x=2, m=1) + attachment("support", x=2.0),
        "attachments[1].x",
        "2.0",
        "already fixes Y",
    ),
    "two_supports_at_one_x": (
        uniform("free", "free") + attachment("support", x=1.5) + attachment("support", x=1.5),
        "attachments[1].x",
        "1.5",
        "the attachments[0] constraint at the same x already fixes Y",
    ),
    "two_hinges_at_one_x": (
        uniform("free", "free") + attachment("hinge", x=1.5) + attachment("hinge", x=1.5, k=2.0),
        "attachments[1].x",
        "1.5",
        "at the same x as the hinge attachments[0]",
    ),
    # oscillator chains
    "chain_unequal_lists": (
        uniform() + attachment("oscillator_chain", x=1, k=[1.0, 2.0], m=[1.0]),
        "attachments[0].m",
        "[1.0]",
        "must have as many entries as k (2)",
    ),
    "chain_empty_lists": (
        uniform() + attachment("oscillator_chain", x=1, k=[], m=[]),
        "attachments[0].k",
        "[]",
        "non-empty",
    ),
    "chain_not_a_list": (
        uniform() + attachment("oscillator_chain", x=1, k=5.0, m=[1.0]),
        "attachments[0].k",
        "5.0",
        "must be a list of numbers",
    ),
    "chain_bad_element": (
        uniform() + attachment("oscillator_chain", x=1, k=[1.0, -2.0], m=[1.0, 1.0]),
        "attachments[0].k[1]",
        "-2.0",
        "must be > 0",
    ),
    "chain_element_not_a_number": (
        uniform() + attachment("oscillator_chain", x=1, k=[1.0, 2.0], m='[1.0, "a"]'),
        "attachments[0].m[1]",
        "'a'",
        "must be a number",
    ),
    "chain_missing_m": (
        uniform() + attachment("oscillator_chain", x=1, k=[1.0]),
        "attachments[0].m",
        None,
        "missing",
    ),
    "chain_ratio_beyond_float64": (
        uniform() + attachment("oscillator_chain", x=1, k=[1.0, 1e200], m=[1.0, 1e-90]),
        "attachments[0].k[1]",
        "1e+200",
        "k/m is about 1e+290",
    ),
    # rotary inertia
    "J_negative": (
        uniform() + attachment("mass", x=1, m=1, J=-0.5),
        "attachments[0].J",
        "-0.5",
        "must be >= 0",
    ),
    "J_beyond_float64": (
        uniform() + attachment("mass", x=1, m=1, J=1e300),
        "attachments[0].J",
        "1e+300",
        "float64",
    ),
    # rotational components at a hinge
    "rotary_mass_at_hinge": (
        uniform() + attachment("hinge", x=1) + attachment("mass", x=1, m=1, J=0.5),
        "attachments[1].x",
        "1",
        "ambiguous",
    ),
    "rotational_spring_at_hinge": (
        uniform() + attachment("rotational_spring", x=1.5, k=2) + attachment("hinge", x=1.5),
        "attachments[0].x",
        "1.5",
        "the hinge attachments[1]",
    ),
    # a key of another kind, a missing key, an unknown kind
    "spring_with_mass_key": (
        uniform() + attachment("spring", x=1, k=1, m=2),
        "attachments[0].m",
        "2",
        "unknown key (allowed: type, x, k)",
    ),
    "support_with_k": (
        uniform() + attachment("support", x=1, k=2),
        "attachments[0].k",
        "2",
        "unknown key (allowed: type, x)",
    ),
    "mass_with_J_of_hinge_kind": (
        uniform() + attachment("hinge", x=1, J=2),
        "attachments[0].J",
        "2",
        "unknown key (allowed: type, x, k)",
    ),
    "spring_missing_k": (
        uniform() + attachment("spring", x=1),
        "attachments[0].k",
        None,
        "missing",
    ),
    "mass_missing_m": (
        uniform() + attachment("mass", x=1, J=1),
        "attachments[0].m",
        None,
        "missing",
    ),
    "rotational_spring_k_zero": (
        uniform() + attachment("rotational_spring", x=1, k=0),
        "attachments[0].k",
        "0",
        "must be > 0",
    ),
    "unknown_kind": (
        uniform() + attachment("damper", x=1, c=2),
        "attachments[0].type",
        "'damper'",
        "'oscillator_chain'",
    ),
    "x_outside_stepped_beam": (
        STEPPED + attachment("spring", x=1.5, k=1),
        "attachments[0].x",
        "1.5",
        "must lie in [0, length] with beam length 1.0",
    ),
}


@pytest.mark.parametrize("case", sorted(ERRORS))
def test_error_through_load_scene(tmp_path, case):
    text, field, value, words = ERRORS[case]
    path = write(tmp_path, text, f"bad_{case}.toml")
    with pytest.raises(SceneError) as info:
        load_scene(path)
    message = str(info.value)
    assert len(message.splitlines()) == 1, message
    assert message.startswith(f"{path}: {field}: "), message
    assert info.value.field == field
    assert words in message, message
    if value is None:
        assert not info.value.has_value and message.endswith(": missing")
    else:
        assert f"(got {value}" in message, message


@pytest.mark.parametrize("case", sorted(ERRORS))
def test_error_through_the_command_line(tmp_path, case):
    """``mstmm solve FILE``: exit status 2, nothing on stdout, the same one line."""
    text, field, _, _ = ERRORS[case]
    path = write(tmp_path, text, f"bad_{case}.toml")
    result = run_cli_solve(path)
    assert result.returncode == 2, result.stderr
    assert result.stdout == ""
    (line,) = result.stderr.splitlines()
    with pytest.raises(SceneError) as info:
        load_scene(path)
    assert line == f"mstmm: error: {info.value}"
    assert f"{path}: {field}: " in line


def test_first_error_in_file_order_names_the_file_index(tmp_path):
    """Placement errors are found on the sorted scene but named by the place in the file."""
    text = (
        uniform("free", "free")
        + attachment("spring", x=1.9, k=1)
        + attachment("support", x=0.5)
        + attachment("spring", x=0.1, k=1)
        + attachment("support", x=0.5)
    )
    with pytest.raises(SceneError) as info:
        load_scene(write(tmp_path, text))
    assert info.value.field == "attachments[3].x"
    assert "attachments[1]" in info.value.problem


# ---------------------------------------------------------------------------
# A kind registered after import is accepted (read from the registry when validating)


def _toy_energy(v):
    """Its physics: a spring to the ground (a kind declares its energy or descriptor)."""
    import sympy as sp

    from mstmm.physics import Energy

    return Energy(K=sp.diag(v["stiffness"], 0), C=sp.zeros(2, 2), M=sp.zeros(2, 2))


@pytest.fixture
def toy_kind():
    module = types.ModuleType("toy_grounded_spring")
    module.KIND = "toy_grounded_spring"
    module.DOC = "a grounded spring with another key name (test only)"
    module.KEYS = (
        catalog.Key("x", "m", check="position"),
        catalog.Key("stiffness", "N/m"),
    )
    module.COUNT = "stiffness"
    module.RIGID = ("Y",)
    module.energy = _toy_energy
    catalog.register_kind(module)
    try:
        yield module
    finally:
        del catalog.kinds()[module.KIND]


def test_the_kinds_of_issue_13_are_built_in():
    """Issue 13's kinds, and issue 14's dashpot."""
    assert set(ATTACHMENT_TYPES) == {*KINDS, "dashpot"}


def test_registered_kind_is_accepted(toy_kind):
    assert "toy_grounded_spring" in scene_module.ATTACHMENT_TYPES
    beam = {"length": 1.0, "EI": 1.0, "mass_per_length": 1.0, "left": "free", "right": "free"}
    data = {
        "name": "toy",
        "beam": beam,
        "attachments": [{"type": "toy_grounded_spring", "x": 0.25, "stiffness": 9.0}],
    }
    scene = scene_from_dict(data)
    assert scene.attachments[0].stiffness == 9.0
    assert scene_to_dict(scene) == data
    # [L, EI, mbar, 1, 1, free 2, free 2], segment [1, 1, 1, 0, 0, 0, 0, 0, 0], event (tag 0,
    # 0.25, 19), data [9]
    expected = [1.0, 1.0, 1.0, 1.0, 1.0, 2.0, 2.0, 1.0, 1.0, 1.0, 0.0] + [0.0] * 5
    expected += [0.0, 0.25, 19.0, 9.0]
    assert mstmm.parameter_vector(scene).tolist() == expected
    data["attachments"][0]["k"] = 1.0
    with pytest.raises(SceneError, match=r"attachments\[0\]\.k: unknown key \(allowed: type, x,"):
        scene_from_dict(data)


# ---------------------------------------------------------------------------
# Property: random valid scenes of every kind round-trip unchanged

KINDS = (
    "hinge",
    "mass",
    "oscillator_chain",
    "rotational_spring",
    "spring",
    "spring_mass",
    "support",
)


def decades(lo: int, hi: int) -> st.SearchStrategy[float]:
    return st.builds(lambda a, e: a * 10.0**e, st.floats(1.0, 9.999), st.integers(lo, hi))


@st.composite
def components(draw, length: float):
    kind = draw(st.sampled_from(KINDS))
    u = draw(st.one_of(st.sampled_from([0.0, 0.25, 0.5, 1.0]), st.floats(0.0, 1.0)))
    item: dict = {"type": kind, "x": u * length}
    if kind in ("spring", "rotational_spring"):
        item["k"] = draw(decades(-3, 6))
    elif kind == "spring_mass":
        item |= {"k": draw(decades(-3, 6)), "m": draw(decades(-3, 3))}
    elif kind == "mass":
        item["m"] = draw(decades(-3, 3))
        if draw(st.booleans()):
            item["J"] = draw(st.one_of(st.just(0.0), decades(-3, 3)))
    elif kind == "hinge" and draw(st.booleans()):
        item["k"] = draw(st.one_of(st.just(0.0), decades(-3, 6)))
    elif kind == "oscillator_chain":
        n = draw(st.integers(1, 4))
        item["k"] = draw(st.lists(decades(-3, 6), min_size=n, max_size=n))
        item["m"] = draw(st.lists(decades(-3, 3), min_size=n, max_size=n))
    return item


def placement_is_valid(beam: dict, length: float, items: list[dict]) -> bool:
    """The placement rules, written out independently of mstmm.scene."""
    fixes_y = {"clamped": True, "pinned": True, "free": False, "sliding": False}
    hinges = {a["x"] for a in items if a["type"] == "hinge"}
    supports = [a["x"] for a in items if a["type"] == "support"]
    if len(set(supports)) != len(supports):
        return False
    if len(hinges) != sum(a["type"] == "hinge" for a in items):
        return False
    for a in items:
        if a["type"] == "hinge" and not 0.0 < a["x"] < length:
            return False
        if a["type"] == "support":
            if (a["x"] == 0.0 and fixes_y[beam["left"]]) or (
                a["x"] == length and fixes_y[beam["right"]]
            ):
                return False
        turns = a["type"] == "rotational_spring" or (a["type"] == "mass" and a.get("J", 0.0) > 0)
        if turns and a["x"] in hinges:
            return False
    return True


@st.composite
def kind_scene_dicts(draw):
    beam: dict = {
        "left": draw(st.sampled_from(BOUNDARY_KINDS)),
        "right": draw(st.sampled_from(BOUNDARY_KINDS)),
    }
    if draw(st.booleans()):
        segments = draw(
            st.lists(
                st.fixed_dictionaries(
                    {
                        "length": decades(-2, 1),
                        "EI": decades(-3, 9),
                        "mass_per_length": decades(-3, 4),
                    }
                ),
                min_size=1,
                max_size=5,
            )
        )
        beam["segments"] = segments
        length = float(sum(s["length"] for s in segments))
    else:
        length = draw(decades(-2, 2))
        beam |= {"length": length, "EI": draw(decades(-3, 9)), "mass_per_length": 2.5}
    items = draw(st.lists(components(length), max_size=15))
    assume(placement_is_valid(beam, length, items))
    return {"beam": beam, "attachments": items}


@settings(max_examples=200, deadline=None)
@given(kind_scene_dicts())
def test_property_every_kind_round_trips(data):
    scene = scene_from_dict(data)
    back = scene_to_dict(scene)
    assert scene_from_dict(back) == scene
    assert scene_to_dict(scene_from_dict(back)) == back
    # the values given come back (defaults filled in), sorted by x, stably
    order = sorted(range(len(data["attachments"])), key=lambda i: data["attachments"][i]["x"])
    for i, item in zip(order, back["attachments"]):
        assert {k: v for k, v in item.items() if k in data["attachments"][i]} == data[
            "attachments"
        ][i]
    if "segments" in data["beam"]:
        assert back["beam"] == data["beam"]
        assert scene.beam.EI == data["beam"]["segments"][0]["EI"]
    else:
        assert scene.beam.segments == ()
    assert np.all(np.diff([a.x for a in scene.attachments]) >= 0)

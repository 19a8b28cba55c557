"""Tests of mstmm.scene: the scene file format and its validation."""

from __future__ import annotations

import math
import pickle
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mstmm.scene import (
    ATTACHMENT_TYPES,
    BOUNDARY_KINDS,
    Attachment,
    Beam,
    Scene,
    SceneError,
    SpringMass,
    load_scene,
    scene_from_dict,
    scene_to_dict,
)

DATA = Path(__file__).parent / "data"

BEAM_TOML = """\
[beam]
length = 2.0
EI = 100.0
mass_per_length = 3.0
left = "clamped"
right = "free"
"""

ATTACHMENT_TOML = """
[[attachments]]
type = "spring_mass"
x = {x}
k = {k}
m = {m}
"""


def good_toml(*attachments: tuple[object, object, object]) -> str:
    text = BEAM_TOML
    for x, k, m in attachments:
        text += ATTACHMENT_TOML.format(x=x, k=k, m=m)
    return text


def write(tmp_path: Path, text: str, name: str = "scene.toml") -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def raises_scene_error(path: Path, field: str, value: str | None) -> SceneError:
    """Load ``path``, expect SceneError; check the message is one line naming all parts."""
    with pytest.raises(SceneError) as info:
        load_scene(path)
    message = str(info.value)
    assert len(message.splitlines()) == 1, message
    assert message.strip() == message and message
    assert str(path) in message
    assert path.name in message
    assert f": {field}: " in message, message
    assert info.value.field == field
    if value is not None:
        assert value in message, message
    return info.value


# ---------------------------------------------------------------------------
# The shipped scenes


def test_constants():
    assert BOUNDARY_KINDS == ("clamped", "pinned", "free", "sliding")
    assert "spring_mass" in ATTACHMENT_TYPES  # every kind: tests/test_scene_kinds.py
    assert SpringMass(0.5, 2.0, 3.0).kind == "spring_mass"
    assert SpringMass(0.5, 2.0, 3.0) == Attachment("spring_mass", 0.5, (("k", 2.0), ("m", 3.0)))


def test_load_wu_chou():
    scene = load_scene(DATA / "wu_chou_1998.toml")
    assert isinstance(scene, Scene)
    assert scene.name == "wu_chou_1998"
    assert scene.source == str(DATA / "wu_chou_1998.toml")
    assert scene.beam == Beam(
        length=1.0,
        EI=63476.125002707834,
        mass_per_length=15.3875,
        left="clamped",
        right="free",
    )
    assert scene.attachments == (
        SpringMass(x=0.1, k=190428.3750081235, m=3.0775),
        SpringMass(x=0.4, k=285642.56251218525, m=7.69375),
        SpringMass(x=0.8, k=380856.750016247, m=15.3875),
    )
    xs = [a.x for a in scene.attachments]
    assert xs == sorted(xs)
    for value in (scene.beam.length, scene.beam.EI, scene.beam.mass_per_length):
        assert type(value) is float
    assert isinstance(scene.attachments, tuple)


def test_load_bare_cantilever():
    scene = load_scene(str(DATA / "bare_cantilever.toml"))
    assert scene.name == "bare_cantilever"
    assert scene.beam == Beam(1.0, 63476.125002707834, 15.3875, "clamped", "free")
    assert scene.attachments == ()


def test_unsorted_attachments_get_sorted_stably(tmp_path):
    text = good_toml((1.5, 10, 1), (0.5, 20, 2), (2, 30, 3), (0, 40, 4), (0.5, 50, 5))
    scene = load_scene(write(tmp_path, text))
    assert [(a.x, a.k) for a in scene.attachments] == [
        (0.0, 40.0),
        (0.5, 20.0),
        (0.5, 50.0),
        (1.5, 10.0),
        (2.0, 30.0),
    ]
    # ints are converted to float
    assert all(type(v) is float for a in scene.attachments for v in (a.x, a.k, a.m))
    assert type(scene.beam.length) is float


def test_ends_and_coincident_attachments_allowed(tmp_path):
    scene = load_scene(write(tmp_path, good_toml((0, 1, 1), (2.0, 1, 1), (2.0, 2, 2))))
    assert [a.x for a in scene.attachments] == [0.0, 2.0, 2.0]


def test_default_name_is_file_stem(tmp_path):
    scene = load_scene(write(tmp_path, good_toml(), "my-beam.v2.toml"))
    assert scene.name == "my-beam.v2"
    assert scene_from_dict(scene_to_dict(scene) | {"name": "other"}).name == "other"


def test_default_name_is_sanitised(tmp_path):
    scene = load_scene(write(tmp_path, good_toml(), "my beam (1).toml"))
    assert scene.name == "my_beam__1_"


def test_all_boundary_kinds(tmp_path):
    for left in BOUNDARY_KINDS:
        for right in BOUNDARY_KINDS:
            text = BEAM_TOML.replace('left = "clamped"', f'left = "{left}"')
            text = text.replace('right = "free"', f'right = "{right}"')
            beam = load_scene(write(tmp_path, text)).beam
            assert (beam.left, beam.right) == (left, right)


def test_many_attachments(tmp_path):
    n = 3000
    items = [(2.0 * ((i * 7919) % n) / n, 1.0 + i, 0.5 + i) for i in range(n)]
    scene = load_scene(write(tmp_path, good_toml(*items)))
    assert len(scene.attachments) == n
    xs = [a.x for a in scene.attachments]
    assert xs == sorted(xs)


# ---------------------------------------------------------------------------
# Bad input, one test per class


def test_file_not_found(tmp_path):
    path = tmp_path / "nope.toml"
    error = raises_scene_error(path, "-", repr(str(path)))
    assert "not found" in str(error)


def test_unreadable_directory(tmp_path):
    path = tmp_path / "adir.toml"
    path.mkdir()
    raises_scene_error(path, "-", repr(str(path)))


def test_not_utf8(tmp_path):
    path = tmp_path / "latin1.toml"
    path.write_bytes(b'name = "caf\xe9"\n' + BEAM_TOML.encode())
    error = raises_scene_error(path, "-", None)
    assert "UTF-8" in str(error)


def test_malformed_toml(tmp_path):
    path = write(tmp_path, BEAM_TOML + "k = = 3\n")
    error = raises_scene_error(path, "-", "'k = = 3'")
    assert "malformed TOML" in str(error)
    assert "line 7" in str(error)  # tomllib's own message is included


def test_malformed_toml_duplicate_key(tmp_path):
    path = write(tmp_path, BEAM_TOML + "length = 3.0\n")
    raises_scene_error(path, "-", "length = 3.0")


def test_malformed_toml_unterminated_string(tmp_path):
    path = write(tmp_path, 'name = "abc\n' + BEAM_TOML)
    raises_scene_error(path, "-", "abc")


@pytest.mark.parametrize(
    ("text", "field"),
    [
        ('name = "x"\n', "beam"),
        (BEAM_TOML.replace("length = 2.0\n", ""), "beam.length"),
        (BEAM_TOML.replace("EI = 100.0\n", ""), "beam.EI"),
        (BEAM_TOML.replace("mass_per_length = 3.0\n", ""), "beam.mass_per_length"),
        (BEAM_TOML.replace('left = "clamped"\n', ""), "beam.left"),
        (BEAM_TOML.replace('right = "free"\n', ""), "beam.right"),
        (good_toml((1, 1, 1), (1, 1, 2)).replace("m = 2\n", ""), "attachments[1].m"),
        (good_toml((1, 1, 1)).replace("x = 1\n", ""), "attachments[0].x"),
        (good_toml((1, 1, 1)).replace("k = 1\n", ""), "attachments[0].k"),
        (good_toml((1, 1, 1)).replace('type = "spring_mass"\n', ""), "attachments[0].type"),
    ],
)
def test_missing_key(tmp_path, text, field):
    error = raises_scene_error(write(tmp_path, text), field, None)
    assert str(error).endswith(f": {field}: missing")


@pytest.mark.parametrize(
    ("text", "field", "value"),
    [
        ("nmae = 'x'\n" + BEAM_TOML, "nmae", "'x'"),
        (BEAM_TOML.replace("EI =", "E_I ="), "beam.E_I", "100.0"),
        (BEAM_TOML + "density = 7800.0\n", "beam.density", "7800.0"),
        (good_toml((1, 1, 1), (1, 2, 3)) + "zeta = 0.5\n", "attachments[1].zeta", "0.5"),
        (good_toml((1, 1, 1)).replace("m = 1", "mass = 1"), "attachments[0].mass", "1"),
        (BEAM_TOML + "[extra]\na = 1\n", "extra", "{'a': 1}"),
        ('"odd key" = 1\n' + BEAM_TOML, '"odd key"', "1"),
    ],
)
def test_unknown_key(tmp_path, text, field, value):
    error = raises_scene_error(write(tmp_path, text), field, value)
    assert "unknown key" in str(error)


@pytest.mark.parametrize(
    ("old", "new", "field", "value"),
    [
        ("length = 2.0", 'length = "2.0"', "beam.length", "'2.0'"),
        ("EI = 100.0", "EI = true", "beam.EI", "True"),
        ("mass_per_length = 3.0", "mass_per_length = [3.0]", "beam.mass_per_length", "[3.0]"),
        ("k = 1", 'k = "1e5"', "attachments[0].k", "'1e5'"),
        ("m = 1", "m = false", "attachments[0].m", "False"),
        ("x = 1", "x = 1979-05-27", "attachments[0].x", "1979"),
        ('left = "clamped"', "left = 1", "beam.left", "1"),
        ('right = "free"', "right = true", "beam.right", "True"),
        ('type = "spring_mass"', "type = 3", "attachments[0].type", "3"),
        ('name = "n"', "name = 5", "name", "5"),
    ],
)
def test_wrong_type(tmp_path, old, new, field, value):
    text = 'name = "n"\n' + good_toml((1, 1, 1))
    assert old in text
    raises_scene_error(write(tmp_path, text.replace(old, new, 1)), field, value)


def test_beam_not_a_table(tmp_path):
    error = raises_scene_error(write(tmp_path, "beam = 3\n"), "beam", "3")
    assert "table" in str(error)


def test_attachments_not_an_array_of_tables(tmp_path):
    path = write(tmp_path, 'attachments = "none"\n' + BEAM_TOML)
    error = raises_scene_error(path, "attachments", "'none'")
    assert "array of tables" in str(error)
    path = write(tmp_path, "attachments = [1, 2]\n" + BEAM_TOML)
    error = raises_scene_error(path, "attachments[0]", "1")
    assert "table" in str(error)
    path = write(tmp_path, BEAM_TOML + "[attachments]\nx = 1.0\n")
    raises_scene_error(path, "attachments", "{'x': 1.0}")


def test_inline_array_of_tables_accepted(tmp_path):
    text = 'attachments = [{type = "spring_mass", x = 1, k = 2, m = 3}]\n' + BEAM_TOML
    assert load_scene(write(tmp_path, text)).attachments == (SpringMass(1.0, 2.0, 3.0),)
    assert load_scene(write(tmp_path, "attachments = []\n" + BEAM_TOML)).attachments == ()


@pytest.mark.parametrize(
    ("old", "new", "field", "value"),
    [
        ("length = 2.0", "length = nan", "beam.length", "nan"),
        ("EI = 100.0", "EI = inf", "beam.EI", "inf"),
        ("mass_per_length = 3.0", "mass_per_length = -inf", "beam.mass_per_length", "-inf"),
        ("x = 1", "x = nan", "attachments[0].x", "nan"),
        ("k = 1", "k = +inf", "attachments[0].k", "inf"),
        ("m = 1", "m = -nan", "attachments[0].m", "nan"),
    ],
)
def test_not_finite(tmp_path, old, new, field, value):
    text = good_toml((1, 1, 1)).replace(old, new, 1)
    error = raises_scene_error(write(tmp_path, text), field, value)
    assert "must be finite" in str(error)


@pytest.mark.parametrize(
    ("old", "new", "field", "value"),
    [
        ("length = 2.0", "length = 0.0", "beam.length", "0.0"),
        ("length = 2.0", "length = -2.0", "beam.length", "-2.0"),
        ("EI = 100.0", "EI = 0", "beam.EI", "0"),
        ("mass_per_length = 3.0", "mass_per_length = -3", "beam.mass_per_length", "-3"),
        ("k = 1", "k = 0", "attachments[0].k", "0"),
        ("k = 1", "k = -5e3", "attachments[0].k", "-5000.0"),
        ("m = 1", "m = -0.0", "attachments[0].m", "-0.0"),
        ("m = 1", "m = -1e-300", "attachments[0].m", "-1e-300"),
    ],
)
def test_not_positive(tmp_path, old, new, field, value):
    text = good_toml((1, 1, 1)).replace(old, new, 1)
    error = raises_scene_error(write(tmp_path, text), field, value)
    assert "must be > 0" in str(error)


@pytest.mark.parametrize("x", ["2.0000001", "-0.001", "3", "1e300"])
def test_x_outside_beam(tmp_path, x):
    path = write(tmp_path, good_toml((1, 1, 1), (x, 1, 1)))
    error = raises_scene_error(path, "attachments[1].x", None)
    message = str(error)
    assert "must lie in [0, length]" in message
    assert "2.0" in message  # the length
    assert repr(error.value) in message


def test_unknown_boundary_kind(tmp_path):
    path = write(tmp_path, BEAM_TOML.replace('"free"', '"fixed"'))
    error = raises_scene_error(path, "beam.right", "'fixed'")
    for kind in BOUNDARY_KINDS:
        assert kind in str(error)
    path = write(tmp_path, BEAM_TOML.replace('"clamped"', '"Clamped"'))
    raises_scene_error(path, "beam.left", "'Clamped'")


def test_unknown_attachment_type(tmp_path):
    text = good_toml((1, 1, 1), (1, 1, 1))
    text = text[::-1].replace('"spring_mass"'[::-1], '"damper"'[::-1], 1)[::-1]
    error = raises_scene_error(write(tmp_path, text), "attachments[1].type", "'damper'")
    for kind in ATTACHMENT_TYPES:
        assert kind in str(error)


@pytest.mark.parametrize("name", ["", "a b", "../etc", "x/y", "é", ".", "..", "a\nb", "x" * 129])
def test_bad_name(tmp_path, name):
    text = f"name = {name!r}\n".replace("'", '"') if "\n" not in name else 'name = "a\\nb"\n'
    error = raises_scene_error(write(tmp_path, text + BEAM_TOML), "name", None)
    assert repr(name)[:60] in str(error)


@pytest.mark.parametrize("name", ["a", "wu_chou_1998", "A-b.c_9", "x" * 128])
def test_good_name(tmp_path, name):
    assert load_scene(write(tmp_path, f'name = "{name}"\n' + BEAM_TOML)).name == name


def test_first_error_wins_in_file_order(tmp_path):
    text = good_toml((1, 1, 1), (1, -1, 1), (1, 1, -1))
    raises_scene_error(write(tmp_path, text), "attachments[1].k", "-1")


# ---------------------------------------------------------------------------
# dict interface, round trip, replace


def valid_dict() -> dict:
    return {
        "name": "d",
        "beam": {
            "length": 2,
            "EI": 1e4,
            "mass_per_length": 5.0,
            "left": "pinned",
            "right": "sliding",
        },
        "attachments": [
            {"type": "spring_mass", "x": 1.5, "k": 3.0, "m": 4.0},
            {"type": "spring_mass", "x": 0.5, "k": 1.0, "m": 2.0},
        ],
    }


def test_round_trip_dict():
    scene = scene_from_dict(valid_dict())
    assert scene.source == "<dict>"
    assert [a.x for a in scene.attachments] == [0.5, 1.5]
    data = scene_to_dict(scene)
    assert data == {
        "name": "d",
        "beam": {
            "length": 2.0,
            "EI": 1e4,
            "mass_per_length": 5.0,
            "left": "pinned",
            "right": "sliding",
        },
        "attachments": [
            {"type": "spring_mass", "x": 0.5, "k": 1.0, "m": 2.0},
            {"type": "spring_mass", "x": 1.5, "k": 3.0, "m": 4.0},
        ],
    }
    assert scene_from_dict(data) == scene
    assert scene_to_dict(scene_from_dict(data)) == data


def test_round_trip_files():
    for path in sorted(DATA.glob("*.toml")):
        scene = load_scene(path)
        again = scene_from_dict(scene_to_dict(scene), source=scene.source)
        assert again == scene
        assert again.source == scene.source


def test_dict_errors_use_source():
    data = valid_dict()
    data["beam"]["EI"] = -1.0
    with pytest.raises(SceneError, match=r"^<dict>: beam\.EI: must be > 0 \(got -1\.0\)$"):
        scene_from_dict(data)
    with pytest.raises(SceneError, match=r"^here\.toml: beam\.EI: "):
        scene_from_dict(data, source="here.toml")
    with pytest.raises(SceneError, match=r"^<dict>: -: "):
        scene_from_dict([1, 2])  # type: ignore[arg-type]


def test_dict_default_name():
    data = valid_dict()
    del data["name"]
    assert scene_from_dict(data).name == "scene"
    assert scene_from_dict(data, source="/some/dir/abc.toml").name == "abc"


def test_dict_numeric_types():
    data = valid_dict()
    data["beam"]["length"] = 10**400  # too big for a float
    with pytest.raises(SceneError, match="beam.length: must be finite"):
        scene_from_dict(data)
    data = valid_dict()
    data["attachments"][0]["k"] = None
    with pytest.raises(SceneError, match=r"attachments\[0\]\.k: must be a number \(got None\)"):
        scene_from_dict(data)


def test_scene_is_frozen_and_hashable():
    scene = scene_from_dict(valid_dict())
    with pytest.raises(AttributeError):
        scene.name = "x"  # type: ignore[misc]
    assert hash(scene) == hash(scene_from_dict(valid_dict(), source="elsewhere"))


def test_replace_revalidates():
    scene = scene_from_dict(valid_dict(), source="s.toml")
    new = scene.replace(name="other")
    assert new.name == "other" and new.beam == scene.beam and new.source == "s.toml"
    bigger = scene.replace(beam=Beam(3.0, 1.0, 1.0, "free", "free"))
    assert bigger.beam.length == 3.0
    moved = scene.replace(attachments=[SpringMass(1.9, 1, 1), SpringMass(0.1, 2, 2)])
    assert moved.attachments == (SpringMass(0.1, 2.0, 2.0), SpringMass(1.9, 1.0, 1.0))
    with pytest.raises(SceneError, match=r"^s\.toml: beam\.EI: must be > 0"):
        scene.replace(beam=Beam(2.0, 0.0, 1.0, "free", "free"))
    with pytest.raises(SceneError, match=r"attachments\[1\]\.x: must lie in \[0, length\]"):
        scene.replace(beam=Beam(1.0, 1.0, 1.0, "free", "free"))
    with pytest.raises(SceneError, match=r"^s\.toml: beam\.left: must be one of"):
        scene.replace(beam=Beam(2.0, 1.0, 1.0, "fixed", "free"))
    with pytest.raises(SceneError, match=r"^s\.toml: name: "):
        scene.replace(name="a b")
    with pytest.raises(SceneError, match=r"attachments\[1\]\.m: must be finite"):
        scene.replace(attachments=[SpringMass(0.1, 2, 2), SpringMass(1.9, 1, math.nan)])
    with pytest.raises(TypeError):
        scene.replace(colour="red")


def test_scene_error_parts_and_pickle():
    error = SceneError("f.toml", "beam.EI", "must be > 0", -1.0)
    assert str(error) == "f.toml: beam.EI: must be > 0 (got -1.0)"
    assert isinstance(error, ValueError)
    assert (error.source, error.field, error.problem, error.value) == (
        "f.toml",
        "beam.EI",
        "must be > 0",
        -1.0,
    )
    again = pickle.loads(pickle.dumps(error))
    assert str(again) == str(error) and type(again) is SceneError
    missing = SceneError("f.toml", "beam", "missing")
    assert str(missing) == "f.toml: beam: missing" and not missing.has_value
    assert str(pickle.loads(pickle.dumps(missing))) == str(missing)


def test_long_values_are_shortened():
    data = valid_dict()
    data["beam"]["left"] = "y" * 10_000
    with pytest.raises(SceneError) as info:
        scene_from_dict(data)
    assert len(str(info.value)) < 300


# ---------------------------------------------------------------------------
# Property tests

BC = st.sampled_from(BOUNDARY_KINDS)


def decades(lo: int, hi: int) -> st.SearchStrategy[float]:
    """Positive floats spread over the decades 10**lo .. 10**hi."""
    return st.builds(
        lambda mantissa, exponent: mantissa * 10.0**exponent,
        st.floats(1.0, 9.999),
        st.integers(lo, hi),
    )


@st.composite
def scene_dicts(draw):
    length = draw(decades(-3, 3))
    beam = {
        "length": length,
        "EI": draw(decades(-6, 12)),
        "mass_per_length": draw(decades(-6, 6)),
        "left": draw(BC),
        "right": draw(BC),
    }
    position = st.one_of(st.sampled_from([0.0, 1.0]), st.floats(0.0, 1.0)).map(lambda u: u * length)
    attachments = draw(
        st.lists(
            st.fixed_dictionaries(
                {
                    "type": st.just("spring_mass"),
                    "x": position,
                    "k": decades(-6, 12),
                    "m": decades(-6, 6),
                }
            ),
            max_size=20,
        )
    )
    data = {"beam": beam, "attachments": attachments}
    if draw(st.booleans()):
        data["name"] = draw(
            st.text("abcXYZ019_.-", min_size=1, max_size=20).filter(lambda s: set(s) != {"."})
        )
    return data


@settings(max_examples=200, deadline=None)
@given(scene_dicts())
def test_property_valid_dicts_load_and_round_trip(data):
    scene = scene_from_dict(data)
    assert scene.name == data.get("name", "scene")
    assert scene.beam.length == data["beam"]["length"]
    assert scene.beam.left == data["beam"]["left"]
    xs = [a.x for a in scene.attachments]
    assert xs == sorted(xs)
    assert sorted((a.x, a.k, a.m) for a in scene.attachments) == sorted(
        (d["x"], d["k"], d["m"]) for d in data["attachments"]
    )
    assert all(0.0 <= x <= scene.beam.length for x in xs)
    assert scene_from_dict(scene_to_dict(scene)) == scene
    assert scene_to_dict(scene_from_dict(scene_to_dict(scene))) == scene_to_dict(scene)


BAD_NUMBERS = st.one_of(
    st.sampled_from([math.nan, math.inf, -math.inf, -math.nan]),
    st.floats(max_value=-1e-300, allow_nan=False, allow_infinity=False),
)


@settings(max_examples=300, deadline=None)
@given(scene_dicts(), st.data())
def test_property_one_bad_number_is_named(data, chooser):
    fields = [("beam", key) for key in ("length", "EI", "mass_per_length")]
    fields += [(i, key) for i in range(len(data["attachments"])) for key in ("x", "k", "m")]
    where, key = chooser.draw(st.sampled_from(fields))
    bad = chooser.draw(BAD_NUMBERS)
    if key != "x":  # x = 0 is legal; everything else must also reject zero
        bad = chooser.draw(st.one_of(st.just(bad), st.just(0.0), st.just(0)))
    if where == "beam":
        data["beam"][key] = bad
        field = f"beam.{key}"
    else:
        data["attachments"][where][key] = bad
        field = f"attachments[{where}].{key}"
    with pytest.raises(SceneError) as info:
        scene_from_dict(data, source="prop.toml")
    message = str(info.value)
    assert message.startswith(f"prop.toml: {field}: "), message
    assert len(message.splitlines()) == 1
    assert repr(bad) in message


# ---------------------------------------------------------------------------
# The command line reports scene errors as one line on stderr and exits with 2.
# These run a subprocess; deselect them with -k "not subprocess".


def run_cli_solve(path: Path) -> subprocess.CompletedProcess[str]:
    # Same interpreter, environment and working directory as this test run, so a
    # relative PYTHONPATH (e.g. PYTHONPATH=src) still finds the package.
    return subprocess.run(
        [sys.executable, "-m", "mstmm", "solve", str(path)],
        capture_output=True,
        text=True,
        timeout=300,
    )


CLI_CASES = {
    "malformed": (BEAM_TOML + "k = = 3\n", "-"),
    "missing": (BEAM_TOML.replace("EI = 100.0\n", ""), "beam.EI"),
    "boundary": (BEAM_TOML.replace('"free"', '"fixed"'), "beam.right"),
    "k_not_positive": (good_toml((1, 1, 1), (1, 0, 1)), "attachments[1].k"),
    "x_outside": (good_toml((2.5, 1, 1)), "attachments[0].x"),
    "nan": (good_toml((1, 1, "nan")), "attachments[0].m"),
    "unknown_key": (BEAM_TOML.replace("EI =", "ei ="), "beam.ei"),
}


@pytest.mark.parametrize("case", sorted(CLI_CASES))
def test_cli_subprocess_scene_error(tmp_path, case):
    text, field = CLI_CASES[case]
    path = write(tmp_path, text, f"bad_{case}.toml")
    result = run_cli_solve(path)
    assert result.returncode == 2, result.stderr
    assert result.stdout == ""
    lines = result.stderr.splitlines()
    assert len(lines) == 1, result.stderr
    line = lines[0]
    assert line.strip()
    assert path.name in line
    assert f": {field}: " in line
    with pytest.raises(SceneError) as info:
        load_scene(path)
    assert str(info.value) in line


def test_cli_subprocess_missing_file(tmp_path):
    path = tmp_path / "does_not_exist.toml"
    result = run_cli_solve(path)
    assert result.returncode == 2, result.stderr
    assert result.stdout == ""
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and path.name in lines[0]


# ---------------------------------------------------------------------------
# What float64 arithmetic can carry: finite values the numerics cannot represent are
# rejected like any other bad value, and accepted extremes solve without a warning.

CANTILEVER_BETA = (1.8751040687119611, 4.6940911329741745)  # roots of 1 + cos b cosh b


@pytest.mark.parametrize(
    "beam, field",
    [
        ({"EI": 1e308}, "beam.EI"),
        ({"mass_per_length": 1e-308}, "beam.mass_per_length"),
        ({"length": 5e-324}, "beam.length"),
        ({"EI": 1e200, "mass_per_length": 1e-100}, "beam.EI"),  # EI/mbar = 1e300
        ({"length": 1e-70}, "beam.length"),  # EI/(mbar L^4) = 1e280 * ...
    ],
)
def test_beam_beyond_float64_is_named(beam, field):
    data = {"beam": {"length": 1.0, "EI": 1.0, "mass_per_length": 1.0, **beam}}
    data["beam"] |= {"left": "clamped", "right": "free"}
    with pytest.raises(SceneError) as info:
        scene_from_dict(data, source="big.toml")
    assert info.value.field == field
    assert str(info.value).startswith(f"big.toml: {field}: ")
    assert len(str(info.value).splitlines()) == 1


@pytest.mark.parametrize(
    "k, m, field",
    [
        (5e-324, 1.0, "attachments[0].k"),
        (1.0, 1e-300, "attachments[0].m"),
        (1e200, 1e-100, "attachments[0].k"),  # k/m = 1e300
    ],
)
def test_attachment_beyond_float64_is_named(k, m, field):
    data = {
        "beam": {"length": 1.0, "EI": 1.0, "mass_per_length": 1.0, "left": "clamped"},
        "attachments": [{"type": "spring_mass", "x": 0.5, "k": k, "m": m}],
    }
    data["beam"]["right"] = "free"
    with pytest.raises(SceneError) as info:
        scene_from_dict(data, source="big.toml")
    assert info.value.field == field
    assert info.value.value in (k, m)


def test_accepted_extremes_solve_exactly_without_warnings():
    """EI = 1e100, mbar = 1e-100: omega_n = beta_n^2 sqrt(EI/mbar) / L^2 (closed form)."""
    import warnings

    import mstmm

    scene = scene_from_dict(
        {
            "beam": {
                "length": 2.0,
                "EI": 1e100,
                "mass_per_length": 1e-100,
                "left": "clamped",
                "right": "free",
            }
        }
    )
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        sol = mstmm.solve(scene, modes=2, shapes=False)
    exact = [b**2 * 1e100 / 4.0 for b in CANTILEVER_BETA]
    assert sol.omega == pytest.approx(exact, rel=1e-12)


def test_band_beyond_float64_or_too_wide_is_rejected():
    from mstmm.scene import check_band

    scene = load_scene(DATA / "wu_chou_1998.toml")
    check_band(scene, (0.0, 1e6), "<command line>", "--band")  # about 40 beam modes
    for band in [(1e299, 1e300), (0.0, 1e160), (1.0, 1e20)]:
        with pytest.raises(SceneError) as info:
            check_band(scene, band, "<command line>", "--band")
        assert info.value.field == "--band"


def test_sweep_point_beyond_float64_is_named():
    import mstmm

    scene = load_scene(DATA / "wu_chou_1998.toml")
    with pytest.raises(SceneError) as info:
        mstmm.sweep(scene, {"attachments[1].k": [1e5, 2e5, 5e-324]}, modes=2)
    assert info.value.field == "attachments[1].k"
    assert "at point 2," in str(info.value)


REPRESENTABLE_CASES = {
    "EI": (BEAM_TOML.replace("EI = 100.0", "EI = 1e308"), [], "beam.EI", "1e+308"),
    "mbar": (
        BEAM_TOML.replace("mass_per_length = 3.0", "mass_per_length = 1e-308"),
        [],
        "beam.mass_per_length",
        "1e-308",
    ),
    "k": (good_toml((1, "5e-324", 1)), [], "attachments[0].k", "5e-324"),
    "band": (BEAM_TOML, ["--band", "1e299", "1e300"], "--band", "1e+300"),
}


@pytest.mark.parametrize("case", sorted(REPRESENTABLE_CASES))
def test_cli_subprocess_unrepresentable_is_one_line_no_warning(tmp_path, case):
    """The values of issue 12 item 7b: exit 2, one line, and no warning even under -W error."""
    text, extra, field, value = REPRESENTABLE_CASES[case]
    path = write(tmp_path, text, f"big_{case}.toml")
    result = subprocess.run(
        [sys.executable, "-W", "error", "-m", "mstmm", "solve", str(path), *extra],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert result.returncode == 2, result.stderr
    assert result.stdout == ""
    (line,) = result.stderr.splitlines()
    assert line.startswith("mstmm: error: ")
    assert f": {field}: " in line and value in line, line

"""Finite periodic structures: ``repeat = N`` cells and graded values (mstmm.scene).

A repeated scene is its expanded explicit scene (==, the same parameter vector and
topology, the same frequencies); graded values, every refusal (one line naming the file,
the field and the value; exit status 2 from the command line), and one independent
check: N bare pinned cells are one pinned-pinned beam of length N L.
"""

from __future__ import annotations

import math
import pickle
import subprocess
import sys
import time

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import mstmm
from mstmm.cli import main
from mstmm.scene import REPEAT_MAX, SceneError, load_scene, scene_from_dict, scene_to_dict
from mstmm.topology import parameter_vector, topology_of

EI, MBAR = 63.5, 1.5


def uniform(length: float = 0.1, left: str = "clamped", right: str = "free") -> dict:
    return {"length": length, "EI": EI, "mass_per_length": MBAR, "left": left, "right": right}


def spring_mass(x: float = 0.05, k: object = 2.0e3, m: object = 0.02) -> dict:
    return {"type": "spring_mass", "x": x, "k": k, "m": m}


def expanded(beam: dict, attachments: list[dict], n: int, values=None) -> dict:
    """The explicit scene of ``n`` cells, written out as a user would (cell by cell);
    ``values(j, i, key, raw)`` gives a graded value of cell ``j``."""
    if "segments" in beam:
        cell_length = float(sum(s["length"] for s in beam["segments"]))
        whole = {**beam, "segments": beam["segments"] * n}
    else:
        cell_length = beam["length"]
        whole = {**beam, "length": n * beam["length"]}
    out = []
    for j in range(n):
        for i, a in enumerate(attachments):
            b = dict(a)
            b["x"] = a["x"] + j * cell_length
            for key, raw in a.items():
                if isinstance(raw, dict):
                    b[key] = values(j, i, key, raw)
            out.append(b)
    return {"beam": whole, "attachments": out}


def graded_value(n: int):
    def value(j: int, i: int, key: str, raw: dict) -> float:
        if "each" in raw:
            return float(raw["each"][j])
        first, last = raw["linear"]
        if n == 1:
            return float(first)
        return float(last) if j == n - 1 else first + (last - first) * j / (n - 1)

    return value


def same_scene(repeated, explicit) -> None:
    assert repeated == explicit
    assert np.array_equal(parameter_vector(repeated), parameter_vector(explicit))
    assert topology_of(repeated) == topology_of(explicit)


def toml_value(v: object) -> str:
    if isinstance(v, dict):
        return "{" + ", ".join(f"{k} = {toml_value(w)}" for k, w in v.items()) + "}"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(toml_value(w) for w in v) + "]"
    if isinstance(v, str):
        return f'"{v}"'
    if isinstance(v, bool):
        return "true" if v else "false"
    return repr(v)


def to_toml(data: dict) -> str:
    """A scene dict as TOML (top-level keys, [beam], [[beam.segments]], [[attachments]])."""
    lines = [f"{k} = {toml_value(v)}" for k, v in data.items() if k not in ("beam", "attachments")]
    beam = data.get("beam", {})
    lines.append("[beam]")
    lines += [f"{k} = {toml_value(v)}" for k, v in beam.items() if k != "segments"]
    for s in beam.get("segments", ()):
        lines.append("[[beam.segments]]")
        lines += [f"{k} = {toml_value(v)}" for k, v in s.items()]
    for a in data.get("attachments", ()):
        lines.append("[[attachments]]")
        lines += [f"{k} = {toml_value(v)}" for k, v in a.items()]
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------------------
# The expanded scene


def test_uniform_cell_gives_one_uniform_beam_and_shifted_attachments():
    scene = scene_from_dict({"repeat": 4, "beam": uniform(), "attachments": [spring_mass()]})
    assert scene.beam.segments == ()
    assert scene.beam.length == 4 * 0.1
    assert [a.x for a in scene.attachments] == [0.05 + j * 0.1 for j in range(4)]
    assert scene.repeat == 4 and not scene.graded
    assert scene.cell.beam.length == 0.1 and scene.cell.attachments == scene.attachments[:1]
    same_scene(scene, scene_from_dict(expanded(uniform(), [spring_mass()], 4)))
    other = scene.replace(name="other")  # works on the expanded form
    assert other.name == "other" and other.attachments == scene.attachments
    assert other.cell is None and other.repeat == 1


def test_repeat_one_is_the_scene_without_repeat():
    data = {"beam": uniform(), "attachments": [spring_mass(), spring_mass(0.0)]}
    one = scene_from_dict({"repeat": 1, **data})
    same_scene(one, scene_from_dict(data))
    assert one.repeat == 1 and one.cell == scene_from_dict(data)


def test_stepped_cell_repeats_its_segments():
    beam = {
        "left": "pinned",
        "right": "sliding",
        "segments": [
            {"length": 0.04, "EI": 50.0, "mass_per_length": 1.0},
            {"length": 0.06, "EI": 80.0, "mass_per_length": 2.0, "axial_force": 30.0},
        ],
    }
    attachments = [spring_mass(0.05), {"type": "mass", "x": 0.0, "m": 0.01, "J": 1e-6}]
    scene = scene_from_dict({"repeat": 7, "beam": beam, "attachments": attachments})
    assert len(scene.beam.segments) == 14
    assert scene.beam.segments[2:4] == scene.cell.beam.segments
    same_scene(scene, scene_from_dict(expanded(beam, attachments, 7)))


@pytest.mark.parametrize(
    ("n", "attachments"),
    [
        # cell 1: 0.1 + 0.1 and 2.2e-308 + 0.1 are equal: the file's order decides
        (2, [{"type": "mass", "x": 2.2250738585072014e-308, "m": 1.0}, spring_mass(0.0)]),
        # cell 12's last attachment rounds past cell 13's first
        (14, [spring_mass(0.0), {"type": "mass", "x": math.nextafter(0.1, 0.0), "m": 1.0}]),
    ],
)
def test_rounding_keeps_the_explicit_order(n, attachments):
    repeated = scene_from_dict({"repeat": n, "beam": uniform(), "attachments": attachments})
    same_scene(repeated, scene_from_dict(expanded(uniform(), attachments, n)))


def test_rounding_past_the_right_end_is_refused():
    attachments = [{"type": "mass", "x": math.nextafter(0.1, 0.0), "m": 1.0}]
    with pytest.raises(SceneError) as info:
        scene_from_dict({"repeat": 13, "beam": uniform(), "attachments": attachments})
    assert info.value.field == "attachments[0].x (cell 12)"
    assert "rounded" in str(info.value)


KINDS = st.sampled_from(["spring_mass", "mass", "rotational_spring", "oscillator_chain", "spring"])


@st.composite
def cells(draw):
    """A cell (uniform or stepped) with a few attachments at 0 <= x < cell length, some
    values graded, and a number of cells."""
    n = draw(st.integers(1, 6))
    positive = st.floats(0.5, 2.0)
    if draw(st.booleans()):
        lengths = draw(st.lists(st.sampled_from([0.25, 0.5, 1.0]), min_size=1, max_size=3))
        beam = {
            "left": draw(st.sampled_from(["clamped", "pinned", "free", "sliding"])),
            "right": draw(st.sampled_from(["clamped", "pinned", "free", "sliding"])),
            "segments": [
                {"length": h, "EI": draw(positive), "mass_per_length": draw(positive)}
                for h in lengths
            ],
        }
        cell_length = float(sum(lengths))
    else:
        cell_length = draw(st.sampled_from([0.1, 0.3, 1.0, 2.5]))
        beam = uniform(cell_length, *draw(st.permutations(["clamped", "free"])))
    attachments = []
    for _ in range(draw(st.integers(0, 3))):
        kind = draw(KINDS)
        x = draw(st.floats(0.0, cell_length, exclude_max=True))
        a: dict = {"type": kind, "x": x}
        keys = {
            "spring_mass": ["k", "m"],
            "mass": ["m"],
            "rotational_spring": ["k"],
            "spring": ["k"],
            "oscillator_chain": [],
        }[kind]
        for key in keys:
            how = draw(st.sampled_from(["plain", "linear", "each"]))
            if how == "plain":
                a[key] = draw(positive)
            elif how == "linear":
                a[key] = {"linear": [draw(positive), draw(positive)]}
            else:
                a[key] = {"each": [draw(positive) for _ in range(n)]}
        if kind == "oscillator_chain":
            size = draw(st.integers(1, 3))
            a["k"] = [draw(positive) for _ in range(size)]
            a["m"] = [draw(positive) for _ in range(size)]
        attachments.append(a)
    return n, beam, attachments


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(cells())
def test_repeated_scene_is_the_explicit_scene(cell):
    n, beam, attachments = cell
    repeated = scene_from_dict({"repeat": n, "beam": beam, "attachments": attachments})
    explicit = scene_from_dict(expanded(beam, attachments, n, graded_value(n)))
    same_scene(repeated, explicit)
    assert scene_from_dict(scene_to_dict(repeated)) == repeated
    again = pickle.loads(pickle.dumps(repeated))
    assert again == repeated and again.cell == repeated.cell and again.repeat == n
    assert repeated.graded == any(isinstance(v, dict) for a in attachments for v in a.values())


@pytest.mark.parametrize("n", [3, 10])
def test_frequencies_equal_those_of_the_explicit_scene(n):
    attachments = [spring_mass(0.07, 5.0e3, 0.03)]
    repeated = scene_from_dict({"repeat": n, "beam": uniform(), "attachments": attachments})
    explicit = scene_from_dict(expanded(uniform(), attachments, n))
    assert np.array_equal(parameter_vector(repeated), parameter_vector(explicit))
    a = mstmm.solve(repeated, modes=2 * n + 4, shapes=False)
    b = mstmm.solve(explicit, modes=2 * n + 4, shapes=False)
    assert a.omega.size == 2 * n + 4
    # the same parameters; the kernel may run interpreted once and compiled the other
    # time (mstmm.interpret), which can differ in the last bit
    np.testing.assert_allclose(a.omega, b.omega, rtol=1e-13)


def test_stepped_graded_frequencies_equal_those_of_the_explicit_scene():
    beam = {
        "left": "clamped",
        "right": "pinned",
        "segments": [
            {"length": 0.05, "EI": 60.0, "mass_per_length": 1.4},
            {"length": 0.05, "EI": 90.0, "mass_per_length": 1.8},
        ],
    }
    attachments = [spring_mass(0.02, {"linear": [3e3, 6e3]}, {"each": [0.01, 0.03, 0.02]})]
    repeated = scene_from_dict({"repeat": 3, "beam": beam, "attachments": attachments})
    explicit = scene_from_dict(expanded(beam, attachments, 3, graded_value(3)))
    assert np.array_equal(parameter_vector(repeated), parameter_vector(explicit))
    a = mstmm.solve(repeated, modes=8, shapes=False)
    b = mstmm.solve(explicit, modes=8, shapes=False)
    np.testing.assert_allclose(a.omega, b.omega, rtol=1e-13)


@pytest.mark.parametrize("n", [1, 4, 9])
def test_bare_pinned_cells_are_one_pinned_beam(n):
    """Independent of the expansion: (k pi / (N L))^2 sqrt(EI / mbar), the closed form."""
    cell_length = 0.37
    scene = scene_from_dict({"repeat": n, "beam": uniform(cell_length, "pinned", "pinned")})
    omega = mstmm.solve(scene, modes=12, shapes=False).omega
    exact = [(k * math.pi / (n * cell_length)) ** 2 * math.sqrt(EI / MBAR) for k in range(1, 13)]
    np.testing.assert_allclose(omega, exact, rtol=1e-10)


# ---------------------------------------------------------------------------
# Graded values


def test_linear_and_each_grading():
    n = 5
    data = {
        "repeat": n,
        "beam": uniform(),
        "attachments": [
            spring_mass(0.05, {"linear": [1.0e3, 3.0e3]}, {"each": [0.01, 0.02, 0.03, 0.04, 5]}),
            {"type": "spring_mass", "x": 0.01, "k": 7.0, "m": 1.0, "c": {"linear": [0, 0.5]}},
        ],
    }
    scene = scene_from_dict(data)
    assert scene.graded and topology_of(scene).damped
    assert [a.k for a in scene.attachments[1::2]] == [1e3, 1.5e3, 2e3, 2.5e3, 3e3]
    assert [a.m for a in scene.attachments[1::2]] == [0.01, 0.02, 0.03, 0.04, 5.0]
    assert [a.c for a in scene.attachments[::2]] == [0.0, 0.125, 0.25, 0.375, 0.5]
    # the cell: sorted by x, graded values at cell 0
    assert [(a.x, a.k, a.m) for a in scene.cell.attachments] == [
        (0.01, 7.0, 1.0),
        (0.05, 1e3, 0.01),
    ]
    assert not topology_of(scene.cell).damped  # c is 0 in cell 0 only
    same_scene(
        scene, scene_from_dict(expanded(data["beam"], data["attachments"], n, graded_value(n)))
    )


def test_linear_grading_of_one_cell_is_its_first_value_and_the_last_cell_is_exact():
    one = scene_from_dict(
        {"repeat": 1, "beam": uniform(), "attachments": [spring_mass(k={"linear": [5.0, 9.0]})]}
    )
    assert one.attachments[0].k == 5.0
    many = scene_from_dict(
        {"repeat": 3, "beam": uniform(), "attachments": [spring_mass(k={"linear": [0.1, 0.7]})]}
    )
    assert many.attachments[-1].k == 0.7


# ---------------------------------------------------------------------------
# Refusals: one line naming the file, the field and the value; exit status 2

BAD = [
    # (scene, field, text in the message)
    ({"repeat": 3.0}, "repeat", "3.0"),
    ({"repeat": True}, "repeat", "True"),
    ({"repeat": 0}, "repeat", "(got 0)"),
    ({"repeat": REPEAT_MAX + 1}, "repeat", str(REPEAT_MAX + 1)),
    ({"repeat": "3"}, "repeat", "'3'"),
    ({"repeat": 3, "attachments": [spring_mass(0.1)]}, "attachments[0].x", "next cell"),
    ({"repeat": 3, "attachments": [spring_mass(0.25)]}, "attachments[0].x", "0.25"),
    ({"repeat": 3, "attachments": [spring_mass(-0.01)]}, "attachments[0].x", "-0.01"),
    (
        {"repeat": 3, "attachments": [{"type": "hinge", "x": 0.0}]},
        "attachments[0].x",
        "(0, cell length)",
    ),
    (
        {"repeat": 20, "attachments": [spring_mass(m={"linear": [1.0, -1.0]})]},
        "attachments[0].m (cell 10)",
        "must be > 0",
    ),
    (
        {"repeat": 3, "attachments": [spring_mass(m={"each": [1.0, 2.0, -3.0]})]},
        "attachments[0].m (cell 2)",
        "-3.0",
    ),
    (
        {"repeat": 3, "attachments": [spring_mass(m={"each": [1.0, "a", 3.0]})]},
        "attachments[0].m (cell 1)",
        "'a'",
    ),
    (
        {"repeat": 3, "attachments": [spring_mass(m={"each": [1.0, 2.0]})]},
        "attachments[0].m.each",
        "[1.0, 2.0]",
    ),
    (
        {"repeat": 3, "attachments": [spring_mass(m={"linear": [1.0]})]},
        "attachments[0].m.linear",
        "[1.0]",
    ),
    (
        {"repeat": 3, "attachments": [spring_mass(m={"linear": [1.0, True]})]},
        "attachments[0].m.linear[1]",
        "True",
    ),
    (
        {"repeat": 3, "attachments": [spring_mass(m={"steps": [1.0, 2.0]})]},
        "attachments[0].m.steps",
        "[1.0, 2.0]",
    ),
    (
        {"repeat": 3, "attachments": [spring_mass(m={"linear": [1, 2], "each": [1, 2, 3]})]},
        "attachments[0].m",
        "linear",
    ),
    (
        {"repeat": 3, "attachments": [spring_mass(m={})]},
        "attachments[0].m",
        "{}",
    ),
    (
        {"repeat": 3, "attachments": [spring_mass(x={"linear": [0.01, 0.02]})]},
        "attachments[0].x",
        "linear",
    ),
    (
        {
            "repeat": 3,
            "attachments": [
                {"type": "oscillator_chain", "x": 0.05, "k": {"each": [1, 2, 3]}, "m": [1.0]}
            ],
        },
        "attachments[0].k",
        "list",
    ),
    ({"attachments": [spring_mass(k={"linear": [1.0, 2.0]})]}, "attachments[0].k", "repeat"),
    (
        {"attachments": [{"type": "oscillator_chain", "x": 0.05, "k": {"each": [1]}, "m": [1.0]}]},
        "attachments[0].k",
        "list",
    ),
    # checked on the whole structure, named by cell
    (
        {"repeat": 5, "attachments": [spring_mass(k={"each": [1.0, 2.0, 3.0, 1e260, 5.0]})]},
        "attachments[0].k (cell 3)",
        "1e+260",
    ),
    (
        {
            "repeat": 4,
            "attachments": [
                {"type": "hinge", "x": 0.05},
                {"type": "mass", "x": 0.05, "m": 1.0, "J": {"each": [0, 0, 1e-3, 0]}},
            ],
        },
        "attachments[1].x (cell 2)",
        "hinge attachments[0] (cell 2)",
    ),
    (
        {
            "repeat": 3,
            "beam": uniform(left="pinned"),
            "attachments": [{"type": "support", "x": 0.0}],
        },
        "attachments[0].x (cell 0)",
        "redundant constraint",
    ),
    (
        {"repeat": 10_000, "beam": uniform(length=1e70)},
        "beam.length (times repeat)",
        "length^4",
    ),
]


def _bad_scene(spec: dict) -> dict:
    return {"beam": uniform(), **spec}


@pytest.mark.parametrize(("spec", "field", "text"), BAD, ids=[b[1] for b in BAD])
def test_refusals_name_the_field_and_the_value(tmp_path, capsys, spec, field, text):
    path = tmp_path / "cells.toml"
    path.write_text(to_toml(_bad_scene(spec)), encoding="utf-8")
    with pytest.raises(SceneError) as info:
        load_scene(path)
    message = str(info.value)
    assert len(message.splitlines()) == 1, message
    assert message.startswith(f"{path}: {field}: "), message
    assert info.value.field == field
    assert text in message, message
    assert main(["solve", str(path)]) == 2
    err = [ln for ln in capsys.readouterr().err.splitlines() if ln.strip()]
    assert len(err) == 1 and err[0].startswith(f"mstmm: error: {path}: {field}: "), err


def test_cli_exit_status_2_in_a_fresh_process(tmp_path):
    path = tmp_path / "cells.toml"
    path.write_text(
        to_toml(_bad_scene({"repeat": 3, "attachments": [spring_mass(m={"each": [1.0]})]})),
        encoding="utf-8",
    )
    result = subprocess.run(
        [sys.executable, "-m", "mstmm", "solve", str(path)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert result.returncode == 2
    lines = [ln for ln in result.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and "Traceback" not in result.stderr
    assert "attachments[0].m.each" in lines[0] and str(path) in lines[0]


# ---------------------------------------------------------------------------
# Speed: the cell is validated once and the structure built from it


def test_one_hundred_thousand_cells_load_fast(tmp_path):
    n = 100_000
    path = tmp_path / "big.toml"
    path.write_text(
        to_toml({"repeat": n, "beam": uniform(), "attachments": [spring_mass()]}), encoding="utf-8"
    )
    start = time.perf_counter()
    scene = load_scene(path)
    elapsed = time.perf_counter() - start
    assert len(scene.attachments) == n and scene.attachments[-1].x == 0.05 + (n - 1) * 0.1
    assert elapsed < 5.0  # about 0.1 s; a per-attachment validation would take seconds

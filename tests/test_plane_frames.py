"""Plane frames (issue 43): the frame solver against independent references.

* the mpmath plane-frame model (``tests/reference_frame.py``: exact member dynamic
  stiffness assembled, its own Wittrick-Williams count in 30 digits): each root the
  solver reports is bracketed by that model's count within 1e-12 (relative), with the
  count's jump equal to the reported multiplicity and the count below it equal to the
  roots reported below it (none missed, none spurious);
* NAFEMS FV2's published values (centre held) with its two seven-fold roots;
* today's single-beam solver (``mstmm.solve``): a straight structure of members is the
  beam, with its attachments, segments and segment terms, plus its rod modes (closed form);
* errors that name the field, and the CLI on the bundled example.
"""

from __future__ import annotations

import math
import os
import subprocess
import sys
from pathlib import Path

import mpmath
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from mpmath import mp

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from reference_frame import Frame as RFrame  # noqa: E402
from reference_frame import as_table, count_below, nafems_fv2, sample_frames  # noqa: E402

from mstmm import scene_from_dict, solve  # noqa: E402
from mstmm.frame import frame_from_dict, load_frame, solve_frame  # noqa: E402
from mstmm.frame.assembly import Assembly  # noqa: E402
from mstmm.scene import SceneError  # noqa: E402

EXAMPLES = HERE.parent / "examples"
DPS = 30
#: Relative half-width of the bracket the reference's count must jump across.
BRACKET = 1e-12


def check_against_reference(rf: RFrame, sol, bracket: float = BRACKET) -> None:
    """Every distinct root of ``sol`` is where the reference's count jumps by its
    multiplicity (within ``bracket``, relative), and nothing lies below it but the roots
    reported below it."""
    distinct = []
    for w, m in zip(sol.omega, sol.multiplicity):
        if not distinct or w != distinct[-1][0]:
            distinct.append((w, int(m)))
    below_sum = 0
    with mp.workdps(DPS):
        for w, m in distinct:
            lo = count_below(rf, mpmath.mpf(w) * (1 - bracket), DPS)
            hi = count_below(rf, mpmath.mpf(w) * (1 + bracket), DPS)
            assert (lo, hi) == (below_sum, below_sum + m), (w, m, lo, hi)
            below_sum += m


def _fv2_exact_hz() -> list[float]:
    """FV2 with its centre held, from closed forms (tests/test_reference_frame.py): the
    arms pinned-pinned (b = pi, 2 pi) and clamped-pinned (tan b = tanh b)."""
    E, rho, side, arm = 200e9, 8000.0, 0.125, 5.0
    c = math.sqrt(E * side**4 / 12 / (rho * side * side)) / arm**2 / (2 * math.pi)
    cp = [float(mpmath.findroot(lambda b: mpmath.tan(b) - mpmath.tanh(b), x)) for x in (3.9, 7.07)]
    return [math.pi**2 * c, cp[0] ** 2 * c, (2 * math.pi) ** 2 * c, cp[1] ** 2 * c]


def test_fv2_centre_held_has_the_published_values_and_two_sevenfold_roots():
    sol = solve_frame(frame_from_dict(as_table(nafems_fv2(held_centre=True))), 16)
    distinct = sorted(set(zip(sol.f.tolist(), sol.multiplicity.tolist())))
    assert [m for _, m in distinct] == [1, 7, 1, 7]
    assert [round(f, 3) for f, _ in distinct] == [11.336, 17.709, 45.345, 57.390]
    for (f, _), exact in zip(distinct, _fv2_exact_hz()):
        assert abs(f / exact - 1) < 1e-13
    assert len(sol.modes) == 16
    check_against_reference(nafems_fv2(held_centre=True), sol)


def test_fv2_free_centre_against_the_reference_model():
    """Axially elastic arms, the centre free: five of each seven stay, the two doubles
    fall (17.681 and 57.075 Hz), every multiplicity as the reference counts it."""
    rf = nafems_fv2()
    sol = solve_frame(frame_from_dict(as_table(rf)), 16)
    distinct = sorted(set(zip(sol.f.tolist(), sol.multiplicity.tolist())))
    assert [m for _, m in distinct] == [1, 2, 5, 1, 2, 5]
    assert [round(f, 3) for f, _ in distinct] == [11.336, 17.681, 17.709, 45.345, 57.075, 57.39]
    check_against_reference(rf, sol)


@pytest.mark.parametrize("name", ["L", "portal", "tree", "two_bay_two_storey"])
def test_frames_against_the_reference_model(name):
    rf = sample_frames()[name]
    sol = solve_frame(frame_from_dict(as_table(rf)), 12)
    assert sol.omega.size >= 12
    check_against_reference(rf, sol)


def _mode_residual(sol) -> float:
    """The largest |D x| of a solution's modes, relative to |D| |x| (x the freedom vector
    in D's dimensionless units)."""
    worst = 0.0
    for mode in sol.modes:
        asm = mode.assembly or sol.assembly  # a root on a member's pole: the cut frame's
        D, _ = asm.matrix(mode.omega)
        x = mode.vector / asm.scale
        worst = max(worst, np.linalg.norm(D @ x) / (np.linalg.norm(D, 2) * np.linalg.norm(x)))
    return worst


def test_modes_are_null_vectors_mass_orthonormal_and_continuous_along_members():
    rf = sample_frames()["portal"]
    sol = solve_frame(frame_from_dict(as_table(rf)), 6)
    assert _mode_residual(sol) < 1e-12
    for j, mode in enumerate(sol.modes):
        for member in sol.assembly.members:
            L, c, s = sol.frame.geometry(member.member)
            fields = sol.member_fields(j, member.member.name, 41)
            for end, node in ((0, member.member.start), (-1, member.member.end)):
                X, Y, T = mode.nodes[node]
                scale = max(1e-30, max(abs(v) for v in mode.nodes[node][:2]))
                # the member's ends move with its nodes (the end marched from the start)
                assert abs(fields["u"][end] - (c * X + s * Y)) < 1e-9 * scale + 1e-12
                assert abs(fields["w"][end] - (-s * X + c * Y)) < 1e-7 * scale + 1e-12
                assert abs(fields["psi"][end] - T) < 1e-7 * (abs(T) + scale) + 1e-12
    # unit modal mass: the kinetic energy sum of member integrals and the node mass
    for j, mode in enumerate(sol.modes):
        total = 0.0
        for member in sol.assembly.members:
            f = sol.member_fields(j, member.member.name, 2001)
            mbar = member.member.segments[0].mass_per_length
            total += mbar * np.trapezoid(f["u"] ** 2 + f["w"] ** 2, f["x"])
        X, Y, T = mode.nodes["C"]
        total += 5.0 * (X * X + Y * Y) + 0.7 * T * T
        assert abs(total - 1.0) < 1e-5


def _beam_and_members(beam: dict, attachments: list, cut: float) -> tuple:
    """A clamped-free beam scene and the same structure as two horizontal members meeting
    at x = cut (its attachments along the members)."""
    L = beam["length"]
    beam_scene = scene_from_dict({"beam": {**beam, "left": "clamped", "right": "free"},
                                  "attachments": attachments})  # fmt: skip
    props = {k: v for k, v in beam.items() if k != "length"}
    members, atts = [], []
    for name, start, end, x0, x1 in (("a", "A", "B", 0.0, cut), ("b", "B", "C", cut, L)):
        members.append({"name": name, "start": start, "end": end, "EA": 3e7, **props})
        for a in attachments:
            if x0 < a["x"] < x1:
                atts.append({**a, "member": name, "x": a["x"] - x0})
    table = {
        "nodes": [
            {"name": "A", "x": 0.0, "y": 0.0, "support": "fixed"},
            {"name": "B", "x": cut, "y": 0.0},
            {"name": "C", "x": L, "y": 0.0},
        ],
        "members": members,
        "attachments": atts,
    }
    return beam_scene, frame_from_dict(table)


@pytest.mark.parametrize(
    "beam, attachments",
    [
        ({"length": 2.0, "EI": 3.0e3, "mass_per_length": 4.0}, []),
        (
            {"length": 2.0, "EI": 3.0e3, "mass_per_length": 4.0, "kappa_GA": 2e5, "rho_I": 0.02},
            [{"type": "spring_mass", "x": 1.3, "k": 4e4, "m": 1.5}],
        ),
        (
            {"length": 2.0, "EI": 3.0e3, "mass_per_length": 4.0, "axial_force": 800.0},
            [{"type": "mass", "x": 0.4, "m": 2.0, "J": 0.1}],
        ),
    ],
    ids=["bare", "timoshenko_absorber", "tension_mass"],
)
def test_a_straight_structure_of_members_is_the_beam(beam, attachments):
    """A straight frame of two members has the beam's bending frequencies (today's
    solver) to round-off; its lowest rod frequency (2150 rad/s, EA L^2 / EI = 4e4, a
    slender member's) lies above the five compared."""
    scene, frame = _beam_and_members(beam, attachments, 0.7)
    n = 5
    expected = solve(scene, modes=n, shapes=False).omega
    got = solve_frame(frame, n, shapes=False).omega[:n]
    np.testing.assert_allclose(got, expected, rtol=1e-12)


def test_rod_modes_of_a_collinear_structure_are_the_closed_form():
    """A clamped-free bar of two members along a diagonal: its axial frequencies
    ``(2k - 1) pi c / (2 L)`` among the bending ones, each simple."""
    EA, mbar, L, EI = 2e6, 2.0, 3.0, 1.0e-3  # bending far below: its modes crowd low
    c, s = math.cos(0.6), math.sin(0.6)
    table = {
        "nodes": [
            {"name": "A", "x": 0.0, "y": 0.0, "support": "fixed"},
            {"name": "B", "x": 1.2 * c, "y": 1.2 * s},
            {"name": "C", "x": L * c, "y": L * s},
        ],
        "members": [
            {"start": "A", "end": "B", "EI": EI, "EA": EA, "mass_per_length": mbar},
            {"start": "B", "end": "C", "EI": EI, "EA": EA, "mass_per_length": mbar},
        ],
    }
    frame = frame_from_dict(table)
    wave = math.sqrt(EA / mbar)
    for k in (1, 2):
        w = (2 * k - 1) * math.pi / 2 * wave / L
        sol = solve_frame(frame, band=(w * (1 - 1e-9), w * (1 + 1e-9)), shapes=False)
        assert sol.omega.size == 1 and abs(sol.omega[0] / w - 1) < 1e-12


@pytest.mark.parametrize(
    "change, field, problem",
    [
        (lambda t: t["members"][0].update(end="A"), "members[0].end", "zero length"),
        (lambda t: t["members"][1].update(start="Q"), "members[1].start", "no node"),
        (lambda t: t["nodes"].append({"name": "Z", "x": 9.0, "y": 9.0}), "nodes[3].name",
         "no member reaches"),
        (lambda t: t["members"][0].update(EI=-1.0), "members[0].EI", "> 0"),
        (lambda t: t["nodes"][0].update(support="glued"), "nodes[0].support", "one of"),
        (lambda t: t["members"][0].update(colour="red"), "members[0]", "colour"),
    ],
)  # fmt: skip
def test_bad_frames_name_the_field(change, field, problem):
    _refused(as_table(sample_frames()["L"]), change, field, problem)


def _refused(table: dict, change, field: str, problem: str) -> None:
    """``change`` made to a frame table: one error naming the file, the field, the problem."""
    change(table)
    with pytest.raises(SceneError) as err:
        frame_from_dict(table, "f.toml")
    assert f"f.toml: {field}" in str(err.value) and problem in str(err.value)


def test_a_mechanism_is_refused():
    table = as_table(sample_frames()["L"])
    table["nodes"][0]["support"] = "pinned"  # the L turns about its pinned foot
    with pytest.raises(SceneError, match="mechanism: 1 free rigid motion"):
        solve_frame(frame_from_dict(table, "f.toml"), 3)


def test_cli_solves_the_fv2_example_with_its_multiplicities(tmp_path, capsys):
    out = subprocess.run(
        [sys.executable, "-m", "mstmm", "solve", str(EXAMPLES / "frames" / "nafems_fv2.toml"),
         "--modes", "16", "--format", "csv"],
        capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert out.returncode == 0, out.stderr
    rows = [r.split(",") for r in out.stdout.splitlines()[1:] if r]
    mult = [int(r[3]) for r in rows]
    assert mult == [1, 2, 2, 5, 5, 5, 5, 5, 1, 2, 2, 5, 5, 5, 5, 5]
    frame = load_frame(EXAMPLES / "frames" / "nafems_fv2.toml")
    assert Assembly(frame).count(2 * math.pi * 60.0) == 16
    bad = tmp_path / "bad.toml"
    text = (EXAMPLES / "frames" / "nafems_fv2.toml").read_text()
    bad.write_text(text.replace('end = "P3"', 'end = "P9"'))
    from mstmm.cli import main  # the same entry point, in this process

    assert main(["solve", str(bad)]) == 2
    assert "members[3].end: no node of this name" in capsys.readouterr().err


def test_effective_masses_of_a_column_are_the_beams():
    """A vertical cantilever column (clamped base) with a tip mass and an absorber at
    mid-height: its effective masses along X are the beam solver's (another code path:
    the beam's own shapes), along Y the rod's share only, and their sums approach the
    mass that moves (all of it but nothing at the base)."""
    EI, mbar, L, EA = 4.0e5, 30.0, 6.0, 8.0e9
    beam = scene_from_dict(
        {
            "beam": {"length": L, "EI": EI, "mass_per_length": mbar, "left": "clamped",
                     "right": "free"},
            "attachments": [
                {"type": "mass", "x": L, "m": 50.0},
                {"type": "spring_mass", "x": 2.5, "k": 3.0e4, "m": 8.0},
            ],
        }
    )  # fmt: skip
    frame = frame_from_dict(
        {
            "nodes": [
                {"name": "base", "x": 0.0, "y": 0.0, "support": "fixed"},
                {"name": "top", "x": 0.0, "y": L, "mass": 50.0},
            ],
            "members": [{"name": "col", "start": "base", "end": "top", "EI": EI, "EA": EA,
                         "mass_per_length": mbar}],
            "attachments": [{"type": "spring_mass", "member": "col", "x": 2.5, "k": 3.0e4,
                             "m": 8.0, "direction": [1.0, 0.0]}],
        }
    )  # fmt: skip
    n = 5
    ref = solve(beam, modes=n)
    sol = solve_frame(frame, n)
    np.testing.assert_allclose(sol.omega[:n], ref.omega, rtol=1e-12)
    got = np.array([m.effective_mass[0] for m in sol.modes[:n]])
    expected = np.array([s.effective_mass for s in ref.shapes])
    np.testing.assert_allclose(got, expected, rtol=1e-9, atol=1e-9 * frame.mass)
    assert max(m.effective_mass[1] for m in sol.modes[:n]) < 1e-9 * frame.mass


def _damped_column() -> tuple:
    """``(beam, frame, L)``: a vertical cantilever column carrying a damped absorber 2.5 m
    up, as a beam scene and as a frame (the absorber along X, the member cut there)."""
    EI, mbar, L, EA = 4.0e5, 30.0, 6.0, 8.0e9
    absorber = {"type": "spring_mass", "k": 3.0e4, "m": 8.0, "c": 60.0}
    beam = scene_from_dict(
        {
            "beam": {"length": L, "EI": EI, "mass_per_length": mbar, "left": "clamped",
                     "right": "free"},
            "attachments": [{**absorber, "x": 2.5}],
        }
    )  # fmt: skip
    frame = frame_from_dict(
        {
            "nodes": [
                {"name": "base", "x": 0.0, "y": 0.0, "support": "fixed"},
                {"name": "top", "x": 0.0, "y": L},
            ],
            "members": [{"name": "col", "start": "base", "end": "top", "EI": EI, "EA": EA,
                         "mass_per_length": mbar}],
            "attachments": [{**absorber, "member": "col", "x": 2.5, "direction": [1.0, 0.0]}],
        }
    )  # fmt: skip
    return beam, frame, L


def test_frequency_response_of_a_column_with_a_damped_absorber_is_the_beams():
    """The receptance at the top of a vertical cantilever column carrying a damped
    absorber (force and displacement along X there) equals the mpmath reference model's
    (``reference_model.frf``: a direct solve of the beam's global system) at frequencies
    across the first three modes."""
    from reference_model import frf as reference_frf

    from mstmm.frame import frf

    beam, frame, L = _damped_column()
    omega = np.array([20.0, 31.0, 150.0, 400.0])
    point = ("force", "x", L)
    expected = reference_frf(beam, point, ("displacement", "x", L), omega, dps=20)
    expected = np.array([complex(h) for h in expected])
    got = frf(frame, ("force", "top", (1.0, 0.0)), ("displacement", "top", (1.0, 0.0)), omega)
    np.testing.assert_allclose(got, expected, rtol=1e-9)
    # between points inside the member (cut there; the absorber's cut already splits it)
    inside = [("displacement", "x", L), ("displacement", "x", 4.0)]
    expected = np.array(
        [[complex(h) for h in reference_frf(beam, ("force", "x", 1.0), d, omega, dps=20)]
         for d in inside]
    ).T  # fmt: skip
    X = (1.0, 0.0)
    got = frf(frame, ("force", ("col", 1.0), X),
              [("displacement", "top", X), ("displacement", ("col", 4.0), X)], omega)  # fmt: skip
    np.testing.assert_allclose(got, expected, rtol=1e-9)


def test_damped_roots_of_a_column_with_a_damped_absorber_are_the_beams():
    """The same column's damped natural frequencies (``mstmm.frame.damped``) equal the
    beam's mpmath reference model's (``reference_model.damped_frequencies``, certified by
    its own argument principle); the column's axial roots lie far above."""
    from reference_model import damped_frequencies

    beam, frame, _ = _damped_column()
    expected = np.array([complex(w) for w in damped_frequencies(beam, 4)])
    sol = solve_frame(frame, 4)
    assert sol.count_checked
    np.testing.assert_allclose(sol.omega, expected, rtol=1e-11)


def test_the_building_example_splits_its_first_mode_with_the_roof_damper():
    """examples/frames/building_tmd.toml: the roof damper, tuned by Den Hartog's rule to
    the bare frame's first mode, splits it into two roots on either side, both swaying
    the roof along X; with Den Hartog's dashpot the roof's receptance has two humps near
    them, each lower than the bare frame's response 3 % off its resonance (Den
    Hartog's peak for mu = 0.02 is about sqrt(1 + 2 / mu) = 10 times the static
    response, the bare frame's 3 % off resonance 16 times)."""
    from mstmm.frame import frf

    path = EXAMPLES / "frames" / "building_tmd.toml"
    table = _toml(path)
    frame = load_frame(path)
    bare = frame_from_dict({**table, "attachments": []}, str(path))
    bare_sol = solve_frame(bare, 3)
    f_bare = bare_sol.f
    sol = solve_frame(frame, 4)
    assert sol.f[0] < f_bare[0] < sol.f[1] < f_bare[1]
    assert all(m.effective_mass[0] > 0.1 * frame.mass for m in sol.modes[:2])
    assert sol.multiplicity[:4].tolist() == [1, 1, 1, 1]
    damper = table["attachments"][0]
    roof = damper["node"]
    modal_mass = 1.0 / bare_sol.modes[0].nodes[roof][0] ** 2  # the mode scaled to 1 at the roof
    mu = damper["m"] / modal_mass
    assert 0.01 < mu < 0.05  # as the example's comment says it was chosen
    zeta = math.sqrt(3 * mu / (8 * (1 + mu) ** 3))
    damper["c"] = 2 * zeta * math.sqrt(damper["k"] * damper["m"])
    damped = frame_from_dict(table, str(path))
    push, look = ("force", roof, (1.0, 0.0)), ("displacement", roof, (1.0, 0.0))
    w = 2 * math.pi * f_bare[0] * np.linspace(0.7, 1.3, 241)
    H = np.abs(frf(damped, push, look, w))
    peaks = [j for j in range(1, len(w) - 1) if H[j] >= H[j - 1] and H[j] >= H[j + 1]]
    assert len(peaks) == 2
    assert w[peaks[0]] < 2 * math.pi * f_bare[0] < w[peaks[1]]
    off = np.abs(frf(bare, push, look, [2 * math.pi * 1.03 * f_bare[0]]))
    assert H.max() < off[0]


def test_the_tower_with_a_branch_example_against_the_reference_model(capsys):
    """examples/frames/tower_branch.toml (a tree: mast, branch node, arm with a platform
    mass), through the CLI's default path (shapes on) and the Python call: every root
    where the 30-digit reference model's count jumps, the modes null vectors of D."""
    from reference_frame import Frame as RF
    from reference_frame import Member as RMember

    from mstmm.cli import main

    path = EXAMPLES / "frames" / "tower_branch.toml"
    table = _toml(path)
    rf = RF(
        {n["name"]: (n["x"], n["y"]) for n in table["nodes"]},
        tuple(
            RMember(m["start"], m["end"], m["EI"], m["EA"], m["mass_per_length"])
            for m in table["members"]
        ),
        held={n["name"]: "xyt" for n in table["nodes"] if n.get("support") == "fixed"},
        masses={n["name"]: (n["mass"], n["J"]) for n in table["nodes"] if "mass" in n},
    )
    sol = solve_frame(load_frame(path), 8)
    check_against_reference(rf, sol)
    assert _mode_residual(sol) < 1e-12
    assert main(["solve", str(path), "--modes", "8", "--format", "json"]) == 0
    import json

    shown = json.loads(capsys.readouterr().out)
    np.testing.assert_allclose(shown["omega"], sol.omega, rtol=1e-15)


def test_cli_frf_of_a_frame_between_a_node_and_a_point_inside_a_member(capsys, tmp_path):
    """``mstmm frf`` on the building example: a horizontal force at the roof, responses at
    the roof and at mid-span of the first floor beam (``m3@3``), as JSON: the numbers of
    the Python call (checked against the reference model in the column test above) times
    i omega for mobility; a point off its member or a force without a direction: one line
    naming the option, exit 2, nothing written."""

    from mstmm.cli import main
    from mstmm.frame import frf

    path = EXAMPLES / "frames" / "building_tmd.toml"
    outputs = ["displacement:N10_0=x", "displacement:m3@3=y"]
    shown, got = _cli_frf(capsys, path, "force:N10_0=x", outputs, (1, 5, 9), "mobility")
    w = np.linspace(1.0, 5.0, 9)
    H = frf(load_frame(path), ("force", "N10_0", (1.0, 0.0)),
            [("displacement", "N10_0", (1.0, 0.0)), ("displacement", ("m3", 3.0), (0.0, 1.0))],
            w)  # fmt: skip
    np.testing.assert_allclose(shown["omega"], w)
    np.testing.assert_allclose(got, 1j * w[:, None] * H, rtol=1e-12)
    assert shown["outputs"] == outputs
    out = tmp_path / "h.csv"
    for bad, option in (("force:m3@9=x", "input"), ("force:N10_0", "--input")):
        bad_args = ["frf", str(path), "--input", bad, "--output", "displacement:N10_0=x",
                    "--band", "1", "5", "--out", str(out)]  # fmt: skip
        assert main(bad_args) == 2
        err = capsys.readouterr().err
        assert option in err and len(err.strip().splitlines()) == 1
        assert not out.exists()


def test_cli_sweep_of_a_frame_against_the_reference_model(capsys, tmp_path):
    """``mstmm sweep`` of a frame file: the L-frame's second member's EI over three values,
    each row's frequencies where the reference model of that frame counts them (within
    1e-12); a field the scene lacks and a refused value name the option and the point,
    exit 2, nothing written."""
    import csv
    import io
    import json
    import types
    from dataclasses import replace

    from mstmm.cli import main

    rf = sample_frames()["L"]
    path = tmp_path / "L.toml"
    lines = []
    for array, items in as_table(rf).items():
        for item in items:
            lines.append(f"[[{array}]]")
            lines += [f"{k} = {json.dumps(v)}" for k, v in item.items()]  # TOML's scalars
    path.write_text("\n".join(lines) + "\n")
    vary = "members[1].EI=LIN:1000:4000:3"
    assert main(["sweep", str(path), "--vary", vary, "--modes", "4"]) == 0
    rows = list(csv.reader(io.StringIO(capsys.readouterr().out)))
    assert rows[0] == ["members[1].EI [N m^2]"] + [f"omega_{i} [rad/s]" for i in range(1, 5)]
    assert [float(r[0]) for r in rows[1:]] == [1000.0, 2500.0, 4000.0]
    for r in rows[1:]:
        members = (rf.members[0], replace(rf.members[1], EI=float(r[0])))
        omega = np.array([float(v) for v in r[1:]])
        sol = types.SimpleNamespace(omega=omega, multiplicity=np.ones(4, dtype=int))
        check_against_reference(replace(rf, members=members), sol)
    out = tmp_path / "s.csv"
    for vary, field in (("members[7].EI=1,2", "--vary members[7].EI"),
                        ("members[0].EI=LIN:-1:1:3", "members[0].EI at point 0")):  # fmt: skip
        assert main(["sweep", str(path), "--vary", vary, "--out", str(out)]) == 2
        err = capsys.readouterr().err.strip()
        assert field in err and len(err.splitlines()) == 1, err
        assert not out.exists()


def _cli_frf(capsys, path, load: str, outputs: list, band: tuple, quantity: str):
    """``mstmm frf`` of a frame file as JSON (LO, HI, POINTS in ``band``): what it printed
    and its responses (frequencies x outputs, complex)."""
    import json

    from mstmm.cli import main

    args = ["frf", str(path), "--input", load, "--band", str(band[0]), str(band[1]),
            "--points", str(band[2]), "--format", "json", "--quantity", quantity]  # fmt: skip
    for out in outputs:
        args += ["--output", out]
    assert main(args) == 0
    shown = json.loads(capsys.readouterr().out)
    return shown, (np.array(shown["re"]) + 1j * np.array(shown["im"])).T


def _toml(path) -> dict:
    import tomllib

    with open(path, "rb") as f:
        return tomllib.load(f)


def test_the_mode_shape_plot_draws_the_structure_on_equal_axes(tmp_path):
    """``mstmm plot`` of a frame (the path a user calls): a PNG of its modes; through the
    API each panel is on equal axes, titled with its frequency (and multiplicity), and
    its deformed members end where the joints' displacements put them."""
    from mstmm.cli import main  # mstmm plot, in this process
    from mstmm.frame.plot import AMPLITUDE, mode_shapes

    out = tmp_path / "fv2.png"
    assert (
        main(["plot", str(EXAMPLES / "frames" / "nafems_fv2.toml"), "--modes", "4", "-o", str(out)])
        == 0
    )
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    sol = solve_frame(frame_from_dict(as_table(sample_frames()["portal"])), 3)
    fig = mode_shapes(sol, None, 3)
    panels = [ax for ax in fig.axes if ax.get_title()]
    assert len(panels) == 3
    for j, ax in enumerate(panels):
        assert ax.get_aspect() == 1.0
        assert f"{sol.f[j]:.5g} Hz" in ax.get_title()
        lines = ax.get_lines()
        deformed = [ln for ln in lines if ln.get_color() == "C0"]
        assert len(deformed) == len(sol.frame.members)
        # the portal's beam (member 1, B to C) ends at C displaced by the scaled joint motion
        X, Y = deformed[1].get_xdata()[-1], deformed[1].get_ydata()[-1]
        dX, dY, _ = sol.modes[j].nodes["C"]
        biggest = max(
            float(np.max(np.hypot(*_xy(sol, j, m.member.name)))) for m in sol.assembly.members
        )
        scale = AMPLITUDE * 4.0 / biggest
        assert abs(X - (4.0 + scale * dX)) < 1e-9 and abs(Y - (3.0 + scale * dY)) < 1e-9


def _xy(sol, j: int, member: str) -> tuple:
    """The displacement along X and Y of a member's drawn points in mode j."""
    m = next(mm for mm in sol.assembly.members if mm.member.name == member)
    L, c, s = sol.frame.geometry(m.member)
    f = sol.member_fields(j, member, 21)
    return c * f["u"] - s * f["w"], s * f["u"] + c * f["w"]


def _drawn(default: int):
    """The property tests' settings: ``default`` examples in CI, ``FRAME_EXAMPLES`` more."""
    return settings(
        max_examples=int(os.environ.get("FRAME_EXAMPLES", str(default))),
        deadline=None,
        suppress_health_check=[HealthCheck.too_slow],
    )


def _random_layout(draw) -> tuple[int, dict, list]:
    """3 to 5 nodes on a grid, a random tree of members from node 0 and up to two more
    closing loops: ``(n, nodes, pairs)``."""
    n = draw(st.integers(3, 5))
    points = draw(
        st.lists(st.tuples(st.integers(0, 4), st.integers(0, 4)), min_size=n, max_size=n,
                 unique=True)
    )  # fmt: skip
    nodes = {f"n{i}": (1.5 * x, 1.2 * y) for i, (x, y) in enumerate(points)}
    pairs = [(draw(st.integers(0, i - 1)), i) for i in range(1, n)]
    extra = draw(st.lists(st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)), max_size=2))
    pairs += [(a, b) for a, b in extra if a != b and (a, b) not in pairs and (b, a) not in pairs]
    return n, nodes, pairs


@st.composite
def random_frames(draw) -> RFrame:
    """A random plane frame of 3 to 5 nodes on a grid: a random tree of members from a
    fixed node, up to two more members closing loops, random member properties (EI over
    two decades, EA L^2 / EI from 1e2 to 1e4), pinned member ends (at a node where another
    member stays rigid: the reference gives every node a rotation), a node mass, and a
    second support. Mechanisms are drawn too: the solver must refuse those."""
    from reference_frame import Member as RMember

    n, nodes, pairs = _random_layout(draw)
    rigid = {i: sum(i in pair for pair in pairs) for i in range(n)}
    members = []
    for a, b in pairs:
        EI = draw(st.floats(1e3, 1e5))
        slender = draw(st.floats(1e2, 1e4))
        L = math.dist(nodes[f"n{a}"], nodes[f"n{b}"])
        pinned = []
        for node in (a, b):
            pin = rigid[node] > 1 and draw(st.booleans()) and draw(st.booleans())
            rigid[node] -= pin
            pinned.append(pin)
        mbar = draw(st.floats(1.0, 20.0))
        members.append(RMember(f"n{a}", f"n{b}", EI, slender * EI / L**2, mbar, tuple(pinned)))
    held = {"n0": "xyt"}
    if draw(st.booleans()):
        held[f"n{n - 1}"] = draw(st.sampled_from(["xy", "xyt"]))
    masses = {}
    if draw(st.booleans()):
        masses[f"n{draw(st.integers(1, n - 1))}"] = (draw(st.floats(1.0, 50.0)), 0.0)
    return RFrame(nodes, tuple(members), held, masses)


@_drawn(6)
@given(random_frames())
def test_random_frames_match_the_reference_count(rf):
    """Random frames, trees and loops: every root the solver reports is where the
    30-digit reference model's count jumps by its multiplicity, none missed below the
    last; a mechanism is refused, and the reference agrees that it is one (a root below
    1e-6 rad/s: a rigid motion). Within 1e-10, not the 1e-12 of the frames above: random
    frames meet what costs digits (docs/frames.md, "Accuracy"): a root 1.2e-5 from a
    member's clamped-clamped frequency (1.7e-12 off), a stiff member (3e4 times) moving
    rigidly on a soft one in a low mode (2.3e-11 off)."""
    try:
        sol = solve_frame(frame_from_dict(as_table(rf)), 6, shapes=False)
    except SceneError as exc:
        assert "mechanism" in str(exc)
        with mp.workdps(DPS):
            assert count_below(rf, mpmath.mpf("1e-6"), DPS) > 0
        return
    assert sol.omega.size >= 6
    check_against_reference(rf, sol, 1e-10)


def test_show_prints_the_topology_and_the_overall_equation(capsys):
    """``mstmm show`` of a frame: each member with its transfer direction, the freedoms
    of ``D(omega) q = 0`` (FV2: the centre's X, Y, Theta and each pinned end's Theta) and
    the pattern of D (the centre couples to every arm end, an arm end only to the centre)."""
    from mstmm.cli import main

    assert main(["show", str(EXAMPLES / "frames" / "nafems_fv2.toml")]) == 0
    text = capsys.readouterr().out
    assert "arm2: O -> P2, L = 5 m at 90 deg, joints rigid/rigid" in text
    assert "q (11 freedoms) =" in text
    assert "X(O), Y(O), Theta(O), Theta(P0)" in text
    rows = [line.strip() for line in text.splitlines() if set(line.strip()) <= {"X", "."}]
    rows = [r for r in rows if len(r) == 11]
    assert len(rows) == 11
    assert sorted(r.count("X") for r in rows) == [4] * 8 + [11] * 3


# ---------------------------------------------------------------- out of the plane: grillages


def _grillages() -> dict:
    """An L-grillage (clamped, a corner, a free end with a mass and its rotary inertia),
    a cross of four clamped arms (square symmetry: double roots) and a two-by-two floor
    on its corners (closed loops)."""
    from reference_frame import Member as RMember

    def member(a, b, EI=3.0e3, GJ=1.2e3, mbar=6.0, rhoIp=0.05):
        return RMember(a, b, EI, 0.0, mbar, GJ=GJ, rhoIp=rhoIp)

    out = "out_of_plane"
    return {
        "L": RFrame(
            {"A": (0.0, 0.0), "B": (2.0, 0.0), "C": (2.0, 1.5)},
            (member("A", "B"), member("B", "C", EI=2.0e3, GJ=0.8e3)),
            held={"A": "zab"},
            masses={"C": (4.0, 0.3)},
            motion=out,
        ),  # fmt: skip
        "cross": RFrame(
            {"O": (0.0, 0.0), "E": (2.0, 0.0), "N": (0.0, 2.0), "W": (-2.0, 0.0), "S": (0.0, -2.0)},
            tuple(member("O", k) for k in "ENWS"),
            held={k: "zab" for k in "ENWS"},
            motion=out,
        ),  # fmt: skip
        "floor": RFrame(
            {f"N{i}{j}": (3.0 * j, 2.5 * i) for i in range(3) for j in range(3)},
            tuple(member(f"N{i}{j}", f"N{i}{j + 1}") for i in range(3) for j in range(2))
            + tuple(
                member(f"N{i}{j}", f"N{i + 1}{j}", EI=5.0e3) for i in range(2) for j in range(3)
            ),
            held={f"N{i}{j}": "z" for i in (0, 2) for j in (0, 2)},
            masses={"N11": (30.0, 2.0)},
            motion=out,
        ),  # fmt: skip
    }


@pytest.mark.parametrize("angle", [0.0, 30.0, 135.0])
def test_a_cantilever_out_of_the_plane_is_the_beam_and_the_shaft(angle):
    """Two collinear members clamped at one end, pointing anywhere in the plane, out of
    the plane: the bending roots of ``1 + cos b cosh b = 0`` and the shaft's
    ``(2k - 1) pi / (2 L) sqrt(GJ / rho_Ip)``, each simple (1e-12); the bending modes'
    effective masses along Z are the closed-form shapes' ``mbar (int phi)^2 / int phi^2``
    (mpmath quadrature), the torsion modes' zero."""
    L, EI, mbar, GJ, rIp = 2.0, 3.0e3, 7.0, 1.5e3, 0.02
    c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
    props = {"EI": EI, "GJ": GJ, "rho_Ip": rIp, "mass_per_length": mbar}
    table = {
        "motion": "out_of_plane",
        "nodes": [{"name": "A", "x": 0.0, "y": 0.0, "support": "fixed"},
                  {"name": "B", "x": 0.37 * L * c, "y": 0.37 * L * s},
                  {"name": "C", "x": L * c, "y": L * s}],
        "members": [{"start": "A", "end": "B", **props}, {"start": "B", "end": "C", **props}],
    }  # fmt: skip
    sol = solve_frame(frame_from_dict(table), 8)
    f = lambda b: 1 + mpmath.cos(b) * mpmath.cosh(b)  # noqa: E731
    betas = [mpmath.findroot(f, (k - mpmath.mpf(0.5)) * mpmath.pi) for k in range(1, 9)]
    bending = {float(b * b / L**2) * math.sqrt(EI / mbar): b for b in betas}
    torsion = [(2 * k - 1) * math.pi / (2 * L) * math.sqrt(GJ / rIp) for k in range(1, 9)]
    exact = sorted([*bending, *torsion])[:8]
    np.testing.assert_allclose(sol.omega, exact, rtol=1e-12)
    assert sol.multiplicity.tolist() == [1] * 8
    for mode, w in zip(sol.modes, exact, strict=True):
        if w in bending:
            assert abs(
                mode.effective_mass[0] - _cantilever_effective_mass(bending[w], mbar * L)
            ) < (1e-9 * mbar * L)
        else:
            assert abs(mode.effective_mass[0]) < 1e-12 * mbar * L


def _cantilever_effective_mass(b, mass) -> float:
    """``mass (int phi)^2 / int phi^2`` of a uniform cantilever's mode of root b (its
    closed-form shape, mpmath quadrature over x / L)."""
    sigma = (mpmath.cosh(b) + mpmath.cos(b)) / (mpmath.sinh(b) + mpmath.sin(b))

    def phi(x):
        return (
            mpmath.cosh(b * x)
            - mpmath.cos(b * x)
            - sigma * (mpmath.sinh(b * x) - mpmath.sin(b * x))
        )

    square = mpmath.quad(lambda x: phi(x) ** 2, [0, 1])
    return float(mass * mpmath.quad(phi, [0, 1]) ** 2 / square)


@pytest.mark.parametrize("name", ["L", "cross", "floor"])
def test_grillages_against_the_reference_model(name):
    """Grillages (torsion and bending out of the plane, coupled at every corner through
    the members' angles): every root where the 30-digit reference model's count jumps by
    its multiplicity (1e-12), none missed; the cross's square symmetry gives double
    roots, found as such."""
    rf = _grillages()[name]
    sol = solve_frame(frame_from_dict(as_table(rf)), 10)
    check_against_reference(rf, sol)
    assert _mode_residual(sol) < 1e-12
    if name == "cross":
        assert 2 in sol.multiplicity.tolist()


def test_the_floor_grillage_example_with_its_damper(capsys):
    """examples/frames/floor_grillage.toml, through the CLI's default path: the floor
    without its damper against the reference model; with it, the first mode split on
    either side of the bare floor's (both moving the centre: large effective masses along
    Z), the table's effective masses along Z; the vertical receptance at the centre as
    ``mstmm frf ... force:N11=z`` equals the Python call."""

    from reference_frame import Member as RMember

    from mstmm.cli import main
    from mstmm.frame import frf

    path = EXAMPLES / "frames" / "floor_grillage.toml"
    table = _toml(path)
    rf = RFrame(
        {n["name"]: (n["x"], n["y"]) for n in table["nodes"]},
        tuple(
            RMember(
                m["start"],
                m["end"],
                m["EI"],
                0.0,
                m["mass_per_length"],
                GJ=m["GJ"],
                rhoIp=m["rho_Ip"],
            )
            for m in table["members"]
        ),  # fmt: skip
        held={n["name"]: "z" for n in table["nodes"] if n.get("support") == "pinned"},
        motion="out_of_plane",
    )
    bare = solve_frame(frame_from_dict({**table, "attachments": []}, str(path)), 5)
    check_against_reference(rf, bare)
    assert main(["solve", str(path), "--modes", "4", "--shapes"]) == 0
    text = capsys.readouterr().out
    assert "M_eff,Z (kg)" in text and "sum of effective masses: Z" in text
    sol = solve_frame(load_frame(path), 4)
    assert sol.omega[0] < bare.omega[0] < sol.omega[1] < bare.omega[1]
    assert all(m.effective_mass[0] > 0.2 * sol.frame.mass for m in sol.modes[:2])
    outputs = ["displacement:N11=z", "rotation:m0@3=y"]
    _, got = _cli_frf(capsys, path, "force:N11=z", outputs, (5, 12, 8), "receptance")
    w = np.linspace(5.0, 12.0, 8)
    H = frf(load_frame(path), ("force", "N11", (0.0, 0.0)),
            [("displacement", "N11", (0.0, 0.0)), ("rotation", ("m0", 3.0), (0.0, 1.0))],
            w)  # fmt: skip
    np.testing.assert_allclose(got, H, rtol=1e-12)


@pytest.mark.parametrize(
    "change, field, problem",
    [
        (lambda t: t["members"][0].update(EA=1e9), "members[0].EA", "not used out of the plane"),
        (lambda t: t["members"][0].pop("GJ"), "members[0].GJ", "missing"),
        (lambda t: t["members"][0].update(start_joint="pinned"), "members[0].start_joint",
         "in the plane only"),
        (lambda t: t["nodes"][0].update(support="roller"), "nodes[0].support", "roller"),
        (lambda t: t["nodes"][0].update(k_x=1.0), "nodes[0]", "k_x"),
        (lambda t: t["attachments"][0].update(direction=[1.0, 0.0]), "attachments[0].direction",
         "along Z"),
        (lambda t: t.update(motion="sideways"), "motion", "sideways"),
    ],
)  # fmt: skip
def test_bad_grillages_name_the_field(change, field, problem):
    _refused(_toml(EXAMPLES / "frames" / "floor_grillage.toml"), change, field, problem)


def test_torsion_keys_in_the_plane_say_where_they_belong():
    table = as_table(sample_frames()["L"])
    table["members"][0]["GJ"] = 1.0
    with pytest.raises(SceneError, match=r"members\[0\]\.GJ: torsion is out of the plane"):
        frame_from_dict(table)


def test_show_of_a_grillage_names_its_freedoms_and_its_torsion(capsys):
    """``mstmm show`` of the floor grillage: W, ThetaX, ThetaY freedoms (a pinned corner
    keeps its two rotations), each member's GJ and rho_Ip, the damper along Z, the
    grid's transformation in the overall equation."""
    from mstmm.cli import main

    assert main(["show", str(EXAMPLES / "frames" / "floor_grillage.toml")]) == 0
    text = capsys.readouterr().out
    assert "q (24 freedoms) =" in text
    assert "ThetaX(N00), ThetaY(N00), W(N01)" in text
    assert "GJ 97200, rho_Ip 2.4335" in text and "EA" not in text.split("overall")[0]
    assert "absorber 0: at N11 along Z" in text
    assert "phi = c ThetaX + s ThetaY, w = W, psi = s ThetaX - c ThetaY" in text


@st.composite
def random_grillages(draw) -> RFrame:
    """A random grillage of 3 to 5 nodes on a grid: a random tree of members from a
    clamped node, up to two more members closing loops, random bending and torsion
    (EI over two decades, GJ / EI from 0.05 to 2, rho_Ip / mbar from 1e-3 to 1e-1 m^2), a
    node mass with its rotary inertia, and a second support (pinned or clamped)."""
    from reference_frame import Member as RMember

    n, nodes, pairs = _random_layout(draw)
    members = []
    for a, b in pairs:
        EI = draw(st.floats(1e3, 1e5))
        mbar = draw(st.floats(1.0, 20.0))
        GJ = EI * draw(st.floats(0.05, 2.0))
        rhoIp = mbar * draw(st.floats(1e-3, 1e-1))
        members.append(RMember(f"n{a}", f"n{b}", EI, 0.0, mbar, GJ=GJ, rhoIp=rhoIp))
    held = {"n0": "zab"}
    if draw(st.booleans()):
        held[f"n{n - 1}"] = draw(st.sampled_from(["z", "zab"]))
    masses = {}
    if draw(st.booleans()):
        masses[f"n{draw(st.integers(1, n - 1))}"] = (
            draw(st.floats(1.0, 50.0)), draw(st.floats(0.0, 5.0))
        )  # fmt: skip
    return RFrame(nodes, tuple(members), held, masses, motion="out_of_plane")


@_drawn(4)
@given(random_grillages())
def test_random_grillages_match_the_reference_count(rf):
    """Random grillages, trees and loops out of the plane: every root where the 30-digit
    reference model's count jumps by its multiplicity (1e-10, as for the frames in the
    plane), none missed below the last, the modes null vectors of D."""
    sol = solve_frame(frame_from_dict(as_table(rf)), 6)
    assert sol.omega.size >= 6
    check_against_reference(rf, sol, 1e-10)
    assert _mode_residual(sol) < 1e-10

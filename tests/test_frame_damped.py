"""Damped natural frequencies of frames (``mstmm.frame.damped``) against independent models.

* the mpmath plane-frame model (``tests/reference_frame.py``) at a complex frequency: each
  member's bending stiffness from its exact solutions' energy (``bending_energy``, not the
  closed form the undamped tests use), the rod's closed form, the absorbers' ``k + i w c``;
  each root reported is within 1e-11 of the 30-digit model's root nearest it, and each
  mode is a null vector of the model's dynamic stiffness there;
* the count: a finite-element model of the same frame (``tests/reference_frame_fem.py``,
  8 to 32 elements a member, the quadratic eigenproblem linearised) has as many roots in the
  band and below the counted rectangle's top, each within 1e-3 of one reported;
* (``tests/test_plane_frames.py``) a column carrying a damped absorber is the beam's mpmath
  reference model (``reference_model.damped_frequencies``);
* the CLI on a damped building: the table, the JSON and the exit status.
"""

from __future__ import annotations

import json
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import reference_frame as rf  # noqa: E402
import reference_frame_fem as fem  # noqa: E402

from mstmm.frame import frame_from_dict, solve_frame  # noqa: E402

EXAMPLES = HERE.parent / "examples"
FRAMES = rf.sample_frames()
#: Frames with absorbers (node, k, m, c, direction), the band's top (rad/s, in a gap of
#: the finite-element roots) and the elements a member of the FE model takes: a lightly
#: damped tip absorber; two at the corners of a portal, one of them overdamped (two roots
#: on the imaginary axis); one on the roof of a two-bay frame.
CASES = {
    "L": (replace(FRAMES["L"], absorbers=(("C", 400.0, 2.0, 15.0, (0.0, 1.0)),)), 100.0, 32),
    "portal": (
        replace(
            FRAMES["portal"],
            absorbers=(
                ("C", 2000.0, 3.0, 40.0, (1.0, 0.0)),
                ("B", 500.0, 1.0, 300.0, (0.6, 0.8)),
            ),
        ),
        70.0,
        16,
    ),
    "two_bay": (
        replace(FRAMES["two_bay_two_storey"], absorbers=(("R2", 3000.0, 4.0, 25.0, (1.0, 0.0)),)),
        35.0,
        8,
    ),
}


def _frame(r: rf.Frame, name: str):
    return frame_from_dict(rf.as_table(r), name, name)


def _reference_residual(r: rf.Frame, mode) -> float:
    """``|K(w) x| / (|K(w)| |x|)`` of the 30-digit model at the mode's root, x its joints'
    and absorbers' displacements in the model's freedoms."""
    import mpmath

    index, n = rf._freedoms(r)
    x = np.zeros(n, dtype=complex)
    for key, g in index.items():
        if key[0] == "absorber":
            x[g] = mode.absorbers[key[1]]
        else:
            x[g] = mode.nodes[key[0]][key[1]]
    with mpmath.workdps(30):
        K = rf.dynamic_stiffness(r, mpmath.mpc(mode.omega))[0]
        K = np.array([[complex(K[i, j]) for j in range(n)] for i in range(n)])
    return float(np.linalg.norm(K @ x) / (np.linalg.norm(K, 2) * np.linalg.norm(x)))


@pytest.mark.parametrize("name", sorted(CASES))
def test_damped_frames_against_the_reference_model_and_the_fe_count(name):
    """Every root of the band through the default path (shapes on): to 1e-11 of the
    reference model's, its mode a null vector of the model's D; as many as the
    finite-element model has in the counted rectangle, each FE root near one of them;
    the portal's overdamped absorber gives roots on the imaginary axis (w_d exactly 0)."""
    r, top, elements = CASES[name]
    sol = solve_frame(_frame(r, name), band=(0.0, top))
    assert sol.count_checked and not sol.warnings
    for w in np.unique(sol.omega):
        ref = complex(rf.damped_root(r, w))
        assert abs(ref - w) <= 1e-11 * abs(w), (w, ref)
    for mode in sol.modes:
        assert _reference_residual(r, mode) < 1e-9
    fe = fem.damped_roots(r, elements)
    inside = fe[(fe.real <= top) & (fe.imag < sol.rectangle[3])]
    assert len(inside) == len(sol.omega)
    for w in inside:
        assert np.min(np.abs(sol.omega - w)) <= 1e-3 * abs(w)
    if name == "portal":
        axis = sol.omega[sol.omega.real == 0.0]
        assert len(axis) == 2 and np.all(axis.imag > 0)


def test_a_dashpot_the_proof_does_not_cover_is_said():
    """A dashpot along the only member at its node (the tree's free tip, pushed along X):
    the decay-rate bound does not apply, so the roots are found but the count is not
    called checked, and the warning says why; the roots are still the model's."""
    r = replace(FRAMES["tree"], absorbers=(("D", 300.0, 0.5, 2.0, (1.0, 0.0)),))
    sol = solve_frame(_frame(r, "tree"), 3, shapes=False)
    assert not sol.count_checked
    assert any("no proved bound on the decay rate" in w for w in sol.warnings)
    for w in sol.omega:
        assert abs(complex(rf.damped_root(r, w)) - w) <= 1e-11 * abs(w)


def test_cli_solves_a_damped_building(capsys, tmp_path):
    """``mstmm solve`` on the building example with Den Hartog's dashpot in its roof
    damper: the damper splits the bare frame's first mode into two damped roots on either
    side of it, each with a few percent of damping (the frame's own modes have none), as
    the table and the JSON say alike; exit 0 (the count checked)."""
    from mstmm.cli import main

    path = _damped_building(tmp_path)
    bare = solve_frame(frame_from_dict(_bare(path.read_text())), 2, shapes=False)
    assert main(["solve", str(path), "--modes", "4", "--format", "json"]) == 0
    shown = json.loads(capsys.readouterr().out)
    assert shown["damped"] and shown["count_checked"]
    w_d, zeta = np.array(shown["w_d"]), np.array(shown["zeta"])
    assert w_d[0] < bare.omega[0] < w_d[1] < bare.omega[1]
    assert np.all((zeta[:2] > 0.01) & (zeta[:2] < 0.1)) and np.all(zeta[2:] < 1e-3)
    assert main(["solve", str(path), "--modes", "4"]) == 0
    table = capsys.readouterr().out
    assert "damped natural frequencies" in table and "argument principle checked: True" in table
    assert f"{w_d[0]:.16g}"[:12] in table


def _damped_building(folder: Path) -> Path:
    """The building example with Den Hartog's dashpot (c = 1076 N s/m) in its roof damper,
    written to ``folder``."""
    text = (EXAMPLES / "frames" / "building_tmd.toml").read_text()
    damper = "m = 2441.62848191887    # kg\n"
    assert damper in text
    path = folder / "damped.toml"
    path.write_text(text.replace(damper, damper + "c = 1076.0\n"))
    return path


def _bare(text: str) -> dict:
    """The building's table without its damper."""
    import tomllib

    table = tomllib.loads(text)
    table.pop("attachments")
    return table


def test_a_sweep_of_a_dashpot_is_a_damped_study():
    """``sweep_frame`` varying an absorber's ``c`` returns each point's damped roots
    (complex; the point with c = 0 real), each the reference model's."""
    from mstmm.frame.study import sweep_frame

    r, _, _ = CASES["L"]
    table = rf.as_table(r)
    cs = np.array([0.0, 40.0])
    omega = sweep_frame(table, {"attachments[0].c": cs}, modes=2)
    assert np.iscomplexobj(omega) and omega.shape == (2, 2)
    assert np.all(omega[0].imag == 0.0) and np.all(omega[1].imag > 0.0)
    for c, row in zip(cs, omega):
        point = replace(r, absorbers=((*r.absorbers[0][:3], c, r.absorbers[0][4]),))
        for w in row:
            assert abs(complex(rf.damped_root(point, w)) - w) <= 1e-11 * abs(w)


def test_a_damped_grillage_against_the_reference_model():
    """Out of the plane: an L-grillage (clamped, bending and torsion members) with a damped
    absorber along Z at its free corner: every root of the lowest five to 1e-11 of the
    reference model's (extended out of the plane), the count checked (the dashpot moves
    W, every member's own deflection there)."""
    out = "out_of_plane"
    r = rf.Frame(
        {"A": (0.0, 0.0), "B": (2.0, 0.0), "C": (2.0, 1.5)},
        (
            rf.Member("A", "B", 3.0e3, 0.0, 6.0, GJ=1.2e3, rhoIp=0.05),
            rf.Member("B", "C", 2.0e3, 0.0, 6.0, GJ=0.8e3, rhoIp=0.05),
        ),
        held={"A": "zab"},
        masses={"C": (4.0, 0.3)},
        motion=out,
        absorbers=(("C", 900.0, 1.5, 12.0, (0.0, 0.0)),),
    )
    sol = solve_frame(_frame(r, "grillage"), 5)
    assert sol.count_checked and not sol.warnings
    for w in np.unique(sol.omega):
        assert abs(complex(rf.damped_root(r, w)) - w) <= 1e-11 * abs(w)
    for mode in sol.modes:
        assert _reference_residual(r, mode) < 1e-9


def test_loss_factors_of_members_against_the_reference_model_and_the_fe_count():
    """Members with a loss factor (EI and EA times 1 + i eta), with and without an
    absorber's dashpot: every root of the band (default path, shapes on) within 1e-11 of
    the reference model's (its members complex too), the modes its null vectors, as many
    as the finite-element model's (its K times 1 + i eta) in the counted rectangle. No
    mirror symmetry now: the search's rectangle starts just left of the imaginary axis."""
    lossy = tuple(replace(m, eta=0.02 + 0.01 * j) for j, m in enumerate(FRAMES["L"].members))
    cases = [
        replace(FRAMES["L"], members=lossy),
        replace(FRAMES["L"], members=lossy, absorbers=CASES["L"][0].absorbers),
    ]
    for r in cases:
        sol = solve_frame(_frame(r, "lossy"), band=(0.0, 100.0))
        assert sol.count_checked and not sol.warnings
        for w in np.unique(sol.omega):
            assert abs(complex(rf.damped_root(r, w)) - w) <= 1e-11 * abs(w)
        for mode in sol.modes:
            assert _reference_residual(r, mode) < 1e-9
        fe = fem.damped_roots(r, 32)
        inside = fe[(fe.real <= 100.0) & (fe.imag < sol.rectangle[3])]
        assert len(inside) == len(sol.omega)


def test_frequency_response_of_a_frame_with_loss_factors_is_the_reference_models():
    """The receptance of the lossy L-frame with its tip absorber (force along X at the
    corner, displacement along Y at the tip) equals the reference model's direct solve
    ``K(w)^-1 f`` (30 digits, members complex) to 1e-9 across its first modes."""
    import mpmath

    from mstmm.frame import frf

    lossy = tuple(replace(m, eta=0.03) for m in FRAMES["L"].members)
    r = replace(FRAMES["L"], members=lossy, absorbers=CASES["L"][0].absorbers)
    omega = np.array([3.0, 4.2, 11.0, 60.0])
    got = frf(
        _frame(r, "lossy"), ("force", "B", (1.0, 0.0)), ("displacement", "C", (0.0, 1.0)), omega
    )
    index, n = rf._freedoms(r)
    with mpmath.workdps(30):
        for w, h in zip(omega, got):
            K = rf.dynamic_stiffness(r, w)[0]
            f = mpmath.matrix(n, 1)
            f[index[("B", 0)]] = 1
            x = mpmath.lu_solve(K, f)
            expected = complex(x[index[("C", 1)]])
            assert abs(h - expected) <= 1e-9 * abs(expected)


def test_damped_member_fields_are_the_exact_solutions_between_their_joints():
    """Each member's fields in a damped mode (complex; the lossy L-frame with its tip
    absorber): the deflection, slope and moment are the member's exact bending solution
    (the mpmath model's cos, sin, cosh, sinh at the complex root, EI times 1 + i eta)
    through its joints' displacements, and u the rod's, to 1e-8 of their largest."""
    import mpmath

    lossy = tuple(replace(m, eta=0.02) for m in FRAMES["L"].members)
    r = replace(FRAMES["L"], members=lossy, absorbers=CASES["L"][0].absorbers)
    sol = solve_frame(_frame(r, "lossy"), 3)
    xs = np.linspace(0.0, 1.0, 7)
    for k, mode in enumerate(sol.modes):
        for i, m in enumerate(r.members):
            (xa, ya), (xb, yb) = r.nodes[m.a], r.nodes[m.b]
            L = float(np.hypot(xb - xa, yb - ya))
            c, s = (xb - xa) / L, (yb - ya) / L
            ends = [mode.nodes.get(n, (0j, 0j, 0j)) for n in (m.a, m.b)]
            d = [(c * X + s * Y, -s * X + c * Y, T) for X, Y, T in ends]
            got = sol.member_fields(k, f"m{i}", len(xs))
            with mpmath.workdps(30):
                w = mpmath.mpc(mode.omega)
                EI = m.EI * (1 + 1j * mpmath.mpf(m.eta))
                b = mpmath.root(m.mbar * w * w / EI, 4)
                A = mpmath.matrix([rf._basis(b, q, x) for q, x in ((0, 0), (1, 0), (0, L), (1, L))])
                coef = mpmath.lu_solve(A, mpmath.matrix([d[0][1], d[0][2], d[1][1], d[1][2]]))
                EA = m.EA * (1 + 1j * mpmath.mpf(m.eta))
                kappa = w * mpmath.sqrt(m.mbar / EA)
                for q, key, scale in ((0, "w", 1), (1, "psi", 1), (2, "M", EI)):
                    ref = [
                        complex(scale * sum(g * a for g, a in zip(rf._basis(b, q, x * L), coef)))
                        for x in xs
                    ]
                    big = max(abs(v) for v in ref)
                    assert np.max(np.abs(got[key] - ref)) <= 1e-8 * big, (k, i, key)
                u = [
                    complex(
                        (
                            d[0][0] * mpmath.sin(kappa * (L - x * L))
                            + d[1][0] * mpmath.sin(kappa * x * L)
                        )
                        / mpmath.sin(kappa * L)
                    )
                    for x in xs
                ]
                assert np.max(np.abs(got["u"] - u)) <= 1e-8 * max(abs(v) for v in u), (k, i)


def test_the_plot_draws_damped_modes_at_their_peak(tmp_path):
    """``mstmm plot`` of a damped frame (the building with its dashpot): a PNG; through the
    API (the portal with its absorbers) each panel's title has the damped frequency and
    the damping ratio, and the beam's deformed curve ends where the real part of the
    joint's complex displacement puts it (the mode scaled so that its largest translation
    is real: the instant it peaks)."""
    from mstmm.cli import main
    from mstmm.frame.plot import AMPLITUDE, mode_shapes

    path = _damped_building(tmp_path)
    out = tmp_path / "building.png"
    assert main(["plot", str(path), "--modes", "3", "-o", str(out)]) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    r = CASES["portal"][0]
    sol = solve_frame(_frame(r, "portal"), 3)
    fig = mode_shapes(sol, None, 3)
    panels = [ax for ax in fig.axes if ax.get_title()]
    assert len(panels) == 3
    for j, ax in enumerate(panels):
        assert f"{sol.f[j]:.5g} Hz, zeta {sol.zeta[j]:.3g}" in ax.get_title()
        deformed = [ln for ln in ax.get_lines() if ln.get_color() == "C0"]
        biggest = 0.0
        for m in sol.frame.members:
            L, c, s = sol.frame.geometry(m)
            f = sol.member_fields(j, m.name, 21)
            u, w = f["u"].real, f["w"].real
            biggest = max(biggest, float(np.max(np.hypot(c * u - s * w, s * u + c * w))))
        scale = AMPLITUDE * 4.0 / biggest
        dX, dY, _ = sol.modes[j].nodes["C"]
        X, Y = deformed[1].get_xdata()[-1], deformed[1].get_ydata()[-1]
        assert abs(X - (4.0 + scale * dX.real)) < 1e-9 and abs(Y - (3.0 + scale * dY.real)) < 1e-9

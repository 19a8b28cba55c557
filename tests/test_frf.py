"""Frequency response (issue 14): ``mstmm.frf`` against closed forms and the reference.

* The undamped uniform cantilever's tip receptance in closed form,
  ``H = W(L) / F = (sin bL cosh bL - cos bL sinh bL) / (EI b^3 (1 + cos bL cosh bL))``
  (b^4 = mbar w^2 / EI; checked in ``tests/test_reference_damped.py``), evaluated in
  mpmath at 40 digits: from below the first mode to ``bL = 300`` (the 95th mode), where a
  transfer of the load without orthonormalisation would have lost every digit.
* A damped stepped beam with a point mass and rotary inertia, a spring-dashpot-mass, a
  grounded dashpot and a damped two-stage chain: force, couple and mass loads, displacement,
  rotation and mass responses, at 50 frequencies (real, and a few complex), against the
  reference model's direct solve of its global system (``reference_model.frf``): 1e-10
  relative away from the resonances.
* Reciprocity (hypothesis): ``H(a, b) = H(b, a)`` for force-displacement pairs, and
  ``H_theta,F(a, b) = H_Y,M(b, a)``, on random damped scenes.
* Mobility and accelerance are ``i w H`` and ``-w^2 H``; an undamped scene's receptance is
  real.
* Den Hartog's tuned mass damper (``examples/den_hartog.py``): the two peaks of the tuned
  beam within 3 % of each other and 10 times below the bare beam's.
* The command line: ``mstmm frf`` CSV and JSON, one-line errors with exit status 2,
  ``mstmm plot --frf`` writes an image.
"""

from __future__ import annotations

import csv
import io
import json
import subprocess
import sys
from pathlib import Path

import mpmath
import numpy as np
import pytest
import reference_model as ref
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st
from test_fem_damped import FRF_PAIRS, FRF_SCENE

import mstmm
from mstmm.response import frf

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "examples"))


def rel(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return np.abs(a - b) / np.where(b == 0, 1.0, np.abs(b))


def cantilever_tip(L, EI, mbar, w):
    """The closed form above, 40 digits."""
    with mpmath.workdps(40):
        b = mpmath.sqrt(mpmath.sqrt(mbar * mpmath.mpf(w) ** 2 / EI))
        x = b * L
        num = mpmath.sin(x) * mpmath.cosh(x) - mpmath.cos(x) * mpmath.sinh(x)
        return float(num / (EI * b**3 * (1 + mpmath.cos(x) * mpmath.cosh(x))))


def test_cantilever_tip_receptance_in_closed_form_up_to_the_95th_mode():
    L, EI, mbar = 1.3, 2.1e4, 7.9
    scene = mstmm.scene_from_dict(
        {
            "beam": {"length": L, "EI": EI, "mass_per_length": mbar}
            | {"left": "clamped", "right": "free"},
            "attachments": [],
        }
    )
    unit = np.sqrt(EI / mbar) / L**2
    bL = np.concatenate([np.linspace(0.05, 20.0, 37), np.linspace(280.0, 300.0, 13)])
    bL = bL[np.abs(np.cos(bL) * np.cosh(bL) + 1) > 1e-3 * np.cosh(bL)]  # not at a root
    w = bL**2 * unit
    got = frf(scene, f"force:x={L!r}", f"displacement:x={L!r}", w)
    exact = np.array([cantilever_tip(L, EI, mbar, v) for v in w])
    assert np.abs(got.imag).max() == 0.0  # undamped: real
    assert rel(got.real, exact).max() <= 1e-10, rel(got.real, exact)
    # w -> 0: the static tip flexibility L^3 / (3 EI)
    assert frf(scene, f"force:x={L!r}", f"displacement:x={L!r}", [0.0])[0] == pytest.approx(
        L**3 / (3 * EI), rel=1e-13
    )


FREQUENCIES = [
    *np.linspace(0.5, 3.3, 8),
    *np.linspace(4.2, 11.0, 12),
    *np.linspace(12.6, 14.2, 5),
    *np.linspace(16.0, 21.0, 8),
    *np.linspace(23.5, 26.0, 5),
    *np.linspace(28.5, 60.0, 8),
    6.0 + 2.0j,
    19.0 - 0.5j,
    40.0 + 5.0j,
    2.0 + 0.1j,
]


@pytest.mark.parametrize("pair", FRF_PAIRS, ids=lambda p: f"{p[0][0]}@{p[0][1]}-{p[1][0]}")
def test_damped_receptances_against_the_reference_at_50_frequencies(pair):
    """Resonances of the scene (roots' w_d): 3.67, 11.8, 15.0, 22.1, 27.0 rad/s, avoided."""
    src, dst = pair
    exact = np.array([complex(h) for h in ref.frf(FRF_SCENE, src, dst, FREQUENCIES, dps=25)])
    got = frf(mstmm.scene_from_dict(FRF_SCENE), src, dst, np.asarray(FREQUENCIES))
    assert len(FREQUENCIES) == 50
    assert rel(got, exact).max() <= 1e-10, rel(got, exact)


def test_undamped_twin_against_the_reference():
    from mstmm.damped import undamped_twin

    scene = undamped_twin(mstmm.scene_from_dict(FRF_SCENE))
    sc = mstmm.scene.scene_to_dict(scene)
    w = np.array([1.0, 7.0, 13.0, 33.0])
    for src, dst in FRF_PAIRS:
        exact = np.array([complex(h) for h in ref.frf(sc, src, dst, list(w), dps=25)])
        got = frf(scene, src, dst, w)
        assert np.abs(got.imag).max() == 0.0
        assert rel(got, exact).max() <= 1e-10


def test_mobility_and_accelerance():
    scene = mstmm.scene_from_dict(FRF_SCENE)
    w = np.array([2.0, 9.0, 30.0])
    args = ("force:x=0.55", "displacement:x=0.85", w)
    H = frf(scene, *args)
    assert np.allclose(frf(scene, *args, quantity="mobility"), 1j * w * H, rtol=1e-15)
    assert np.allclose(frf(scene, *args, quantity="accelerance"), -(w**2) * H, rtol=1e-15)


def test_many_inputs_and_outputs_in_one_call():
    scene = mstmm.scene_from_dict(FRF_SCENE)
    w = np.array([2.0, 9.0])
    ins = ["force:x=0.3", "moment:x=0.9", "force:mass=1"]
    outs = ["displacement:x=0.6", "rotation:x=0.2", "displacement:mass=2"]
    H = frf(scene, ins, outs, w)
    assert H.shape == (2, 3, 3)
    for i, a in enumerate(ins):
        for j, b in enumerate(outs):
            # the same up to round-off (the march stops at every output's x)
            assert np.allclose(H[:, i, j], frf(scene, a, b, w), rtol=1e-13, atol=0.0)


#: none, or a value a scene accepts (a subnormal is refused: tests/test_scene.py)
DAMPING = st.one_of(st.just(0.0), st.floats(1e-6, 1.0))
LOSS = st.one_of(st.just(0.0), st.floats(1e-5, 0.1))


@st.composite
def scenes_and_points(draw):
    ends = ("clamped", "pinned", "free", "sliding")
    atts = []
    for _ in range(draw(st.integers(0, 3))):
        x = draw(st.sampled_from([0.0, 0.2, 0.45, 0.7, 1.0]))
        kind = draw(st.sampled_from(["spring_mass", "dashpot", "mass", "spring"]))
        if kind == "spring_mass":
            atts.append(
                {"type": kind, "x": x, "k": draw(st.floats(5.0, 300.0))}
                | {"m": draw(st.floats(0.05, 0.5)), "c": draw(DAMPING)}
            )
        elif kind == "dashpot":
            atts.append({"type": kind, "x": x, "c": draw(st.floats(0.05, 2.0))})
        elif kind == "mass":
            atts.append({"type": kind, "x": x, "m": draw(st.floats(0.05, 0.5))})
        else:
            atts.append({"type": kind, "x": x, "k": draw(st.floats(1.0, 100.0))})
    beam = {"length": 1.0, "EI": 1.0, "mass_per_length": 1.0}
    beam |= {"left": draw(st.sampled_from(ends)), "right": draw(st.sampled_from(ends))}
    if draw(st.booleans()):
        beam["loss_factor"] = draw(LOSS)
    a = draw(st.floats(0.05, 0.95))
    b = draw(st.floats(0.05, 0.95))
    w = draw(st.floats(0.5, 80.0))
    return {"beam": beam, "attachments": atts}, a, b, w


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(scenes_and_points())
@example(  # a cross receptance that vanishes by symmetry: only round-off is left of it
    (
        {
            "beam": {"length": 1.0, "EI": 1.0, "mass_per_length": 1.0}
            | {"left": "clamped", "right": "clamped"},
            "attachments": [],
        },
        0.5,
        0.5,
        1.0,
    )
)
def test_property_reciprocity(case):
    sc, a, b, w = case
    scene = mstmm.scene_from_dict(sc)
    ws = np.array([w, w * (1 + 0.05j)])
    pairs = [
        ((f"force:x={a!r}", f"displacement:x={b!r}"), (f"force:x={b!r}", f"displacement:x={a!r}")),
        ((f"force:x={a!r}", f"rotation:x={b!r}"), (f"moment:x={b!r}", f"displacement:x={a!r}")),
        ((f"moment:x={a!r}", f"rotation:x={b!r}"), (f"moment:x={b!r}", f"rotation:x={a!r}")),
    ]
    dual = {"force": "displacement", "moment": "rotation"}
    dual |= {v: k for k, v in dual.items()}

    def swap(spec: str) -> str:  # "force:x=a" -> "displacement:x=a"
        kind, where = spec.split(":")
        return f"{dual[kind]}:{where}"

    for one, two in pairs:
        h1, h2 = frf(scene, *one, ws), frf(scene, *two, ws)
        # round-off is relative to the point receptances at both places, not to a cross
        # receptance that vanishes (a force and a rotation at a symmetric beam's middle)
        at_in = frf(scene, one[0], swap(one[0]), ws)
        at_out = frf(scene, swap(one[1]), one[1], ws)
        scale = np.maximum(np.maximum(np.abs(h1), np.abs(h2)), np.sqrt(np.abs(at_in * at_out)))
        assert np.all(np.abs(h1 - h2) <= 1e-9 * scale + 1e-300), (one, h1, h2)


def test_den_hartog_equal_peaks_far_below_the_bare_beam():
    import den_hartog

    d = den_hartog.design(0.02)
    w1, x = d["w1"], d["damper"]["x"]
    before = den_hartog.peaks(d["bare"], 0.6 * w1, 1.4 * w1, x, n=1201)
    after = den_hartog.peaks(d["tuned"], 0.6 * w1, 1.4 * w1, x, n=1201)
    assert len(before) == 1 and len(after) == 2
    (w_a, p1), (w_b, p2) = after
    assert abs(p1 / p2 - 1.0) <= 0.03, (p1, p2)
    assert before[0][1] >= 10.0 * max(p1, p2)
    # the classic frequency ratio and damping: the design matches the scene shipped
    shipped = mstmm.load_scene(ROOT / "examples" / "tmd_den_hartog.toml").attachments[0]
    for key in ("m", "k", "c"):
        assert getattr(shipped, key) == pytest.approx(d["damper"][key], rel=1e-9)


def _run(*args, **kw):
    return subprocess.run(
        [sys.executable, "-m", "mstmm", *args], capture_output=True, text=True, **kw
    )


def test_cli_frf_csv_and_json(tmp_path):
    scene = ROOT / "examples" / "tmd_den_hartog.toml"
    common = ["frf", str(scene), "--input", "force:x=5.0", "--band", "5", "15"]
    res = _run(
        *common,
        "--output",
        "displacement:x=5.0",
        "--output",
        "displacement:mass=0",
        "--points",
        "7",
    )
    assert res.returncode == 0, res.stderr
    rows = list(csv.reader(io.StringIO(res.stdout)))
    assert rows[0][:4] == [
        "omega [rad/s]", "f [Hz]", "displacement:x=5.0_re [m/N]", "displacement:x=5.0_im [m/N]"
    ]  # fmt: skip
    assert len(rows) == 8 and len(rows[1]) == 2 + 4 * 2
    sc = mstmm.load_scene(scene)
    w = float(rows[3][0])
    H = frf(sc, "force:x=5.0", "displacement:x=5.0", [w])[0]
    assert complex(float(rows[3][2]), float(rows[3][3])) == pytest.approx(H, rel=1e-15)
    out = tmp_path / "frf.json"
    res = _run(*common, "--output", "rotation:x=2.0", "--format", "json", "--out", str(out))
    assert res.returncode == 0, res.stderr
    data = json.loads(out.read_text())
    assert data["input"] == "force:x=5.0" and len(data["omega"]) == 1000


@pytest.mark.parametrize(
    "args,field",
    [
        (["--input", "push:x=5.0"], "input"),
        (["--input", "force:x=50"], "input"),
        (["--input", "force:mass=3"], "input"),
        (["--input", "force:x=5.0", "--output", "rotation:mass=0"], "output"),
        (["--input", "force:x=5.0", "--output", "rotation:inertia=0"], "output"),
        (["--input", "force:inertia=0"], "input"),
        (["--input", "moment:inertia=1.5"], "input"),
        (["--input", "force"], "input"),
    ],
)
def test_cli_frf_bad_input_is_one_line_exit_2(args, field):
    scene = ROOT / "examples" / "tmd_den_hartog.toml"
    extra = [] if "--output" in args else ["--output", "displacement:x=5.0"]
    res = _run("frf", str(scene), *args, *extra, "--band", "1", "2")
    assert res.returncode == 2, res.stderr
    assert res.stderr.count("\n") == 1 and field in res.stderr and "Traceback" not in res.stderr


def test_cli_plot_frf(tmp_path):
    pytest.importorskip("matplotlib")
    out = tmp_path / "frf.png"
    scene = ROOT / "examples" / "tmd_den_hartog.toml"
    res = _run(
        "plot",
        str(scene),
        "--frf",
        "--input",
        "force:x=5.0",
        "--output",
        "displacement:x=5.0",
        "--band",
        "5",
        "15",
        "--points",
        "300",
        "-o",
        str(out),
    )
    assert res.returncode == 0, res.stderr
    assert out.stat().st_size > 10_000


@pytest.mark.parametrize(
    "attachment",
    [
        {"type": "spring_mass", "x": 0.7, "k": 50.0, "m": 0.3},
        {"type": "spring_mass", "x": 0.7, "k": 50.0, "m": 0.3, "c": 3.0},
        {"type": "oscillator_chain", "x": 0.6, "k": [40.0, 30.0], "m": [0.2, 0.1]},
        {"type": "oscillator_chain", "x": 0.6, "k": [40.0, 30.0], "m": [0.2, 0.1]}
        | {"c": [1.0, 0.5]},
    ],
    ids=["spring_mass", "spring_mass_damped", "chain", "chain_damped"],
)
def test_force_on_a_hanging_mass_against_the_reference(attachment):
    """A force on a hanging mass enters its equation of motion whatever the scale of the
    row its kind's descriptor uses (a spring-mass's row is divided by k): against the
    mpmath reference's (k + i w c - m w^2) u - (k + i w c) W = F, and reciprocal to a force
    on the beam read at the mass. The undamped spring-mass was off by its stiffness."""
    sc = {"beam": {"length": 1.0, "EI": 1.0, "mass_per_length": 1.0}, "attachments": [attachment]}
    sc["beam"] |= {"left": "clamped", "right": "free"}
    scene = mstmm.scene_from_dict(sc)
    w = [2.0, 9.0, 20.0]
    masses = len(attachment["m"]) if isinstance(attachment["m"], list) else 1
    for j in range(masses):
        got = frf(scene, f"force:mass={j}", "displacement:x=0.4", w)
        exact = ref.frf(sc, ("force", "mass", j), ("displacement", "x", 0.4), w, dps=25)
        assert rel(got, np.array([complex(h) for h in exact])).max() <= 1e-12
        dual = frf(scene, "force:x=0.4", f"displacement:mass={j}", w)
        assert rel(got, dual).max() <= 1e-12

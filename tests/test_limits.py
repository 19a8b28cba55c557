"""Issue 41: inputs that ran for minutes (or died of MemoryError / OverflowError) are
refused at once with one line naming the field, the limit and the value (exit 2), from
the command line and from the API alike; and extreme-but-legal segment physics finishes.

Every refusal here happens before any kernel is loaded: the tests run in well under a
second each. The frequencies checked are closed forms (the simply supported beam)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

import mstmm
from mstmm import limits
from mstmm.cli import main
from mstmm.numerics.field import clamped_clamped_bound
from mstmm.scene import LOSS_FACTOR_MAX, PHYSICS_LIMITS, SceneError, scene_from_dict

EI, MU, L = 1e4, 10.0, 1.0
METAMATERIAL = Path(__file__).resolve().parent.parent / "examples" / "metamaterial.toml"


def _beam(**physics) -> dict:
    return {
        "beam": {
            "left": "pinned",
            "right": "pinned",
            "length": L,
            "EI": EI,
            "mass_per_length": MU,
            **physics,
        }
    }


def _write(tmp_path, **physics):
    lines = [
        f"{k} = {v!r}" if isinstance(v, str) else f"{k} = {v:.17g}"
        for k, v in _beam(**physics)["beam"].items()
    ]
    lines = [ln.replace("'", '"') for ln in lines]
    path = tmp_path / "scene.toml"
    path.write_text("[beam]\n" + "\n".join(lines) + "\n")
    return path


def _refused(capsys, argv, *words) -> str:
    assert main(argv) == 2
    err = capsys.readouterr().err
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("mstmm: error: "), err
    for w in words:
        assert w in lines[0], lines[0]
    return lines[0]


@pytest.mark.parametrize(
    "key, value, words",
    [
        ("kappa_GA", 1e300, ["[1e-250, 1e+250]", "1e+300"]),
        ("kappa_GA", 1e-300, ["[1e-250, 1e+250]", "1e-300"]),
        ("kappa_GA", 1e-5, ["kappa_GA length^2/EI is 1e-09", "at least 1e-06"]),
        ("rho_I", 1e300, ["[1e-250, 1e+250]"]),
        ("rho_I", 1e11, ["rho_I/(mass_per_length length^2) is 1e+10", "at most 1e+06"]),
        ("foundation_k", 1e300, ["[1e-250, 1e+250]"]),
        ("foundation_k", 1e25, ["foundation_k length^4/EI is 1e+21", "at most 1e+20"]),
        ("axial_force", 1e300, ["[1e-250, 1e+250]"]),
        ("axial_force", -1e300, ["[1e-250, 1e+250]", "-1e+300"]),
        ("axial_force", 1e17, ["|axial_force| length^2/EI is 1e+13", "at most 1e+12"]),
        ("axial_force", -1e17, ["|axial_force| length^2/EI is 1e+13", "-1e+17"]),
        ("foundation_kG", 1e17, ["foundation_kG length^2/EI is 1e+13"]),
        ("loss_factor", 1e300, ["[1e-250, 1e+250]"]),
        ("loss_factor", 1e5, ["loss_factor is 1e+05", f"at most {LOSS_FACTOR_MAX:g}"]),
    ],
)
def test_segment_keys_refused_at_load(tmp_path, capsys, key, value, words):
    """Each once ran for minutes (or exit 1/3); now exit 2, one line: file, field, value."""
    path = _write(tmp_path, **{key: value})
    _refused(capsys, ["solve", str(path)], str(path), f"beam.{key}", *words)


def test_segment_limits_on_a_stepped_beam_name_the_segment():
    seg = {"length": 0.5, "EI": EI, "mass_per_length": MU}
    data = {
        "beam": {
            "left": "pinned",
            "right": "pinned",
            "segments": [seg, {**seg, "rho_I": 1e9}],
        }
    }
    with pytest.raises(SceneError, match=r"beam\.segments\[1\]\.rho_I: .*at most 1e\+06"):
        scene_from_dict(data)


def test_legal_physics_inside_the_limits_is_read():
    """The limits leave real beams alone: a deep beam, a taut cable, a rail bed, a buckled
    column (reported as buckled by solve, not refused here)."""
    for key, value in (
        ("kappa_GA", 1e-6 * EI / L**2 * 1.01),
        ("rho_I", 0.5 * 1e6 * MU * L**2),
        ("axial_force", 0.99e12 * EI / L**2),
        ("axial_force", -1e8),
        ("foundation_k", 0.99e20 * EI / L**4),
        ("loss_factor", 2.0),
    ):
        scene_from_dict(_beam(**{key: value}))
    assert set(PHYSICS_LIMITS) == {"loss_factor", *(k for k, _, _ in mstmm.catalog.SEGMENT_PHYSICS)}


def _pinned_pinned(n: int) -> float:
    """Euler-Bernoulli closed form, the limit of an infinitely stiff shear."""
    return (n * math.pi / L) ** 2 * math.sqrt(EI / MU)


@pytest.mark.parametrize("kga", [1e32, 1e250])
def test_stiff_shear_finishes_as_euler_bernoulli(kga):
    """kappa_GA 1e28 times EI/L^2 and more used to hang (the piece count of the count
    doubled for ever: k11 k22 - kGA^2 cancelled to 0). Now Euler-Bernoulli's roots."""
    sol = mstmm.solve(scene_from_dict(_beam(kappa_GA=kga)), modes=3, shapes=False)
    for n, w in enumerate(sol.omega, 1):
        assert w == pytest.approx(_pinned_pinned(n), rel=1e-12)


def test_clamped_clamped_bound_with_a_stiff_shear():
    """The bound tends to Euler-Bernoulli's (EI q + tension) q / mbar as kGA grows, and
    stays finite when b^2 would overflow."""
    q = math.pi**2
    eb = clamped_clamped_bound(1.0, math.inf, 0.0, 1.0, 0.0, 1.0)
    assert eb == pytest.approx(q * q, rel=1e-15)
    for kga in (1e20, 1e40, 1e200):
        assert clamped_clamped_bound(1.0, kga, 0.0, 1.0, 0.0, 1.0) == pytest.approx(eb, rel=1e-12)
        with_rho = clamped_clamped_bound(1.0, kga, 1e-3, 1.0, 0.0, 1.0)
        assert 0.0 < with_rho <= eb and math.isfinite(with_rho)


@pytest.mark.parametrize(
    "argv, words",
    [
        (["solve", "--modes", "1000000000"], ["--modes", "at most 100,000 modes"]),
        (["plot", "-o", "x.png", "--modes", "1000000000"], ["--modes", "at most 100,000"]),
        (
            ["sweep", "EXAMPLE", "--vary", "beam.EI=LIN:1e3:1e6:1000000000"],
            ["--vary beam.EI", "at most 1,000,000 points"],
        ),
        (
            ["sweep", "EXAMPLE", "--vary", "beam.EI=LIN:1e3:1e6:3", "--modes", "1000000"],
            ["--modes", "at most 100,000"],
        ),
        (["bands", "CELL", "--points", "1000000000"], ["--points", "at most 1,000,000"]),
        (["bands", "CELL", "--band", "0", "1e200"], ["--band", "float64"]),
        (["bands", "CELL", "--band", "0", "1e30"], ["--band", "at most 1000"]),
        (["bands", "CELL", "--hz", "--band", "0", "1e12"], ["--band", "at most 1000"]),
    ],
)
def test_unbounded_sizes_refused_at_once(capsys, argv, words):
    """These died with MemoryError / OverflowError (exit 1) or ran for minutes."""
    cell = str(METAMATERIAL)
    example = str(mstmm.example_path("wu_chou_1998"))
    argv = [{"CELL": cell, "EXAMPLE": example}.get(a, a) for a in argv]
    _refused(capsys, argv, "<command line>", *words)


def test_api_refuses_the_same_sizes():
    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    cell = mstmm.load_scene(METAMATERIAL)
    with pytest.raises(ValueError, match="modes: at most 100,000 modes"):
        mstmm.solve(scene, modes=10**9)
    with pytest.raises(ValueError, match="points: at most 1,000,000"):
        mstmm.bands(cell, points=10**9)
    with pytest.raises(ValueError, match="band: the band spans .* at most 1000"):
        mstmm.bands(cell, band=(0.0, 1e30))
    with pytest.raises(ValueError, match="band: HI is beyond what float64"):
        mstmm.bands(cell, band=(0.0, 1e200))
    with pytest.raises(ValueError, match="modes: at most 100,000"):
        mstmm.sweep(scene, {"beam.EI": [1.0, 2.0]}, modes=10**6)
    assert limits.MAX_SWEEP_POINTS < 10**9

"""Redundant constraints and springs where the motion is already fixed (issue 20, item 18).

One rule, in README's "What a scene may not do": a constraint (a ``support``) where Y
is already fixed (a clamped or pinned end, another support at the same x) is refused,
always with the same message ("a redundant constraint"), because the damped chain is
singular there; a spring (translational or rotational) where the motion it resists is
already fixed is no constraint: accepted, it changes nothing, damped or not. Checked
against the closed form of the clamped-pinned beam, tan b = tanh b.
"""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest

import mstmm

BEAM = """
[beam]
length = 2.0
EI = 3.0
mass_per_length = 1.5
left = "{left}"
right = "{right}"
"""


def _att(kind: str, **keys) -> str:
    body = "".join(f"{k} = {v}\n" for k, v in keys.items())
    return f'[[attachments]]\ntype = "{kind}"\n{body}'


def _clamped_pinned(n: int) -> np.ndarray:
    """omega of the clamped-pinned beam: roots b of tan b = tanh b, (b/L)^2 sqrt(EI/mbar)."""
    out = []
    for j in range(1, n + 1):
        lo, hi = j * math.pi, j * math.pi + 0.5 * math.pi - 1e-9
        f = lambda b: math.sin(b) * math.cosh(b) - math.cos(b) * math.sinh(b)  # noqa: E731
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            lo, hi = (lo, mid) if f(lo) * f(mid) <= 0 else (mid, hi)
        out.append((0.5 * (lo + hi) / 2.0) ** 2 * math.sqrt(3.0 / 1.5))
    return np.array(out)


@pytest.mark.parametrize(
    "left,right,extra",
    [
        ("clamped", "free", _att("support", x=0.0)),
        ("pinned", "free", _att("support", x=0.0)),
        ("free", "clamped", _att("support", x=2.0)),
        ("free", "free", _att("support", x=0.7) + _att("support", x=0.7)),
        (
            "free",
            "free",
            _att("support", x=0.7) + _att("spring", x=1.0, k=5.0) + _att("support", x=0.7),
        ),
    ],
)
def test_every_redundant_constraint_is_refused_with_one_message(tmp_path, left, right, extra):
    path = tmp_path / "s.toml"
    path.write_text(BEAM.format(left=left, right=right) + extra)
    run = subprocess.run(
        [sys.executable, "-m", "mstmm", "solve", str(path)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert run.returncode == 2 and not run.stdout
    (line,) = run.stderr.splitlines()
    assert line.startswith(f"mstmm: error: {path}: attachments[")
    assert "already fixes Y is a redundant constraint" in line and "leave it out" in line


def test_springs_where_the_motion_is_fixed_change_nothing(tmp_path):
    """A rotational spring at the clamped end, springs at both ends of a clamped-pinned
    beam: its closed-form frequencies, count checked; damped (a dashpot inside), the roots
    of the same damped scene without the springs."""
    springs = (
        _att("rotational_spring", x=0.0, k=1.0e3)
        + _att("spring", x=0.0, k=1.0e3)
        + _att("spring", x=2.0, k=7.0)
    )
    path = tmp_path / "cp.toml"
    path.write_text(BEAM.format(left="clamped", right="pinned") + springs)
    sol = mstmm.solve(mstmm.load_scene(path), modes=5)
    assert sol.count_checked
    np.testing.assert_allclose(sol.omega, _clamped_pinned(5), rtol=1e-12)

    dashpot = _att("dashpot", x=0.5, c=0.8)
    path.write_text(BEAM.format(left="clamped", right="pinned") + springs + dashpot)
    damped = mstmm.solve(mstmm.load_scene(path), modes=4, shapes=False)
    path.write_text(BEAM.format(left="clamped", right="pinned") + dashpot)
    plain = mstmm.solve(mstmm.load_scene(path), modes=4, shapes=False)
    assert damped.count_checked and plain.count_checked
    np.testing.assert_allclose(damped.omega, plain.omega, rtol=1e-10)
    assert np.all(damped.sigma > 0.0)

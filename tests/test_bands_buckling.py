"""Issue 41: ``bands`` on a cell far beyond buckling said "0 stop band(s)", exit 0; now it
says "buckled" and exits 3, as ``solve`` does on the finite structure.

The reference is closed-form: an infinite uniform beam on a Winkler foundation under a
compression P has omega^2 mbar = EI q^4 - P q^2 + k_w for every wavenumber q, so it is
stable iff P < 2 sqrt(EI k_w), the least being at q = (k_w / EI)^(1/4)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

import mstmm
from mstmm.bands import BUCKLING_PHASES
from mstmm.cli import main
from mstmm.scene import scene_from_dict

EI, MU, L = 1.0, 1.0, 1.0
#: q_c L = pi / 2: a wave the test sees (BUCKLING_PHASES is a multiple of 2).
K_W = EI * (math.pi / (2 * L)) ** 4
P_CRITICAL = 2.0 * math.sqrt(EI * K_W)
METAMATERIAL = Path(__file__).resolve().parent.parent / "examples" / "metamaterial.toml"


def _cell(factor: float):
    beam = {"left": "free", "right": "free", "length": L, "EI": EI, "mass_per_length": MU}
    beam |= {"foundation_k": K_W, "axial_force": -factor * P_CRITICAL}
    return scene_from_dict({"name": "founded", "beam": beam})


def test_founded_beam_buckles_at_its_closed_form_load():
    assert BUCKLING_PHASES % 2 == 0
    below = mstmm.bands(_cell(0.9), points=50)
    assert below.buckling is None and below.count_checked
    above = mstmm.bands(_cell(1.1), points=50)
    assert above.buckling is not None and above.buckling.startswith("buckled:")
    # the shortest unstable wave tried: the largest sampled q with EI q^4 - P q^2 + k_w < 0
    P = 1.1 * P_CRITICAL
    q = max(
        math.pi * j / (BUCKLING_PHASES * L)
        for j in range(1, BUCKLING_PHASES + 1)
        if EI * (math.pi * j / (BUCKLING_PHASES * L)) ** 4
        - P * (math.pi * j / (BUCKLING_PHASES * L)) ** 2
        + K_W
        < 0.0
    )
    assert f"(at k L = {q * L:.4g}, 1 buckling mode(s) exceeded)" in above.buckling
    assert not above.count_checked and not above.edges


def test_bands_cli_says_buckled_and_exits_3(tmp_path, capsys):
    text = METAMATERIAL.read_text().replace(
        "mass_per_length = 0.108", "mass_per_length = 0.108\naxial_force = -1e6"
    )
    path = tmp_path / "buckled.toml"
    path.write_text(text)
    assert main(["bands", str(path)]) == 3
    out = capsys.readouterr().out.strip().splitlines()
    # P L^2 / EI = 107 > (3 pi)^2: the waves of k L = pi and 3 pi (cos and sin each)
    assert out == [
        "metamaterial: buckled: the axial forces exceed the buckling load of the periodic"
        " structure (at k L = 3.142, 4 buckling mode(s) exceeded); it has no dispersion"
        " about an unstable equilibrium"
    ]
    assert 1e6 * 0.01**2 / (0.9333333333333333 * math.pi**2) == pytest.approx(10.86, rel=1e-3)

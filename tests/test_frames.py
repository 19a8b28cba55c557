"""A solution's short ``repr`` and ``to_dataframe()`` (issue 41, "What an engineer misses").

Numbers against the closed form of a pinned-pinned uniform beam: omega_n =
(n pi / L)^2 sqrt(EI / mbar), shapes sin(n pi x / L) (sign free, see
tests/test_csv_units.py). pandas is in the ``test`` extra.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

import mstmm

L, EI, MBAR = 2.0, 3.0, 1.5
EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


@pytest.fixture(scope="module")
def pinned():
    scene = mstmm.scene_from_dict(
        {
            "name": "pp",
            "beam": {
                "length": L,
                "EI": EI,
                "mass_per_length": MBAR,
                "left": "pinned",
                "right": "pinned",
            },
        }
    )
    return mstmm.solve(scene, modes=40)


def _omega(n: int) -> float:
    return (n * math.pi / L) ** 2 * math.sqrt(EI / MBAR)


def test_repr_is_one_short_line(pinned):
    text = repr(pinned)
    assert "\n" not in text and len(text) < 200, text
    assert text.startswith("Solution('pp': 40 natural frequencies [rad/s]: ")
    assert f"{_omega(1):.6g}, {_omega(2):.6g}" in text and f"{_omega(40):.6g}" in text
    assert "count checked" in text and "40 mode shapes" in text
    assert "array(" not in text and "Scene(" not in text


def test_repr_of_a_damped_solution():
    sol = mstmm.solve(mstmm.load_scene(EXAMPLES / "tmd_den_hartog.toml"), modes=2)
    text = repr(sol)
    assert text.startswith("DampedSolution('tmd_den_hartog': 2 damped natural frequencies")
    assert "\n" not in text and len(text) < 200, text


def test_to_dataframe_one_row_per_mode(pinned):
    pytest.importorskip("pandas")  # in the test extra; a user's install may lack it
    frame = pinned.to_dataframe()
    assert list(frame.index) == list(range(1, 41)) and frame.index.name == "mode"
    exact = np.array([_omega(n) for n in range(1, 41)])
    np.testing.assert_allclose(frame["omega"], exact, rtol=1e-12)
    np.testing.assert_allclose(frame["f"], exact / (2.0 * math.pi), rtol=1e-12)
    # a pinned-pinned mode sin(k x) scaled to 1 m: modal mass mbar L / 2 (the lowest
    # modes: the quadrature over the 201 samples reads 1.5059 at mode 8, 1.658 at mode 40)
    np.testing.assert_allclose(frame["modal_mass"][:5], MBAR * L / 2.0, rtol=1e-10)
    assert frame.attrs["units"]["omega"] == "rad/s"
    assert frame.attrs["units"]["modal_mass"] == "kg m^2"


def test_to_dataframe_shapes_in_long_form(pinned):
    pytest.importorskip("pandas")
    frame = pinned.to_dataframe(shapes=True)
    assert list(frame.columns) == ["mode", "x", "Y", "theta", "M", "Q"]
    for n in (1, 3):
        rows = frame[frame["mode"] == n]
        k = n * math.pi / L
        exact = np.sin(k * rows["x"].to_numpy())
        sign = math.copysign(1.0, float(np.dot(rows["Y"], exact)))
        np.testing.assert_allclose(rows["Y"], sign * exact, atol=1e-12)
        np.testing.assert_allclose(rows["M"], -sign * EI * k * k * exact, atol=1e-10 * EI * k * k)
    assert frame.attrs["units"]["Q"] == "N"


def test_to_dataframe_without_pandas_says_how_to_install_it(pinned, monkeypatch):
    monkeypatch.setitem(sys.modules, "pandas", None)  # import pandas raises ImportError
    with pytest.raises(ImportError, match="pip install pandas"):
        pinned.to_dataframe()

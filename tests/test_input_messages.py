"""Issue 41: a mistyped scene key is answered with the key meant, and ``bands --plot``
refuses an image format it cannot write before any work (as ``plot -o`` does)."""

from __future__ import annotations

import time
from pathlib import Path

import pytest

from mstmm.cli import main
from mstmm.scene import SceneError, scene_from_dict

METAMATERIAL = Path(__file__).resolve().parent.parent / "examples" / "metamaterial.toml"
BEAM = {"left": "pinned", "right": "pinned", "length": 1.0, "EI": 1.0, "mass_per_length": 1.0}


@pytest.mark.parametrize(
    "table, key, meant",
    [
        ("beam", "kappa_ga", "kappa_GA"),
        ("beam", "kapa_GA", "kappa_GA"),
        ("beam", "mass_per_lenght", "mass_per_length"),
        ("beam", "axial_forces", "axial_force"),
        ("attachment", "tpye", "type"),
        ("top", "atachments", "attachments"),
    ],
)
def test_mistyped_key_names_the_key_meant(table, key, meant):
    data: dict = {"beam": dict(BEAM)}
    attachment = {"type": "spring_mass", "x": 0.5, "k": 1.0, "m": 1.0}
    if table == "beam":
        data["beam"][key] = 1.0
    elif table == "attachment":
        data["attachments"] = [{**attachment, key: "spring_mass"}]
    else:
        data[key] = [attachment]
    with pytest.raises(SceneError) as info:
        scene_from_dict(data, source="s.toml")
    message = str(info.value)
    assert f"unknown key; did you mean {meant!r}? (allowed: " in message, message
    assert "\n" not in message


def test_an_unrelated_key_gets_no_guess():
    with pytest.raises(SceneError) as info:
        scene_from_dict({"beam": {**BEAM, "density": 7800.0}}, source="s.toml")
    assert "did you mean" not in str(info.value)
    assert "unknown key (allowed: " in str(info.value)


def test_bands_plot_refuses_an_unknown_format_at_once(tmp_path, capsys):
    """It computed the whole dispersion (22 s) and then died with ValueError (exit 1)."""
    pytest.importorskip("matplotlib")
    t0 = time.perf_counter()
    status = main(["bands", str(METAMATERIAL), "--plot", str(tmp_path / "d.xyz")])
    err = capsys.readouterr().err.strip().splitlines()
    assert status == 2 and len(err) == 1, err
    assert err[0].startswith("mstmm: error: <command line>: --plot: unknown image format")
    assert "d.xyz" in err[0]
    assert time.perf_counter() - t0 < 10.0
    assert not (tmp_path / "d.xyz").exists()

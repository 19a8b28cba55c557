"""Issue 41: ``mstmm show`` with 100 spring-masses took 33 s and with 1,000 past 300 s; the
README says "in seconds for any number of attachments". The structure it prints (the
chain, Z_all, Z_bar, U_bar's zero pattern) is now carried on booleans
(``mstmm.structure.structure_of``), which must agree with the SymPy derivation's
(``symbolic(scene, evaluate=False)``, itself compared with the evaluated derivation in
tests/test_cli.py) for every kind."""

from __future__ import annotations

import time

import pytest

import mstmm
from mstmm.cli import main

pytest.importorskip("sympy")

from mstmm.derive import symbolic  # noqa: E402

from mstmm.structure import structure_of  # noqa: E402

EVERY_KIND = [
    {"type": "spring_mass", "x": 0.1, "k": 1.0, "m": 1.0},
    {"type": "spring_mass", "x": 0.15, "k": 1.0, "m": 1.0, "c": 0.2},
    {"type": "mass", "x": 0.2, "m": 1.0},
    {"type": "spring", "x": 0.3, "k": 1.0},
    {"type": "rotational_spring", "x": 0.4, "k": 1.0},
    {"type": "hinge", "x": 0.5, "k": 2.0},
    {"type": "support", "x": 0.6},
    {"type": "dashpot", "x": 0.7, "c": 0.5},
    {"type": "oscillator_chain", "x": 0.8, "k": [1.0, 2.0, 3.0], "m": [1.0, 1.0, 2.0]},
]


def _scene(attachments, left="clamped", right="free", **beam):
    base = {"length": 1.0, "EI": 1.0, "mass_per_length": 1.0, "left": left, "right": right}
    return mstmm.scene_from_dict({"beam": base | beam, "attachments": attachments})


@pytest.mark.parametrize(
    "scene",
    [
        _scene([]),
        _scene(EVERY_KIND),
        _scene(EVERY_KIND, "free", "sliding"),
        _scene(EVERY_KIND[:3], "pinned", "pinned", kappa_GA=10.0, rho_I=0.01),
        _scene([{**a, "x": 0.05 * (i + 1)} for i, a in enumerate(EVERY_KIND * 2)]),
    ],
    ids=["bare", "every_kind", "free_sliding", "timoshenko", "twice"],
)
def test_structure_is_that_of_the_symbolic_derivation(scene):
    fast, slow = structure_of(scene), symbolic(scene, evaluate=False)
    assert list(fast.Z_all) == [str(z) for z in slow.Z_all]
    assert list(fast.Z_bar) == [str(z) for z in slow.Z_bar]
    assert list(fast.chain) == slow.chain()
    assert fast.sparsity() == slow.sparsity()


def test_show_a_thousand_spring_masses_in_seconds(tmp_path, capsys):
    n = 1000
    text = '[beam]\nlength = 1.0\nEI = 1.0\nmass_per_length = 1.0\nleft = "pinned"\n'
    text += 'right = "pinned"\n'
    for i in range(n):
        text += (
            f'[[attachments]]\ntype = "spring_mass"\nx = {(i + 1) / (n + 1)!r}\nk = 1.0\nm = 1.0\n'
        )
    path = tmp_path / "many.toml"
    path.write_text(text)
    t0 = time.perf_counter()
    assert main(["show", str(path)]) == 0
    seconds = time.perf_counter() - t0
    out = capsys.readouterr().out
    assert f"U_bar: {n + 4}x{n + 4}," in out  # 4 + n + 4 states, half known at the ends
    assert "(the pattern is drawn up to 60x60)" in out
    assert max(len(line) for line in out.splitlines() if str(path) not in line) < 200
    assert seconds < 60.0  # about 2 s (it ran past 300 s)

"""The component library's design (issue 13): a kind is one file, everything else generic.

* a kind defined in a file under tests/ is registered and solved against the reference
  (no edit anywhere else);
* a kernel holds its kinds' code and nothing else: the emitted sources of two topologies
  that differ by one kind differ by that kind's functions and dispatch branches only;
* every kind's printed compound step is its descriptor's pole-free step, equal to
  ``det(Cq) C2(P)`` with ``P = A - B Cq^-1 Cz`` (the point matrix), checked symbolically.
"""

from __future__ import annotations

import re

import numpy as np
import pytest
import sympy as sp
import toy_kind
from mstmm.derive import descriptor
from mstmm.derive.compound import second_compound
from mstmm.derive.emit import kernel_source
from reference_model import frequencies

import mstmm
from mstmm import catalog


def _beam(left="clamped", right="free"):
    return {"length": 2.0, "EI": 3.0e3, "mass_per_length": 1.5, "left": left, "right": right}


def test_a_kind_defined_in_a_test_file_solves_against_the_reference(tmp_path, monkeypatch):
    monkeypatch.setenv("MSTMM_CACHE", str(tmp_path))
    catalog.register_kind(toy_kind)
    try:
        parts = [
            {"type": "spring_mass", "x": 0.5, "k": 2.0e3, "m": 0.7},
            {"x": 1.2, "stiffness": 8.0e3},
        ]
        scene = mstmm.scene_from_dict(
            {"beam": _beam(), "attachments": [parts[0], {"type": "ground_spring", **parts[1]}]}
        )
        sol = mstmm.solve(scene, modes=6)
        same = {
            "beam": _beam(),
            "attachments": [parts[0], {"type": "spring", "x": 1.2, "k": 8.0e3}],
        }
        exact = np.array(frequencies(same, 6, dps=30), dtype=float)
        assert sol.count_checked
        np.testing.assert_allclose(sol.omega, exact, rtol=1e-12)
        assert len(sol.shapes) == 6 and all(np.isfinite(s.Y).all() for s in sol.shapes)
    finally:
        catalog.kinds().pop("ground_spring", None)


#: The kernel's dispatch functions: one branch per kind present.
#: The functions holding one branch per kind present: the dispatch functions, and the two
#: hot loops whose branches are printed in place.
DISPATCH = tuple(
    f"event_{w}"
    for w in (
        "descriptor",
        "descriptor_c",
        "nq",
        "internal",
        "rigid",
        "damps",
        "inertia",
        "chain",
        "count",
    )
)


def _functions(source: str) -> dict[str, str]:
    """Top-level functions of a kernel source: name -> text (to the next one)."""
    blocks = re.split(r"\n(?=def )", source.split("\nbind_characteristic")[0])
    out = {}
    for block in blocks:
        m = re.search(r"^def (\w+)\(", block, re.M)
        if m:
            out[m.group(1)] = block.rstrip()
    return out


def _indent(line: str) -> int:
    return len(line) - len(line.lstrip())


def _without_branches(text: str, tag: int) -> str:
    """A function without the branch of ``tag``: its ``if``/``elif`` line and the lines
    indented deeper below it (an ``elif`` after it becomes the ``if`` when it was first)."""
    lines = text.split("\n")
    out: list[str] = []
    i = 0
    while i < len(lines):
        m = re.match(rf"( *)(el)?if tag == {tag}:", lines[i])
        if not m:
            out.append(lines[i])
            i += 1
            continue
        pad = len(m.group(1))
        i += 1
        while i < len(lines) and (not lines[i].strip() or _indent(lines[i]) > pad):
            i += 1
        if not m.group(2) and i < len(lines) and lines[i].lstrip().startswith("elif tag =="):
            lines[i] = lines[i].replace("elif", "if", 1)
    return "\n".join(out)


def test_a_kernel_holds_its_kinds_and_nothing_else():
    """(hinge, mass) -> (hinge, mass, support): the support's branches (tag 2) in the
    dispatch functions are all that is added; every other function is the same text."""
    small = _functions(kernel_source(catalog.Topology("pinned", "free", ("hinge", "mass"))))
    big = _functions(
        kernel_source(catalog.Topology("pinned", "free", ("hinge", "mass", "support")))
    )
    assert set(small) == set(big)
    for name, text in small.items():
        other = big[name]
        if name in DISPATCH:
            assert "if tag == 2:" in other, name
            other = _without_branches(other, 2)
        assert other == text, name
    bare = _functions(kernel_source(catalog.Topology("pinned", "free", ())))
    assert set(bare) == set(small)
    assert "tag ==" not in "".join(bare[n] for n in DISPATCH)
    assert "val_" not in "".join(bare.values())


@pytest.mark.parametrize("name", catalog.builtin_kinds())
def test_compound_step_is_the_pole_free_compound_of_the_point_matrix(name):
    module = catalog.kind(name)
    values = {k.name: sp.Symbol(f"val_{k.name}", positive=True) for k in module.KEYS[1:]}
    if hasattr(module, "stage"):  # a kind of stages: condensed from its tip at run time
        d = descriptor.chain_reduced()
    else:
        d = descriptor.of(module, values)
    v = sp.Matrix(sp.symbols("v0:6"))
    step = descriptor.compound_step(d, v)
    P, pole = descriptor.point_matrix(d)
    if pole != 0:
        # det(Cq) C2(P) = det(Cq) C2(det(Cq) P) / det(Cq)^2
        want = (second_compound(P) * v / pole).applyfunc(sp.simplify)
        assert (step - want).applyfunc(sp.simplify) == sp.zeros(6, 1)
    else:
        # a constraint: the step is the limit of a stiff spring along it, k -> oo
        k = sp.Symbol("k_big", positive=True)
        A = d.A - k * d.B * d.Cz
        limit = (second_compound(A) * v / k).applyfunc(lambda e: sp.limit(e, k, sp.oo))
        assert (step + limit).applyfunc(sp.simplify) == sp.zeros(6, 1) or (step - limit).applyfunc(
            sp.simplify
        ) == sp.zeros(6, 1)


@pytest.mark.parametrize(
    ("name", "held"),
    [("spring", ("Y",)), ("rotational_spring", ("theta",)), ("mass", ()), ("dashpot", ())]
    + [("spring_mass", ())],
)
def test_constraint_on_rigid_motions_is_derived_from_the_energy(name, held):
    """A rigid motion stores no energy only where the static stiffness a kind adds on
    [Y, theta] (its unknowns free) vanishes: a grounded spring holds Y, a grounded
    rotational spring theta; a spring-mass's mass follows the beam."""
    module = catalog.kind(name)
    assert not hasattr(module, "RIGID")
    values = {k.name: sp.Symbol(k.name, positive=True) for k in module.KEYS[1:]}
    assert descriptor.rigid_of(module, values) == held

"""A kind declares its physics and only that (issue 21): a constraint by the freedom it
holds (``CONSTRAINS``), a hinge by the freedom it releases (``RELEASES``), and
``mstmm.derive`` derives its descriptor, its count rule, its constraint on rigid motions.

Checked against a closed form, through the default path (mode shapes on): a rotation
held at the middle of a pinned-pinned beam of length 2 (a kind registered from its one
file, ``tests/kinds/rotation_clamp.py``, touching nothing else). Its symmetric modes are
those of the free beam (zero slope at the middle already), ``beta = n pi / 2`` for odd
n; its antisymmetric ones have Y = 0 and theta = 0 at the middle, so each half is a
pinned-clamped beam of length 1, ``tan(beta) = tanh(beta)``. And the declaration errors
a contributor meets.
"""

from __future__ import annotations

import importlib.util
import math
import types
from pathlib import Path

import mpmath
import numpy as np
import pytest

import mstmm
from mstmm import catalog

KIND_FILE = Path(__file__).parent / "kinds" / "rotation_clamp.py"


def _rotation_clamp() -> types.ModuleType:
    """A fresh module of ``tests/kinds/rotation_clamp.py`` (a kind's file is hashed into
    its kernel's signature)."""
    spec = importlib.util.spec_from_file_location("rotation_clamp", KIND_FILE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture
def rotation_clamp():
    module = _rotation_clamp()
    catalog.register_kind(module)
    try:
        yield module
    finally:
        del catalog.kinds()[module.KIND]


def _closed_form(n: int) -> list[float]:
    """The lowest n values of beta (units of the half length 1): odd multiples of pi/2 and
    the roots of tan(b) = tanh(b) (mpmath, 30 digits)."""
    mpmath.mp.dps = 30
    betas = [(2 * k + 1) * math.pi / 2 for k in range(n)]
    for k in range(1, n + 1):
        guess = (k + 0.25) * mpmath.pi
        betas.append(float(mpmath.findroot(lambda b: mpmath.tan(b) - mpmath.tanh(b), guess)))
    return sorted(betas)[:n]


def test_a_held_rotation_against_the_closed_form(rotation_clamp):
    EI, mbar = 7.0, 3.0
    scene = mstmm.scene_from_dict(
        {
            "beam": {
                "length": 2.0,
                "EI": EI,
                "mass_per_length": mbar,
                "left": "pinned",
                "right": "pinned",
            },
            "attachments": [{"type": "rotation_clamp", "x": 1.0}],
        }
    )
    sol = mstmm.solve(scene, modes=8)
    want = np.array([b**2 * math.sqrt(EI / mbar) for b in _closed_form(8)])
    assert sol.count_checked and all(sol.converged)
    np.testing.assert_allclose(sol.omega, want, rtol=1e-10)
    for shape in sol.shapes:  # the rotation held at the middle, in every mode shape
        i = int(np.argmin(abs(shape.x - 1.0)))
        assert abs(shape.x[i] - 1.0) < 1e-12
        assert abs(shape.theta[i]) <= 1e-8 * np.max(abs(shape.theta))


def test_the_count_rule_and_rigid_motions_follow_the_declaration():
    from mstmm.derive import descriptor

    support, hinge = catalog.kind("support"), catalog.kind("hinge")
    assert catalog.count_rule(support) == "constraint"
    assert catalog.count_rule(hinge) == "split"
    assert catalog.count_rule(catalog.kind("spring_mass")) == "stiffness"
    assert descriptor.rigid_of(support, {}) == ("Y",)
    assert descriptor.rigid_of(hinge, {}) == ("kink_if_free",)
    assert descriptor.rigid_of(_rotation_clamp(), {}) == ("theta",)


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"energy": lambda v: None}, "declares one of"),
        ({"CONSTRAINS": ("Y", "theta")}, "CONSTRAINS is"),
        ({"COUNT": "stiffness"}, "its physics makes COUNT 'constraint'"),
    ],
)
def test_declaration_errors(change, message):
    module = _rotation_clamp()
    for name, value in change.items():
        setattr(module, name, value)
    with pytest.raises(ValueError, match=message):
        catalog.register_kind(module)


def test_a_release_names_its_spring():
    module = types.ModuleType("bad_hinge")
    module.KIND = "bad_hinge"
    module.DOC = "test only"
    module.KEYS = (catalog.Key("x", "m", check="interior"), catalog.Key("k", "N m/rad"))
    module.RELEASES = ("theta", "stiffness")
    with pytest.raises(ValueError, match="names the key of its spring"):
        catalog.register_kind(module)


def _kind_file(name: str) -> types.ModuleType:
    path = Path(__file__).parent / "kinds" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_what_a_damping_connects_is_derived():
    """The proved decay bound's classes and the constraint on rigid motions at omega -> 0,
    from each kind's energy: no declaration (``DAMPS``) left on a built-in kind."""
    from mstmm.derive import descriptor

    c, k, m, J = (sp_symbol(n) for n in ("c", "k", "m", "J"))
    cases = {
        "dashpot": ({"c": c}, "grounded", ("Y",)),
        "spring_mass": ({"k": k, "m": m, "c": c}, "carried", ()),
        "oscillator_chain": ({"k": k, "m": m, "c": c}, "carried", ()),
        "spring": ({"k": k}, "none", ("Y",)),
    }
    for name, (values, klass, damps) in cases.items():
        module = catalog.kind(name)
        assert not hasattr(module, "DAMPS"), name
        assert descriptor.damper_of(module, values) == klass, name
        if name != "spring":
            assert descriptor.damps_of(module, values) == damps, name
    absorber = _kind_file("torsional_absorber")
    assert descriptor.damper_of(absorber, {"k": k, "J": J, "c": c}) == "unproved"
    assert descriptor.damper_of(_kind_file("maxwell"), {"k": k, "c": c}) == "unproved"


def sp_symbol(name: str):
    import sympy as sp

    return sp.Symbol(f"val_{name}", real=True)


def test_the_decay_bound_refuses_a_damper_it_does_not_cover():
    """A damper in N s/m on a massless node (a Maxwell element, one test file): its energy
    says the proof does not cover it (the kernel's ``DAMPERS``), so no bound (None) and
    the solver says which roots it did not count; a grounded dashpot gets its bound."""
    from mstmm.decay_bound import sigma_max

    module = _kind_file("maxwell")
    catalog.register_kind(module)
    try:
        beam = dict(length=2.0, EI=7.0, mass_per_length=3.0, left="clamped", right="free")
        maxwell = {"type": "maxwell", "x": 1.0, "k": 30.0, "c": 0.2}
        scene = mstmm.scene_from_dict({"beam": beam, "attachments": [maxwell]})
        assert sigma_max(scene, 100.0) is None
        dashpot = {"type": "dashpot", "x": 1.0, "c": 0.2}
        grounded = mstmm.scene_from_dict({"beam": beam, "attachments": [dashpot]})
        assert sigma_max(grounded, 100.0).gamma == 0.2
    finally:
        del catalog.kinds()["maxwell"]


def test_the_decay_bound_takes_a_carried_dampers_mass_from_its_energy():
    """The proof's ``2 c |q|^2 <= (2 c / m_a) m`` needs ``m_a |q|^2 <= u* M u`` for every
    motion u: for the inerter absorber (``tests/kinds/inerter_absorber.py``) the kinetic
    energy is ``b (Y_m - Y)^2 + m Y_m^2 >= m Y_m^2`` (equality at Y = Y_m), so m_a = m,
    whatever b; not the smallest key in kg (b < m here), nor m + b. The kernel prints it
    (``own_masses``) from the kind's mass matrix; the bound's R is 2 c / m_a."""
    from mstmm.decay_bound import sigma_max

    module = _kind_file("inerter_absorber")
    catalog.register_kind(module)
    try:
        beam = dict(length=2.0, EI=1.0e4, mass_per_length=10.0, left="clamped", right="free")
        m, b, c = 1.5, 0.25, 4.0
        absorber = {"type": "inerter_absorber", "x": 1.25, "k": 3000.0, "m": m, "b": b, "c": c}
        scene = mstmm.scene_from_dict({"beam": beam, "attachments": [absorber]})
        bound = sigma_max(scene, 100.0)
        assert bound is not None
        assert bound.rate == pytest.approx(2.0 * c / m, rel=1e-14)
    finally:
        del catalog.kinds()["inerter_absorber"]

"""Checks of the independent reference model (tests/reference_model.py) against
values that do not come from it: published reference numbers, closed-form
characteristic equations solved here with mpmath, and physical limits."""

from __future__ import annotations

import json
import math
import random
import sys
import tomllib
from pathlib import Path
from types import SimpleNamespace

import mpmath
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from mpmath import mp, mpf

sys.path.insert(0, str(Path(__file__).resolve().parent))

from reference_model import (  # noqa: E402
    KINDS,
    band,
    count_below,
    eigenspace,
    frequencies,
    global_determinant,
    rigid_body_mode_count,
    segment_stiffness_matrix,
)

DATA = Path(__file__).resolve().parent / "data"
ENDS = ("clamped", "pinned", "free", "sliding")


@pytest.fixture(autouse=True)
def _precise_arithmetic():
    """The tests' own mpmath arithmetic (expected values, tolerances) at 50 digits: at the
    default 15 a 1e-30 comparison would only check 1e-16."""
    with mp.workdps(50):
        yield


def scene(left, right, attachments=(), length=1.0, ei=1.0, mbar=1.0):
    return {
        "beam": {"length": length, "EI": ei, "mass_per_length": mbar, "left": left, "right": right},
        "attachments": [{"type": "spring_mass", "x": x, "k": k, "m": m} for x, k, m in attachments],
    }


def mirrored(sc):
    beam = dict(sc["beam"], left=sc["beam"]["right"], right=sc["beam"]["left"])
    with mp.workdps(80):  # exact for the binary fractions used here
        length = mpf(beam["length"])
        atts = [dict(a, x=length - mpf(a["x"])) for a in sc["attachments"]]
    return {"beam": beam, "attachments": atts}


def rel_err(a, b):
    """|a - b| / |b| of the values as given (mpf(a) at the default 15 digits would round)."""
    with mp.workdps(80):
        a, b = mpf(a), mpf(b)
        if b == 0:
            return abs(a)
        return abs(a - b) / abs(b)


# ----------------------------------------------------------------- reference.json


@pytest.mark.parametrize("name", ["wu_chou_1998", "bare_cantilever"])
def test_reference_json(name):
    expected = json.loads((DATA / "reference.json").read_text())[name]["omega"]
    with open(DATA / f"{name}.toml", "rb") as fh:
        sc = tomllib.load(fh)
    got = frequencies(sc, len(expected), dps=30)
    assert len(got) == len(expected) == 10
    for w, ref in zip(got, expected, strict=True):
        assert rel_err(w, ref) < 1e-15, (w, ref)


# -------------------------------------------------------- closed-form bare beams

# Characteristic equations (beta = lam L), each divided by cosh b so that it is
# O(1) for large b, with asymptotic first guesses for the n-th root (n >= 1).
# Derived independently (see the module docstring of reference_model for the
# conditions; W -> W'' maps clamped <-> free, pinned <-> pinned, sliding <-> sliding).
_EQ = {
    "CF": (lambda b: mpmath.cos(b) + mpmath.sech(b), [mpf("1.8751")], lambda n: n - 0.5),
    "CC": (lambda b: mpmath.cos(b) - mpmath.sech(b), [mpf("4.7300")], lambda n: n + 0.5),
    "CP": (
        lambda b: mpmath.sin(b) - mpmath.cos(b) * mpmath.tanh(b),
        [mpf("3.9266")],
        lambda n: n + 0.25,
    ),
    "CS": (
        lambda b: mpmath.sin(b) + mpmath.cos(b) * mpmath.tanh(b),
        [mpf("2.3650")],
        lambda n: n - 0.25,
    ),
    "PP": (None, None, lambda n: n),
    "PS": (None, None, lambda n: n - 0.5),
}

# (equation, number of rigid-body zeros) for each unordered pair of end conditions
_PAIRS = {
    frozenset(["clamped", "free"]): ("CF", 0),
    frozenset(["clamped"]): ("CC", 0),
    frozenset(["free"]): ("CC", 2),
    frozenset(["clamped", "pinned"]): ("CP", 0),
    frozenset(["pinned", "free"]): ("CP", 1),
    frozenset(["clamped", "sliding"]): ("CS", 0),
    frozenset(["free", "sliding"]): ("CS", 1),
    frozenset(["pinned"]): ("PP", 0),
    frozenset(["sliding"]): ("PP", 1),
    frozenset(["pinned", "sliding"]): ("PS", 0),
}


def closed_form_betas(left, right, count):
    eq, nzero = _PAIRS[frozenset([left, right])]
    func, first, guess = _EQ[eq]
    betas = [mpf(0)] * nzero
    n = 1
    while len(betas) < count:
        if func is None:
            root = mpf(guess(n)) * mp.pi
        else:
            start = first[0] if n == 1 else mpf(guess(n)) * mp.pi
            root = mpmath.findroot(func, start)
            # each root must sit in its own quarter-period window: nothing skipped
            assert abs(root - mpf(guess(n)) * mp.pi) < 0.35
        betas.append(root)
        n += 1
    return betas


@pytest.mark.parametrize("left", ENDS)
@pytest.mark.parametrize("right", ENDS)
@pytest.mark.parametrize(
    "length, ei, mbar", [(1, 1, 1), ("3.2", "2.5", "0.7")], ids=["unit", "scaled"]
)
def test_bare_beam_closed_form(left, right, length, ei, mbar):
    with mp.workdps(40):
        length, ei, mbar = mpf(length), mpf(ei), mpf(mbar)
        sc = scene(left, right, length=length, ei=ei, mbar=mbar)
        got = frequencies(sc, 8, dps=40)
        assert rigid_body_mode_count(sc) == _PAIRS[frozenset([left, right])][1]
    with mp.workdps(60):
        scale = mpmath.sqrt(mpf(ei) / mbar) / length**2
        expected = [b * b * scale for b in closed_form_betas(left, right, 8)]
    assert len(got) == 8
    for w, ref in zip(got, expected, strict=True):
        if ref == 0:
            assert w == 0
        else:
            assert rel_err(w, ref) < 1e-35, (left, right, w, ref)


@pytest.mark.parametrize("left", ENDS)
@pytest.mark.parametrize("right", ENDS)
def test_rigid_modes_equal_count_near_zero(left, right):
    sc = scene(left, right, [(0.0, 50.0, 0.3), (0.37, 80.0, 0.2), (1.0, 20.0, 0.1)])
    nrigid = rigid_body_mode_count(sc)
    assert count_below(sc, "1e-12", dps=30) == nrigid
    got = frequencies(sc, nrigid + 2, dps=30)
    assert got[:nrigid] == [0] * nrigid
    assert all(w > 0 for w in got[nrigid:])


# ------------------------------------------------------- attachments: limits


def _tip_mass_betas(mu, count):
    """Cantilever with a tip point mass mu * mbar L:
    1 + cos b cosh b + mu b (cos b sinh b - sin b cosh b) = 0, scanned on a grid."""

    def f(b):
        return (
            mpmath.cos(b)
            + mpmath.sech(b)
            + mu * b * (mpmath.cos(b) * mpmath.tanh(b) - mpmath.sin(b))
        )

    return roots_on_grid(f, count, step="0.01", start="0.01")


def test_stiff_spring_tip_mass_limit_fixes_sign_convention():
    mu = mpf("0.7")
    with mp.workdps(40):
        expected = _tip_mass_betas(mu, 6)
    # k -> infinity: the spring-mass becomes a rigidly attached point mass
    right_tip = scene("clamped", "free", [(1.0, mpf("1e40"), mu)])
    left_tip = scene("free", "clamped", [(0.0, mpf("1e40"), mu)])
    for sc in (right_tip, left_tip):
        got = frequencies(sc, 6, dps=40)
        for w, b in zip(got, expected, strict=True):
            assert rel_err(w, b * b) < 1e-25


def test_tiny_mass_changes_nothing():
    bare = frequencies(scene("clamped", "free"), 8, dps=40)
    # stiff or moderate spring, tiny mass: its own root sqrt(k/m) is far out of range
    for k in (1e3, 1e12):
        got = frequencies(scene("clamped", "free", [(0.6, k, 1e-30)]), 8, dps=40)
        for w, ref in zip(got, bare, strict=True):
            assert rel_err(w, ref) < 1e-20
    # tiny mass tuned to w0 = 100 rad/s (between modes 3 and 4): adds a root near w0
    with mp.workdps(80):
        tiny = mpf("1e-30")
        tuned = scene("clamped", "free", [(0.6, tiny * 100**2, tiny)])
    got = frequencies(tuned, 9, dps=40)
    expected = sorted(bare + [mpf(100)])
    for w, ref in zip(got, expected, strict=True):
        assert rel_err(w, ref) < 1e-20


def test_mass_at_clamped_end_is_decoupled():
    # W(0) = 0: the oscillators see a fixed point, sqrt(k/m) exactly, three times
    bare = frequencies(scene("clamped", "free"), 6, dps=40)
    got = frequencies(scene("clamped", "free", [(0.0, 1250.0, 0.125)] * 3), 9, dps=40)
    expected = sorted(bare + [mpf(100)] * 3)
    for w, ref in zip(got, expected, strict=True):
        assert rel_err(w, ref) < 1e-30


@pytest.mark.parametrize("x", [0.5, 1.0], ids=["interior", "free_end"])
def test_three_identical_oscillators_double_root(x):
    sc = scene("clamped", "free", [(x, 1250.0, 0.125)] * 3)  # sqrt(k/m) = 100 exactly
    got = frequencies(sc, 10, dps=40)
    at_w0 = [w for w in got if rel_err(w, 100) < 1e-30]
    assert len(at_w0) == 2
    assert count_below(sc, 101, dps=40) - count_below(sc, 99, dps=40) >= 2
    assert sum(rel_err(w, 100) < 1e-30 for w in band(sc, 99.9, 100.1, dps=40)) == 2
    # the in-phase motion of the three masses couples to the beam: a further root
    assert len(got) == len(set(got)) + 1


# ------------------------------------------------------------ self-consistency


def test_segment_stiffness_closed_form_matches_numerical_solve():
    with mp.workdps(50):
        for beta, ell in [(mpf("0.3"), mpf("0.2")), (mpf("7.5"), mpf("0.9")), (mpf(40), mpf(1))]:
            k = segment_stiffness_matrix(beta, ell)

            def basis(s, n, beta=beta):
                z = beta * s
                d = [
                    [mpmath.cos(z), -mpmath.sin(z), -mpmath.cos(z), mpmath.sin(z)],
                    [mpmath.sin(z), mpmath.cos(z), -mpmath.sin(z), -mpmath.cos(z)],
                    [mpmath.cosh(z), mpmath.sinh(z), mpmath.cosh(z), mpmath.sinh(z)],
                    [mpmath.sinh(z), mpmath.cosh(z), mpmath.sinh(z), mpmath.cosh(z)],
                ]
                return [d[i][n] * beta**n for i in range(4)]

            a = mpmath.matrix([basis(0, 0), basis(0, 1), basis(ell, 0), basis(ell, 1)])
            b = mpmath.matrix(
                [basis(0, 3), [-v for v in basis(0, 2)], [-v for v in basis(ell, 3)], basis(ell, 2)]
            )
            num = b * mpmath.inverse(a)
            for i in range(4):
                for j in range(4):
                    assert abs(num[i, j] - k[i][j]) <= mpf("1e-30") * (1 + abs(num[i, j]))


def test_mirror_symmetry_with_end_and_interior_attachments():
    atts = [
        (0.0, 300.0, 0.4),
        (0.25, 1e4, 0.5),
        (0.25, 500.0, 0.1),
        (0.8, 50.0, 2.0),
        (1.0, 80.0, 1),
    ]
    for left, right in [("clamped", "free"), ("free", "sliding"), ("pinned", "free")]:
        sc = scene(left, right, atts, length=2.0, ei=3.0, mbar=0.5)
        a = frequencies(sc, 12, dps=30)
        b = frequencies(mirrored(sc), 12, dps=30)
        for wa, wb in zip(a, b, strict=True):
            assert rel_err(wa, wb) < 1e-25


def test_determinant_sign_changes_match_roots_on_a_grid():
    with open(DATA / "wu_chou_1998.toml", "rb") as fh:
        sc = tomllib.load(fh)
    roots = band(sc, 1, 5000, dps=20)
    assert len(roots) == 6
    assert roots == frequencies(sc, 6, dps=20)
    # an independent scan of the global determinant, fine enough for these roots
    grid = [mpf(1) + i * mpf(4999) / 1500 for i in range(1501)]
    vals = [global_determinant(sc, w, dps=20) for w in grid]
    changes = [(grid[i], grid[i + 1]) for i in range(1500) if (vals[i] > 0) != (vals[i + 1] > 0)]
    assert len(changes) == len(roots)
    for (lo, hi), r in zip(changes, roots, strict=True):
        assert lo < r < hi


def test_many_attachments_and_many_modes():
    rng = random.Random(7)
    atts = [
        (round(rng.uniform(0, 2.0), 3), rng.uniform(10, 1e5), rng.uniform(0.01, 1))
        for _ in range(50)
    ]
    sc = scene("clamped", "free", atts, length=2.0, ei=3.0, mbar=0.5)
    a = frequencies(sc, 20, dps=30)
    b = frequencies(mirrored(sc), 20, dps=30)
    for wa, wb in zip(a, b, strict=True):
        assert rel_err(wa, wb) < 1e-25
    # 100 modes with 3 attachments: consecutive roots are separated, count agrees
    sc3 = scene("free", "free", [(0.3, 1e4, 0.5), (0.7, 2e5, 0.2), (1.0, 5e3, 1.0)])
    ws = frequencies(sc3, 100, dps=30)
    assert ws[:2] == [0, 0] and all(x < y for x, y in zip(ws[2:], ws[3:], strict=False))
    mid = (ws[-1] + ws[-2]) / 2
    assert count_below(sc3, mid, dps=30) == 99


_HARD = {
    "soft_oscillator": ("clamped", "free", [(0.5, 1e-12, 1.0)]),
    "soft_free_free": ("free", "free", [(0.5, 1e-12, 1.0), (1.0, 1e-8, 1e-3)]),
    "close_positions": ("clamped", "free", [(0.5, 100.0, 0.1), (0.5 + 1e-12, 200.0, 0.3)]),
    "heavy_mass": ("pinned", "pinned", [(0.3, 1e6, 1e3)]),
    "stiff_spring": ("sliding", "free", [(0.2, 1e30, 0.5), (0.9, 1e-3, 1e-6)]),
    "both_ends": ("free", "free", [(0.0, 1e3, 0.1), (1.0, 1e3, 0.1), (0.0, 5e2, 0.2)]),
}


@pytest.mark.parametrize("case", sorted(_HARD))
def test_converged_in_precision_and_band_agrees(case):
    left, right, atts = _HARD[case]
    sc = scene(left, right, atts)
    a = frequencies(sc, 10, dps=30)
    b = frequencies(sc, 10, dps=50)
    for wa, wb in zip(a, b, strict=True):
        assert rel_err(wa, wb) < 1e-30
    with mp.workdps(50):
        top = b[-1] * (1 + mpf("1e-20"))
    assert len(band(sc, 0, top, dps=30)) == 10
    for i in range(9):
        if 0 < b[i] < b[i + 1]:
            assert count_below(sc, (b[i] + b[i + 1]) / 2, dps=30) == i + 1


def test_pinned_pinned_double_root_at_a_beam_frequency():
    # two identical oscillators at the node of mode 2 (x = L/2), tuned to it:
    # the beam mode (masses at rest) and the antiphase mass motion, a double root
    with mp.workdps(80):
        w2 = 4 * mp.pi**2
        sc = scene("pinned", "pinned", [(0.5, w2**2, 1)] * 2)
    got = frequencies(sc, 6, dps=40)
    assert sum(rel_err(w, w2) < 1e-38 for w in got) == 2


def test_input_layouts():
    class Obj:
        def __init__(self, **kw):
            self.__dict__.update(kw)

    atts = [(0.1, 190428.3750081235, 3.0775), (0.4, 285642.56251218525, 7.69375)]
    beam = Obj(
        length=1.0, EI=63476.125002707834, mass_per_length=15.3875, left="clamped", right="free"
    )
    obj = Obj(beam=beam, attachments=[Obj(x=x, k=k, m=m) for x, k, m in atts])
    dct = scene("clamped", "free", atts, ei=63476.125002707834, mbar=15.3875)
    assert frequencies(obj, 5, dps=25) == frequencies(dct, 5, dps=25)


# ================================================== every attachment kind, stepped beams


def kscene(left, right, attachments=(), segments=None, length=1.0, ei=1.0, mbar=1.0):
    """Scene with attachments given as dicts in the TOML layout (any kind)."""
    beam = {"left": left, "right": right}
    if segments is None:
        beam.update(length=length, EI=ei, mass_per_length=mbar)
    else:
        beam["segments"] = [{"length": a, "EI": b, "mass_per_length": c} for a, b, c in segments]
    return {"beam": beam, "attachments": list(attachments)}


def close(got, expected, tol):
    assert len(got) == len(expected), (got, expected)
    for w, ref in zip(got, expected, strict=True):
        assert rel_err(w, ref) < tol, (w, ref)


def roots_on_grid(f, count, step="0.02", start="0.02"):
    """The first ``count`` sign changes of f, scanned from ``start`` and polished."""
    roots, step = [], mpf(step)
    a = mpf(start)
    fa = f(a)
    while len(roots) < count:
        b = a + step
        fb = f(b)
        if fa * fb < 0:
            roots.append(mpmath.findroot(f, (a, b), solver="anderson"))
        a, fa = b, fb
    return roots


def test_tip_point_mass_equal_to_beam_mass_published():
    """Cantilever, tip point mass = beam mass, no J: (beta L)^2 = 1.557298, 16.25009,
    50.89584, 105.1983, 179.2320 (published); both ways round."""
    published = ["1.557298", "16.25009", "50.89584", "105.1983", "179.2320"]
    for left, right, x in (("clamped", "free", 1.0), ("free", "clamped", 0.0)):
        sc = kscene(left, right, [{"type": "mass", "x": x, "m": 1.0}])
        got = frequencies(sc, 5, dps=30)  # EI = mbar = L = 1: omega = (beta L)^2
        for w, ref in zip(got, published, strict=True):
            half_ulp = mpf(10) ** (-len(ref.split(".")[1])) / 2
            assert abs(w - mpf(ref)) <= half_ulp, (w, ref)


def _tip_mass_inertia_betas(mass, inertia, count):
    """Cantilever (clamped at 0) with a tip mass M and rotary inertia J at xi = 1, from the
    4x4 boundary determinant written out here.  W = c1 cos + c2 sin + c3 cosh + c4 sinh
    of beta xi; at the tip EI W'' = J w^2 W' and EI W''' = -M w^2 W, i.e. (rows divided by
    beta^n) W''/b^2 - J b^3 W'/b = 0 and W'''/b^3 + M b W = 0 (M, J in mbar L, mbar L^3)."""

    def f(b):
        c, s, ch, sh = mpmath.cos(b), mpmath.sin(b), mpmath.cosh(b), mpmath.sinh(b)
        r0 = [c, s, ch, sh]
        r1 = [-s, c, sh, ch]
        r2 = [-c, -s, ch, sh]
        r3 = [s, -c, sh, ch]
        rows = [
            [1, 0, 1, 0],
            [0, 1, 0, 1],
            [(r2[i] - inertia * b**3 * r1[i]) / ch for i in range(4)],
            [(r3[i] + mass * b * r0[i]) / ch for i in range(4)],
        ]
        return mpmath.det(mpmath.matrix(rows))

    return roots_on_grid(f, count)


def test_tip_mass_with_rotary_inertia_closed_form():
    mass, inertia = mpf("0.5"), mpf("0.02")
    with mp.workdps(40):
        expected = [b * b for b in _tip_mass_inertia_betas(mass, inertia, 6)]
    tip = {"type": "mass", "m": mass, "J": inertia}
    right = frequencies(kscene("clamped", "free", [dict(tip, x=1.0)]), 6, dps=30)
    left = frequencies(kscene("free", "clamped", [dict(tip, x=0.0)]), 6, dps=30)
    close(right, expected, 1e-25)
    close(left, expected, 1e-25)
    # rotary inertia adds kinetic energy only: every frequency drops (min-max principle)
    no_j = frequencies(kscene("clamped", "free", [{"type": "mass", "x": 1.0, "m": mass}]), 6)
    assert all(a < b for a, b in zip(right, no_j, strict=True))


def _two_span_betas(count):
    """Equal spans l, pinned - support - pinned: antisymmetric modes are pinned-pinned
    spans (beta l = n pi), symmetric ones clamped-pinned spans (sin b = cos b tanh b)."""
    cp = closed_form_betas("clamped", "pinned", count)
    pp = [n * mp.pi for n in range(1, count + 1)]
    return sorted(cp + pp)[:count]


def test_two_span_continuous_beam():
    sc = kscene("pinned", "pinned", [{"type": "support", "x": 2.0}], length=4.0)
    with mp.workdps(40):
        got = frequencies(sc, 8, dps=30)
        expected = [(b / 2) ** 2 for b in _two_span_betas(8)]  # l = 2, omega = (beta / l)^2
    close(got, expected, 1e-28)
    assert rel_err(mpmath.sqrt(got[0]) * 2, mp.pi) < 1e-28
    assert abs(mpmath.sqrt(got[1]) * 2 - mpf("3.9266")) < 5e-5
    assert rigid_body_mode_count(sc) == 0


def test_free_hinge_at_mid_span_of_pinned_beam_is_a_mechanism():
    """One zero frequency (the rigid rotation about either pin); the elastic modes are those
    of the two-span beam: antisymmetric ones pinned-pinned halves (W = 0 at the hinge),
    symmetric ones pinned-free halves (isospectral with clamped-pinned)."""
    sc = kscene("pinned", "pinned", [{"type": "hinge", "x": 0.5}])
    assert rigid_body_mode_count(sc) == 1
    assert count_below(sc, "1e-9", dps=30) == 1
    got = frequencies(sc, 7, dps=30)
    with mp.workdps(40):
        expected = [0] + [(2 * b) ** 2 for b in _two_span_betas(6)]
    assert got[0] == 0
    close(got[1:], expected[1:], 1e-28)


def test_tuned_absorber_on_simply_supported_steel_beam():
    """L = 10 m steel beam (E = 2e11 Pa, rho = 7800 kg/m^3, A = 0.01 m^2, I = 3.9e-6 m^4),
    absorber m = 7.8 kg, k = 759.791 N/m at 2.5 m: 1.4937, 1.6506, 6.2874 Hz."""
    sc = kscene(
        "pinned",
        "pinned",
        [{"type": "spring_mass", "x": 2.5, "k": 759.791, "m": 7.8}],
        length=10.0,
        ei=2e11 * 3.9e-6,
        mbar=7800 * 0.01,
    )
    hz = [w / (2 * mp.pi) for w in frequencies(sc, 3, dps=20)]
    for f, ref in zip(hz, ["1.4937", "1.6506", "6.2874"], strict=True):
        assert abs(f - mpf(ref)) <= mpf("5e-5"), (f, ref)


# ------------------------------------------------------------------------- limits


def test_stiff_spring_approaches_a_support():
    base = [{"type": "spring_mass", "x": 0.8, "k": 300.0, "m": 0.5}]
    support = frequencies(kscene("clamped", "free", base + [{"type": "support", "x": 0.3}]), 6)
    for k, tol in ((1e8, 1e-4), (1e12, 1e-8)):
        spring = frequencies(
            kscene("clamped", "free", base + [{"type": "spring", "x": 0.3, "k": k}]), 6
        )
        errs = [rel_err(a, b) for a, b in zip(spring, support, strict=True)]
        assert max(errs) < tol and max(errs) > tol * 1e-4  # converging, not equal
        assert all(a < b for a, b in zip(spring, support, strict=True))  # from below


def test_stiff_end_springs_approach_a_clamped_end():
    """An elastically restrained free end (spring + rotational spring) tends to a clamped
    end; a rotational spring at a pinned end too.  Closed form: clamped-free."""
    with mp.workdps(40):
        expected = closed_form_betas("clamped", "free", 5)
    big = 1e14
    restrained = [
        {"type": "spring", "x": 0.0, "k": big},
        {"type": "rotational_spring", "x": 0.0, "k": big},
    ]
    for sc in (
        kscene("free", "free", restrained),
        kscene("pinned", "free", restrained[1:]),
    ):
        got = frequencies(sc, 5, dps=30)
        close(got, [b * b for b in expected], 1e-11)
        assert rigid_body_mode_count(sc) == 0


def test_stiff_hinge_is_no_hinge_and_mass_is_stiff_spring_mass():
    atts = [{"type": "spring_mass", "x": 0.7, "k": 500.0, "m": 0.3}]
    plain = frequencies(kscene("clamped", "pinned", atts), 6, dps=30)
    hinged = frequencies(
        kscene("clamped", "pinned", atts + [{"type": "hinge", "x": 0.4, "k": 1e13}]), 6
    )
    close(hinged, plain, 1e-10)
    free_hinge = frequencies(kscene("clamped", "pinned", atts + [{"type": "hinge", "x": 0.4}]), 6)
    assert all(a < b for a, b in zip(free_hinge, plain, strict=True))
    # a point mass (J = 0) is a spring-mass whose spring is rigid
    mass = [{"type": "mass", "x": 0.35, "m": 0.4}]
    stiff = [{"type": "spring_mass", "x": 0.35, "k": mpf("1e40"), "m": 0.4}]
    close(
        frequencies(kscene("free", "sliding", atts + mass), 6, dps=30),
        frequencies(kscene("free", "sliding", atts + stiff), 6, dps=30),
        1e-25,
    )


def test_free_free_beam_with_a_free_hinge_or_a_support():
    hinge = kscene("free", "free", [{"type": "hinge", "x": 0.375}])
    assert rigid_body_mode_count(hinge) == 3
    assert count_below(hinge, "1e-9", dps=30) == 3
    got = frequencies(hinge, 5, dps=30)
    assert got[:3] == [0, 0, 0] and got[3] > 1
    support = kscene("free", "free", [{"type": "support", "x": 0.3}])
    assert rigid_body_mode_count(support) == 1
    assert count_below(support, "1e-9", dps=30) == 1
    got = frequencies(support, 3, dps=30)
    assert got[0] == 0 and got[1] > 1
    # a support at the mid-point of a free-free beam: symmetric modes are clamped-free
    # halves, antisymmetric ones pinned-free halves (isospectral with clamped-pinned)
    mid = frequencies(kscene("free", "free", [{"type": "support", "x": 0.5}]), 7, dps=30)
    with mp.workdps(40):
        halves = closed_form_betas("clamped", "free", 6) + closed_form_betas("clamped", "pinned", 6)
        expected = [(2 * b) ** 2 for b in sorted(halves)[:6]]
    assert mid[0] == 0
    close(mid[1:], expected, 1e-28)


def test_stepped_beam_of_equal_segments_is_the_uniform_beam():
    atts = [
        {"type": "spring_mass", "x": 0.25, "k": 800.0, "m": 0.2},
        {"type": "mass", "x": 0.6, "m": 0.1, "J": 0.001},
        {"type": "rotational_spring", "x": 1.125, "k": 2.0},
    ]
    uniform = kscene("clamped", "free", atts, length=1.125, ei=2.0, mbar=0.5)
    stepped = kscene(
        "clamped", "free", atts, segments=[(0.25, 2.0, 0.5), (0.5, 2.0, 0.5), (0.375, 2.0, 0.5)]
    )
    close(frequencies(stepped, 8, dps=30), frequencies(uniform, 8, dps=30), 1e-28)


def _stepped_cantilever_betas(a, e2, mu2, count):
    """Clamped-free two-step beam (unit total length; segment 1 EI = mbar = 1 on [0, a],
    segment 2 EI = e2, mbar = mu2 on [a, 1]) from its 8x8 determinant written out here;
    roots in beta = (mbar1 w^2 / EI1)^(1/4)."""
    r = (mu2 / e2) ** mpf("0.25")

    def d(z, n):  # n-th derivative / lam^n of (cos, sin, cosh, sinh)(z)
        c, s, ch, sh = mpmath.cos(z), mpmath.sin(z), mpmath.cosh(z), mpmath.sinh(z)
        return [
            [c, s, ch, sh],
            [-s, c, sh, ch],
            [-c, -s, ch, sh],
            [s, -c, sh, ch],
        ][n]

    def f(b):
        b2 = b * r
        z1, z2 = b * a, b2 * (1 - a)
        zero = [0, 0, 0, 0]
        rows = [d(0, 0) + zero, d(0, 1) + zero]
        for n, weight in ((0, 1), (1, 1), (2, e2), (3, e2)):
            rows.append(d(z1, n) + [-weight * (b2 / b) ** n * v for v in d(0, n)])
        scale = mpmath.cosh(z2)
        rows += [zero + [v / scale for v in d(z2, 2)], zero + [v / scale for v in d(z2, 3)]]
        return mpmath.det(mpmath.matrix(rows)) / mpmath.cosh(z1)

    return roots_on_grid(f, count, step="0.1")


def test_stepped_cantilever_closed_form():
    a, e2, mu2 = mpf("0.375"), mpf("0.375"), mpf("0.625")  # binary fractions: exact
    expected = [b * b for b in _stepped_cantilever_betas(a, e2, mu2, 5)]
    sc = kscene("clamped", "free", segments=[(0.375, 1.0, 1.0), (0.625, 0.375, 0.625)])
    close(frequencies(sc, 5, dps=30), expected, 1e-25)
    # scaled units: L, EI, mbar of the first segment enter only through omega's scale
    big = kscene("clamped", "free", segments=[(0.75, 4.0, 2.0), (1.25, 1.5, 1.25)])
    scale = mpmath.sqrt(mpf(2)) / 4
    close(frequencies(big, 5, dps=30), [w * scale for w in expected], 1e-25)


def _chain_own_frequencies(k1, k2, m1, m2):
    """Two masses in series on a fixed base: det([[k1 + k2 - m1 s, -k2], [-k2, k2 - m2 s]])."""
    a = m1 * m2
    b = -(m1 * k2 + m2 * (k1 + k2))
    c = k1 * k2
    disc = mpmath.sqrt(b * b - 4 * a * c)
    return [mpmath.sqrt((-b - disc) / (2 * a)), mpmath.sqrt((-b + disc) / (2 * a))]


def test_oscillator_chains():
    sm = {"type": "spring_mass", "x": 0.55, "k": 900.0, "m": 0.3}
    one = {"type": "oscillator_chain", "x": 0.55, "k": [900.0], "m": [0.3]}
    for left, right in (("clamped", "free"), ("free", "free")):
        close(
            frequencies(kscene(left, right, [one]), 6, dps=30),
            frequencies(kscene(left, right, [sm]), 6, dps=30),
            1e-30,
        )
    # a rigid second stage: one spring-mass carrying m1 + m2
    stiff = {"type": "oscillator_chain", "x": 0.55, "k": [900.0, 1e16], "m": [0.2, 0.1]}
    close(
        frequencies(kscene("clamped", "free", [stiff]), 5, dps=30)[:5],
        frequencies(kscene("clamped", "free", [sm]), 5, dps=30),
        1e-10,
    )
    # held beam point (clamped end, support): the chain's own frequencies, counted by the
    # Sturm part of the count and found with the beam's
    k1, k2, m1, m2 = mpf(400), mpf(250), mpf("0.5"), mpf("0.25")
    with mp.workdps(50):
        own = _chain_own_frequencies(k1, k2, m1, m2)
    chain = {"type": "oscillator_chain", "k": [k1, k2], "m": [m1, m2]}
    for sc in (
        kscene("clamped", "free", [dict(chain, x=0.0)]),
        kscene("pinned", "free", [dict(chain, x=0.5), {"type": "support", "x": 0.5}]),
    ):
        got = frequencies(sc, 8, dps=30)
        bare = [
            w for w in frequencies(kscene(sc["beam"]["left"], "free", sc["attachments"][1:]), 8)
        ]
        close(got, sorted(bare + own)[:8], 1e-28)
        for w in own:
            with mp.workdps(50):
                lo, hi = w * (1 - mpf("1e-20")), w * (1 + mpf("1e-20"))
            assert count_below(sc, hi, dps=30) == count_below(sc, lo, dps=30) + 1


# ----------------------------------------------------------- random scenes, every kind

_POSITIONS = [i / 8 for i in range(9)]  # of L; binary fractions, so segment sums are exact


@st.composite
def mixed_scenes(draw):
    """Stepped beams (1-3 segments) with up to 5 attachments of any kind, positions on a
    grid of L/8 that the segment boundaries also lie on (so kinds share points)."""
    nseg = draw(st.integers(1, 3))
    cuts = sorted(draw(st.sets(st.integers(1, 7), min_size=nseg - 1, max_size=nseg - 1)))
    edges = [0, *cuts, 8]
    props = st.sampled_from([0.5, 1.0, 2.0])
    segments = [(mpf(b - a) / 8, draw(props), draw(props)) for a, b in zip(edges, edges[1:])]
    stiff = st.floats(5.0, 2000.0)
    mass = st.floats(0.05, 1.0)
    atts, hinges, rotary = [], set(), set()
    for _ in range(draw(st.integers(0, 5))):
        kind = draw(st.sampled_from(KINDS))
        i = draw(st.integers(1, 7) if kind == "hinge" else st.integers(0, 8))
        att = {"type": kind, "x": _POSITIONS[i]}
        if kind == "spring_mass":
            att.update(k=draw(stiff), m=draw(mass))
        elif kind == "oscillator_chain":
            n = draw(st.integers(1, 3))
            att.update(k=[draw(stiff) for _ in range(n)], m=[draw(mass) for _ in range(n)])
        elif kind == "mass":
            att.update(m=draw(mass), J=draw(st.sampled_from([0.0, 0.002, 0.01])))
        elif kind in ("spring", "rotational_spring"):
            att.update(k=draw(stiff) / (1 if kind == "spring" else 100))
        elif kind == "hinge":
            att.update(k=draw(st.sampled_from([0.0, 0.0, 3.0])))
        # a rotational spring / rotary inertia at a hinge is ambiguous: not generated
        turns = kind == "rotational_spring" or (kind == "mass" and att["J"] > 0)
        if (kind == "hinge" and (i in hinges or i in rotary)) or (turns and i in hinges):
            continue
        (hinges if kind == "hinge" else rotary if turns else set()).add(i)
        atts.append(att)
    ends = st.sampled_from(ENDS)
    return kscene(draw(ends), draw(ends), atts, segments=segments)


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(mixed_scenes())
def test_property_count_equals_roots_below_on_a_grid(sc):
    """For random scenes mixing every kind: J(0+) is the rigid-body count; on a grid up to
    past the 6th elastic root, the count equals the number of roots below each point, and
    the global determinant changes sign across an odd number of roots (with multiplicity)
    between neighbouring points, even otherwise (sign and count are independent)."""
    nrigid = rigid_body_mode_count(sc)
    ws = frequencies(sc, nrigid + 6, dps=20)
    assert ws[:nrigid] == [0] * nrigid and all(w > 0 for w in ws[nrigid:])
    assert count_below(sc, ws[nrigid] * mpf("1e-4"), dps=20) == nrigid
    top = ws[-1]
    distinct = sorted(set(ws[nrigid:]))
    grid = [top * (i + mpf("0.37")) / 24 for i in range(24)]
    grid += [(a + b) / 2 for a, b in zip(distinct, distinct[1:])]
    grid = sorted(grid)
    signs = []
    for g in grid:
        below = sum(1 for w in ws if w < g)
        assert count_below(sc, g, dps=20) == below, (g, below)
        signs.append((global_determinant(sc, g, dps=20) > 0, below))
    for (s0, n0), (s1, n1) in zip(signs, signs[1:]):
        assert (s0 != s1) == ((n1 - n0) % 2 == 1)


# ------------------------------------------------------------------ eigenspaces


def _same_direction(a, b, tol):
    a = [float(v) for v in a]
    b = [float(v) for v in b]
    na = math.sqrt(sum(v * v for v in a))
    nb = math.sqrt(sum(v * v for v in b))
    dot = sum(x * y for x, y in zip(a, b, strict=True)) / (na * nb)
    assert 1 - abs(dot) < tol, dot


def test_eigenspace_two_span_and_hinged_beams():
    """The first two-span mode is sin(pi x / l) (W = 0 at the support); the pinned beam with
    a free hinge at mid-span has the same antisymmetric mode."""
    xs = [i / 10 for i in range(41)]
    two_span = kscene("pinned", "pinned", [{"type": "support", "x": 2.0}], length=4.0)
    w1 = frequencies(two_span, 1, dps=30)[0]
    (vec,) = eigenspace(two_span, w1, 1, xs, dps=30)
    _same_direction(vec, [math.sin(math.pi * x / 2) for x in xs], 1e-14)
    hinged = kscene("pinned", "pinned", [{"type": "hinge", "x": 2.0}], length=4.0)
    assert frequencies(hinged, 2, dps=30)[0] == 0
    (vec,) = eigenspace(hinged, w1, 1, xs, dps=30)
    _same_direction(vec, [math.sin(math.pi * x / 2) for x in xs], 1e-14)


def test_eigenspace_rigid_motions_with_a_free_hinge():
    """Free-free with a free hinge and a spring-mass: 3 rigid motions, spanned by 1, x and
    the kink (x - h)+; the hanging mass moves with its beam point."""
    h = 0.375
    sc = kscene(
        "free",
        "free",
        [{"type": "hinge", "x": h}, {"type": "spring_mass", "x": 0.75, "k": 50.0, "m": 0.1}],
    )
    xs = [i / 16 for i in range(17)]
    basis = eigenspace(sc, 0, 3, xs)
    assert len(basis) == 3
    funcs = [[1.0] * 18, xs + [0.75], [max(x - h, 0.0) for x in xs] + [0.75 - h]]
    # same span: the 3 x 3 matrix of least-squares coefficients reproduces the vectors
    F = np.array(funcs).T
    B = np.array(basis).T
    coef, *_ = np.linalg.lstsq(F, B, rcond=None)
    assert np.abs(F @ coef - B).max() < 1e-14 * np.abs(B).max()
    assert np.linalg.matrix_rank(coef) == 3
    with pytest.raises(ValueError):
        eigenspace(sc, 0, 2, xs)


def test_eigenspace_chain_at_a_clamped_end_and_stepped_beam():
    k1, k2, m1, m2 = mpf(400), mpf(250), mpf("0.5"), mpf("0.25")
    w = _chain_own_frequencies(k1, k2, m1, m2)[0]
    chain = {"type": "oscillator_chain", "x": 0.0, "k": [k1, k2], "m": [m1, m2]}
    sm = {"type": "spring_mass", "x": 0.5, "k": 1e4, "m": 0.01}
    sc = kscene("clamped", "free", [sm, chain])
    xs = [0.25, 0.5, 1.0]
    (vec,) = eigenspace(sc, w, 1, xs, dps=30)
    # hanging masses sorted by x: the chain's two (at 0), then the spring-mass's (at 0.5)
    u1, u2 = vec[3], vec[4]
    assert max(abs(v) for v in vec[:3] + vec[5:]) < 1e-25 * abs(u1)
    assert rel_err(u2 / u1, k2 / (k2 - m2 * w**2)) < 1e-14
    # a stepped beam of equal segments has the uniform beam's modes
    atts = [sm, {"type": "mass", "x": 0.75, "m": 0.2, "J": 0.01}]
    uniform = kscene("clamped", "pinned", atts)
    stepped = kscene("clamped", "pinned", atts, segments=[(0.5, 1.0, 1.0), (0.5, 1.0, 1.0)])
    ws = frequencies(uniform, 3, dps=30)
    for w in ws:
        (a,) = eigenspace(uniform, w, 1, xs, dps=30)
        (b,) = eigenspace(stepped, w, 1, xs, dps=30)
        _same_direction(a, b, 1e-14)


def test_input_objects_with_segments_and_kinds():
    atts = [
        {"type": "mass", "x": 0.25, "m": 0.3, "J": 0.01},
        {"type": "oscillator_chain", "x": 0.5, "k": [300.0, 200.0], "m": [0.1, 0.2]},
        {"type": "support", "x": 0.625},
        {"type": "hinge", "x": 0.75, "k": 2.0},
        {"type": "rotational_spring", "x": 1.0, "k": 1.0},
    ]
    segments = [(0.5, 2.0, 1.0), (0.5, 1.0, 0.5)]
    dct = kscene("clamped", "free", atts, segments=segments)

    def obj(d):
        out = SimpleNamespace(**{k: v for k, v in d.items() if k != "type"})
        out.kind = d["type"]
        return out

    beam = SimpleNamespace(
        left="clamped",
        right="free",
        segments=[SimpleNamespace(length=a, EI=b, mass_per_length=c) for a, b, c in segments],
    )
    objs = SimpleNamespace(beam=beam, attachments=[obj(a) for a in atts])
    assert frequencies(objs, 6, dps=25) == frequencies(dct, 6, dps=25)
    assert rigid_body_mode_count(objs) == 0


@pytest.mark.parametrize(
    "att",
    [
        {"type": "hinge", "x": 0.0},
        {"type": "hinge", "x": 1.0, "k": 1.0},
        {"type": "glue", "x": 0.5},
        {"type": "spring", "x": 0.5, "k": -1.0},
        {"type": "oscillator_chain", "x": 0.5, "k": [1.0, 2.0], "m": [1.0]},
        {"type": "mass", "x": 1.5, "m": 1.0},
    ],
)
def test_bad_attachments_raise(att):
    with pytest.raises(ValueError):
        frequencies(kscene("clamped", "free", [att]), 1)


def test_rotational_attachment_at_a_hinge_is_ambiguous():
    atts = [{"type": "hinge", "x": 0.5}, {"type": "rotational_spring", "x": 0.5, "k": 1.0}]
    with pytest.raises(ValueError, match="ambiguous"):
        frequencies(kscene("clamped", "free", atts), 1)

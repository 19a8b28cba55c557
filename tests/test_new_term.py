"""A segment term is one file (issue 42, item 4): the rotational foundation of
docs/components.md (``tests/terms/rotational_winkler.py``), dropped into
``mstmm/physics/terms/`` of a copy of the package and nothing else touched, is a scene key
of beams and segments, and solves: frequencies, the count (a band solve and the rigid
motions it holds), modal masses, a damped root. Each against an independent model written
here from the energies (the Euler-Lagrange equations of a Timoshenko beam on the
foundation, solved with 30-digit mpmath: ``exp(A x)`` of its field matrix, the
frequencies from the boundary determinant, the shapes integrated by quadrature), and the
Euler-Bernoulli pinned-pinned closed form ``mbar w^2 = EI k^4 + k_r k^2``, k = n pi / L.

The copy runs in a fresh process (``PYTHONPATH`` first, its own kernel cache), as
tests/test_new_kind.py runs a new point kind.
"""

from __future__ import annotations

import functools
import math
import textwrap
from pathlib import Path

import mpmath
import numpy as np
import pytest
from package_copy import run_with_file

HERE = Path(__file__).resolve().parent
TERM_FILE = HERE / "terms" / "rotational_winkler.py"

L, EI, MBAR, KGA, RHOI = 2.0, 1.0e4, 10.0, 2.0e6, 0.05
KR = 3.0e4  # k_r L^2 / EI = 12: the lowest modes move by tens of per cent
ETA = 0.02
MODES = 5
mpmath.mp.dps = 30

SCRIPT = textwrap.dedent(
    """
    import json, sys
    import numpy as np
    import mstmm
    from mstmm import catalog

    L, EI, MBAR, KGA, RHOI, KR, ETA, MODES = {args}
    tim = dict(length=L, EI=EI, mass_per_length=MBAR, kappa_GA=KGA, rho_I=RHOI,
               foundation_kr=KR, left="clamped", right="free")
    sol = mstmm.solve(mstmm.scene_from_dict(dict(beam=tim)), modes=MODES)
    top = 0.5 * (sol.omega[3] + sol.omega[4])
    band = mstmm.solve(mstmm.scene_from_dict(dict(beam=tim)), band=(0.0, top), shapes=False)
    damped = mstmm.solve(
        mstmm.scene_from_dict(dict(beam=dict(tim, loss_factor=ETA))), modes=2, shapes=False
    )
    pp = dict(length=L, EI=EI, mass_per_length=MBAR, foundation_kr=KR,
              left="pinned", right="pinned")
    pinned = mstmm.solve(mstmm.scene_from_dict(dict(beam=pp)), modes=MODES)
    # a stepped free-free beam, the foundation on its second segment only: it holds the
    # rigid rotation, not the translation (one rigid mode at 0)
    segs = [dict(length=0.8, EI=EI, mass_per_length=MBAR),
            dict(length=1.2, EI=EI, mass_per_length=MBAR, foundation_kr=KR)]
    ff = dict(segments=segs, left="free", right="free")
    free = mstmm.solve(mstmm.scene_from_dict(dict(beam=ff)), modes=3, shapes=False)
    json.dump(dict(
        package=mstmm.__file__,
        physics=[key for key, _, _ in catalog.SEGMENT_PHYSICS],
        omega=sol.omega.tolist(),
        count_checked=sol.count_checked,
        modal=[s.modal_mass / s.Y[-1] ** 2 for s in sol.shapes],
        tip=[float(s.x[-1]) for s in sol.shapes],
        band=band.omega.tolist(),
        band_checked=band.count_checked,
        damped=[[w.real, w.imag] for w in damped.omega],
        damped_checked=damped.count_checked,
        pinned=pinned.omega.tolist(),
        pinned_modal=[s.modal_mass for s in pinned.shapes],
        pinned_peak=[float(np.max(np.abs(s.Y))) for s in pinned.shapes],
        free=free.omega.tolist(),
        free_checked=free.count_checked,
    ), sys.stdout)
    """
)


@pytest.fixture(scope="module")
def got(tmp_path_factory) -> dict:
    script = SCRIPT.format(args=(L, EI, MBAR, KGA, RHOI, KR, ETA, MODES))
    return run_with_file(tmp_path_factory.mktemp("pkg"), TERM_FILE, "physics/terms", script)


# -- the independent model -------------------------------------------------------------------


def field(w, stiff=1):
    """``A`` of ``Z' = A Z``, Z = [w, psi, M, Q], from the energies ``EI psi'^2 + kGA (w' -
    psi)^2 + k_r psi^2`` and ``mbar w^2 + rhoI psi^2`` (halved): ``M = EI psi'``,
    ``Q = -kGA (w' - psi)``; the Euler-Lagrange equations give ``w' = psi - Q / kGA``,
    ``psi' = M / EI``, ``M' = Q + (k_r - rhoI w^2) psi``, ``Q' = mbar w^2 w``. ``stiff``
    (1 + i eta) multiplies the stiffnesses."""
    ei, kga, kr = EI * stiff, KGA * stiff, KR * stiff
    return mpmath.matrix(
        [
            [0, 1, 0, -1 / kga],
            [0, 0, 1 / ei, 0],
            [0, kr - RHOI * w * w, 0, 1],
            [MBAR * w * w, 0, 0, 0],
        ]
    )


def clamped_free(w, stiff=1):
    """Clamped at 0 (w = psi = 0), free at L (M = Q = 0): det of U[M, Q rows; M, Q cols]."""
    U = mpmath.expm(field(w, stiff) * L)
    return U[2, 2] * U[3, 3] - U[2, 3] * U[3, 2]


def sign_changes(f, top: float, n: int = 1500) -> list:
    ws = np.linspace(1e-3, top, n)
    vals = [f(mpmath.mpf(w)) for w in ws]
    return [(ws[i], ws[i + 1]) for i in range(n - 1) if vals[i] * vals[i + 1] < 0]


@functools.cache
def reference_frequencies() -> list:
    brackets = sign_changes(clamped_free, 2000.0)
    roots = [
        mpmath.findroot(clamped_free, (mpmath.mpf(a), mpmath.mpf(b)), solver="anderson")
        for a, b in brackets
    ]
    return roots


def shape(w):
    """``x -> (w(x), psi(x))`` of the mode at w, from its initial state [0, 0, M0, Q0]."""
    U = mpmath.expm(field(w) * L)
    M0, Q0 = -U[2, 3], U[2, 2]  # the null vector of the free end's rows
    A = field(w)
    return lambda x: (lambda Z: (Z[0], Z[1]))(mpmath.expm(A * x) * mpmath.matrix([0, 0, M0, Q0]))


def modal_mass_per_tip(w):
    f = shape(w)
    wL = f(L)[0]
    integrand_w = mpmath.quad(lambda x: MBAR * f(x)[0] ** 2, [0, L / 2, L])
    integrand_psi = mpmath.quad(lambda x: RHOI * f(x)[1] ** 2, [0, L / 2, L])
    return (integrand_w + integrand_psi) / wL**2


# -- the checks --------------------------------------------------------------------------------


def test_the_new_file_is_a_segment_key(got):
    assert "foundation_kr" in got["physics"]
    assert got["physics"][:5] == [
        "kappa_GA",
        "rho_I",
        "axial_force",
        "foundation_k",
        "foundation_kG",
    ]


def test_frequencies_and_the_count_against_the_model(got):
    exact = [float(w) for w in reference_frequencies()[:MODES]]
    assert got["count_checked"] and got["band_checked"]
    np.testing.assert_allclose(got["omega"], exact, rtol=1e-11)
    # the band holds exactly the four lowest: none missed, none spurious
    np.testing.assert_allclose(got["band"], exact[:4], rtol=1e-11)


def test_modal_masses_against_the_model(got):
    assert all(x == L for x in got["tip"])
    exact = [float(modal_mass_per_tip(w)) for w in reference_frequencies()[:MODES]]
    np.testing.assert_allclose(got["modal"], exact, rtol=1e-9)


def test_a_damped_root_against_the_model(got):
    """The loss factor multiplies the new term's stiffness too (``LOSS = True``)."""
    stiff = 1 + 1j * ETA
    want = [
        complex(
            mpmath.findroot(lambda w: clamped_free(w, stiff), mpmath.mpc(w0) * mpmath.sqrt(stiff))
        )
        for w0 in reference_frequencies()[:2]
    ]
    w = np.array([complex(*z) for z in got["damped"]])
    assert got["damped_checked"]
    np.testing.assert_allclose(w, want, rtol=1e-10)


def test_euler_bernoulli_pinned_closed_form(got):
    """psi = w' without shear: ``mbar w^2 = EI k^4 + k_r k^2``; modal mass ``mbar L / 2``
    times the squared peak of ``sin(k x)``."""
    k = np.arange(1, MODES + 1) * math.pi / L
    np.testing.assert_allclose(got["pinned"], np.sqrt((EI * k**4 + KR * k**2) / MBAR), rtol=1e-12)
    modal = np.array(got["pinned_modal"]) / np.array(got["pinned_peak"]) ** 2
    np.testing.assert_allclose(modal, MBAR * L / 2, rtol=1e-6)  # the peak is sampled


def test_the_term_holds_the_rigid_rotation_not_the_translation(got):
    """A free-free beam with the foundation on one segment: one rigid mode (the
    translation, at 0), then the elastic ones, counted."""
    assert got["free_checked"]
    assert got["free"][0] == 0.0
    assert got["free"][1] > 1.0


@pytest.mark.parametrize(
    "declared, why",
    [
        (dict(POTENTIAL={("w", "psi"): 1}), "none of what a segment's field carries"),
        (dict(KINETIC={("w'", "w'"): 1}), "none of what a segment's field carries"),
        (dict(POTENTIAL={("w", "w"): 1, ("psi", "psi"): 1}), "none of what"),
        (dict(POTENTIAL={("w", "w"): 1}, CHECK="finite"), "must be nonnegative"),
        (dict(POTENTIAL={("w", "v"): 1}), "is not a pair of"),
    ],
)
def test_a_term_the_field_cannot_carry_is_refused_naming_its_file(declared, why):
    """Refuse, never half-carry: an energy that is none of the roles (a coupling, a
    kinetic w'^2, two roles in one file), a foundation that may be negative (the count's
    bound drops it only because it is not), a field that does not exist."""
    import types

    from mstmm.physics import segment as segment_terms

    module = types.ModuleType("bad_term")
    module.__file__ = "/somewhere/terms/bad_term.py"
    module.NAME, module.UNIT, module.CHECK = "bad", "N", "nonnegative"
    for key, value in declared.items():
        setattr(module, key, value)
    with pytest.raises(segment_terms.TermRefused, match=why) as err:
        segment_terms.role(module)
    message = str(err.value)
    assert message.startswith("/somewhere/terms/bad_term.py: ") and "\n" not in message

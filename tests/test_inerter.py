"""An inertial coupling is one file too (issue 42, items 3 and 4): the inerter absorber
(``tests/kinds/inerter_absorber.py``: a mass m on a spring k and a dashpot c, with an
inerter b in parallel between the mass and the beam), declared by its energy, whose mass
matrix couples the beam's Y to the absorber's own unknown, dropped into
``src/mstmm/kinds/`` of a copy of the package and nothing else touched.

Checked in a fresh process against an independent model written here, in mpmath at 40
digits: the clamped-free Euler-Bernoulli beam in two exact pieces (cos, sin, cosh, sinh)
joined at the absorber, whose equation of motion is condensed into a frequency-dependent
point stiffness; the determinant's shear row is multiplied by the absorber's own dynamic
stiffness, so that it has no pole. Its roots (bracketed sign changes, then
``mpmath.findroot``), exact mode shapes, the modal mass
``int mbar Y^2 dx + b (Y_m - Y(x_a))^2 + m Y_m^2`` and the effective mass
``(int mbar Y dx + m Y_m)^2 / modal mass`` (``mpmath.quad``), damped roots (from the
undamped ones, continued in the dashpot) and forced responses (the same system with a
load on its right side).
"""

from __future__ import annotations

import functools
import importlib.util
import re
import sys
import textwrap
import types
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from package_copy import run_with_kind  # noqa: E402

HERE = Path(__file__).resolve().parent
KIND_FILE = HERE / "kinds" / "inerter_absorber.py"

L, EI, MBAR = 2.0, 1.0e4, 10.0  # a 20 kg cantilever, first mode about 27.8 rad/s
# the absorber: its own frequency with the beam held sqrt(k / (m + b)) = 44.7 rad/s; its
# coupling to the beam 1 - b omega^2 / k vanishes at sqrt(k / b) = 77.5 rad/s
XA, KA, MA, BA, CA = 1.25, 3000.0, 1.0, 0.5, 4.0
MODES = 6
WS = (5.0, 40.0, 77.4, 150.0)  # the frequency responses (rad/s)
DPS = 40

SCRIPT = textwrap.dedent(
    """
    import json, sys
    import numpy as np
    import mstmm
    from mstmm import catalog, kernels

    L, XA, KA, MA, BA, CA, MODES, WS = {args}
    beam = dict(length=L, EI={EI}, mass_per_length={MBAR}, left="clamped", right="free")
    absorber = dict(type="inerter_absorber", x=XA, k=KA, m=MA, b=BA)
    scene = mstmm.scene_from_dict(dict(beam=beam, attachments=[absorber]))
    damped = mstmm.scene_from_dict(dict(beam=beam, attachments=[dict(absorber, c=CA)]))
    sol = mstmm.solve(scene, modes=MODES)
    band = mstmm.solve(scene, band=(0.0, 0.5 * (sol.omega[4] + sol.omega[5])), shapes=False)
    dsol = mstmm.solve(damped, modes=4)
    ws = np.array(WS)
    tip = f"displacement:x={{L!r}}"
    H = mstmm.frf(damped, f"force:x={{L!r}}", [tip, "displacement:mass=0"], ws)
    Hm = mstmm.frf(damped, "force:mass=0", [tip, "displacement:mass=0"], ws)
    H0 = mstmm.frf(scene, f"force:x={{L!r}}", tip, ws)
    bundled = catalog.Topology("clamped", "free", ("spring_mass",))

    def pairs(z):
        return [[v.real, v.imag] for v in np.ravel(z)]

    json.dump(dict(
        package=mstmm.__file__,
        kinds=list(catalog.kinds()),
        bundled_origin=kernels.kernel_module(bundled)[1],
        omega=sol.omega.tolist(),
        count_checked=sol.count_checked,
        band=band.omega.tolist(),
        band_checked=band.count_checked,
        modal=[s.modal_mass / s.Y[-1] ** 2 for s in sol.shapes],
        effective=[s.effective_mass for s in sol.shapes],
        tip=[float(s.x[-1]) for s in sol.shapes],
        absorber=[float(s.mass_Y[0] / s.Y[-1]) for s in sol.shapes],
        damped=pairs(dsol.omega),
        H=pairs(H),
        Hm=pairs(Hm),
        H0=pairs(H0),
    ), sys.stdout)
    """
)


@pytest.fixture(scope="module")
def got(tmp_path_factory) -> dict:
    script = SCRIPT.format(args=(L, XA, KA, MA, BA, CA, MODES, WS), EI=EI, MBAR=MBAR)
    return run_with_kind(tmp_path_factory.mktemp("pkg"), KIND_FILE, script, timeout=900)


# ---------------------------------------------------------------------------------------
# The independent model (mpmath, SI units): w(x) on [0, x_a] and [x_a, L], each
# a1 cos(beta s) + a2 sin(beta s) + a3 cosh(beta s) + a4 sinh(beta s) in its own s, with
# beta^4 = mbar w^2 / EI and time dependence exp(i w t).


def _basis(beta, s, n: int) -> list:
    """The n-th derivative in s of (cos, sin, cosh, sinh)(beta s)."""
    c, si, ch, sh = mp.cos(beta * s), mp.sin(beta * s), mp.cosh(beta * s), mp.sinh(beta * s)
    d = ([c, si, ch, sh], [-si, c, sh, ch], [-c, -si, ch, sh], [si, -c, sh, ch])[n]
    return [beta**n * v for v in d]


def _absorber(w, c):
    """``kappa = k + i w c - w^2 b`` (spring, dashpot and inerter between the mass and
    the beam) and the mass's own dynamic stiffness ``kappa - w^2 m``: its equation of
    motion ``-kappa Y + (kappa - w^2 m) Y_m = F_m``."""
    kappa = KA + 1j * w * c - w * w * BA if c else KA - w * w * BA
    return kappa, kappa - w * w * MA


def _system(w, c=0.0):
    """The 8 x 8 matrix of the two pieces' coefficients: clamped at 0, w, w', w''
    continuous at x_a, the shear jump ``EI [w'''] = kappa w^2 m / (kappa - w^2 m) Y`` of
    the condensed absorber (multiplied by ``kappa - w^2 m``: no pole), free at L."""
    w = mp.mpmathify(w)
    beta = mp.sqrt(mp.sqrt(MBAR * w * w / EI))
    kappa, own = _absorber(w, c)
    A = mp.zeros(8, 8)
    la, lb = mp.mpf(XA), mp.mpf(L) - mp.mpf(XA)
    for j in range(4):
        A[0, j] = _basis(beta, 0, 0)[j]
        A[1, j] = _basis(beta, 0, 1)[j]
        for n in range(3):
            A[2 + n, j] = _basis(beta, la, n)[j]
            A[2 + n, 4 + j] = -_basis(beta, 0, n)[j]
        A[5, j] = -own * EI * _basis(beta, la, 3)[j] - kappa * w * w * MA * _basis(beta, la, 0)[j]
        A[5, 4 + j] = own * EI * _basis(beta, 0, 3)[j]
        A[6, 4 + j] = _basis(beta, lb, 2)[j]
        A[7, 4 + j] = EI * _basis(beta, lb, 3)[j]
    return A


def _det(w, c=0.0):
    return mp.det(_system(w, c))


def _shape(a, beta, x):
    x = mp.mpf(x)
    if x <= XA:
        return sum(a[j] * _basis(beta, x, 0)[j] for j in range(4))
    return sum(a[4 + j] * _basis(beta, x - mp.mpf(XA), 0)[j] for j in range(4))


@functools.cache
def reference_modes() -> list[tuple]:
    """The lowest MODES natural frequencies (rad/s) with the modal mass per unit tip
    deflection, the effective mass in a base translation and Y_m / Y(L)."""
    with mp.workdps(DPS):
        scale = mp.sqrt(EI / MBAR) / mp.mpf(L) ** 2
        grid = [(mp.mpf(k) / 40) ** 2 * scale for k in range(1, 40 * 20)]  # beta L to 20
        values = [_det(w) for w in grid]
        roots = []
        for k in range(len(grid) - 1):
            if mp.sign(values[k]) != mp.sign(values[k + 1]):
                roots.append(
                    mp.findroot(_det, (grid[k], grid[k + 1]), solver="anderson", verify=False)
                )
            if len(roots) == MODES:
                break
        out = []
        for w in roots:
            beta = mp.sqrt(mp.sqrt(MBAR * w * w / EI))
            U, S, V = mp.svd_r(_system(w))
            a = [V[7, j] for j in range(8)]  # the null vector: the smallest singular value
            assert S[7] < mp.mpf(10) ** (-DPS + 12) * S[0]
            kappa, own = _absorber(w, 0.0)
            ya = _shape(a, beta, XA)
            ym = kappa * ya / own  # the absorber's equation, no force on it
            tip = _shape(a, beta, L)
            pieces = [0, XA, L]

            def y(x, a=a, beta=beta):
                return _shape(a, beta, x)

            modal = MBAR * mp.quad(lambda x: y(x) ** 2, pieces)
            modal += BA * (ym - ya) ** 2 + MA * ym**2
            carried = MBAR * mp.quad(y, pieces) + MA * ym
            out.append((w, modal / tip**2, carried**2 / modal, ym / tip))
        return out


@functools.cache
def reference_damped(n: int = 4) -> list:
    """The n lowest damped roots w = w_d + i sigma (exp(i w t)), each continued from its
    undamped root in 8 steps of the dashpot (a complex secant in each)."""
    with mp.workdps(DPS):
        out = []
        for w0 in [m[0] for m in reference_modes()[:n]]:
            w = mp.mpc(w0)
            for step in range(1, 9):
                c = CA * step / 8
                w = mp.findroot(
                    lambda z, c=c: _det(z, c), w, tol=mp.mpf(10) ** (-DPS + 6), verify=False
                )
            out.append(complex(w))
        return out


def reference_frf(w, c: float, on_mass: bool) -> tuple[complex, complex]:
    """(tip displacement, absorber displacement) for a unit force at the tip or on the
    absorber's mass (its equation ``-kappa Y + (kappa - w^2 m) Y_m = F_m`` puts
    ``kappa F_m / (kappa - w^2 m)`` on the beam's shear jump)."""
    with mp.workdps(DPS):
        w = mp.mpf(w)
        A = _system(w, c)
        rhs = mp.zeros(8, 1)
        kappa, own = _absorber(w, c)
        if on_mass:
            rhs[5] = kappa  # the row: own EI [w'''] - kappa w^2 m Y = kappa F_m
        else:
            rhs[7] = -1  # EI w'''(L) = -F
        a = mp.lu_solve(A, rhs)
        beta = mp.sqrt(mp.sqrt(MBAR * w * w / EI))
        ya = _shape(a, beta, XA)
        ym = (kappa * ya + (1 if on_mass else 0)) / own
        return complex(_shape(a, beta, L)), complex(ym)


def _complex(pairs) -> np.ndarray:
    return np.array([complex(*z) for z in pairs])


def test_the_new_file_is_a_kind_and_leaves_every_other_kernel_valid(got):
    assert "inerter_absorber" in got["kinds"]
    assert got["bundled_origin"] == "mstmm.generated.beam__spring_mass"


def test_frequencies_and_the_count_against_the_exact_model(got):
    exact = np.array([float(m[0]) for m in reference_modes()])
    assert got["count_checked"] and got["band_checked"]
    np.testing.assert_allclose(got["omega"], exact, rtol=1e-12)
    # the band holds exactly the five lowest: none missed, none spurious
    np.testing.assert_allclose(got["band"], exact[:5], rtol=1e-12)


def test_modal_and_effective_masses_carry_the_inertial_coupling(got):
    """Modal mass per unit tip deflection with the inerter's ``b (Y_m - Y)^2`` in it, and
    the effective mass in a base translation (which carries the absorber: its inerter
    stores nothing), against the exact mode shapes."""
    modes = reference_modes()
    assert all(x == L for x in got["tip"])
    np.testing.assert_allclose(got["absorber"], [float(m[3]) for m in modes], rtol=1e-10)
    np.testing.assert_allclose(got["modal"], [float(m[1]) for m in modes], rtol=1e-10)
    np.testing.assert_allclose(got["effective"], [float(m[2]) for m in modes], rtol=1e-10)


def test_damped_roots_against_the_exact_model(got):
    w = _complex(got["damped"])
    np.testing.assert_allclose(w, reference_damped(), rtol=1e-10)


def test_frequency_response_against_the_exact_model(got):
    """Tip force: the tip's and the absorber's displacement (damped and undamped); a force
    on the absorber's mass (``force:mass=0``): the same two, each against the model's own
    forced solution (not by reciprocity)."""
    tip_force = [reference_frf(w, CA, on_mass=False) for w in WS]
    mass_force = [reference_frf(w, CA, on_mass=True) for w in WS]
    np.testing.assert_allclose(_complex(got["H"]), np.ravel(tip_force), rtol=1e-10)
    np.testing.assert_allclose(_complex(got["Hm"]), np.ravel(mass_force), rtol=1e-10)
    undamped = [reference_frf(w, 0.0, on_mass=False)[0] for w in WS]
    np.testing.assert_allclose(_complex(got["H0"]), undamped, rtol=1e-10)


# ---------------------------------------------------------------------------------------
# What the derivation carries of an energy, and what it refuses (in this process: SymPy).


def _kind(name: str, energy, keys=("k", "m", "b")):
    """A kind module named ``name`` declared by ``energy`` (a file of its own in a real
    contribution: here ``__file__`` says where it would be)."""
    from mstmm.catalog import Key

    module = types.ModuleType(name)
    module.__file__ = f"/somewhere/kinds/{name}.py"
    module.KIND, module.DOC = name, "test only"
    module.KEYS = (Key("x", "m", check="position"), *(Key(k, "kg") for k in keys))
    module.energy = energy
    return module


def _symbols(*names):
    import sympy as sp

    return {n: sp.Symbol(f"val_{n}", real=True) for n in names}


def test_the_inerter_carries_its_full_mass_matrix():
    """The descriptor of the inerter absorber: its row divided by ``-k`` (the pivot
    ``1 - (m + b) b4 / k``, negative above its own frequency), its coupling ``M_Yq = -b``,
    the mass ``b`` on the beam's Y and the participation row ``-b`` (a base translation
    moves the inerter's two ends together: ``R^T M u = m Y_m``), the mass ``m`` a
    translation carries with Y_m; its dashpot is carried by the mass ``m`` (the proof of
    the decay bound: ``u^T M u >= m Y_m^2``), not ``m + b``."""
    import sympy as sp
    from mstmm.derive import descriptor

    module = _kind_file()
    v = _symbols("k", "m", "b", "c")
    k, m, b = v["k"], v["m"], v["b"]
    d = descriptor.of(module, v)
    b4 = descriptor.b4
    c = v["c"]
    assert sp.expand(d.Cq[0, 0] + 1 + sp.I * descriptor.w1 * c / k - (m + b) * b4 / k) == 0
    assert sp.expand(d.Cz[0, 0] - (1 + sp.I * descriptor.w1 * c / k - b * b4 / k)) == 0
    assert d.qcouple == ((-b, 0),) and d.qmass == (m + b,) and d.qpart == (m,)
    assert d.inertia == sp.Matrix([[b, 0], [0, 0], [-b, 0]])
    assert descriptor.damper_of(module, v) == "carried"
    # an inerter and a spring without a mass: the dashpot's node has no mass of its own
    assert descriptor.damper_of(module, dict(v, m=0)) == "unproved"


def test_every_built_in_kind_keeps_its_point_inertia():
    """For the kinds without an inertial coupling, the mass matrix on [Y, theta] read from
    the energy is the one the jump ``A`` holds (``descriptor.point_inertia``), and no
    participation row: their modal and effective masses are unchanged."""
    import sympy as sp
    from mstmm.derive import descriptor

    from mstmm import catalog

    for name in catalog.builtin_kinds():
        module = catalog.kind(name)
        if not hasattr(module, "energy"):
            continue
        values = _symbols(*(key.name for key in module.KEYS[1:]))
        d = descriptor.of(module, values)
        assert d.inertia[:2, :] == descriptor.point_inertia(d), name
        assert d.inertia[2, :] == sp.zeros(1, 2), name
        assert all(c == (0, 0) for c in d.qcouple), name


def test_the_printed_and_the_read_mass_rows_agree():
    from mstmm.derive import emit

    from mstmm.numerics import shapes

    assert emit.QMASS_ROWS == shapes.QMASS_ROWS


def _two_unknowns(v):
    """Two masses on springs in series whose masses are coupled (an inerter between them)."""
    import sympy as sp
    from mstmm.derive.descriptor import Energy

    k, m, b = v["k"], v["m"], v["b"]
    K = k * sp.Matrix([[1, 0, -1, 0], [0, 0, 0, 0], [-1, 0, 2, -1], [0, 0, -1, 1]])
    M = sp.Matrix([[0, 0, 0, 0], [0, 0, 0, 0], [0, 0, m + b, -b], [0, 0, -b, m + b]])
    return Energy(K=K, C=sp.zeros(4, 4), M=M, moves=("Y", "Y"))


def _inerter_to_ground(v):
    """A mass on a grounded spring, coupled to the beam by an inerter alone: its row has
    no stiffness coupling to divide by, so the count's pivot would have the wrong sign."""
    import sympy as sp
    from mstmm.derive.descriptor import Energy

    k, m, b = v["k"], v["m"], v["b"]
    M = sp.Matrix([[b, 0, -b], [0, 0, 0], [-b, 0, m + b]])
    return Energy(K=sp.diag(0, 0, k), C=sp.zeros(3, 3), M=M, moves=("Y",))


def _turning_with_a_translating_mass(v):
    """An unknown a rigid rotation carries whose mass a translation moves too."""
    import sympy as sp
    from mstmm.derive.descriptor import Energy

    k, m, b = v["k"], v["m"], v["b"]
    K = k * sp.Matrix([[0, 0, 0], [0, 1, -1], [0, -1, 1]])
    M = sp.Matrix([[b, 0, -b], [0, 0, 0], [-b, 0, m + b]])
    return Energy(K=K, C=sp.zeros(3, 3), M=M, moves=("theta",))


@pytest.mark.parametrize(
    ("energy", "term"),
    [
        (_two_unknowns, r"M\[2, 3\] = -val_b couples the unknowns q0 and q1"),
        (_inerter_to_ground, r"its row is divided by 1\.0 \(its first stiffness coupling"),
        (_turning_with_a_translating_mass, r"q0 moves with theta but .* \(R\^T M\)_q0 = -val_b"),
    ],
)
def test_what_cannot_be_carried_is_refused_naming_the_file_and_the_term(energy, term):
    """Refused when its kernel is derived, in one line that names the kind's file and the
    term (a mass between two unknowns; a row without a negative stiffness coupling, whose
    pivot would not count; an unknown the FRF and the mode shapes would take for what it
    is not), never a wrong modal mass or count."""
    from mstmm.derive import emit

    from mstmm import catalog

    module = _kind(energy.__name__.strip("_"), energy)
    catalog.register_kind(module)
    try:
        with pytest.raises(ValueError) as raised:
            emit.kernel_source(catalog.Topology("clamped", "free", (module.KIND,)))
    finally:
        del catalog.kinds()[module.KIND]
    message = str(raised.value)
    assert "\n" not in message
    assert message.startswith(f"kind {module.KIND!r} ({module.__file__}): ")
    assert re.search(term, message), message


def _kind_file():
    spec = importlib.util.spec_from_file_location("inerter_absorber", KIND_FILE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module

"""A kind is one file (issue 21, item 3): the torsional absorber of docs/components.md,
dropped into ``src/mstmm/kinds/`` of a copy of the package and nothing else touched,
solves, counts, gives mode shapes with modal and effective masses, damped roots and the
frequency response, each against an independent finite-element model that gives the
absorber its own degree of freedom (Hermite beam elements, consistent mass, Richardson
extrapolation in h^4).

The copy runs in a fresh process (``PYTHONPATH`` first, its own kernel cache): the built-in
kinds are found by listing the folder, and the new file changes the signature of its own
topologies only, so the committed kernels of the bundled scenes stay in use.
"""

from __future__ import annotations

import functools
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg

sys.path.insert(0, str(Path(__file__).resolve().parent))
import reference_fem as fem  # noqa: E402
from package_copy import run_with_kind  # noqa: E402

HERE = Path(__file__).resolve().parent
KIND_FILE = HERE / "kinds" / "torsional_absorber.py"

L, EI, MBAR = 2.0, 1.0e4, 10.0  # a 20 kg cantilever, first mode about 27.8 rad/s
XA, KA, JA, CA = 1.25, 3000.0, 0.5, 4.0  # the absorber: sqrt(k/J) = 77.5 rad/s
MODES = 6


SCRIPT = textwrap.dedent(
    """
    import json, sys
    import numpy as np
    import mstmm
    from mstmm import kernels
    from mstmm import catalog

    L, XA, KA, JA, CA, MODES = {args}
    beam = dict(length=L, EI={EI}, mass_per_length={MBAR}, left="clamped", right="free")
    absorber = dict(type="torsional_absorber", x=XA, k=KA, J=JA)
    scene = mstmm.scene_from_dict(dict(beam=beam, attachments=[absorber]))
    damped = mstmm.scene_from_dict(dict(beam=beam, attachments=[dict(absorber, c=CA)]))
    sol = mstmm.solve(scene, modes=MODES)
    band = mstmm.solve(scene, band=(0.0, 0.5 * (sol.omega[4] + sol.omega[5])), shapes=False)
    dsol = mstmm.solve(damped, modes=4)
    ws = np.array([5.0, 40.0, 77.0, 150.0])
    H = mstmm.frf(damped, f"force:x={{L!r}}", f"displacement:x={{L!r}}", ws)
    H0 = mstmm.frf(scene, f"force:x={{L!r}}", f"rotation:x={{XA!r}}", ws)
    H1 = mstmm.frf(damped, f"force:x={{L!r}}", "rotation:inertia=0", ws)
    H2 = mstmm.frf(damped, "moment:inertia=0", f"displacement:x={{L!r}}", ws)
    bundled = catalog.Topology("clamped", "free", ("spring_mass",))
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
        damped=[[w.real, w.imag] for w in dsol.omega],
        damped_checked=dsol.count_checked,
        H=[[h.real, h.imag] for h in H],
        H0=[[h.real, h.imag] for h in H0],
        H1=[[h.real, h.imag] for h in H1],
        H2=[[h.real, h.imag] for h in H2],
    ), sys.stdout)
    """
)


@pytest.fixture(scope="module")
def got(tmp_path_factory) -> dict:
    script = SCRIPT.format(args=(L, XA, KA, JA, CA, MODES), EI=EI, MBAR=MBAR)
    return run_with_kind(tmp_path_factory.mktemp("pkg"), KIND_FILE, script, timeout=600)


def fe_matrices(n: int, c: float = 0.0):
    """K, C, M of the clamped-free beam in n Hermite elements (the project's FE model,
    ``tests/reference_fem.py``), the absorber's rotation added as the last degree of freedom;
    dofs (w, w') of nodes 1..n."""
    beam = {"length": L, "EI": EI, "mass_per_length": MBAR, "left": "clamped", "right": "free"}
    K0, M0 = (X.toarray() for X in fem.assemble({"beam": beam, "attachments": []}, n))
    size = K0.shape[0] + 1
    K, M, C = np.zeros((size, size)), np.zeros((size, size)), np.zeros((size, size))
    K[:-1, :-1], M[:-1, :-1] = K0, M0
    node = round(XA / (L / n))
    assert abs(node * L / n - XA) < 1e-12
    pair = [2 * node - 1, size - 1]  # w' of the absorber's node (node 0's dofs removed)
    spring = np.array([[1.0, -1.0], [-1.0, 1.0]])
    K[np.ix_(pair, pair)] += KA * spring
    C[np.ix_(pair, pair)] += c * spring
    M[size - 1, size - 1] += JA
    return K, C, M


def tip(n: int) -> int:
    return 2 * n - 2  # w at node n, after the clamped node's two dofs


def richardson(f, n: int = 64):
    """f(n) and f(2n) extrapolated with the h^4 rate of Hermite elements."""
    a, b = np.asarray(f(n)), np.asarray(f(2 * n))
    return (16 * b - a) / 15


def richardson_h3(f, n: int = 64):
    """f(n), f(2n), f(4n) extrapolated with the rates h^3 then h^4 (the participation
    integral of a Hermite model converges as h^3)."""
    a, b, c = (np.asarray(f(k)) for k in (n, 2 * n, 4 * n))
    r1, r2 = (8 * b - a) / 7, (8 * c - b) / 7
    return (16 * r2 - r1) / 15


def solve(A: np.ndarray, b: np.ndarray) -> np.ndarray:
    """A x = b to full precision: LU, then refinement with residuals in extended precision
    (the element matrices are conditioned as lambda_max / lambda_1, about 1e9 here)."""
    lu = scipy.linalg.lu_factor(A)
    x = scipy.linalg.lu_solve(lu, b)
    wide = A.astype(np.clongdouble)
    for _ in range(4):
        r = b.astype(np.clongdouble) - wide @ x.astype(np.clongdouble)
        x = x + scipy.linalg.lu_solve(lu, r.astype(complex))
    return x


def quadratic_eigenpair(K, C, M, lam: complex, u: np.ndarray):
    """Newton's nonlinear inverse iteration for (K + lam C + lam^2 M) u = 0 from an
    estimate; returns (lam, u) with u normalised by its largest entry."""
    v = u / u[np.argmax(abs(u))]
    w = np.conj(v)
    for _ in range(8):
        T = K + lam * C + lam * lam * M
        x = solve(T, (C + 2 * lam * M) @ v)
        step = (w @ v) / (w @ x)
        lam, v = lam - step, x / (w @ x)
        if abs(step) < 1e-15 * abs(lam):
            break
    # the symmetric quadratic Rayleigh quotient of the converged vector, in extended
    # precision: its error is the square of the vector's
    k, c, m = (v.astype(np.clongdouble) @ X.astype(np.clongdouble) @ v for X in (K, C, M))
    roots = np.roots([complex(m), complex(c), complex(k)])
    lam = roots[np.argmin(abs(roots - lam))]
    for _ in range(3):  # Newton on m lam^2 + c lam + k = 0 in extended precision
        lam = lam - (m * lam * lam + c * lam + k) / (2 * m * lam + c)
    return complex(lam), v


def fe_modes(n: int):
    """The lowest MODES eigenpairs (omega^2, shape) of the undamped model, refined."""
    K, C, M = fe_matrices(n)
    lam, vec = scipy.linalg.eigh(K, M, subset_by_index=[0, MODES - 1])
    out = []
    for j in range(MODES):
        mu, u = quadratic_eigenpair(K, C, M, 1j * np.sqrt(lam[j]), vec[:, j].astype(complex))
        out.append((-(mu * mu).real, u.real))
    return out, M


def fe_frequencies(n: int):
    return [np.sqrt(w2) for w2, _ in fe_modes(n)[0]]


@functools.cache
def fe_modal(n: int):
    """Modal mass per unit tip deflection and effective mass in a base translation."""
    modes, M = fe_modes(n)
    r = np.zeros(M.shape[0])
    r[0 : 2 * n : 2] = 1.0  # w = 1 at every node, w' = 0, the absorber does not turn
    out = []
    for _, phi in modes:
        modal = phi @ M @ phi
        out.append((modal / phi[tip(n)] ** 2, float(phi @ M @ r) ** 2 / modal))
    return out


def fe_damped(n: int):
    """The 4 lowest damped roots w = -i lam (exp(i w t) = exp(lam t)), refined."""
    K, C, M = fe_matrices(n, CA)
    size = K.shape[0]
    A = np.block([[np.zeros((size, size)), np.eye(size)], [-K, -C]])
    B = np.block([[np.eye(size), np.zeros((size, size))], [np.zeros((size, size)), M]])
    lam, vec = scipy.linalg.eig(A, B)
    w = -1j * lam
    pick = [j for j in np.argsort(w.real) if w[j].real > 0 and np.isfinite(w[j])][:4]
    out = [-1j * quadratic_eigenpair(K, C, M, lam[j], vec[:size, j])[0] for j in pick]
    return np.array(out)


def fe_frf(n: int, c: float, out_dof):
    K, C, M = fe_matrices(n, c)
    f = np.zeros(K.shape[0], dtype=complex)
    f[tip(n)] = 1.0
    ws = [5.0, 40.0, 77.0, 150.0]
    return [solve(K + 1j * w * C - w * w * M, f)[out_dof(n)] for w in ws]


def test_the_new_file_is_a_kind_and_leaves_every_other_kernel_valid(got):
    assert "torsional_absorber" in got["kinds"]
    assert "spring_mass" in got["kinds"]
    assert got["bundled_origin"] == "mstmm.generated.beam__spring_mass"


def test_frequencies_and_the_count_against_finite_elements(got):
    exact = richardson(fe_frequencies)
    assert got["count_checked"] and got["band_checked"]
    np.testing.assert_allclose(got["omega"], exact, rtol=1e-9)
    # the band holds exactly the five lowest: none missed, none spurious
    np.testing.assert_allclose(got["band"], exact[:5], rtol=1e-9)


def test_modal_and_effective_masses_count_the_rotary_inertia(got):
    """Modal mass per unit tip deflection (the absorber's J theta_a^2 in it) and the
    effective mass in a base translation (which does not turn the absorber)."""
    assert all(x == L for x in got["tip"])
    np.testing.assert_allclose(got["modal"], richardson(fe_modal)[:, 0], rtol=1e-7)
    # the FE model's own round-off and extrapolation leave about 5e-8 here
    np.testing.assert_allclose(got["effective"], richardson_h3(fe_modal)[:, 1], rtol=1e-6)


def test_damped_roots_against_finite_elements(got):
    exact = richardson(fe_damped)
    w = np.array([complex(*z) for z in got["damped"]])
    np.testing.assert_allclose(w, exact, rtol=1e-8)


def test_frequency_response_against_finite_elements(got):
    exact = richardson(lambda n: fe_frf(n, CA, tip))
    H = np.array([complex(*z) for z in got["H"]])
    np.testing.assert_allclose(H, exact, rtol=1e-7)
    node = round(XA / (L / 64))
    rotation = richardson(lambda n: fe_frf(n, 0.0, lambda n: 2 * (node * n // 64) - 1))
    H0 = np.array([complex(*z) for z in got["H0"]])
    np.testing.assert_allclose(H0, rotation, rtol=1e-7)


def test_the_absorber_rotation_is_a_response_and_a_load_point(got):
    """``rotation:inertia=0`` (the absorber's own rotation, its energy says a rigid rotation
    carries it) against the finite-element model's extra degree of freedom, and
    ``moment:inertia=0`` by reciprocity (a couple on the absorber, the tip's response)."""
    exact = richardson(lambda n: fe_frf(n, CA, lambda n: -1))
    H1 = np.array([complex(*z) for z in got["H1"]])
    H2 = np.array([complex(*z) for z in got["H2"]])
    np.testing.assert_allclose(H1, exact, rtol=1e-7)
    np.testing.assert_allclose(H2, H1, rtol=1e-10)

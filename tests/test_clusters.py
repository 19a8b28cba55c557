"""Clusters of roots: many spring-masses whose own frequencies coincide or crowd.

* identical spring-masses at one point: the multiplicity of their own frequency is exact
  and the other roots are those of one equivalent spring-mass (proof below);
* identical spring-masses at evenly spaced points: every root of their cluster, counted
  in narrow windows against the independent reference count (``tests/reference_model``);
* random spring-masses with their own frequencies in the band (``benchmarks.scaling``'s
  "in band" family): the lowest 20 certified by the count, checked against the reference
  count, in a bounded number of evaluations of the characteristic function and the count.
"""

from __future__ import annotations

import math
import sys

import numpy as np
import pytest
import reference_model as ref

import mstmm
from mstmm import interpret

# the paper's beam (tests/data/wu_chou_1998.toml), clamped-free
L, EI, MBAR = 1.0, 63476.125002707834, 15.3875
BEAM = {"length": L, "EI": EI, "mass_per_length": MBAR, "left": "clamped", "right": "free"}
#: omega = SCALE beta^2 on this beam
SCALE = math.sqrt(EI / MBAR) / L**2


def scene(attachments: list[tuple[float, float, float]], name: str = "cluster"):
    """The paper's cantilever carrying spring-masses ``(x, k, m)``."""
    atts = [{"type": "spring_mass", "x": x, "k": k, "m": m} for x, k, m in attachments]
    return mstmm.scene_from_dict({"name": name, "beam": BEAM, "attachments": atts})


@pytest.mark.parametrize("n,x0", [(2, 0.8), (3, 0.8), (300, 0.8), (3000, 0.37), (40, 0.0)])
def test_identical_at_one_point(n, x0):
    """n identical spring-masses (k, m) at one point x0: w0 = sqrt(k/m) is a root of
    multiplicity exactly n - 1 (n at the clamped end), and the other roots are those of
    the same beam with ONE spring-mass (n k, n m) at x0.

    Proof. With u_j the masses' displacements and Y the beam's at x0, each mass obeys
    m u_j'' = -k (u_j - Y), and the beam takes the force sum_j k (u_j - Y) at x0. The mean
    U = sum_j u_j / n obeys (n m) U'' = -(n k) (U - Y), and the beam's force is
    (n k) (U - Y): the beam with U moves exactly as the beam with one spring-mass
    (n k, n m). The differences d_j = u_j - U (sum_j d_j = 0: an (n - 1)-dimensional
    space) obey m d_j'' = -k d_j and put no force on the beam. So a mode of the n masses
    is a mode of the single system (or U = Y = 0) plus a motion of the differences, which
    is harmonic only at w0, with the beam at rest; and each of these is a mode. The
    spectrum is the single system's plus w0 with multiplicity n - 1 (added to w0's own
    multiplicity in the single system: 0 at x0 > 0, where the mass moves the beam; 1 at
    the clamped end, where it cannot)."""
    m = 0.02 * MBAR * L
    w0 = 3000.0
    k = m * w0**2
    single = mstmm.solve(scene([(x0, n * k, n * m)], "single"), modes=8, shapes=False)
    many = mstmm.solve(scene([(x0, k, m)] * n, "many"), modes=8 + n - 1, shapes=False)
    assert single.count_checked and many.count_checked
    assert many.converged.all()
    decoupled = 1 if x0 == 0.0 else 0
    assert np.count_nonzero(np.abs(single.omega - w0) <= 4e-16 * w0) == decoupled
    at_w0 = np.abs(many.omega - w0) <= 4e-16 * w0
    assert np.count_nonzero(at_w0) == n - 1 + decoupled
    assert np.all(many.multiplicity[at_w0] == n - 1 + decoupled)
    rest = many.omega[~at_w0]
    others = single.omega[np.abs(single.omega - w0) > 4e-16 * w0]
    assert len(rest) == len(others)
    assert np.max(np.abs(rest - others) / others) < 1e-13


def spaced(n: int, w0: float = 3000.0):
    """n identical spring-masses (half the beam's mass in all, own frequency w0) at the
    midpoints of n equal cells: (scene, w0)."""
    m = 0.5 * MBAR * L / n
    return scene([((i + 0.5) * L / n, m * w0**2, m) for i in range(n)], "spaced"), w0


def test_identical_spaced_every_root_of_the_cluster():
    """200 identical spring-masses at evenly spaced points (half the beam's mass): their
    roots crowd below w0 towards w0 (1 - 7.1e-9), 5e-12 apart at the end. Every one of the
    cluster, counted in windows down to 2e-8 wide, against the reference's own count (mpmath,
    independent of mstmm); all distinct, converged, the count check held."""
    n = 200
    sc, w0 = spaced(n)
    sol = mstmm.solve(sc, modes=n + 6, shapes=False)
    assert sol.count_checked and sol.converged.all()
    assert np.all(sol.multiplicity == 1) and np.all(np.diff(sol.omega) > 0.0)
    for d in (1e-3, 1e-5, 1e-7, 2e-8):
        lo, hi = w0 * (1.0 - d), w0 * (1.0 + d)
        got = np.count_nonzero((sol.omega > lo) & (sol.omega < hi))
        assert got == ref.count_below(sc, hi, dps=30) - ref.count_below(sc, lo, dps=30), d
    assert np.count_nonzero(sol.omega < w0) == ref.count_below(sc, w0, dps=30)


def test_identical_spaced_never_counted_at_their_own_frequency():
    """1,500 identical spring-masses at evenly spaced points: their roots crowd into
    w0 (1 - 1e-9) .. w0 (1 - 1e-12) (the reference's count). The count taken exactly at w0
    (the midpoint of the two nodes beside it) used to see 144 roots below instead of 1500
    (each resonator a support there), and 1226 roots came out as one of multiplicity 1226
    at w0 (1 + 3e-16), certified. Now every window down to 1e-12 holds the reference's
    number, nothing lies in w0 (1 - 1e-12) .. w0 (1 + 1e-6), and the count asked for
    exactly at w0 is right."""
    n = 1500
    sc, w0 = spaced(n)
    sol = mstmm.solve(sc, modes=n + 2, shapes=False)
    assert sol.count_checked and sol.converged.all()
    near = (sol.omega >= w0 * (1.0 - 1e-12)) & (sol.omega <= w0 * (1.0 + 1e-6))
    assert not near.any() and ref.count_below(sc, w0 * (1.0 - 1e-12), dps=30) == n
    kernel = mstmm.kernel_for(sc)  # the count asked for exactly at w0 is taken beside it
    assert kernel.count_below(np.array([w0]), mstmm.parameter_vector(sc))[0] == n
    for d in (1e-9, 1e-11):
        got = np.count_nonzero(sol.omega < w0 * (1.0 - d))
        assert got == ref.count_below(sc, w0 * (1.0 - d), dps=30), d


def in_band(n: int, seed: int = 7):
    """``benchmarks.scaling``'s "in band" family: n spring-masses at random points, half
    the beam's mass in all, own frequencies log-uniform between the cantilever's first and
    20th natural frequencies."""
    rng = np.random.default_rng(seed)
    w1, w20 = SCALE * 1.8751040687119611**2, SCALE * (19.5 * math.pi) ** 2
    x = rng.uniform(0.0, L, n)
    m = rng.uniform(0.5, 1.5, n) * MBAR * L / (2 * n)
    w = np.exp(rng.uniform(math.log(w1), math.log(w20), n))
    return scene([(float(a), float(b * c * c), float(b)) for a, b, c in zip(x, m, w)], "in_band")


def counted_lowest(sc, modes: int, probes: bool = True):
    """The kernel's ``lowest`` run as Python around its compiled characteristic function
    and count, each call counted: (frequencies, certified, delta calls, count calls).
    ``probes=False``: without the scan's probes beside close nodes (``pair_probe``)."""
    kernel = mstmm.kernel_for(sc)
    p = mstmm.parameter_vector(sc)
    mod = kernel.module
    ns = interpret.python_copy(mod)
    if not probes:
        ns["PROBE_REACH"] = 0.0
    calls = {"delta": 0, "count": 0}

    def delta(w, p):
        calls["delta"] += 1
        return mod.delta_stable(w, p)

    def count(w, p):
        calls["count"] += 1
        return mod.count_below(w, p)

    out = np.zeros(modes)
    flags = np.zeros(modes, dtype=np.int64)
    state = np.zeros(mod.STATE_SIZE)
    args = (mod.oscillator_frequencies, mod.rigid_body_modes, p, modes, out, flags, state)
    k = ns["lowest"](delta, count, *args, True, 0.0)
    assert k == modes and not flags.any()
    return out, state[mod.STATE_CERTIFIED] == 1.0, calls["delta"], calls["count"]


def test_in_band_lowest_20_in_few_evaluations():
    """500 spring-masses in the band: the 20 lowest roots crowd next to the lowest own
    frequencies. The scan brackets each by its own sign change (a node on either side of
    each own frequency, a probe where a weakly coupled mass's root lies just outside its
    two nodes), so ONE count at the top certifies them all: 2 counts (the bottom and the
    top) and at most 10 evaluations of the characteristic function per root (Brent's
    method started from the scan's values, on the function with the far pole factors
    divided out). The same roots as the compiled search, and the reference count jumps
    across sample roots."""
    sc = in_band(500)
    omega, certified, deltas, counts = counted_lowest(sc, 20)
    assert certified
    assert counts == 2
    assert deltas <= 10 * 20, deltas
    sol = mstmm.solve(sc, modes=20, shapes=False)
    assert sol.count_checked and np.array_equal(sol.omega, omega)
    for i in (0, 10, 19):
        w = float(omega[i])
        assert ref.count_below(sc, w * (1.0 - 1e-9), dps=30) <= i
        assert ref.count_below(sc, w * (1.0 + 1e-9), dps=30) >= i + 1


def test_weakly_coupled_root_gets_its_own_sign_change():
    """A spring-mass 1e-3 L from the clamped end barely moves the beam: its root lies
    1.1e-8 below its own frequency w_a, outside the scan's two nodes there (1e-9 either
    side), in the bracket of a light spring-mass's root just above its own frequency
    w_a (1 - 1e-5): two roots, no sign change between the nodes. The secant through the
    two nodes at w_a puts a probe beyond the root, so each root gets a sign change and the
    first count certifies the block (2 counts: the bottom and the top). Without the probe
    the count bisects that bracket."""
    ma, mb = 0.01 * MBAR * L, 1e-6 * MBAR * L
    w_a = SCALE * 9.0**2
    w_b = w_a * (1.0 - 1e-5)
    sc = scene([(1e-3, ma * w_a**2, ma), (0.6, mb * w_b**2, mb)], "weak")
    omega, certified, _, counts = counted_lowest(sc, 6)
    assert certified and counts == 2
    _, certified, _, counts = counted_lowest(sc, 6, probes=False)
    assert certified and counts > 2
    near = (omega - w_a) / w_a
    assert np.count_nonzero((near > -2e-8) & (near < -1e-9)) == 1
    assert np.count_nonzero((near > -1e-5) & (near < -2e-8)) == 1
    for i in range(6):
        w = float(omega[i])
        assert ref.count_below(sc, w * (1.0 - 1e-12), dps=40) <= i
        assert ref.count_below(sc, w * (1.0 + 1e-12), dps=40) >= i + 1


if __name__ == "__main__":  # pragma: no cover
    sys.exit(pytest.main([__file__, "-q"]))


@pytest.mark.parametrize("compiled", [False, True])
def test_brent_across_a_bracket_whose_scale_moves_by_more_than_the_doubles_reach(compiled):
    """The characteristic functions come as (mantissa, log): across a bracket whose log
    moves by 2000 (e^2000: next to a component's own frequency, the repeated cells' next to
    their resonators) the end scaled by exp(-2000) was flushed to zero and Brent's method
    returned it as the root, converged. The closed form: a sign change at 1.2345."""
    r = 1.2345

    def delta(x, p):
        return (x - r) / (1.0 + abs(x - r)), 2000.0 * (x - 1.0)

    kernel = mstmm.kernel_for(mstmm.load_scene(mstmm.example_path("wu_chou_1998")))
    if compiled:
        from numba import njit

        from mstmm.numerics import refine

        root, _, conv = refine(njit(delta), 1.0, 2.0, np.zeros(8), 0.0, 200)
    else:
        ns = interpret.python_copy(kernel.module)
        root, _, conv = ns["refine"](delta, 1.0, 2.0, np.zeros(8), 0.0, 200)
    assert conv and abs(root - r) <= 4e-16 * r, root

"""Issue 41: an oscillator chain of 200 stages took 39 s to solve, of 1,000 past 300 s: its
own frequencies were bisected one at a time (n bisections of n-stage Sturm sweeps). Now
all are bisected together (``chain_own_many``), with the same result bit for bit.

The reference is independent: the chain's own frequencies (beam point held) are the
eigenvalues of its tridiagonal stiffness K and diagonal mass M (scipy's dense ``eigh``)."""

from __future__ import annotations

import time

import numpy as np
import pytest
import scipy.linalg

import mstmm
from mstmm.numerics import chain


def _chain_scene(k: np.ndarray, m: np.ndarray):
    beam = {"left": "pinned", "right": "pinned", "length": 2.0, "EI": 1e4, "mass_per_length": 10.0}
    attachment = {"type": "oscillator_chain", "x": 0.7, "k": k.tolist(), "m": m.tolist()}
    return mstmm.scene_from_dict({"name": "chain", "beam": beam, "attachments": [attachment]})


def _eigh_own(k: np.ndarray, m: np.ndarray) -> np.ndarray:
    """sqrt of the eigenvalues of K u = w^2 M u, node 0 (the beam point) held."""
    below = np.r_[k[1:], 0.0]
    K = np.diag(k + below) - np.diag(k[1:], 1) - np.diag(k[1:], -1)
    return np.sqrt(scipy.linalg.eigh(K, np.diag(m), eigvals_only=True))


def test_own_frequencies_of_a_long_chain_are_its_eigenvalues():
    rng = np.random.default_rng(41)
    n = 300
    k = 1e5 * 10 ** rng.uniform(-1, 1, n)
    m = 10 ** rng.uniform(-1, 0, n)
    scene = _chain_scene(k, m)
    kernel = mstmm.kernel_for(scene)
    t0 = time.perf_counter()
    own = kernel.oscillator_frequencies(mstmm.parameter_vector(scene))
    seconds = time.perf_counter() - t0
    ref = _eigh_own(k, m)
    assert own.shape == (n,)
    # eigh is good to about n eps of the largest eigenvalue
    np.testing.assert_allclose(np.sort(own), ref, rtol=1e-10, atol=1e-9 * ref[-1])
    assert seconds < 30.0  # was about 2 minutes in the plain-Python tier


def _one_at_a_time(st0: np.ndarray) -> np.ndarray:
    """The former chain_internal: each own frequency bisected alone (``chain_own``)."""
    n = st0.shape[1]
    st = np.empty_like(st0)
    top = chain.own_bound(st0)
    out = np.empty(n)
    for k in range(n):
        lo, hi = 0.0, top
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if mid <= lo or mid >= hi:
                break
            if chain.chain_own(st0, mid, st) > k:
                hi = mid
            else:
                lo = mid
        out[k] = np.sqrt(0.5 * (lo + hi))
    return out


@pytest.mark.parametrize("spread", [(3.0, 5.0), (-6.0, 12.0)])
def test_all_at_once_is_one_at_a_time_bit_for_bit(spread):
    """The stages' arrays as the kind's ``event_stages`` fills them at b4 = 0 (a: k,
    b: -k, c: k, s1: 0, m); stiffnesses over up to 18 decades."""
    rng = np.random.default_rng(7)
    n = 60
    k = 10 ** rng.uniform(*spread, n)
    st0 = np.zeros((5, n))
    st0[0], st0[1], st0[2], st0[4] = k, -k, k, 10 ** rng.uniform(-6, 6, n)
    out = np.empty(n)
    with np.errstate(all="ignore"):
        assert chain.chain_internal(st0, 1.0, 1.0, 1.0, out, 0) == n
        assert np.array_equal(out, _one_at_a_time(st0))


def test_plain_python_tier_sweeps_the_chain_a_bounded_number_of_times():
    """The plain-Python tier (``interpret.python_copy``) runs what the compiled one does:
    all own frequencies of 1,000 stages in at most OWN_BISECTIONS sweeps of the stages (the
    former code made one sweep per bisection step per frequency: 1,000 x ~55)."""
    from mstmm.interpret import python_copy

    rng = np.random.default_rng(3)
    n = 1000
    k = 1e5 * 10 ** rng.uniform(-1, 1, n)
    m = 10 ** rng.uniform(-1, 0, n)
    ns = python_copy(mstmm.kernel_for(_chain_scene(k[:2], m[:2])).module)
    sweeps = []
    for name in ("chain_own", "chain_own_many"):
        inner = ns[name]
        ns[name] = lambda *a, inner=inner: sweeps.append(1) or inner(*a)
    st0 = np.zeros((5, n))
    st0[0], st0[1], st0[2], st0[4] = k, -k, k, m
    out = np.empty(n)
    t0 = time.perf_counter()
    with np.errstate(all="ignore"):
        ns["chain_internal"](st0, 1.0, 1.0, 1.0, out, 0)
    seconds = time.perf_counter() - t0
    assert len(sweeps) <= chain.OWN_BISECTIONS
    np.testing.assert_allclose(np.sort(out), _eigh_own(k, m), rtol=1e-9)
    assert seconds < 60.0

"""The frame's band factorization (``mstmm.frame.banded``) against numpy's dense eigensolver.

The count of a frame is the inertia of D(omega) from :func:`ldl` (no pivoting) wherever
its backward error bound says the factors can be trusted; these tests check the inertia,
the bound, the determinant and the solves on random symmetric band matrices, indefinite
and near singular, against ``numpy.linalg.eigvalsh`` and ``numpy.linalg.solve`` of the same
matrix written out dense.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from mstmm.frame.banded import backward, band_matvec, ldl, ldl_solve, reverse_band, row_norm


def _dense(B: np.ndarray) -> np.ndarray:
    n, b1 = B.shape
    A = np.zeros((n, n))
    for k in range(b1):
        i = np.arange(n - k)
        A[i, i + k] = B[: n - k, k]
        A[i + k, i] = B[: n - k, k]
    return A


@st.composite
def band_matrices(draw):
    """A random symmetric band matrix (n up to 40, half-bandwidth up to 6), its entries
    over six decades, shifted so that some eigenvalues are negative; sometimes shifted
    onto one of its eigenvalues (near singular: the bound must then refuse or be right)."""
    n = draw(st.integers(1, 40))
    b = draw(st.integers(0, min(6, n - 1)))
    seed = draw(st.integers(0, 2**31))
    rng = np.random.default_rng(seed)
    B = np.zeros((n, b + 1))
    for k in range(b + 1):
        B[: n - k, k] = rng.standard_normal(n - k) * 10.0 ** rng.uniform(-3, 3, n - k)
    e = np.linalg.eigvalsh(_dense(B))
    shift = float(e[draw(st.integers(0, n - 1))]) if draw(st.booleans()) else 0.0
    return B, shift


@settings(max_examples=120, deadline=None)
@given(band_matrices())
def test_the_inertia_is_the_eigenvalues_wherever_the_bound_vouches(case):
    B, shift = case
    A = _dense(B)
    n, b1 = B.shape
    e = np.linalg.eigvalsh(A) - shift
    W = np.empty_like(B)
    negatives, G, logdet = ldl(B, shift, W)
    if not math.isfinite(G):
        return  # an exactly zero pivot: the caller counts otherwise
    err = backward(G, b1 - 1)
    # every eigenvalue farther from 0 than the backward error (and numpy's own) is
    # counted on its side
    sure = np.abs(e) > err + 64 * np.finfo(float).eps * np.abs(e).max()
    assert (
        np.count_nonzero(e[sure] < 0)
        <= negatives
        <= np.count_nonzero(e < 0) + np.count_nonzero(~sure)
    )
    if sure.all():
        assert negatives == np.count_nonzero(e < 0)
        # Weyl: each eigenvalue of the factored A + E lies within err of A's
        slack = err + 64 * np.finfo(float).eps * np.abs(e).max()
        bound = float(-np.sum(np.log1p(-np.minimum(slack / np.abs(e), 0.5))))
        assert abs(logdet - float(np.sum(np.log(np.abs(e))))) <= 1.01 * bound + 1e-12 * n
    # G bounds |A| from above (the factors reproduce A, so their size is at least A's)
    assert G >= (1 - 1e-12) * np.abs(A - shift * np.eye(n)).sum(axis=1).max() / (2 * b1)


@settings(max_examples=80, deadline=None)
@given(band_matrices())
def test_solves_products_and_the_reverse_order(case):
    B, shift = case
    A = _dense(B) - shift * np.eye(len(B))
    n = len(B)
    x = np.cos(np.arange(n) * 0.7)
    W = np.empty_like(B)
    Bs = B.copy()
    Bs[:, 0] -= shift
    y = np.empty(n)
    band_matvec(Bs, x, y)
    assert np.allclose(y, A @ x, rtol=1e-13, atol=1e-13 * np.abs(A).max())
    assert math.isclose(row_norm(Bs), np.abs(A).sum(axis=1).max(), rel_tol=1e-13)
    R = reverse_band(B, np.empty_like(B))
    assert np.array_equal(_dense(R), _dense(B)[::-1, ::-1])
    _, G, _ = ldl(B, shift, W)
    if (
        math.isfinite(G)
        and np.linalg.cond(A) < 1e8
        and backward(G, B.shape[1] - 1) < 1e-10 * np.abs(A).max()
    ):
        z = x.copy()
        ldl_solve(W, z)
        assert np.allclose(z, np.linalg.solve(A, x), rtol=1e-6, atol=1e-6 * np.abs(z).max())

"""A symmetric band matrix's inertia, determinant and solves (compiled): the frame's count.

D(omega) is kept in the reverse Cuthill-McKee order of its freedoms as upper band rows,
``B[i, k] = D[i, i + k]`` (``k = 0 .. b``, zero past the end), n x (b + 1).

:func:`ldl` factors ``D - shift I = L diag(d) L^T`` without pivoting, as Wittrick and
Williams's count does: by Sylvester's law of inertia the negative pivots are the negative
eigenvalues. In floating point the factors are exact for ``D + E`` with
``|E| <= gamma_(b+1) |L| |d| |L^T|`` (Higham, *Accuracy and Stability*, Thm. 10.5 for the
symmetric case): ``ldl`` returns ``G``, the largest row sum of ``|L| |d| |L^T|`` (a bound
on its 2-norm), and :func:`backward` turns it into a bound on ``||E||_2``, hence on how far
any eigenvalue moved. Where a leading block of D is near singular a pivot is small, ``G``
grows and the bound says so: the caller then counts by an orthogonal reduction instead
(:meth:`mstmm.frame.assembly.Assembly.sure_count`).
"""

from __future__ import annotations

import math

import numpy as np

import mstmm.numerics.cache  # noqa: F401  (numba's user-cache locator, before any njit below)
from mstmm.jit import njit

__all__ = [
    "backward", "band_matvec", "inverse_iteration", "ldl", "ldl_solve", "reverse_band", "row_norm",
]  # fmt: skip


@njit(cache=True, error_model="numpy")
def ldl(B, shift, W):
    """W (n x (b + 1)) <- the factors of ``D - shift I`` (``W[j, 0] = d_j``, ``W[j, k] =
    L[j + k, j]``), D in upper band rows B. Returns ``(negatives, G, log|det|)``; a zero
    pivot returns ``G = inf``. G, the largest row sum of ``|L| |d| |L^T|``, is gathered
    column by column: column j adds ``|L[i, j]| |d_j| (1 + sum_k |L[k, j]|)`` to row i."""
    n, b1 = B.shape
    for j in range(n):
        for k in range(b1):
            W[j, k] = B[j, k]
        W[j, 0] -= shift
    rows = np.zeros(n)
    negatives = 0
    logdet = 0.0
    for j in range(n):
        d = W[j, 0]
        if d == 0.0 or not math.isfinite(d):
            return negatives, math.inf, -math.inf
        if d < 0.0:
            negatives += 1
        logdet += math.log(abs(d))
        top = min(b1 - 1, n - 1 - j)
        inv = 1.0 / d
        column = 1.0
        for k in range(1, top + 1):
            ell = W[j, k] * inv
            row = W[j + k]
            for m in range(k, top + 1):
                row[m - k] -= ell * W[j, m]
            W[j, k] = ell
            column += abs(ell)
        t = abs(d) * column
        rows[j] += t
        for k in range(1, top + 1):
            rows[j + k] += abs(W[j, k]) * t
    return negatives, rows.max(), logdet


@njit(cache=True)
def ldl_solve(W, x):
    """x <- (L diag(d) L^T)^-1 x from the factors of :func:`ldl`."""
    n, b1 = W.shape
    for j in range(n):
        top = min(b1 - 1, n - 1 - j)
        for k in range(1, top + 1):
            x[j + k] -= W[j, k] * x[j]
    for j in range(n):
        x[j] /= W[j, 0]
    for j in range(n - 1, -1, -1):
        top = min(b1 - 1, n - 1 - j)
        for k in range(1, top + 1):
            x[j] -= W[j, k] * x[j + k]


@njit(cache=True)
def band_matvec(B, x, y):
    """y <- D x, D in upper band rows B."""
    n, b1 = B.shape
    for i in range(n):
        y[i] = B[i, 0] * x[i]
    for i in range(n):
        top = min(b1 - 1, n - 1 - i)
        for k in range(1, top + 1):
            y[i] += B[i, k] * x[i + k]
            y[i + k] += B[i, k] * x[i]


def inverse_iteration(W: np.ndarray, steps: int) -> np.ndarray:
    """The unit eigenvector of the eigenvalue nearest 0 of the matrix whose :func:`ldl`
    factors W holds (in its band order), by ``steps`` inverse iterations from a fixed
    start that no eigenvector is orthogonal to in practice."""
    x = np.cos(np.arange(len(W)) * 1.618)
    for _ in range(steps):
        ldl_solve(W, x)
        x /= np.linalg.norm(x)
    return x


def backward(G: float, bandwidth: int) -> float:
    """A bound on ``||E||_2`` for :func:`ldl`'s factors: ``gamma_(b+1) G``."""
    u = np.finfo(float).eps / 2
    m = bandwidth + 1
    return m * u / (1 - m * u) * G


@njit(cache=True)
def row_norm(B):
    """The largest absolute row sum of D (upper band rows B): a bound on its 2-norm."""
    n, b1 = B.shape
    rows = np.zeros(n)
    for i in range(n):
        for k in range(b1):
            if i + k < n:
                a = abs(B[i, k])
                rows[i] += a
                if k:
                    rows[i + k] += a
    return rows.max() if n else 0.0


@njit(cache=True)
def reverse_band(B, out):
    """out <- D with its freedoms in reverse order, as upper band rows (the factors of
    :func:`ldl` then eliminate from the other end: other leading blocks, other pivots)."""
    n, b1 = B.shape
    for i in range(n):
        for k in range(b1):
            out[i, k] = B[n - 1 - i - k, k] if i + k < n else 0.0
    return out

"""Small dense linear algebra the numerics share: the partial pivot of an LU step, and a
linear solve in place (real or complex, a few right-hand sides)."""

import math

from mstmm.jit import njit


@njit(cache=True, inline="always")
def pivot_row(A, k):
    """(row, |entry|) of the largest entry of column k of A on or below the diagonal: the
    partial pivot of LU step k (A real or complex)."""
    piv = k
    big = abs(A[k, k])
    for r in range(k + 1, A.shape[0]):
        if abs(A[r, k]) > big:
            big = abs(A[r, k])
            piv = r
    return piv, big


@njit(cache=True)
def solve_in_place(A, R, n_rhs):
    """R <- A^-1 R for the n x n A (real or complex) by Gaussian elimination with partial
    pivoting, ``n_rhs`` columns of R; A is overwritten. False when A is singular or a pivot
    is not finite."""
    n = A.shape[0]
    for k in range(n):
        piv, big = pivot_row(A, k)
        if big == 0.0 or not math.isfinite(big):
            return False
        if piv != k:
            for j in range(n):
                A[k, j], A[piv, j] = A[piv, j], A[k, j]
            for j in range(n_rhs):
                R[k, j], R[piv, j] = R[piv, j], R[k, j]
        for r in range(k + 1, n):
            f = A[r, k] / A[k, k]
            if f != 0.0:
                for j in range(k + 1, n):
                    A[r, j] -= f * A[k, j]
                for j in range(n_rhs):
                    R[r, j] -= f * R[k, j]
    for j in range(n_rhs):
        for k in range(n - 1, -1, -1):
            acc = R[k, j]
            for c in range(k + 1, n):
                acc -= A[k, c] * R[c, j]
            R[k, j] = acc / A[k, k]
    return True

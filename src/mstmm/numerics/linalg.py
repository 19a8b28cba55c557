"""Small dense linear algebra the numerics share, real or complex: the partial pivot of an LU
step, an LU in place and the determinant from it (plain, or as phase and log), and a linear
solve in place (a few right-hand sides)."""

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


@njit(cache=True)
def lu_in_place(A):
    """A (square, real or complex) overwritten by its LU factors with partial pivoting (U on and
    above the diagonal); returns the permutation's sign, 0 for a singular A."""
    n = A.shape[0]
    sign = 1.0
    for k in range(n):
        piv, big = pivot_row(A, k)
        if big == 0.0:
            return 0.0
        if piv != k:
            sign = -sign
            for j in range(n):
                tmp = A[k, j]
                A[k, j] = A[piv, j]
                A[piv, j] = tmp
        d = A[k, k]
        for r in range(k + 1, n):
            f = A[r, k] / d
            if f != 0.0:
                for j in range(k + 1, n):
                    A[r, j] -= f * A[k, j]
    return sign


@njit(cache=True)
def lu_logdet(A):
    """Determinant of the square A (real or complex) by LU with partial pivoting, as
    (phase, log|det|) with |phase| = 1, of A's type (phase 0 for a singular A); A is
    overwritten."""
    sign = lu_in_place(A)
    if sign == 0.0:
        return A[0, 0] * 0.0, 0.0
    phase = A[0, 0] / abs(A[0, 0]) * sign
    log = math.log(abs(A[0, 0]))
    for k in range(1, A.shape[0]):
        d = A[k, k]
        phase *= d / abs(d)
        log += math.log(abs(d))
    return phase, log


@njit(cache=True)
def lu_det(A):
    """Determinant of a small square A (real or complex) with entries O(1) (no overflow);
    A is overwritten."""
    sign = lu_in_place(A)
    if sign == 0.0:
        return A[0, 0] * 0.0
    det = A[0, 0] * sign
    for k in range(1, A.shape[0]):
        det *= A[k, k]
    return det

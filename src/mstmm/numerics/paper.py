"""The paper's formulation: transfer matrices of segments applied to column sets, and an
LU log-determinant (paper Eq. (4), ``delta_paper``)."""

import math

from numba import njit

from .segment import (
    long_transfer,
)


@njit(cache=True)
def segment_transfer(p, seg, beta, rho, U):
    """U <- the transfer across a piece of segment seg (paper Eq. (1) in units L = EI_0 =
    1, or exp(A rho) of a general segment), unscaled (``segment.long_transfer``)."""
    long_transfer(p, seg, beta, rho, U)


@njit(cache=True)
def apply_columns(U, W, ncols, col):
    """W[:, :ncols] <- U W[:, :ncols] (the transfers of all boundaries so far)."""
    for j in range(ncols):
        for r in range(4):
            col[r] = U[r, 0] * W[0, j] + U[r, 1] * W[1, j] + U[r, 2] * W[2, j] + U[r, 3] * W[3, j]
        for r in range(4):
            W[r, j] = col[r]


@njit(cache=True)
def lu_logdet(A):
    """Determinant by LU with partial pivoting, as (sign, log|det|); A is overwritten."""
    n = A.shape[0]
    sign = 1.0
    log = 0.0
    for k in range(n):
        piv = k
        big = abs(A[k, k])
        for r in range(k + 1, n):
            if abs(A[r, k]) > big:
                big = abs(A[r, k])
                piv = r
        if big == 0.0:
            return 0.0, 0.0
        if piv != k:
            sign = -sign
            for j in range(n):
                tmp = A[k, j]
                A[k, j] = A[piv, j]
                A[piv, j] = tmp
        d = A[k, k]
        if d < 0.0:
            sign = -sign
        log += math.log(abs(d))
        for r in range(k + 1, n):
            f = A[r, k] / d
            if f != 0.0:
                for j in range(k + 1, n):
                    A[r, j] -= f * A[k, j]
    return sign, log

"""The paper's formulation: transfer matrices of segments applied to column sets, and an
LU log-determinant (paper Eq. (4), ``delta_paper``)."""

import math

import numpy as np

from mstmm.jit import njit

from .beam import (
    beam_transfer_scaled,
)
from .field import (
    expm_short,
)
from .segment import (
    balance,
    is_general,
    segment_field,
)
from .walk import (
    segment_scale,
)


@njit(cache=True)
def segment_transfer(p, seg, beta, rho, U):
    """U <- the transfer across rho of segment seg, unscaled (paper Eq. (1) in units L =
    EI_0 = 1, or exp(A rho) of a general segment): growing and decaying solutions
    together, as the paper forms them (``u_bar_paper``)."""
    if is_general(p, seg):
        A = np.empty((4, 4))
        segment_field(p, seg, beta**4, 1.0, A)
        expm_short(A, rho, balance(A), U)
    else:
        e, a = segment_scale(p, seg)
        shift = beam_transfer_scaled(beta * a, rho, U)
        f = math.exp(shift)
        for r in range(4):
            for c in range(4):
                U[r, c] *= f * (e if r >= 2 else 1.0) / (e if c >= 2 else 1.0)


@njit(cache=True)
def apply_columns(U, W, ncols, col):
    """W[:, :ncols] <- U W[:, :ncols] (the transfers of all boundaries so far)."""
    for j in range(ncols):
        for r in range(4):
            col[r] = U[r, 0] * W[0, j] + U[r, 1] * W[1, j] + U[r, 2] * W[2, j] + U[r, 3] * W[3, j]
        for r in range(4):
            W[r, j] = col[r]

"""The Wittrick-Williams count: negative pivots of the dynamic stiffness eliminated node
by node on the minors of the state subspace (paper's Eq. (4) reduced; docs/components.md)."""

import numpy as np

from mstmm.jit import njit

from .beam import (
    beam_compound_step,
    beam_transfer_scaled,
)
from .segment import (
    compound_step,
    count_pieces,
    field_exp,
    field_prepare,
    second_compound,
)
from .walk import (
    renormalise_lazy,
)


@njit(cache=True, inline="always")
def neg2(a, c, det):
    """Number of negative eigenvalues of a symmetric 2x2 matrix with diagonal a, c and
    determinant det."""
    if det < 0.0:
        return 1
    if a + c < 0.0:
        return 2 if det > 0.0 else 1
    return 0


@njit(cache=True)
def pair_count(Zc, U, beta, rho):
    """Carry the node's state subspace across a piece (beta*rho <= RICCATI_STEP); returns
    the negative pivots of eliminating the near node.

    The subspace of states [Y, theta, M, Q] that everything left of the node admits is
    held by the 2x2 minors Zc of a basis Z = [Xd; Xf] (Pluecker coordinates, index as
    ``PAIRS`` of the second compound), carried by the same compound step as the stable
    chain (PI_LEFT = [[0, -1], [1, 0]] and PI_RIGHT = [[0, 1], [-1, 0]] take the nodal
    forces [F, M_theta] to the internal [M, Q] at a segment's left and right end). Its
    condensed stiffness S = PI_RIGHT^-1 Xf Xd^-1 is never formed: after a
    short segment from a pinned end S is huge and near-singular (det Xd ~ rho^3), and
    neither a Riccati step on S nor an orthonormalised basis Z keeps a digit of det Xd,
    while Zc(0,1) = det Xd is a coordinate here. The pivot block M = S + k_aa =
    -(B PI_LEFT)^-1 Xd' Xd^-1, Xd' the d block of U Z, and by Cauchy-Binet
    W = Xd' adj(Xd) is linear in Zc: W[i, 0] = sum_k U[i, k] Zc(k, 1),
    W[i, 1] = sum_k U[i, k] Zc(0, k). So det M has the sign of
    det Xd det Xd' det(B PI_LEFT), and tr M that of -tr(adj(B PI_LEFT) W) / (det Xd
    det(B PI_LEFT)).
    """
    beam_transfer_scaled(beta, rho, U)
    a = Zc[0]
    w00, w10, w01, w11 = pivot_products(Zc, U)
    beam_compound_step(Zc, beta, rho)
    renormalise_lazy(Zc)
    return pivot_negatives(U, a, Zc[0], w00, w10, w01, w11)


@njit(cache=True, inline="always")
def pivot_products(Zc, U):
    """W = Xd' adj(Xd) from the minors before the step (Zc(2,1) = -Zc[3], Zc(3,1) =
    -Zc[4]): (W00, W10, W01, W11) (``pair_count``)."""
    w00 = U[0, 0] * Zc[0] - U[0, 2] * Zc[3] - U[0, 3] * Zc[4]
    w10 = U[1, 0] * Zc[0] - U[1, 2] * Zc[3] - U[1, 3] * Zc[4]
    w01 = U[0, 1] * Zc[0] + U[0, 2] * Zc[1] + U[0, 3] * Zc[2]
    w11 = U[1, 1] * Zc[0] + U[1, 2] * Zc[1] + U[1, 3] * Zc[2]
    return w00, w10, w01, w11


@njit(cache=True, inline="always")
def pivot_negatives(U, a, b, w00, w10, w01, w11):
    """Negative pivots of the near node's block M = S + k_aa from the signs of det Xd
    before (a) and after (b) the step, det(B PI_LEFT) and tr(adj(B PI_LEFT) W)
    (``pair_count``)."""
    # B PI_LEFT = [[U03, -U02], [U13, -U12]]; tr(adj(B PI_LEFT) W):
    detBP = U[0, 2] * U[1, 3] - U[0, 3] * U[1, 2]
    tr = -U[1, 2] * w00 + U[0, 2] * w10 - U[1, 3] * w01 + U[0, 3] * w11
    negative_det = ((a < 0.0) != (b < 0.0)) != (detBP < 0.0)
    n = 0
    if negative_det and a != 0.0 and b != 0.0:
        n = 1
    elif tr != 0.0 and a != 0.0 and (tr > 0.0) == ((detBP > 0.0) == (a > 0.0)):
        n = 2
    return n


@njit(cache=True)
def field_count(Zc, p, seg, w2, rho, F, ready):
    """The count across rho of a general segment (``derive/segments/general.py``): in
    pieces whose J0 is proved 0 (``segment.count_pieces``), each its near node's negative
    pivots (``pair_count`` with the piece's ``exp(A h)`` and its second compound). F holds
    (A, A^2, A^3) of segment ``ready`` (prepared again when seg differs). Returns (the
    count, seg)."""
    if ready != seg:
        field_prepare(p, seg, w2, 1.0, F)
    pieces = count_pieces(p, seg, F, w2, rho)
    U = np.empty((4, 4))
    field_exp(F, rho / pieces, U)
    E = np.empty((6, 6))
    second_compound(U, E)
    v = np.empty(6)
    n = 0
    for _ in range(pieces):
        a = Zc[0]
        w00, w10, w01, w11 = pivot_products(Zc, U)
        compound_step(E, Zc, v)
        renormalise_lazy(Zc)
        n += pivot_negatives(U, a, Zc[0], w00, w10, w01, w11)
    return n, seg


@njit(cache=True, inline="always")
def det_symmetric(S):
    """det of the symmetric part of the 2x2 matrix S."""
    s01 = 0.5 * (S[0, 1] + S[1, 0])
    return S[0, 0] * S[1, 1] - s01 * s01


@njit(cache=True, inline="always")
def pair_stiffness(Zc, S):
    """S = PI_RIGHT^-1 Xf Xd^-1 from the minors of Z = [Xd; Xf] (Cramer's rule); returns
    det S = (Zc(1,3) Zc(0,2) - Zc(0,3) Zc(1,2)) / Zc(0,1)^2 = Zc(2,3) / Zc(0,1) by the
    Pluecker relation: no cancellation when S is near-singular (a rigid-body rotation
    about a pin next to a short segment, its pivot -I omega^2)."""
    detXd = Zc[0]
    if detXd == 0.0:
        detXd = 5e-324  # exactly at a frequency of the node clamped: take one side
    S[0, 0] = Zc[4] / detXd
    S[0, 1] = -Zc[2] / detXd
    S[1, 0] = -Zc[3] / detXd
    S[1, 1] = Zc[1] / detXd
    if Zc[0] != 0.0:
        return Zc[5] / Zc[0]
    return det_symmetric(S)

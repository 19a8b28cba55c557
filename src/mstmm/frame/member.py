"""One member's exact dynamic stiffness and its clamped-clamped count (compiled).

Bending: the member is its beam (a parameter vector of ``catalog.layout``, ends clamped,
no components), cut into pieces short enough that each piece's transfer matrix is
well conditioned (k h <= 1, ``segment.segment_pieces``) and that its proved
clamped-clamped bound (``field.clamped_clamped_bound``) lies above the frequency: each
piece's J0 is then 0. Every segment term the beam declares (``mstmm/physics/terms``)
enters through ``segment.piece_matrix``, the same transfer the beam's walks take. Each
piece's transfer ``Z(h) = U Z(0)``, ``Z = [Y, psi, M, Q]``, becomes its dynamic stiffness
(``piece_stiffness``), and the pieces' inner nodes are eliminated along the member: the
negative pivots counted there are the member's clamped-clamped frequencies below omega
(Wittrick and Williams 1971: J0 of the member = the pieces' J0, 0, plus the negative
eigenvalues of its inner nodes' eliminated stiffness).

Axial: each segment is a rod, ``EA mu / (h sin mu) [[cos mu, -1], [-1, cos mu]]``, ``mu =
omega h sqrt(mbar / EA)``, J0 = floor(mu / pi); the segments' inner nodes eliminated the
same way.
"""

from __future__ import annotations

import cmath
import math

import numpy as np

from mstmm.jit import njit
from mstmm.numerics.field import clamped_clamped_bound
from mstmm.numerics.layout import COL_EI, COL_ETA, COL_MBAR, HEAD, SEGMENT_WIDTH, X_END
from mstmm.numerics.segment import (
    field_exp,
    field_prepare,
    is_general,
    piece_matrix,
    piece_transfer_c,
    segment_piece,
    segment_pieces,
    segment_values,
)

#: Each piece's proved clamped-clamped bound lies this many times above omega^2: its
#: transfer's B block (the end displacements the end forces make) stays well conditioned.
BOUND_MARGIN = 2.0
#: The longest piece, in k h (a wavenumber times its length).
PIECE_STEP = 1.0
#: An inner node's pivot whose least eigenvalue is below this fraction of its largest
#: (a part of the member at one of its own clamped-clamped frequencies: 5 of 8 pieces of
#: a member at beta = 7.568 are at 4.730) costs digits of the member's stiffness (4e-10
#: there): the member is cut again with one more piece a segment (other parts, other
#: frequencies), up to PIECE_RETRIES cuts, the best kept. J0 is the same for any cut.
PIVOT_RATIO = 1e-3
PIECE_RETRIES = 4
#: The longest piece (k h) at a complex frequency far above the real axis (a tall
#: rectangle's side): its transfer's entries grow as e^(k h), its stiffness keeps the
#: digits the argument principle's phase needs.
WIDE_STEP = 8.0


@njit(cache=True)
def inv2(A, out):
    """out <- A^-1 of a 2 x 2; returns det A."""
    det = A[0, 0] * A[1, 1] - A[0, 1] * A[1, 0]
    out[0, 0] = A[1, 1] / det
    out[0, 1] = -A[0, 1] / det
    out[1, 0] = -A[1, 0] / det
    out[1, 1] = A[0, 0] / det
    return det


@njit(cache=True)
def piece_stiffness(U, k):
    """k (4 x 4 over the nodal [Y_0, psi_0, Y_h, psi_h]) <- the dynamic stiffness of a piece
    whose transfer is U (``Z(h) = U Z(0)``, ``Z = [Y, psi, M, Q]``, blocks ``[[A, B], [C,
    D]]``). The nodal force and moment are ``[Q, -M]`` at the start and ``[-Q, M]`` at the
    end (``count.pair_count``'s PI_LEFT and PI_RIGHT): with ``f_0 = B^-1 (d_h - A d_0)``
    and ``f_h = C d_0 + D f_0``, symmetrised (its asymmetry is round-off)."""
    Bi = np.empty((2, 2), U.dtype)
    inv2(U[0:2, 2:4], Bi)
    f0 = np.zeros((2, 4), U.dtype)  # f_0 = [-Bi A | Bi] [d_0; d_h]
    fh = np.zeros((2, 4), U.dtype)
    for r in range(2):
        for c in range(2):
            f0[r, 2 + c] = Bi[r, c]
            for j in range(2):
                f0[r, c] -= Bi[r, j] * U[j, c]
    for r in range(2):
        for c in range(4):
            acc = U[2 + r, c] if c < 2 else 0.0 * U[0, 0]
            for j in range(2):
                acc += U[2 + r, 2 + j] * f0[j, c]
            fh[r, c] = acc
    for c in range(4):
        k[0, c] = f0[1, c]
        k[1, c] = -f0[0, c]
        k[2, c] = -fh[1, c]
        k[3, c] = fh[0, c]
    for r in range(4):
        for c in range(r + 1, 4):
            s = 0.5 * (k[r, c] + k[c, r])
            k[r, c] = s
            k[c, r] = s


@njit(cache=True)
def negatives_sym(P):
    """Negative eigenvalues of a symmetric 2 x 2 (an exactly singular one counts its
    negative part only)."""
    det = P[0, 0] * P[1, 1] - P[0, 1] * P[1, 0]
    if det < 0.0:
        return 1
    if P[0, 0] + P[1, 1] < 0.0:
        return 2 if det > 0.0 else 1
    return 0


@njit(cache=True)
def chain_pivot(S, k, n):
    """The pivot ``P = S_far + k_near`` (n x n) of appending piece k to the chain S."""
    P = np.empty((n, n), S.dtype)
    for r in range(n):
        for c in range(n):
            P[r, c] = S[n + r, n + c] + k[r, c]
    return P


@njit(cache=True)
def chain_eliminate(S, k, n, Pi):
    """S <- over [start; far] after eliminating the middle node, whose pivot's inverse is
    Pi: ``[[S_ss, 0], [0, k_ff]] - X Pi X^T``, ``X = [S_sm; k_fm]`` (real or complex)."""
    X = np.empty((2 * n, n), S.dtype)
    for r in range(n):
        for c in range(n):
            X[r, c] = S[r, n + c]
            X[n + r, c] = k[n + r, c]
    Y = X @ Pi
    T = np.zeros((2 * n, 2 * n), S.dtype)
    for r in range(n):
        for c in range(n):
            T[r, c] = S[r, c]
            T[n + r, n + c] = k[n + r, n + c]
    R = T - Y @ X.T
    for r in range(2 * n):
        for c in range(2 * n):
            S[r, c] = 0.5 * (R[r, c] + R[c, r])


@njit(cache=True)
def chain_add(S, k, n, first, worst):
    """Append a piece of stiffness k (2n x 2n over [near; far], n freedoms a node) to the
    chain S (2n x 2n over [start; last node]), eliminating the last node: S <- over [start;
    far]. Returns the negative pivots eliminated (``first``: S <- k, none); ``worst[0]``
    <- the least of itself and the pivot's conditioning (its least eigenvalue over its
    largest, about: a pivot near singular loses that many digits of S)."""
    if first:
        S[:, :] = k
        return 0
    P = chain_pivot(S, k, n)
    if n == 1:
        neg = 1 if P[0, 0] < 0.0 else 0
        Pi = np.empty((1, 1))
        Pi[0, 0] = 1.0 / P[0, 0]
        ratio = abs(P[0, 0]) / (abs(S[1, 1]) + abs(k[0, 0]))
    else:
        neg = negatives_sym(P)
        Pi = np.empty((2, 2))
        det = inv2(P, Pi)
        big = max(abs(P[0, 0]), abs(P[1, 1]), abs(P[0, 1]))
        ratio = abs(det) / (big * big) if big > 0.0 else 0.0
    worst[0] = min(worst[0], ratio)
    chain_eliminate(S, k, n, Pi)
    return neg


@njit(cache=True)
def chain_add_c(S, k, n, first):
    """``chain_add`` in complex arithmetic (a complex frequency): returns the log of the
    eliminated pivot's determinant (0 for the first piece). The chain's pivots multiply
    the condensed determinant into that of every piece's node kept: ``det D_full = det
    D * prod(det P)`` (block elimination)."""
    if first:
        S[:, :] = k
        return 0j
    P = chain_pivot(S, k, n)
    Pi = np.empty((n, n), S.dtype)
    if n == 1:
        det = P[0, 0]
        Pi[0, 0] = 1.0 / det
    else:
        det = inv2(P, Pi)
    chain_eliminate(S, k, n, Pi)
    return cmath.log(det)


@njit(cache=True)
def segment_cut(p, seg, rho, beta, step, w2, F, ready):
    """``(pieces, ready)``: equal pieces across rho (units of L) of segment seg, k h <=
    step at beta (``segment.segment_pieces``: F, ready) and each piece's proved
    clamped-clamped bound above ``BOUND_MARGIN`` w2 (so that its J0 is 0 and its
    stiffness has no pole up to w2 = (lam_0 L)^4)."""
    pieces, ready = segment_pieces(p, seg, beta, rho, step, F, ready)
    e, m, kGA, rhoI, t, r, k_w = segment_values(p, seg, 1.0)
    shear = math.inf if kGA == 0.0 else kGA
    for _ in range(60):
        if clamped_clamped_bound(e, shear, rhoI, m, t, rho / pieces) > BOUND_MARGIN * w2:
            break
        pieces *= 2
    return pieces, ready


@njit(cache=True)
def member_bending(p, beta, K):
    """K (4 x 4 over the nodal [Y_a, psi_a, Y_b, psi_b], units L = EI_0 = 1) <- the exact
    bending dynamic stiffness of the member whose beam is p at beta = lam_0 L; returns its
    clamped-clamped frequencies below (J0). Cut again with more pieces where an inner
    node's pivot is near singular (:data:`PIVOT_RATIO`)."""
    U = np.empty((4, 4))
    F = np.empty((4, 4, 4))
    k = np.empty((4, 4))
    S = np.empty((4, 4))
    worst = np.empty(1)
    w2 = beta**4
    best = -1.0
    J0 = 0
    for extra in range(PIECE_RETRIES):
        worst[0] = math.inf
        ready = -1
        n_seg = int(p[3])
        start = 0.0
        count = 0
        first = True
        for seg in range(n_seg):
            end = 1.0 if seg == n_seg - 1 else p[HEAD + SEGMENT_WIDTH * seg + X_END] / p[0]
            rho = end - start
            start = end
            pieces, ready = segment_cut(p, seg, rho, beta, PIECE_STEP, w2, F, ready)
            pieces += extra
            ready = piece_matrix(p, seg, beta, rho / pieces, U, F, ready)
            piece_stiffness(U, k)
            for _ in range(pieces):
                count += chain_add(S, k, 2, first, worst)
                first = False
        if worst[0] > best:
            best = worst[0]
            J0 = count
            K[:, :] = S
        if best >= PIVOT_RATIO:
            break
    return J0


@njit(cache=True)
def member_rod(EA, mbar, h, w, K):
    """K (2 x 2 over [u_a, u_b], SI) <- the exact axial dynamic stiffness of segments of
    axial stiffness EA, mass per length mbar and lengths h at w (rad/s); returns the
    member's clamped-clamped axial frequencies below w (J0)."""
    k = np.empty((2, 2))
    J0 = 0
    worst = np.empty(1)
    for j in range(len(EA)):
        mu = w * h[j] * math.sqrt(mbar[j] / EA[j])
        f = EA[j] / h[j] * (mu / math.sin(mu) if mu != 0.0 else 1.0)
        c = math.cos(mu)
        k[0, 0] = f * c
        k[1, 1] = f * c
        k[0, 1] = -f
        k[1, 0] = -f
        J0 += int(math.floor(mu / math.pi))
        J0 += chain_add(K, k, 1, j == 0, worst)
    return J0


@njit(cache=True)
def member_march(p, w1, Z0, xs, out):
    """out[j] <- the state Z = [Y, psi, M, Q] (units L = EI_0 = 1) at xs[j] (ascending, in
    units of L) from Z0 at the member's start, piece by piece (k h <= 1), at ``w1 = (lam_0
    L)^2``: real (Z0 real), or complex with the segments' loss factors (Z0 complex: a
    damped mode, ``segment.segment_piece`` chooses by the type)."""
    U = np.empty((4, 4), Z0.dtype)
    F = np.empty((4, 4, 4), Z0.dtype)
    beta = w1**0.5
    n_seg = int(p[3])
    Z = Z0.copy()
    x = 0.0
    seg = 0
    j = 0
    while j < len(xs):
        end = 1.0 if seg == n_seg - 1 else p[HEAD + SEGMENT_WIDTH * seg + X_END] / p[0]
        target = min(xs[j], end)
        if target > x:
            pieces, _ = segment_piece(p, seg, w1, beta, True, target - x, PIECE_STEP, U, F)
            for _ in range(pieces):
                Z = U @ Z
            x = target
        if xs[j] <= end or seg == n_seg - 1:
            out[j] = Z
            j += 1
        else:
            seg += 1


@njit(cache=True)
def member_stiffnesses(P, p_off, EA, mbar, h, r_off, L, omega, K, J0):
    """K[t] (6 x 6 over the local ``[u_a, w_a, psi_a, u_b, w_b, psi_b]``, SI) <- the exact
    dynamic stiffness at omega (rad/s) of member type t, J0[t] <- its clamped-clamped
    frequencies below omega: type t's beam is ``P[p_off[t]:p_off[t + 1]]``, its rod
    segments ``EA, mbar, h[r_off[t]:r_off[t + 1]]``, its length ``L[t]``."""
    K4 = np.empty((4, 4))
    K2 = np.empty((2, 2))
    for t in range(len(p_off) - 1):
        p = P[p_off[t] : p_off[t + 1]]
        Lt = L[t]
        beta = Lt * (p[2] * omega * omega / p[1]) ** 0.25
        count = member_bending(p, beta, K4)
        r0, r1 = r_off[t], r_off[t + 1]
        count += member_rod(EA[r0:r1], mbar[r0:r1], h[r0:r1], omega, K2)
        J0[t] = count
        place(K[t], K4, K2, p[1] / Lt**3, Lt)


@njit(cache=True)
def place(k, K4, K2, scale, Lt):
    """k (6 x 6 over ``[u_a, w_a, psi_a, u_b, w_b, psi_b]``, SI) <- the bending K4 (units L
    = EI_0 = 1, times ``scale`` = EI_0 / L^3 and L on each rotation) and the rod K2."""
    k[:, :] = 0.0
    for r in range(4):
        br = 1 + r + r // 2  # (1, 2, 4, 5): w_a, psi_a, w_b, psi_b
        dr = Lt if r % 2 == 1 else 1.0
        for c in range(4):
            dc = Lt if c % 2 == 1 else 1.0
            k[br, 1 + c + c // 2] = scale * dr * K4[r, c] * dc
    k[0, 0] = K2[0, 0]
    k[0, 3] = K2[0, 1]
    k[3, 0] = K2[1, 0]
    k[3, 3] = K2[1, 1]


@njit(cache=True)
def scatter(K, kind, T, idx, B):
    """B += every member's local stiffness ``K[kind[i]]`` (6 x 6) turned to the global
    freedoms: ``T[i]`` (6 x 6) maps the freedoms at band positions ``idx[i]`` (-1: none) to
    its local ``[u_a, w_a, psi_a, u_b, w_b, psi_b]`` and carries D's units; B holds D's
    upper band rows (``B[i, k] = D[i, i + k]``, :mod:`.banded`), real or complex."""
    kT = np.empty((6, 6), B.dtype)
    for i in range(len(kind)):
        k = K[kind[i]]
        Ti = T[i]
        for r in range(6):  # kT <- k Ti (loops: BLAS costs more than the 6 x 6 product)
            for c in range(6):
                acc = 0.0 * k[0, 0]
                for j in range(6):
                    acc += k[r, j] * Ti[j, c]
                kT[r, c] = acc
        for a in range(6):
            ga = idx[i, a]
            if ga < 0:
                continue
            for b in range(6):
                gb = idx[i, b]
                if gb < ga:
                    continue
                acc = 0.0 * k[0, 0]
                for r in range(6):
                    acc += Ti[r, a] * kT[r, b]
                B[ga, gb - ga] += acc


@njit(cache=True)
def assemble_members(P, p_off, EA, mbar, h, r_off, L, kind, T, idx, omega, B):
    """D += every member's exact dynamic stiffness at omega (rad/s), turned to the global
    freedoms, D in upper band rows B (``B[i, k] = D[i, i + k]``, :mod:`.banded`).

    Members of one type (the same beam, rod and length: a building's columns) share
    their local stiffness: :func:`member_stiffnesses` computes each type once; member i
    is of type ``kind[i]`` (:func:`scatter`). Returns the members' J0."""
    n_types = len(p_off) - 1
    K = np.empty((n_types, 6, 6))
    J = np.zeros(n_types, dtype=np.int64)
    member_stiffnesses(P, p_off, EA, mbar, h, r_off, L, omega, K, J)
    scatter(K, kind, T, idx, B)
    J0 = 0
    for i in range(len(kind)):
        J0 += J[kind[i]]
    return J0


# -- a complex frequency (damped natural frequencies: mstmm.frame.damped) ---------------


@njit(cache=True)
def bending_pieces(p, beta_top, beta, out):
    """out[seg] <- the pieces of each segment of the member whose beam is p for the
    complex frequencies of a rectangle whose real points have ``|lam_0 L| <= beta_top``
    and all ``|lam_0 L| <= beta``: each piece's proved clamped-clamped bound above
    ``BOUND_MARGIN`` beta_top^4 and k h <= ``WIDE_STEP`` at beta. A piece's
    clamped-clamped frequencies are real (an undamped piece), so its transfer's B block
    is then regular in the whole rectangle: the pieces' stiffnesses have no pole there."""
    F = np.empty((4, 4, 4))
    ready = -1
    start = 0.0
    n_seg = int(p[3])
    for seg in range(n_seg):
        end = 1.0 if seg == n_seg - 1 else p[HEAD + SEGMENT_WIDTH * seg + X_END] / p[0]
        rho = end - start
        start = end
        out[seg], ready = segment_cut(p, seg, rho, beta, WIDE_STEP, beta_top**4, F, ready)


@njit(cache=True)
def member_bending_c(p, w1, pieces, t, K):
    """K (4 x 4, complex) <- the bending dynamic stiffness of the member whose beam is p at
    the complex ``w1 = (lam_0 L)^2 = omega / unit``, segment seg cut in ``pieces[seg]``
    (:func:`bending_pieces`), its stiffnesses times ``1 + i t eta`` (eta its loss factor,
    t the damping scale); returns the log of its inner pivots' determinants."""
    U = np.empty((4, 4), np.complex128)
    F = np.empty((4, 4, 4), np.complex128)
    k = np.empty((4, 4), np.complex128)
    beta = cmath.sqrt(w1)
    log = 0j
    first = True
    start = 0.0
    n_seg = int(p[3])
    for seg in range(n_seg):
        i = HEAD + SEGMENT_WIDTH * seg
        end = 1.0 if seg == n_seg - 1 else p[i + X_END] / p[0]
        h = (end - start) / pieces[seg]
        start = end
        stiff = 1.0 + 1j * t * p[i + COL_ETA]
        if is_general(p, seg):
            field_prepare(p, seg, w1 * w1, stiff, F)
            field_exp(F, h, U)
        else:
            e = p[i + COL_EI] / p[1] * stiff
            piece_transfer_c(beta * cmath.sqrt(cmath.sqrt(p[i + COL_MBAR] / p[2] / e)), e, h, U)
        piece_stiffness(U, k)
        for _ in range(pieces[seg]):
            log += chain_add_c(K, k, 2, first)
            first = False
    return log


@njit(cache=True)
def rod_pieces(EA, mbar, h, top, omega, out):
    """out[j] <- the pieces of rod segment j for the complex frequencies of a rectangle
    whose real points have ``|omega| <= top`` and all ``|omega| <= omega`` (rad/s): ``|mu|
    <= 1`` at top, below the first zero of sin mu (a real pi), and ``|mu| <= WIDE_STEP``
    at omega."""
    for j in range(len(EA)):
        a = h[j] * math.sqrt(mbar[j] / EA[j])
        out[j] = max(1, int(math.ceil(top * a)), int(math.ceil(omega * a / WIDE_STEP)))


@njit(cache=True)
def member_rod_c(EA, mbar, h, eta, pieces, t, w, K):
    """``member_rod`` at the complex w (rad/s), segment j in ``pieces[j]``, its EA times
    ``1 + i t eta[j]``; returns the log of its inner pivots."""
    k = np.empty((2, 2), np.complex128)
    log = 0j
    first = True
    for j in range(len(EA)):
        hj = h[j] / pieces[j]
        ea = EA[j] * (1.0 + 1j * t * eta[j])
        mu = w * hj * cmath.sqrt(mbar[j] / ea)
        f = ea / hj * (mu / cmath.sin(mu) if mu != 0.0 else 1.0)
        c = cmath.cos(mu)
        k[0, 0] = f * c
        k[1, 1] = f * c
        k[0, 1] = -f
        k[1, 0] = -f
        for _ in range(pieces[j]):
            log += chain_add_c(K, k, 1, first)
            first = False
    return log


@njit(cache=True)
def assemble_members_c(P, p_off, EA, mbar, h, r_off, L, kind, T, idx, bp, rp, eta, s, omega, B):
    """:func:`assemble_members` at the complex omega (rad/s), B complex; each type's
    segments in the pieces ``bp[t, seg]`` (bending) and ``rp[r_off[t]:r_off[t + 1]]``
    (rod), the loss factors (the beams' own, the rods' ``eta``) scaled by s. Returns the
    log of every member's inner pivots' determinants: D's determinant times their product
    is that of the frame with every piece's node kept, which has no pole where the
    pieces have none."""
    n_types = len(p_off) - 1
    K = np.zeros((n_types, 6, 6), np.complex128)
    logs = np.zeros(n_types, np.complex128)
    K4 = np.empty((4, 4), np.complex128)
    K2 = np.empty((2, 2), np.complex128)
    for t in range(n_types):
        p = P[p_off[t] : p_off[t + 1]]
        Lt = L[t]
        w1 = Lt * Lt * math.sqrt(p[2] / p[1]) * omega
        logs[t] = member_bending_c(p, w1, bp[t], s, K4)
        r0, r1 = r_off[t], r_off[t + 1]
        logs[t] += member_rod_c(
            EA[r0:r1], mbar[r0:r1], h[r0:r1], eta[r0:r1], rp[r0:r1], s, omega, K2
        )
        place(K[t], K4, K2, p[1] / Lt**3, Lt)
    scatter(K, kind, T, idx, B)
    log = 0j
    for i in range(len(kind)):
        log += logs[kind[i]]
    return log

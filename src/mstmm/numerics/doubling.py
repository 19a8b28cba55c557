"""A finite structure of N identical cells (``repeat = N``, issue 23): its Wittrick-Williams
count and its characteristic function in O(log N) per frequency, so that a cluster of N
roots costs O(N log N) instead of N walks over N components.

**The cell's transfer, squared.** The cell's transfer matrix T (Z_L = T Z_0, the paper's
Eqs. (2)-(4) with each component's unknowns eliminated) is kept as its increment E = T - I
(``cell_increment``): a short cell's transfer is I, its static terms, and inertia terms
(lam h)^4 small; multiplied as I + E, the inertia on the diagonal would be lost to the
round-off of the 1 beside it, and N cells would carry that loss N times. The increments
of 2^m cells are squared, (I + E)^2 = I + 2E + E^2 (``square_increment``), while a block's
inertia stays small against its static stiffness (``SWITCH``; its waves grow by at most
e across it).

**The count by substructures.** A block's dynamic stiffness D (end forces
f = (Q_0, -M_0, -Q_L, M_L) against end displacements d = (Y_0, theta_0, Y_L, theta_L),
symmetric by reciprocity; ``transfer_stiffness``) exists away from the block's
clamped-clamped frequencies. Two blocks a, b joined at a joint share its two displacements;
condensing them (Wittrick and Williams: J = J0 + s{K}, K the stiffness of the retained
freedoms, J0 the count with them held)

    S = D_a[L, L] + D_b[0, 0],    J0_ab = J0_a + J0_b + s{S},
    D_ab = [[D_a00 - D_a0L S^-1 D_aL0,  -D_a0L S^-1 D_b0L],
            [-D_bL0 S^-1 D_aL0,          D_bLL - D_bL0 S^-1 D_b0L]]

(``join``); J0 of one cell is its kernel's count. Beyond the switch the blocks of 2^m cells
are doubled by their stiffness (``chain_power``), which no growing wave swamps. At the
structure's ends the displacements an end condition leaves free are retained: the count of
the whole is J0_N + s{D_N[free, free]} (``structure_at``).

**The characteristic function** is not det D_N[free, free]: its poles (the clamped
structure's frequencies) interlace the roots, and next to one its determinant cancels
large terms (a root 3e-7 from a pole lost 6 digits). It is the determinant of T_N's rows
the right end's conditions zero and columns of the left end's unknowns, carried as the
plane of those unknowns through second compounds (``characteristic``): no poles but the
components' own frequencies, and no growing wave swamps the other.

Units are the cell kernel's (its first segment's L = EI = mbar = 1); counts and signs do
not depend on them.
"""

import math

import numpy as np

from mstmm.jit import njit

from .bloch import (
    bloch_work,
)
from .layout import (
    PAIRS,
    POLE_GUARD,
)
from .linalg import (
    solve_in_place,
)
from .search import (
    at_scale,
    brent_step,
    near_pole,
    pole_data,
)
from .segment import (
    is_general,
    segment_piece_r,
)
from .walk import (
    STOP_END,
    STOP_EVENT,
    walk_next,
)

#: Most joins of ``chain_power`` (N < 2**62).
MAX_LEVELS = 62
#: Most bisections of one root's bracket on the count (it halves a relative width of
#: at most 1 down to round-off well within this).
MAX_HALVINGS = 200
EPS = 2.220446049250313e-16
#: The search starts this far below the first frequency's scale (``repeated_search``), and
#: 100 times lower at each of at most START_TRIES tries, until the count there holds only
#: the rigid-body modes.
START = 1e-3
START_TRIES = 12
#: Most doublings of the top of the search until the count there holds the modes asked for.
MAX_DOUBLINGS = 200
#: Most Brent iterations on the characteristic function in a bracket holding one root.
MAX_BRENT = 100


@njit(cache=True)
def negatives2(a, b, c):
    """Negative eigenvalues of the symmetric [[a, b], [b, c]]."""
    det = a * c - b * b
    if det < 0.0:
        return 1
    if det > 0.0:
        return 2 if a < 0.0 else 0
    return int(a < 0.0) + int(c < 0.0)


@njit(cache=True)
def join(Ja, Da, Jb, Db, Dout, S, R, t):
    """(J0, ok) of block a followed by block b, Dout <- their condensed stiffness (module
    docstring; Dout may be Da or Db). S (2x2), R (2x4), t (4x4): scratch. Not ok where S
    is singular or a value is not finite (a frequency of the joined block's parts)."""
    for r in range(2):
        for c in range(2):
            S[r, c] = Da[2 + r, 2 + c] + Db[r, c]
    neg = negatives2(S[0, 0], 0.5 * (S[0, 1] + S[1, 0]), S[1, 1])
    for r in range(2):  # R <- S^-1 [D_aL0, D_b0L]
        for c in range(2):
            R[r, c] = Da[2 + r, c]
            R[r, 2 + c] = Db[r, 2 + c]
    if not solve_in_place(S, R, 4):
        return 0, False
    for r in range(2):
        for c in range(2):
            a0 = 0.0
            a1 = 0.0
            b1 = 0.0
            for j in range(2):
                a0 += Da[r, 2 + j] * R[j, c]
                a1 += Da[r, 2 + j] * R[j, 2 + c]
                b1 += Db[2 + r, j] * R[j, 2 + c]
            t[r, c] = Da[r, c] - a0
            t[r, 2 + c] = -a1
            t[2 + r, 2 + c] = Db[2 + r, 2 + c] - b1
    for r in range(2):
        for c in range(2):
            t[2 + r, c] = t[c, 2 + r]
    ok = True
    for r in range(4):
        for c in range(4):
            Dout[r, c] = t[r, c]
            ok = ok and math.isfinite(t[r, c])
    return Ja + Jb + neg, ok


@njit(cache=True)
def chain_power(Jc, Dc, n, DN, P, S, R, t):
    """(J0, ok) of n cells end to end (cell: count Jc, stiffness Dc), DN <- their condensed
    stiffness; binary powers of the cell, 2 log2 n joins at most. P, t: 4x4, S: 2x2, R: 2x4
    scratch."""
    P[:, :] = Dc
    Jp = Jc
    have = False
    J = 0
    m = n
    for _ in range(MAX_LEVELS):
        if m & 1:
            if have:
                J, ok = join(J, DN, Jp, P, DN, S, R, t)
                if not ok:
                    return J, False
            else:
                DN[:, :] = P
                J = Jp
                have = True
        m >>= 1
        if m == 0:
            break
        Jp, ok = join(Jp, P, Jp, P, P, S, R, t)
        if not ok:
            return J, False
    return J, True


@njit(cache=True)
def end_freedoms(D, free, K):
    """K <- D[free, free] (free: the retained end displacements' indices into d, the first
    ``len`` entries; -1 ends the list); returns how many."""
    n = 0
    for i in range(4):
        if free[i] >= 0:
            n += 1
    for r in range(n):
        for c in range(n):
            K[r, c] = D[free[r], free[c]]
    return n


@njit(cache=True)
def negatives(K, n):
    """Negative eigenvalues of the symmetric n x n K (n <= 4), by cyclic Jacobi rotations
    until the off-diagonal part is round-off against the diagonal; K is overwritten."""
    for _ in range(50):
        off = 0.0
        diag = 0.0
        for i in range(n):
            diag += K[i, i] * K[i, i]
            for j in range(i + 1, n):
                off += K[i, j] * K[i, j]
        if off <= 1e-32 * diag or off == 0.0:
            break
        for i in range(n):
            for j in range(i + 1, n):
                if K[i, j] == 0.0:
                    continue
                theta = 0.5 * (K[j, j] - K[i, i]) / K[i, j]
                t = (1.0 if theta >= 0.0 else -1.0) / (abs(theta) + math.sqrt(theta * theta + 1.0))
                c = 1.0 / math.sqrt(t * t + 1.0)
                sn = t * c
                for k in range(n):  # K <- K G (columns i, j)
                    ki = K[k, i]
                    kj = K[k, j]
                    K[k, i] = c * ki - sn * kj
                    K[k, j] = sn * ki + c * kj
                for k in range(n):  # K <- G^T K (rows i, j)
                    ik = K[i, k]
                    jk = K[j, k]
                    K[i, k] = c * ik - sn * jk
                    K[j, k] = sn * ik + c * jk
    neg = 0
    for i in range(n):
        if K[i, i] < 0.0:
            neg += 1
    return neg


@njit(cache=True)
def krylov_s_minus_1(x):
    """S(x) - 1 = (cosh x + cos x) / 2 - 1 = x^4/4! + x^8/8! + ... for |x| <= 1.5, to
    round-off of itself (the difference loses x^-4 eps of it)."""
    x4 = x * x * x * x
    term = x4 / 24.0
    acc = term
    k = 4
    while abs(term) > 1e-17 * abs(acc):
        term *= x4 / ((k + 1) * (k + 2) * (k + 3) * (k + 4))
        acc += term
        k += 4
    return acc


@njit(cache=True)
def add_increment(Eu, E, S):
    """E <- Eu + E + Eu E: the increment of (I + Eu)(I + E) (4x4; S: scratch)."""
    for i in range(4):
        for j in range(4):
            acc = Eu[i, j] + E[i, j]
            for k in range(4):
                acc += Eu[i, k] * E[k, j]
            S[i, j] = acc
    for i in range(4):
        for j in range(4):
            E[i, j] = S[i, j]


@njit(cache=True)
def cell_increment(event, w, p, E, work):
    """E <- T - I for the cell's transfer matrix Z_L = T Z_0 at the real w (kernel units of
    p), by the walk (``walk.walk_next``): each piece's transfer, each component's point
    matrix A - B Cq^-1 Cz (its unknowns q eliminated: Cz Z + Cq q = 0, Z+ = A Z + B q),
    multiplied as increments, (I + Eu)(I + E) = I + Eu + E + Eu E. A short cell's transfer
    is I plus its static terms plus inertia terms (lam h)^4 small, those on the diagonal
    lost to round-off in I + them: an Euler-Bernoulli piece's diagonal S(lam h) - 1 is
    summed as a series instead (``krylov_s_minus_1``; a general segment's is the
    difference), so that N cells multiplied keep them. False where a component constrains
    the state (no point matrix) or stands at its own frequency."""
    L = p[0]
    w1 = w * L * L * math.sqrt(p[2] / p[1])
    beta = math.sqrt(w1)
    X, S, Cz, Cq, Ad, B, ev_mass, C, rhs, row_scale, N, xp, Y, U, Ff = work[:15]
    E[:, :] = 0.0
    n_ev = int(p[4])
    pos = 0.0
    seg = 0
    r = 0
    while True:
        sg, stop, what, row, r, seg = walk_next(p, r, seg, pos, n_ev, math.inf)
        rho = (stop - pos) / L
        if rho > 0.0:
            pieces, kh = segment_piece_r(p, sg, w1, beta, False, rho, 1.0, U, Ff)
            d = krylov_s_minus_1(kh) if not is_general(p, sg) else 0.0
            for i in range(4):
                U[i, i] = d if not is_general(p, sg) else U[i, i] - 1.0
            for _ in range(pieces):
                add_increment(U, E, S)
            pos = stop
        if what == STOP_END:
            break
        if what != STOP_EVENT:
            continue
        nc, nq = event(p, row, w1 * w1, Cz, Cq, Ad, B, ev_mass)
        if nc != nq:
            return False
        if nq > 0:
            Q = np.empty((nq, nq))
            R = np.empty((nq, 4))
            for i in range(nq):
                for j in range(nq):
                    Q[i, j] = Cq[i, j]
                for j in range(4):
                    R[i, j] = Cz[i, j]
            if not solve_in_place(Q, R, 4):
                return False
        for i in range(4):
            for j in range(4):
                acc = Ad[i, j] - (1.0 if i == j else 0.0)
                for k in range(nq):
                    acc -= B[i, k] * R[k, j]
                U[i, j] = acc
        add_increment(U, E, S)
    return True


@njit(cache=True)
def plus_identity(E, T):
    """T <- I + E (4x4)."""
    for i in range(4):
        for j in range(4):
            T[i, j] = E[i, j] + (1.0 if i == j else 0.0)


@njit(cache=True)
def transfer_stiffness(T, D):
    """D <- the dynamic stiffness (module docstring) of the transfer Z_L = T Z_0, with
    Z = (d, f), d = (Y, theta), f = (M, Q): f_0 = G (d_L - A d_0), f_L = (C - E G A) d_0 +
    E G d_L for T = [[A, Bm], [C, E]] and G = Bm^-1. False where Bm is singular (a
    frequency of the block clamped at both ends)."""
    det = T[0, 2] * T[1, 3] - T[0, 3] * T[1, 2]
    if det == 0.0 or not math.isfinite(det):
        return False
    g00 = T[1, 3] / det
    g01 = -T[0, 3] / det
    g10 = -T[1, 2] / det
    g11 = T[0, 2] / det
    ga = np.empty((2, 2))  # G A
    eg = np.empty((2, 2))  # E G
    for i in range(2):
        for j in range(2):
            gi0 = g00 if i == 0 else g10
            gi1 = g01 if i == 0 else g11
            ga[i, j] = gi0 * T[0, j] + gi1 * T[1, j]
            eg[i, j] = T[2 + i, 2] * (g00 if j == 0 else g01) + T[2 + i, 3] * (
                g10 if j == 0 else g11
            )
    cega = np.empty((2, 2))  # C - E G A
    for i in range(2):
        for j in range(2):
            cega[i, j] = T[2 + i, j] - (eg[i, 0] * T[0, j] + eg[i, 1] * T[1, j])
    g = ((g00, g01), (g10, g11))
    for j in range(2):
        # (Q_0, -M_0) = (f_0[1], -f_0[0]), f_0 = -G A d_0 + G d_L
        D[0, j] = -ga[1, j]
        D[0, 2 + j] = g[1][j]
        D[1, j] = ga[0, j]
        D[1, 2 + j] = -g[0][j]
        # (-Q_L, M_L) = (-f_L[1], f_L[0])
        D[2, j] = -cega[1, j]
        D[2, 2 + j] = -eg[1, j]
        D[3, j] = cega[0, j]
        D[3, 2 + j] = eg[0, j]
    for i in range(4):
        for j in range(i + 1, 4):
            v = 0.5 * (D[i, j] + D[j, i])
            D[i, j] = v
            D[j, i] = v
    return True


@njit(cache=True)
def square_increment(E, E2):
    """E2 <- 2 E + E E: the increment of (I + E)^2 (4x4, real)."""
    for i in range(4):
        for j in range(4):
            acc = 2.0 * E[i, j]
            for k in range(4):
                acc += E[i, k] * E[k, j]
            E2[i, j] = acc


@njit(cache=True)
def joined_count(Ja, Ta, Jb, Tb, Da, Db, S):
    """(J0, ok) of block a followed by block b from their transfers (Wittrick-Williams: the
    negative eigenvalues of the joint's stiffness added). Da, Db: 4x4, S: 2x2 scratch."""
    if not (transfer_stiffness(Ta, Da) and transfer_stiffness(Tb, Db)):
        return 0, False
    for r in range(2):
        for c in range(2):
            S[r, c] = Da[2 + r, 2 + c] + Db[r, c]
    return Ja + Jb + negatives2(S[0, 0], 0.5 * (S[0, 1] + S[1, 0]), S[1, 1]), True



@njit(cache=True)
def compound(T, C):
    """C <- the second compound of the 4x4 T (6x6: its 2x2 minors, rows and columns in the
    order of PAIRS): the map T induces on planes of states, whose powers carry the plane
    of the solutions that meet the left end's conditions without the growing wave
    swamping the other (the stable form of the paper's characteristic function)."""
    for a in range(6):
        i, j = PAIRS[a]
        for b in range(6):
            k, l = PAIRS[b]
            C[a, b] = T[i, k] * T[j, l] - T[i, l] * T[j, k]


@njit(cache=True)
def apply_scaled(C, v, tmp):
    """v <- C v / max|C v|; returns log max|C v| (v: 6, tmp: 6 scratch)."""
    big = 0.0
    for a in range(6):
        acc = 0.0
        for b in range(6):
            acc += C[a, b] * v[b]
        tmp[a] = acc
        big = max(big, abs(acc))
    if big == 0.0 or not math.isfinite(big):
        return -math.inf if big == 0.0 else math.inf
    for a in range(6):
        v[a] = tmp[a] / big
    return math.log(big)


@njit(cache=True)
def square_scaled(C, C2):
    """C2 <- C C / max|C C|; returns log max|C C|."""
    big = 0.0
    for a in range(6):
        for b in range(6):
            acc = 0.0
            for k in range(6):
                acc += C[a, k] * C[k, b]
            C2[a, b] = acc
            big = max(big, abs(acc))
    if big == 0.0 or not math.isfinite(big):
        return -math.inf if big == 0.0 else math.inf
    for a in range(6):
        for b in range(6):
            C2[a, b] /= big
    return math.log(big)


@njit(cache=True)
def characteristic(Tf, TB, q, ends, cw):
    """The structure's characteristic function as (mantissa, log): det of the rows of
    T_N = TB^q Tf that the right end's conditions zero and the columns of the left end's
    unknowns (``ends``: the compound indices of both), carried as the plane of the left
    end's unknowns through the second compounds of Tf and of TB's binary powers, scaled at
    every step: free of the poles of the stiffness and of the growing waves' round-off.
    cw: (C, C2, v, tmp) scratch."""
    C, C2, v, tmp = cw
    for a in range(6):
        v[a] = 0.0
    v[ends[0]] = 1.0
    compound(Tf, C)
    log = apply_scaled(C, v, tmp)
    if q > 0:
        compound(TB, C)
        scale = 0.0  # log of the factor C (as held) was divided by
        m = q
        while True:
            if m & 1:
                log += apply_scaled(C, v, tmp) + scale
            m >>= 1
            if m == 0:
                break
            scale = 2.0 * scale + square_scaled(C, C2)
            C[:, :] = C2
    return v[ends[1]], log


#: The transfer of a block is squared while its inertia (lam h)^4 ~ |T[Q, Y]| (h / h_cell)^3
#: stays below this: beyond, its waves grow and the stiffness takes over (``structure_at``).
SWITCH = 1.0


@njit(cache=True)
def repeated_work(levels):
    """Scratch of ``structure_at``: the powers T^(2^j) of the cell (j <= levels) and their
    counts, the first block's transfer, the stiffness of a block, of the chain, of a power,
    three more 4x4, the join's 2x2 and 2x4."""
    return (
        np.zeros((levels + 1, 4, 4)),
        np.zeros(levels + 1, dtype=np.int64),
        np.zeros((4, 4)),
        np.zeros((4, 4)),
        np.zeros((4, 4)),
        np.zeros((4, 4)),
        np.zeros((4, 4)),
        np.zeros((4, 4)),
        np.zeros((4, 4)),
        np.zeros((2, 2)),
        np.zeros((2, 4)),
        np.zeros((4, 4)),
        (np.zeros((6, 6)), np.zeros((6, 6)), np.zeros(6), np.zeros(6)),
    )


@njit(cache=True)
def structure_at(event, count, w, p, n_cells, ends, free, work, mats):
    """At the real w (rad/s), for ``n_cells`` cells (p: the cell clamped at both ends, its
    kernel's ``event`` and ``count``): (J, J0, g, ok) with J the natural frequencies of
    the whole structure below w (Wittrick-Williams), J0 those of the structure clamped at
    both ends (the poles of g) and g = det D_N[free, free] (1 when no end freedom is
    retained). The cell's transfer is squared while a block's inertia is small against its
    static stiffness (``SWITCH``): 2^m cells; the first block, 2^m + (n_cells mod 2^m)
    cells, and the block of 2^m then enter by their stiffness (exact now: inertia and
    static stiffness alike), the rest by doubling the stiffness (``chain_power``), whose
    waves no longer grow across a block. ``work``: ``bloch_work``; ``mats``:
    ``repeated_work``. Not ok where a stiffness does not exist (a clamped-clamped
    frequency of a block)."""
    Tp, Jp, Tf, Tt, Dc, DN, Pw, A, K, S, R, t, cw = mats
    levels = Tp.shape[0] - 1
    Ep = Tp  # the increments T - I of the powers of the cell
    if not cell_increment(event, w, p, Ep[0], work):
        return 0, 0.0, 0.0, False
    Jp[0] = count(w, p)
    m = 0
    while m < levels and (1 << (m + 1)) <= n_cells:
        inertia = abs(Ep[m, 3, 0]) * float(1 << (3 * m)) if m < 20 else math.inf
        if inertia >= SWITCH:
            break
        square_increment(Ep[m], Ep[m + 1])
        plus_identity(Ep[m], Tt)
        Jn, ok = joined_count(Jp[m], Tt, Jp[m], Tt, Dc, DN, S)
        if not ok:
            return 0, 0.0, 0.0, False
        Jp[m + 1] = Jn
        m += 1
    # the first block: 2^m cells and the remainder's powers of the cell after them
    Ef = Pw
    Ef[:, :] = Ep[m]
    Jf = Jp[m]
    rest = n_cells & ((1 << m) - 1)
    for j in range(m):
        if rest & (1 << j):
            plus_identity(Ef, Tf)
            plus_identity(Ep[j], Tt)
            Jf, ok = joined_count(Jf, Tf, Jp[j], Tt, Dc, DN, S)
            if not ok:
                return 0, 0.0, 0.0, False
            add_increment(Ep[j], Ef, t)
    plus_identity(Ef, Tf)
    plus_identity(Ep[m], Tt)  # the block of 2^m cells
    if not transfer_stiffness(Tf, DN):
        return 0, 0.0, 0.0, False
    J0 = Jf
    q = (n_cells >> m) - 1
    if q > 0:
        if not transfer_stiffness(Tt, Dc):
            return 0, 0.0, 0.0, False
        Jq, ok = chain_power(Jp[m], Dc, q, Pw, A, S, R, t)
        if not ok:
            return 0, 0.0, 0.0, False
        J0, ok = join(J0, DN, Jq, Pw, DN, S, R, t)
        if not ok:
            return 0, 0.0, 0.0, False
    nf = end_freedoms(DN, free, K)
    neg = negatives(K, nf)
    fm, fl = characteristic(Tf, Tt, (n_cells >> m) - 1, ends, cw)
    return J0 + neg, fm, fl, True


@njit(cache=True)
def levels_of(n):
    """floor(log2 n) for n >= 1."""
    m = 0
    while (n >> (m + 1)) > 0:
        m += 1
    return m


@njit(cache=True)
def guarded(own, w):
    """w, or w (1 - POLE_GUARD) when w lies within POLE_GUARD of a component's own frequency
    (the count is not defined exactly there: ``search.off_pole``)."""
    at = near_pole(own, w)
    return w if math.isnan(at) else at * (1.0 - POLE_GUARD)


@njit(cache=True)
def value_at(event, count, x, p, n_cells, ends, free, work, mats, ref):
    """The characteristic function at x as mantissa exp(log - ref) (``search.at_scale``:
    never zero where the function is not; next to a component's own frequency its log
    moves by hundreds across a bracket), and whether it exists."""
    _, fm, fl, ok = structure_at(event, count, x, p, n_cells, ends, free, work, mats)
    return at_scale(fm, fl, ref), ok


@njit(cache=True)
def brent(event, count, a, fa, b, fb, p, n_cells, ends, free, work, mats, ref):
    """Brent's method on the characteristic function (``characteristic``, values scaled by
    exp(-ref)) across [a, b], fa and fb of opposite signs: (root, converged)."""
    c, fc = a, fa
    d = e = b - a
    for _ in range(MAX_BRENT):
        if (fb > 0.0) == (fc > 0.0):
            c, fc = a, fa
            d = e = b - a
        if abs(fc) < abs(fb):
            a, b, c = b, c, b
            fa, fb, fc = fb, fc, fb
        tol = 2.0 * EPS * abs(b)
        m = 0.5 * (c - b)
        if abs(m) <= tol or fb == 0.0:
            return b, True
        d, e = brent_step(a, b, c, fa, fb, fc, d, e, m, tol)
        a, fa = b, fb
        b = b + (d if abs(d) > tol else (tol if m > 0.0 else -tol))
        fb, ok = value_at(event, count, b, p, n_cells, ends, free, work, mats, ref)
        if not ok:
            return b, False
    return b, False


#: A root from Brent is kept where the count steps within this of it (relative): the count
#: of 1,000 spaced resonators steps 4e-14 beside the root that the function puts right.
CONFIRM = 1e-12


@njit(cache=True)
def both_sides(event, count, x, h, p, n_cells, ends, free, work, mats):
    """The count and the characteristic function's mantissa at x - h and x + h: (J1, f1,
    J2, f2, ok)."""
    J1, f1, _, ok1 = structure_at(event, count, x - h, p, n_cells, ends, free, work, mats)
    J2, f2, _, ok2 = structure_at(event, count, x + h, p, n_cells, ends, free, work, mats)
    return J1, f1, J2, f2, ok1 and ok2


@njit(cache=True)
def steps_at(event, count, x, h, Ja, p, n_cells, ends, free, work, mats):
    """Whether the count is Ja at x - h and Ja + 1 at x + h (one root between)."""
    J1, _, J2, _, ok = both_sides(event, count, x, h, p, n_cells, ends, free, work, mats)
    return ok and J1 == Ja and J2 == Ja + 1


@njit(cache=True)
def flips_at(event, count, x, h, ma, p, n_cells, ends, free, work, mats):
    """Whether the characteristic function has the sign of ``ma`` at x - h and the other
    at x + h."""
    _, f1, _, f2, ok = both_sides(event, count, x, h, p, n_cells, ends, free, work, mats)
    return ok and (f1 > 0.0) == (ma > 0.0) and (f2 > 0.0) != (ma > 0.0)


#: The distances (relative) at which a root's count or function is read for being clean
#: around it: a root is taken from the one that is clean at all of them.
CLEAN = (1e-13, 1e-12, 1e-11, 1e-10)


@njit(cache=True)
def clean_count(event, count, x, Ja, p, n_cells, ends, free, work, mats):
    """``steps_at`` at every distance of CLEAN."""
    for r in CLEAN:
        if not steps_at(event, count, x, r * x, Ja, p, n_cells, ends, free, work, mats):
            return False
    return True


@njit(cache=True)
def clean_sign(event, count, x, ma, p, n_cells, ends, free, work, mats):
    """``flips_at`` at every distance of CLEAN."""
    for r in CLEAN:
        if not flips_at(event, count, x, r * x, ma, p, n_cells, ends, free, work, mats):
            return False
    return True


@njit(cache=True)
def structure_beside(event, count, mid, a, b, p, n_cells, ends, free, work, mats):
    """``structure_at`` at mid, or just above it where mid is a clamped-clamped frequency
    of a block (no stiffness there): (mid, J, mantissa, log, ok), not ok where neither
    exists inside (a, b)."""
    J, fm, fl, ok = structure_at(event, count, mid, p, n_cells, ends, free, work, mats)
    if not ok:
        mid = mid * (1.0 + 64.0 * EPS)
        J, fm, fl, ok = structure_at(event, count, mid, p, n_cells, ends, free, work, mats)
        ok = ok and a < mid < b
    return mid, J, fm, fl, ok


@njit(cache=True)
def count_bisect(event, count, a, b, Ja, p, n_cells, ends, free, work, mats):
    """The one root in (a, b] (the count Ja at a, Ja + 1 at b) by bisection on the count
    down to round-off: (root, converged)."""
    for _ in range(MAX_HALVINGS):
        mid = 0.5 * (a + b)
        if not (a < mid < b) or b - a <= 4.0 * EPS * b:
            return mid, True
        mid, J, _, _, ok = structure_beside(
            event, count, mid, a, b, p, n_cells, ends, free, work, mats
        )
        if not ok:
            return 0.5 * (a + b), False
        if J <= Ja:
            a = mid
        else:
            b = mid
    return 0.5 * (a + b), False


@njit(cache=True)
def own_inside(own, a, b):
    """Whether a component's own frequency (a pole of the characteristic function) lies in
    [a, b]."""
    j = np.searchsorted(own, a)
    return j < own.shape[0] and own[j] <= b


@njit(cache=True)
def repeated_roots(event, count, sizes, osc, p, n_cells, ends, free, lo, hi, out, mult, flags):
    """The natural frequencies of the structure in (lo, hi] (rad/s), the lowest out.size of
    them: isolated by bisection on the count (a piece holding one root, or a cluster
    narrower than round-off), each then refined by Brent on the characteristic function
    where it changes sign across its piece and no component's own frequency lies in it
    (kept where the count steps within CONFIRM of it; else the count's bisection where the
    count is clean around its root, else Brent's where the function's sign is, else
    Brent's not trusted), else by bisection on the count to round-off. Writes out[k] (the
    root), mult[k] (its multiplicity), flags[k] (1: not converged); returns (k, certified):
    how many distinct roots were written and whether every count could be taken."""
    own = pole_data(osc(p))[0]
    work = bloch_work(p, sizes, np.float64)
    mats = repeated_work(levels_of(n_cells))
    certified = True
    lo = guarded(own, lo)
    hi = guarded(own, hi)
    Jl, fml, fll, okl = structure_at(event, count, lo, p, n_cells, ends, free, work, mats)
    Jh, fmh, flh, okh = structure_at(event, count, hi, p, n_cells, ends, free, work, mats)
    if not (okl and okh):
        return 0, False
    # a stack of pieces (a, b) with their counts and function values, the lowest on top
    cap = 8 * MAX_LEVELS + MAX_HALVINGS
    sx = np.empty((cap, 2))
    sj = np.empty((cap, 2), dtype=np.int64)
    sm = np.empty((cap, 2))
    sl = np.empty((cap, 2))
    sx[0, 0], sx[0, 1] = lo, hi
    sj[0, 0], sj[0, 1] = Jl, Jh
    sm[0, 0], sm[0, 1] = fml, fmh
    sl[0, 0], sl[0, 1] = fll, flh
    top = 1
    k = 0
    while top > 0 and k < out.size:
        top -= 1
        a, b = sx[top, 0], sx[top, 1]
        Ja, Jb = sj[top, 0], sj[top, 1]
        ma, mb = sm[top, 0], sm[top, 1]
        la, lb = sl[top, 0], sl[top, 1]
        if Jb <= Ja:
            continue
        if Jb - Ja == 1 and (ma > 0.0) != (mb > 0.0) and not own_inside(own, a, b):
            ref = max(la, lb)
            fa = at_scale(ma, la, ref)
            fb = at_scale(mb, lb, ref)
            root, conv = brent(event, count, a, fa, b, fb, p, n_cells, ends, free, work, mats, ref)
            if not steps_at(
                event, count, root, CONFIRM * root, Ja, p, n_cells, ends, free, work, mats
            ):
                # the count does not step there: either the function lost its digits beside
                # this root (a cluster at a band edge of the cells) or the count did (waves
                # that grow by e^2 a cell); the one that is clean around its root wins
                by_count, c_conv = count_bisect(
                    event, count, a, b, Ja, p, n_cells, ends, free, work, mats
                )
                if c_conv and clean_count(
                    event, count, by_count, Ja, p, n_cells, ends, free, work, mats
                ):
                    root = by_count
                elif not clean_sign(event, count, root, ma, p, n_cells, ends, free, work, mats):
                    conv = False  # neither: not trusted
            out[k] = root
            mult[k] = 1
            flags[k] = 0 if conv else 1
            k += 1
            continue
        mid = guarded(own, 0.5 * (a + b))
        if not (a < mid < b) or b - a <= 4.0 * EPS * b:  # round-off wide: one value
            out[k] = 0.5 * (a + b)
            mult[k] = Jb - Ja
            flags[k] = 0
            k += 1
            continue
        mid, Jm, mm, lm, ok = structure_beside(
            event, count, mid, a, b, p, n_cells, ends, free, work, mats
        )
        if not ok:
            certified = False
            out[k] = 0.5 * (a + b)
            mult[k] = Jb - Ja
            flags[k] = 1
            k += 1
            continue
        if Jm < Ja or Jm > Jb:  # counts out of order: not certified
            certified = False
            Jm = max(Ja, min(Jb, Jm))
        if top + 2 > cap:
            certified = False
            break
        # the upper half first: the lower one is taken next
        sx[top, 0], sx[top, 1] = mid, b
        sj[top, 0], sj[top, 1] = Jm, Jb
        sm[top, 0], sm[top, 1] = mm, mb
        sl[top, 0], sl[top, 1] = lm, lb
        top += 1
        sx[top, 0], sx[top, 1] = a, mid
        sj[top, 0], sj[top, 1] = Ja, Jm
        sm[top, 0], sm[top, 1] = ma, mm
        sl[top, 0], sl[top, 1] = la, lm
        top += 1
    return k, certified


@njit(cache=True)
def repeated_search(
    event, count, sizes, osc, p, n_cells, ends, free, rigid, want, lo, hi, scale, out, mult,
    flags,
):  # fmt: skip
    """``repeated_roots`` from a start below every elastic root (START times the smaller of
    ``scale`` and the lowest own frequency, lowered until the count there is ``rigid``, the
    rigid-body modes) up to hi, or (hi <= 0) up to where the count reaches ``want`` (the
    top doubled from ``scale``); from max(lo, start) in the first case. Returns (k,
    certified, started): started False where the cells have no transfer matrix (a
    component that constrains the state) or no start was found: the general search runs
    instead."""
    own = pole_data(osc(p))[0]
    work = bloch_work(p, sizes, np.float64)
    mats = repeated_work(levels_of(n_cells))
    first = min(scale, own[0]) if own.shape[0] > 0 else scale
    start = START * first
    found = False
    for _ in range(START_TRIES):
        J, _, _, ok = structure_at(event, count, start, p, n_cells, ends, free, work, mats)
        if not ok:
            return 0, False, False
        if J == rigid:
            found = True
            break
        start *= 0.01
    if not found:
        return 0, False, False
    if hi > 0.0:
        k, certified = repeated_roots(
            event, count, sizes, osc, p, n_cells, ends, free, max(lo, start), hi, out, mult,
            flags,
        )  # fmt: skip
        return k, certified, True
    top = max(4.0 * start, scale)
    for _ in range(MAX_DOUBLINGS):
        J, _, _, ok = structure_at(event, count, top, p, n_cells, ends, free, work, mats)
        if ok and J >= want:
            break
        top *= 2.0
    k, certified = repeated_roots(
        event, count, sizes, osc, p, n_cells, ends, free, start, top, out, mult, flags
    )
    return k, certified, True

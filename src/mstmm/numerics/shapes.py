"""Mode shapes (paper Eq. (5)): the orthonormalisation march with every attached unknown
kept, walked back by the stored maps (``mode_shapes``)."""

import math

import numpy as np

from mstmm.jit import njit

from .layout import (
    COL_MBAR,
    HEAD,
    SEGMENT_WIDTH,
)
from .segment import (
    piece_matrix,
    segment_pieces,
    segment_rotary,
)
from .walk import (
    STOP_END,
    STOP_EVENT,
    walk_next,
)

# Mode shapes (paper Eq. (5)): an orthonormalisation march with every attached unknown kept.
#
# The state Z = [Y, theta, M, Q] (units L = EI = 1) admitted by everything left of a point
# is a two-dimensional subspace, held by an orthonormal basis W (4 x 2): Z = W a. A point
# component adds its own unknowns q (the displacement of a hanging mass) and constraints
# (its geometric equation, paper Eq. (3)); in descriptor form
#     Cz Z + Cq q = 0,        Z+ = A Z + B q,
# so nothing is divided by a pole factor: at a branch's own frequency (B00 = 0) the
# constraint says Y = 0 and the mass moves freely. The solutions (a, q) are the null space N
# of [Cz W, Cq]; the new basis and the map back, (a, q) = G (a+, f), come from an SVD of
# [W, B] N. Its two largest singular directions carry the state; any further one (a
# constraint that is degenerate at this omega: a mass moving while the beam point is held)
# leaves a state that is zero from here on and becomes a "frozen" parameter f, kept to the
# end: it is a mode of the part left of the point, and so of the whole structure.
# At x = L the end's two conditions on W a have a null space (SVD); the shapes are walked
# back by the stored maps G, which are multiplications only: no solve, nothing singular.

#: Longest piece (in lam*l) of the mode-shape march: a piece's transfer matrix has
#: condition ~ exp(2 lam l), so the basis loses nothing between two orthonormalisations.
MARCH_STEP = 1.0
#: A constraint row of a point component (scaled to O(1)) this small is dependent on the
#: others at this omega: within this relative distance of the component's own frequency.
#: Roots closer than this are one cluster for the mode shapes (``mstmm.modes``).
DEGENERATE = 1e-8
#: Rows of a component's ``qmass`` (``event_descriptor`` writes every one, for each of its
#: unknowns q): the mass moving with q, its share in a rigid translation (R^T M)_q, the
#: factor of a force on q in its row, and the mass q shares with the beam's Y and theta
#: (M_Yq, M_thetaq: an inerter between the beam and q). ``mstmm.derive.emit`` prints it.
QMASS_ROWS = 5
#: Rows of a component's ``Mp`` (``event_inertia``): its mass matrix on the beam's own
#: [Y, theta] (2 x 2) and the participation row its couplings add (sum of M_(q, [Y,
#: theta]) over the q's a rigid translation carries).
INERTIA_ROWS = 3
#: Gauss-Legendre nodes and weights on [0, 1] (8 points: exact to degree 15).
GAUSS_POINTS = 8
_GX, _GW = np.polynomial.legendre.leggauss(GAUSS_POINTS)
GAUSS_X = 0.5 * (_GX + 1.0)
GAUSS_W = 0.5 * _GW


@njit(cache=True)
def jacobi_svd(A, V):
    """One-sided Jacobi SVD: A (n x k) becomes A V with orthogonal columns, V (k x k) the
    rotations; returns the column norms (the singular values, unsorted; k - n of them ~0 when
    k > n). Accurate to round-off relative to each column, and small to compile."""
    n = A.shape[0]
    k = A.shape[1]
    for i in range(k):
        for j in range(k):
            V[i, j] = 1.0 if i == j else 0.0
    for _ in range(64):
        rotated = False
        for i in range(k - 1):
            for j in range(i + 1, k):
                a = 0.0
                b = 0.0
                c = 0.0
                for r in range(n):
                    a += A[r, i] * A[r, i]
                    b += A[r, j] * A[r, j]
                    c += A[r, i] * A[r, j]
                if c == 0.0 or abs(c) <= 2.2e-16 * math.sqrt(a) * math.sqrt(b):
                    continue
                rotated = True
                if abs(b - a) > 1e150 * abs(c):
                    t = c / (b - a)  # tan of a negligible angle, 1 / (2 zeta)
                else:
                    zeta = (b - a) / (2.0 * c)
                    t = (1.0 if zeta >= 0.0 else -1.0) / (abs(zeta) + math.hypot(1.0, zeta))
                cs = 1.0 / math.hypot(1.0, t)
                sn = cs * t
                for r in range(n):
                    ai = A[r, i]
                    aj = A[r, j]
                    A[r, i] = cs * ai - sn * aj
                    A[r, j] = sn * ai + cs * aj
                for r in range(k):
                    vi = V[r, i]
                    vj = V[r, j]
                    V[r, i] = cs * vi - sn * vj
                    V[r, j] = sn * vi + cs * vj
        if not rotated:
            break
    s = np.empty(k)
    for i in range(k):
        t = 0.0
        for r in range(n):
            t += A[r, i] * A[r, i]
        s[i] = math.sqrt(t)
    return s


@njit(cache=True)
def carry(S, k, W, G):
    """New basis W (4 x 2) and map G (k x k) from the states S (4 x k) of k parameters.

    ``S G = [W, 0]`` up to round-off: G's first two columns take the new basis coordinates
    a+ to the old parameters, the others (k > 2) are frozen directions whose state is zero.
    Returns the number of frozen directions, k - 2."""
    V = np.empty((k, k))
    s = jacobi_svd(S, V)
    # the two largest singular values carry the state (the admitted subspace is 2-dim)
    i1 = 0
    for i in range(k):
        if s[i] > s[i1]:
            i1 = i
    i2 = 1 if i1 == 0 else 0
    for i in range(k):
        if i != i1 and s[i] > s[i2]:
            i2 = i
    col = 2
    for i in range(k):
        if i == i1 or i == i2:
            c = 0 if i == i1 else 1
            inv = 1.0 / s[i] if s[i] > 0.0 else 0.0
            for r in range(4):
                W[r, c] = S[r, i] * inv
            for r in range(k):
                G[r, c] = V[r, i] * inv
        else:
            for r in range(k):
                G[r, col] = V[r, i]
            col += 1
    return k - 2


@njit(cache=True)
def piece_step(W, G, U):
    """W <- U W re-orthonormalised (U the transfer across a piece); G (2 x 2) takes the new
    coordinates to the old."""
    S = np.empty((4, 2))
    for r in range(4):
        for c in range(2):
            S[r, c] = U[r, 0] * W[0, c] + U[r, 1] * W[1, c] + U[r, 2] * W[2, c] + U[r, 3] * W[3, c]
    carry(S, 2, W, G)


@njit(cache=True)
def event_step(W, G, Cz, Cq, A, B, nc, nq):
    """W <- basis after a point component with constraints Cz Z + Cq q = 0 (nc rows) and
    jump Z+ = A Z + B q (nq unknowns); G ((2 + nq) x (2 + nf)) takes (a+, f) to (a, q).
    Returns nf, the frozen directions it adds (its constraints degenerate at this omega)."""
    n = 2 + nq
    C = np.zeros((max(nc, 1), n))
    for r in range(nc):
        scale = 1.0
        for j in range(nq):
            scale = max(scale, abs(Cq[r, j]))
        for j in range(4):
            scale = max(scale, abs(Cz[r, j]))
        for c in range(2):
            C[r, c] = (
                Cz[r, 0] * W[0, c] + Cz[r, 1] * W[1, c] + Cz[r, 2] * W[2, c] + Cz[r, 3] * W[3, c]
            ) / scale
        for j in range(nq):
            C[r, 2 + j] = Cq[r, j] / scale
    V = np.empty((n, n))
    s = jacobi_svd(C, V)
    if nc == 0:
        for j in range(n):
            s[j] = 0.0
    # null space of the constraints: the columns whose singular value is negligible
    nn = 0
    for j in range(n):
        if s[j] <= DEGENERATE:
            nn += 1
    N = np.empty((n, nn))
    c = 0
    for j in range(n):
        if s[j] <= DEGENERATE:
            for r in range(n):
                N[r, c] = V[r, j]
            c += 1
    AW = np.zeros((4, 2))
    for r in range(4):
        for c in range(2):
            AW[r, c] = A[r, 0] * W[0, c] + A[r, 1] * W[1, c] + A[r, 2] * W[2, c] + A[r, 3] * W[3, c]
    S = np.zeros((4, nn))
    for r in range(4):
        for j in range(nn):
            t = 0.0
            for i in range(2):
                t += AW[r, i] * N[i, j]
            for i in range(nq):
                t += B[r, i] * N[2 + i, j]
            S[r, j] = t
    H = np.zeros((nn, nn))
    nf = carry(S, nn, W, H)
    for r in range(n):
        for j in range(nn):
            t = 0.0
            for i in range(nn):
                t += N[r, i] * H[i, j]
            G[r, j] = t
    return nf


@njit(cache=True)
def svd_2x2(E, V):
    """SVD of the 2 x 2 end matrix E: V's columns are its right singular vectors, smallest
    singular value first; returns the singular values in that order."""
    A = np.empty((2, 2))
    for r in range(2):
        for c in range(2):
            A[r, c] = E[r, c]
    Vr = np.empty((2, 2))
    s = jacobi_svd(A, Vr)
    lo = 0 if s[0] <= s[1] else 1
    hi = 1 - lo
    for r in range(2):
        V[r, 0] = Vr[r, lo]
        V[r, 1] = Vr[r, hi]
    out = np.empty(2)
    out[0] = s[lo]
    out[1] = s[hi]
    return out


@njit(cache=True)
def shape_steps(p, beta):
    """Number of steps of the march: every point component and every piece."""
    L = p[0]
    n_ev = int(p[4])
    steps = n_ev
    r = 0
    pos = 0.0
    seg = 0
    F = np.empty((4, 4, 4))  # a general segment's field_prepare (of segment ``ready``)
    ready = -1
    while True:  # the walk along the beam (``walk_next``)
        sg, stop, what, _, r, seg = walk_next(p, r, seg, pos, n_ev, math.inf)
        rho = (stop - pos) / L
        if rho > 0.0:
            pieces, ready = segment_pieces(p, sg, beta, rho, MARCH_STEP, F, ready)
            steps += pieces
            pos = stop
        if what == STOP_END:
            return steps


@njit(cache=True)
def mode_shapes(
    event, inertia, sizes, ends, omega, p, m, xs, Z_out, q_out, q_x, q_mass, gram, part, ratio
):
    """The ``m`` shapes of the eigenspace at omega (a root of multiplicity m, or the centre
    of a cluster of m roots), units L = EI_0 = mbar_0 = 1.

    Z_out (m, len(xs), 4): state [Y, theta, M, Q] at the sample points xs (SI, ascending,
    right limits at a point component); q_out (m, n_q): the unknowns of every point
    component, q_x (n_q) the x (SI) of the component each belongs to and q_mass (2, n_q) the
    mass (or rotary inertia) moving with it and the share of that a rigid translation
    carries (units mbar_0 L for a displacement, mbar_0 L^3 for a rotation; 0 for a
    reaction); gram (m, m) and part (m): the mass inner products int mbar Y_i Y_j + sum
    q_mass[0] q_i q_j + sum z_i^T M z_j + sum (M_Yq (Y_i q_j + Y_j q_i) + M_thetaq
    (theta_i q_j + theta_j q_i)) and int mbar Y_i + sum q_mass[1] q_i + sum (M z_i)_Y +
    sum P z_i (for the participation factor in a base translation), z = [Y, theta] at
    a component holding the point mass matrix M on the beam (a lumped mass and its
    rotary inertia; an inerter's M_YY), M_Yq and M_thetaq the mass an unknown shares
    with the beam's z (an inerter between them) and P the participation row of those
    couplings (``inertia`` fills [M; P], 3 x 2); ratio (m): singular value of each shape
    over the largest of the end matrix. Shapes are the right singular vectors of the end
    matrix for its m smallest singular values, walked back to the left end. ``event(p,
    row, b4, Cz, Cq, A, B, qmass)`` fills a component's descriptor, ``inertia(p, row, M)``
    its point mass matrix (returns 0 if none), ``sizes(p)`` gives the unknowns (total,
    most of one), ``ends`` = the left end's unknowns and the right end's knowns."""
    L = p[0]
    EI = p[1]
    mbar = p[2]
    beta = L * math.sqrt(math.sqrt(mbar * omega * omega / EI))
    b4 = (beta * beta) ** 2
    n_ev = int(p[4])
    nq_all, max_q = sizes(p)
    n_steps = shape_steps(p, beta)
    # per step: kind (0 piece, 1 point), rho, its segment's (beta_s, e, mbar_s/mbar_0),
    # nq, nf, offsets of its q and frozen params
    kind = np.zeros(n_steps, dtype=np.int64)
    rho_s = np.zeros(n_steps)
    seg_s = np.zeros(n_steps, dtype=np.int64)
    r_s = np.ones(n_steps)
    rot_s = np.zeros(n_steps)
    U = np.empty((4, 4))
    F = np.empty((4, 4, 4))  # a general segment's field_prepare (of segment ``ready``)
    ready = -1
    x_s = np.zeros(n_steps + 1)
    nq_s = np.zeros(n_steps, dtype=np.int64)
    nf_s = np.zeros(n_steps, dtype=np.int64)
    qofs = np.zeros(n_steps, dtype=np.int64)
    fofs = np.zeros(n_steps, dtype=np.int64)
    width = 2 + max_q
    Gbuf = np.zeros((n_steps, width, width))
    Wbuf = np.zeros((n_steps + 1, 4, 2))
    W = np.zeros((4, 2))
    W[ends[0], 0] = 1.0
    W[ends[1], 1] = 1.0
    for r in range(4):
        for c in range(2):
            Wbuf[0, r, c] = W[r, c]
    nb = max(1, max_q)
    Cz = np.zeros((nb, 4))
    Cq = np.zeros((nb, nb))
    Ad = np.zeros((4, 4))
    B = np.zeros((4, nb))
    ev_mass = np.zeros((QMASS_ROWS, nb))
    Mp = np.zeros((INERTIA_ROWS, 2))
    Mbuf = np.zeros((n_steps, INERTIA_ROWS, 2))
    # each unknown's mass shared with the beam's (Y, theta), and its component's step
    q_couple = np.zeros((2, max(1, nq_all)))
    q_step = np.zeros(max(1, nq_all), dtype=np.int64)
    G = np.zeros((width, width))
    s = 0
    nq_total = 0
    nf_total = 0
    pos = 0.0
    seg = 0
    ev = 0  # the walk's next event
    while True:  # the walk along the beam (``walk_next``)
        sg, x, what, row, ev, seg = walk_next(p, ev, seg, pos, n_ev, math.inf)
        rho = (x - pos) / L
        if rho > 0.0:
            pieces, ready = segment_pieces(p, sg, beta, rho, MARCH_STEP, F, ready)
            ready = piece_matrix(p, sg, beta, rho / pieces, U, F, ready)
            for _ in range(pieces):
                piece_step(W, G, U)
                kind[s] = 0
                rho_s[s] = rho / pieces
                seg_s[s] = sg
                r_s[s] = p[HEAD + SEGMENT_WIDTH * sg + COL_MBAR] / mbar
                rot_s[s] = segment_rotary(p, sg)
                x_s[s + 1] = x_s[s] + rho / pieces
                for r in range(2):
                    for c in range(2):
                        Gbuf[s, r, c] = G[r, c]
                s += 1
                for r in range(4):
                    for c in range(2):
                        Wbuf[s, r, c] = W[r, c]
            x_s[s] = x / L
            pos = x
        if what == STOP_END:
            break
        if what != STOP_EVENT:
            continue
        nc, nq = event(p, row, b4, Cz, Cq, Ad, B, ev_mass)
        nf = event_step(W, G, Cz, Cq, Ad, B, nc, nq)
        if inertia(p, row, Mp) != 0:
            for r in range(INERTIA_ROWS):
                for c in range(2):
                    Mbuf[s, r, c] = Mp[r, c]
        kind[s] = 1
        nq_s[s] = nq
        nf_s[s] = nf
        qofs[s] = nq_total
        fofs[s] = nf_total
        for j in range(nq):
            q_mass[0, nq_total + j] = ev_mass[0, j]
            q_mass[1, nq_total + j] = ev_mass[1, j]
            q_couple[0, nq_total + j] = ev_mass[3, j]
            q_couple[1, nq_total + j] = ev_mass[4, j]
            q_step[nq_total + j] = s
            q_x[nq_total + j] = x
        nq_total += nq
        nf_total += nf
        for r in range(2 + nq):
            for c in range(2 + nf):
                Gbuf[s, r, c] = G[r, c]
        s += 1
        x_s[s] = x / L
        for r in range(4):
            for c in range(2):
                Wbuf[s, r, c] = W[r, c]
    # the end: its two conditions on Z = W a; frozen parameters are exact null directions
    E = np.empty((2, 2))
    for c in range(2):
        E[0, c] = W[ends[2], c]
        E[1, c] = W[ends[3], c]
    Ve = np.empty((2, 2))
    se = svd_2x2(E, Ve)
    top = se[1]
    a = np.zeros((m, 2))
    f = np.zeros((m, max(1, nf_total)))
    for k in range(m):
        if k < nf_total:
            f[k, k] = 1.0
            ratio[k] = 0.0
        else:
            j = min(k - nf_total, 1)
            a[k, 0] = Ve[0, j]
            a[k, 1] = Ve[1, j]
            ratio[k] = se[j] / top if top > 0.0 else 0.0
    # walk back: the state at every node, the unknowns of every point component
    Zn = np.zeros((m, n_steps + 1, 4))
    for k in range(m):
        for r in range(4):
            Zn[k, n_steps, r] = W[r, 0] * a[k, 0] + W[r, 1] * a[k, 1]
    cols = np.empty(width)
    for t in range(n_steps - 1, -1, -1):
        nq = nq_s[t]
        nf = nf_s[t]
        for k in range(m):
            cols[0] = a[k, 0]
            cols[1] = a[k, 1]
            for j in range(nf):
                cols[2 + j] = f[k, fofs[t] + j]
            a0 = 0.0
            a1 = 0.0
            for c in range(2 + nf):
                a0 += Gbuf[t, 0, c] * cols[c]
                a1 += Gbuf[t, 1, c] * cols[c]
            for j in range(nq):
                v = 0.0
                for c in range(2 + nf):
                    v += Gbuf[t, 2 + j, c] * cols[c]
                q_out[k, qofs[t] + j] = v
            a[k, 0] = a0
            a[k, 1] = a1
            for r in range(4):
                Zn[k, t, r] = Wbuf[t, r, 0] * a0 + Wbuf[t, r, 1] * a1
    # samples (right limits) and the mass inner products, piece by piece
    for i in range(m):
        part[i] = 0.0
        for j in range(m):
            gram[i, j] = 0.0
    Y = np.empty(m)
    psi = np.empty(m)
    j = 0
    ns = xs.shape[0]
    for t in range(n_steps):
        if kind[t] != 0:
            # a point mass matrix on [Y, theta] left of the component (where A acts), and
            # the participation its couplings to the unknowns add
            for k in range(m):
                mk0 = Mbuf[t, 0, 0] * Zn[k, t, 0] + Mbuf[t, 0, 1] * Zn[k, t, 1]
                mk1 = Mbuf[t, 1, 0] * Zn[k, t, 0] + Mbuf[t, 1, 1] * Zn[k, t, 1]
                part[k] += mk0
                part[k] += Mbuf[t, 2, 0] * Zn[k, t, 0] + Mbuf[t, 2, 1] * Zn[k, t, 1]
                for l in range(m):
                    gram[k, l] += Zn[l, t, 0] * mk0 + Zn[l, t, 1] * mk1
            continue
        x0 = x_s[t]
        x1 = x0 + rho_s[t]
        while j < ns and xs[j] / L < x1:
            d = max(xs[j] / L - x0, 0.0)
            ready = piece_matrix(p, seg_s[t], beta, d, U, F, ready)
            for k in range(m):
                for r in range(4):
                    Z_out[k, j, r] = (
                        U[r, 0] * Zn[k, t, 0]
                        + U[r, 1] * Zn[k, t, 1]
                        + U[r, 2] * Zn[k, t, 2]
                        + U[r, 3] * Zn[k, t, 3]
                    )
            j += 1
        for g in range(GAUSS_X.shape[0]):
            ready = piece_matrix(p, seg_s[t], beta, rho_s[t] * GAUSS_X[g], U, F, ready)
            w = rho_s[t] * GAUSS_W[g] * r_s[t]
            wr = rho_s[t] * GAUSS_W[g] * rot_s[t]  # rho_I psi^2: a section's rotary inertia
            for k in range(m):
                Y[k] = (
                    U[0, 0] * Zn[k, t, 0]
                    + U[0, 1] * Zn[k, t, 1]
                    + U[0, 2] * Zn[k, t, 2]
                    + U[0, 3] * Zn[k, t, 3]
                )
                psi[k] = (
                    U[1, 0] * Zn[k, t, 0]
                    + U[1, 1] * Zn[k, t, 1]
                    + U[1, 2] * Zn[k, t, 2]
                    + U[1, 3] * Zn[k, t, 3]
                )
            for k in range(m):
                part[k] += w * Y[k]
                for l in range(m):
                    gram[k, l] += w * Y[k] * Y[l] + wr * psi[k] * psi[l]
    while j < ns:  # at x = L: the state after every component there
        for k in range(m):
            for r in range(4):
                Z_out[k, j, r] = Zn[k, n_steps, r]
        j += 1
    for i in range(nq_total):
        for k in range(m):
            part[k] += q_mass[1, i] * q_out[k, i]
            for l in range(m):
                gram[k, l] += q_mass[0, i] * q_out[k, i] * q_out[l, i]
        if q_couple[0, i] != 0.0 or q_couple[1, i] != 0.0:
            # the mass the unknown shares with the beam's [Y, theta] left of its component
            t = q_step[i]
            for k in range(m):
                for l in range(m):
                    gram[k, l] += q_couple[0, i] * (
                        Zn[k, t, 0] * q_out[l, i] + Zn[l, t, 0] * q_out[k, i]
                    ) + q_couple[1, i] * (Zn[k, t, 1] * q_out[l, i] + Zn[l, t, 1] * q_out[k, i])
    return nq_total

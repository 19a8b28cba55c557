"""The frequency response (receptance): the forced march, and damped mode shapes as the
unloaded march at a root (``frf_march``)."""

import cmath
import math

import numpy as np

from mstmm.jit import njit

from .segment import (
    segment_piece_c,
)
from .shapes import (
    DEGENERATE,
    MARCH_STEP,
    QMASS_ROWS,
)
from .walk import (
    STOP_END,
    STOP_EXTRA,
    STOP_SEGMENT,
    event_at,
    event_row,
    walk_next,
)

# Frequency response (receptance): the forced march. The state left of x is
# Z = W b + z: W (4 x 2, orthonormal) spans the states the left end admits, z is the
# particular state the load puts there (kept orthogonal to W). Pieces carry both with the
# transfer matrix (lam l <= MARCH_STEP: no scaling, so the load's particular state keeps
# its true size), a point component eliminates its unknowns (Cz Z + Cq q = -f, f the
# force on its masses) by pivoting, and each step re-orthonormalises W and records how the
# new coordinates b relate to the old. An output is recorded where the march passes it
# as out = T b + t and carried forward with the coordinates; at x = L the right end's
# conditions fix b. One sweep, nothing walked back: the cost is that of the march.
#: Kinds of input and output of ``frf_march``.
FRF_FORCE = 0  # input: a force on the beam at x (Q jumps by F); output: Y at x
FRF_MOMENT = 1  # input: a couple at x (M jumps by -C); output: theta at x
FRF_MASS = 2  # a load on / the response of a component's unknown (hanging mass, rotary inertia)
FRF_M = 3  # output: the moment M at x
FRF_Q = 4  # output: the shear Q at x
#: Inputs of a homogeneous march (a mode shape at a root): no load. Kind -(j + 1) asks for
#: the root's j-th shape: the modes localised on the way (frozen, in the order the march
#: meets them) first, then the end's conditions E b = 0 taken along the right singular
#: vector of E for its smaller (FRF_NULL when no mode is localised) or larger singular
#: value (FRF_NULL2: the second shape of a double root); NaN past those (singular inf).
FRF_NULL = -1
FRF_NULL2 = -2


#: In a homogeneous march, a basis direction whose state shrinks below this fraction of
#: the other's has vanished: a mode localised left of here (``orthonormalise_c``).
COLLAPSED = 1e-9


@njit(cache=True)
def orthonormalise_c(W, z, T, t, done, ep, G, g, nep, frozen, nf):
    """W <- Q of W = Q R (complex Gram-Schmidt, twice), z <- z minus its part in span Q;
    the recorded outputs out = T b + t follow the new coordinates (a map pushed with
    ``lazy_push``, applied once at the end). Returns nf.

    In a homogeneous march (frozen has rows), a direction whose state vanishes (R11 <=
    COLLAPSED R00: two identical absorbers moving against each other with the beam at
    rest, at their own frequency) is a mode of the part left of here alone: its outputs so
    far go into frozen[nf] (the later ones are 0), and the basis goes on with the other
    direction and a fresh one orthogonal to it."""
    R = np.zeros((2, 2), dtype=np.complex128)
    for c in range(2):
        for _ in range(2):
            for k in range(c):
                d = 0.0j
                for r in range(4):
                    d += W[r, k].conjugate() * W[r, c]
                R[k, c] += d
                for r in range(4):
                    W[r, c] -= d * W[r, k]
        nrm = 0.0
        for r in range(4):
            nrm += abs(W[r, c]) ** 2
        nrm = math.sqrt(nrm)
        R[c, c] = nrm
        if nrm > 0.0 and not (c == 1 and frozen.shape[0] > 0 and nrm <= COLLAPSED * abs(R[0, 0])):
            for r in range(4):
                W[r, c] /= nrm
    if frozen.shape[0] > 0 and abs(R[1, 1]) <= COLLAPSED * abs(R[0, 0]):
        # the old coordinates (-R01 / R00, 1) give no state: record that mode's outputs
        f0 = -R[0, 1] / R[0, 0]
        lazy_apply(G, g, nep, ep, done, T, t)  # T, t in the current coordinates
        n_out = T.shape[0]
        if nf < frozen.shape[0]:
            for j in range(n_out):
                frozen[nf, j] = T[j, 0] * f0 + T[j, 1]
        nf += 1
        # a fresh second direction, orthogonal to the first (the unit vector farthest from it)
        best = -1.0
        for k in range(4):
            res = 1.0 - abs(W[k, 0]) ** 2
            if res > best:
                best = res
                kb = k
        for r in range(4):
            W[r, 1] = (1.0 if r == kb else 0.0) - W[kb, 0].conjugate() * W[r, 0]
        nrm = 0.0
        for r in range(4):
            nrm += abs(W[r, 1]) ** 2
        nrm = math.sqrt(nrm)
        for r in range(4):
            W[r, 1] /= nrm
        # what is left of the old coordinates: b0 = R00 a0 + R01 a1; the fresh b1 has no past
        for j in range(n_out):
            T[j, 0] = T[j, 0] / R[0, 0]
            T[j, 1] = 0.0
        return nf
    # z = Q s + z_perp: the coordinates absorb s
    s0 = 0.0j
    s1 = 0.0j
    for r in range(4):
        s0 += W[r, 0].conjugate() * z[r]
        s1 += W[r, 1].conjugate() * z[r]
    for r in range(4):
        z[r] -= s0 * W[r, 0] + s1 * W[r, 1]
    # old coordinates a = R^-1 (b - s): out = T a + t = (T R^-1) b + (t - T R^-1 s)
    det = R[0, 0] * R[1, 1]
    i00 = R[1, 1] / det
    i01 = -R[0, 1] / det
    i11 = R[0, 0] / det
    lazy_push(G, g, nep, ep, done, T, t, i00, i01, 0.0j, i11, -(i00 * s0 + i01 * s1), -i11 * s1)
    return nf


@njit(cache=True)
def lazy_push(G, g, nep, ep, done, T, t, m00, m01, m10, m11, c0, c1):
    """The coordinates of the march change, a_old = M a_new + c: kept as the map
    nep[0] of G, g (the recorded outputs out = T a + t are read in the coordinates
    ep[j] of their recording: ``lazy_apply``), so that a change costs O(1), not O(outputs).
    A full store is applied first."""
    if nep[0] == G.shape[0]:
        lazy_apply(G, g, nep, ep, done, T, t)
    k = nep[0]
    G[k, 0, 0] = m00
    G[k, 0, 1] = m01
    G[k, 1, 0] = m10
    G[k, 1, 1] = m11
    g[k, 0] = c0
    g[k, 1] = c1
    nep[0] = k + 1


@njit(cache=True)
def lazy_apply(G, g, nep, ep, done, T, t):
    """Every recorded output in the current coordinates: the maps from its recording on
    composed backwards (one pass over the maps, one over the outputs); the store empties."""
    n = nep[0]
    P = np.zeros((n + 1, 2, 2), dtype=np.complex128)
    c = np.zeros((n + 1, 2), dtype=np.complex128)
    P[n, 0, 0] = 1.0
    P[n, 1, 1] = 1.0
    for k in range(n - 1, -1, -1):
        for a in range(2):
            for b in range(2):
                P[k, a, b] = G[k, a, 0] * P[k + 1, 0, b] + G[k, a, 1] * P[k + 1, 1, b]
            c[k, a] = G[k, a, 0] * c[k + 1, 0] + G[k, a, 1] * c[k + 1, 1] + g[k, a]
    for j in range(T.shape[0]):
        if done[j]:
            e = ep[j]
            T0 = T[j, 0]
            T1 = T[j, 1]
            T[j, 0] = T0 * P[e, 0, 0] + T1 * P[e, 1, 0]
            T[j, 1] = T0 * P[e, 0, 1] + T1 * P[e, 1, 1]
            t[j] += T0 * c[e, 0] + T1 * c[e, 1]
        ep[j] = 0
    nep[0] = 0


@njit(cache=True)
def eliminate_c(C, rhs, scale, nc, n, X, xp, piv_col, used):
    """The solutions of C x = rhs (nc x n, real or complex) as x = xp + X a, X n x (n -
    rank): Gauss-Jordan with complete pivoting; a row whose pivot falls below DEGENERATE
    times its scale (its largest entry of Cz and Cq) depends on the others at this
    frequency (a component exactly at its own frequency with the beam point held): it
    leaves one more free parameter. Returns the number of free parameters (columns of X),
    or -1 when such a row's right-hand side is not zero (the load drives a decoupled
    resonance). C, rhs and scale are overwritten; ``piv_col`` (int) and ``used`` (bool),
    of at least nc and n entries, are the caller's scratch (the marches call this at every
    component and frequency: five allocations a call were a fifth of a Bloch cell's)."""
    M = C
    r_ = rhs
    sc = scale
    for j in range(n):
        used[j] = False
    rank = 0
    for k in range(nc):
        best = -1.0
        bi = k
        bj = 0
        for i in range(k, nc):
            for j in range(n):
                if not used[j] and abs(M[i, j]) / sc[i] > best:
                    best = abs(M[i, j]) / sc[i]
                    bi = i
                    bj = j
        if best <= DEGENERATE:
            break
        if bi != k:
            for j in range(n):
                tmp = M[k, j]
                M[k, j] = M[bi, j]
                M[bi, j] = tmp
            tmp = r_[k]
            r_[k] = r_[bi]
            r_[bi] = tmp
            tmp2 = sc[k]
            sc[k] = sc[bi]
            sc[bi] = tmp2
        used[bj] = True
        piv_col[k] = bj
        inv = 1.0 / M[k, bj]
        for j in range(n):
            M[k, j] *= inv
        r_[k] *= inv
        for i in range(nc):
            if i != k and M[i, bj] != 0.0:
                f = M[i, bj]
                for j in range(n):
                    M[i, j] -= f * M[k, j]
                r_[i] -= f * r_[k]
        rank += 1
    for i in range(rank, nc):  # the dependent rows: consistent only without load
        if abs(r_[i]) > DEGENERATE * sc[i]:
            return -1
    free = 0
    for j in range(n):
        xp[j] = 0.0
        for c in range(X.shape[1]):
            X[j, c] = 0.0
    for j in range(n):
        if not used[j]:
            X[j, free] = 1.0
            for k in range(rank):
                X[piv_col[k], free] = -M[k, j]
            free += 1
    for k in range(rank):
        xp[piv_col[k]] = r_[k]
    return free


@njit(cache=True)
def carry_c(S, nn, X, T, n_out, q0, nq, outputs, frozen, nf):
    """Keep two of the nn state columns S (4 x nn) of the free parameters X (n x nn): the
    largest, then the largest left of it (pivoted Gram-Schmidt); each other column is a
    combination of those two up to round-off, and that combination of the parameters
    (a, q) = X c gives no state: a frozen mode (the outputs recorded so far and this
    component's masses go into frozen[nf]). S and X come back with the two kept columns
    first. Returns nf."""
    for k in range(2):
        # the largest column, the second time of what is left beside the first
        n0 = 0.0
        for r in range(4):
            n0 += abs(S[r, 0]) ** 2
        best = -1.0
        bj = k
        for j in range(k, nn):
            d = 0.0j
            if k == 1:
                for r in range(4):
                    d += S[r, 0].conjugate() * S[r, j]
                d /= n0
            nrm = 0.0
            for r in range(4):
                nrm += abs(S[r, j] - d * S[r, 0]) ** 2
            if nrm > best:
                best = nrm
                bj = j
        if bj != k:
            for r in range(4):
                tmp = S[r, k]
                S[r, k] = S[r, bj]
                S[r, bj] = tmp
            for r in range(X.shape[0]):
                tmp = X[r, k]
                X[r, k] = X[r, bj]
                X[r, bj] = tmp
    # the other columns in terms of the first two: S[:, j] = S[:, :2] y (least squares)
    g00 = 0.0j
    g01 = 0.0j
    g11 = 0.0j
    for r in range(4):
        g00 += S[r, 0].conjugate() * S[r, 0]
        g01 += S[r, 0].conjugate() * S[r, 1]
        g11 += S[r, 1].conjugate() * S[r, 1]
    det = g00 * g11 - g01 * g01.conjugate()
    for j in range(2, nn):
        h0 = 0.0j
        h1 = 0.0j
        for r in range(4):
            h0 += S[r, 0].conjugate() * S[r, j]
            h1 += S[r, 1].conjugate() * S[r, j]
        y0 = (g11 * h0 - g01 * h1) / det
        y1 = (g00 * h1 - g01.conjugate() * h0) / det
        if nf < frozen.shape[0]:
            # c = e_j - (y0, y1): the parameters X c give no state
            for o in range(n_out):
                v = 0.0j
                for c in range(2):
                    xc = X[c, j] - y0 * X[c, 0] - y1 * X[c, 1]
                    v += T[o, c] * xc
                if int(outputs[o, 0]) == FRF_MASS and q0 <= int(outputs[o, 2]) < q0 + nq:
                    k = 2 + int(outputs[o, 2]) - q0
                    v = X[k, j] - y0 * X[k, 0] - y1 * X[k, 1]
                frozen[nf, o] = v
        nf += 1
    return nf


@njit(cache=True)
def frf_record_at(outputs, x, bo, bptr, done, W, z, T, t, ep, nep):
    """Record the beam outputs at x not yet recorded (bo: the beam outputs by x, from
    bptr on every one before x is recorded or skipped). Returns the new bptr."""
    while bptr < bo.shape[0] and (done[bo[bptr]] or outputs[bo[bptr], 1] < x):
        bptr += 1
    k = bptr
    while k < bo.shape[0] and outputs[bo[k], 1] == x:
        j = bo[k]
        if not done[j]:
            frf_record(outputs, j, W, z, T, t, ep, nep)
            done[j] = True
        k += 1
    return bptr


@njit(cache=True)
def frf_record(outputs, j, W, z, T, t, ep, nep):
    """Record beam output j at the current state: out = T b + t, b the current
    coordinates (ep[j])."""
    kind = int(outputs[j, 0])
    k = 0 if kind == FRF_FORCE else (1 if kind == FRF_MOMENT else (2 if kind == FRF_M else 3))
    T[j, 0] = W[k, 0]
    T[j, 1] = W[k, 1]
    t[j] = z[k]
    ep[j] = nep[0]


@njit(cache=True)
def null_2x2(e00, e01, e10, e11, second):
    """The right singular vector of the 2 x 2 complex matrix E for its smaller singular
    value (the larger with ``second``), and that value over the larger one (from the
    Hermitian E^H E)."""
    a = abs(e00) ** 2 + abs(e10) ** 2
    d = abs(e01) ** 2 + abs(e11) ** 2
    b = e00.conjugate() * e01 + e10.conjugate() * e11
    mid = 0.5 * (a + d)
    rad = math.sqrt(max(0.25 * (a - d) ** 2 + abs(b) ** 2, 0.0))
    big = mid + rad
    # the smaller eigenvalue of E^H E from its determinant |det E|^2: no cancellation
    small = abs(e00 * e11 - e01 * e10) ** 2 / big if big > 0.0 else 0.0
    lam = big if second else small
    # (E^H E - lam I) v = 0: v = (b, lam - a) or (lam - d, conj(b)), the larger
    v0 = b
    v1 = lam - a + 0.0j
    u0 = lam - d + 0.0j
    u1 = b.conjugate()
    if abs(u0) ** 2 + abs(u1) ** 2 > abs(v0) ** 2 + abs(v1) ** 2:
        v0 = u0
        v1 = u1
    nrm = math.sqrt(abs(v0) ** 2 + abs(v1) ** 2)
    if nrm == 0.0:  # E^H E a multiple of I: any vector
        v0 = 1.0 + 0.0j if not second else 0.0j
        v1 = 0.0j if not second else 1.0 + 0.0j
        nrm = 1.0
    ratio = math.sqrt(small / big) if big > 0.0 else 0.0
    return v0 / nrm, v1 / nrm, (1.0 if second else ratio)


@njit(cache=True)
def frf_march(event, sizes, ends, w, p, damped, inputs, outputs, out, singular):
    """Receptances at the complex frequency w (rad/s) for a unit load: ``inputs`` rows
    (kind, x, q index, scale), ``outputs`` rows (kind, x, q index, scale) with kinds
    FRF_FORCE / FRF_MOMENT / FRF_MASS; x in m, the q index counts every component's
    unknowns in x order; scale turns the dimensionless load or response into SI. out[i, j]
    is output j for input i alone (one march per input); NaN where a component's
    constraint degenerates exactly (a decoupled oscillator at its own frequency). A force
    on a hanging mass enters its component's row (the rows of a component whose unknowns
    are masses are their equations of motion, Cz Z + Cq q = -f) and the beam's shear at
    the component (Z+ = A Z + B q + f e_Q: B q is only the masses' inertia).
    ``damped``: read each segment's loss factor (a damped kernel's descriptors carry the
    dashpots). ``event(p, row, w1, Cz, Cq, A, B, qmass)`` fills a component's complex
    descriptor (paper Eqs. (2)-(3)), ``sizes(p)`` gives the unknowns. An input of kind
    FRF_NULL (FRF_NULL2) is no load: the march gives the mode shape at a root w, the
    end's null vector (the second one of a double root), and singular[i] the singular
    value it belongs to over the end matrix's largest."""
    L = p[0]
    EI = p[1]
    mbar = p[2]
    w1 = w * L * L * math.sqrt(mbar / EI)
    beta = cmath.sqrt(w1)
    n_ev = int(p[4])
    nq_all, max_q = sizes(p)
    nb = max(1, max_q)
    Cz = np.zeros((nb, 4), dtype=np.complex128)
    Cq = np.zeros((nb, nb), dtype=np.complex128)
    Ad = np.zeros((4, 4), dtype=np.complex128)
    B = np.zeros((4, nb), dtype=np.complex128)
    ev_mass = np.zeros((QMASS_ROWS, nb))
    C = np.zeros((nb, nb + 2), dtype=np.complex128)
    rhs = np.zeros(nb, dtype=np.complex128)
    row_scale = np.ones(nb)
    piv_col = np.empty(nb, dtype=np.int64)  # ``eliminate_c``'s scratch
    used = np.empty(nb + 2, dtype=np.bool_)
    X = np.zeros((nb + 2, nb + 2), dtype=np.complex128)
    SS = np.zeros((4, nb + 2), dtype=np.complex128)
    xp = np.zeros(nb + 2, dtype=np.complex128)
    U = np.zeros((4, 4), dtype=np.complex128)
    Ff = np.zeros((4, 4, 4), dtype=np.complex128)
    S = np.zeros((4, 2), dtype=np.complex128)
    zz = np.zeros(4, dtype=np.complex128)
    W = np.zeros((4, 2), dtype=np.complex128)
    z = np.zeros(4, dtype=np.complex128)
    n_out = outputs.shape[0]
    T = np.zeros((n_out, 2), dtype=np.complex128)
    t = np.zeros(n_out, dtype=np.complex128)
    done = np.zeros(n_out, dtype=np.bool_)
    # the coordinate changes since each output's recording (lazy_push, lazy_apply)
    ep = np.zeros(n_out, dtype=np.int64)
    cap = n_out + n_ev + 64
    G = np.zeros((cap, 2, 2), dtype=np.complex128)
    g = np.zeros((cap, 2), dtype=np.complex128)
    nep = np.zeros(1, dtype=np.int64)
    # the beam outputs by x and the masses' by q index: each found from a pointer
    n_beam = 0
    for j in range(n_out):
        if int(outputs[j, 0]) != FRF_MASS:
            n_beam += 1
    bo = np.empty(n_beam, dtype=np.int64)
    mo = np.empty(n_out - n_beam, dtype=np.int64)
    kb = 0
    km = 0
    for j in range(n_out):
        if int(outputs[j, 0]) != FRF_MASS:
            bo[kb] = j
            kb += 1
        else:
            mo[km] = j
            km += 1
    bo = bo[np.argsort(outputs[bo, 1], kind="mergesort")]
    mo = mo[np.argsort(outputs[mo, 2], kind="mergesort")]
    for i_in in range(inputs.shape[0]):
        homogeneous = inputs[i_in, 0] < 0
        kind_in = int(inputs[i_in, 0])
        pick = -kind_in - 1 if homogeneous else 0  # the shape asked for (FRF_NULL: 0)
        frozen = np.zeros((pick + 1 if homogeneous else 0, n_out), dtype=np.complex128)
        nf = 0
        x_in = inputs[i_in, 1]
        q_in = int(inputs[i_in, 2])
        load = inputs[i_in, 3]
        for a in range(4):
            z[a] = 0.0
            for c in range(2):
                W[a, c] = 0.0
        W[ends[0], 0] = 1.0
        W[ends[1], 1] = 1.0
        for j in range(n_out):
            done[j] = False
            t[j] = 0.0
            T[j, 0] = 0.0
            T[j, 1] = 0.0
            ep[j] = 0
        nep[0] = 0
        bptr = 0
        mptr = 0
        applied = kind_in == FRF_MASS or kind_in < 0
        pos = 0.0
        seg = 0
        q0 = 0
        failed = False
        r = 0
        while True:  # the walk along the beam (``walk_next``), stopping at the load and
            # the outputs between components too
            _, x = event_at(p, r, n_ev)  # the next component's x (L past the last)
            extra = x_in if not applied and pos <= x_in else math.inf
            while bptr < n_beam and (done[bo[bptr]] or outputs[bo[bptr], 1] < pos):
                bptr += 1  # the next beam output not recorded
            if bptr < n_beam and outputs[bo[bptr], 1] < extra:
                extra = outputs[bo[bptr], 1]
            sg, stop, what, row, r, seg = walk_next(p, r, seg, pos, n_ev, extra)
            rho = (stop - pos) / L
            if rho > 0.0:
                pieces, _ = segment_piece_c(p, sg, w1, beta, damped, rho, MARCH_STEP, U, Ff)
                for _ in range(pieces):
                    for a in range(4):
                        zz[a] = U[a, 0] * z[0] + U[a, 1] * z[1] + U[a, 2] * z[2] + U[a, 3] * z[3]
                        for c in range(2):
                            S[a, c] = (
                                U[a, 0] * W[0, c]
                                + U[a, 1] * W[1, c]
                                + U[a, 2] * W[2, c]
                                + U[a, 3] * W[3, c]
                            )
                    for a in range(4):
                        z[a] = zz[a]
                        for c in range(2):
                            W[a, c] = S[a, c]
                    nf = orthonormalise_c(W, z, T, t, done, ep, G, g, nep, frozen, nf)
                pos = stop
            if pos < x:  # the load and the outputs between components
                if not applied and x_in == pos:
                    if kind_in == FRF_FORCE:
                        z[3] += load
                    else:
                        z[2] -= load
                    applied = True
                bptr = frf_record_at(outputs, pos, bo, bptr, done, W, z, T, t, ep, nep)
            if what == STOP_EXTRA or what == STOP_SEGMENT:
                continue
            if not applied and x_in == x:  # a load at a component, or at x = L
                if kind_in == FRF_FORCE:
                    z[3] += load
                else:
                    z[2] -= load
                applied = True
            if what == STOP_END:
                break
            nc, nq = event(p, row, w1, Cz, Cq, Ad, B, ev_mass)
            n = 2 + nq
            for a in range(nc):
                rhs[a] = -(Cz[a, 0] * z[0] + Cz[a, 1] * z[1] + Cz[a, 2] * z[2] + Cz[a, 3] * z[3])
                if kind_in == FRF_MASS and q_in == q0 + a:
                    # the rows are the masses' equations of motion, times -ev_mass[2]
                    rhs[a] -= load * ev_mass[2, a]
                for c in range(2):
                    C[a, c] = (
                        Cz[a, 0] * W[0, c]
                        + Cz[a, 1] * W[1, c]
                        + Cz[a, 2] * W[2, c]
                        + Cz[a, 3] * W[3, c]
                    )
                for j in range(nq):
                    C[a, 2 + j] = Cq[a, j]
            nn = n
            if nc > 0:
                for a in range(nc):
                    sc = 0.0
                    for c in range(4):
                        sc = max(sc, abs(Cz[a, c]))
                    for j in range(nq):
                        sc = max(sc, abs(Cq[a, j]))
                    row_scale[a] = sc if sc > 0.0 else 1.0
                nn = eliminate_c(C, rhs, row_scale, nc, n, X, xp, piv_col, used)
                if nn < 0 or (nn > 2 and not homogeneous):
                    failed = True  # a decoupled resonance: the response is infinite
                    break
            else:
                for j in range(n):
                    xp[j] = 0.0
                    for c in range(X.shape[1]):
                        X[j, c] = 1.0 if j == c else 0.0
            # the new state: Z+ = A (W a + z) + B q
            for a in range(4):
                aw0 = (
                    Ad[a, 0] * W[0, 0]
                    + Ad[a, 1] * W[1, 0]
                    + Ad[a, 2] * W[2, 0]
                    + Ad[a, 3] * W[3, 0]
                )
                aw1 = (
                    Ad[a, 0] * W[0, 1]
                    + Ad[a, 1] * W[1, 1]
                    + Ad[a, 2] * W[2, 1]
                    + Ad[a, 3] * W[3, 1]
                )
                az = Ad[a, 0] * z[0] + Ad[a, 1] * z[1] + Ad[a, 2] * z[2] + Ad[a, 3] * z[3]
                zz[a] = aw0 * xp[0] + aw1 * xp[1] + az
                for c in range(nn):
                    SS[a, c] = aw0 * X[0, c] + aw1 * X[1, c]
                for j in range(nq):
                    zz[a] += B[a, j] * xp[2 + j]
                    for c in range(nn):
                        SS[a, c] += B[a, j] * X[2 + j, c]
            if nn > 2:  # degenerate constraints: keep two columns, the rest are frozen modes
                lazy_apply(G, g, nep, ep, done, T, t)
                nf = carry_c(SS, nn, X, T, n_out, q0, nq, outputs, frozen, nf)
            for a in range(4):
                for c in range(2):
                    S[a, c] = SS[a, c]
            # recorded outputs follow (a, q) = xp + X a_new; then this component's masses
            lazy_push(G, g, nep, ep, done, T, t, X[0, 0], X[0, 1], X[1, 0], X[1, 1], xp[0], xp[1])
            while mptr < mo.shape[0] and int(outputs[mo[mptr], 2]) < q0 + nq:
                j = mo[mptr]
                if int(outputs[j, 2]) >= q0:
                    k = 2 + int(outputs[j, 2]) - q0
                    T[j, 0] = X[k, 0]
                    T[j, 1] = X[k, 1]
                    t[j] = xp[k]
                    ep[j] = nep[0]
                    done[j] = True
                mptr += 1
            if kind_in == FRF_MASS and q0 <= q_in < q0 + nq:
                # B q is the unknowns' inertia passed to the beam; a force on a hanging
                # mass reaches the beam's shear too, a couple on a rotary inertia (a
                # translation does not carry it: ev_mass[1] = 0) its moment
                if ev_mass[1, q_in - q0] > 0.0:
                    zz[3] += load
                else:
                    zz[2] -= load
            for a in range(4):
                z[a] = zz[a]
                for c in range(2):
                    W[a, c] = S[a, c]
            nf = orthonormalise_c(W, z, T, t, done, ep, G, g, nep, frozen, nf)
            q0 += nq
            if r == n_ev or p[event_row(p, r) + 1] != x:  # outputs after the last one here
                bptr = frf_record_at(outputs, x, bo, bptr, done, W, z, T, t, ep, nep)
        if failed:
            for j in range(n_out):
                out[i_in, j] = complex(math.nan, math.nan)
            continue
        for j in range(n_out):  # outputs at x = L
            if not done[j] and int(outputs[j, 0]) != FRF_MASS:
                frf_record(outputs, j, W, z, T, t, ep, nep)
                done[j] = True
        lazy_apply(G, g, nep, ep, done, T, t)  # T, t in the end's coordinates
        # the right end: its known states vanish, E b = -e
        e00 = W[ends[2], 0]
        e01 = W[ends[2], 1]
        e10 = W[ends[3], 0]
        e11 = W[ends[3], 1]
        if homogeneous and pick < nf:  # a localised mode (orthonormalise_c, carry_c)
            for j in range(n_out):
                out[i_in, j] = frozen[pick, j] * outputs[j, 3]
            singular[i_in] = 0.0
            continue
        if homogeneous and pick - nf > 1:  # the end has two directions only
            for j in range(n_out):
                out[i_in, j] = complex(math.nan, math.nan)
            singular[i_in] = math.inf
            continue
        if homogeneous:
            b0, b1, ratio = null_2x2(e00, e01, e10, e11, pick - nf == 1)
            singular[i_in] = ratio
        else:
            det = e00 * e11 - e01 * e10
            b0 = (-z[ends[2]] * e11 + z[ends[3]] * e01) / det
            b1 = (-z[ends[3]] * e00 + z[ends[2]] * e10) / det
        for j in range(n_out):
            out[i_in, j] = (T[j, 0] * b0 + T[j, 1] * b1 + t[j]) * outputs[j, 3]

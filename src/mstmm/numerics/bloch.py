"""A periodic cell's Bloch conditions (issue 23): the cell's transfer relation as one
descriptor pencil, its characteristic polynomial in the Bloch multiplier, and the
condensed dynamic stiffness of the cell closed on itself.

The cell [0, L] is marched like the paper's overall transfer equation (Eqs. (2)-(4)),
keeping every unknown: u = [Z_0, q_1 .. q_n] (the state at x = 0 and the components'
unknowns, in x order), the state at x = L is Z_L = Phi u, and each component adds its
constraint rows Cz Z + Cq q = 0. A Bloch wave Z_L = lam Z_0 is a null vector of

    M(lam) = [[C], [Phi - lam [I 0]]]      ((n + 4)-square),

and det M(lam) = g det(T - lam I) for the cell's transfer matrix T (when it exists; a
support makes T singular and M stays regular): T is symplectic (reciprocity: the dynamic
stiffness is symmetric, complex symmetric when damped), so det M is palindromic,
c0 + c1 lam + c2 lam^2 + c1 lam^3 + c0 lam^4 = lam^2 P(mu) with mu = lam + 1/lam and

    P(mu) = c0 mu^2 + c1 mu + (c2 - 2 c0).

Three determinants give it: c0 = det M(0), P(2) = det M(1), P(-2) = det M(-1). Each root
mu = 2 cos(k L) of P is a pair of waves +-k. The frequencies where a wave pair turns
propagating or evanescent at k L = 0 or pi are the zeros of P(+-2) = det M(+-1): the
eigenvalues of the cell closed on itself periodically (Z_L = Z_0) or antiperiodically
(Z_L = -Z_0), whose Wittrick-Williams count is the count of the cell clamped at both
ends plus the negative eigenvalues of the 2x2 dynamic stiffness K of the closed cell at
its joint (``closed_stiffness``).

Units are the kernel's (L = EI_0 = mbar_0 = 1 in the parameter vector's first segment);
mu, lam and k L do not depend on them.
"""

import cmath
import math

import numpy as np
from numba import types
from numba.extending import overload

from mstmm.jit import njit

from .frf import (
    eliminate_c,
)
from .linalg import (
    lu_det,
    lu_logdet,
    solve_in_place,
)
from .segment import (
    segment_piece,
)
from .shapes import QMASS_ROWS
from .walk import (
    STOP_END,
    STOP_EVENT,
    walk_next,
)

#: Most beam (in lam h, over one piece or several short ones) between two
#: re-orthonormalisations of the subspace: across it a decaying solution loses at most
#: exp(2 BLOCH_STEP) eps against a growing one.
BLOCH_STEP = 2.0
SQRT_HALF = math.sqrt(0.5)


@njit(cache=True)
def orthonormalise8(X):
    """The columns of X (8 x 4) made orthonormal (modified Gram-Schmidt, one pass: the
    subspace is what counts, orthogonality only keeps it well conditioned): the same
    subspace, of states whose growth across the cell no longer swamps the others. Returns
    log det R of X = X_new R (the sum of the logs of the columns' norms; -inf for a zero
    column), what det X0 is divided by."""
    det = 1.0
    for c in range(4):
        for k in range(c):
            d = X[0, k].conjugate() * X[0, c]
            for r in range(1, 8):
                d += X[r, k].conjugate() * X[r, c]
            for r in range(8):
                X[r, c] -= d * X[r, k]
        nrm = 0.0
        for r in range(8):
            nrm += X[r, c].real ** 2 + X[r, c].imag ** 2
        nrm = math.sqrt(nrm)
        if nrm > 0.0:
            for r in range(8):
                X[r, c] /= nrm
        det *= nrm  # four norms of a basis grown by at most exp(BLOCH_STEP): no overflow
    return math.log(det) if det > 0.0 else -math.inf


@njit(cache=True, inline="always")
def times_end(M, a, X, c):
    """(M X_L)[a, c]: row a of M (k x 4) times column c of X's lower half X_L."""
    return M[a, 0] * X[4, c] + M[a, 1] * X[5, c] + M[a, 2] * X[6, c] + M[a, 3] * X[7, c]


def event_frequency(w1):
    """What a kernel's descriptor takes: w1 = (lam_0 L)^2 (the complex ``shape_event_c``)
    or b4 = w1^2 (the real ``shape_event``)."""
    return w1 if isinstance(w1, complex) else w1 * w1


@overload(event_frequency)
def _event_frequency(w1):
    if isinstance(w1, types.Complex):
        return lambda w1: w1
    return lambda w1: w1 * w1


#: Where ``bloch_work``'s tuple holds det X0 (``cell_subspace_in``).
DET0 = 15


@njit(cache=True)
def bloch_work(p, sizes, c):
    """Scratch for ``cell_subspace_in`` (allocated once per thread, not per frequency): the
    arrays of the march, of type c (np.complex128, or np.float64 for the real march of an
    undamped cell at a real frequency)."""
    nq_all, max_q = sizes(p)
    nb = max(1, max_q)
    return (
        np.zeros((8, 4), dtype=c),  # X
        np.zeros((4, 4), dtype=c),  # S
        np.zeros((nb, 4), dtype=c),  # Cz
        np.zeros((nb, nb), dtype=c),  # Cq
        np.zeros((4, 4), dtype=c),  # A
        np.zeros((4, nb), dtype=c),  # B
        np.zeros((QMASS_ROWS, nb)),  # the unknowns' masses
        np.zeros((nb, nb + 4), dtype=c),  # C
        np.zeros(nb, dtype=c),  # rhs
        np.ones(nb),  # row scales
        np.zeros((nb + 4, nb + 4), dtype=c),  # N
        np.zeros(nb + 4, dtype=c),  # xp
        np.zeros((8, 4), dtype=c),  # Y
        np.zeros((4, 4), dtype=c),  # U
        np.zeros((4, 4, 4), dtype=c),  # a general segment's powers of A
        np.zeros(2, dtype=c),  # det X0 as (phase, log): ``cell_subspace_in``
        np.empty(nb, dtype=np.int64),  # ``eliminate_c``'s pivot columns
        np.empty(nb + 4, dtype=np.bool_),  # and its used columns
    )


@njit(cache=True)
def cell_subspace(event, sizes, w, p, damped):
    """``cell_subspace_in`` with its own scratch (complex)."""
    return cell_subspace_in(event, w, p, damped, bloch_work(p, sizes, np.complex128))


@njit(cache=True)
def cell_subspace_in(event, w, p, damped, work):
    """The pairs (Z_0, Z_L) of states at the cell's ends that its beam and components admit,
    at the frequency w (rad/s; complex, or real with a real ``work`` and the kernel's real
    descriptor for an undamped cell: the same march in real arithmetic, about a third of
    the time): a 4-dimensional subspace of C^8, returned as an
    orthonormal basis X = [X0; XL] (8 x 4; ``work``'s array). Pieces carry XL by their
    transfer (lam h <= BLOCH_STEP), a component's constraints Cz Z + Cq q = 0 are solved
    for the free parameters (``eliminate_c``) and Z+ = A Z + B q; X is re-orthonormalised
    after every component and before a piece would carry more than BLOCH_STEP of lam h
    since the last time (short pieces share one), so the growing solutions never swamp the
    decaying ones (a long cell, a high frequency). ``event`` is the kernel's complex
    descriptor (``shape_event_c``; real: ``shape_event``), ``work`` from ``bloch_work``;
    ``damped``: the segments' loss factors count. An empty array where a component leaves
    fewer than four free parameters.

    work[DET0] <- det X0 as (phase, log |det|) (phase 0: exactly singular, a support in the
    cell), followed through the march rather than taken from X: X0 = X0_prev N_a at a
    component (N_a the free parameters' rows of Z_0), divided by det R at each
    re-orthonormalisation. It is P's leading coefficient c0 (``bloch_poly``), which is
    ~ 1 / |lam| for a wave growing by lam across the cell: an LU of X0 (entries O(1))
    gets it only to eps absolute, and an evanescent pair's Im k L (40 for a bare beam's
    at lam L = 40) came out 9 % off; a supported cell's c0 = 0 came out as 1e-16, a
    spurious pair with Im k L = 37."""
    L = p[0]
    EI = p[1]
    mbar = p[2]
    w1 = w * L * L * math.sqrt(mbar / EI)
    beta = np.sqrt(w1)  # real for the real march (w >= 0), else complex
    X, S, Cz, Cq, Ad, B, ev_mass, C, rhs, row_scale, N, xp, Y, U, Ff, det0, piv, used = work
    det0[0] = 1.0
    det0[1] = -math.log(4.0)  # det X0 = SQRT_HALF^4
    n_ev = int(p[4])
    for a in range(8):
        for c in range(4):
            X[a, c] = 0.0
    for a in range(4):  # Z_L = Z_0 before the first piece, orthonormal
        X[a, a] = SQRT_HALF
        X[4 + a, a] = SQRT_HALF
    pos = 0.0
    seg = 0
    grown = 0.0  # lam h carried since X was last orthonormalised (<= BLOCH_STEP)
    r = 0
    while True:  # the walk along the beam (``walk_next``)
        sg, stop, what, row, r, seg = walk_next(p, r, seg, pos, n_ev, math.inf)
        rho = (stop - pos) / L
        if rho > 0.0:
            pieces, kh = segment_piece(p, sg, w1, beta, damped, rho, BLOCH_STEP, U, Ff)
            for _ in range(pieces):
                if grown + kh > BLOCH_STEP:
                    det0[1] -= orthonormalise8(X)
                    grown = 0.0
                for a in range(4):
                    for c in range(4):
                        S[a, c] = times_end(U, a, X, c)
                for a in range(4):
                    for c in range(4):
                        X[4 + a, c] = S[a, c]
                grown += kh
            pos = stop
        if what == STOP_END:
            break
        if what != STOP_EVENT:
            continue
        nc, nq = event(p, row, event_frequency(w1), Cz, Cq, Ad, B, ev_mass)
        n = 4 + nq
        for a in range(nc):
            sc = 0.0
            for c in range(4):
                C[a, c] = times_end(Cz, a, X, c)
                sc = max(sc, abs(Cz[a, c]))
            for j in range(nq):
                C[a, 4 + j] = Cq[a, j]
                sc = max(sc, abs(Cq[a, j]))
            rhs[a] = 0.0
            row_scale[a] = sc if sc > 0.0 else 1.0
        if nc > 0:
            free = eliminate_c(C, rhs, row_scale, nc, n, N, xp, piv, used)
        else:
            free = n
            for j in range(n):
                for c in range(n):
                    N[j, c] = 1.0 if j == c else 0.0
        # (Z_0, Z+) of the free parameters (a, q) = N c: Z+ = A XL a + B q; four of them
        # (more only exactly at a component's own frequency with the beam held)
        for a in range(4):
            for j in range(4):
                S[a, j] = times_end(Ad, a, X, j)
        for c in range(4):
            for a in range(4):
                z0 = X[a, 0] * N[0, c]
                zl = S[a, 0] * N[0, c]
                for j in range(1, 4):
                    z0 += X[a, j] * N[j, c]
                    zl += S[a, j] * N[j, c]
                for j in range(nq):
                    zl += B[a, j] * N[4 + j, c]
                Y[a, c] = z0
                Y[4 + a, c] = zl
        if free < 4:
            return X[:0]
        for a in range(4):  # X0 <- X0 N_a
            for c in range(4):
                S[a, c] = N[a, c]
        d = lu_det(S)
        if d == 0.0:
            det0[0] = 0.0
        else:
            det0[0] *= d / abs(d)
            det0[1] += math.log(abs(d))
        X[:, :] = Y
        det0[1] -= orthonormalise8(X)
        grown = 0.0
    if grown > 0.0:
        det0[1] -= orthonormalise8(X)
    return X


@njit(cache=True)
def pencil_det(X, lam, A):
    """det(XL - lam X0) as (phase, log|det|): g det(T - lam I), T the cell's transfer (A:
    4x4 scratch of X's type, real or complex)."""
    for a in range(4):
        for c in range(4):
            A[a, c] = X[4 + a, c] - lam * X[a, c]
    return lu_logdet(A)


@njit(cache=True)
def bloch_poly(X, A, det0):
    """P(mu) = c0 mu^2 + c1 mu + c2 from det(XL - lam X0) at lam = 1, -1 and c0 = det X0
    as ``cell_subspace_in`` followed it (``det0``: phase, log) (A: 4x4 scratch of X's type),
    over a common scale exp(ref): returns (c0, c1, c2, P(2), P(-2), ref)."""
    ph0, l0 = det0[0], det0[1].real
    ph1, l1 = pencil_det(X, 1.0, A)
    ph2, l2 = pencil_det(X, -1.0, A)
    ref = max(l0, max(l1, l2))
    c0 = ph0 * math.exp(l0 - ref)
    pp = ph1 * math.exp(l1 - ref)  # P(2)
    pm = ph2 * math.exp(l2 - ref)  # P(-2)
    c1 = 0.25 * (pp - pm)
    c2 = 0.5 * (pp + pm) - 4.0 * c0  # c2 - 2 c0 of the module docstring
    return c0, c1, c2, pp, pm, ref


#: Both roots of P within this of +-2 (as omega -> 0): their sum is taken from P at a
#: third point (``bloch_slope``), not from P(2) - P(-2).
CROWDED = 0.1


@njit(cache=True)
def bloch_slope(X, A, c0, ps, sh, h, ref):
    """b = P'(sh) (sh = +-2) from P(sh + sign(sh) h) = det(XL - lam X0) / lam^2 (lam real,
    |lam| > 1): b = (P(sh + nu) - P(sh) - c0 nu^2) / nu. Where both roots of P lie within
    about h of sh, each term is about c0 h^2 and b keeps its digits; from c1 =
    (P(2) - P(-2)) / 4 it is the difference of numbers about 4 c0 apart, an error of
    about eps c0 that moves roots only ~h from sh by eps (k L loses digits as 1 / omega)."""
    nu = h if sh > 0.0 else -h
    lam = 1.0 + 0.5 * h + math.sqrt(0.5 * h * (2.0 + 0.5 * h))
    if sh < 0.0:
        lam = -lam
    ph, lg = pencil_det(X, lam, A)
    q = ph * math.exp(lg - ref) / (lam * lam)  # P(sh + nu), on bloch_poly's scale
    return (q - ps - c0 * nu * nu) / nu


@njit(cache=True)
def bloch_mu(c0, c1, c2, pp, pm):
    """The roots mu = 2 cos(k L) of P (``bloch_poly``) and each one's offset nu from the
    nearer of +2 and -2, s (inf when P is linear: a constrained cell has one pair):
    ``(mu_1, mu_2, nu_1, nu_2, s)``.

    The roots are those of P(s + nu) = c0 nu^2 + (2 s c0 + c1) nu + P(s), s = +-2 the
    nearer to the roots' mean, whose constant term P(+-2) = det M(+-1) is a determinant
    of its own (``bloch_poly``'s pp, pm), not a difference: as omega -> 0 both roots
    crowd at mu = 2 (k L -> 0 and the evanescent pair's i k L -> 0) and the quadratic in
    mu itself kept about the square root of the working precision of mu - 2 (k L 15 %
    off at omega = 1e-3 rad/s on examples/metamaterial.toml)."""
    if c0 == 0.0:  # linear: one pair
        if c1 == 0.0:
            inf = complex(math.inf, 0.0)
            return inf, inf, inf, inf, 2.0
        mu = -c2 / c1
        sh = 2.0 if mu.real >= 0.0 else -2.0
        inf = complex(math.inf, 0.0)
        return inf, mu, inf, mu - sh, sh
    mean = -c1 / (2.0 * c0)
    sh = 2.0 if mean.real >= 0.0 else -2.0
    ps = pp if sh > 0.0 else pm
    nu1, nu2 = shifted_roots(c0, 2.0 * sh * c0 + c1, ps)
    return sh + nu1, sh + nu2, nu1, nu2, sh


@njit(cache=True)
def shifted_roots(c0, b, ps):
    """The roots nu of c0 nu^2 + b nu + ps (c0 != 0), without cancellation: the larger
    in modulus from -(b + sqrt(disc)) / 2 with the sign that adds, the other from the
    product ps / c0."""
    disc = cmath.sqrt(b * b - 4.0 * c0 * ps)
    if (b.conjugate() * disc).real < 0.0:
        disc = -disc
    qq = -0.5 * (b + disc)
    if qq == 0.0:  # both at 0
        return complex(0.0, 0.0), complex(0.0, 0.0)
    return qq / c0, ps / qq


@njit(cache=True)
def propagating_count(c0, c1, c2, pp, pm):
    """How many roots of the real P lie in [-2, 2] (wave pairs that propagate), from the
    signs of P(2) and P(-2), each exact away from its own zeros (the band edges): one
    when they differ; else two when both roots are real, the vertex lies inside and P(+-2)
    have the leading coefficient's sign; else none (a complex pair, or both outside)."""
    a = c0.real
    if (pp.real > 0.0) != (pm.real > 0.0):
        return 1
    if a == 0.0:
        return 0
    if c1.real * c1.real - 4.0 * a * c2.real < 0.0:
        return 0
    v = -c1.real / (2.0 * a)
    if -2.0 < v < 2.0 and (pp.real > 0.0) == (a > 0.0):
        return 2
    return 0


@njit(cache=True)
def bloch_k(mu, nu, sh, fold):
    """k L from mu = 2 cos(k L) (nu = mu - sh, sh = +-2: ``bloch_mu``): Im k L >= 0 (the
    wave decaying towards +x); with ``fold`` (an undamped cell at a real frequency) also
    0 <= Re k L <= pi, the pair's wave -conj(k) taken where k has Re k L < 0 (the other
    root of a complex conjugate pair of mu); pi + i inf for an infinite mu. Where |nu| is
    small, k L = 2 asin(sqrt(-nu / 4)) (sh = 2) or pi - 2 asin(sqrt(nu / 4)) (sh = -2)
    from nu itself, whose digits acos(mu / 2) would lose as k L -> 0 or pi."""
    if not (math.isfinite(mu.real) and math.isfinite(mu.imag)):
        return complex(math.pi, math.inf)
    if abs(nu) < 1.0:
        if sh > 0.0:
            kL = 2.0 * cmath.asin(cmath.sqrt(-0.25 * nu))
        else:
            kL = math.pi - 2.0 * cmath.asin(cmath.sqrt(0.25 * nu))
    else:
        kL = cmath.acos(0.5 * mu)
    # k L and k L + 2 pi n are one wave (lam = exp(i k L)): Re k L into (-pi, pi]
    if kL.real > math.pi:
        kL = complex(kL.real - 2.0 * math.pi, kL.imag)
    elif kL.real <= -math.pi:
        kL = complex(kL.real + 2.0 * math.pi, kL.imag)
    if kL.imag < 0.0 or (kL.imag == 0.0 and kL.real < 0.0):
        kL = -kL  # the pair's wave decaying towards +x
    if kL.real <= -math.pi:
        kL = complex(kL.real + 2.0 * math.pi, kL.imag)
    if fold:
        kL = complex(abs(kL.real), abs(kL.imag))
    return kL


@njit(cache=True)
def bloch_waves(X, A, det0, fold, out):
    """out <- (mu_1, mu_2, k_1 L, k_2 L, n): ``bloch_mu`` and ``bloch_k``, the more
    attenuated pair first (of a complex conjugate pair, Im mu > 0 first), and n the pairs
    that propagate (``propagating_count``; meaningful for an undamped cell) (A: 4x4
    scratch of X's type; ``fold``: ``bloch_k``'s)."""
    c0, c1, c2, pp, pm, ref = bloch_poly(X, A, det0)
    mu1, mu2, nu1, nu2, sh = bloch_mu(c0, c1, c2, pp, pm)
    h = max(abs(nu1), abs(nu2))
    if c0 != 0.0 and 0.0 < h < CROWDED:  # both roots crowd at sh: b from a third point
        ps = pp if sh > 0.0 else pm
        nu1, nu2 = shifted_roots(c0, bloch_slope(X, A, c0, ps, sh, h, ref), ps)
        mu1, mu2 = sh + nu1, sh + nu2
    if abs(mu2) > abs(mu1):  # the larger modulus first
        mu1, mu2, nu1, nu2 = mu2, mu1, nu2, nu1
    out[4] = propagating_count(c0, c1, c2, pp, pm)
    k1 = bloch_k(mu1, nu1, sh, fold)
    k2 = bloch_k(mu2, nu2, sh, fold)
    if k2.imag > k1.imag or (k2.imag == k1.imag and mu2.imag > mu1.imag):
        # (a complex conjugate pair of mu in a gap, equally attenuated: Im mu > 0 first)
        mu1, mu2, k1, k2 = mu2, mu1, k2, k1
    out[0] = mu1
    out[1] = mu2
    out[2] = k1
    out[3] = k2


@njit(cache=True)
def closed_stiffness(X, s, K):
    """K <- the 2x2 dynamic stiffness (symmetric) of the cell closed on itself at its joint
    (Z_L = s Z_0 for the displacements Y, theta; s = +1 periodic, -1 antiperiodic): the
    pairs of X = [X0; XL] with (Y, theta) = d at x = 0 and s d at x = L need the joint
    forces F = (M, Q)_L - s (M, Q)_0; K pairs them with d by virtual work (rows -Q, M,
    times s; units of the kernel). Undamped (real) X. Returns False where no pair has a
    given d: a frequency of the cell clamped at both ends (the count's J0 jumps there)."""
    A = np.zeros((4, 4))
    R = np.zeros((4, 2))
    for c in range(4):
        for a in range(2):
            A[a, c] = X[4 + a, c].real - s * X[a, c].real
            A[2 + a, c] = X[a, c].real
    R[2, 0] = 1.0
    R[3, 1] = 1.0
    if not solve_in_place(A, R, 2):
        return False
    for j in range(2):
        fm = 0.0
        fq = 0.0
        for c in range(4):
            fm += (X[6, c].real - s * X[2, c].real) * R[c, j]
            fq += (X[7, c].real - s * X[3, c].real) * R[c, j]
        K[0, j] = -s * fq
        K[1, j] = s * fm
    return True

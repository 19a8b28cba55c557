"""A segment's transfer across a piece, whichever its kind: the Euler-Bernoulli segment by
its printed beam functions (paper Eq. (1)), a segment with a Timoshenko shear stiffness,
a rotary inertia, an axial force or an elastic foundation (``derive/segments/general.py``,
issue 22) by ``exp(A h)`` of its printed field matrix (``general_field``,
``mstmm.numerics.field``). Every walk along the beam (the stable chain, the count, the
paper's determinant, the mode shapes, the frequency response) asks here.

Units are the kernel's, L = EI_0 = mbar_0 = 1; ``w2 = (lam_0 L)^4`` the squared frequency
(complex in damped kernels), ``stiff = 1 + i eta`` the segment's loss factor on its stiffnesses
(EI and every term declared with ``LOSS``: ``mstmm/physics/terms/``; not on the axial
force, a load).
"""

import cmath
import math

import numpy as np
from numba import types
from numba.extending import overload

from mstmm.jit import njit

from .beam import (
    beam_transfer_scaled,
    beam_transfer_scaled_c,
    general_field,
)
from .field import (
    PAIR_I,
    PAIR_J,
    clamped_clamped_bound,
    det4,
    wavenumber,
)
from .layout import (
    COL_EI,
    COL_ETA,
    COL_MBAR,
    FOUNDATION,
    HEAD,
    N_TERMS,
    ROTARY,
    ROTATIONAL,
    SEGMENT_WIDTH,
    SHEAR,
    TENSION,
    TERM_LOSS,
    TERM_ROLE,
    TERM_SCALE,
    TERMS,
    X_END,
)
from .walk import (
    renormalise_lazy,
    segment_scale,
)

#: Longest piece (in k h, k a wavenumber of the segment) whose ``exp(A h)`` the walks form
#: in one step: short enough that no growing solution swamps a decaying one within it.
FIELD_STEP = 1.0


@njit(cache=True, inline="always")
def balance(A):
    """The wavenumber that balances A (``wavenumber``), at least 1 (units L = 1): at a low
    frequency the field matrix is balanced as it stands."""
    return max(wavenumber(A), 1.0)


@njit(cache=True, inline="always")
def is_general(p, seg):
    """Whether segment seg has any term beyond Euler-Bernoulli (a nonzero value in its
    row's terms: ``catalog.SEGMENT_PHYSICS``)."""
    i = HEAD + SEGMENT_WIDTH * seg + TERMS
    # no branches in the sum (the walks' compile time): it is 0 only when all are
    total = 0.0
    for j in range(N_TERMS):
        total += abs(p[i + j])
    return total != 0.0


@njit(cache=True)
def any_general(p):
    """Whether any segment of p has a term beyond Euler-Bernoulli."""
    for seg in range(int(p[3])):
        if is_general(p, seg):
            return True
    return False


@njit(cache=True, inline="always")
def term_value(p, seg, j):
    """Term j of segment seg, dimensionless (units L = EI_0 = mbar_0 = 1: its unit's
    exponents, ``layout.TERM_SCALE``)."""
    s = TERM_SCALE[j]
    return p[HEAD + SEGMENT_WIDTH * seg + TERMS + j] * p[0] ** s[0] * p[1] ** s[1] * p[2] ** s[2]


@njit(cache=True, inline="always")
def segment_values(p, seg, stiff):
    """The dimensionless ``(e, m, kGA, rhoI, t, r, k_w)`` of segment seg (units L = EI_0 =
    mbar_0 = 1): EI and mbar over the first segment's, and each role's sum of its terms
    (``physics.segment.ROLES``: shear, rotary inertia, tension, rotational and Winkler
    foundation), a term with ``LOSS`` times ``stiff`` (1, or 1 + i eta; EI too)."""
    i = HEAD + SEGMENT_WIDTH * seg
    zero = 0.0 * stiff
    e = p[i + COL_EI] / p[1] * stiff
    kGA = zero
    rhoI = 0.0
    t = zero
    r = zero
    k_w = zero
    for j in range(N_TERMS):
        v = term_value(p, seg, j)
        if v == 0.0:
            continue
        f = v * stiff if TERM_LOSS[j] else v + zero
        role = TERM_ROLE[j]
        if role == SHEAR:
            kGA += f
        elif role == ROTARY:
            rhoI += v
        elif role == TENSION:
            t += f
        elif role == ROTATIONAL:
            r += f
        elif role == FOUNDATION:
            k_w += f
    return e, p[i + COL_MBAR] / p[2], kGA, rhoI, t, r, k_w


@njit(cache=True)
def segment_field(p, seg, w2, stiff, A):
    """A <- the field matrix of segment seg at the squared frequency w2 (real or complex
    like A), its stiffnesses times ``stiff`` (1, or 1 + i eta)."""
    e, m, kGA, rhoI, t, r, k_w = segment_values(p, seg, stiff)
    general_field(e, m, w2, kGA, rhoI, t, r, k_w, A)


@njit(cache=True, inline="always")
def field_compound(v, F, rho, U, E, w):
    """v <- C2(exp(A rho)) v (the stable chain's step across a piece of a general
    segment; F from ``field_prepare``), in equal pieces of k h <=
    FIELD_STEP, renormalised when its largest entry leaves [2^-20, 2^20]
    (``renormalise_lazy``: a piece's step grows it by e^2 or so); returns the log taken
    out. One ``field_exp`` and
    one ``second_compound`` per call; U (4 x 4), E (6 x 6) and w (6) are work space."""
    k = field_balance(F)
    pieces = max(1, int(math.ceil(k * rho / FIELD_STEP)))
    field_exp(F, rho / pieces, U)
    second_compound(U, E)
    log = 0.0
    for _ in range(pieces):
        compound_step(E, v, w)
        log += renormalise_lazy(v)
    return log


@njit(cache=True, inline="always")
def compound_step(E, v, w):
    """v <- E v, the minors carried across a piece by its second compound E (w: work space)."""
    for a in range(6):
        w[a] = (
            E[a, 0] * v[0]
            + E[a, 1] * v[1]
            + E[a, 2] * v[2]
            + E[a, 3] * v[3]
            + E[a, 4] * v[4]
            + E[a, 5] * v[5]
        )
    for a in range(6):
        v[a] = w[a]


@njit(cache=True)
def segment_compound(v, p, seg, w2, stiff, rho, F, ready, U, E, w):
    """``field_compound`` across rho of general segment seg at the squared frequency w2
    (real, or complex with ``stiff`` = 1 + i eta); F holds (A, A^2, A^3) of segment
    ``ready`` (prepared again when seg differs); U, E, w: work space. Returns (the log
    taken out, seg)."""
    if ready != seg:
        field_prepare(p, seg, w2, stiff, F)
    return field_compound(v, F, rho, U, E, w), seg


@njit(cache=True)
def count_pieces(p, seg, F, w2, rho):
    """Pieces of equal length for the count across rho of general segment seg (F from
    ``field_prepare``): k h <= FIELD_STEP, and each piece's proved clamped-clamped bound
    (``clamped_clamped_bound``) above w2, so that its J0 is 0."""
    e, m, kGA, rhoI, t, r, k_w = segment_values(p, seg, 1.0)
    pieces = max(1, int(math.ceil(field_balance(F) * rho / FIELD_STEP)))
    shear = math.inf if kGA == 0.0 else kGA
    # the rotational and Winkler foundations (nonnegative: physics.segment.ROLES) only
    # raise the clamped-clamped frequencies: the bound without them holds
    for _ in range(200):
        if clamped_clamped_bound(e, shear, rhoI, m, t, rho / pieces) > w2:
            break
        pieces *= 2
    return pieces


@njit(cache=True, inline="always")
def piece_transfer(bs, e, rho, U):
    """U <- D U(bs rho) D^-1, D = diag(1, 1, e, e): a piece of an Euler-Bernoulli segment
    whose EI is e times the first's, unscaled (the printed functions take exp(bs rho) out
    beyond bs rho = 1.5: it is put back; none on the marches' pieces of bs rho <=
    MARCH_STEP)."""
    shift = beam_transfer_scaled(bs, rho, U)
    f = math.exp(shift) if shift != 0.0 else 1.0
    if e != 1.0 or f != 1.0:
        for r in range(4):
            for c in range(4):
                U[r, c] *= f * (e if r >= 2 else 1.0) / (e if c >= 2 else 1.0)


@njit(cache=True)
def piece_transfer_c(bs, e, rho, U):
    """U <- D U(bs rho) D^-1 for a complex bs and segment factor e (its EI, with its loss
    factor, over the first's), unscaled (the printed functions take exp(bs rho) out beyond
    |bs rho| = 1.5: it is put back)."""
    shift = beam_transfer_scaled_c(bs, rho, U)
    f = cmath.exp(shift) if shift != 0.0 else 1.0
    for r in range(4):
        for c in range(4):
            U[r, c] *= f * (e if r >= 2 else 1.0) / (e if c >= 2 else 1.0)


@njit(cache=True)
def segment_piece_c(p, seg, w1, beta, damped, rho, step, U, F):
    """U <- the transfer across rho / pieces of segment seg in complex arithmetic (w1 =
    (lam_0 L)^2, beta = sqrt(w1); ``damped``: its stiffnesses times 1 + i eta), the
    pieces of equal length keeping k h <= step; F is scratch for a general segment's
    powers of A. Returns the number of pieces and the k h of each (<= step)."""
    i = HEAD + SEGMENT_WIDTH * seg
    stiff = 1.0 + 1j * (p[i + COL_ETA] if damped else 0.0)
    if is_general(p, seg):
        field_prepare(p, seg, w1 * w1, stiff, F)
        k = field_balance(F)
        pieces = max(1, int(math.ceil(k * rho / step)))
        field_exp(F, rho / pieces, U)
        return pieces, k * rho / pieces
    e = p[i + COL_EI] / p[1] * stiff
    bs = beta * cmath.sqrt(cmath.sqrt(p[i + COL_MBAR] / p[2] / e))
    pieces = max(1, int(math.ceil(abs(bs) * rho / step)))
    piece_transfer_c(bs, e, rho / pieces, U)
    return pieces, abs(bs) * rho / pieces


@njit(cache=True)
def segment_piece_r(p, seg, w1, beta, damped, rho, step, U, F):
    """``segment_piece_c`` in real arithmetic: an undamped segment at a real frequency (w1
    = (lam_0 L)^2 >= 0, beta = sqrt(w1); ``damped`` unused), a quarter of the complex
    twin's multiplications."""
    if is_general(p, seg):
        field_prepare(p, seg, w1 * w1, 1.0, F)
        k = field_balance(F)
        pieces = max(1, int(math.ceil(k * rho / step)))
        field_exp(F, rho / pieces, U)
        return pieces, k * rho / pieces
    e, a = segment_scale(p, seg)
    bs = beta * a
    pieces = max(1, int(math.ceil(bs * rho / step)))
    h = rho / pieces
    piece_transfer(bs, e, h, U)
    return pieces, bs * h


def segment_piece(p, seg, w1, beta, damped, rho, step, U, F):
    """``segment_piece_c`` or ``segment_piece_r`` by the type of U (complex or real): the
    Bloch cell's march is written once for both (compiled: chosen when numba types it)."""
    twin = segment_piece_c if np.iscomplexobj(U) else segment_piece_r
    return twin(p, seg, w1, beta, damped, rho, step, U, F)


@overload(segment_piece)
def _segment_piece(p, seg, w1, beta, damped, rho, step, U, F):
    twin = segment_piece_c if isinstance(U.dtype, types.Complex) else segment_piece_r
    return lambda p, seg, w1, beta, damped, rho, step, U, F: twin(
        p, seg, w1, beta, damped, rho, step, U, F
    )


@njit(cache=True)
def segment_pieces(p, seg, beta, rho, step, F, ready):
    """Pieces of equal length across rho of segment seg for a march whose pieces keep
    k h <= step (beta: lam_0 L, real). F holds ``field_prepare`` of segment ``ready``
    (prepared again when a general seg differs). Returns (pieces, the segment F holds)."""
    if is_general(p, seg):
        if ready != seg:
            field_prepare(p, seg, beta**4, 1.0, F)
            ready = seg
        k = field_balance(F)
    else:
        e, a = segment_scale(p, seg)
        k = beta * a
    return max(1, int(math.ceil(k * rho / step))), ready


@njit(cache=True)
def piece_matrix(p, seg, beta, h, U, F, ready):
    """U <- the transfer across a short piece h of segment seg (real, beta = lam_0 L;
    k h <= 1, as ``segment_pieces`` cuts them). F holds ``field_prepare`` of segment
    ``ready`` (prepared again when a general seg differs). Returns the segment F holds."""
    if is_general(p, seg):
        if ready != seg:
            field_prepare(p, seg, beta**4, 1.0, F)
            ready = seg
        field_exp(F, h, U)
    else:
        e, a = segment_scale(p, seg)
        piece_transfer(beta * a, e, h, U)
    return ready


@njit(cache=True, inline="always")
def _role_sum(p, seg, role):
    """The dimensionless sum of segment seg's terms of one role."""
    out = 0.0
    for j in range(N_TERMS):
        if TERM_ROLE[j] == role:
            out += term_value(p, seg, j)
    return out


@njit(cache=True)
def segment_rotary(p, seg):
    """The segment's rotary inertia per length rhoI (units mbar_0 L^2): the mass a section's
    rotation psi carries in the modal mass (``mode_shapes``' gram; once per piece, so its
    rotary terms alone, not every term's value)."""
    return _role_sum(p, seg, ROTARY)


@njit(cache=True)
def segment_constraints(p, knots, h, cx, ct, n):
    """Append to (cx, ct) the constraints the segments' own energy puts on the rigid
    motions (``rigid_dimension``: ct 1 for Y = 0, 2 for theta = 0 at cx; the h free hinges
    at knots), by the roles of their terms (``physics.segment.ROLES``): a Winkler
    foundation holds Y = 0 along its segment (at its ends and at each hinge inside), and
    a tension or a rotational foundation stores ``(t + r) b^2`` per length in a rigid
    rotation b, so that a piece between hinges where the sum of ``t + r`` times length is
    not 0 holds theta = 0 (in compression the rotation is not free either: its energy is
    negative, the count's buckling). Returns the new n."""
    L = p[0]
    start = 0.0
    for seg in range(int(p[3])):
        i = HEAD + SEGMENT_WIDTH * seg
        end = L if seg == int(p[3]) - 1 else p[i + X_END]
        if _role_sum(p, seg, FOUNDATION) != 0.0 and end > start:
            cx[n] = start
            ct[n] = 1
            cx[n + 1] = end
            ct[n + 1] = 1
            n += 2
            for j in range(h):
                if start < knots[j] < end:
                    cx[n] = knots[j]
                    ct[n] = 1
                    n += 1
        start = end
    for j in range(h + 1):  # the pieces between hinges
        a = 0.0 if j == 0 else knots[j - 1]
        b = L if j == h else knots[j]
        work = 0.0
        start = 0.0
        for seg in range(int(p[3])):
            i = HEAD + SEGMENT_WIDTH * seg
            end = L if seg == int(p[3]) - 1 else p[i + X_END]
            overlap = min(end, b) - max(start, a)
            if overlap > 0.0:
                work += (_role_sum(p, seg, TENSION) + _role_sum(p, seg, ROTATIONAL)) * overlap
            start = end
        if work != 0.0 and b > a:
            cx[n] = 0.5 * (a + b)
            ct[n] = 2
            n += 1
    return n


#: Terms of the series of ``field_exp`` (|w| <= 2 (k h)^2 <= 2: the last term is below
#: 4^16 / 32! ~ 1.6e-26 of the first).
SERIES_TERMS = 16
#: A term of ``field_exp``'s series below this ends it: ``f0`` and ``g0`` are about 1 on
#: a piece with k h <= 1, and the remaining terms fall by more than 1/12 each.
SERIES_TAIL = 1e-19


@njit(cache=True)
def field_prepare(p, seg, w2, stiff, F):
    """F[0] <- A of segment seg (``segment_field``), F[1] <- A^2, F[2] <- A^3, and in
    F[3, 0, :3] the coefficients ``a = -tr(A^2)/2``, ``b = det A`` of its characteristic
    polynomial ``l^4 + a l^2 + b`` and its balancing wavenumber ``sqrt(|a| + sqrt|b|)``
    (at least 1): what ``field_exp`` needs, once per segment and frequency. F is 4 x 4 x 4."""
    A = F[0]
    segment_field(p, seg, w2, stiff, A)
    # A vanishes where r + c is even (every segment kind's field: derive.emit checks it),
    # so A^2 where r + c is odd and A^3 where it is even: each entry below is the dense
    # product's, whose other terms are exact zeros, in the same order
    for r in range(4):
        for c in range(4):
            if (r + c) % 2 == 0:
                k = 1 - r % 2  # the columns k of row r where A is not 0: k and k + 2
                F[1, r, c] = A[r, k] * A[k, c] + A[r, k + 2] * A[k + 2, c]
                F[2, r, c] = 0.0
            else:
                F[1, r, c] = 0.0
    for r in range(4):
        for c in range(4):
            if (r + c) % 2 == 1:
                k = r % 2  # the columns of row r where A^2 is not 0
                F[2, r, c] = F[1, r, k] * A[k, c] + F[1, r, k + 2] * A[k + 2, c]
    a = -0.5 * (F[1, 0, 0] + F[1, 1, 1] + F[1, 2, 2] + F[1, 3, 3])
    b = det4(A)
    F[3, 0, 0] = a
    F[3, 0, 1] = b
    F[3, 0, 2] = max(math.sqrt(abs(a) + math.sqrt(abs(b))), 1.0)


@njit(cache=True, inline="always")
def field_exp(F, h, U):
    """U <- exp(A h) from F of ``field_prepare``, for a piece with k h <= 1 (k =
    ``field_balance(F)``).

    The characteristic polynomial of every field matrix here is even, ``l^4 + a l^2 +
    b`` (``a = -tr(A^2)/2``, ``b = det A``: the odd coefficients vanish by its zero pattern),
    so ``M = (A h)^2`` satisfies ``M^2 = -a h^2 M - b h^4 I`` (Cayley-Hamilton) and every
    power ``M^m = p_m I + q_m M`` by a two-term recurrence. With ``exp(B) = f(B^2) + B
    g(B^2)``, ``f(w) = sum w^m/(2m)!``, ``g(w) = sum w^m/(2m+1)!``::

        exp(A h) = f0 I + g0 h A + f1 h^2 A^2 + g1 h^3 A^3

    with ``(f0, f1) = sum (p_m, q_m)/(2m)!`` and ``(g0, g1) = sum (p_m, q_m)/(2m+1)!``. No
    eigenvalue is formed (they coalesce at the foundation's and the shear's cut-offs), no
    matrix is squared, and on a short piece the series has no cancellation: about 30
    scalar operations and one 4 x 4 combination per piece (``tests/test_field.py`` checks
    it against mpmath)."""
    A = F[0]
    h2 = h * h
    a = F[3, 0, 0] * h2
    b = F[3, 0, 1] * h2 * h2
    pm = A[0, 0] * 0.0 + 1.0
    qm = A[0, 0] * 0.0
    f0 = pm * 0.0
    f1 = pm * 0.0
    g0 = pm * 0.0
    g1 = pm * 0.0
    even = 1.0  # 1/(2m)!
    for m in range(SERIES_TERMS):
        odd = even / (2 * m + 1)  # 1/(2m+1)!
        f0 += pm * even
        f1 += qm * even
        g0 += pm * odd
        g1 += qm * odd
        if (abs(pm) + abs(qm)) * even < SERIES_TAIL:  # the rest below rounding of f0 ~ 1
            break
        pm, qm = -b * qm, pm - a * qm
        even = odd / (2 * m + 2)
    g0 *= h
    f1 *= h2
    g1 *= h2 * h
    for r in range(4):  # the even part on r + c even, the odd part elsewhere
        for c in range(4):
            if (r + c) % 2 == 0:
                U[r, c] = f1 * F[1, r, c]
            else:
                U[r, c] = g0 * A[r, c] + g1 * F[2, r, c]
        U[r, r] += f0


@njit(cache=True, inline="always")
def field_balance(F):
    """``balance(A)`` from ``field_prepare``'s F: sqrt(|a| + sqrt|b|), at least 1."""
    return F[3, 0, 2].real


@njit(cache=True, inline="always")
def second_compound(U, E):
    """E <- the 2 x 2 minors of U over the stable chain's pairs (``field.PAIR_I``, ``PAIR_J``):
    C2(U), the step of the minors across a short piece (k h <= 1: no growing solution
    swamps a decaying one within it)."""
    for x in range(6):
        i = PAIR_I[x]
        j = PAIR_J[x]
        for y in range(6):
            k = PAIR_I[y]
            m = PAIR_J[y]
            E[x, y] = U[i, k] * U[j, m] - U[i, m] * U[j, k]

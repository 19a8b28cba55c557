"""A segment's transfer across a piece, whichever its kind: the Euler-Bernoulli segment by
its printed beam functions (paper Eq. (1)), a segment with a Timoshenko shear stiffness,
a rotary inertia, an axial force or an elastic foundation (``derive/segments/general.py``,
issue 22) by ``exp(A h)`` of its printed field matrix (``general_field``,
``mstmm.numerics.field``). Every walk along the beam (the stable chain, the count, the
paper's determinant, the mode shapes, the frequency response) asks here.

Units are the kernel's, L = EI_0 = mbar_0 = 1; ``w2 = (lam_0 L)^4`` the squared frequency (complex
in damped kernels), ``stiff = 1 + i eta`` the segment's loss factor on its stiffnesses
(EI, kappa_GA, foundation_k, foundation_kG; not on the axial force, a load).
"""

import math

import numpy as np
from numba import njit

from mstmm.generated.euler_bernoulli import (
    beam_transfer_scaled,
    beam_transfer_scaled_c,
    general_field,
)

from .field import (
    additive_compound,
    clamped_clamped_bound,
    expm_short,
    wavenumber,
)
from .layout import (
    HEAD,
    SEGMENT_WIDTH,
)
from .walk import (
    renormalise,
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
    """Whether segment seg has any term beyond Euler-Bernoulli (its row's kappa_GA, rho_I,
    axial force, foundation_k, foundation_kG: ``catalog.SEGMENT_KEYS``)."""
    i = HEAD + SEGMENT_WIDTH * seg
    return (
        p[i + 4] != 0.0 or p[i + 5] != 0.0 or p[i + 6] != 0.0 or p[i + 7] != 0.0 or p[i + 8] != 0.0
    )


@njit(cache=True)
def any_general(p):
    """Whether any segment of p has a term beyond Euler-Bernoulli."""
    for seg in range(int(p[3])):
        if is_general(p, seg):
            return True
    return False


@njit(cache=True, inline="always")
def segment_values(p, seg):
    """The dimensionless (e, m, kGA, rhoI, P, k_w, k_G) of segment seg (units L = EI_0 =
    mbar_0 = 1)."""
    L = p[0]
    EI = p[1]
    mbar = p[2]
    i = HEAD + SEGMENT_WIDTH * seg
    L2 = L * L / EI
    return (
        p[i + 1] / EI,
        p[i + 2] / mbar,
        p[i + 4] * L2,
        p[i + 5] / (mbar * L * L),
        p[i + 6] * L2,
        p[i + 7] * L2 * L * L,
        p[i + 8] * L2,
    )


@njit(cache=True)
def segment_field(p, seg, w2, stiff, A):
    """A <- the field matrix of segment seg at the squared frequency w2 (real or complex
    like A), its stiffnesses times ``stiff`` (1, or 1 + i eta)."""
    e, m, kGA, rhoI, P, k_w, k_G = segment_values(p, seg)
    general_field(e * stiff, m, w2, kGA * stiff, rhoI, P, k_w * stiff, k_G * stiff, A)


@njit(cache=True)
def field_compound(v, A, rho):
    """v <- C2(exp(A rho)) v (the stable chain's step across a piece of a general
    segment), in equal pieces of k h <= FIELD_STEP, renormalised after each; returns the
    log taken out. One ``exp(A2 h)`` per call (A2 the additive compound): no 2 x 2 minor of
    the transfer matrix is formed."""
    k = balance(A)
    pieces = max(1, int(math.ceil(k * rho / FIELD_STEP)))
    A2 = np.empty((6, 6), dtype=A.dtype)
    additive_compound(A, A2)
    E = np.empty((6, 6), dtype=A.dtype)
    expm_short(A2, rho / pieces, k, E)
    w = np.empty(6, dtype=v.dtype)
    log = 0.0
    for _ in range(pieces):
        for a in range(6):
            acc = v[0] * 0.0
            for b in range(6):
                acc += E[a, b] * v[b]
            w[a] = acc
        for a in range(6):
            v[a] = w[a]
        log += renormalise(v)
    return log


@njit(cache=True)
def segment_compound(v, p, seg, w2, stiff, rho):
    """``field_compound`` across rho of general segment seg at the squared frequency w2
    (real, or complex with ``stiff`` = 1 + i eta); returns the log taken out."""
    A = np.empty((4, 4), dtype=v.dtype)
    segment_field(p, seg, w2, stiff, A)
    return field_compound(v, A, rho)


@njit(cache=True)
def count_pieces(p, seg, A, w2, rho):
    """Pieces of equal length for the count across rho of general segment seg: k h <=
    FIELD_STEP, and each piece's proved clamped-clamped bound (``clamped_clamped_bound``)
    above w2, so that its J0 is 0."""
    e, m, kGA, rhoI, P, k_w, k_G = segment_values(p, seg)
    k = balance(A)
    pieces = max(1, int(math.ceil(k * rho / FIELD_STEP)))
    shear = math.inf if kGA == 0.0 else kGA
    for _ in range(200):
        if clamped_clamped_bound(e, shear, rhoI, m, P + k_G, rho / pieces) > w2:
            break
        pieces *= 2
    return pieces


@njit(cache=True, inline="always")
def piece_transfer(bs, e, rho, U):
    """U <- D U(bs rho) D^-1, D = diag(1, 1, e, e): a piece of an Euler-Bernoulli segment
    whose EI is e times the first's (bs*rho <= MARCH_STEP: no scaling, shift 0)."""
    beam_transfer_scaled(bs, rho, U)
    if e != 1.0:
        for r in range(4):
            for c in range(4):
                U[r, c] *= (e if r >= 2 else 1.0) / (e if c >= 2 else 1.0)


@njit(cache=True)
def piece_transfer_c(bs, e, rho, U):
    """U <- D U(bs rho) D^-1 for a complex bs and segment factor e (its EI, with its loss
    factor, over the first's), bs*rho <= MARCH_STEP (no scaling)."""
    beam_transfer_scaled_c(bs, rho, U)
    for r in range(4):
        for c in range(4):
            U[r, c] *= (e if r >= 2 else 1.0) / (e if c >= 2 else 1.0)


@njit(cache=True)
def segment_pieces(p, seg, beta, rho, step):
    """Pieces of equal length across rho of segment seg for a march whose pieces keep
    k h <= step (beta: lam_0 L, real)."""
    if is_general(p, seg):
        A = np.empty((4, 4))
        segment_field(p, seg, beta**4, 1.0, A)
        k = balance(A)
    else:
        e, a = segment_scale(p, seg)
        k = beta * a
    return max(1, int(math.ceil(k * rho / step)))


@njit(cache=True)
def piece_matrix(p, seg, beta, h, U):
    """U <- the transfer across a short piece h of segment seg (real, beta = lam_0 L)."""
    if is_general(p, seg):
        A = np.empty((4, 4))
        segment_field(p, seg, beta**4, 1.0, A)
        expm_short(A, h, balance(A), U)
    else:
        e, a = segment_scale(p, seg)
        piece_transfer(beta * a, e, h, U)


@njit(cache=True)
def long_transfer(p, seg, beta, rho, U):
    """U <- the transfer across rho of segment seg, unscaled (the paper's formulation,
    ``u_bar_paper``: growing and decaying solutions together, as the paper forms them)."""
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
def segment_rotary(p, seg):
    """The segment's rotary inertia per length rhoI (units mbar_0 L^2): the mass a section's
    rotation psi carries in the modal mass (``mode_shapes``' gram)."""
    return p[HEAD + SEGMENT_WIDTH * seg + 5] / (p[2] * p[0] * p[0])


@njit(cache=True)
def segment_constraints(p, knots, h, cx, ct, n):
    """Append to (cx, ct) the constraints the segments' own energy puts on the rigid
    motions (``rigid_dimension``: ct 1 for Y = 0, 2 for theta = 0 at cx; the h free hinges
    at knots): a foundation (``foundation_k`` > 0) holds Y = 0 along its segment (at its
    ends and at each hinge inside), and an axial force or a Pasternak layer stores
    ``t b^2`` per length in a rigid rotation b, so that a piece between hinges where
    the sum of ``t`` times length is not 0 holds theta = 0 (in compression the rotation is
    not free either: its energy is negative, the count's buckling). Returns the new n."""
    L = p[0]
    start = 0.0
    for seg in range(int(p[3])):
        i = HEAD + SEGMENT_WIDTH * seg
        end = L if seg == int(p[3]) - 1 else p[i]
        if p[i + 7] != 0.0 and end > start:
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
            end = L if seg == int(p[3]) - 1 else p[i]
            overlap = min(end, b) - max(start, a)
            if overlap > 0.0:
                work += (p[i + 6] + p[i + 8]) * overlap
            start = end
        if work != 0.0 and b > a:
            cx[n] = 0.5 * (a + b)
            ct[n] = 2
            n += 1
    return n

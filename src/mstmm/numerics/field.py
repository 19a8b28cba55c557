"""The field transfer matrix of a segment kind from its differential equation: ``Z' = A Z``
over ``Z = [Y, theta, M, Q]`` with ``A`` constant along the segment (printed by SymPy
from the segment kind's declaration, ``derive/segments``), so that ``U(h) = exp(A h)``
exactly, for any beam theory whose equations have constant coefficients (Euler-Bernoulli,
Timoshenko, axial force, elastic foundations): no closed form and no case analysis (the
sign of each branch's wavenumber squared, the Timoshenko cut-off, buckling) is needed.

``exp(A h)`` is evaluated to rounding on a *short* piece: ``A`` is balanced by the state
scaling ``D = diag(1, k, k^2, k^3)`` (``k`` a wavenumber of the piece, so that every entry
of ``D A D^-1 h`` is O(k h)), then a Taylor series of degree ``TAYLOR`` after scaling the
argument below ``1/2`` by powers of two, squared back. Its second compound (the stable
chain's step) is ``exp(A2 h)`` with ``A2`` the additive compound of ``A`` (eigenvalues
``lam_i + lam_j``): no 2 x 2 minor of ``U`` is formed, so no cancellation between the
growing and decaying solutions. Generic in the dtype: real kernels and complex (damped)
ones share it.
"""

import math

import numpy as np

from mstmm.jit import njit

#: Degree of the Taylor series on a matrix of norm <= 1/2: the remainder is below
#: 0.5^19 / 19! ~ 1.6e-23 of the norm, far under rounding.
TAYLOR = 18
#: The pairs of state indices of the second compound, in the stable chain's order
#: (``mstmm.catalog.PAIRS``).
PAIR_I = np.array([0, 0, 0, 1, 1, 2])
PAIR_J = np.array([1, 2, 3, 2, 3, 3])
#: The order of each state in the wavenumber (Y ~ 1, theta ~ k, M ~ k^2, Q ~ k^3) and of
#: each pair of the compound (the sum of its two).
DEGREES_4 = np.array([0, 1, 2, 3])
DEGREES_6 = np.array([1, 2, 3, 3, 4, 5])


@njit(cache=True)
def additive_compound(A, A2):
    """``A2`` (6 x 6) with ``C2(exp(A t)) = exp(A2 t)``: the derivative of the second
    compound of ``I + t A`` at t = 0, over the pairs (0,1), (0,2), (0,3), (1,2), (1,3),
    (2,3) of the stable chain (``mstmm.catalog.PAIRS``)."""
    for a in range(6):
        i = PAIR_I[a]
        j = PAIR_J[a]
        for b in range(6):
            k = PAIR_I[b]
            m = PAIR_J[b]
            value = (
                A[i, k] * (j == m) + A[j, m] * (i == k) - A[i, m] * (j == k) - A[j, k] * (i == m)
            )
            A2[a, b] = value


@njit(cache=True)
def expm_short(A, h, k, U):
    """``U = exp(A h)`` (n x n, n = 4 or 6) to rounding, for a piece on which ``k h`` is a
    few units at most (``k`` a wavenumber of the piece: it balances the state, ``D = diag(
    k^d)`` with ``d`` each state's order, ``DEGREES``). Taylor series of degree ``TAYLOR``
    on ``D A D^-1 h / 2^s`` (norm <= 1/2), squared s times."""
    n = A.shape[0]
    degrees = DEGREES_4 if n == 4 else DEGREES_6
    B = np.empty_like(U)
    norm = 0.0
    for r in range(n):
        row = 0.0
        for c in range(n):
            B[r, c] = A[r, c] * h * k ** (degrees[c] - degrees[r])
            row += abs(B[r, c])
        norm = max(norm, row)
    s = 0
    while norm > 0.5:
        norm *= 0.5
        s += 1
    f = 0.5**s
    for r in range(n):
        for c in range(n):
            B[r, c] *= f
    # Horner: U = I + B (I + B/2 (I + B/3 (...)))
    T = np.empty_like(U)
    for r in range(n):
        for c in range(n):
            U[r, c] = B[r, c] / TAYLOR + (1.0 if r == c else 0.0)
    for m in range(TAYLOR - 1, 0, -1):
        for r in range(n):
            for c in range(n):
                acc = U[r, c] * 0.0
                for t in range(n):
                    acc += B[r, t] * U[t, c]
                T[r, c] = acc / m + (1.0 if r == c else 0.0)
        for r in range(n):
            for c in range(n):
                U[r, c] = T[r, c]
    for _ in range(s):
        for r in range(n):
            for c in range(n):
                acc = U[r, c] * 0.0
                for t in range(n):
                    acc += U[r, t] * U[t, c]
                T[r, c] = acc
        for r in range(n):
            for c in range(n):
                U[r, c] = T[r, c]
    for r in range(n):
        for c in range(n):
            U[r, c] *= k ** (degrees[r] - degrees[c])


@njit(cache=True)
def wavenumber(A):
    """A wavenumber of ``Z' = A Z`` (4 x 4, trace-free, its characteristic polynomial
    ``lam^4 + a2 lam^2 + a0`` even, as every beam theory's): ``sqrt(|a2| + sqrt|a0|)``
    bounds ``|lam|`` (``a2 = -tr(A^2)/2``, ``a0 = det A``), the scale that balances it."""
    tr2 = A[0, 0] * 0.0
    for r in range(4):
        for c in range(4):
            tr2 += A[r, c] * A[c, r]
    a2 = -0.5 * tr2
    a0 = det4(A)
    return math.sqrt(abs(a2) + math.sqrt(abs(a0)))


@njit(cache=True)
def det4(A):
    """Determinant of a 4 x 4 by its Laplace expansion in 2 x 2 minors."""
    s0 = A[0, 0] * A[1, 1] - A[1, 0] * A[0, 1]
    s1 = A[0, 0] * A[1, 2] - A[1, 0] * A[0, 2]
    s2 = A[0, 0] * A[1, 3] - A[1, 0] * A[0, 3]
    s3 = A[0, 1] * A[1, 2] - A[1, 1] * A[0, 2]
    s4 = A[0, 1] * A[1, 3] - A[1, 1] * A[0, 3]
    s5 = A[0, 2] * A[1, 3] - A[1, 2] * A[0, 3]
    c5 = A[2, 2] * A[3, 3] - A[3, 2] * A[2, 3]
    c4 = A[2, 1] * A[3, 3] - A[3, 1] * A[2, 3]
    c3 = A[2, 1] * A[3, 2] - A[3, 1] * A[2, 2]
    c2 = A[2, 0] * A[3, 3] - A[3, 0] * A[2, 3]
    c1 = A[2, 0] * A[3, 2] - A[3, 0] * A[2, 2]
    c0 = A[2, 0] * A[3, 1] - A[3, 0] * A[2, 1]
    return s0 * c5 - s1 * c4 + s2 * c3 + s3 * c2 - s4 * c1 + s5 * c0


@njit(cache=True)
def clamped_clamped_bound(EI, kGA, rhoI, mbar, tension, h):
    """A proved lower bound of the lowest squared natural frequency of a piece of length h
    clamped at both ends (w = psi = 0), for the energies ``int EI psi'^2 + kGA (w' -
    psi)^2 + tension w'^2 + k_w w^2`` and ``int mbar w^2 + rhoI psi^2`` (``tension``: the
    axial force plus a Pasternak layer's ``k_G``; ``k_w >= 0`` dropped; ``kGA = inf``
    for Euler-Bernoulli, where ``psi = w'``). With ``a = ||w'||``, ``b = ||psi||``:
    ``||psi'|| >= (pi/h) b`` and ``||w|| <= (h/pi) a`` (Poincare: both vanish at the
    ends), ``||w' - psi|| >= |a - b|``; so the Rayleigh quotient is at least the smallest
    eigenvalue of the 2 x 2 pencil ``K2 = [[kGA + tension, -kGA], [-kGA, kGA + EI
    (pi/h)^2]]``, ``M2 = diag(mbar (h/pi)^2, rhoI)`` (K2 positive definite; else no
    bound, -inf). A piece whose bound exceeds omega^2 has J0 = 0: the Wittrick-Williams
    count on such pieces is its nodes' negative pivots alone, for any segment kind."""
    q = (math.pi / h) ** 2
    m1 = mbar / q
    if math.isinf(kGA):  # psi = w': the shear term is a constraint, ||w''|| >= (pi/h) ||w'||
        top = EI * q + tension
        return top / (m1 + rhoI) if top > 0.0 else -math.inf
    k11 = kGA + tension
    k22 = kGA + EI * q
    # k11 k22 - kGA^2 with the kGA^2 cancelled by hand: formed as the difference, a kGA
    # 1e16 times EI q or more leaves 0 (no bound, and count_pieces doubled for ever)
    det = kGA * (tension + EI * q) + tension * EI * q
    if k11 <= 0.0 or det <= 0.0:
        return -math.inf
    if rhoI <= 0.0:  # psi follows w' through the shear spring in series with bending
        return det / k22 / m1
    # smallest root of m1 m2 l^2 - (k11 m2 + k22 m1) l + det = 0 (both roots positive);
    # sqrt(b^2 - 4 m1 m2 det) as b sqrt(1 - r): b^2 overflows for a stiff enough kGA
    b = k11 * rhoI + k22 * m1
    r = 4.0 * m1 * rhoI * (det / b) / b
    return 2.0 * det / (b + b * math.sqrt(max(1.0 - r, 0.0)))

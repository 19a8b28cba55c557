"""Numerics shared by every MSTMM kernel (generated, do not edit).

The beam functions (reduced Krylov and compound functions, series below x = 1.5),
the renormalised compound and count steps, the segment walk of the event table, the
paper's tree (``u_bar_paper``), LU, the scan with Brent and the count (``lowest``), and
the mode-shape march. A topology's kernel holds only its characteristic functions and
its kinds' branches; the drivers here take them as first-class functions (``delta``,
``count``, ``osc_frequencies``, ``rigid_modes``, ``event``, ``sizes``), so they are
compiled once per machine (numba caches them) and shared by every topology: a new
topology compiles only what is its own.

Regenerate: python -m mstmm.derive --bundled
Derived by mstmm.derive with SymPy 1.14.0.
"""

import cmath
import math

import numpy as np
from numba import njit, prange, types
from numba.core import cgutils
from numba.core.types import FunctionType
from numba.extending import intrinsic

#: sha1 of the derive/ sources this module was printed from (each kernel checks it).
DIGEST = "17758bf79b78f1990e649e0ec46fdc419567f723"
#: Parameter layout: head, then segment rows, then event rows (tag, x, offset).
HEAD = 5
SEGMENT_WIDTH = 4
EVENT_WIDTH = 3
#: Stiffness (units L = EI = 1) standing for a constrained degree of freedom in the count.
PENALTY = 1e60
#: A piece shorter than this (units of L) is merged into its node by the count: its
#: stiffness (~12/rho^3) must stay far below PENALTY.
MERGE_LENGTH = 1e-15
#: Longest piece (in lam*l) carried by one step of the count.
RICCATI_STEP = 1.0
#: Scan nodes per pi of beta = lam L in ``lowest`` (beam modes are about pi apart).
NODES_PER_MODE = 8
#: The scan's nodes beside a component's own frequency w0 are w0 (1 -+ OSC_SIDE).
OSC_SIDE = 1e-9


@njit(cache=True, inline="always")
def krylov(x):
    """Reduced Krylov functions K0 = S, K1 = T/x, K2 = G/x^2, K3 = V/x^3 (paper Eq. (1))."""
    if x < 1.5:
        z = x**4
        K0 = 1.0 + z * (0.041666666666666664 + z * (2.48015873015873e-05 + z * (2.08767569878681e-09 + z * (4.779477332387385e-14 + z * (4.110317623312165e-19)))))
        K1 = 1.0 + z * (0.008333333333333333 + z * (2.7557319223985893e-06 + z * (1.6059043836821613e-10 + z * (2.8114572543455206e-15 + z * (1.9572941063391263e-20)))))
        K2 = 0.5 + z * (0.001388888888888889 + z * (2.755731922398589e-07 + z * (1.1470745597729725e-11 + z * (1.5619206968586225e-16 + z * (8.896791392450574e-22)))))
        K3 = 0.16666666666666666 + z * (0.0001984126984126984 + z * (2.505210838544172e-08 + z * (7.647163731819816e-13 + z * (8.22063524662433e-18))))
    else:
        t0 = math.cos(x)
        t1 = math.cosh(x)
        t2 = math.sin(x)
        t3 = math.sinh(x)
        K0 = (0.5)*t0 + (0.5)*t1
        K1 = (0.5)*(t2 + t3)/x
        K2 = (0.5)*(-t0 + t1)/x**2
        K3 = (0.5)*(-t2 + t3)/x**3
    return K0, K1, K2, K3


@njit(cache=True, inline="always")
def krylov_scaled(x):
    """krylov(x) times exp(-shift), shift = x above the threshold (no overflow); returns shift."""
    if x < 1.5:
        K0, K1, K2, K3 = krylov(x)
        return 0.0, K0, K1, K2, K3
    E = math.exp(-x)
    chs = 0.5 + 0.5 * E * E
    shs = 0.5 - 0.5 * E * E
    t0 = (0.5)*E
    t1 = t0*math.cos(x)
    t2 = 1.0/x
    t3 = t0*math.sin(x)
    t4 = x**(-2.0)
    t5 = x**(-3.0)
    K0 = (0.5)*chs + t1
    K1 = (0.5)*shs*t2 + t2*t3
    K2 = (0.5)*chs*t4 - t1*t4
    K3 = (0.5)*shs*t5 - t3*t5
    return x, K0, K1, K2, K3


@njit(cache=True, inline="always")
def compound_krylov(x):
    """Compound functions F1..F4 and E, scaled by exp(-x) above the threshold; returns the shift."""
    if x < 1.5:
        z = x**4
        shift = 0.0
        E = 1.0
        F1 = 1.0 + z * (-0.03333333333333333 + z * (4.409171075837743e-05 + z * (-1.0277788055565833e-08 + z * (7.197330571124533e-13 + z * (-2.0042691648912653e-17 + z * (2.6406708364838804e-22))))))
        F2 = 0.5 + z * (-0.005555555555555556 + z * (4.409171075837742e-06 + z * (-7.341277182547024e-10 + z * (3.9985169839580737e-14 + z * (-9.110314385869388e-19)))))
        F3 = 0.3333333333333333 + z * (-0.0015873015873015873 + z * (8.01667468334135e-07 + z * (-9.788369576729365e-11 + z * (4.208965246271657e-15 + z * (-7.922012509451641e-20)))))
        F4 = 0.08333333333333333 + z * (-0.0001984126984126984 + z * (6.680562236117792e-08 + z * (-6.117730985455853e-12 + z * (2.1044826231358284e-16 + z * (-3.3008385456048505e-21)))))
    else:
        shift = x
        E = math.exp(-x)
        chs = 0.5 + 0.5 * E * E
        shs = 0.5 - 0.5 * E * E
        t0 = (0.5)/x
        t1 = math.sin(x)
        t2 = chs*t1
        t3 = math.cos(x)
        t4 = shs*t3
        t5 = (0.5)/x**3
        t6 = (0.5)/x**4
        F1 = t0*t2 + t0*t4
        F2 = (0.5)*shs*t1/x**2
        F3 = t2*t5 - t4*t5
        F4 = E*t6 - chs*t3*t6
    return shift, E, F1, F2, F3, F4


@njit(cache=True)
def beam_transfer(lam, l, EI, U):
    """Beam segment transfer matrix exactly as printed in paper Eq. (1)."""
    t0 = l*lam
    t1 = (0.5)*math.cos(t0)
    t2 = math.cosh(t0)
    t3 = t1 + (0.5)*t2
    t4 = (0.5)*math.sin(t0)
    t5 = math.sinh(t0)
    t6 = t4 + (0.5)*t5
    t7 = t6/lam
    t8 = 1.0/EI
    t9 = lam**2
    t10 = -t1 + (0.5)*t2
    t11 = t10*t8/t9
    t12 = lam**3
    t13 = -t4 + (0.5)*t5
    t14 = lam*t13
    t15 = EI*t10*t9
    U[0, 0] = t3
    U[0, 1] = t7
    U[0, 2] = t11
    U[0, 3] = t13*t8/t12
    U[1, 0] = t14
    U[1, 1] = t3
    U[1, 2] = t7*t8
    U[1, 3] = t11
    U[2, 0] = t15
    U[2, 1] = EI*t14
    U[2, 2] = t3
    U[2, 3] = t7
    U[3, 0] = EI*t12*t6
    U[3, 1] = t15
    U[3, 2] = t14
    U[3, 3] = t3


@njit(cache=True, inline="always")
def beam_transfer_scaled(beta, rho, U):
    """Eq. (1) in units L = 1, EI = 1, times exp(-shift); returns shift."""
    shift, K0, K1, K2, K3 = krylov_scaled(beta * rho)
    t0 = K1*rho
    t1 = K2*rho**2
    t2 = K3*rho**3
    t3 = beta**4
    t4 = t2*t3
    t5 = t1*t3
    U[0, 0] = K0
    U[0, 1] = t0
    U[0, 2] = t1
    U[0, 3] = t2
    U[1, 0] = t4
    U[1, 1] = K0
    U[1, 2] = t0
    U[1, 3] = t1
    U[2, 0] = t5
    U[2, 1] = t4
    U[2, 2] = K0
    U[2, 3] = t0
    U[3, 0] = t0*t3
    U[3, 1] = t5
    U[3, 2] = t4
    U[3, 3] = K0
    return shift


@njit(cache=True, inline="always")
def beam_compound_step(v, beta, rho):
    """v <- C2(U_beam) v in units L = 1, EI = 1; returns the log of the scale taken out."""
    x = beta * rho
    shift, E, F1, F2, F3, F4 = compound_krylov(x)
    v0 = v[0]
    v1 = v[1]
    v2 = v[2]
    v3 = v[3]
    v4 = v[4]
    v5 = v[5]
    t0 = beta**4
    t1 = rho**4
    t2 = F4*t1
    t3 = t0*t2
    t4 = E - t3
    t5 = F1*rho
    t6 = t5*v1
    t7 = F2*rho**2
    t8 = t7*v2
    t9 = t7*v3
    t10 = F3*rho**3
    t11 = t10*v4
    t12 = E - 2.0*t3
    t13 = 2.0*t7
    t14 = t0*v0
    t15 = t0*t10
    t16 = -t14*t7 - t15*v1 + t5*v4 + t7*v5
    v[0] = t11 + t2*v5 + t4*v0 + t6 + t8 + t9
    v[1] = -t10*t14 + t10*v5 + t12*v1 + t13*v4 + t5*v2 + t5*v3
    v[2] = t16 - t3*v3 + t4*v2
    v[3] = t16 - t3*v2 + t4*v3
    v[4] = F1*rho*v5 - t0*t13*v1 + t12*v4 - t14*t5 - t15*v2 - t15*v3
    v[5] = F4*beta**8*t1*v0 - t0*t11 - t0*t6 - t0*t8 - t0*t9 + t4*v5
    return shift



# The same beam functions for a complex argument (damped kernels and the frequency
# response): the branch is chosen by |x|; the closed forms keep their exp(-x) scaling,
# which stays bounded while Re x >= |Im x| (beta = sqrt(w1) with w_d >= 0).


@njit(cache=True, inline="always")
def krylov_c(x):
    """``krylov`` for a complex argument."""
    if abs(x) < 1.5:
        x2 = x * x  # a complex power would go through exp and log
        z = x2 * x2
        K0 = 1.0 + z * (0.041666666666666664 + z * (2.48015873015873e-05 + z * (2.08767569878681e-09 + z * (4.779477332387385e-14 + z * (4.110317623312165e-19)))))
        K1 = 1.0 + z * (0.008333333333333333 + z * (2.7557319223985893e-06 + z * (1.6059043836821613e-10 + z * (2.8114572543455206e-15 + z * (1.9572941063391263e-20)))))
        K2 = 0.5 + z * (0.001388888888888889 + z * (2.755731922398589e-07 + z * (1.1470745597729725e-11 + z * (1.5619206968586225e-16 + z * (8.896791392450574e-22)))))
        K3 = 0.16666666666666666 + z * (0.0001984126984126984 + z * (2.505210838544172e-08 + z * (7.647163731819816e-13 + z * (8.22063524662433e-18))))
    else:
        rx = 1.0 / x
        t0 = cmath.cos(x)
        t1 = cmath.cosh(x)
        t2 = cmath.sin(x)
        t3 = cmath.sinh(x)
        K0 = (0.5)*t0 + (0.5)*t1
        K1 = (0.5)*rx*(t2 + t3)
        K2 = (0.5)*rx*rx*(-t0 + t1)
        K3 = (0.5)*rx*rx*rx*(-t2 + t3)
    return K0, K1, K2, K3


@njit(cache=True, inline="always")
def krylov_scaled_c(x):
    """``krylov_scaled`` for a complex argument: times exp(-shift), shift complex."""
    if abs(x) < 1.5:
        K0, K1, K2, K3 = krylov_c(x)
        return 0.0j, K0, K1, K2, K3
    E = cmath.exp(-x)
    chs = 0.5 + 0.5 * E * E
    shs = 0.5 - 0.5 * E * E
    rx = 1.0 / x
    t0 = (0.5)*E
    t1 = t0*cmath.cos(x)
    t2 = t0*cmath.sin(x)
    t3 = rx*rx
    t4 = rx*rx*rx
    K0 = (0.5)*chs + t1
    K1 = (0.5)*rx*shs + rx*t2
    K2 = (0.5)*chs*t3 - t1*t3
    K3 = (0.5)*shs*t4 - t2*t4
    return x, K0, K1, K2, K3


@njit(cache=True, inline="always")
def compound_krylov_c(x):
    """``compound_krylov`` for a complex argument (shift and E complex)."""
    if abs(x) < 1.5:
        x2 = x * x  # a complex power would go through exp and log
        z = x2 * x2
        shift = 0.0j
        E = 1.0 + 0.0j
        F1 = 1.0 + z * (-0.03333333333333333 + z * (4.409171075837743e-05 + z * (-1.0277788055565833e-08 + z * (7.197330571124533e-13 + z * (-2.0042691648912653e-17 + z * (2.6406708364838804e-22))))))
        F2 = 0.5 + z * (-0.005555555555555556 + z * (4.409171075837742e-06 + z * (-7.341277182547024e-10 + z * (3.9985169839580737e-14 + z * (-9.110314385869388e-19)))))
        F3 = 0.3333333333333333 + z * (-0.0015873015873015873 + z * (8.01667468334135e-07 + z * (-9.788369576729365e-11 + z * (4.208965246271657e-15 + z * (-7.922012509451641e-20)))))
        F4 = 0.08333333333333333 + z * (-0.0001984126984126984 + z * (6.680562236117792e-08 + z * (-6.117730985455853e-12 + z * (2.1044826231358284e-16 + z * (-3.3008385456048505e-21)))))
    else:
        shift = x
        E = cmath.exp(-x)
        chs = 0.5 + 0.5 * E * E
        shs = 0.5 - 0.5 * E * E
        rx = 1.0 / x
        t0 = (0.5)*rx
        t1 = cmath.sin(x)
        t2 = chs*t1
        t3 = cmath.cos(x)
        t4 = shs*t3
        t5 = (0.5)*rx*rx*rx
        t6 = (0.5)*rx*rx*rx*rx
        F1 = t0*t2 + t0*t4
        F2 = (0.5)*rx*rx*shs*t1
        F3 = t2*t5 - t4*t5
        F4 = E*t6 - chs*t3*t6
    return shift, E, F1, F2, F3, F4


@njit(cache=True, inline="always")
def beam_transfer_scaled_c(beta, rho, U):
    """``beam_transfer_scaled`` for a complex beta: U (complex) times exp(-shift)."""
    shift, K0, K1, K2, K3 = krylov_scaled_c(beta * rho)
    t0 = K1*rho
    t1 = K2*rho*rho
    t2 = K3*rho*rho*rho
    t3 = beta*beta*beta*beta
    t4 = t2*t3
    t5 = t1*t3
    U[0, 0] = K0
    U[0, 1] = t0
    U[0, 2] = t1
    U[0, 3] = t2
    U[1, 0] = t4
    U[1, 1] = K0
    U[1, 2] = t0
    U[1, 3] = t1
    U[2, 0] = t5
    U[2, 1] = t4
    U[2, 2] = K0
    U[2, 3] = t0
    U[3, 0] = t0*t3
    U[3, 1] = t5
    U[3, 2] = t4
    U[3, 3] = K0
    return shift


@njit(cache=True, inline="always")
def beam_compound_step_c(v, beta, rho):
    """``beam_compound_step`` for a complex beta and minors v; returns the complex log of
    the scale taken out."""
    x = beta * rho
    shift, E, F1, F2, F3, F4 = compound_krylov_c(x)
    v0 = v[0]
    v1 = v[1]
    v2 = v[2]
    v3 = v[3]
    v4 = v[4]
    v5 = v[5]
    t0 = beta*beta*beta*beta
    t1 = rho*rho*rho*rho
    t2 = F4*t1
    t3 = t0*t2
    t4 = E - t3
    t5 = F1*rho
    t6 = t5*v1
    t7 = F2*rho*rho
    t8 = t7*v2
    t9 = t7*v3
    t10 = F3*rho*rho*rho
    t11 = t10*v4
    t12 = E - 2.0*t3
    t13 = 2.0*t7
    t14 = t0*v0
    t15 = t0*t10
    t16 = -t14*t7 - t15*v1 + t5*v4 + t7*v5
    v[0] = t11 + t2*v5 + t4*v0 + t6 + t8 + t9
    v[1] = -t10*t14 + t10*v5 + t12*v1 + t13*v4 + t5*v2 + t5*v3
    v[2] = t16 - t3*v3 + t4*v2
    v[3] = t16 - t3*v2 + t4*v3
    v[4] = F1*rho*v5 - t0*t13*v1 + t12*v4 - t14*t5 - t15*v2 - t15*v3
    v[5] = F4*beta*beta*beta*beta*beta*beta*beta*beta*t1*v0 - t0*t11 - t0*t6 - t0*t8 - t0*t9 + t4*v5
    return shift


@njit(cache=True, inline="always")
def renormalise(v):
    """Divide v by a power of two near its largest entry; return the natural log taken out.
    (The largest real or imaginary part: for a complex v, abs would cost a hypot each.)"""
    big = 0.0
    for a in range(v.shape[0]):
        big = max(big, abs(v[a].real), abs(v[a].imag))
    if big == 0.0 or not math.isfinite(big):
        return 0.0
    e = math.frexp(big)[1]
    f = math.ldexp(1.0, -e)
    for a in range(v.shape[0]):
        v[a] *= f
    return e * 0.6931471805599453


@njit(cache=True, inline="always")
def scale_minors(v, f):
    """v <- C2(diag(1, 1, f, f)) v: the minors of a state whose M and Q are scaled by f."""
    for a in range(1, 5):
        v[a] *= f
    v[5] *= f * f


@njit(cache=True, inline="always")
def segment_scale(p, seg):
    """(e, a) of segment seg: its EI over the first's, and beta_s / beta =
    (mbar_s / mbar_0 / e)^(1/4) (docs/components.md, section 3)."""
    i = HEAD + SEGMENT_WIDTH * seg
    e = p[i + 1] / p[1]
    return e, math.sqrt(math.sqrt(p[i + 2] / p[2] / e))


@njit(cache=True, inline="always")
def next_piece(p, seg, x):
    """End of the next beam piece towards x inside segment seg, and the segment after it
    (seg itself once x is reached)."""
    n_seg = int(p[3])
    if seg < n_seg - 1:
        x_end = p[HEAD + SEGMENT_WIDTH * seg]
        if x_end <= x:
            return x_end, seg + 1
    return x, seg


@njit(cache=True)
def insertion_order(keys, out):
    """out <- indices 0..n-1 in the stable ascending order of keys (insertion sort: the
    keys are sorted or nearly so, and it compiles in a fraction of np.argsort's time)."""
    n = keys.shape[0]
    for i in range(n):
        out[i] = i
    for i in range(1, n):
        j = i
        while j > 0 and keys[out[j - 1]] > keys[out[j]]:
            tmp = out[j - 1]
            out[j - 1] = out[j]
            out[j] = tmp
            j -= 1


@njit(cache=True, inline="always")
def event_row(p, r):
    """Start of the r-th row of the event table: rows are sorted by x (stable), as
    ``catalog.layout`` writes them and ``study.parameter_matrix`` keeps them."""
    return HEAD + SEGMENT_WIDTH * int(p[3]) + EVENT_WIDTH * r


@njit(cache=True)
def event_order(p):
    """Start of each row of the event table, in x order."""
    n_ev = int(p[4])
    rows = np.empty(n_ev, dtype=np.int64)
    for r in range(n_ev):
        rows[r] = event_row(p, r)
    return rows




@njit(cache=True, inline="always")
def neg2(a, c, det):
    """Number of negative eigenvalues of a symmetric 2x2 matrix with diagonal a, c and
    determinant det."""
    if det < 0.0:
        return 1
    if a + c < 0.0:
        return 2 if det > 0.0 else 1
    return 0


@njit(cache=True, inline="always")
def clamped_clamped_count(x):
    """Natural frequencies of a segment clamped at both ends below x = lam l (J0 of one member)."""
    if x < math.pi:
        return 0
    E = math.exp(-x)
    chs = 0.5 + 0.5 * E * E
    f = E - chs*math.cos(x)
    i = int(x / math.pi)
    s = 1 if f > 0.0 else -1
    return i - (1 - (1 if i % 2 == 0 else -1) * s) // 2


@njit(cache=True, inline="always")
def node_stiffness_step(Zc, kY, kT):
    """Zc <- the minors after a node stiffness kY on Y (Q -= kY Y) and kT on theta
    (M += kT theta), units L = EI = 1."""
    v0 = Zc[0]
    v1 = Zc[1]
    v2 = Zc[2]
    v3 = Zc[3]
    v4 = Zc[4]
    v5 = Zc[5]
    t0 = kT*v0
    Zc[0] = v0
    Zc[1] = t0 + v1
    Zc[2] = v2
    Zc[3] = v3
    Zc[4] = kY*v0 + v4
    Zc[5] = kT*v4 + kY*t0 + kY*v1 + v5


@njit(cache=True, inline="always")
def pair_count(Zc, U, beta, rho):
    """Carry the node's state subspace across a piece (beta*rho <= RICCATI_STEP); returns
    the negative pivots of eliminating the near node.

    The subspace of states [Y, theta, M, Q] that everything left of the node admits is
    held by the 2x2 minors Zc of a basis Z = [Xd; Xf] (Pluecker coordinates, index as
    ``PAIRS`` of the second compound), carried by the same compound step as the stable
    chain. Its condensed stiffness S = PI_RIGHT^-1 Xf Xd^-1 is never formed: after a
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
    # W = Xd' adj(Xd) from the minors before the step (Zc(2,1) = -Zc[3], Zc(3,1) = -Zc[4])
    w00 = U[0, 0] * Zc[0] - U[0, 2] * Zc[3] - U[0, 3] * Zc[4]
    w10 = U[1, 0] * Zc[0] - U[1, 2] * Zc[3] - U[1, 3] * Zc[4]
    w01 = U[0, 1] * Zc[0] + U[0, 2] * Zc[1] + U[0, 3] * Zc[2]
    w11 = U[1, 1] * Zc[0] + U[1, 2] * Zc[1] + U[1, 3] * Zc[2]
    beam_compound_step(Zc, beta, rho)
    renormalise(Zc)
    b = Zc[0]
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


@njit(cache=True)
def counts(count, omegas, p, out):
    """out[i] = count(omegas[i], p)."""
    for i in range(omegas.shape[0]):
        out[i] = count(omegas[i], p)


@njit(cache=True)
def segment_transfer(p, seg, beta, rho, U):
    """U <- D U(beta_s rho) D^-1, the transfer across a piece of segment seg (paper Eq. (1)
    in units L = EI_0 = 1), unscaled."""
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


@njit(cache=True)
def lu_logdet(A):
    """Determinant by LU with partial pivoting, as (sign, log|det|); A is overwritten."""
    n = A.shape[0]
    sign = 1.0
    log = 0.0
    for k in range(n):
        piv = k
        big = abs(A[k, k])
        for r in range(k + 1, n):
            if abs(A[r, k]) > big:
                big = abs(A[r, k])
                piv = r
        if big == 0.0:
            return 0.0, 0.0
        if piv != k:
            sign = -sign
            for j in range(n):
                tmp = A[k, j]
                A[k, j] = A[piv, j]
                A[piv, j] = tmp
        d = A[k, k]
        if d < 0.0:
            sign = -sign
        log += math.log(abs(d))
        for r in range(k + 1, n):
            f = A[r, k] / d
            if f != 0.0:
                for j in range(k + 1, n):
                    A[r, j] -= f * A[k, j]
    return sign, log


@njit(cache=True)
def evaluate(delta, omegas, p, mant, logs):
    """mant[i], logs[i] = delta(omegas[i], p): the scan loop."""
    for i in range(omegas.shape[0]):
        mant[i], logs[i] = delta(omegas[i], p)


@njit(cache=True)
def scaled(delta, omega, p, ref):
    """mantissa * exp(log - ref), clipped to stay finite: continuous in omega, exact sign."""
    m, g = delta(omega, p)
    return m * math.exp(min(g - ref, 700.0))


@njit(cache=True)
def refine(delta, a, b, p, rtol, maxiter):
    """Brent's method on a sign change in [a, b]; returns (root, iterations, converged)."""
    ma, ga = delta(a, p)
    mb, gb = delta(b, p)
    ref = max(ga, gb)
    fa = ma * math.exp(ga - ref)
    fb = mb * math.exp(gb - ref)
    if fa == 0.0:
        return a, 0, True
    if fb == 0.0:
        return b, 0, True
    if (fa > 0.0) == (fb > 0.0):
        return 0.5 * (a + b), 0, False
    c = a
    fc = fa
    d = b - a
    e = d
    for it in range(maxiter):
        if (fb > 0.0) == (fc > 0.0):
            c = a
            fc = fa
            d = b - a
            e = d
        if abs(fc) < abs(fb):
            a = b
            b = c
            c = a
            fa = fb
            fb = fc
            fc = fa
        tol = 2.0 * 2.220446049250313e-16 * abs(b) + 0.5 * rtol * abs(b)
        m = 0.5 * (c - b)
        if abs(m) <= tol or fb == 0.0:
            return b, it, True
        if abs(e) >= tol and abs(fa) > abs(fb):
            s = fb / fa
            if a == c:
                pp = 2.0 * m * s
                q = 1.0 - s
            else:
                q = fa / fc
                r = fb / fc
                pp = s * (2.0 * m * q * (q - r) - (b - a) * (r - 1.0))
                q = (q - 1.0) * (r - 1.0) * (s - 1.0)
            if pp > 0.0:
                q = -q
            else:
                pp = -pp
            if 2.0 * pp < min(3.0 * m * q - abs(tol * q), abs(e * q)):
                e = d
                d = pp / q
            else:
                d = m
                e = d
        else:
            d = m
            e = d
        a = b
        fa = fb
        if abs(d) > tol:
            b += d
        else:
            b += tol if m > 0.0 else -tol
        fb = scaled(delta, b, p, ref)
    return b, maxiter, False


#: Layout of the search state shared by ``lowest_start``, ``lowest_run`` and
#: ``lowest_block``: the search has covered (0, state[STATE_W]], whose count is
#: state[STATE_COUNT]; state[STATE_K] roots are written; state[STATE_LAST] is the
#: true multiplicity of the last root written (it may exceed the copies written
#: when the lowest ``modes`` end inside a multiple root); state[STATE_CERTIFIED] is 1
#: while the count certifies every root written, 0 once it could not (the search then
#: goes on without it, and state[STATE_FAILED] is the frequency where it stopped).
STATE_W = 0
STATE_COUNT = 1
STATE_K = 2
STATE_LAST = 3
STATE_CERTIFIED = 4
STATE_FAILED = 5
STATE_SIZE = 6
#: Blocks in a row that may end without a new root before the search gives up
#: (a beam has a natural frequency in every stretch of a few pi of beta = lam L).
MAX_STALLED_BLOCKS = 4
#: Flag of a root in ``flags``: 0 trusted; 1 the count holds exactly one root in a piece
#: of round-off width across which the function does not change sign, or Brent's
#: method did not converge (the caller checks it again, and reports it NOT TRUSTED
#: if nothing confirms it).
UNTRUSTED = 1


@njit(cache=True)
def push_halves(lo, hi, nlo, nhi, top, a, mid, b, na, nm, nb):
    """Push the pieces (mid, b) and (a, mid) with their counts on a bisection stack (the
    lower one pops first); returns the new top."""
    lo[top] = mid
    hi[top] = b
    nlo[top] = nm
    nhi[top] = nb
    lo[top + 1] = a
    hi[top + 1] = mid
    nlo[top + 1] = na
    nhi[top + 1] = nm
    return top + 2


@njit(cache=True)
def write_root(out, flags, k, modes, root, flag, copies, state):
    """Write ``copies`` copies of a root (up to ``modes`` values) with its flag; its
    multiplicity becomes state[STATE_LAST]. Returns the new k."""
    for _ in range(copies):
        if k < modes:
            out[k] = root
            flags[k] = flag
            k += 1
    state[STATE_LAST] = copies
    return k


@njit(cache=True)
def isolate(delta, count, a, b, na, nb, p, out, flags, k, modes, state, rtol):
    """Roots in (a, b) by bisection on the count N(b) - N(a), lowest first, each polished
    by Brent once alone on a sign change; a count jump that stays > 1 down to round-off
    width is a multiple root. The count at a midpoint is clamped into [na, nb], so that
    a count off by one at round-off distance from a root cannot add or lose a root.
    A simple root that the function never changes sign across, or on which Brent does
    not converge, is written flagged UNTRUSTED. Writes out[k:] and flags[k:] (with
    multiplicity, up to modes) and the true multiplicity of the last root written into
    state[STATE_LAST]; returns the new k, or -1 if the bisection stack overflows."""
    cap = 256
    sa = np.empty(cap)
    sb = np.empty(cap)
    sna = np.empty(cap, dtype=np.int64)
    snb = np.empty(cap, dtype=np.int64)
    sa[0] = a
    sb[0] = b
    sna[0] = na
    snb[0] = nb
    top = 1
    while top > 0 and k < modes:
        top -= 1
        a = sa[top]
        b = sb[top]
        na = sna[top]
        nb = snb[top]
        if nb <= na:
            continue
        if b - a <= 8.9e-16 * b:
            flag = 0
            if nb - na == 1:
                # a simple root that the function never changed sign across: the count
                # and the function disagree here
                ma = delta(a * (1.0 - 1e-12), p)[0]
                mb = delta(b * (1.0 + 1e-12), p)[0]
                if (ma > 0.0) == (mb > 0.0):
                    flag = UNTRUSTED
            k = write_root(out, flags, k, modes, 0.5 * (a + b), flag, nb - na, state)
            continue
        if nb - na == 1:
            ma = delta(a, p)[0]
            mb = delta(b, p)[0]
            if (ma > 0.0) != (mb > 0.0):
                root, its, ok = refine(delta, a, b, p, rtol, 200)
                k = write_root(out, flags, k, modes, root, 0 if ok else UNTRUSTED, 1, state)
                continue
        if top + 2 > cap:
            return -1
        mid = 0.5 * (a + b)
        # the count may dip or jump by one within an ulp or so of an oscillator
        # frequency (k - m w^2 at round-off); clamped, the piece keeps its total
        nm = min(max(count(mid, p), na), nb)
        top = push_halves(sa, sb, sna, snb, top, a, mid, b, na, nm, nb)
    return k


@njit(cache=True)
def rigid_dimension(L, knots, h, cx, ct, n):
    """Dimension of the rigid motions left free by n constraints, exactly (no threshold).

    A rigid motion is continuous and piecewise linear on [0, L] with kinks only at the h
    free hinges knots[0] <= ... <= knots[h-1]: with the nodes 0, knots..., L it is its
    values v_0..v_{h+1} there (hat basis), dimension 2 + h. Constraint c sits at cx[c]
    (SI), ct[c] = 1 for Y = 0, 2 for theta = 0; it acts in the piece i = the number of
    knots < cx[c] (on a hinge it acts on its left side), on (v_i, v_{i+1}) only: a Y at x
    as the row (n_{i+1} - x, x - n_i), a theta as (-1, 1). Per piece, by exact float
    comparisons: two Y at different x, or a Y and a theta, have a 2 x 2 determinant
    (n_{i+1} - n_i)(x_2 - x_1) resp. n_{i+1} - n_i, nonzero: both node values are 0. Else
    the rows are one up to scale: a Y at a node zeroes that node's value; a Y inside links
    v_{i+1} = c v_i, c = -(n_{i+1} - x)/(x - n_i) != 0; a theta links v_{i+1} = v_i. The
    constraints then say: along each run of linked nodes the values are one times nonzero
    factors, zero if one of them is zeroed; so the dimension is the number of such runs
    (connected components of the link graph, a path) holding no zeroed node.
    Degenerate pieces (n_i = n_{i+1}: a hinge at an end, two hinges at one x) are the
    same point: v_i = v_{i+1} (a link), plus a slope of their own (one more dimension,
    unless a theta constraint acts on it: only at x = 0 with a hinge there); a Y there
    zeroes the node. This is the dimension of the null space of the exact constraints
    on W(x) = a + b x + sum_j c_j (x - k_j)_+ with the same assignment of constraints to
    pieces (``tests/reference_model.rigid_body_mode_count``)."""
    m = h + 1
    n_y = np.zeros(m, dtype=np.int64)
    y_at = np.zeros(m)
    two_y = np.zeros(m, dtype=np.bool_)
    theta = np.zeros(m, dtype=np.bool_)
    for c in range(n):
        i = 0
        while i < h and cx[c] > knots[i]:
            i += 1
        if ct[c] == 2:
            theta[i] = True
        elif n_y[i] == 0:
            n_y[i] = 1
            y_at[i] = cx[c]
        elif cx[c] != y_at[i]:
            two_y[i] = True
    zero = np.zeros(m + 1, dtype=np.bool_)
    link = np.zeros(m, dtype=np.bool_)
    dim = 0
    for i in range(m):
        a = 0.0 if i == 0 else knots[i - 1]
        b = L if i == h else knots[i]
        if a == b:
            link[i] = True
            zero[i] = zero[i] or n_y[i] > 0
            if not theta[i]:
                dim += 1
        elif two_y[i] or (n_y[i] > 0 and theta[i]):
            zero[i] = True
            zero[i + 1] = True
        elif n_y[i] > 0 and y_at[i] == a:
            zero[i] = True
        elif n_y[i] > 0 and y_at[i] == b:
            zero[i + 1] = True
        else:
            link[i] = n_y[i] > 0 or theta[i]
    i = 0
    while i <= m:
        dead = zero[i]
        while i < m and link[i]:
            i += 1
            dead = dead or zero[i]
        if not dead:
            dim += 1
        i += 1
    return dim


@njit(cache=True)
def lowest_start(count, rigid_modes, p, modes, out, flags, state, certify):
    """Start the search of the lowest ``modes``: the rigid-body zeros into out, the
    state at the bottom of the scan (lowest node beta = 1e-3). With ``certify`` the
    count there must hold exactly the rigid-body modes (else no elastic root below is
    excluded); where it does not, the search goes on uncertified from the lowest node
    (state[STATE_CERTIFIED] = 0). Returns the number of values written."""
    L = p[0]
    EI = p[1]
    mbar = p[2]
    scale = math.sqrt(EI / mbar) / (L * L)  # omega = scale * beta^2
    rigid = rigid_modes(p)
    state[STATE_K] = 0
    k = write_root(out, flags, 0, modes, 0.0, 0, rigid, state)
    state[STATE_K] = k
    state[STATE_CERTIFIED] = 1.0 if certify else 0.0
    state[STATE_FAILED] = 0.0
    w_lo = scale * 1e-6
    if k < modes and certify:
        # settle the bottom where the count holds exactly the rigid-body modes: lower
        # when an elastic root (a very soft oscillator) lies below it, higher when the
        # count has not yet registered a rigid-body mode (its -omega^2 pivot drowns in
        # round-off at very low frequency next to a constrained end); a count of exactly
        # the rigid-body modes at the bottom proves that no elastic root lies below it
        w = w_lo
        n = count(w, p)
        while n > rigid and w > 1e-300:
            w *= 1e-3
            n = count(w, p)
        while n < rigid and w < 1e300:
            w *= 2.0
            n = count(w, p)
        if n == rigid:
            w_lo = w
        else:
            state[STATE_CERTIFIED] = 0.0
            state[STATE_FAILED] = w_lo
    state[STATE_W] = w_lo
    state[STATE_COUNT] = rigid
    return k


@njit(cache=True)
def right_of_zero(delta, x, p):
    """The first point right of x (x (1 + eps), eps from 1e-15 up to 1e-8) where the
    function is not exactly zero, and its value there (x and 0 if there is none)."""
    eps = 1e-15
    while eps <= 1e-8:
        y = x * (1.0 + eps)
        m = delta(y, p)[0]
        if m != 0.0:
            return y, m
        eps *= 8.0
    return x, 0.0


@njit(cache=True)
def lowest_block(
    delta, count, osc_frequencies, p, modes, out, flags, state, quota, certify, w_stop, rtol
):
    """Up to ``quota`` more roots above state[STATE_W], certified by ONE count.

    Scans the characteristic function (pole-free: each sign change brackets an odd
    number of roots) on a grid uniform in beta (NODES_PER_MODE per pi) plus a node on
    each side of every oscillator frequency, with Brent on each sign change, until ``quota`` sign
    changes are found (or (quota + 2) pi of beta are covered), and stops at the next
    uniform node, or at ``w_stop`` (a band's top) if that comes first. With ``certify``,
    the count at that node proves the whole block when N(top) - N(bottom) equals the
    number of sign changes: then each brackets exactly one simple root and no root lies
    elsewhere. A piece where the two disagree is halved at a uniform node by the count
    (never at an oscillator frequency, where multiple roots sit and the count is at
    round-off), down to single pieces whose roots ``isolate`` finds by count bisection:
    so a spurious sign change (a function that has lost its digits) is dropped and a
    root without one (a double root) is found. Without ``certify`` the sign-change roots
    are written unchecked. A root on which Brent does not converge is flagged UNTRUSTED.
    Writes out[k:] and flags[k:] (up to ``modes``), advances ``state``; returns the new
    k, or -1 with the state unchanged (a count that decreases, a bisection that
    overflows)."""
    L = p[0]
    EI = p[1]
    mbar = p[2]
    scale = math.sqrt(EI / mbar) / (L * L)
    w_a = state[STATE_W]
    n_a = int(state[STATE_COUNT])
    k = int(state[STATE_K])
    b_a = math.sqrt(w_a / scale)
    h = math.pi / NODES_PER_MODE
    b_cap = b_a + (quota + 2) * math.pi
    # a node on each side of every component's own frequency, OSC_SIDE apart: a root
    # exactly there (a decoupled oscillator, identical ones) sits between two nodes where
    # the function has a clean sign, never on a node whose sign is round-off (Brent would
    # take that node for the root of a bracket holding another one)
    own = osc_frequencies(p)
    osc = np.empty(2 * own.shape[0])
    for i in range(own.shape[0]):
        osc[2 * i] = own[i] * (1.0 - OSC_SIDE)
        osc[2 * i + 1] = own[i] * (1.0 + OSC_SIDE)
    osc = osc[(osc > w_a) & (osc < scale * b_cap * b_cap * (1.0 + 1e-15))]
    size = int(math.ceil((b_cap - b_a) / h)) + 3 + osc.shape[0]
    w = np.empty(size)
    uniform = np.zeros(size, dtype=np.bool_)
    change = np.zeros(size, dtype=np.int64)  # change[i]: a sign change in (w[i-1], w[i]]
    root = np.empty(size)
    root_flag = np.zeros(size, dtype=np.int64)
    w[0] = w_a
    uniform[0] = True
    m_prev = delta(w_a, p)[0]
    a_left = w_a
    if m_prev == 0.0:
        a_left, m_prev = right_of_zero(delta, w_a, p)
    n = 1
    j = 1
    io = 0
    found = 0
    while n < size:
        bu = b_a + j * h
        wu = scale * bu * bu
        if io < osc.shape[0] and osc[io] < wu:
            x = osc[io]
            io += 1
            is_uniform = False
        else:
            x = wu
            j += 1
            is_uniform = True
        at_stop = x >= w_stop
        if at_stop:
            x = w_stop
            is_uniform = True
        if x <= w[n - 1]:
            continue
        m = delta(x, p)[0]
        if m == 0.0:
            x *= 1.0 + 4.4e-16
            m = delta(x, p)[0]
        w[n] = x
        uniform[n] = is_uniform
        if (m > 0.0) != (m_prev > 0.0):
            r, its, ok = refine(delta, a_left, x, p, rtol, 200)
            change[n] = 1
            root[n] = r
            root_flag[n] = 0 if ok else UNTRUSTED
            found += 1
        a_left = x
        m_prev = m
        if m == 0.0:
            # a root exactly at this node (one at a component's own frequency): the next
            # bracket starts just right of it, where the function has a sign again
            a_left, m_prev = right_of_zero(delta, x, p)
        n += 1
        if at_stop or (is_uniform and (found >= quota or bu >= b_cap)):
            break
    top = n - 1
    if not certify:
        for i in range(1, n):
            if change[i] == 1:
                k = write_root(out, flags, k, modes, root[i], root_flag[i], 1, state)
        state[STATE_W] = w[top]
        state[STATE_COUNT] = n_a + found
        state[STATE_K] = k
        return k
    n_b = count(w[top], p)
    if n_b < n_a:
        return -1
    changes = np.zeros(n, dtype=np.int64)  # sign changes in (w[0], w[i]]
    for i in range(1, n):
        changes[i] = changes[i - 1] + change[i]
    cap = 128
    si = np.empty(cap, dtype=np.int64)
    sj = np.empty(cap, dtype=np.int64)
    sni = np.empty(cap, dtype=np.int64)
    snj = np.empty(cap, dtype=np.int64)
    si[0] = 0
    sj[0] = top
    sni[0] = n_a
    snj[0] = n_b
    depth = 1
    while depth > 0 and k < modes:
        depth -= 1
        i0 = si[depth]
        j0 = sj[depth]
        ni = sni[depth]
        nj = snj[depth]
        if nj - ni == changes[j0] - changes[i0]:
            for i in range(i0 + 1, j0 + 1):
                if change[i] == 1:
                    k = write_root(out, flags, k, modes, root[i], root_flag[i], 1, state)
            continue
        # cut at the uniform node nearest the middle
        cut = -1
        mid = (i0 + j0) // 2
        for d in range(j0 - i0):
            if i0 < mid + d < j0 and uniform[mid + d]:
                cut = mid + d
                break
            if i0 < mid - d < j0 and uniform[mid - d]:
                cut = mid - d
                break
        if cut < 0:
            k = isolate(delta, count, w[i0], w[j0], ni, nj, p, out, flags, k, modes, state, rtol)
            if k < 0:
                return -1
            continue
        if depth + 2 > cap:
            return -1
        nm = min(max(count(w[cut], p), ni), nj)
        depth = push_halves(si, sj, sni, snj, depth, i0, cut, j0, ni, nm, nj)
    state[STATE_W] = w[top]
    state[STATE_COUNT] = n_b
    state[STATE_K] = k
    return k


@njit(cache=True)
def lowest_run(
    delta, count, osc_frequencies, p, modes, out, flags, state, k_stop, certify, w_stop, rtol
):
    """Blocks of ``lowest_block`` until k_stop values are written (k_stop <= modes) or
    the search reaches ``w_stop`` (the top of a band; inf for the lowest modes). A block
    the count cannot certify runs again without it, and so does the rest of the search
    (state[STATE_CERTIFIED] = 0, state[STATE_FAILED] = where it stopped). Returns the new
    k, or -1 when MAX_STALLED_BLOCKS blocks in a row found nothing (the count or the
    function is broken here)."""
    k = int(state[STATE_K])
    certify = certify and state[STATE_CERTIFIED] == 1.0
    stalled = 0
    while 0 <= k < k_stop and state[STATE_W] < w_stop:
        k_before = k
        k = lowest_block(
            delta, count, osc_frequencies, p, modes, out, flags, state, k_stop - k, certify,
            w_stop, rtol
        )
        if k < 0 and certify:
            certify = False
            state[STATE_CERTIFIED] = 0.0
            state[STATE_FAILED] = state[STATE_W]
            k = k_before
            continue
        if k < 0:
            return -1
        stalled = stalled + 1 if k == k_before else 0
        if stalled > MAX_STALLED_BLOCKS:
            return -1
    return k


@njit(cache=True)
def lowest(delta, count, osc_frequencies, rigid_modes, p, modes, out, flags, state, certify, rtol):
    """The lowest ``modes`` frequencies (rad/s, repeated by multiplicity) into ``out``, a
    flag for each in ``flags`` (0 trusted, UNTRUSTED), the search state in ``state``.

    ``lowest_start`` then ``lowest_run`` with the whole remaining quota (one count
    certifies the scan when every root is a sign change). Returns the number of values
    written (``modes`` unless the search stalled); state[STATE_LAST] is the true
    multiplicity of the last root (the count's, even when fewer copies fit in ``out``),
    state[STATE_CERTIFIED] whether the count certified them all."""
    k = lowest_start(count, rigid_modes, p, modes, out, flags, state, certify)
    return lowest_run(
        delta, count, osc_frequencies, p, modes, out, flags, state, modes, certify, np.inf, rtol
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
#: Gauss-Legendre nodes and weights on [0, 1] (8 points: exact to degree 15).
GAUSS_X = np.array([0.019855071751231912, 0.10166676129318664, 0.2372337950418355, 0.4082826787521751, 0.5917173212478248, 0.7627662049581645, 0.8983332387068134, 0.9801449282487681])
GAUSS_W = np.array([0.05061426814518853, 0.11119051722668721, 0.15685332293894344, 0.18134189168918083, 0.18134189168918083, 0.15685332293894344, 0.11119051722668721, 0.05061426814518853])


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
def piece_transfer(bs, e, rho, U):
    """U <- D U(bs rho) D^-1, D = diag(1, 1, e, e): a piece of a segment whose EI is e
    times the first's (bs*rho <= MARCH_STEP: no scaling, shift 0)."""
    beam_transfer_scaled(bs, rho, U)
    if e != 1.0:
        for r in range(4):
            for c in range(4):
                U[r, c] *= (e if r >= 2 else 1.0) / (e if c >= 2 else 1.0)


@njit(cache=True)
def piece_step(W, G, bs, e, rho):
    """W <- U(rho) W re-orthonormalised; G (2 x 2) takes the new coordinates to the old."""
    U = np.empty((4, 4))
    piece_transfer(bs, e, rho, U)
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
            C[r, c] = (Cz[r, 0] * W[0, c] + Cz[r, 1] * W[1, c] + Cz[r, 2] * W[2, c]
                       + Cz[r, 3] * W[3, c]) / scale
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
def shape_steps(p, beta, rows):
    """Number of steps of the march: every point component and every piece."""
    L = p[0]
    n_ev = rows.shape[0]
    steps = n_ev
    pos = 0.0
    seg = 0
    for r in range(n_ev + 1):
        x = p[rows[r] + 1] if r < n_ev else L
        while True:
            target, after = next_piece(p, seg, x)
            rho = (target - pos) / L
            if rho > 0.0:
                e, a = segment_scale(p, seg)
                steps += max(1, int(math.ceil(beta * a * rho / MARCH_STEP)))
                pos = target
            if after == seg:
                break
            seg = after
    return steps


@njit(cache=True)
def mode_shapes(
    event, inertia, sizes, ends, omega, p, m, xs, Z_out, q_out, q_x, q_mass, gram, part, ratio
):
    """The ``m`` shapes of the eigenspace at omega (a root of multiplicity m, or the centre
    of a cluster of m roots), units L = EI_0 = mbar_0 = 1.

    Z_out (m, len(xs), 4): state [Y, theta, M, Q] at the sample points xs (SI, ascending,
    right limits at a point component); q_out (m, n_q): the unknowns of every point
    component, q_x (n_q) the x (SI) of the component each belongs to and q_mass (n_q) the
    mass moving with it (units mbar_0 L; 0 for a reaction or a rotation); gram (m, m) and
    part (m): the mass inner products int mbar Y_i Y_j + sum mu q_i q_j + sum z_i^T M z_j
    and int mbar Y_i + sum mu q_i + sum (M z_i)_Y (for the participation factor in a base
    translation), z = [Y, theta] at a component holding the point mass matrix M on the
    beam (a lumped mass and its rotary inertia); ratio (m): singular value of each shape
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
    rows = event_order(p)
    n_ev = rows.shape[0]
    nq_all, max_q = sizes(p)
    n_steps = shape_steps(p, beta, rows)
    # per step: kind (0 piece, 1 point), rho, its segment's (beta_s, e, mbar_s/mbar_0),
    # nq, nf, offsets of its q and frozen params
    kind = np.zeros(n_steps, dtype=np.int64)
    rho_s = np.zeros(n_steps)
    bs_s = np.zeros(n_steps)
    e_s = np.ones(n_steps)
    r_s = np.ones(n_steps)
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
    ev_mass = np.zeros(nb)
    Mp = np.zeros((2, 2))
    Mbuf = np.zeros((n_steps, 2, 2))
    G = np.zeros((width, width))
    s = 0
    nq_total = 0
    nf_total = 0
    pos = 0.0
    seg = 0
    for i in range(n_ev + 1):
        x = p[rows[i] + 1] if i < n_ev else L
        while True:
            target, after = next_piece(p, seg, x)
            rho = (target - pos) / L
            if rho > 0.0:
                e, a = segment_scale(p, seg)
                pieces = max(1, int(math.ceil(beta * a * rho / MARCH_STEP)))
                for j in range(pieces):
                    piece_step(W, G, beta * a, e, rho / pieces)
                    kind[s] = 0
                    rho_s[s] = rho / pieces
                    bs_s[s] = beta * a
                    e_s[s] = e
                    r_s[s] = p[HEAD + SEGMENT_WIDTH * seg + 2] / mbar
                    x_s[s + 1] = x_s[s] + rho / pieces
                    for r in range(2):
                        for c in range(2):
                            Gbuf[s, r, c] = G[r, c]
                    s += 1
                    for r in range(4):
                        for c in range(2):
                            Wbuf[s, r, c] = W[r, c]
                x_s[s] = target / L
                pos = target
            if after == seg:
                break
            seg = after
        if i == n_ev:
            break
        nc, nq = event(p, rows[i], b4, Cz, Cq, Ad, B, ev_mass)
        nf = event_step(W, G, Cz, Cq, Ad, B, nc, nq)
        if inertia(p, rows[i], Mp) != 0:
            for r in range(2):
                for c in range(2):
                    Mbuf[s, r, c] = Mp[r, c]
        kind[s] = 1
        nq_s[s] = nq
        nf_s[s] = nf
        qofs[s] = nq_total
        fofs[s] = nf_total
        for j in range(nq):
            q_mass[nq_total + j] = ev_mass[j]
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
    U = np.empty((4, 4))
    Y = np.empty(m)
    j = 0
    ns = xs.shape[0]
    for t in range(n_steps):
        if kind[t] != 0:
            # a point mass matrix on [Y, theta] left of the component (where A acts)
            for k in range(m):
                mk0 = Mbuf[t, 0, 0] * Zn[k, t, 0] + Mbuf[t, 0, 1] * Zn[k, t, 1]
                mk1 = Mbuf[t, 1, 0] * Zn[k, t, 0] + Mbuf[t, 1, 1] * Zn[k, t, 1]
                part[k] += mk0
                for l in range(m):
                    gram[k, l] += Zn[l, t, 0] * mk0 + Zn[l, t, 1] * mk1
            continue
        x0 = x_s[t]
        x1 = x0 + rho_s[t]
        while j < ns and xs[j] / L < x1:
            d = max(xs[j] / L - x0, 0.0)
            piece_transfer(bs_s[t], e_s[t], d, U)
            for k in range(m):
                for r in range(4):
                    Z_out[k, j, r] = (U[r, 0] * Zn[k, t, 0] + U[r, 1] * Zn[k, t, 1]
                                      + U[r, 2] * Zn[k, t, 2] + U[r, 3] * Zn[k, t, 3])
            j += 1
        for g in range(GAUSS_X.shape[0]):
            piece_transfer(bs_s[t], e_s[t], rho_s[t] * GAUSS_X[g], U)
            w = rho_s[t] * GAUSS_W[g] * r_s[t]
            for k in range(m):
                Y[k] = (U[0, 0] * Zn[k, t, 0] + U[0, 1] * Zn[k, t, 1]
                        + U[0, 2] * Zn[k, t, 2] + U[0, 3] * Zn[k, t, 3])
            for k in range(m):
                part[k] += w * Y[k]
                for l in range(m):
                    gram[k, l] += w * Y[k] * Y[l]
    while j < ns:  # at x = L: the state after every component there
        for k in range(m):
            for r in range(4):
                Z_out[k, j, r] = Zn[k, n_steps, r]
        j += 1
    for i in range(nq_total):
        for k in range(m):
            part[k] += q_mass[i] * q_out[k, i]
            for l in range(m):
                gram[k, l] += q_mass[i] * q_out[k, i] * q_out[l, i]
    return nq_total


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
FRF_MASS = 2  # a force on / the displacement of a hanging mass (a component's unknown)
FRF_M = 3  # output: the moment M at x
FRF_Q = 4  # output: the shear Q at x
#: Inputs of a homogeneous march (a mode shape at a root): no load; the end's conditions
#: E b = 0 taken along the right singular vector of E for its smaller (FRF_NULL) or larger
#: (FRF_NULL2: the second shape of a double root) singular value.
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
def eliminate_c(C, rhs, scale, nc, n, X, xp):
    """The solutions of C x = rhs (nc x n, complex) as x = xp + X a, X n x (n - rank):
    Gauss-Jordan with complete pivoting; a row whose pivot falls below DEGENERATE times its
    scale (its largest entry of Cz and Cq) depends on the others at this frequency (a
    component exactly at its own frequency with the beam point held): it leaves one more
    free parameter. Returns the number of free parameters (columns of X), or -1 when such
    a row's right-hand side is not zero (the load drives a decoupled resonance)."""
    M = np.empty((nc, n), dtype=np.complex128)
    r_ = np.empty(nc, dtype=np.complex128)
    sc = np.empty(nc)
    for i in range(nc):
        r_[i] = rhs[i]
        sc[i] = scale[i]
        for j in range(n):
            M[i, j] = C[i, j]
    piv_col = np.empty(nc, dtype=np.int64)
    used = np.zeros(n, dtype=np.bool_)
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
def piece_transfer_c(bs, e, rho, U):
    """U <- D U(bs rho) D^-1 for a complex bs and segment factor e (its EI, with its loss
    factor, over the first's), bs*rho <= MARCH_STEP (no scaling)."""
    beam_transfer_scaled_c(bs, rho, U)
    for r in range(4):
        for c in range(4):
            U[r, c] *= (e if r >= 2 else 1.0) / (e if c >= 2 else 1.0)


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
    rows = event_order(p)
    n_ev = rows.shape[0]
    nq_all, max_q = sizes(p)
    nb = max(1, max_q)
    Cz = np.zeros((nb, 4), dtype=np.complex128)
    Cq = np.zeros((nb, nb), dtype=np.complex128)
    Ad = np.zeros((4, 4), dtype=np.complex128)
    B = np.zeros((4, nb), dtype=np.complex128)
    ev_mass = np.zeros(nb)
    C = np.zeros((nb, nb + 2), dtype=np.complex128)
    rhs = np.zeros(nb, dtype=np.complex128)
    row_scale = np.ones(nb)
    X = np.zeros((nb + 2, nb + 2), dtype=np.complex128)
    SS = np.zeros((4, nb + 2), dtype=np.complex128)
    xp = np.zeros(nb + 2, dtype=np.complex128)
    U = np.zeros((4, 4), dtype=np.complex128)
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
        frozen = np.zeros((2 if homogeneous else 0, n_out), dtype=np.complex128)
        nf = 0
        kind_in = int(inputs[i_in, 0])
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
        for r in range(n_ev + 1):
            x = p[rows[r] + 1] if r < n_ev else L
            while True:  # to x, stopping at segment ends, the load and the outputs
                target, after = next_piece(p, seg, x)
                stop = target
                if not applied and pos <= x_in < stop:
                    stop = x_in
                while bptr < n_beam and (done[bo[bptr]] or outputs[bo[bptr], 1] < pos):
                    bptr += 1  # the next beam output not recorded
                if bptr < n_beam and outputs[bo[bptr], 1] < stop:
                    stop = outputs[bo[bptr], 1]
                rho = (stop - pos) / L
                if rho > 0.0:
                    i = HEAD + SEGMENT_WIDTH * seg
                    e = p[i + 1] / EI * (1.0 + 1j * (p[i + 3] if damped else 0.0))
                    bs = beta * cmath.sqrt(cmath.sqrt(p[i + 2] / mbar / e))
                    pieces = max(1, int(math.ceil(abs(bs) * rho / MARCH_STEP)))
                    for _ in range(pieces):
                        piece_transfer_c(bs, e, rho / pieces, U)
                        for a in range(4):
                            zz[a] = U[a, 0] * z[0] + U[a, 1] * z[1] + U[a, 2] * z[2] + U[a, 3] * z[3]
                            for c in range(2):
                                S[a, c] = (U[a, 0] * W[0, c] + U[a, 1] * W[1, c]
                                           + U[a, 2] * W[2, c] + U[a, 3] * W[3, c])
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
                if stop < target:
                    continue
                if after == seg:
                    break
                seg = after
            if not applied and x_in == x:  # a load at a component, or at x = L
                if kind_in == FRF_FORCE:
                    z[3] += load
                else:
                    z[2] -= load
                applied = True
            if r == n_ev:
                break
            nc, nq = event(p, rows[r], w1, Cz, Cq, Ad, B, ev_mass)
            n = 2 + nq
            for a in range(nc):
                rhs[a] = -(Cz[a, 0] * z[0] + Cz[a, 1] * z[1] + Cz[a, 2] * z[2] + Cz[a, 3] * z[3])
                if kind_in == FRF_MASS and q_in == q0 + a:
                    rhs[a] -= load  # the rows are the masses' equations of motion
                for c in range(2):
                    C[a, c] = (Cz[a, 0] * W[0, c] + Cz[a, 1] * W[1, c]
                               + Cz[a, 2] * W[2, c] + Cz[a, 3] * W[3, c])
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
                nn = eliminate_c(C, rhs, row_scale, nc, n, X, xp)
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
                aw0 = Ad[a, 0] * W[0, 0] + Ad[a, 1] * W[1, 0] + Ad[a, 2] * W[2, 0] + Ad[a, 3] * W[3, 0]
                aw1 = Ad[a, 0] * W[0, 1] + Ad[a, 1] * W[1, 1] + Ad[a, 2] * W[2, 1] + Ad[a, 3] * W[3, 1]
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
                # B q is the masses' inertia passed to the beam; a force on one of them
                # reaches the beam's shear too
                zz[3] += load
            for a in range(4):
                z[a] = zz[a]
                for c in range(2):
                    W[a, c] = S[a, c]
            nf = orthonormalise_c(W, z, T, t, done, ep, G, g, nep, frozen, nf)
            q0 += nq
            if r + 1 == n_ev or p[rows[r + 1] + 1] != x:  # outputs after the last one here
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
        pick = 0 if kind_in == FRF_NULL else 1
        if homogeneous and pick < nf:  # a localised mode (orthonormalise_c)
            for j in range(n_out):
                out[i_in, j] = frozen[pick, j] * outputs[j, 3]
            singular[i_in] = 0.0
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


# Entry points called from Python. A topology's functions arrive as the addresses of their
# compiled code (``fa``: pairs (C wrapper, numba entry) in the order of FA_*; see
# ``mstmm.kernels.Kernel``), turned into first-class function values inside: plain
# integers cross the Python boundary in microseconds, and one compiled driver serves
# every topology (numba caches it on disk).
_f8 = types.float64
_i8 = types.int64
_A1 = types.float64[::1]
_A2 = types.float64[:, ::1]
DELTA = FunctionType(types.UniTuple(_f8, 2)(_f8, _A1))
COUNT = FunctionType(_i8(_f8, _A1))
OSC = FunctionType(_A1(_A1))
RIGID = FunctionType(_i8(_A1))
EVENT = FunctionType(types.UniTuple(_i8, 2)(_A1, _i8, _f8, _A2, _A2, _A2, _A2, _A1))
INERTIA = FunctionType(_i8(_A1, _i8, _A2))
_c16 = types.complex128
_C2 = types.complex128[:, ::1]
EVENT_C = FunctionType(types.UniTuple(_i8, 2)(_A1, _i8, _c16, _C2, _C2, _C2, _C2, _A1))
SIZES = FunctionType(types.UniTuple(_i8, 2)(_A1))
#: Position of each function's address pair in ``fa``, and its type.
FA_STABLE = 0
FA_COUNT = 2
FA_OSC = 4
FA_RIGID = 6
FA_PAPER = 8
FA_EVENT = 10
FA_SIZES = 12
FA_EVENT_C = 14
FA_INERTIA = 16
FA_SIZE = 18
FUNCTION_TYPES = {
    "delta_stable": (FA_STABLE, DELTA),
    "count_below": (FA_COUNT, COUNT),
    "oscillator_frequencies": (FA_OSC, OSC),
    "rigid_body_modes": (FA_RIGID, RIGID),
    "delta_paper": (FA_PAPER, DELTA),
    "shape_event": (FA_EVENT, EVENT),
    "shape_sizes": (FA_SIZES, SIZES),
    "shape_event_c": (FA_EVENT_C, EVENT_C),
    "shape_inertia": (FA_INERTIA, INERTIA),
}


def _function_value(ftype):
    """An intrinsic that makes a first-class function value of type ``ftype`` from the
    addresses of its C wrapper and of its numba entry (exceptions propagate through it)."""

    @intrinsic
    def make(typingctx, c_addr, jit_addr):
        def codegen(context, builder, signature, args):
            value = cgutils.create_struct_proxy(ftype)(context, builder)
            voidptr = context.get_value_type(types.voidptr)
            value.c_addr = builder.inttoptr(args[0], voidptr)
            value.py_addr = voidptr(None)
            value.jit_addr = builder.inttoptr(args[1], voidptr)
            return value._getvalue()

        return ftype(types.int64, types.int64), codegen

    return make


as_delta = _function_value(DELTA)
as_count = _function_value(COUNT)
as_osc = _function_value(OSC)
as_rigid = _function_value(RIGID)
as_event = _function_value(EVENT)
as_sizes = _function_value(SIZES)
as_event_c = _function_value(EVENT_C)
as_inertia = _function_value(INERTIA)


@njit(cache=True)
def entry_evaluate(fa, at, omegas, p, mant, logs):
    """``evaluate`` with the characteristic function whose addresses are at fa[at]."""
    evaluate(as_delta(fa[at], fa[at + 1]), omegas, p, mant, logs)


@njit(cache=True)
def entry_refine(fa, at, a, b, p, rtol, maxiter):
    """``refine`` with the characteristic function whose addresses are at fa[at]."""
    return refine(as_delta(fa[at], fa[at + 1]), a, b, p, rtol, maxiter)


@njit(cache=True)
def entry_counts(fa, omegas, p, out):
    """``counts`` with the kernel's count."""
    counts(as_count(fa[FA_COUNT], fa[FA_COUNT + 1]), omegas, p, out)


@njit(cache=True)
def entry_lowest(fa, at, p, modes, out, flags, state, certify, rtol):
    """``lowest`` with the kernel's functions (the characteristic function at fa[at])."""
    return lowest(
        as_delta(fa[at], fa[at + 1]),
        as_count(fa[FA_COUNT], fa[FA_COUNT + 1]),
        as_osc(fa[FA_OSC], fa[FA_OSC + 1]),
        as_rigid(fa[FA_RIGID], fa[FA_RIGID + 1]),
        p,
        modes,
        out,
        flags,
        state,
        certify,
        rtol,
    )


@njit(cache=True)
def entry_lowest_start(fa, p, modes, out, flags, state, certify):
    """``lowest_start`` with the kernel's functions."""
    return lowest_start(
        as_count(fa[FA_COUNT], fa[FA_COUNT + 1]),
        as_rigid(fa[FA_RIGID], fa[FA_RIGID + 1]),
        p,
        modes,
        out,
        flags,
        state,
        certify,
    )


@njit(cache=True)
def entry_lowest_run(fa, at, p, modes, out, flags, state, k_stop, certify, w_stop, rtol):
    """``lowest_run`` with the kernel's functions (the characteristic function at fa[at])."""
    return lowest_run(
        as_delta(fa[at], fa[at + 1]),
        as_count(fa[FA_COUNT], fa[FA_COUNT + 1]),
        as_osc(fa[FA_OSC], fa[FA_OSC + 1]),
        p,
        modes,
        out,
        flags,
        state,
        k_stop,
        certify,
        w_stop,
        rtol,
    )


@njit(cache=True, parallel=True)
def entry_sweep_lowest(fa, P, modes, out, certified):
    """``lowest`` (stable) for every parameter vector (row of P), in parallel over the
    rows; a row is certified when the count certifies all its roots and none is flagged."""
    delta = as_delta(fa[FA_STABLE], fa[FA_STABLE + 1])
    count = as_count(fa[FA_COUNT], fa[FA_COUNT + 1])
    osc = as_osc(fa[FA_OSC], fa[FA_OSC + 1])
    rigid = as_rigid(fa[FA_RIGID], fa[FA_RIGID + 1])
    for i in prange(P.shape[0]):
        flags = np.zeros(modes, dtype=np.int64)
        state = np.zeros(STATE_SIZE)
        k = lowest(delta, count, osc, rigid, P[i], modes, out[i], flags, state, True, 0.0)
        trusted = True
        for j in range(modes):
            trusted = trusted and flags[j] == 0
        certified[i] = k == modes and state[STATE_CERTIFIED] == 1.0 and trusted


@njit(cache=True)
def entry_mode_shapes(fa, ends, omega, p, m, xs, Z_out, q_out, q_x, q_mass, gram, part, ratio):
    """``mode_shapes`` with the kernel's descriptor functions."""
    return mode_shapes(
        as_event(fa[FA_EVENT], fa[FA_EVENT + 1]),
        as_inertia(fa[FA_INERTIA], fa[FA_INERTIA + 1]),
        as_sizes(fa[FA_SIZES], fa[FA_SIZES + 1]),
        ends,
        omega,
        p,
        m,
        xs,
        Z_out,
        q_out,
        q_x,
        q_mass,
        gram,
        part,
        ratio,
    )


@njit(cache=True, parallel=True)
def entry_frf(fa, ends, damped, ws, p, inputs, outputs, out):
    """``frf_march`` at every frequency ws[k] (complex, rad/s), in parallel over them:
    out[k, i, j] the response j to the load i."""
    event = as_event_c(fa[FA_EVENT_C], fa[FA_EVENT_C + 1])
    sizes = as_sizes(fa[FA_SIZES], fa[FA_SIZES + 1])
    for k in prange(ws.shape[0]):
        singular = np.zeros(inputs.shape[0])
        frf_march(event, sizes, ends, ws[k], p, damped, inputs, outputs, out[k], singular)


@njit(cache=True)
def entry_damped_shapes(fa, ends, damped, w, p, inputs, outputs, out, singular):
    """``frf_march`` without load at the root w: the mode shapes (one per input row,
    FRF_NULL or FRF_NULL2) sampled as ``outputs`` says."""
    event = as_event_c(fa[FA_EVENT_C], fa[FA_EVENT_C + 1])
    sizes = as_sizes(fa[FA_SIZES], fa[FA_SIZES + 1])
    frf_march(event, sizes, ends, w, p, damped, inputs, outputs, out, singular)

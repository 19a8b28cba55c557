"""The Euler-Bernoulli segment's beam functions (generated, do not edit).

Printed by SymPy from ``derive/segments/euler_bernoulli.py`` and ``derive/special.py``: the
reduced Krylov functions and the second-compound functions (series below x = 1.5,
closed forms with their exp(-x) scaling above), the segment transfer matrix (paper units
and reduced units), the compound step of the minors, their complex twins (damped kernels,
the frequency response), the clamped-clamped count of one segment (J0, Wittrick-Williams)
and a node stiffness step of the count; and from ``derive/segments/general.py`` the
differential equation ``Z' = A Z`` of a segment with a Timoshenko shear stiffness, an
axial force or an elastic foundation (issue 22), whose transfer matrix is ``exp(A l)``.
The numerics that use them are ordinary code (``mstmm.numerics``).

Regenerate: python -m mstmm.derive --bundled
Derived by mstmm.derive with SymPy 1.14.0.
"""

import cmath
import math

from mstmm.jit import njit

#: sha1 of the derive/ sources this module was printed from (the runtime checks it).
DIGEST = "2736d5c2cf94587c599053aedcff2f6338d53261"


@njit(cache=True, inline="always")
def krylov(x):
    """Reduced Krylov functions K0 = S, K1 = T/x, K2 = G/x^2, K3 = V/x^3 (paper Eq. (1))."""
    if x < 0.00013509300777591815:  # the constant terms, to the last bit (a piece between close components)
        return 1.0, 1.0, 0.5, 0.16666666666666666
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
    if x < 0.00014284346431400855:  # the constant terms, to the last bit (a piece between close components)
        return 0.0, 1.0, 1.0, 0.5, 0.3333333333333333, 0.08333333333333333
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


@njit(cache=True)
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


@njit(cache=True)
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


@njit(cache=True)
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



@njit(cache=True)
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


@njit(cache=True)
def general_field(e, m, w2, kGA, rhoI, P, k_w, k_G, A):
    """A of Z' = A Z, Z = [Y, psi, M, Q], for a segment of ``derive/segments/general.py``
    in units L = EI_0 = mbar_0 = 1: e = EI / EI_0, m = mbar / mbar_0, w2 = (lam_0 L)^4 (the
    squared frequency), kGA, rhoI, P, k_w, k_G dimensionless (kGA = 0: no shear
    deformation). Real or complex (a loss factor in e, kGA, k_w, k_G), like its arguments."""
    if kGA == 0.0:
        A[0, 0] = 0.0
        A[0, 1] = 1.0
        A[0, 2] = 0.0
        A[0, 3] = 0.0
        A[1, 0] = 0.0
        A[1, 1] = 0.0
        A[1, 2] = 1.0/e
        A[1, 3] = 0.0
        A[2, 0] = 0.0
        A[2, 1] = P + k_G - rhoI*w2
        A[2, 2] = 0.0
        A[2, 3] = 1.0
        A[3, 0] = -k_w + m*w2
        A[3, 1] = 0.0
        A[3, 2] = 0.0
        A[3, 3] = 0.0
    else:
        t0 = P + k_G
        t1 = 1.0/(kGA + t0)
        t2 = kGA*t1
        A[0, 0] = 0.0
        A[0, 1] = t2
        A[0, 2] = 0.0
        A[0, 3] = -t1
        A[1, 0] = 0.0
        A[1, 1] = 0.0
        A[1, 2] = 1.0/e
        A[1, 3] = 0.0
        A[2, 0] = 0.0
        A[2, 1] = -rhoI*w2 + t0*t2
        A[2, 2] = 0.0
        A[2, 3] = t2
        A[3, 0] = -k_w + m*w2
        A[3, 1] = 0.0
        A[3, 2] = 0.0
        A[3, 3] = 0.0

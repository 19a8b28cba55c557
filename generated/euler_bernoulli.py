"""The Euler-Bernoulli segment's beam functions (generated, do not edit).

Printed by SymPy from ``derive/segments/euler_bernoulli.py`` (paper Eq. (1)),
``derive/special.py`` and ``derive/segments/general.py``: constant terms, series below
x = 1.5, closed forms scaled by exp(-x) above; compiled by ``mstmm.numerics.beam``.

Regenerate: python -m mstmm.derive --bundled
Derived by mstmm.derive with SymPy 1.14.0.
"""

import cmath
import math

DIGEST = "7705f80b1dd3bac8636dc31fb19af1b72032bc7c"

SERIES_THRESHOLD = 1.5
KRYLOV_TINY = 0.00013509300777591815
COMPOUND_TINY = 0.00014284346431400855


def krylov(x):
    if x < KRYLOV_TINY:
        return (1.0, 1.0, 0.5, 0.16666666666666666)
    if x < SERIES_THRESHOLD:
        z = x**4
        K0 = z*(z*(z*(z*((4.110317623312165e-19)*z + 4.779477332387385e-14) + 2.08767569878681e-09) + 2.48015873015873e-05) + 0.041666666666666664) + 1.0
        K1 = z*(z*(z*(z*((1.9572941063391263e-20)*z + 2.8114572543455206e-15) + 1.6059043836821613e-10) + 2.7557319223985893e-06) + 0.008333333333333333) + 1.0
        K2 = z*(z*(z*(z*((8.896791392450574e-22)*z + 1.5619206968586225e-16) + 1.1470745597729725e-11) + 2.755731922398589e-07) + 0.001388888888888889) + 0.5
        K3 = z*(z*(z*((8.22063524662433e-18)*z + 7.647163731819816e-13) + 2.505210838544172e-08) + 0.0001984126984126984) + 0.16666666666666666
        return (K0, K1, K2, K3)
    t0 = math.cos(x)
    t1 = math.cosh(x)
    t2 = math.sin(x)
    t3 = math.sinh(x)
    K0 = (0.5)*t0 + (0.5)*t1
    K1 = (0.5)*(t2 + t3)/x
    K2 = (0.5)*(-t0 + t1)/x**2
    K3 = (0.5)*(-t2 + t3)/x**3
    return (K0, K1, K2, K3)


def krylov_scaled(x):
    if x < KRYLOV_TINY:
        return (0.0, 1.0, 1.0, 0.5, 0.16666666666666666)
    if x < SERIES_THRESHOLD:
        z = x**4
        K0 = z*(z*(z*(z*((4.110317623312165e-19)*z + 4.779477332387385e-14) + 2.08767569878681e-09) + 2.48015873015873e-05) + 0.041666666666666664) + 1.0
        K1 = z*(z*(z*(z*((1.9572941063391263e-20)*z + 2.8114572543455206e-15) + 1.6059043836821613e-10) + 2.7557319223985893e-06) + 0.008333333333333333) + 1.0
        K2 = z*(z*(z*(z*((8.896791392450574e-22)*z + 1.5619206968586225e-16) + 1.1470745597729725e-11) + 2.755731922398589e-07) + 0.001388888888888889) + 0.5
        K3 = z*(z*(z*((8.22063524662433e-18)*z + 7.647163731819816e-13) + 2.505210838544172e-08) + 0.0001984126984126984) + 0.16666666666666666
        return (0.0, K0, K1, K2, K3)
    E = math.exp(-x)
    chs = (0.5)*E**2 + 0.5
    shs = 0.5 - 0.5*E**2
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
    return (x, K0, K1, K2, K3)


def compound_krylov(x):
    if x < COMPOUND_TINY:
        return (0.0, 1.0, 1.0, 0.5, 0.3333333333333333, 0.08333333333333333)
    if x < SERIES_THRESHOLD:
        z = x**4
        F1 = z*(z*(z*(z*(z*((2.6406708364838804e-22)*z - 2.0042691648912653e-17) + 7.197330571124533e-13) - 1.0277788055565833e-08) + 4.409171075837743e-05) - 0.03333333333333333) + 1.0
        F2 = z*(z*(z*(z*(3.9985169839580737e-14 + (-9.110314385869388e-19)*z) - 7.341277182547024e-10) + 4.409171075837742e-06) - 0.005555555555555556) + 0.5
        F3 = z*(z*(z*(z*(4.208965246271657e-15 + (-7.922012509451641e-20)*z) - 9.788369576729365e-11) + 8.01667468334135e-07) - 0.0015873015873015873) + 0.3333333333333333
        F4 = z*(z*(z*(z*(2.1044826231358284e-16 + (-3.3008385456048505e-21)*z) - 6.117730985455853e-12) + 6.680562236117792e-08) - 0.0001984126984126984) + 0.08333333333333333
        return (0.0, 1.0, F1, F2, F3, F4)
    E = math.exp(-x)
    chs = (0.5)*E**2 + 0.5
    shs = 0.5 - 0.5*E**2
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
    return (x, E, F1, F2, F3, F4)


def beam_transfer(lam, l, EI, U):
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


def krylov_c(x):
    if abs(x) < SERIES_THRESHOLD:
        x2 = x*x
        z = x2*x2
        K0 = z*(z*(z*(z*((4.110317623312165e-19)*z + 4.779477332387385e-14) + 2.08767569878681e-09) + 2.48015873015873e-05) + 0.041666666666666664) + 1.0
        K1 = z*(z*(z*(z*((1.9572941063391263e-20)*z + 2.8114572543455206e-15) + 1.6059043836821613e-10) + 2.7557319223985893e-06) + 0.008333333333333333) + 1.0
        K2 = z*(z*(z*(z*((8.896791392450574e-22)*z + 1.5619206968586225e-16) + 1.1470745597729725e-11) + 2.755731922398589e-07) + 0.001388888888888889) + 0.5
        K3 = z*(z*(z*((8.22063524662433e-18)*z + 7.647163731819816e-13) + 2.505210838544172e-08) + 0.0001984126984126984) + 0.16666666666666666
        return (K0, K1, K2, K3)
    rx = 1.0/x
    t0 = cmath.cos(x)
    t1 = cmath.cosh(x)
    t2 = cmath.sin(x)
    t3 = cmath.sinh(x)
    K0 = (0.5)*t0 + (0.5)*t1
    K1 = (0.5)*rx*(t2 + t3)
    K2 = (0.5)*rx*rx*(-t0 + t1)
    K3 = (0.5)*rx*rx*rx*(-t2 + t3)
    return (K0, K1, K2, K3)


def krylov_scaled_c(x):
    if abs(x) < SERIES_THRESHOLD:
        x2 = x*x
        z = x2*x2
        K0 = z*(z*(z*(z*((4.110317623312165e-19)*z + 4.779477332387385e-14) + 2.08767569878681e-09) + 2.48015873015873e-05) + 0.041666666666666664) + 1.0
        K1 = z*(z*(z*(z*((1.9572941063391263e-20)*z + 2.8114572543455206e-15) + 1.6059043836821613e-10) + 2.7557319223985893e-06) + 0.008333333333333333) + 1.0
        K2 = z*(z*(z*(z*((8.896791392450574e-22)*z + 1.5619206968586225e-16) + 1.1470745597729725e-11) + 2.755731922398589e-07) + 0.001388888888888889) + 0.5
        K3 = z*(z*(z*((8.22063524662433e-18)*z + 7.647163731819816e-13) + 2.505210838544172e-08) + 0.0001984126984126984) + 0.16666666666666666
        return (0.0j, K0, K1, K2, K3)
    E = cmath.exp(-x)
    chs = (0.5)*E*E + 0.5
    shs = 0.5 - 0.5*E*E
    rx = 1.0/x
    t0 = (0.5)*E
    t1 = t0*cmath.cos(x)
    t2 = t0*cmath.sin(x)
    t3 = rx*rx
    t4 = rx*rx*rx
    K0 = (0.5)*chs + t1
    K1 = (0.5)*rx*shs + rx*t2
    K2 = (0.5)*chs*t3 - t1*t3
    K3 = (0.5)*shs*t4 - t2*t4
    return (x, K0, K1, K2, K3)


def compound_krylov_c(x):
    if abs(x) < SERIES_THRESHOLD:
        x2 = x*x
        z = x2*x2
        F1 = z*(z*(z*(z*(z*((2.6406708364838804e-22)*z - 2.0042691648912653e-17) + 7.197330571124533e-13) - 1.0277788055565833e-08) + 4.409171075837743e-05) - 0.03333333333333333) + 1.0
        F2 = z*(z*(z*(z*(3.9985169839580737e-14 + (-9.110314385869388e-19)*z) - 7.341277182547024e-10) + 4.409171075837742e-06) - 0.005555555555555556) + 0.5
        F3 = z*(z*(z*(z*(4.208965246271657e-15 + (-7.922012509451641e-20)*z) - 9.788369576729365e-11) + 8.01667468334135e-07) - 0.0015873015873015873) + 0.3333333333333333
        F4 = z*(z*(z*(z*(2.1044826231358284e-16 + (-3.3008385456048505e-21)*z) - 6.117730985455853e-12) + 6.680562236117792e-08) - 0.0001984126984126984) + 0.08333333333333333
        return (0.0j, 1.0 + 0.0j, F1, F2, F3, F4)
    E = cmath.exp(-x)
    chs = (0.5)*E*E + 0.5
    shs = 0.5 - 0.5*E*E
    rx = 1.0/x
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
    return (x, E, F1, F2, F3, F4)


def beam_transfer_scaled(beta, rho, U):
    shift, K0, K1, K2, K3 = krylov_scaled(beta*rho)
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


def beam_compound_step(v, beta, rho):
    x = beta*rho
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


def beam_transfer_scaled_c(beta, rho, U):
    shift, K0, K1, K2, K3 = krylov_scaled_c(beta*rho)
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


def beam_compound_step_c(v, beta, rho):
    x = beta*rho
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


def clamped_clamped_sign(x, E, chs, shs):
    f = E - chs*math.cos(x)
    return (f,)


def node_stiffness_step(Zc, kY, kT):
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


def general_field_rigid(e, m, w2, kGA, rhoI, t, r, k_w, A):
    A[0, 0] = 0.0
    A[0, 1] = 1.0
    A[0, 2] = 0.0
    A[0, 3] = 0.0
    A[1, 0] = 0.0
    A[1, 1] = 0.0
    A[1, 2] = 1.0/e
    A[1, 3] = 0.0
    A[2, 0] = 0.0
    A[2, 1] = r - rhoI*w2 + t
    A[2, 2] = 0.0
    A[2, 3] = 1.0
    A[3, 0] = -k_w + m*w2
    A[3, 1] = 0.0
    A[3, 2] = 0.0
    A[3, 3] = 0.0


def general_field_shear(e, m, w2, kGA, rhoI, t, r, k_w, A):
    t0 = 1.0/(kGA + t)
    t1 = kGA*t0
    A[0, 0] = 0.0
    A[0, 1] = t1
    A[0, 2] = 0.0
    A[0, 3] = -t0
    A[1, 0] = 0.0
    A[1, 1] = 0.0
    A[1, 2] = 1.0/e
    A[1, 3] = 0.0
    A[2, 0] = 0.0
    A[2, 1] = r - rhoI*w2 + t*t1
    A[2, 2] = 0.0
    A[2, 3] = t1
    A[3, 0] = -k_w + m*w2
    A[3, 1] = 0.0
    A[3, 2] = 0.0
    A[3, 3] = 0.0

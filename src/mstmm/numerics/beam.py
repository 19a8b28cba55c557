"""The Euler-Bernoulli beam functions, composed from what SymPy prints.

``mstmm.generated.euler_bernoulli`` holds the printed expressions (plain Python): each
reduced function's series in ``z = x^4`` and its closed forms (plain, and times exp(-x) in
terms of ``E = exp(-x)``, ``chs = E cosh x``, ``shs = E sinh x``), the transfer matrix
and the compound step filled from them, the sign of the clamped-clamped frequency
equation. This module compiles them and decides which to use: the series below
``SERIES_THRESHOLD`` (the closed forms cancel there), the constant terms below the
``*_TINY`` arguments (the pieces between close components), the exp(-x) scaling above the
threshold (no overflow: the scale taken out is returned as a shift of the log), real or
complex (a damped kernel, the frequency response: the branch by |x|; the scaled closed
forms stay bounded while Re x >= |Im x|, beta = sqrt(w1) with w_d >= 0).
"""

import cmath
import math

from mstmm.generated import euler_bernoulli as printed
from mstmm.jit import njit

SERIES_THRESHOLD = printed.SERIES_THRESHOLD
KRYLOV_TINY = printed.KRYLOV_TINY
KRYLOV_LEADING = printed.KRYLOV_LEADING
COMPOUND_TINY = printed.COMPOUND_TINY
COMPOUND_LEADING = printed.COMPOUND_LEADING


def _inlined(f):
    """A printed function, compiled into each caller (one call site each)."""
    return njit(cache=True, inline="always")(f)


krylov_series = _inlined(printed.krylov_series)
krylov_closed = _inlined(printed.krylov_closed)
krylov_closed_scaled = _inlined(printed.krylov_closed_scaled)
compound_series = _inlined(printed.compound_series)
compound_closed_scaled = _inlined(printed.compound_closed_scaled)
krylov_closed_c = _inlined(printed.krylov_closed_c)
krylov_closed_scaled_c = _inlined(printed.krylov_closed_scaled_c)
compound_closed_scaled_c = _inlined(printed.compound_closed_scaled_c)
clamped_clamped_sign = _inlined(printed.clamped_clamped_sign)
beam_transfer_fill = _inlined(printed.beam_transfer_fill)
beam_transfer_fill_c = _inlined(printed.beam_transfer_fill_c)
beam_compound_fill = _inlined(printed.beam_compound_fill)
beam_compound_fill_c = _inlined(printed.beam_compound_fill_c)
general_field_rigid = _inlined(printed.general_field_rigid)
general_field_shear = _inlined(printed.general_field_shear)
#: Zc <- the minors after a node stiffness kY on Y (Q -= kY Y) and kT on theta
#: (M += kT theta), units L = EI = 1.
node_stiffness_step = _inlined(printed.node_stiffness_step)
#: Beam segment transfer matrix exactly as printed in paper Eq. (1): ``(lam, l, EI, U)``.
beam_transfer = njit(cache=True)(printed.beam_transfer)


@njit(cache=True, inline="always")
def krylov(x):
    """Reduced Krylov functions K0 = S, K1 = T/x, K2 = G/x^2, K3 = V/x^3 (paper Eq. (1))."""
    if x < KRYLOV_TINY:  # the constant terms, to the last bit
        return KRYLOV_LEADING
    if x < SERIES_THRESHOLD:
        return krylov_series(x**4)
    return krylov_closed(x)


@njit(cache=True, inline="always")
def _scales(E):
    """``(E, chs, shs)`` from ``E = exp(-x)``: ``chs = E cosh x``, ``shs = E sinh x``."""
    return E, 0.5 + 0.5 * E * E, 0.5 - 0.5 * E * E


@njit(cache=True, inline="always")
def krylov_scaled(x):
    """krylov(x) times exp(-shift), shift = x above the threshold (no overflow); returns
    ``(shift, K0, K1, K2, K3)``."""
    if x < SERIES_THRESHOLD:
        K0, K1, K2, K3 = krylov(x)
        return 0.0, K0, K1, K2, K3
    E, chs, shs = _scales(math.exp(-x))
    K0, K1, K2, K3 = krylov_closed_scaled(x, E, chs, shs)
    return x, K0, K1, K2, K3


@njit(cache=True, inline="always")
def compound_krylov(x):
    """Compound functions F1..F4 and E, scaled by exp(-x) above the threshold; returns
    ``(shift, E, F1, F2, F3, F4)``."""
    if x < COMPOUND_TINY:  # the constant terms, to the last bit
        F1, F2, F3, F4 = COMPOUND_LEADING
        return 0.0, 1.0, F1, F2, F3, F4
    if x < SERIES_THRESHOLD:
        F1, F2, F3, F4 = compound_series(x**4)
        return 0.0, 1.0, F1, F2, F3, F4
    E, chs, shs = _scales(math.exp(-x))
    F1, F2, F3, F4 = compound_closed_scaled(x, E, chs, shs)
    return x, E, F1, F2, F3, F4


@njit(cache=True)
def beam_transfer_scaled(beta, rho, U):
    """Eq. (1) in units L = 1, EI = 1, times exp(-shift); returns shift."""
    shift, K0, K1, K2, K3 = krylov_scaled(beta * rho)
    beam_transfer_fill(beta, rho, K0, K1, K2, K3, U)
    return shift


@njit(cache=True)
def beam_compound_step(v, beta, rho):
    """v <- C2(U_beam) v in units L = 1, EI = 1; returns the log of the scale taken out."""
    shift, E, F1, F2, F3, F4 = compound_krylov(beta * rho)
    beam_compound_fill(v, beta, rho, E, F1, F2, F3, F4)
    return shift


@njit(cache=True, inline="always")
def _quartic(x):
    """x^4 of a complex x by two products (a complex power goes through exp and log)."""
    x2 = x * x
    return x2 * x2


@njit(cache=True, inline="always")
def krylov_c(x):
    """``krylov`` for a complex argument."""
    if abs(x) < SERIES_THRESHOLD:
        return krylov_series(_quartic(x))
    return krylov_closed_c(x)


@njit(cache=True, inline="always")
def krylov_scaled_c(x):
    """``krylov_scaled`` for a complex argument: times exp(-shift), shift complex."""
    if abs(x) < SERIES_THRESHOLD:
        K0, K1, K2, K3 = krylov_c(x)
        return 0.0j, K0, K1, K2, K3
    E, chs, shs = _scales(cmath.exp(-x))
    K0, K1, K2, K3 = krylov_closed_scaled_c(x, E, chs, shs)
    return x, K0, K1, K2, K3


@njit(cache=True, inline="always")
def compound_krylov_c(x):
    """``compound_krylov`` for a complex argument (shift and E complex)."""
    if abs(x) < SERIES_THRESHOLD:
        F1, F2, F3, F4 = compound_series(_quartic(x))
        return 0.0j, 1.0 + 0.0j, F1, F2, F3, F4
    E, chs, shs = _scales(cmath.exp(-x))
    F1, F2, F3, F4 = compound_closed_scaled_c(x, E, chs, shs)
    return x, E, F1, F2, F3, F4


@njit(cache=True)
def beam_transfer_scaled_c(beta, rho, U):
    """``beam_transfer_scaled`` for a complex beta: U (complex) times exp(-shift)."""
    shift, K0, K1, K2, K3 = krylov_scaled_c(beta * rho)
    beam_transfer_fill_c(beta, rho, K0, K1, K2, K3, U)
    return shift


@njit(cache=True, inline="always")
def beam_compound_step_c(v, beta, rho):
    """``beam_compound_step`` for a complex beta and minors v; returns the complex log of
    the scale taken out."""
    shift, E, F1, F2, F3, F4 = compound_krylov_c(beta * rho)
    beam_compound_fill_c(v, beta, rho, E, F1, F2, F3, F4)
    return shift


@njit(cache=True)
def clamped_clamped_count(x):
    """Natural frequencies of a segment clamped at both ends below x = lam l (J0 of one
    member), from the sign of its frequency equation times exp(-x)."""
    if x < math.pi:
        return 0
    E, chs, shs = _scales(math.exp(-x))
    (f,) = clamped_clamped_sign(x, E, chs, shs)
    i = int(x / math.pi)
    s = 1 if f > 0.0 else -1
    return i - (1 - (1 if i % 2 == 0 else -1) * s) // 2


@njit(cache=True)
def general_field(e, m, w2, kGA, rhoI, P, k_w, k_G, A):
    """A of Z' = A Z, Z = [Y, psi, M, Q], for a segment of ``derive/segments/general.py``
    in units L = EI_0 = mbar_0 = 1: e = EI / EI_0, m = mbar / mbar_0, w2 = (lam_0 L)^4 (the
    squared frequency), kGA, rhoI, P, k_w, k_G dimensionless (kGA = 0: no shear
    deformation). Real or complex (a loss factor in e, kGA, k_w, k_G), like its arguments."""
    if kGA == 0.0:
        general_field_rigid(e, m, w2, kGA, rhoI, P, k_w, k_G, A)
    else:
        general_field_shear(e, m, w2, kGA, rhoI, P, k_w, k_G, A)

"""What differs between the real chain (undamped, omega real) and the complex one (damped,
w = w_d + i sigma), so that one walk serves both (``characteristic.delta_chain``).

Each function is a real and a complex implementation: in plain Python (the interpreted
tier) it asks its argument's type; compiled, an ``overload`` lets numba pick one by the
argument's type, so a walk compiled for a real frequency holds only the real arithmetic
and one for a complex frequency only the complex, each with the formulas it had when the
two chains were two functions.
"""

import cmath
import math

import numpy as np
from numba import types
from numba.extending import overload

from mstmm.generated.euler_bernoulli import beam_compound_step, beam_compound_step_c

from .layout import HEAD, SEGMENT_WIDTH

__all__ = ["beam_step", "chain_frequency", "segment_factors", "stiffness", "work", "zero"]


def _chain_frequency_r(w, L, EI, mbar):
    beta = L * math.sqrt(math.sqrt(mbar * w * w / EI))
    w1 = beta * beta
    return w1, w1 * w1, beta


def _chain_frequency_c(w, L, EI, mbar):
    w1 = w * L * L * math.sqrt(mbar / EI)
    return w1, w1 * w1, cmath.sqrt(w1)


def chain_frequency(w, L, EI, mbar):
    """(w1, b4, beta) at the frequency w (rad/s): w1 = (lam_0 L)^2, b4 = w1^2 and beta =
    lam_0 L, complex for a complex w (any branch of beta: the chain depends on b4 only)."""
    f = _chain_frequency_c if isinstance(w, complex) else _chain_frequency_r
    return f(w, L, EI, mbar)


def _work_r(x, shape):
    return np.empty(shape)


def _work_c(x, shape):
    return np.empty(shape, dtype=np.complex128)


def work(x, shape):
    """``np.empty(shape)`` of x's kind (float or complex): the walk's work arrays."""
    return (_work_c if isinstance(x, complex) else _work_r)(x, shape)


def _zero_r(x):
    return 0.0


def _zero_c(x):
    return 0.0j


def zero(x):
    """0 of x's kind: where the chain's log starts."""
    return (_zero_c if isinstance(x, complex) else _zero_r)(x)


def _stiffness_r(x, eta):
    return 1.0


def _stiffness_c(x, eta):
    return 1.0 + 1j * eta


def stiffness(x, eta):
    """What a segment's stiffnesses are multiplied by: 1 + i eta in complex arithmetic (its
    loss factor), 1 in real (an undamped kernel has no loss factor)."""
    return (_stiffness_c if isinstance(x, complex) else _stiffness_r)(x, eta)


def _segment_factors_r(p, seg, beta, EI, mbar):
    if seg == 0:  # the first segment's EI and mbar are EI_0 and mbar_0: e = 1 exactly
        return 1.0, 1.0, beta
    i = HEAD + SEGMENT_WIDTH * seg
    e = p[i + 1] / EI
    return e, 1.0 / e, beta * math.sqrt(math.sqrt(p[i + 2] / mbar / e))


def _segment_factors_c(p, seg, beta, EI, mbar):
    i = HEAD + SEGMENT_WIDTH * seg
    e = p[i + 1] / EI * (1.0 + 1j * p[i + 3])
    f = 1.0 / e
    return e, f, beta * cmath.sqrt(cmath.sqrt(p[i + 2] / mbar * f))


def segment_factors(p, seg, beta, EI, mbar):
    """(e, 1 / e, beta_s) of Euler-Bernoulli segment seg: e its EI over the first's
    (times 1 + i eta in complex arithmetic), beta_s = beta (mbar_s / mbar_0 / e)^(1/4)
    (docs/components.md, section 3)."""
    f = _segment_factors_c if isinstance(beta, complex) else _segment_factors_r
    return f(p, seg, beta, EI, mbar)


def _beam_step_r(v, beta, rho):
    return beam_compound_step(v, beta, rho)


def _beam_step_c(v, beta, rho):
    return beam_compound_step_c(v, beta, rho)


def beam_step(v, beta, rho):
    """v <- C2(U_beam) v across rho (units L = EI = 1): ``beam_compound_step`` (real, a
    call) or ``beam_compound_step_c`` (complex, inlined: called, the damped walk was 3 %
    slower); returns the log of the scale taken out."""
    return (_beam_step_c if isinstance(beta, complex) else _beam_step_r)(v, beta, rho)


# Compiled, numba picks one of the two by the argument's type (the typing functions'
# parameters are the implementations').


def _pick(x, real, cplx):
    return cplx if isinstance(x, types.Complex) else real


@overload(chain_frequency, inline="always")
def _chain_frequency(w, L, EI, mbar):
    return _pick(w, _chain_frequency_r, _chain_frequency_c)


@overload(work, inline="always")
def _work(x, shape):
    return _pick(x, _work_r, _work_c)


@overload(zero, inline="always")
def _zero(x):
    return _pick(x, _zero_r, _zero_c)


@overload(stiffness, inline="always")
def _stiffness(x, eta):
    return _pick(x, _stiffness_r, _stiffness_c)


@overload(segment_factors, inline="always")
def _segment_factors(p, seg, beta, EI, mbar):
    return _pick(beta, _segment_factors_r, _segment_factors_c)


@overload(beam_step, inline="always")
def _beam_step(v, beta, rho):
    return _pick(beta, _beam_step_r, _beam_step_c)

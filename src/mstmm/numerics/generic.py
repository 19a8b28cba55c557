"""What differs between the real chain (undamped, omega real) and the complex one (damped,
w = w_d + i sigma), so that one walk serves both (``characteristic.delta_chain``).

Each helper is a real and a complex twin. A kernel is real or complex (damped), and
``characteristic.bind_characteristic`` puts one set (:data:`REAL` or :data:`COMPLEX`) into
its namespace under the names the walks call (``chain_frequency``, ...): numba resolves
them by name when it compiles the walk, as it resolves the kernel's printed events, so a
compiled chain holds only its own arithmetic, with the formulas each had when the two
chains were two functions. (An ``overload`` picking the twin by type did the same at run
time but cost the first run of a topology 0.9 s of typing; the interpreted tier runs the
same names in Python.)
"""

import cmath
import math

import numpy as np

from mstmm.jit import njit

from .beam import beam_compound_step, beam_compound_step_c
from .layout import COL_EI, COL_ETA, COL_MBAR, HEAD, SEGMENT_WIDTH

__all__ = ["REAL", "COMPLEX"]


@njit(cache=True, inline="always")
def chain_frequency_real(w, L, EI, mbar):
    """(w1, b4, beta) at omega = w (rad/s): beta = lam_0 L, w1 = beta^2, b4 = w1^2."""
    beta = L * math.sqrt(math.sqrt(mbar * w * w / EI))
    w1 = beta * beta
    return w1, w1 * w1, beta


@njit(cache=True, inline="always")
def chain_frequency_complex(w, L, EI, mbar):
    """(w1, b4, beta) at the complex w: w1 = w L^2 sqrt(mbar_0 / EI_0), b4 = w1^2, beta =
    sqrt(w1) (any branch: the chain depends on b4 only)."""
    w1 = w * L * L * math.sqrt(mbar / EI)
    return w1, w1 * w1, cmath.sqrt(w1)


@njit(cache=True, inline="always")
def work_real(shape):
    """The walk's work arrays."""
    return np.empty(shape)


@njit(cache=True, inline="always")
def work_complex(shape):
    """The walk's work arrays, complex."""
    return np.empty(shape, dtype=np.complex128)


@njit(cache=True, inline="always")
def stiffness_real(eta):
    """What a segment's stiffnesses are multiplied by: 1 (no loss factor)."""
    return 1.0


@njit(cache=True, inline="always")
def stiffness_complex(eta):
    """What a segment's stiffnesses are multiplied by: 1 + i eta (its loss factor)."""
    return 1.0 + 1j * eta


@njit(cache=True, inline="always")
def segment_factors_real(p, seg, beta, EI, mbar):
    """(e, 1 / e, beta_s) of Euler-Bernoulli segment seg: e its EI over the first's,
    beta_s = beta (mbar_s / mbar_0 / e)^(1/4) (docs/components.md, section 3)."""
    if seg == 0:  # the first segment's EI and mbar are EI_0 and mbar_0: e = 1 exactly
        return 1.0, 1.0, beta
    i = HEAD + SEGMENT_WIDTH * seg
    e = p[i + COL_EI] / EI
    return e, 1.0 / e, beta * math.sqrt(math.sqrt(p[i + COL_MBAR] / mbar / e))


@njit(cache=True, inline="always")
def segment_factors_complex(p, seg, beta, EI, mbar):
    """The same with the segment's loss factor: e = EI_s (1 + i eta_s) / EI_0."""
    i = HEAD + SEGMENT_WIDTH * seg
    e = p[i + COL_EI] / EI * (1.0 + 1j * p[i + COL_ETA])
    f = 1.0 / e
    return e, f, beta * cmath.sqrt(cmath.sqrt(p[i + COL_MBAR] / mbar * f))


#: The real kernel's helpers, by the names the walks call them.
REAL = {
    "chain_frequency": chain_frequency_real,
    "work": work_real,
    "stiffness": stiffness_real,
    "segment_factors": segment_factors_real,
    # a call (compiled once per machine); the walks' compile time, no run time lost
    "beam_step": beam_compound_step,
}
#: The damped kernel's.
COMPLEX = {
    "chain_frequency": chain_frequency_complex,
    "work": work_complex,
    "stiffness": stiffness_complex,
    "segment_factors": segment_factors_complex,
    # inlined: called, the damped walk was 3 % slower
    "beam_step": beam_compound_step_c,
}

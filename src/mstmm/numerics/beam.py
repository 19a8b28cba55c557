"""The Euler-Bernoulli beam functions SymPy prints, compiled; and what composes them that
is counting, not arithmetic.

``mstmm.generated.euler_bernoulli`` holds them as printed (plain Python): the reduced
Krylov functions and the compound functions (the constant terms below the ``*_TINY``
arguments, the series in x^4 below ``SERIES_THRESHOLD``, the closed forms above it,
plain or times exp(-x), whose exponent is returned as the shift of a log: no overflow;
real, and complex for a damped kernel and the frequency response, the branch by |x|),
the transfer matrix and the compound step filled from them, the sign of the
clamped-clamped frequency equation, a node stiffness step and the general segment's field
matrices. This module compiles each in that module's own namespace (a printed function
calls another by name, as a kernel's do: ``characteristic.bind_characteristic``), inlined
where its caller is a hot loop, and exports them.
"""

import math

from mstmm.generated import euler_bernoulli as printed
from mstmm.jit import njit

#: The printed functions compiled into their callers (a call costs about 20 ns, a
#: piece's arithmetic about 40 ns); the others are called.
INLINED = (
    "krylov",
    "krylov_scaled",
    "compound_krylov",
    "krylov_c",
    "krylov_scaled_c",
    "compound_krylov_c",
    "beam_compound_step_c",
    "clamped_clamped_sign",
    "node_stiffness_step",
    "general_field_rigid",
    "general_field_shear",
)
CALLED = ("beam_transfer", "beam_transfer_scaled", "beam_compound_step", "beam_transfer_scaled_c")

_namespace = vars(printed)
for _name in INLINED + CALLED:
    _inline = "always" if _name in INLINED else "never"
    _namespace[_name] = njit(cache=True, inline=_inline)(_namespace[_name])

krylov = printed.krylov
krylov_scaled = printed.krylov_scaled
compound_krylov = printed.compound_krylov
krylov_c = printed.krylov_c
krylov_scaled_c = printed.krylov_scaled_c
compound_krylov_c = printed.compound_krylov_c
#: Beam segment transfer matrix exactly as printed in paper Eq. (1): ``(lam, l, EI, U)``.
beam_transfer = printed.beam_transfer
#: Eq. (1) in units L = 1, EI = 1, times exp(-shift): ``(beta, rho, U)``, returns shift
#: (``_c``: complex beta).
beam_transfer_scaled = printed.beam_transfer_scaled
beam_transfer_scaled_c = printed.beam_transfer_scaled_c
#: v <- C2(U_beam) v in units L = 1, EI = 1: ``(v, beta, rho)``, returns the log of the
#: scale taken out (``_c``: complex beta and minors).
beam_compound_step = printed.beam_compound_step
beam_compound_step_c = printed.beam_compound_step_c
#: Zc <- the minors after a node stiffness kY on Y (Q -= kY Y) and kT on theta
#: (M += kT theta), units L = EI = 1.
node_stiffness_step = printed.node_stiffness_step
clamped_clamped_sign = printed.clamped_clamped_sign
general_field_rigid = printed.general_field_rigid
general_field_shear = printed.general_field_shear


@njit(cache=True)
def clamped_clamped_count(x):
    """Natural frequencies of a segment clamped at both ends below x = lam l (J0 of one
    member), from the sign of its frequency equation times exp(-x)."""
    if x < math.pi:
        return 0
    E = math.exp(-x)
    chs = 0.5 + 0.5 * E * E
    (f,) = clamped_clamped_sign(x, E, chs, 0.5 - 0.5 * E * E)
    i = int(x / math.pi)
    s = 1 if f > 0.0 else -1
    return i - (1 - (1 if i % 2 == 0 else -1) * s) // 2


@njit(cache=True)
def general_field(e, m, w2, kGA, rhoI, t, r, k_w, A):
    """A of Z' = A Z, Z = [Y, psi, M, Q], for a segment of ``derive/segments/general.py``
    in units L = EI_0 = mbar_0 = 1: e = EI / EI_0, m = mbar / mbar_0, w2 = (lam_0 L)^4 (the
    squared frequency), and the sums of its terms by role (``physics.segment.ROLES``):
    the shear stiffness kGA (0: no shear deformation), the rotary inertia rhoI, the
    tension t, the rotational foundation r and the Winkler foundation k_w, dimensionless.
    Real or complex (a loss factor in the stiffnesses), like its arguments."""
    if kGA == 0.0:
        general_field_rigid(e, m, w2, kGA, rhoI, t, r, k_w, A)
    else:
        general_field_shear(e, m, w2, kGA, rhoI, t, r, k_w, A)

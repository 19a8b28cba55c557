"""Mode shapes from the null vector of ``U_bar`` (paper Eq. (5)), then along the beam.

The right singular vector of the smallest singular value of ``U_bar(omega_n)``
gives the unknown boundary states ``Z_bar = [Z_1 unknowns, Y of each mass,
Z_root unknowns]``. From ``Z_1`` the state is carried along the beam with the
segment matrix of Eq. (1) (reduced form, exact for short segments), each
rigid body adding its branch shear ``U_I2 B [Y_m, 0]^T`` (Eq. (2)).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .kernels import Kernel
from .topology import unknown


@dataclass(frozen=True)
class ModeShape:
    """Transverse displacement of the beam and of each hanging mass, max |Y| = 1."""

    omega: float
    x: np.ndarray
    Y: np.ndarray
    mass_x: np.ndarray
    mass_Y: np.ndarray
    #: smallest over largest singular value of U_bar: how singular it is at omega
    singular_ratio: float


def _null_vector(A: np.ndarray) -> tuple[np.ndarray, float]:
    """Right singular vector of the smallest singular value (paper Eq. (5)), equilibrated.

    U_bar mixes metres, radians, newton-metres and newtons: its rows and columns
    differ by many decades, which costs the plain SVD as many digits of the null
    vector. Columns and rows are scaled to unit norm first (a few sweeps), and
    the column scaling is undone on the vector.
    """
    col = np.ones(A.shape[1])
    B = A.copy()
    for _ in range(3):
        r = np.linalg.norm(B, axis=1)
        B /= np.where(r > 0, r, 1.0)[:, None]
        c = np.linalg.norm(B, axis=0)
        c = np.where(c > 0, c, 1.0)
        B /= c[None, :]
        col /= c
    _u, sv, vt = np.linalg.svd(B)
    ratio = float(sv[-1] / sv[0]) if sv[0] > 0 else 0.0
    return col * vt[-1], ratio


def mode_shape(kernel: Kernel, p: np.ndarray, omega: float, n_points: int = 201) -> ModeShape:
    """The mode shape of the natural frequency ``omega`` (rad/s)."""
    p = np.ascontiguousarray(p, dtype=np.float64)
    L, EI, mbar = p[0], p[1], p[2]
    rec = p[3:].reshape(-1, 3) if kernel.topology.kinds else np.empty((0, 3))
    n = rec.shape[0]
    z, ratio = _null_vector(kernel.u_bar(omega, p))
    lam = (mbar * omega**2 / EI) ** 0.25
    Z = np.zeros(4)
    Z[list(unknown(kernel.topology.left))] = z[:2]
    mass_Y = z[2 : 2 + n].copy()
    xs = np.linspace(0.0, L, n_points)
    Y = np.empty_like(xs)
    pos, j = 0.0, 0
    for i in range(n + 1):
        end = rec[i, 0] if i < n else L
        while j < len(xs) and (xs[j] < end or (i == n and xs[j] <= end)):
            Y[j] = (kernel.beam_transfer(lam, xs[j] - pos, EI) @ Z)[0]
            j += 1
        if i < n:
            Z = kernel.beam_transfer(lam, end - pos, EI) @ Z
            _geometric, shear = kernel.module.spring_mass_tip(rec[i, 1], rec[i, 2], omega)
            Z[3] += shear * mass_Y[i]
            pos = end
    scale = max(np.max(np.abs(Y)), np.max(np.abs(mass_Y)) if n else 0.0)
    if scale > 0:
        k = np.argmax(np.abs(np.concatenate([Y, mass_Y])))
        sign = np.sign(np.concatenate([Y, mass_Y])[k]) or 1.0
        Y, mass_Y = Y * sign / scale, mass_Y * sign / scale
    return ModeShape(float(omega), xs, Y, rec[:, 0].copy(), mass_Y, ratio)

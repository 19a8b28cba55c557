"""Frequency response of a frame between node loads and node responses.

``frf(frame, input, output, omega)``: the steady-state response (time dependence
``exp(i w t)``) of ``output`` to a unit harmonic ``input``, from the exact dynamic
stiffness: ``x = D(omega)^-1 f`` with ``D = members + K + i omega C - omega^2 M`` (the
members exact and undamped, the absorbers' dashpots in C). Loads and responses are at
nodes: ``("force", node, (dx, dy))`` (N along the unit vector), ``("moment", node)`` (N m,
counterclockwise); ``("displacement", node, (dx, dy))`` (m), ``("rotation", node)``
(rad). A component along a held freedom is 0.
"""

from __future__ import annotations

import math

import numpy as np

from mstmm.scene import SceneError

from .assembly import Assembly
from .model import Frame

__all__ = ["frf"]


def _vector(asm: Assembly, spec, role: str) -> np.ndarray:
    """The freedoms' coefficients of a load or response spec (SI, unscaled)."""
    kind, node, *rest = spec
    if node not in asm.node_freedoms:
        raise SceneError(asm.frame.source, role, "no node of this name", node)
    if kind in ("force", "displacement"):
        dx, dy = rest[0]
        norm = math.hypot(dx, dy)
        d = (dx / norm, dy / norm, 0.0)
    elif kind in ("moment", "rotation"):
        d = (0.0, 0.0, 1.0)
    else:
        raise SceneError(asm.frame.source, role, "force, moment, displacement or rotation", kind)
    v = np.zeros(asm.n)
    for g in asm.node_freedoms[node]:
        v[g] = float(np.dot(asm.freedoms[g].vector, d))
    return v


def frf(frame: Frame, input, output, omega) -> np.ndarray:
    """Receptance (m/N, rad/N, m/(N m), rad/(N m)) of ``output`` to ``input`` at each
    omega (rad/s), complex; NaN where D is singular (a natural frequency, undamped)."""
    asm = Assembly(frame)
    f = _vector(asm, input, "input")
    g = _vector(asm, output, "output")
    units = asm.L_ref / asm.EI_ref
    # D_SI = S^-1 D S^-1 / units (D dimensionless): x = units S D^-1 S f
    fs, gs = asm.scale * f, asm.scale * g
    out = np.empty(len(np.atleast_1d(omega)), dtype=complex)
    for j, w in enumerate(np.atleast_1d(np.asarray(omega, dtype=float))):
        D, _ = asm.matrix(w)
        Dc = D + 1j * w * asm.C_lumped
        try:
            out[j] = units * (gs @ np.linalg.solve(Dc, fs))
        except np.linalg.LinAlgError:
            out[j] = np.nan
    return out

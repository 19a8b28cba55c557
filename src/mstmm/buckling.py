"""Buckling under axial compression: whether a scene's static equilibrium is stable, and
the factor on its axial forces at which it buckles (issue 22).

A segment under compression (``axial_force < 0``) lowers the stiffness: beyond the
buckling load the stiffness operator K has a negative eigenvalue, the structure has no
stable equilibrium, and "natural frequencies" about it are not defined (omega^2 < 0 for
a mode). The Wittrick-Williams count proves it without any root: the number of
eigenvalues of ``K - omega^2 M`` below 0 at a frequency ``omega_0`` above 0 and below
every positive natural frequency is ``n_neg + n_rigid`` (the negative eigenvalues of K
and the zero ones), and ``n_rigid`` is known exactly (``rigid_body_modes``: a segment's
axial force, even a compression, takes the rigid rotation from the zero modes). So the
structure is buckled iff ``count(omega_0) > rigid``. The load factor ``lam`` (all axial
forces times ``lam``: the structure buckles at ``lam = 1`` exactly when it is at its
buckling load) is found by bisection on that test, to 1e-12.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .catalog import HEAD, SEGMENT_COLUMNS, SEGMENT_WIDTH
from .kernels import Kernel
from .physics import segment as segment_terms

#: The term the load factor scales (the signed tension: the axial force) and its column
#: in a segment row.
COMPRESSION = segment_terms.compression_key()
AXIAL = SEGMENT_COLUMNS[COMPRESSION]
#: The test frequency, as a fraction of the beam's frequency scale sqrt(EI_0 / (mbar_0
#: L^4)) and of the lowest own frequency of a component.
PROBE = 1e-9
#: Relative width of the bisection's last bracket of the load factor.
LOAD_FACTOR_RTOL = 1e-12
#: Most bisection steps (a structure unstable under any compression, such as a free beam
#: whose rigid rotation the compression destabilises, has the load factor 0).
BISECTIONS = 64
#: Largest load factor searched for a scene that is not buckled.
LOAD_FACTOR_MAX = 1e12


@dataclass(frozen=True)
class Buckling:
    """Stability of a compressed scene: ``buckled`` (its axial forces reach the buckling
    load), the ``load_factor`` on them at which it buckles (below 1 when buckled; inf
    when no factor up to :data:`LOAD_FACTOR_MAX` buckles it), and ``unstable_modes``,
    the negative eigenvalues of its stiffness (the buckling modes exceeded)."""

    buckled: bool
    load_factor: float
    unstable_modes: int

    def message(self) -> str:
        """One line for the user."""
        if self.buckled:
            return (
                f"buckled: the axial forces exceed the buckling load ({self.unstable_modes}"
                f" buckling mode(s) exceeded); the structure buckles at {self.load_factor:.12g}"
                " times the given axial forces, and has no natural frequencies about an"
                " unstable equilibrium"
            )
        return f"buckling load factor {self.load_factor:.12g} (times the given axial forces)"


def axial_columns(p: np.ndarray) -> np.ndarray:
    """Indices of the segments' axial forces in a parameter vector."""
    return HEAD + SEGMENT_WIDTH * np.arange(int(p[3])) + AXIAL


def shear_limit(p: np.ndarray) -> float:
    """The largest load factor short of a Timoshenko segment's shear limit ``kappa_GA + lam
    P + k_G = 0`` (where its field matrix has no meaning), times ``1 - 1e-9``; inf when no
    compressed segment has a shear stiffness. A Timoshenko column buckles below it
    (``P_E / (1 + P_E / kappa_GA) < kappa_GA``), so the search never needs to go past."""
    rows = np.asarray(p[HEAD : HEAD + SEGMENT_WIDTH * int(p[3])]).reshape(-1, SEGMENT_WIDTH)
    values = segment_terms.row_values(rows, SEGMENT_COLUMNS)
    P = rows[:, AXIAL]
    kGA = segment_terms.total(values, "shear")
    shear = (kGA > 0.0) & (P < 0.0)
    if not shear.any():
        return math.inf
    rest = kGA  # g without the compression the load factor scales
    for t in segment_terms.of_role("tension"):
        if t.name != COMPRESSION:
            rest = rest + values[t.name]
    return float(np.min(rest[shear] / -P[shear])) * (1.0 - 1e-9)


def compressed(p: np.ndarray) -> bool:
    """Whether any segment of p is under compression."""
    return bool(np.any(np.asarray(p)[axial_columns(p)] < 0.0))


def probe_frequency(kernel: Kernel, p: np.ndarray) -> float:
    """A frequency (rad/s) above 0 and below every positive natural frequency of a stable
    structure of p's kind: far below the beam's scale and every component's own."""
    scale = math.sqrt(p[1] / (p[2] * p[0] ** 4))
    own = kernel.oscillator_frequencies(p)
    own = own[own > 0.0]
    return PROBE * min([scale, *own.tolist()])


def unstable_modes(kernel: Kernel, p: np.ndarray, probe: float | None = None) -> int:
    """Negative eigenvalues of the stiffness of p: the count at the probe frequency minus
    the rigid motions."""
    probe = probe_frequency(kernel, p) if probe is None else probe
    count = int(kernel.count_below(np.array([probe]), p)[0])
    return max(0, count - kernel.rigid_body_modes(p))


def buckling(kernel: Kernel, p: np.ndarray) -> Buckling | None:
    """The stability of p (None when no segment is compressed)."""
    if not compressed(p):
        return None
    probe = probe_frequency(kernel, p)
    cols = axial_columns(p)
    base = np.asarray(p, dtype=float)

    def negatives(lam: float) -> int:
        q = base.copy()
        q[cols] = base[cols] * lam
        return unstable_modes(kernel, q, probe)

    n = negatives(1.0)
    cap = shear_limit(p)
    if n > 0:
        lo, hi = 0.0, 1.0
    else:
        lo, hi = 1.0, min(2.0, cap)
        while negatives(hi) == 0:
            if hi >= cap:  # up to where kappa_GA + P + k_G reaches 0: no static equilibrium
                return Buckling(False, cap, 0)
            lo, hi = hi, min(2.0 * hi, cap)
            if hi > LOAD_FACTOR_MAX:
                return Buckling(False, math.inf, 0)
    for _ in range(BISECTIONS):
        if hi - lo <= LOAD_FACTOR_RTOL * hi:
            break
        mid = 0.5 * (lo + hi)
        if negatives(mid) > 0:
            hi = mid
        else:
            lo = mid
    if lo == 0.0 and hi <= LOAD_FACTOR_RTOL:  # unstable under any compression
        return Buckling(True, 0.0, n)
    return Buckling(n > 0, 0.5 * (lo + hi), n)

"""Natural frequencies of a plane frame with their exact multiplicities, and mode shapes.

Every root comes from the count (:meth:`Assembly.count`, Wittrick-Williams), so none is
missed and a repeated root's multiplicity is the count's jump across it:

1. a bracket ``[a, b]`` whose count rises is cut in two until the members' own count J0
   is the same at both ends (no member's clamped frequency inside: D(omega) has no pole
   there) and, while it is wider than :data:`SEPARATE`, until it holds one root;
2. a bracket of one root: ``det D`` changes sign once in it; :func:`refine_simple`
   finds the root from the band factors' determinant and the Rayleigh quotient of its
   null vector (compiled, no eigensolver: about seven evaluations of D a root); the
   bracket's counts already say it holds one root, of multiplicity 1;
3. any other bracket (a repeated root, a cluster, or where the factors' pivots grew):
   ``g(omega)``, the ``(count(a) - J0)``-th eigenvalue of D in ascending order, is
   >= 0 at a and < 0 from the bracket's first root on (D's negative eigenvalues never
   fall between poles, as the count never does): Brent's method finds that root to
   1e-11 and :func:`polish` to round-off;
4. for those, the counts just below and above it say how many roots lie there: the narrowest
   window (from the root's own, ``polish``, up to 1e-6) at whose edges no eigenvalue
   of D lies within its round-off (:meth:`Assembly.sure_count`), with the bracket's
   count below, gives the root's multiplicity, and the bracket's rest is searched
   again. Roots closer than that window are one root of their joint multiplicity.

Mode shapes: the null space of D at the root (one independent shape per multiplicity),
the joints' displacements, and along each member the fields ``u, w, psi, N, Q, M``
marched from its start (:func:`mstmm.frame.member.member_march` and the rod's closed form).
Each shape is normalised to unit modal mass, the kinetic energy form ``-dD/d(omega^2)``
(exact for a dynamic stiffness, Wittrick and Williams), evaluated by a central difference.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np

from mstmm.scene import SceneError

from .assembly import Assembly, MemberMap
from .banded import backward, band_matvec, inverse_iteration, ldl, row_norm
from .member import (
    bending_pieces,
    member_bending,
    member_bending_c,
    member_march,
    member_rod,
    member_rod_c,
    rod_pieces,
)
from .model import Frame

__all__ = ["FrameMode", "FrameSolution", "solve_undamped_frame"]

#: Relative precision of Brent's refinement (ulp of float64).
ROOT_GUARD = 4 * np.finfo(float).eps
#: Relative half-widths of the windows tried around a refined root: the first at whose
#: edges every eigenvalue of D is decided (beyond its round-off) gives the root's
#: multiplicity. Near a root the count is decided by eigenvalues of D as small as its
#: round-off: with members EA L^2 / EI = 2e4 times stiffer axially (FV2), its sign
#: wavers within about 1e-12 of a five-fold root.
SETTLE = (ROOT_GUARD, 1e-14, 1e-13, 1e-12, 1e-11, 1e-10, 1e-9, 1e-8, 1e-7, 1e-6)
#: A bracket narrower than this (relative) whose windows never settle is one root of its
#: count's jump (a cluster float64 cannot separate).
CLUSTER = 1e-9
#: Relative size of the smallest eigenvalue of the static D (0) that means a mechanism.
MECHANISM = 1e-11
#: Relative step of the central difference in omega^2 for the modal mass (at most).
MASS_STEP = 1e-4
#: The modal mass's difference keeps this many steps from a pole of D (``_mass_form``):
#: its error then is about the step over the distance to the pole, to the fourth power.
POLE_CLEARANCE = 64
#: Brent's relative tolerance: ``polish`` takes the root from there to round-off.
BRENT_RTOL = 1e-11
#: Eigenvalues of D within this factor of the least belong to the same root
#: (``local_multiplicity``): at Brent's 1e-11 a root's own eigenvalues are 1e-11 of their
#: slope, another root's 1e-8 away already 1e-8.
SAME_ROOT = 1e2
#: The longest step ``polish`` takes (relative to the root).
POLISH_REACH = 1e-8
#: A bracket holding several roots is cut in two by counts until it is this narrow
#: (relative) before the orthogonal route takes it as one (a repeated root or a cluster).
SEPARATE = 1e-4
#: The determinant's secant stops at this relative step (``refine_simple``): the
#: Rayleigh quotient's secant takes the root from there to round-off.
SIMPLE_RTOL = 1e-6
#: Secant steps on the Rayleigh quotient after it (each but the last evaluates D once)
#: and the step that ends them (relative): the error after a step is about the
#: product of the last two.
SECANT_STEPS = 3
SECANT_DONE = 1e-9
#: Relative step of the one-sided difference that gives ``refine_simple`` its slope.
SLOPE_STEP = 1e-7
#: ``refine_simple`` gives the bracket to the orthogonal route where a factorization's
#: backward error exceeds D's round-off by this factor (its determinant's sign is then
#: not sure).
SIMPLE_GROWTH = 1e3
#: Where ``_shapes`` cuts each member when a root sits on a member's pole (an
#: irrational fraction: the pieces' clamped-clamped frequencies are not the member's).
CUT = math.sqrt(2.0) - 1.0
#: A damped mode's member stiffness is cut for frequencies up to this many times its own.
DAMPED_REACH = 1.25
#: Gauss-Legendre points per segment and per wave in it (a field's wavelength / 2 pi)
#: for the participation integrals.
GAUSS_POINTS = 16


@dataclass
class FrameMode:
    """One mode: its frequency (rad/s), the joints' (X, Y, Theta), the mass-normalised
    freedom vector (SI) and, on demand, each member's fields."""

    omega: float
    multiplicity: int
    nodes: dict[str, tuple[float, float, float]]
    vector: np.ndarray
    participation: tuple[float, float] = (0.0, 0.0)
    #: The assembly ``vector`` is over where it is not the solution's: a root at one of a
    #: member's own clamped-clamped frequencies is solved on the frame with its members cut
    #: (:func:`_shapes`), its members then in pieces ``<name>[0]``, ``<name>[1]``.
    assembly: Assembly | None = None

    @property
    def effective_mass(self) -> tuple[float, float]:
        """Effective masses along X and Y (kg): the participations squared."""
        return self.participation[0] ** 2, self.participation[1] ** 2


@dataclass
class FrameSolution:
    """Natural frequencies (rad/s, ascending, each repeated root once per multiplicity),
    the multiplicity of the root each belongs to, the modes, and whether the count
    confirmed every root (``count_checked``)."""

    frame: Frame
    omega: np.ndarray
    multiplicity: np.ndarray
    modes: list[FrameMode] = field(default_factory=list)
    count_checked: bool = True
    assembly: Assembly | None = None

    @property
    def f(self) -> np.ndarray:
        """Frequencies in Hz."""
        return self.omega / (2 * math.pi)

    def member_fields(self, mode: int, member: str, points: int = 21) -> dict[str, np.ndarray]:
        """Along member ``member`` in mode ``mode``: ``x`` (m from its start) and ``u, w,
        psi, N, Q, M`` (SI, local axes; N tension positive)."""
        m = self.modes[mode]
        return member_fields(m.assembly or self.assembly, m, member, points)

    def to_dict(self) -> dict:
        """Plain data: frequencies, multiplicities and each mode's joint displacements."""
        return {
            "frame": self.frame.name,
            "omega": self.omega.tolist(),
            "f": self.f.tolist(),
            "multiplicity": self.multiplicity.tolist(),
            "count_checked": self.count_checked,
            "motion": self.frame.motion,
            "modes": [
                {
                    "omega": m.omega,
                    "nodes": {k: list(v) for k, v in m.nodes.items()},
                    "participation": list(m.participation),
                    "effective_mass": list(m.effective_mass),
                }
                for m in self.modes
            ],
        }


def _mechanism(asm: Assembly) -> None:
    """Refuse a frame whose supports and joints leave a rigid motion free (D(0) singular)."""
    if asm.n == 0:
        return
    B, _ = asm.banded(0.0)
    free = asm.within(B, MECHANISM * float(row_norm(B)), asm._work())
    if free is None:  # pivots grew (a mechanism's singular D(0), or near it): the dense eigenvalues
        e = np.linalg.eigvalsh(asm.dense(B))
        free = int(np.count_nonzero(np.abs(e) <= MECHANISM * np.max(np.abs(e))))
    if free:
        raise SceneError(
            asm.frame.source, "-",
            f"the structure is a mechanism: {free} free rigid motion(s) at zero frequency"
            " (add supports or rigid joints)",
        )  # fmt: skip


def roots(
    asm: Assembly, modes: int | None = None, band: tuple[float, float] | None = None
) -> list[tuple[float, int]]:
    """The distinct natural frequencies (rad/s) with their multiplicities: the lowest
    ``modes`` (the last root kept whole) or all in ``band``."""
    from scipy.optimize import brentq

    _mechanism(asm)
    if band is None:
        lo, hi = 0.0, asm.omega_ref
        while asm.count(hi) < modes:
            hi *= 2.0
    else:
        lo, hi = band
    found: list[tuple[float, int]] = []

    def total() -> int:
        return sum(m for _, m in found)

    def g(w: float, idx: int) -> float:
        return asm.eigenvalue(asm.banded(w)[0], idx)

    stack = [(lo, *(asm.state(lo) if lo > 0 else (0, 0)), hi, *asm.state(hi))]
    while stack:
        a, ca, ja, b, cb, jb = stack.pop()
        if cb == ca or (modes is not None and total() >= modes):
            continue
        if (ja != jb and b - a > ROOT_GUARD * b) or (cb - ca > 1 and b - a > SEPARATE * b):
            mid = 0.5 * (a + b)
            cm, jm = asm.state(mid)
            stack += [(mid, cm, jm, b, cb, jb), (a, ca, ja, mid, cm, jm)]
            continue
        idx = ca - ja
        simple = None
        if cb - ca == 1 and ja == jb:
            simple = refine_simple(asm, a, b, idx)
        if simple is not None:  # one root, by the bracket's counts: nothing to settle
            found.append((simple, 1))
            continue
        if ja == jb and 0 <= idx < asm.n and g(a, idx) > 0.0 and g(b, idx) < 0.0:
            w = brentq(g, a, b, args=(idx,), xtol=1e-300, rtol=BRENT_RTOL, maxiter=200)
            k = local_multiplicity(asm, w, cb - ca)
            w, window = polish(asm, w, k, w * POLISH_REACH)
            w = min(max(w, a), b)
        else:
            w = 0.5 * (a + b)
            window = ROOT_GUARD
        if b - a <= 2 * CLUSTER * b:  # float64 separates nothing inside: one cluster
            found.append((w, cb - ca))
            continue
        for delta in _ladder(window):
            below = max(a, w * (1 - delta))
            c_below, _, unsure_below = asm.sure_count(below)
            if unsure_below or c_below != ca:
                continue
            above = min(b, w * (1 + delta))
            c_above, j_above, unsure_above = asm.sure_count(above)
            if unsure_above or c_above == ca:
                continue
            found.append((w, c_above - ca))
            if above < b:
                stack.append((above, c_above, j_above, b, cb, jb))
            break
        else:  # no window settles: the bracket is cut in two and searched again
            mid = 0.5 * (a + b)
            cm, jm = asm.state(mid)
            stack += [(mid, cm, jm, b, cb, jb), (a, ca, ja, mid, cm, jm)]
    found.sort()
    return found


def refine_simple(asm: Assembly, a: float, b: float, negatives: int) -> float | None:
    """The one root in a bracket ``[a, b]`` where D has no pole and one more negative
    eigenvalue at b than its ``negatives`` at a, or None where the fast route cannot
    vouch for it (the caller then takes the orthogonal one).

    ``det D(omega)`` changes sign once there, at the root, and is smooth: the
    Anderson-Bjorck bracketing secant on it, from the pivots of :func:`.banded.ldl`
    (``(-1)^(negatives) exp(log|det| - log|det D(a)|)``), until its step is below
    :data:`SIMPLE_RTOL`. Then one secant step on the Rayleigh quotient ``t = x^T D x`` of
    the null vector x (two inverse iterations with the last factors) through the last
    two points: t is smooth where det is, and its root is accurate where det's sign is
    not (D's stiff axial entries set det's round-off, the bending mode's x barely moves
    them). No evaluation of D beyond the secant's."""
    W = asm._work()
    seen: list[tuple[float, np.ndarray]] = []
    grown = False

    def f(w: float) -> float:
        nonlocal grown
        B, _ = asm.banded(w)
        seen.append((w, B))
        neg, G, logabs = ldl(B, 0.0, W)
        grown |= backward(G, asm.bandwidth) > SIMPLE_GROWTH * asm.roundoff(B)
        if not math.isfinite(logabs):
            return 0.0
        return (-1.0) ** (neg - negatives) * _ratio(logabs - log_a)

    def known(w: float) -> float | None:
        """log|det D(w)| from an earlier factorization, or None."""
        log = asm.factors.get(w, (0, 0, math.nan))[2]
        return log if math.isfinite(log) else None

    log_a = known(a)
    if log_a is None:
        log_a = ldl(asm.banded(a)[0], 0.0, W)[2]
    log_b = known(b)
    fa = 1.0
    fb = -_ratio(log_b - log_a) if log_b is not None else f(b)
    if not (math.isfinite(log_a) and fb < 0.0) or grown:
        return None
    wa, wb, w = a, b, b
    for _ in range(100):
        c = wb - fb * (wb - wa) / (fb - fa)
        lo, hi = min(wa, wb), max(wa, wb)
        if not lo < c < hi:
            c = 0.5 * (lo + hi)
        fc = f(c)
        step, w = abs(c - w), c
        if fc == 0.0 or step <= SIMPLE_RTOL * c:
            break
        if (fc > 0.0) == (fb > 0.0):
            m = 1.0 - fc / fb
            fa *= m if m > 0.0 else 0.5
        else:
            wa, fa = wb, fb
        wb, fb = c, fc
    else:
        return None
    if grown:
        return None
    w2, B2 = seen[-1]
    ldl(B2, 0.0, W)
    x = inverse_iteration(W, 2)
    y = np.empty_like(x)

    def t(B: np.ndarray) -> float:
        band_matvec(B, x, y)
        return float(x @ y)

    # the slope through the nearest earlier point at least SLOPE_STEP away (round-off)
    far = [(abs(w1 - w2), w1, B1) for w1, B1 in seen[:-1] if abs(w1 - w2) > SLOPE_STEP * w2]
    _, w1, B1 = min(far, default=(0.0, w2 * (1.0 - SLOPE_STEP), None))
    t1 = t(asm.banded(w1)[0] if B1 is None else B1)
    t2 = t(B2)
    for _ in range(SECANT_STEPS):
        slope = (t2 - t1) / (w2 - w1)
        if not slope < 0.0 or abs(t2 / slope) > POLISH_REACH * w2:
            return None
        step = t2 / slope
        w = min(max(w2 - step, a), b)
        if abs(step) <= SECANT_DONE * w2:
            break
        w1, t1 = w2, t2
        w2, B2 = w, asm.banded(w)[0]
        t2 = t(B2)
    else:
        return None
    return w


def _ratio(log: float) -> float:
    """``exp(log)``, its exponent kept within float64's range (a determinant's ratio)."""
    return math.exp(min(max(log, -700.0), 700.0))


def _mass_form(asm: Assembly, w: float) -> np.ndarray:
    """``-dD/d(omega^2)`` at w (dimensionless units of D per omega_ref^2; band rows, as
    :meth:`Assembly.banded`), by a fourth-order
    central difference in omega^2 whose step keeps :data:`POLE_CLEARANCE` steps from any
    pole of D (a member's clamped-clamped frequency: J0 is the same at both ends of the
    clearance, and J0 never falls). A cantilever's fourth root lies 1.2e-5 below its
    third clamped-clamped one: a step of 1e-4 across that pole threw the slope, and the
    polished root, 4e-9 off."""
    w2 = w * w
    h = MASS_STEP * w2 if w2 > 0 else MASS_STEP * asm.omega_ref**2
    J0 = asm.banded(w)[1]
    for _ in range(40):
        lo, hi = max(w2 - POLE_CLEARANCE * h, 0.0), w2 + POLE_CLEARANCE * h
        if asm.banded(math.sqrt(lo))[1] == J0 == asm.banded(math.sqrt(hi))[1]:
            break
        h /= 4.0
    D = [asm.banded(math.sqrt(max(w2 + j * h, 0.0)))[0] for j in (-2, -1, 1, 2)]
    return -(D[0] - 8 * D[1] + 8 * D[2] - D[3]) / (12 * h)


def _null_space(asm: Assembly, w: float, k: int) -> np.ndarray:
    """The k eigenvectors of D(w) of the smallest eigenvalues in magnitude."""
    B = asm.banded(w)[0]
    if k == 1:
        x = asm.null_vector(B)
        if x is not None:
            return x[:, None]
    return asm.near_zero(B, k)[1]


def _ladder(window: float) -> list[float]:
    """The windows tried: from the root's own (``polish``) up to :data:`SETTLE`'s widest."""
    return [window] + [d for d in SETTLE if d > window]


def local_multiplicity(asm: Assembly, w: float, most: int) -> int:
    """How many of D(w)'s ``most`` eigenvalues of least magnitude belong to the root near
    w: those within :data:`SAME_ROOT` times the least (the others belong to roots farther
    off, as far as their eigenvalues are larger)."""
    e, _ = asm.near_zero(asm.banded(w)[0], most)
    e = np.sort(np.abs(e))
    return max(1, int(np.count_nonzero(e <= SAME_ROOT * e[0] + 1e-300)))


def polish(asm: Assembly, w: float, k: int, reach: float) -> tuple[float, float]:
    """A root of multiplicity k refined by Newton's method on the Rayleigh quotient
    ``t(omega) = tr(X^T D(omega) X)`` of its null space X, ``t' = -2 omega tr(X^T M X)``
    (M = -dD/d(omega^2)).

    Brent's method on an eigenvalue of D stops where that eigenvalue is as small as the
    eigensolver's normwise error, ``eps |D|``: where members are much stiffer axially than
    in bending (EA L^2 / EI = 7e5 in the tests) that leaves 5e-12 of the root. ``X^T D X``
    formed from D's entries errs by ``eps |D| |X|`` entrywise, and the bending modes' X
    barely move the stiff axial freedoms: two steps bring the root to round-off. A step
    longer than ``reach`` is not taken (a polish, not a search); k is the multiplicity the
    bracket allows (at most the root's: X then holds the nearest eigenvectors).

    Returns the root and the narrowest window (relative half-width) at whose edges its
    eigenvalues of D lie beyond D's round-off (:meth:`Assembly.sure_count`): ``4 tau /
    (omega |d lambda / d omega|)`` per eigenvalue, ``tau`` the round-off. A low sway mode
    of a tall frame moves its eigenvalue slowly against D's axial norm: its window is
    wide (1e-8 and more), a beam-like mode's 1e-14."""
    window = ROOT_GUARD
    for _ in range(3):
        B, _ = asm.banded(w)
        X = asm.near_zero(B, k)[1]
        t = float(np.trace(asm.quadratic(B, X)))
        slope = -2.0 * w * float(np.trace(asm.quadratic(_mass_form(asm, w), X)))
        if slope == 0.0 or not math.isfinite(t / slope):
            break
        window = max(ROOT_GUARD, 4.0 * asm.roundoff(B) * k / (w * abs(slope)))
        step = t / slope
        if abs(step) > reach:
            break
        w -= step
        if abs(step) <= ROOT_GUARD * w:
            break
    return w, window


def _shapes(asm: Assembly, w: float, multiplicity: int) -> list[FrameMode]:
    """Mass-orthonormal modes spanning the null space of D(w).

    A root at one of a member's own clamped-clamped frequencies (a pole of D: the
    members' J0 changes across it; a symmetric structure whose joints stand still while
    its members vibrate) has modes D cannot show. They are solved on the frame with every
    member cut at :data:`CUT` of its length, whose pieces' poles lie elsewhere: the
    joints the cuts add carry those modes."""
    near = POLISH_REACH * w
    if asm.banded(w - near)[1] != asm.banded(w + near)[1]:
        cut = Assembly(_cut(asm.frame))
        modes = _shapes(cut, w, multiplicity)
        for mode in modes:
            mode.assembly = cut
        return modes
    X = _null_space(asm, w, multiplicity)
    G = asm.quadratic(_mass_form(asm, w), X)
    G = 0.5 * (G + G.T)
    Lc = np.linalg.cholesky(G)
    X = np.linalg.solve(Lc, X.T).T  # X^T M X = I
    # back to SI: D_dimless = (L_ref/EI_ref) S D S, so x_SI = S x / sqrt(mass units)
    units = asm.L_ref / asm.EI_ref  # M_dimless = units * S M_SI S
    out = []
    for j in range(multiplicity):
        x = asm.scale * X[:, j] * math.sqrt(units)
        out.append(FrameMode(w, multiplicity, _joints(asm, x), x))
    return out


def _cut(frame: Frame) -> Frame:
    """The frame with every member cut at :data:`CUT` of its length."""
    from .reading import with_points

    points = [(m.name, CUT * frame.geometry(m)[0]) for m in frame.members]
    return with_points(frame, points)[0]


def _joints(asm: Assembly, x: np.ndarray) -> dict[str, tuple[float, float, float]]:
    out = {}
    for name, index in asm.node_freedoms.items():
        v = np.zeros(3, dtype=x.dtype)
        for g in index:
            v += x[g] * np.asarray(asm.freedoms[g].vector)
        out[name] = tuple(v.tolist())
    return out


def member_fields(asm: Assembly, mode: FrameMode, member: str, points: int = 21) -> dict:
    """``x, u, w, psi, N, Q, M`` along a member in a mode (SI, its local axes) at
    ``points`` equally spaced points (a member cut in pieces in ``asm``: along them)."""
    pieces = [m for m in asm.members if m.member.name == member] or [
        m for m in asm.members if m.member.name.startswith(f"{member}[")
    ]
    if not pieces:
        raise KeyError(f"no member {member!r}")
    x = np.linspace(0.0, sum(m.L for m in pieces), points)
    parts, start = [], 0.0
    for j, mm in enumerate(pieces):
        end = start + mm.L
        inside = (x >= start) & ((x <= end) if j == len(pieces) - 1 else (x < end))
        f = fields_at(mm, mode, x[inside] - start)
        f["x"] = x[inside]
        parts.append(f)
        start = end
    return {k: np.concatenate([f[k] for f in parts]) for k in parts[0]}


def fields_at(mm: MemberMap, mode: FrameMode, x: np.ndarray) -> dict:
    """``x, u, w, psi, N, Q, M`` of member ``mm`` in a mode at the points x (m from its
    start, ascending): the bending state marched from the start (its end forces from the
    member's stiffness), the rod's closed form. Out of the plane the rod is the member's
    torsion: ``phi`` (its twist, rad) and ``T`` (its torque, N m) instead of u and N, and
    w is along Z."""
    d = mm.T @ mode.vector[mm.index]  # [u_a, w_a, psi_a, u_b, w_b, psi_b]
    L, EI0 = mm.L, mm.p[1]
    w = mode.omega
    w1 = L * L * math.sqrt(mm.p[2] / EI0) * w  # (lam_0 L)^2
    K4 = np.empty((4, 4), d.dtype)
    K2 = np.empty((2, 2), d.dtype)
    if np.iscomplexobj(d):  # a damped mode: the members' stiffnesses at its complex root
        reach = DAMPED_REACH * abs(w1) ** 0.5
        pieces = np.ones(int(mm.p[3]), dtype=np.int64)
        bending_pieces(mm.p, reach, reach, pieces)
        member_bending_c(mm.p, complex(w1), pieces, 1.0, K4)
        rods = np.ones(len(mm.h), dtype=np.int64)
        rod_pieces(mm.EA, mm.mbar, mm.h, DAMPED_REACH * abs(w), DAMPED_REACH * abs(w), rods)
        member_rod_c(mm.EA, mm.mbar, mm.h, mm.eta, rods, 1.0, complex(w), K2)
    else:
        member_bending(mm.p, math.sqrt(w1), K4)
        member_rod(mm.EA, mm.mbar, mm.h, w, K2)
    nodal = K4 @ np.array([d[1] / L, d[2], d[4] / L, d[5]])  # member units: [F, M_t] at a
    Z0 = np.array([d[1] / L, d[2], -nodal[1], nodal[0]])
    Z = np.empty((len(x), 4), d.dtype)
    member_march(mm.p, w1, Z0, np.asarray(x, dtype=float) / L, Z)
    N_a = -(K2[0, 0] * d[0] + K2[0, 1] * d[3])  # the start's nodal force is -N
    u, N = _rod_fields(mm, w, d[0], N_a, np.asarray(x, dtype=float))
    along, force = ("phi", "T") if mm.torsion else ("u", "N")
    return {
        "x": np.asarray(x, dtype=float),
        along: u,
        "w": Z[:, 0] * L,
        "psi": Z[:, 1],
        "M": Z[:, 2] * EI0 / L,
        "Q": Z[:, 3] * EI0 / L**2,
        force: N,
    }


def participation(asm: Assembly, mode: FrameMode) -> tuple[float, float]:
    """``(Gamma_X, Gamma_Y)`` of a mode of unit modal mass (a grillage's: ``(Gamma_Z,
    0)``): the mass-weighted integral of its displacement along X and Y (along Z) (members
    by Gauss-Legendre on each segment, node masses and absorbers); ``Gamma^2`` is the
    mode's effective mass (kg) in that direction."""
    grid = asm.frame.motion == "out_of_plane"
    gx = gy = 0.0
    for mm in asm.members:
        L, c, s = asm.frame.geometry(mm.member)
        start = 0.0
        for j, h in enumerate(mm.h):
            seg = mm.member.segments[j]
            waves = h * (mode.omega * mode.omega * seg.mass_per_length / seg.EI) ** 0.25
            if not mm.torsion:
                waves += h * mode.omega * math.sqrt(mm.mbar[j] / mm.EA[j])
            n = GAUSS_POINTS * (1 + int(waves))
            t, weight = _gauss(n)
            f = fields_at(mm, mode, start + 0.5 * h * (t + 1.0))
            wt = 0.5 * h * weight * seg.mass_per_length
            if grid:  # w is along Z
                gx += float(np.sum(wt * f["w"]))
            else:
                gx += float(np.sum(wt * (c * f["u"] - s * f["w"])))
                gy += float(np.sum(wt * (s * f["u"] + c * f["w"])))
            start += h
    for name, node in asm.frame.nodes.items():
        first, second, _ = mode.nodes[name]  # (X, Y, Theta), or a grillage's (W, ...)
        gx += node.mass * first
        if not grid:
            gy += node.mass * second
    for i, ab in enumerate(asm.frame.absorbers):  # a grillage's along (1, 0): along Z
        q = mode.vector[asm.absorber_freedoms[i]]
        gx += ab.m * q * ab.direction[0]
        gy += ab.m * q * ab.direction[1]
    return gx, gy


@functools.lru_cache(maxsize=64)
def _gauss(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre points and weights on [-1, 1] (computed once per n)."""
    return np.polynomial.legendre.leggauss(n)


def _rod_fields(mm, w, u0, N0, xs: np.ndarray):
    """u and N along the rod's segments from (u, N) at its start (complex at a damped
    mode's complex w: EA times 1 + i eta there)."""
    damped = isinstance(w, complex) or isinstance(u0, complex) or np.iscomplexobj(u0)
    u = np.empty(xs.shape, dtype=complex if damped else float)
    N = np.empty_like(u)
    start = 0.0
    for j, h in enumerate(mm.h):
        EA, mbar = mm.EA[j], mm.mbar[j]
        if damped:
            EA = EA * (1.0 + 1j * mm.eta[j])
        kappa = w * np.sqrt(mbar / EA)
        last = j == len(mm.h) - 1
        inside = (xs >= start) & ((xs <= start + h) if last else (xs < start + h))
        t = xs[inside] - start
        if kappa:
            u[inside] = u0 * np.cos(kappa * t) + N0 / (EA * kappa) * np.sin(kappa * t)
            N[inside] = -EA * kappa * u0 * np.sin(kappa * t) + N0 * np.cos(kappa * t)
            u0, N0 = (
                u0 * np.cos(kappa * h) + N0 / (EA * kappa) * np.sin(kappa * h),
                -EA * kappa * u0 * np.sin(kappa * h) + N0 * np.cos(kappa * h),
            )
        else:
            u[inside] = u0 + N0 / EA * t
            N[inside] = N0
            u0 = u0 + N0 / EA * h
        start += h
    return u, N


def solve_undamped_frame(
    frame: Frame,
    modes: int | None = None,
    band: tuple[float, float] | None = None,
    *,
    shapes: bool = True,
) -> FrameSolution:
    """The lowest ``modes`` natural frequencies of ``frame`` (default 10), or all in
    ``band`` (rad/s), each with its exact multiplicity, and their mode shapes, of a
    frame without damping (:func:`mstmm.frame.solve_frame` chooses)."""
    if modes is None and band is None:
        modes = 10
    asm = Assembly(frame)
    found = roots(asm, modes, band)
    omega = np.array([w for w, m in found for _ in range(m)])
    mult = np.array([m for _, m in found for _ in range(m)], dtype=np.int64)
    modes_out: list[FrameMode] = []
    if shapes:
        for w, m in found:
            modes_out += _shapes(asm, w, m)
        for mode in modes_out:
            mode.participation = participation(mode.assembly or asm, mode)
    return FrameSolution(frame, omega, mult, modes_out, True, asm)

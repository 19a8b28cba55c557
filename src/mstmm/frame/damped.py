"""Damped natural frequencies of a frame: complex roots, found by continuation from the
undamped frame and certified by the argument principle, as a beam's (:mod:`mstmm.damped`).

With the absorbers' dashpots and the members' loss factors (their stiffnesses times ``1 +
i eta``) the natural frequencies are the complex ``w = w_d + i sigma`` (time dependence
``exp(i w t)``, ``sigma > 0`` decays) where the dynamic stiffness ``D(w) = members(w) + K
+ i w C - w^2 M`` is singular. ``det D`` has poles, the members' own clamped-clamped
frequencies, so the function counted is ``g(w) = det D_full(w)``: the frame with the node
between every two pieces of every member kept (:func:`mstmm.frame.member.bending_pieces`,
``rod_pieces``), each piece so short that its clamped-clamped frequencies lie beyond the
counted rectangle's real points (an undamped piece's are real; with a loss factor their
real parts are at least the undamped piece's lowest, by its Rayleigh quotient ``(k_R + i
eta k_L) / m``, ``k_R / m`` at least that). ``g = det D * prod(det P)`` (block
elimination: ``P`` the pivots of the pieces' inner nodes,
:func:`mstmm.frame.member.chain_add_c`) is analytic in the rectangle, its zeros there
exactly the damped roots with their multiplicities. ``det D`` comes from LAPACK's band LU
with partial pivoting (``zgbtrf``) of D's band rows.

The search is the beam's (:func:`mstmm.damped.search`): each simple undamped root carried
to full damping, the rectangle ``w_d < W``, ``sigma < S`` counted, what the count says is
left searched; each simple root polished on the Rayleigh form of its null vector
(:func:`polish`). ``S`` is proved (:func:`sigma_max`) where the proof applies. With
dashpots only, the roots are mirror pairs ``(w, -conj w)`` and ``g`` is real on the
imaginary axis (overdamped roots on it exactly); a loss factor breaks the symmetry, and
the rectangle then starts just left of the axis, as a beam's.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.linalg.lapack import zgbtrf, zgbtrs

from mstmm.damped import (
    DampedRoot,
    DampedRoots,
    DampedValues,
    _Problem,
    roots_table,
    search,
    sigma_top,
)
from mstmm.decay_bound import DecayBound, bound_from

from .assembly import Assembly
from .member import assemble_members_c, bending_pieces, rod_pieces
from .model import Frame
from .solve import _joints, member_fields, roots

__all__ = ["DampedFrameMode", "DampedFrameSolution", "solve_damped_frame", "sigma_max"]

#: The counted disc's radius over the rectangle's farthest corner (the count nudges its
#: edges outward by a few thousandths where a zero sits on one).
COVER = 1.05


class FrameFunction:
    """``log g(w)`` (:class:`mstmm.contour.LogF`) of a frame with its dashpots scaled by
    ``t``, with no pole in a rectangle whose real points have ``|w| <= top`` and whose
    points all have ``|w| <= radius`` (rad/s); :meth:`cover` widens it."""

    def __init__(self, asm: Assembly, t: float, top: float, radius: float | None = None) -> None:
        self.asm = asm
        self.t = t
        self.top = self.radius = 0.0
        self.calls = 0
        self.C_band = t * asm.C_band
        self.cover(top, radius or top)

    def cover(self, top: float, radius: float) -> None:
        """Pieces for a rectangle of real points up to ``top`` and points up to
        ``radius`` (rad/s): a new function where either grows (the count then uses this
        one throughout)."""
        radius = max(radius, top)
        if top <= self.top and radius <= self.radius:
            return
        top, radius = max(top, self.top), max(radius, self.radius)
        P, p_off, EA, mbar, h, r_off, L = self.asm.packed[:7]
        segments = max(int(P[p_off[t] + 3]) for t in range(len(L)))
        self.bp = np.ones((len(L), segments), dtype=np.int64)
        for t in range(len(L)):
            p = P[p_off[t] : p_off[t + 1]]
            beta = [L[t] * (p[2] * w * w / p[1]) ** 0.25 for w in (top, radius)]
            bending_pieces(p, beta[0], beta[1], self.bp[t])
        self.rp = np.ones(len(EA), dtype=np.int64)
        rod_pieces(EA, mbar, h, top, radius, self.rp)
        self.top, self.radius = top, radius

    def band(self, w: complex) -> tuple[np.ndarray, complex]:
        """D(w)'s band rows (complex) and the log of the members' inner pivots."""
        asm = self.asm
        B = asm.K_band + (1j * w) * self.C_band - (w * w) * asm.M_band
        log = assemble_members_c(*asm.packed, self.bp, self.rp, asm.rod_eta, self.t, complex(w), B)
        return B, log

    def lu(self, B: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """LAPACK's band LU with partial pivoting (``zgbtrf``) of D in band rows B: its
        factors and pivots (for ``zgbtrs``)."""
        n, b = self.asm.n, self.asm.bandwidth
        ab = np.zeros((3 * b + 1, n), dtype=np.complex128)
        rows, cols, src = self.asm.general_band
        ab[rows, cols] = B.ravel()[src]
        lu, piv, _ = zgbtrf(ab, b, b)
        return lu, piv

    def one(self, w: complex) -> complex:
        """log g at w (rad/s)."""
        self.calls += 1
        B, log = self.band(w)
        n, b = self.asm.n, self.asm.bandwidth
        if n == 0:
            return log
        lu, piv = self.lu(B)
        d = lu[2 * b]
        if not np.all(np.isfinite(d)):
            return complex(math.nan, math.nan)
        if np.any(d == 0):
            return complex(-math.inf, 0.0)
        swaps = int(np.count_nonzero(piv != np.arange(n)))
        return complex(np.sum(np.log(d))) + log + 1j * math.pi * swaps

    def __call__(self, ws: np.ndarray) -> np.ndarray:
        return np.array([self.one(complex(w)) for w in np.ravel(ws)], dtype=np.complex128)


def sigma_max(frame: Frame, w_top: float) -> DecayBound | None:
    """A proved upper bound on ``sigma`` of every damped root with ``|w_d| <= w_top``
    (rad/s), the beam's proof (:mod:`mstmm.decay_bound`) on the frame; None where it does
    not apply.

    The energies are sums over the members (and the lumped springs and masses), so ``m
    >= mbar_min sum ||w_e||^2`` and ``k_R >= EI_min ||w_e''||^2`` for each member e
    (Euler-Bernoulli, not compressed). An absorber's dashpot c at node N along d gives
    ``c |q - d.U_N|^2 <= 2 c |q|^2 + 2 c |d.U_N|^2``; ``d.U_N`` is bounded by the
    transverse displacements ``w_e = n_e . U_N`` of the members at N: by one member
    whose normal is d (``|d.U_N|^2 = |w_e|^2``), else by two that are not parallel
    (``d.U_N = (N^-T d) . (w_1, w_2)``, ``N`` their normals: ``s = |N^-T d|^2``). Each
    ``|w_e(N)|^2`` is the beam's interpolation over the member (its length the piece
    ``P_j``), so ``Gamma_j = 2 c s`` and the beam's bound follows. Out of the plane (a
    grillage) the dashpot moves W, every member's own w at N (s = 1). A loss factor
    multiplies every member stiffness (EI, EA or GJ, the terms declared with a loss) and
    no spring, so ``k_I <= eta_max k_R``, as the proof takes it. None where a member shears
    (Timoshenko), is compressed, or a damped node has no such members (a dashpot along
    the only member at its node: its axial motion is not bounded so)."""
    from mstmm.physics import segment as segment_terms

    shear = [t.name for t in segment_terms.of_role("shear")]
    tension = [t.name for t in segment_terms.of_role("tension")]
    for m in frame.members:
        for s in m.segments:
            values = dict(s.physics)
            if any(values.get(k, 0.0) > 0.0 for k in shear):
                return None
            if any(values.get(k, 0.0) < 0.0 for k in tension):
                return None
    segs = [s for m in frame.members for s in m.segments]
    EI = min(s.EI for s in segs)
    mbar = min(s.mass_per_length for s in segs)
    gamma = rate = reach = 0.0
    piece = max(frame.geometry(m)[0] for m in frame.members)
    for ab in frame.absorbers:
        if not ab.c:
            continue
        at = [m for m in frame.members if ab.node in (m.start, m.end)]
        best = _spread(frame, ab, at)
        if best is None:
            return None
        s, P = best
        g = 2.0 * ab.c * s
        gamma += g
        reach += g / P
        piece = min(piece, P)
        rate = max(rate, 2.0 * ab.c / ab.m)
    return bound_from(gamma, rate, reach, piece, mbar, EI, loss_factor(frame), w_top)


def _spread(frame: Frame, ab, at: list) -> tuple[float, float] | None:
    """``(s, P)``: ``|d.U_N|^2 <= s sum |w_e(N)|^2`` over the members used, P the
    shortest of them; the least s (then the longest P), None where none bounds it."""
    if not at:
        return None
    lengths = [frame.geometry(m)[0] for m in at]
    if frame.motion == "out_of_plane":
        return 1.0, max(lengths)
    d = np.asarray(ab.direction, dtype=float)
    normals = []
    for m in at:
        _, c, s = frame.geometry(m)
        normals.append(np.array([-s, c]))
    best = None
    for i, n in enumerate(normals):
        if abs(abs(float(n @ d)) - 1.0) <= 1e-12:
            best = min(best or (math.inf, 0.0), (1.0, -lengths[i]))
    for i in range(len(at)):
        for j in range(i + 1, len(at)):
            N = np.array([normals[i], normals[j]])
            if abs(np.linalg.det(N)) <= 1e-6:
                continue  # parallel members: no bound on the motion along them
            s = float(np.sum(np.linalg.solve(N.T, d) ** 2))
            best = min(best or (math.inf, 0.0), (s, -min(lengths[i], lengths[j])))
    return None if best is None else (best[0], -best[1])


def _unproved_reason() -> str:
    return (
        "no proved bound on the decay rate applies (a Timoshenko or compressed member, or"
        " a dashpot along the only member at its node: mstmm.frame.damped.sigma_max)"
    )


def damped_frame_roots(
    frame: Frame, asm: Assembly, undamped: np.ndarray, w_top: float
) -> DampedRoots:
    """Every damped root with ``w_d < w_top`` (rad/s) of ``frame`` (its assembly ``asm``),
    from the natural frequencies ``undamped`` of its undamped twin (ascending, repeated
    by multiplicity) up to beyond ``w_top``."""
    f = FrameFunction(asm, 1.0, 2.0 * w_top)
    undamped = np.asarray(undamped, dtype=float)
    viscous = loss_factor(frame) == 0.0  # else no mirror symmetry (mstmm.damped)
    problem = _Problem(
        None, None, f, None, asm.omega_ref, viscous, 0, 0, np.unique(undamped[undamped > 0])
    )

    def pick(t: float) -> FrameFunction:
        return FrameFunction(asm, t, f.top, f.radius)

    def top(roots: list[DampedRoot]) -> tuple[float, str]:
        bound = sigma_max(frame, w_top)
        S, note = sigma_top(bound, roots, w_top, asm.omega_ref, _unproved_reason())
        # the count nudges the box's edges out by up to 0.2 % of its size (a zero on one)
        f.cover(COVER * (w_top + 0.002 * max(w_top, S)), COVER * abs(complex(w_top, S)))
        return S, note

    found = search(problem, undamped, pick, w_top, top)
    found.roots[:] = [
        replace(r, omega=_polished(asm, r.omega)) if r.multiplicity == 1 else r for r in found.roots
    ]
    return found


#: :func:`polish`'s members are cut for frequencies up to this many times the root's.
POLISH_RADIUS = 1.25
#: Secant steps of :func:`polish` and the relative step that ends them.
POLISH_STEPS = 4
POLISH_DONE = 1e-15


def polish(asm: Assembly, w: complex) -> complex:
    """A simple root w of D to the accuracy of D's entries: the secant method on ``r(w) =
    x^T D(w) x``, x the null vector at w (inverse iteration). D is complex symmetric, so
    ``x^T D x / x^T x`` is stationary at its eigenvector: r's root is w's to the square of
    x's error, and r weighs D's entries by the mode, where ``det D`` weighs them all (a
    member's stiff axial terms spoil a sway mode's determinant by 1e-11 or so). A step
    that does not shrink, or moves the root further than 1e-8 of it, is not taken.

    D is evaluated with its members in as few pieces as ``|w|`` allows (the count's
    pieces, short enough for its whole rectangle, lose digits: a chain of n pieces
    cancels to about n^3 of round-off in a member's stiffness)."""
    if asm.n == 0:
        return w
    f = FrameFunction(asm, 1.0, POLISH_RADIUS * abs(w))  # a real root's neighbourhood
    x = null_vector(f, f.band(w)[0])
    if not np.all(np.isfinite(x)):
        return w

    def r(z: complex) -> complex:
        return band_quadratic(f.band(z)[0], x)

    w0, w1 = w * (1.0 + 1e-9), w
    r0, r1 = r(w0), r(w1)
    start = w
    prev = math.inf
    for _ in range(POLISH_STEPS):
        if r1 == r0:
            break
        step = -r1 * (w1 - w0) / (r1 - r0)
        if not (abs(step) < 0.5 * prev) or abs(w1 + step - start) > 1e-8 * abs(start):
            break
        w0, r0 = w1, r1
        w1 = w1 + step
        prev = abs(step)
        if prev <= POLISH_DONE * abs(w1):
            break
        r1 = r(w1)
    return complex(w1)


def _polished(asm: Assembly, w: complex) -> complex:
    """:func:`polish`, an overdamped root (w_d exactly 0) along the imaginary axis."""
    z = polish(asm, w)
    return complex(0.0, z.imag) if w.real == 0.0 else z


def complex_matrix(asm: Assembly, w: float) -> np.ndarray:
    """The damped frame's dense D at the frequency w (rad/s, dimensionless as
    :meth:`Assembly.matrix`): members with their loss factors, the dashpots' ``i w C``."""
    return _dense(asm, FrameFunction(asm, 1.0, POLISH_RADIUS * abs(w)).band(w)[0])


def null_vector(f: FrameFunction, B: np.ndarray) -> np.ndarray:
    """The unit null vector of D (band rows B, in the band order) at a simple root: three
    steps of inverse iteration on its band LU (``zgbtrs``); not finite where D is exactly
    singular to round-off."""
    b = f.asm.bandwidth
    lu, piv = f.lu(B)
    x = np.ones(f.asm.n, dtype=complex)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        for _ in range(3):
            x, _ = zgbtrs(lu, b, b, x, piv)
            x /= np.linalg.norm(x)
    return x


def band_quadratic(B: np.ndarray, x: np.ndarray) -> complex:
    """``x^T D x`` (no conjugate) of the symmetric D in upper band rows B (``B[i, k] =
    D[i, i + k]``)."""
    n = len(x)
    out = complex(np.sum(B[:, 0] * x * x))
    for k in range(1, min(B.shape[1], n)):
        out += 2.0 * complex(np.sum(B[: n - k, k] * x[: n - k] * x[k:]))
    return out


def _dense(asm: Assembly, B: np.ndarray) -> np.ndarray:
    """Complex band rows B as the dense D over the freedoms."""
    return asm.dense(B.real) + 1j * asm.dense(B.imag)


@dataclass
class DampedFrameMode:
    """A damped mode: its root (rad/s, complex), multiplicity and the joints' complex
    (X, Y, Theta) (out of the plane (W, ThetaX, ThetaY)), scaled so that the largest
    translation is 1 (real)."""

    omega: complex
    multiplicity: int
    nodes: dict[str, tuple[complex, complex, complex]]
    vector: np.ndarray
    #: Each absorber's mass displacement along its direction (m, complex).
    absorbers: tuple[complex, ...] = ()
    #: ``sigma_min(D) / sigma_max(D)`` at the root: how singular D is there.
    residual: float = 0.0

    @property
    def complexity(self) -> float:
        """``1 - |sum x^2| / sum |x|^2`` over the freedoms (SI): 0 for a real shape (every
        point in phase, as an undamped mode), towards 1 for a travelling wave."""
        x = self.vector
        power = float(np.sum(np.abs(x) ** 2))
        return 1.0 - abs(complex(np.sum(x * x))) / power if power else 0.0


@dataclass
class DampedFrameSolution(DampedValues):
    """Damped natural frequencies ``omega = w_d + i sigma`` (rad/s, complex; overdamped
    roots first by sigma, then by w_d; repeated by multiplicity), whether the argument
    principle's count confirmed them (``count_checked``), the counted rectangle, what to
    tell, and the modes."""

    frame: Frame
    omega: np.ndarray
    multiplicity: np.ndarray
    converged: np.ndarray
    count_checked: bool
    rectangle: tuple[float, float, float, float]
    warnings: list[str] = field(default_factory=list)
    modes: list[DampedFrameMode] = field(default_factory=list)
    damped: bool = True
    assembly: Assembly | None = None

    def member_fields(self, mode: int, member: str, points: int = 21) -> dict[str, np.ndarray]:
        """Along member ``member`` in damped mode ``mode``: ``x`` (m from its start) and
        ``u, w, psi, N, Q, M`` (complex, SI, local axes; scaled as the mode's joints)."""
        return member_fields(self.assembly, self.modes[mode], member, points)

    f = DampedValues.hz

    def to_dict(self) -> dict:
        """Plain data: the roots and each mode's joints (complex as [re, im])."""
        return {
            "frame": self.frame.name,
            **self.roots_dict(),
            "motion": self.frame.motion,
            "warnings": list(self.warnings),
            "modes": [
                {
                    "omega": [m.omega.real, m.omega.imag],
                    "nodes": {
                        k: [[complex(c).real, complex(c).imag] for c in v]
                        for k, v in m.nodes.items()
                    },
                    "absorbers": [[a.real, a.imag] for a in m.absorbers],
                }
                for m in self.modes
            ],
        }


def undamped_twin(frame: Frame) -> Frame:
    """The frame without its dashpots and loss factors."""
    members = tuple(
        replace(m, segments=tuple(replace(s, loss_factor=0.0) for s in m.segments))
        for m in frame.members
    )
    return replace(
        frame, members=members, absorbers=tuple(replace(a, c=0.0) for a in frame.absorbers)
    )


def is_damped(frame: Frame) -> bool:
    """Whether anything damps the frame: a dashpot, a member's loss factor."""
    return any(a.c for a in frame.absorbers) or loss_factor(frame) > 0.0


def loss_factor(frame: Frame) -> float:
    """The largest loss factor of the frame's members."""
    return max((s.loss_factor for m in frame.members for s in m.segments), default=0.0)


def solve_damped_frame(
    frame: Frame,
    modes: int | None = None,
    band: tuple[float, float] | None = None,
    *,
    shapes: bool = True,
) -> DampedFrameSolution:
    """The damped natural frequencies of ``frame``: the lowest ``modes`` by w_d
    (overdamped roots first, by sigma) or all with ``band[0] <= w_d <= band[1]``
    (rad/s); with ``shapes``, each root's modes (the null space of D)."""
    if modes is None and band is None:
        modes = 10
    asm = Assembly(frame)
    twin = Assembly(undamped_twin(frame))
    need = (modes if modes is not None else 10) + 4
    while True:
        if band is not None:
            und = roots(twin, None, (0.0, 1.5 * band[1]))
            w_top = band[1] * (1.0 + 1e-6)
            if sum(m for _, m in und) < 2:
                und = roots(twin, need, None)
        else:
            und = roots(twin, need + 3, None)
            values = [w for w, _ in und]
            w_top = 0.5 * (values[-2] + values[-1]) if len(values) >= 2 else 2.0 * values[-1]
        omega_u = np.array([w for w, m in und for _ in range(m)])
        found = damped_frame_roots(frame, asm, omega_u, w_top)
        listed = sum(r.multiplicity for r in found.roots)
        if band is not None or listed >= modes or need > 100_000:
            break
        need *= 2
    kept = found.roots
    if band is not None:
        kept = [r for r in kept if band[0] <= r.omega.real <= band[1]]
    omega, mult, conv, _, warnings = roots_table(found, kept, modes)
    sol = DampedFrameSolution(
        frame,
        np.asarray(omega, dtype=complex),
        np.asarray(mult, dtype=np.int64),
        np.asarray(conv, dtype=bool),
        found.count_checked,
        found.rectangle,
        warnings,
        assembly=asm,
    )
    if shapes:
        done: set[complex] = set()
        for w, m in zip(omega, mult):
            if w in done:
                continue
            done.add(w)
            sol.modes += _damped_shapes(asm, w, m)
        bad = [mo for mo in sol.modes if mo.residual > SHAPE_RESIDUAL]
        if bad:
            sol.warnings.append(
                f"{len(bad)} damped mode shape(s) leave a residual above {SHAPE_RESIDUAL:g}"
                f" of D's norm (largest {max(mo.residual for mo in bad):.2g}): not trusted"
            )
    return sol


#: A damped shape's relative residual ``|D x| / (|D| |x|)`` above this is said.
SHAPE_RESIDUAL = 1e-8


def _damped_shapes(asm: Assembly, w: complex, m: int) -> list[DampedFrameMode]:
    """The modes of the root w of multiplicity m, each scaled so that its largest
    translation is 1: a simple root's null vector by inverse iteration on D's band LU
    (:func:`null_vector`), a multiple root's m right singular vectors of D of least
    singular value; with the residual ``|D x| / (|D| |x|)`` of each."""
    f = FrameFunction(asm, 1.0, POLISH_RADIUS * abs(w))
    B = f.band(w)[0]
    if m == 1:
        x = np.empty(asm.n, dtype=complex)
        x[asm.perm] = null_vector(f, B)
        D = None
        vectors = [x]
    else:
        D = _dense(asm, B)
        _, _, Vh = np.linalg.svd(D)
        vectors = [Vh[-j].conj() for j in range(1, m + 1)]
    D = _dense(asm, B) if D is None else D
    norm = float(np.linalg.norm(D, 2)) if asm.n else 1.0
    out = []
    for x in vectors:
        residual = float(np.linalg.norm(D @ x) / (norm * np.linalg.norm(x))) if norm else 0.0
        xs = asm.scale * x
        trans = [g for g, fr in enumerate(asm.freedoms) if fr.translation and fr.kind == "node"]
        big = max(trans, key=lambda g: abs(xs[g])) if trans else int(np.argmax(np.abs(xs)))
        xs = xs / xs[big] if xs[big] != 0 else xs
        absorbers = tuple(complex(xs[g]) for g in asm.absorber_freedoms)
        out.append(DampedFrameMode(w, m, _joints(asm, xs), xs, absorbers, residual))
    return out

"""Mode shapes: the null space of paper Eq. (5), from the kernel's orthonormalisation march.

The paper takes the right singular vector of ``U_bar(omega_n)`` for the smallest
singular value (Eq. (5)). Built from whole-segment transfer matrices, ``U_bar``
carries ``cosh(lam l)``: its null vector, and the state carried from ``Z_1``
along the beam, lose a digit per ``pi`` of ``lam L``. The kernel's
``mode_shapes`` finds the same null space without that growth (see the comment
at the head of its mode-shape section): the states admitted from the left end
are carried through pieces with ``lam l <= 1`` and re-orthonormalised; every
attached unknown (the displacement of a hanging mass) is kept as an unknown
with its geometric equation (paper Eqs. (2)-(3)), so nothing is divided by
``B00 = 1 - m w^2 / k``: at a branch's own frequency the beam point is held and
the mass moves. The end's conditions give the null space; the shapes are walked
back by multiplications only.

A root of multiplicity ``m``, or a cluster of ``m`` roots each closer (relatively)
than :data:`CLUSTER` to the next, which no float64 computation can tell apart, gets
``m`` shapes: the ``m`` smallest right singular vectors of the end matrix (at the
cluster's centre or at one of its roots, wherever it is most singular on ``m``
directions), made orthonormal in the mass inner product
``int mbar Y_i Y_j dx + sum m Y_mi Y_mj``. Shapes are then scaled to
``max |Y| = 1`` over the beam and the masses (largest entry positive);
:meth:`ModeShape.mass_normalised` gives unit modal mass instead.

A shape is only as sharp as its root is apart from the next: known to a few ulps, the root
puts the end matrix's null vector off towards its neighbour's by about
:data:`SHAPE_NOISE` over their relative distance (a stiff foundation: roots 2e-11 apart,
shapes 2e-4 off). :func:`too_close` says so, with that estimate, for every shape whose
root lies closer than :data:`CLUSTER` to another outside its eigenspace, the nearest
roots beside the asked ones included (:func:`beside` finds them by the count).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from .kernels import Kernel

#: Sample points along the beam (uniform; the attachment points are added).
SAMPLES = 201
#: Roots whose relative distance is below this share one eigenspace for the shapes: the
#: end matrix cannot tell their null vectors apart, and a point component this close to its
#: own frequency counts as at it (the kernel's ``DEGENERATE``, same value).
CLUSTER = 1e-8
#: A cluster's shapes are not held by the end matrix when it is singular on their space
#: only to more than this of its largest singular value: distinct roots 2e-9 apart on a
#: stiff foundation, taken as one cluster, gave 1.0 (garbage shapes, modal mass 1e15 kg);
#: each is then taken at its own root, and a cluster still above it is said. Not a test of
#: every shape: the ratio depends on the end matrix's scaling (stiff springs at the right
#: end of a free beam give 0.1 on shapes exact to 1e-15).
RESOLVED = 1e-2
#: A shape taken at its own root is accurate to about SHAPE_NOISE / gap, gap the relative
#: distance of its root to the nearest root outside its eigenspace: the root is known to a
#: few ulps, and the end matrix's null vector turns towards the neighbour's by that error
#: over the gap. Measured on a stiff foundation (gaps 2e-9 to 2e-14): error times gap
#: within 2e-15 and 8e-15. Shapes of roots closer than CLUSTER are said (error > 1e-6).
SHAPE_NOISE = 1e-14
#: Relative offsets at which the count looks for a root beside the roots asked for (the
#: nearest one outside the set: its distance to within a factor sqrt(10)).
BESIDE = tuple(10.0 ** (k / 2.0) for k in range(-24, -15))


@dataclass(frozen=True)
class Shape:
    """What a mode shape of an undamped (:class:`ModeShape`) and of a damped scene
    (:class:`mstmm.damped.DampedModeShape`: complex amplitudes) both are: the beam's state
    ``Y``, ``theta``, ``M``, ``Q`` (m, rad, N m, N) sampled at ``x`` (right limits at an
    attachment: after its shear jump) and the displacement ``mass_Y`` of each carried mass
    (at ``mass_x``), at the natural frequency ``omega`` (rad/s)."""

    omega: float | complex
    x: np.ndarray
    Y: np.ndarray
    theta: np.ndarray
    M: np.ndarray
    Q: np.ndarray
    mass_x: np.ndarray
    mass_Y: np.ndarray
    #: Singular value of this shape over the largest of the end matrix (0 for a clean root).
    singular_ratio: float


@dataclass(frozen=True)
class ModeShape(Shape):
    """One mode shape: the beam's state along x and the displacement of each carried mass
    (:class:`Shape`), with its modal mass, participation and effective mass.

    The scaling is ``max |Y| = 1`` over the beam and the masses unless the shape came from
    :meth:`mass_normalised`.
    """

    omega: float
    #: ``int mbar Y^2 dx + sum m Y_m^2`` (kg m^2 for Y in m), for this scaling.
    modal_mass: float
    #: Base-translation participation factor ``(int mbar Y dx + sum m Y_m) / modal_mass``.
    participation: float
    #: ``participation^2 modal_mass`` (kg): summed over all modes, the total mass that a
    #: translation of the supports moves.
    effective_mass: float
    #: Dimension of the eigenspace (root multiplicity or cluster size) this shape belongs to.
    multiplicity: int = 1

    @property
    def hz(self) -> float:
        """Frequency in Hz."""
        return self.omega / (2.0 * math.pi)

    def scaled(self, factor: float) -> ModeShape:
        """The same shape multiplied by ``factor``."""
        f = float(factor)
        return dataclasses.replace(
            self,
            Y=self.Y * f,
            theta=self.theta * f,
            M=self.M * f,
            Q=self.Q * f,
            mass_Y=self.mass_Y * f,
            modal_mass=self.modal_mass * f * f,
            participation=self.participation / f,
        )

    def mass_normalised(self) -> ModeShape:
        """The shape scaled to unit modal mass."""
        return self.scaled(1.0 / math.sqrt(self.modal_mass))

    def to_dict(self) -> dict:
        """JSON form: ``omega`` (rad/s), ``hz``, the samples and the masses as lists, the
        numbers as Python floats (:meth:`mstmm.solve.Solution.to_dict`)."""
        return {
            "omega": float(self.omega),
            "hz": float(self.omega) / (2.0 * math.pi),
            "x": self.x.tolist(),
            "Y": self.Y.tolist(),
            "theta": self.theta.tolist(),
            "M": self.M.tolist(),
            "Q": self.Q.tolist(),
            "mass_x": self.mass_x.tolist(),
            "mass_Y": self.mass_Y.tolist(),
            "singular_ratio": float(self.singular_ratio),
            "modal_mass": float(self.modal_mass),
            "participation": float(self.participation),
            "effective_mass": float(self.effective_mass),
            "multiplicity": int(self.multiplicity),
        }


def clusters(omega: np.ndarray) -> list[tuple[int, int]]:
    """``[start, stop)`` index ranges of ``omega`` (ascending, repeated by multiplicity)
    whose consecutive relative distance is below :data:`CLUSTER`; zeros only with zeros."""
    out: list[tuple[int, int]] = []
    start = 0
    for i in range(1, len(omega) + 1):
        if i < len(omega):
            a, b = float(omega[i - 1]), float(omega[i])
            same = a == b or (a > 0.0 and b - a <= CLUSTER * b)
            if same:
                continue
        out.append((start, i))
        start = i
    return out


def sample_points(p: np.ndarray, kernel: Kernel, n_points: int = SAMPLES) -> np.ndarray:
    """Uniform samples of ``[0, L]`` plus every attachment point."""
    L = float(p[0])
    return np.unique(np.concatenate([np.linspace(0.0, L, n_points), kernel.event_positions(p)]))


def mode_shapes(
    kernel: Kernel, p: np.ndarray, omega: np.ndarray, n_points: int = SAMPLES
) -> list[ModeShape]:
    """One :class:`ModeShape` per entry of ``omega`` (rad/s, ascending, repeated by
    multiplicity; zeros included: their shapes are rigid motions)."""
    p = np.ascontiguousarray(p, dtype=np.float64)
    omega = np.asarray(omega, dtype=np.float64)
    xs = sample_points(p, kernel, n_points)
    shapes: list[ModeShape] = []
    for start, stop in clusters(omega):
        got = _cluster_shapes(kernel, p, omega[start:stop], xs)
        distinct = stop - start > 1 and np.all(np.diff(omega[start:stop]) > 0.0)
        if distinct and got[0].singular_ratio > RESOLVED:
            # distinct roots closer than CLUSTER whose joint space the end matrix does not
            # hold at one frequency (a stiff foundation: modes 2e-9 apart): each at its own
            # root, kept where the end matrix holds each and they differ (not one shape
            # found again and again)
            alone = [
                _cluster_shapes(kernel, p, omega[i : i + 1], xs)[0] for i in range(start, stop)
            ]
            if _apart(alone) and max(a.singular_ratio for a in alone) <= RESOLVED:
                got = alone
        shapes.extend(got)
    return shapes


def _apart(shapes: list[ModeShape]) -> bool:
    """Whether no two of these shapes are nearly parallel (|cos| < 1/2 between their
    [Y, mass_Y], the plain inner product)."""
    v = [np.concatenate([s.Y, s.mass_Y]) for s in shapes]
    v = [a / np.linalg.norm(a) for a in v]
    return all(abs(float(v[i] @ v[j])) < 0.5 for i in range(len(v)) for j in range(i))


def unresolved(shapes: list[ModeShape]) -> list[str]:
    """Warnings for the clusters whose space the end matrix does not hold (singular on it
    only to more than RESOLVED): their shapes are not the modes' (the frequencies stand)."""
    out = []
    for a, b in eigenspaces(shapes):
        s = shapes[a]
        if b - a > 1 and not s.singular_ratio <= RESOLVED:
            out.append(
                f"the mode shapes of the {s.multiplicity} roots from omega = {s.omega:.17g}"
                " rad/s are not resolved: the end matrix is singular on their space only to"
                f" {s.singular_ratio:.1e} of its largest singular value"
            )
    return out


def eigenspaces(shapes: list[ModeShape]) -> list[tuple[int, int]]:
    """``[start, stop)`` of each eigenspace in a list of shapes (a cluster's m shapes are
    consecutive, each with multiplicity m)."""
    out = []
    i = 0
    while i < len(shapes):
        m = max(shapes[i].multiplicity, 1)
        out.append((i, i + m))
        i += m
    return out


def too_close(
    shapes: list[ModeShape], below: float = math.nan, above: float = math.nan
) -> list[str]:
    """Warnings for the shapes whose root lies closer than :data:`CLUSTER` (relative) to
    another root outside its eigenspace: accurate to about SHAPE_NOISE / gap only (the
    frequencies stand). ``below``, ``above``: the nearest roots beside the set, if known
    (:func:`beside`), else nan."""
    spaces = eigenspaces(shapes)
    centre = [shapes[a].omega for a, _ in spaces]
    out = []
    for j, (a, b) in enumerate(spaces):
        w = centre[j]
        near = [centre[j - 1] if j > 0 else below, centre[j + 1] if j + 1 < len(spaces) else above]
        gaps = [abs(w - v) / max(w, v) for v in near if v == v and max(w, v) > 0.0]
        gap = min(gaps, default=math.inf)
        if w > 0.0 and gap < CLUSTER:
            k = int(np.argmin([abs(w - v) if v == v else math.inf for v in near]))
            what = "the mode shape" if b - a == 1 else f"the {b - a} mode shapes"
            out.append(
                f"{what} at omega = {w:.17g} rad/s: accurate to about"
                f" {min(1.0, SHAPE_NOISE / max(gap, 1e-300)):.0e} only: its root lies"
                f" {gap:.1e} (relative) from another near {near[k]:.12g} rad/s, closer than"
                " double precision separates their shapes (the frequencies stand)"
            )
    return out


def beside(count, omega: np.ndarray) -> tuple[float, float]:
    """The roots next to the lowest and the highest positive value of ``omega`` (ascending)
    within :data:`CLUSTER` outside them, located by the count to within a factor sqrt(10)
    of their distance and put at the near end of it (nan: none, or the count is not
    defined there). ``count``: omegas ->
    natural frequencies below each (Wittrick-Williams; -1 where not defined)."""
    positive = omega[omega > 0.0]
    if positive.size == 0:
        return math.nan, math.nan
    lo, hi = float(positive[0]), float(positive[-1])
    t = np.array(BESIDE)
    n = np.asarray(count(np.concatenate([lo * (1.0 - t), hi * (1.0 + t)])))
    if np.any(n < 0):
        return math.nan, math.nan
    down, up = n[: t.size], n[t.size :]
    below = above = math.nan
    fewer = np.nonzero(down < down[0])[0]
    if fewer.size:
        below = lo * (1.0 - t[fewer[0] - 1])
    more = np.nonzero(up > up[0])[0]
    if more.size:
        above = hi * (1.0 + t[more[0] - 1])
    return below, above


def _eigenspace(kernel, p, omegas, xs):
    """The kernel's ``m`` null directions for a cluster of ``m`` roots, taken where the end
    matrix is most singular on ``m`` directions: at the cluster's centre or at one of its
    roots (next to a hanging mass's own frequency the end matrix changes so fast with
    omega that 1e-12 away from a root it is no longer singular on its shape)."""
    m = len(omegas)
    trials = np.unique(np.append(omegas, np.mean(omegas))) if m > 1 else omegas[:1]
    best = None
    for w in trials:
        got = kernel.mode_shapes(float(w), p, m, xs)
        if best is None or np.max(got[6]) < np.max(best[6]):
            best = got
    return best


def _cluster_shapes(kernel, p, omegas, xs) -> list[ModeShape]:
    L, EI, mbar = float(p[0]), float(p[1]), float(p[2])
    m = len(omegas)
    Z, q, q_x, q_mass, gram, part, ratio = _eigenspace(kernel, p, omegas, xs)
    # mass-orthonormal basis of the cluster's space: C^T gram C = I (gram is m x m)
    lam, vec = np.linalg.eigh(0.5 * (gram + gram.T))
    lam = np.maximum(lam, np.finfo(float).tiny)
    C = vec / np.sqrt(lam) if m > 1 else np.array([[1.0 / math.sqrt(lam[0])]])
    Z = np.einsum("kj,knr->jnr", C, Z)
    q = C.T @ q
    part = C.T @ part
    # how singular the end matrix is on the whole space (the worst of its m directions)
    worst = float(np.max(ratio))
    units = np.array([L, 1.0, EI / L, EI / L**2])
    carried = q_mass[1] > 0.0  # the unknowns that are displacements of carried masses
    mass_x = q_x[carried]
    out = []
    for j in range(m):
        Y = Z[j, :, 0] * L
        mass_Y = q[j, carried] * L
        big = np.concatenate([Y, mass_Y])
        k = int(np.argmax(np.abs(big)))
        top = big[k] if big[k] != 0.0 else 1.0
        state = Z[j] * units / top  # divided, so that the largest entry is exactly 1
        modal = mbar * L**3 / top**2  # the basis vector has unit nondimensional modal mass
        numerator = mbar * L**2 * part[j] / top
        out.append(
            ModeShape(
                omega=float(omegas[j]),
                x=xs.copy(),
                Y=state[:, 0],
                theta=state[:, 1],
                M=state[:, 2],
                Q=state[:, 3],
                mass_x=mass_x.copy(),
                mass_Y=mass_Y / top,
                singular_ratio=worst,
                modal_mass=float(modal),
                participation=float(numerator / modal),
                effective_mass=float(numerator**2 / modal),
                multiplicity=m,
            )
        )
    return out

"""Damped natural frequencies: complex roots, found by continuation and certified by the
argument principle.

With damping (dashpots ``c``, loss factors ``eta``) the natural frequencies are the
complex zeros ``w = w_d + i sigma`` of the damped kernel's characteristic function
(``delta_damped``: the pole-free second-compound chain in complex arithmetic, entire in
``w``; time dependence ``exp(i w t)``, ``sigma > 0`` a decaying mode). The
Wittrick-Williams count no longer applies; what proves that no root is missed is the
argument principle (Delves & Lyness 1967; Kravanja & Van Barel 2000): the number of zeros
of an analytic function inside a closed contour is the winding number of its values
along the contour.

The search (:func:`damped_roots`):

1. **Start from the undamped structure.** Its roots (the certified search of the
   undamped twin's real kernel: the same scene without its dampers) are the damped
   roots at damping scale ``t = 0``.
2. **Leap, or continuation,** in ``t`` from 0 to 1 (every damping value of the parameter
   vector scaled by ``t``): every simple undamped root at once to a small ``t``, then
   extrapolated linearly to ``t = 1`` and polished there (:func:`_leap`); where the
   polish is not trusted, or two roots arrive at one, followed by Newton's method in
   steps that halve when Newton does not settle (:func:`_continue`; Newton's method is
   the secant method on log f, :mod:`mstmm.secant`).
3. **Count** the zeros in the rectangle ``[-eps, W] x [-delta, S]`` of the ``w`` plane
   (``w_d`` up to the band's top ``W``, ``sigma`` up to ``S``, the origin inside) by the
   winding number, sampled adaptively until no step of the phase exceeds ``pi/4``
   (:mod:`mstmm.contour`); the zero at ``w = 0`` has the known order ``2 n_rigid - r``
   (``r`` the rigid motions the grounded dashpots restrain).
4. **Search what the count says is left**: rectangles whose count exceeds the roots
   known in them are split and searched (Newton from their centres) until every count is
   matched; a rectangle that still holds ``m`` zeros when it is as small as round-off
   allows is a root of multiplicity ``m`` (:mod:`mstmm.subdivision`).

The result says whether the count confirmed every root (``count_checked``); roots with
``sigma > S`` are not counted (``S`` is reported: a multiple of the largest decay rate
the dampers can give and of any root found). Overdamped roots (``w_d = 0``) are reported
with ``w_d`` exactly 0 when the damping is viscous only (the function is then real on the
imaginary axis, up to a constant, and its axis roots are exactly on it).
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass, field

import numpy as np

from mstmm import catalog

from . import contour, subdivision
from .decay_bound import sigma_max
from .frames import Tabulated
from .kernels import Kernel
from .modes import Shape
from .secant import NEWTON_TOL, newton, newton_many
from .undamped import solve_undamped

#: With a loss factor, a root at w_d < -AXIS_TOL |w| lies left of the imaginary axis beyond
#: its accuracy (Newton's 4e-16, the cluster discs' 1e-7 |w| at worst): the loss factor's
#: model holds for w_d > 0 only, and such a root is left out and said (the slow root of
#: an overdamped pair on a beam with a loss factor: one of the pair moves right of the
#: axis, the other left). Within it, a root counts as on the axis and is kept.
AXIS_TOL = 1e-9
#: Steps of the damping scale t in the continuation (halved on failure).
CONTINUATION_STEPS = 8
#: Scenes with this many components evaluate batches of at least PARALLEL_BATCH points
#: on every core (below, starting the threads costs more than it saves).
PARALLEL_EVENTS = 64
PARALLEL_BATCH = 4


@dataclass(frozen=True)
class DampedRoot:
    """A damped natural frequency ``omega = w_d + i sigma`` (rad/s) and its multiplicity."""

    omega: complex
    multiplicity: int = 1
    converged: bool = True
    how: str = "continuation"  # rigid | continuation | search | count

    @property
    def w_d(self) -> float:
        """Damped frequency (rad/s): the real part."""
        return self.omega.real

    @property
    def sigma(self) -> float:
        """Decay rate (1/s): the imaginary part (exp(i w t) = exp(i w_d t) exp(-sigma t))."""
        return self.omega.imag

    @property
    def magnitude(self) -> float:
        """|w| (rad/s): the undamped frequency of an equivalent single degree of freedom."""
        return abs(self.omega)

    @property
    def zeta(self) -> float:
        """Damping ratio sigma / |w| (1 for an overdamped root, 0 at w = 0)."""
        return self.sigma / abs(self.omega) if self.omega != 0 else 0.0


@dataclass
class DampedRoots:
    """The damped roots of a search, whether the count confirmed them, what to tell."""

    roots: list[DampedRoot]
    count_checked: bool
    notes: list[str] = field(default_factory=list)
    #: The rectangle counted: (w_d from, w_d to, sigma from, sigma to), rad/s.
    rectangle: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)


class _Function:
    """log f(w) of the damped kernel at one parameter vector: ``log|f| + i arg f`` with the
    phase taken from f's value (mod 2 pi), so any branch of the kernel's scaling is fine."""

    def __init__(self, kernel: Kernel, p: np.ndarray):
        module = kernel.module
        self.evaluate = module.evaluate_damped
        # the parallel twin where a batch of PARALLEL_BATCH points outweighs the threads
        parallel = getattr(module, "evaluate_damped_parallel", None)
        self.parallel = parallel if int(p[4]) >= PARALLEL_EVENTS else None
        self.delta = module.delta_damped
        self.p = np.ascontiguousarray(p, dtype=np.float64)
        self.calls = 0

    def __call__(self, ws: np.ndarray) -> np.ndarray:
        ws = np.ascontiguousarray(ws, dtype=np.complex128)
        mant = np.empty_like(ws)
        logs = np.empty_like(ws)
        if self.parallel is not None and ws.size >= PARALLEL_BATCH:
            self.parallel(ws, self.p, mant, logs)
        else:
            self.evaluate(ws, self.p, mant, logs)
        self.calls += ws.size
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            out = np.log(np.abs(mant)) + logs.real + 1j * (np.angle(mant) + logs.imag)
        # beyond what the scaling holds (an overflow): no value, never a zero
        out[~(np.isfinite(mant) & np.isfinite(logs))] = complex(math.nan, math.nan)
        return out

    def one(self, w: complex) -> complex:
        m, g = self.delta(complex(w), self.p)
        self.calls += 1
        if m == 0:
            return complex(-math.inf, 0.0)
        m = complex(m)
        if not (cmath.isfinite(m) and cmath.isfinite(g)):
            return complex(math.nan, math.nan)  # beyond what the scaling holds: no value
        return complex(math.log(abs(m)) + g.real, cmath.phase(m) + g.imag)


def damping_scaled(p: np.ndarray, columns: np.ndarray, t: float) -> np.ndarray:
    """The parameter vector with every damping value scaled by t."""
    q = np.array(p, dtype=np.float64)
    q[columns] *= t
    return q


@dataclass
class _Problem:
    """One damped search: the kernel, its function at full damping, the scales."""

    kernel: Kernel
    p: np.ndarray
    f: _Function
    columns: np.ndarray
    unit: float  # the frequency unit sqrt(EI / mbar) / L^2 (rad/s)
    viscous: bool  # no loss factor: f(-conj w) = conj f(w), axis roots exactly on the axis
    order0: int  # order of the zero at w = 0
    rigid: int  # rigid-body modes (zero frequencies reported)
    #: The undamped roots (rad/s): bottom-edge samples of the count.
    nodes: np.ndarray = field(default_factory=lambda: np.zeros(0))
    roots: list[DampedRoot] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)

    def inside(self, w: complex, box) -> bool:
        x0, x1, y0, y1 = box
        return x0 < w.real < x1 and y0 < w.imag < y1

    def known(self, box) -> int:
        """Zeros of f already known in the box: the origin's, the roots, and (viscous) the
        mirror images of roots just right of the imaginary axis."""
        n = self.order0 if self.inside(0j, box) else 0
        for r in self.roots:
            if r.omega == 0:
                continue
            if self.inside(r.omega, box):
                n += r.multiplicity
            mirror = complex(-r.omega.real, r.omega.imag)
            if self.viscous and r.omega.real > 0 and self.inside(mirror, box):
                n += r.multiplicity
        return n

    def add(self, w: complex, multiplicity: int, how: str, converged: bool = True) -> bool:
        """Add a root unless it is one already known, or the zero at the origin (whose
        order is known). A root close to a known one, to its own mirror image (viscous:
        near the imaginary axis), said to be multiple or of unknown multiplicity (0) is
        resolved first by :func:`mstmm.contour.cluster`: the zeros in a disc around it, each to full
        accuracy (a defective multiple root, critical damping, as one root of its
        multiplicity; its count is the multiplicity of a root of unknown multiplicity).
        Returns whether anything new was added."""
        if self.order0 and abs(w) <= 1e-9 * self.unit:
            return False
        w = self.snap(w)
        tiny = max(abs(w), 1e-6 * self.unit)
        near = [r for r in self.roots if abs(r.omega - w) <= 1e-6 * tiny]
        mirrored = self.viscous and 0.0 < w.real <= 1e-6 * tiny
        if not (near or mirrored or multiplicity != 1):
            self.roots.append(DampedRoot(w, multiplicity, converged, how))
            return True
        centre = complex(0.0, w.imag) if mirrored else w
        spread = max([abs(r.omega - centre) for r in near] + [abs(w - centre)])
        found = contour.cluster(self.f, centre, max(4.0 * spread, 1e-7 * tiny), self.unit)
        if found is None and multiplicity == 0:  # unknown: a small square's count says
            multiplicity = contour.multiplicity(self.f, w, self.unit)
            if multiplicity == 0:
                return False
        if found is None:  # the disc could not be resolved: keep what Newton gave
            if near:
                return False
            self.roots.append(DampedRoot(w, multiplicity, converged, how))
            return True
        before = [(r.omega, r.multiplicity) for r in near]
        for r in near:
            self.roots.remove(r)
        added = False
        for z, m in found:
            z = self.snap(z)
            if self.order0 and abs(z) <= 1e-9 * self.unit:
                continue
            if self.viscous and z.real < 0.0:
                continue  # the mirror image of a root kept on the right
            self.roots.append(DampedRoot(z, m, converged, how))
            # new unless it is one of those it replaces (moved by round-off only)
            added |= not any(mb == m and abs(b - z) <= 1e-9 * tiny for b, mb in before)
        return added

    def snap(self, w: complex) -> complex:
        """A viscous scene's root: exactly on the imaginary axis when round-off away from
        it (overdamped), else the one right of the axis (roots come in mirror pairs)."""
        if self.viscous and abs(w.real) <= 1e-9 * abs(w):
            return complex(0.0, w.imag)
        if self.viscous and w.real < 0:
            return complex(-w.real, w.imag)
        return w


#: The tallest rectangle counted, in beam modes: its height is at most the frequency of
#: the beam's mode of this number (its edges then turn the phase about as many times).
TALLEST = 1.0e4


def sigma_top(
    bound, roots: list[DampedRoot], w_top: float, unit: float, unproved: str
) -> tuple[float, str]:
    """Top of the counted rectangle: ``bound``, the proved bound on the decay rate of every
    root with ``w_d <= w_top`` (a :class:`mstmm.decay_bound.DecayBound`, None where the
    proof does not apply), and what to tell when it is not proved (""): where the proof
    does not apply (``unproved``: why), several times the largest decay rate found; where
    the bound exceeds what can be counted (the frequency of the ``TALLEST``-th mode of a
    beam of the frequency unit ``unit``), that height."""
    found = max([abs(r.sigma) for r in roots] + [0.1 * w_top])
    if bound is None:
        top = 4.0 * found
        return top, f"{unproved}: roots with sigma > {top:.6g} rad/s are not counted"
    cap = max(unit * (TALLEST * math.pi) ** 2, 4.0 * found)
    if not bound.sigma <= cap:
        top = 4.0 * found  # what can be searched reliably: several times the rates found
        return top, (
            f"the proved bound on the decay rate ({bound.sigma:.6g} rad/s) is beyond what"
            f" can be counted: roots with sigma > {top:.6g} rad/s are not counted"
        )
    return max(bound.sigma, 1.01 * found), ""


#: Why a beam's decay rate has no proved bound (:func:`mstmm.decay_bound.sigma_max`).
UNPROVED = (
    "no proved bound on the decay rate applies (a rotational damper, a damper on a massless"
    " coordinate, a segment in compression, or a point damper on a Timoshenko segment:"
    " mstmm.decay_bound)"
)


def _continue(
    problem: _Problem, w0: float, pick, steps: int = CONTINUATION_STEPS
) -> tuple[complex, bool]:
    """Follow the root w0 of the undamped structure (damping scale 0) to full damping in
    ``steps`` steps of the damping scale t (halved where Newton does not settle). Each
    step starts from the root extrapolated along the path so far (a secant predictor: on
    a path that bends slowly it lands within a fraction of the step, and does not stray
    onto a neighbour's path), is polished to 1e-9 only (the last one to round-off), and is
    refused when Newton lands much further from the prediction than the root moved so
    far."""
    w = w_prev = complex(w0)
    t = t_prev = 0.0
    dt = 1.0 / steps
    while t < 1.0:
        t_new = min(1.0, t + dt)
        last = t_new == 1.0
        f = problem.f if last else pick(t_new)
        guess = w if t == t_prev else w + (w - w_prev) * ((t_new - t) / (t - t_prev))
        w_new, ok = newton(f, guess, scale=problem.unit, tol=NEWTON_TOL if last else 1e-9)
        # a step that jumps further than the root moved so far is not trusted
        if ok and abs(w_new - guess) <= 0.25 * abs(w0) + 10.0 * abs(w - w0):
            w_prev, t_prev = w, t
            w, t = w_new, t_new
            dt = min(2.0 * dt, 1.0 / steps)
        else:
            dt *= 0.5
            if dt < 1e-4:
                return w, False
    return w, True


#: The damping scale of a leap's first step (:func:`_leap`).
LEAP_T = 1.0 / 64.0


def _leap(problem: _Problem, w0s: np.ndarray, pick) -> tuple[np.ndarray, np.ndarray]:
    """The roots w0s of the undamped structure carried to full damping in one leap: each
    root at the small damping scale ``LEAP_T`` (Newton from w0: it moves a fraction of
    what it moves in all), extrapolated linearly to t = 1 and polished there; all at once
    (:func:`mstmm.secant.newton_many`). A first-order prediction of each path; refused (not
    ok) where the polish moves the root more than half as far as the prediction did (the
    path bends, or Newton went to a neighbour): the continuation in steps then follows it.
    Returns (roots, ok)."""
    w0s = np.asarray(w0s, dtype=np.complex128)
    small = pick(LEAP_T)
    w_t, ok_t = newton_many(small, w0s, scale=problem.unit, tol=1e-10)
    guess = w0s + (w_t - w0s) / LEAP_T
    w, ok = newton_many(problem.f, guess, scale=problem.unit)
    ok &= ok_t & (np.abs(w - guess) <= 0.5 * np.abs(guess - w0s) + 1e-9 * np.abs(w0s))
    return w, ok


def _follow(problem: _Problem, todo: list[tuple[float, int]], pick) -> None:
    """Carry each undamped root ``(w0, steps)`` of ``todo`` to full damping and add where
    it arrives: by a leap (``steps = 0``, :func:`_leap`) or a continuation in ``steps``
    steps. A leap that is refused is continued instead. Two paths that arrive at one root
    means one strayed onto its neighbour's (close roots, damping that moves them further
    than they are apart): both are followed again in eight times finer steps (a leap's in
    ``CONTINUATION_STEPS``), down to 1/512 of the damping scale (what is still lost then
    is left to the count)."""
    start: dict[complex, tuple[float, int]] = {}  # each root continued: its w0 and steps
    first = [w0 for w0, steps in todo if steps == 0]
    leaps = dict(zip(first, zip(*_leap(problem, first, pick)))) if first else {}
    while todo:
        w0, steps = todo.pop(0)
        if steps == 0:
            w, ok = leaps[w0]
            if not ok:
                todo.append((w0, CONTINUATION_STEPS))
                continue
            w = complex(w)
        else:
            w, ok = _continue(problem, w0, pick, steps)
            if not ok:
                continue
        if problem.add(w, 1, "continuation"):
            start[problem.roots[-1].omega] = (w0, steps)
            continue
        near = (w, complex(-w.real, w.imag))
        other = next(
            (r for r in problem.roots for v in near if abs(r.omega - v) <= 1e-9 * abs(w)),
            None,
        )
        key = next(
            (v for v in start if other is not None and abs(v - other.omega) <= 1e-9 * abs(w)),
            None,
        )
        if key is None or steps >= 64 * CONTINUATION_STEPS:
            continue
        w1, steps1 = start.pop(key)
        problem.roots.remove(other)
        finer = max(steps1, steps) * 8 or CONTINUATION_STEPS
        todo += [(w1, finer), (w0, steps * 8 or CONTINUATION_STEPS)]


def _order_key(r: DampedRoot) -> tuple:
    """Roots on the imaginary axis (to ``AXIS_TOL``: overdamped) first, by decay rate;
    then by w_d."""
    w = r.omega
    if abs(w.real) <= AXIS_TOL * abs(w):
        return (0, 0.0, w.imag)
    return (1, w.real, w.imag)


def _axis_roots(problem: _Problem, sigma_lo: float, sigma_hi: float) -> None:
    """The overdamped roots of a viscous scene: f(-conj w) = conj f(w), so on the
    imaginary axis f is real up to a constant phase, and each root of odd multiplicity
    there is a sign change. The axis is sampled (geometric and uniform nodes), each
    change bisected to round-off (an even multiplicity, critical damping, shows no
    change: the count finds it)."""
    f = problem.f
    sig = np.unique(
        np.concatenate(
            [np.geomspace(sigma_lo, sigma_hi, 400), np.linspace(sigma_lo, sigma_hi, 400)]
        )
    )
    g = f(1j * sig)
    ok = np.isfinite(g.real)
    sig, g = sig[ok], g[ok]
    if sig.size < 2:
        return
    ref = g.imag[0]
    side = np.cos(g.imag - ref) > 0.0
    for i in np.flatnonzero(side[1:] != side[:-1]):
        a, b = sig[i], sig[i + 1]
        sa = side[i]
        while b - a > 4e-16 * b:
            m = 0.5 * (a + b)
            gm = f.one(1j * m)
            if not math.isfinite(gm.real):
                a = b = m
                break
            if (math.cos(gm.imag - ref) > 0.0) == sa:
                a = m
            else:
                b = m
        problem.add(complex(0.0, 0.5 * (a + b)), 1, "search")


def damped_roots(
    scene,
    kernel: Kernel,
    p: np.ndarray,
    undamped: np.ndarray,
    w_top: float,
) -> DampedRoots:
    """Every damped root with ``w_d < w_top`` (rad/s) of a damped ``scene``.

    ``kernel``, ``p``: the damped kernel and parameter vector; ``undamped``: the natural
    frequencies of its undamped twin (rad/s, ascending, repeated by multiplicity, zeros
    for rigid-body modes) up to beyond ``w_top``: the continuation starts from them."""
    m = kernel.module
    p = np.ascontiguousarray(p, dtype=np.float64)
    columns = catalog.damping_columns(p, m.KINDS)
    unit = math.sqrt(p[1] / p[2]) / (p[0] * p[0])
    segs = scene.beam.segments or (scene.beam,)
    viscous = all(getattr(s, "loss_factor", 0.0) == 0.0 for s in segs)
    rigid = int(m.rigid_motions(p, False))
    restrained = rigid - int(m.rigid_motions(p, True))
    elastic = np.asarray([w for w in undamped if w > 0.0])
    problem = _Problem(
        kernel,
        p,
        _Function(kernel, p),
        columns,
        unit,
        viscous,
        2 * rigid - restrained,
        rigid,
        np.unique(elastic),
    )

    def pick(t: float) -> _Function:
        return _Function(kernel, damping_scaled(p, columns, t))

    def top(roots: list[DampedRoot]) -> tuple[float, str]:
        return sigma_top(sigma_max(scene, w_top), roots, w_top, unit, UNPROVED)

    return search(problem, undamped, pick, w_top, top)


def search(problem: _Problem, undamped: np.ndarray, pick, w_top: float, top) -> DampedRoots:
    """Steps 2 to 4 of the module's search on ``problem`` (a beam's or a frame's,
    :mod:`mstmm.frame.damped`): the simple roots of ``undamped`` (rad/s, ascending,
    repeated by multiplicity) carried to full damping (``pick(t)``: log f at damping
    scale t), the rectangle ``w_d < w_top``, ``sigma < S`` counted (``top(roots)``: ``(S,
    why it is not proved or "")``, called once the continuation is done) and what the
    count says is left searched."""
    unit = problem.unit
    viscous = problem.viscous
    rigid = problem.rigid
    elastic = np.asarray([w for w in undamped if w > 0.0])
    values, counts = np.unique(elastic, return_counts=True)
    todo = [
        (float(w0), 0)
        for w0, c in zip(values, counts)
        if c == 1 and w0 <= 1.5 * w_top  # a multiple root splits: the count finds its pieces
    ]
    _follow(problem, todo, pick)
    scale = min([unit, *values[:1]])
    # the origin (a zero of order order0) this far inside the left and bottom edges
    eps = delta = 1e-3 * scale
    if viscous:
        # the zeros are mirror pairs (w, -conj w), the mirrors known: the left edge well
        # left of the imaginary axis, where the overdamped roots lie (one so close to the
        # contour would need samples as close), and the bottom as far below the origin's
        # zero (a passive structure has no zero with sigma < 0)
        eps = delta = 0.25 * scale
    s_top, unproved = top(problem.roots)
    proved = not unproved
    if unproved:
        problem.notes.append(unproved)
    box = (-eps, w_top, -delta, s_top)
    count = subdivision.count_box(problem, box)
    checked = count is not None and proved
    if count is not None:
        if viscous and problem.known(box) < count:
            _axis_roots(problem, 1e-9 * scale, s_top)
        subdivision.fill(problem, box, count)
        found = problem.known(box)
        if found != count:
            checked = False
            problem.notes.append(
                f"the argument principle counts {count} zeros in w_d < {w_top:.6g},"
                f" sigma < {s_top:.6g} rad/s (the origin's {problem.order0} included);"
                f" {found} found"
            )
    # the box reaches eps left of the imaginary axis (its contour clear of the origin's
    # zero); with a loss factor, a zero there at w_d < 0 beyond its accuracy is one of
    # those left out below, as far left as any (viscous: roots are snapped onto the axis)
    w_left = [-eps if viscous else -AXIS_TOL * abs(r.omega) for r in problem.roots]
    inside = [
        r
        for r, x0 in zip(problem.roots, w_left)
        if x0 < r.omega.real < w_top and -delta < r.omega.imag < s_top
    ]
    left = [
        r
        for r, x0 in zip(problem.roots, w_left)
        if r.omega.real <= x0 and -delta < r.omega.imag < s_top
    ]
    if left:  # a loss factor's model: no mirror symmetry, a continuation may cross w_d = 0
        problem.notes.append(
            f"{len(left)} zero(s) of the characteristic function lie at w_d < 0 ("
            + ", ".join(f"{r.omega.real:.6g}{r.omega.imag:+.6g}i" for r in left)
            + " rad/s), left out: the loss factor's EI (1 + i eta) is a model of w_d > 0"
            " only (a heavily damped pair near the imaginary axis)"
        )
    out = [DampedRoot(0j, rigid, True, "rigid")] if rigid else []
    out += sorted(inside, key=_order_key)
    return DampedRoots(out, checked, problem.notes, box)


def undamped_twin(scene):
    """The same structure without damping: the kinds that only damp (dashpots) left out,
    every damping value (``Key.damping``) and loss factor dropped. Its natural frequencies
    are the damped roots at damping scale 0, where the continuation starts.

    Built from the validated scene without validating again (dropping damping keeps a
    scene valid: no rule of a scene depends on a damping value) and kept on the scene
    (a scene is immutable), so a repeated solve does not build it twice."""
    import dataclasses

    twin = scene.__dict__.get("_undamped_twin") if hasattr(scene, "__dict__") else None
    if twin is not None:
        return twin
    beam = scene.beam
    beam = dataclasses.replace(
        beam,
        loss_factor=0.0,
        segments=tuple(dataclasses.replace(s, loss_factor=0.0) for s in beam.segments),
    )
    atts = []
    for a in scene.attachments:
        if catalog.damping_only(a.kind):
            continue
        damping = {key.name for key in catalog.kind(a.kind).KEYS[1:] if key.damping}
        values = tuple((k, v) for k, v in a.values if k not in damping)
        atts.append(dataclasses.replace(a, values=values))
    twin = dataclasses.replace(scene, beam=beam, attachments=tuple(atts))
    if hasattr(scene, "__dict__"):
        object.__setattr__(scene, "_undamped_twin", twin)
    return twin


class DampedValues:
    """What a damped solution's roots ``omega`` (complex, rad/s) give: a beam's
    (:class:`DampedSolution`) or a frame's (:class:`mstmm.frame.damped.DampedFrameSolution`)."""

    omega: np.ndarray

    @property
    def w_d(self) -> np.ndarray:
        """Damped frequencies (rad/s)."""
        return self.omega.real

    @property
    def sigma(self) -> np.ndarray:
        """Decay rates (1/s)."""
        return self.omega.imag

    @property
    def magnitude(self) -> np.ndarray:
        """|omega| (rad/s)."""
        return np.abs(self.omega)

    @property
    def zeta(self) -> np.ndarray:
        """Damping ratios sigma / |omega| (0 at a rigid-body zero)."""
        mag = np.abs(self.omega)
        return np.divide(self.omega.imag, mag, out=np.zeros_like(mag), where=mag > 0)

    @property
    def hz(self) -> np.ndarray:
        """Damped frequencies in Hz (w_d / 2 pi)."""
        return self.omega.real / (2.0 * math.pi)

    def roots_dict(self) -> dict:
        """The roots as ``--format json`` writes them (with ``multiplicity``,
        ``converged``, ``count_checked`` and the counted ``rectangle``)."""
        return {
            "damped": True,
            "w_d": self.w_d.tolist(),
            "sigma": self.sigma.tolist(),
            "abs_omega": self.magnitude.tolist(),
            "zeta": self.zeta.tolist(),
            "hz": self.hz.tolist(),
            "multiplicity": self.multiplicity.tolist(),
            "converged": self.converged.tolist(),
            "count_checked": bool(self.count_checked),
            "counted_rectangle": {
                "w_d": [self.rectangle[0], self.rectangle[1]],
                "sigma": [self.rectangle[2], self.rectangle[3]],
            },
        }


@dataclass(repr=False)
class DampedSolution(DampedValues, Tabulated):
    """Damped natural frequencies ``omega = w_d + i sigma`` (rad/s, complex; time
    dependence exp(i w t), sigma > 0 decays), ascending in w_d with overdamped roots
    (w_d = 0) first by sigma and rigid-body zeros first of all, repeated by multiplicity."""

    scene: object
    omega: np.ndarray
    multiplicity: np.ndarray
    converged: np.ndarray
    kernel_origin: str
    timings: dict
    count_checked: bool
    #: The rectangle of the w plane whose zeros were counted (w_d, w_d, sigma, sigma).
    rectangle: tuple[float, float, float, float]
    warnings: list[str] = field(default_factory=list)
    truncated: bool = False
    shapes: list | None = None
    formulation: str = "stable"
    damped: bool = True
    #: A compressed scene's stability (:mod:`mstmm.buckling`, from its undamped twin: the
    #: damping does not change the statics); when buckled, ``omega`` is empty.
    buckling: object = None

    def to_dict(self, shapes: bool = False) -> dict:
        """What ``mstmm solve --format json`` writes for a damped scene."""
        out = {
            "scene": self.scene.name,
            "formulation": self.formulation,
            **self.roots_dict(),
            "truncated": bool(self.truncated),
            "kernel": self.kernel_origin,
            "timings": dict(self.timings),
            "warnings": list(self.warnings),
        }
        return self.buckling_and_shapes(out, shapes)


def roots_table(found: DampedRoots, roots: list[DampedRoot], modes: int | None) -> tuple:
    """``(omega, multiplicity, converged, truncated, warnings)``: ``roots`` (of ``found``)
    one entry per multiplicity, the lowest ``modes`` (``truncated``: a multiple root cut
    there), and what to tell: the search's notes, a count that disagrees, a root not
    converged."""
    omega, mult, conv = [], [], []
    for r in roots:
        omega += [r.omega] * r.multiplicity
        mult += [r.multiplicity] * r.multiplicity
        conv += [r.converged] * r.multiplicity
    truncated = False
    if modes is not None and len(omega) > modes:
        truncated = mult[modes - 1] > 1 and omega[modes] == omega[modes - 1]
        omega, mult, conv = omega[:modes], mult[:modes], conv[:modes]
    warnings = list(found.notes)
    unproved = any(n.startswith("no proved bound on the decay rate") for n in found.notes)
    if not found.count_checked and not unproved:
        warnings.append(
            "the damped roots disagree with the argument-principle count: some may be missing"
        )
    warnings += [
        f"omega = {w:.17g} rad/s: not converged; this value is not trusted"
        for w, c in zip(omega, conv)
        if not c
    ]
    return omega, mult, conv, truncated, warnings


def solve_damped(scene, modes: int | None = None, band=None, *, shapes: bool = True, kernel=None):
    """The damped natural frequencies of a damped ``scene``: the lowest ``modes`` by w_d
    (rigid-body zeros, then overdamped roots by sigma, first), or every one with
    ``band[0] <= w_d <= band[1]`` (rad/s). See :func:`damped_roots`. ``kernel``: the
    damped kernel of the scene's kinds (a parameter study passes it: a point whose
    damping values are all 0 is solved in it too)."""
    import time

    from . import compiling
    from .kernels import load_kernel
    from .topology import parameter_vector, topology_of

    if modes is None and band is None:
        modes = 10
    # the drivers a damped solve calls, if a machine's first run compiles them (helpers)
    compiling.register(("lowest", "damped_shapes") if shapes else ("lowest",))
    timings: dict[str, float] = {}
    t0 = time.perf_counter()
    if kernel is None:
        kernel = load_kernel(topology_of(scene))
    twin = undamped_twin(scene)
    twin_kernel = load_kernel(topology_of(twin))
    p = parameter_vector(scene)
    timings["load"] = time.perf_counter() - t0
    t1 = time.perf_counter()
    need = (modes if modes is not None else 10) + 4
    while True:
        if band is not None:
            und = solve_undamped(twin, band=(0.0, 1.5 * band[1]), shapes=False, kernel=twin_kernel)
            if und.omega.size < need:
                und = solve_undamped(
                    twin, modes=max(need, und.omega.size + 4), shapes=False, kernel=twin_kernel
                )
            w_top = band[1] * (1.0 + 1e-6)
        else:
            und = solve_undamped(twin, modes=need + 3, shapes=False, kernel=twin_kernel)
            if und.buckling is not None and und.buckling.buckled:
                break
            elastic = und.omega[und.omega > 0]
            w_top = 0.5 * (elastic[-2] + elastic[-1]) if elastic.size >= 2 else None
            if w_top is None:
                w_top = 2.0 * float(und.omega.max() or 1.0)
        if und.buckling is not None and und.buckling.buckled:
            break
        found = damped_roots(scene, kernel, p, und.omega, w_top)
        listed = sum(r.multiplicity for r in found.roots)
        if band is not None or listed >= modes or need > 100_000:
            break
        need *= 2
    if und.buckling is not None and und.buckling.buckled:
        empty = np.zeros(0)
        return DampedSolution(
            scene,
            empty.astype(complex),
            empty.astype(int),
            empty.astype(bool),
            kernel.origin,
            timings,
            False,
            (0.0, 0.0, 0.0, 0.0),
            [und.buckling.message()],
            shapes=[] if shapes else None,
            buckling=und.buckling,
        )
    roots = found.roots
    if band is not None:
        lo, hi = band
        roots = [r for r in roots if lo <= r.omega.real <= hi or (lo <= 0.0 and r.omega == 0)]
    timings["scan_refine"] = time.perf_counter() - t1
    omega, mult, conv, truncated, warnings = roots_table(found, roots, modes)
    omega_arr = np.asarray(omega, dtype=complex)
    shape_list = None
    if shapes:
        t2 = time.perf_counter()
        shape_list = damped_shapes(kernel, p, omega_arr, mult)
        warnings = warnings + unresolved_damped(shape_list)
        timings["shapes"] = time.perf_counter() - t2
    sol = DampedSolution(
        scene,
        omega_arr,
        np.asarray(mult, dtype=int),
        np.asarray(conv, dtype=bool),
        kernel.origin,
        timings,
        found.count_checked,
        found.rectangle,
        warnings,
        truncated,
        shape_list,
    )
    return sol


@dataclass(frozen=True)
class DampedModeShape(Shape):
    """A complex mode shape at a damped natural frequency ``omega`` (rad/s): the states
    along the beam and the displacement of every hanging mass (:class:`mstmm.modes.Shape`),
    complex amplitudes of ``exp(i omega t)`` (the physical motion is their real part),
    scaled so that the largest |Y| over the beam and the masses is 1 and real positive."""

    omega: complex
    multiplicity: int = 1

    def to_dict(self) -> dict:
        """JSON form: every complex array as ``*_re`` and ``*_im``."""
        out: dict = {
            "w_d": self.omega.real,
            "sigma": self.omega.imag,
            "x": self.x.tolist(),
            "mass_x": self.mass_x.tolist(),
            "singular_ratio": self.singular_ratio,
            "multiplicity": self.multiplicity,
        }
        for name in ("Y", "theta", "M", "Q", "mass_Y"):
            values = getattr(self, name)
            out[f"{name}_re"] = values.real.tolist()
            out[f"{name}_im"] = values.imag.tolist()
        return out


def unresolved_damped(shapes: list) -> list[str]:
    """Warnings for the multiple roots whose shapes the march does not resolve: a shape past
    the ones it found (NaN), or m shapes that do not span m dimensions (relative singular
    value below 1e-6 of the stacked [Y, mass_Y]). The frequencies stand."""
    from .modes import eigenspaces

    out = []
    for a, b in eigenspaces(shapes):
        if b - a < 2:
            continue
        V = np.array([np.concatenate([s.Y, s.mass_Y]) for s in shapes[a:b]])
        ok = bool(np.all(np.isfinite(V)))
        if ok:
            V = V / np.linalg.norm(V, axis=1, keepdims=True)
            sv = np.linalg.svd(V, compute_uv=False)
            ok = bool(sv[-1] > 1e-6 * sv[0])
        if not ok:
            out.append(
                f"the mode shapes of the root omega = {shapes[a].omega:.17g} rad/s of"
                f" multiplicity {b - a} are not resolved: fewer than {b - a} independent"
                " shapes were found (the frequency stands)"
            )
    return out


def damped_shapes(kernel: Kernel, p: np.ndarray, omega: np.ndarray, multiplicity) -> list:
    """One :class:`DampedModeShape` per entry of ``omega``: a root of multiplicity m gets m
    shapes, the modes the march finds localised first (identical absorbers at one point:
    their differences, the beam at rest), then the end's singular directions (two at
    most; a shape beyond them is NaN, singular ratio inf: :func:`unresolved_damped`). The march
    of the frequency response without its load (``frf_march``, ``FRF_NULL``): the state
    at every sample and every hanging mass's displacement carried forward, the end's null
    vector applied at x = L. A rigid-body zero gets the rigid motion the ends allow."""
    from .modes import sample_points

    p = np.ascontiguousarray(p, dtype=np.float64)
    L, EI = float(p[0]), float(p[1])
    xs = sample_points(p, kernel)
    masses = [(i, x) for i, (x, mass, _) in enumerate(kernel.unknowns(p)) if mass > 0.0]
    rows = []
    for x in xs:
        rows += [[0, x, -1, L], [1, x, -1, 1.0], [3, x, -1, EI / L], [4, x, -1, EI / L**2]]
    rows += [[2, 0.0, q, L] for q, _ in masses]
    outputs = np.asarray(rows, dtype=np.float64)
    shapes = kernel.compiled("damped_shapes")
    ends = kernel.shape_ends(p)
    n = xs.size
    out_shapes = []
    k = 0
    while k < len(omega):
        w = complex(omega[k])
        m = int(multiplicity[k])
        kinds = [-(j + 1) for j in range(m)]  # the root's j-th shape (frf.FRF_NULL)
        inputs = np.asarray([[kind, 0.0, 0.0, 1.0] for kind in kinds], dtype=np.float64)
        res = np.zeros((inputs.shape[0], outputs.shape[0]), dtype=np.complex128)
        singular = np.zeros(inputs.shape[0])
        if w == 0:  # the march cannot tell rigid motions apart at w = 0: the state is static
            w = complex(1e-9 * math.sqrt(EI / p[2]) / (L * L), 0.0)
        shapes(ends, kernel.topology.damped, w, p, inputs, outputs, res, singular)
        for s in range(inputs.shape[0]):
            v = res[s]
            beam = v[: 4 * n].reshape(n, 4)
            mass_y = v[4 * n :]
            Y = beam[:, 0]
            allY = np.concatenate([Y, mass_y])
            j = int(np.nanargmax(np.abs(allY))) if allY.size else 0
            scale = allY[j] if allY.size and abs(allY[j]) > 0 else 1.0
            out_shapes.append(
                DampedModeShape(
                    complex(omega[k]),
                    xs.copy(),
                    Y / scale,
                    beam[:, 1] / scale,
                    beam[:, 2] / scale,
                    beam[:, 3] / scale,
                    np.asarray([x for _, x in masses]),
                    mass_y / scale,
                    float(singular[s]),
                    m,
                )
            )
        k += inputs.shape[0]
    return out_shapes[: len(omega)]

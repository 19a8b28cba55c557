"""A proved upper bound on the decay rate of every damped root in a band.

The damped search counts zeros in the rectangle ``-eps < w_d < W``, ``-delta < sigma <
S`` of the ``w = w_d + i sigma`` plane. A root with ``sigma > S`` would be outside what
is counted, so ``S`` must be an upper bound that is *proved*, not a guess: this module
gives one, :func:`sigma_max`, from the energies of the structure (docs: README, "Damped
roots").

**The relation.** A damped mode ``u`` (beam deflection ``u(x)`` and every lumped
coordinate ``q``) with time dependence ``exp(i w t)`` satisfies
``(K (1 + i eta) + i w C - w^2 M) u = 0`` in weak form. With the Rayleigh forms
``m = u* M u > 0``, ``c = u* C u >= 0``, ``k_R = u* K u >= 0`` (bending, springs) and
``k_I = u* K_eta u`` (the loss factors' part, ``0 <= k_I <= eta_max k_R``):

    m w^2 - i c w - (k_R + i k_I) = 0.

Its real part gives ``k_R = m (w_d^2 - sigma^2) + c sigma <= m W^2 + c sigma`` for a
root with ``|w_d| <= W``. Solving the quadratic, ``sigma = Im w <= c / m +
sqrt(k_I / (2 m))`` (``Im sqrt(a + i b) <= sqrt(b / 2) + sqrt(max(-a, 0))`` with
``-a <= c^2``). So, with ``X = c / m``:

    (1)  sigma <= X + sqrt(eta_max (sigma X + W^2) / 2).

**Point dampers.** ``c`` is a sum over dashpots of ``c_j |relative motion|^2``. A
dashpot between the beam and the ground gives ``c_j |u(x_j)|^2``; one between the beam
and a lumped mass (or between two masses) at most ``2 c_j (|u(x_j)|^2 + |q|^2)``, and
``2 c_j |q_a|^2 <= (2 c_j / m_a) m``. Hence ``c <= sum_j Gamma_j |u(x_j)|^2 + R m`` with
``Gamma_j`` the beam-side damping of damper j (``Gamma`` their sum) and ``R`` the largest
``2 sum(c) / m_a`` of a component.

**Interpolation.** On an interval ``I`` of length ``l`` free of hinges (where ``u`` is
in ``H^2``), ``|u(x)|^2 <= 8 ||u||^2 / l + 2 l^3 ||u''||^2`` for ``x`` in ``I`` (split
``u`` into its L2 projection ``p`` on linear functions, ``max|p|^2 <= 4 ||p||^2 / l``,
and the rest ``e``, which is orthogonal to linears, so ``e`` and ``e'`` vanish in
``I`` and ``|e| <= l^(3/2) ||e''||``). Each damper j takes its own interval, of length
``l_j <= P_j`` (``P_j``: the hinge-free piece that holds it; one at a hinge takes the
wider piece beside it), and the norms over it are at most those over the beam. With
``m >= mbar_min ||u||^2`` and ``EI_min ||u''||^2 <= k_R <= m (sigma X + W^2)``:

    X <= R + sum_j 8 Gamma_j / (mbar_min l_j) + sum_j 2 Gamma_j l_j^3 (sigma X + W^2) / EI_min.

Choosing ``l_j = min(P_j, l)``, ``l = (EI_min / (4 Gamma sigma))^(1/3)`` (so the last sum
is at most half of ``X`` plus ``W^2 / (2 sigma)``), ``1 / min(P_j, l) <= 1 / P_j + 1 / l``
and ``sigma >= W``:

    (2)  X <= X0 + B sigma^(1/3),   X0 = 2 R + 16 sum_j Gamma_j / (mbar_min P_j) + W,
                                    B = 16 Gamma / mbar_min (4 Gamma / EI_min)^(1/3).

**The bound.** (1) and (2) with ``t = sigma^(1/6)``: every root with ``|w_d| <= W`` and
``sigma >= W`` has ``t^6 <= a0 + a2 t^2 + a3 t^3 + a4 t^4`` (``a0 = X0 + W
sqrt(eta/2)``, ``a2 = B``, ``a3 = sqrt(eta X0 / 2)``, ``a4 = sqrt(eta B / 2)``), whose
right side minus the left has one positive root ``t*`` (one sign change, Descartes).
So no root lies above ``S = max(W, t*^6)``.

The bound is loose (tens of times the largest decay rate for a dashpot at a free end)
but certain; the argument principle then counts what lies below it.
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass

from mstmm import catalog
from mstmm.physics import segment as segment_terms


@dataclass(frozen=True)
class DecayBound:
    """The proved bound and what it was made of (SI)."""

    sigma: float  # no root with |w_d| <= W has a larger decay rate (1/s)
    gamma: float  # Gamma: beam-side damping (N s/m)
    rate: float  # R: the largest 2 sum(c) / m of a component (1/s)
    piece: float  # the shortest hinge-free piece holding a damper (m)
    reach: float  # sum_j Gamma_j / P_j: each damper over its hinge-free piece (N s/m^2)
    eta: float  # the largest loss factor


def _kernel_module(scene):
    """The scene's kernel module: what each kind's damping connects and the own masses it
    moves were derived from its declared energy when the kernel was printed (``DAMPERS``:
    ``grounded``, ``carried`` or ``unproved``; ``own_masses``)."""
    from .kernels import load_kernel
    from .topology import topology_of

    return load_kernel(topology_of(scene)).module


def _own_mass(module, kind: str, given: dict, units: tuple[float, float, float]) -> float:
    """The least own mass (kg) of the unknowns a ``carried`` damper of ``kind`` moves, from
    the kernel's ``own_masses`` (the Schur complement of the kind's declared mass matrix,
    in units L = EI_0 = mbar_0 = 1) at the component's values (each stage's for a kind of
    stages); 0 where the kernel has none (the proof then does not apply)."""
    own = getattr(module, "own_masses", None)
    if own is None:
        return 0.0
    L, EI, mbar = units
    values: dict[str, list[float]] = {}
    for key in catalog.kind(kind).KEYS[1:]:
        v = catalog.value(kind, given, key)
        a, b, c = (float(e) for e in key.scale)
        factor = L**a * EI**b * mbar**c
        values[key.name] = [float(x) * factor for x in (v if key.shape == "list" else [v])]
    stages = max((len(v) for v in values.values()), default=1)
    masses = [
        float(m)
        for j in range(stages)
        for m in own(kind, {k: v[min(j, len(v) - 1)] for k, v in values.items()})
    ]
    return min(masses) * mbar * L if masses else 0.0


def _positive_root(coefficients: list[float]) -> float:
    """The positive root of ``t^6 - a4 t^4 - a3 t^3 - a2 t^2 - a0`` (``coefficients`` =
    ``[a0, a2, a3, a4]``, all >= 0; one sign change, so one positive root), inf when it
    overflows. At the root one term is at least a quarter of ``t^6``, so it lies below
    ``T = max((4 a_k)^(1 / (6 - k)))``; the bisection runs on ``x = t / T`` in [0, 1] with
    the coefficients scaled by ``T^(k - 6)`` in logarithms (no overflow for any input)."""
    powers = (0, 2, 3, 4)
    logs = [math.log(4.0 * a) / (6 - k) for a, k in zip(coefficients, powers) if a > 0.0]
    if not logs:
        return 0.0
    log_T = max(logs)
    scaled = [
        math.exp(math.log(a) - (6 - k) * log_T) if a > 0.0 else 0.0
        for a, k in zip(coefficients, powers)
    ]

    def g(x: float) -> float:
        return x**6 - sum(c * x**k for c, k in zip(scaled, powers))

    lo, hi = 0.0, 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if g(mid) <= 0.0:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-15 * hi:
            break
    try:
        return math.exp(math.log(hi) + log_T)
    except OverflowError:
        return math.inf


def sigma_max(scene, w_top: float) -> DecayBound | None:
    """An upper bound on ``sigma`` of every damped root of ``scene`` with ``|w_d| <=
    w_top`` (rad/s), proved as in the module's docstring; None when the proof does not
    apply (a damper the proof does not cover: on a rotation or on a massless coordinate,
    as the kind's energy says; a damping value in a unit other than N s/m; a segment in
    compression, whose geometric stiffness is negative and takes no loss factor; a point
    damper on a beam with a Timoshenko segment, whose ``k_R`` bounds ``EI ||psi'||^2``,
    not ``EI ||u''||^2``). A tension, a foundation and a rotary inertia only add to
    ``k_R`` (with their loss factor) or to ``m``: the proof holds."""
    beam = scene.beam
    segs = beam.segments or (beam,)
    tension = segment_terms.of_role("tension")
    if any(getattr(s, t.name, 0.0) < 0.0 for s in segs for t in tension):
        return None  # a compression: k_R may exceed EI ||u''||^2 and k_I its eta share
    shear = any(getattr(s, t.name, 0.0) > 0.0 for s in segs for t in segment_terms.of_role("shear"))
    EI = min(s.EI for s in segs)
    mbar = min(s.mass_per_length for s in segs)
    eta = max(float(getattr(s, "loss_factor", 0.0) or 0.0) for s in segs)
    breaks = {0.0, float(beam.length)}
    gamma = 0.0
    rate = 0.0
    where: list[tuple[float, float]] = []  # each damper: x and Gamma_j
    module = None  # the kernel's, read at the first damper
    units = (float(beam.length), float(segs[0].EI), float(segs[0].mass_per_length))
    for a in scene.attachments:
        if catalog.splits_rotation(a.kind):
            breaks.add(float(a.x))
        given = dict(a.values)
        cs: list[float] = []
        for key in catalog.kind(a.kind).KEYS[1:]:
            if key.damping:
                v = catalog.value(a.kind, given, key)
                vs = [float(c) for c in v] if key.shape == "list" else [float(v)]
                if any(c > 0.0 for c in vs) and key.unit != "N s/m":
                    return None
                cs += [c for c in vs if c > 0.0]
        if not cs:
            continue
        total = math.fsum(cs)
        if module is None:
            module = _kernel_module(scene)
        what = getattr(module, "DAMPERS", {}).get(a.kind, "unproved")
        if what == "grounded":
            gamma += total
            where.append((float(a.x), total))
            continue
        m_a = _own_mass(module, a.kind, given, units) if what == "carried" else 0.0
        if not m_a > 0.0:
            return None
        gamma += 2.0 * total
        where.append((float(a.x), 2.0 * total))
        rate = max(rate, 2.0 * total / m_a)
    if shear and where:  # a Timoshenko segment's k_R does not hold EI ||u''||^2
        return None
    points = sorted(breaks)
    piece = float(beam.length)
    reach = 0.0
    for x, g in where:  # the interval around each damper lies in its hinge-free piece
        i = bisect.bisect_right(points, x)
        lo, hi = points[max(i - 1, 0)], points[min(i, len(points) - 1)]
        if lo == x and i >= 2:  # at a hinge: the wider of the two pieces beside it
            hi = max(hi - x, x - points[i - 2])
            lo = 0.0
        piece = min(piece, hi - lo)
        reach += g / (hi - lo)
    return bound_from(gamma, rate, reach, piece, mbar, EI, eta, w_top)


def bound_from(
    gamma: float, rate: float, reach: float, piece: float, mbar: float, EI: float, eta: float,
    w_top: float,
) -> DecayBound:  # fmt: skip
    """The bound (2) and (1) of the module's proof from its ingredients (SI): ``gamma``
    (Gamma, the dampers' beam-side damping), ``rate`` (R), ``reach`` (sum_j Gamma_j /
    P_j), ``piece`` (the least P_j, reported), the least mass per length and EI, the
    largest loss factor and the band's top ``w_top`` (W)."""
    W = abs(float(w_top))
    X0 = 2.0 * rate + 16.0 * reach / mbar + W
    B = 16.0 * gamma / mbar * (4.0 * gamma / EI) ** (1.0 / 3.0)
    a = [X0 + W * math.sqrt(eta / 2.0), B, math.sqrt(eta * X0 / 2.0), math.sqrt(eta * B / 2.0)]
    t = _positive_root(a)
    try:
        sigma = max(W, t**6)
    except OverflowError:
        sigma = math.inf
    return DecayBound(sigma, gamma, rate, piece, reach, eta)

"""Independent high-precision reference model for the tests of ``mstmm``.

Natural frequencies of a uniform or stepped Euler-Bernoulli beam carrying
attachments of every kind (:data:`KINDS`: spring-masses, point masses with rotary
inertia, translational and rotational springs to ground, rigid point supports,
internal hinges with or without a spring, oscillator chains), computed WITHOUT
transfer matrices, with mpmath:

* the frequencies are the zeros of the determinant of a *global* linear system
  (4 coefficients per beam segment plus one displacement per hanging mass),
  assembled from the end conditions, the node conditions at the attachment
  points and segment boundaries and the equations of motion of the masses
  (:func:`global_determinant`);
* the roots are bracketed with the Wittrick-Williams algorithm, which counts
  *exactly* how many natural frequencies lie below a trial frequency from the
  inertia (number of negative pivots) of the exact dynamic stiffness matrix
  (:func:`count_below`).  The count is a second, independent formulation
  (energy form of the dynamic stiffness, not the global boundary-value
  system), so every returned simple root is found by both formulations.

Sign convention
---------------
``W(x)`` is the beam deflection and ``u_i`` the displacement of mass ``i``,
both positive in the same direction.  With ``EI W'''' + mbar W_tt = q`` a point
force ``F`` applied to the beam at ``x`` gives ``EI (W'''(x+) - W'''(x-)) = F``.
The spring pulls the beam toward the mass, ``F = k (u - W(x))``, hence::

    EI (W'''(x+) - W'''(x-)) = + sum_i k_i (u_i - W(x))      (interior point)
    EI W'''(0) = + sum_i k_i (u_i - W(0))                      (free / sliding left end)
    EI W'''(L) = - sum_i k_i (u_i - W(L))                      (free / sliding right end)
    -k_i W(x_i) + (k_i - m_i w^2) u_i = 0                      (each mass)

The other kinds follow from the stationary energy; at a node, with ``[.]`` the jump
(right minus left, a missing side counting 0)::

    EI [W'''] = (M w^2 - k) W           point mass M, spring k to ground
    EI [W'']  = (k_t - J w^2) W'        rotational spring k_t, rotary inertia J
    EI W''(x-) = EI W''(x+) = k_h (W'(x+) - W'(x-))   hinge (W, shear continuous)
    W = 0, W' and W'' continuous        support (the shear jumps by the reaction)
    m_i w^2 u_i + k_i (u_{i-1} - u_i) + k_{i+1} (u_{i+1} - u_i) = 0   chain stage i
                                        (u_0 = W, k_{n+1} = 0; force on the beam k_1 (u_1 - W))

A stepped beam keeps W, W', EI W'', EI W''' continuous at a segment boundary; each
segment has its own ``lam = (mbar w^2 / EI)^(1/4)`` (rows scaled by its own powers).
Positions within 1e-14 L of a segment boundary or an end are snapped onto it.  A
rotational spring or rotary inertia at a hinge is rejected (which side?).

The tests check this against the tip-mass cantilever
``1 + cos b cosh b + mu b (cos b sinh b - sin b cosh b) = 0`` (stiff-spring
limit) and against ``tests/data/reference.json``.

Nondimensionalisation
---------------------
``xi = x / L`` (L the total length), ``beta = lam L`` with ``lam^4 = mbar w^2 / EI``
of the first segment, so ``w = beta^2 sqrt(EI / mbar) / L^2``; ``K = k L^3 / EI``,
``M = m / (mbar L)`` (then ``m w^2 L^3 / EI = M beta^4``), ``K_t = k_t L / EI``,
``J = J / (mbar L^3)``; segment s has ``e_s = EI_s / EI`` and its own
``beta_s = beta (mu_s / e_s)^(1/4)``, ``mu_s = mbar_s / mbar``.

Spring-masses at a clamped or pinned end see a fixed point (W = 0 there): each
is a decoupled oscillator and ``sqrt(k/m)`` is a natural frequency of the
system (it is counted and returned like any other).

What is guaranteed about not missing roots
------------------------------------------
* Counting.  ``J(beta)`` = number of natural frequencies (with multiplicity,
  rigid-body modes included) strictly below ``beta`` is computed by the
  Wittrick-Williams algorithm: J = J0 + s{K}, J0 = clamped-clamped
  frequencies of the segments below their own beta_s (closed form), s{K} =
  number of negative pivots of the exact dynamic stiffness matrix (segments'
  closed form times e_s; point masses ``-M beta^4`` on W and ``-J beta^4`` on W';
  springs ``+K``, ``+K_t``; a chain condensed onto W from its tip, its own
  pivots counted: a Sturm count of the chain with the beam point held; a
  support removes the node's W; a hinge node has two rotations coupled by
  K_h), eliminated node by node.  It is exact as long as
  the pivot signs are right; they are computed with ``2 dps + 20`` digits
  (plus extra digits for short segments / low frequency).  ``J`` can be wrong
  only for a trial ``beta`` very close to a natural frequency: within the
  working precision normally, within its square root (~1e-(dps + 10)) when
  that frequency coincides with one of a sub-structure that the elimination
  clamps (e.g. pinned-free vs pinned-clamped, which are isospectral).  Near
  a sub-structure frequency alone, the sign errors cancel in the sum.  An
  exactly zero pivot makes it retry at a minutely lower ``beta``.
* Isolation.  Bisection on ``J`` from ``[0, beta_hi]`` (``J(beta_hi) >=
  n_modes``; ``J(0+)`` = the number of rigid-body modes) splits every interval
  until it holds one frequency.  An interval that still holds ``c >= 2`` when
  its relative width is below 1e-(dps + 5) is returned as a root of
  multiplicity ``c`` at its midpoint: exact multiple roots (identical
  oscillators at one point: ``sqrt(k/m)`` with multiplicity n - 1) and
  clusters closer than that are both reported this way.
* Polishing.  In an interval holding exactly one frequency, Anderson-Bjorck
  regula falsi on the pole-free dynamic-stiffness determinant (sides decided
  by ``J``), then the root is certified by the *global determinant*, which
  must change sign within a relative 1e-(dps + 4) of it; if it does not, the
  window is widened and the root of the global determinant in it is taken
  (same solver; a local one because mpmath.findroot's bracketing solvers stop
  on an absolute ``|f| < tol`` test, meaningless for a determinant whose scale
  is arbitrary).  If the global determinant shows no sign change anywhere in
  the isolating interval, ``RuntimeError``: the two formulations disagree.
  Simple roots are thus zeros of the global determinant to ~1e-(dps + 4);
  multiple roots come from the count alone.
* Rigid-body modes are counted exactly (Fractions) as the dimension of the
  rigid motions ``a + b x + sum_h c_h (x - x_h)+`` (kinks only at free hinges)
  that the ends, supports, springs and rotational springs to ground allow
  (free-free 2, pinned-free 1, ...; a free hinge adds one) and returned as
  exact zeros; the tests check that this equals ``J(0+)``.
* Working precision: ``dps + 20`` digits for the global determinant, plus
  digits for short segments, low frequency and stiff springs
  (log10(K / beta^3)); results agree between dps = 30 and dps = 50 to a few
  1e-32 on stiff, soft, heavy, close-positioned and 50-attachment scenes.

Damping and forced response
---------------------------
Optional scene keys (SI units): ``c`` on a spring_mass (a dashpot parallel to its
spring, whose force becomes ``(k + i w c)(u - W)``), ``c = [c1, c2, ...]`` on an
oscillator_chain (``c_i`` parallel to ``k_i``), a grounded ``dashpot`` attachment
(``x``, ``c``: ``EI [W'''] = -(i w c) W``, a spring with ``k -> i w c``) and
``loss_factor`` (eta >= 0) on a uniform ``beam`` or on each of its ``segments``
(``EI -> EI (1 + i eta)``).  Time dependence ``exp(i w t)``; a natural frequency is a
complex root ``w = w_d + i sigma`` (sigma > 0: decaying) of the entire characteristic
function :func:`damped_global_determinant` (the same global system in the Krylov basis,
dimensionless dashpot ``C = c L / sqrt(EI0 mbar0)``, ``i w c L^3 / EI0 = i (w / w_scale) C``).
:func:`damped_frequencies` returns the lowest roots with ``w_d >= 0``, certified by the
argument principle (:func:`damped_count`, :func:`damped_zero_count`); :func:`frf` the
receptance by a direct solve with the load in the right-hand side.  The undamped
functions refuse a scene with c > 0 or eta > 0 (ValueError) instead of dropping the
damping; with c = 0 and eta = 0 the damped functions reduce to them (same roots, real).

General segments
----------------
Optional keys on a uniform ``beam`` or on each of its ``segments`` (:data:`GENERAL_KEYS`,
SI, default 0 = absent): ``kappa_GA`` (Timoshenko shear stiffness, N; 0: no shear
deformation), ``rho_I`` (rotary inertia per length, kg m), ``axial_force`` (N, tension
positive), ``foundation_k`` (Winkler, N/m^2), ``foundation_kG`` (Pasternak, N).  Energies
per length, ``psi`` the section rotation, ``t = axial_force + foundation_kG``::

    U = [EI psi'^2 + kappa_GA (W' - psi)^2 + t W'^2 + k_w W^2] / 2
    T = [mbar W_t^2 + rho_I psi_t^2] / 2

(``psi = W'`` without shear).  A segment with any of them is integrated in its state
``(W, psi, M, Q)``, ``M = EI psi'``, ``Q = -(kappa_GA (W' - psi) + t W')`` the total
transverse force (the node conditions above hold with W' -> psi, EI W'' -> M and
EI W''' -> Q; a free end has M = Q = 0), by ``Z' = A Z`` from the Euler-Lagrange
equations (see the notes at :func:`_field_matrix`; the tests check A against the energies
with SymPy).  Its field transfer is ``exp(A h)`` (Taylor series reduced by Cayley-Hamilton,
:func:`_expm`) over pieces short enough that ``|lambda| h <= 3``: in the global system each
piece has its own 4 unknowns (multiple shooting; the determinant does not depend on the
cut), in the Wittrick-Williams count each piece is a member whose exact dynamic stiffness
comes from exp(A h) and whose clamped-clamped fundamental is proved above the trial
frequency by an energy bound (:func:`_cc_bound`), so that its J0 is 0.  The other segments
keep their closed forms.  Rigid-body modes: a foundation holds the whole of its segment
(between free hinges too), ``t != 0`` the slope on it (shear and rotary inertia hold
nothing).  With a compression, :func:`frequencies` and :func:`band` first check that the
count at a tiny frequency is the rigid-body count (else ValueError: buckled).  A loss
factor multiplies EI, kappa_GA, foundation_k and foundation_kG (not the axial force); the
damped roots of a scene with general segments are seeded by its undamped roots (no FE
model of them; an overdamped root, unseeded, makes the certificate fail: RuntimeError).
:func:`field_matrix` and :func:`general_segment_stiffness_matrix` expose the pieces to tests.

Public API: :func:`frequencies`, :func:`band`, :func:`global_determinant`,
:func:`count_below`, :func:`rigid_body_mode_count`, :func:`eigenspace`,
:func:`mode_at_attachments`, :func:`segment_stiffness_matrix`, :data:`KINDS`; damped:
:func:`damped_frequencies`, :func:`damped_count`, :func:`damped_zero_count`,
:func:`damped_global_determinant`, :func:`frf`, :data:`DAMPED_KINDS`; general segments:
:data:`GENERAL_KEYS`, :func:`field_matrix`, :func:`general_segment_stiffness_matrix`.

Scenes are dicts in the TOML layout or objects with the same attributes:
``beam`` with ``left``, ``right`` and either ``length``, ``EI``,
``mass_per_length`` or ``segments`` (each ``length``, ``EI``,
``mass_per_length``, from the left end); ``attachments``, each with ``type``
(dict) or ``kind`` (object), default ``spring_mass``, and ``x`` plus: ``k``, ``m``
(spring_mass); ``m``, ``J`` = 0 (mass); ``k`` (spring, rotational_spring);
nothing (support); ``k`` = 0 (hinge, strictly inside); lists ``k``, ``m``
(oscillator_chain, beam to tip); ``c`` (dashpot; optional on spring_mass, a list on
oscillator_chain); ``loss_factor`` and :data:`GENERAL_KEYS` (optional, beam or segment).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from fractions import Fraction

import mpmath
from mpmath import mp, mpc, mpf

__all__ = [
    "DAMPED_KINDS",
    "GENERAL_KEYS",
    "KINDS",
    "band",
    "count_below",
    "damped_count",
    "damped_frequencies",
    "damped_global_determinant",
    "damped_zero_count",
    "eigenspace",
    "field_matrix",
    "frequencies",
    "frf",
    "general_segment_stiffness_matrix",
    "global_determinant",
    "mode_at_attachments",
    "rigid_body_mode_count",
    "segment_stiffness_matrix",
]

# Conditions imposed at an end, as orders n of the scaled derivative W^(n) / beta^n.
# Order 3 (shear) carries the spring forces of attachments sitting at that end.
_END_ROWS = {
    "clamped": (0, 1),
    "pinned": (0, 2),
    "free": (2, 3),
    "sliding": (1, 3),
}
# Which of the nodal degrees of freedom (W, theta) stay free at an end.
_END_FREE_DOFS = {
    "clamped": (),
    "pinned": (1,),
    "free": (0, 1),
    "sliding": (0,),
}
_ALIASES = {
    "clamped": "clamped",
    "fixed": "clamped",
    "built_in": "clamped",
    "pinned": "pinned",
    "simply_supported": "pinned",
    "simple": "pinned",
    "hinged": "pinned",
    "free": "free",
    "sliding": "sliding",
    "guided": "sliding",
    "slide": "sliding",
}

_GUARD_DPS = 20
_SNAP = 10**14  # 1 / (relative distance from a segment boundary or end snapped onto it)


# --------------------------------------------------------------------------- input

#: Attachment kinds and what they put on a node (see the module docstring).
KINDS = (
    "spring_mass",
    "mass",
    "spring",
    "rotational_spring",
    "support",
    "hinge",
    "oscillator_chain",
)

#: The kinds the damped functions also accept: a grounded viscous ``dashpot`` (``x``, ``c``).
#: (Not in :data:`KINDS`, which lists the undamped kinds other tests iterate over.)
DAMPED_KINDS = KINDS + ("dashpot",)


def _get(obj, name):
    if isinstance(obj, dict):
        return obj[name]
    return getattr(obj, name)


def _opt(obj, name, default=None):
    """``obj[name]`` / ``obj.name`` if present and not None, else ``default``."""
    value = obj.get(name) if isinstance(obj, dict) else getattr(obj, name, None)
    return default if value is None else value


def _num(value) -> mpf:
    """Exact conversion of a float / int / str / Fraction / mpf to mpf (current precision)."""
    if isinstance(value, Fraction):
        return mpf(value.numerator) / value.denominator
    if isinstance(value, str):
        return mpf(value)
    if isinstance(value, (int, float, mpf)):
        return mpf(value)
    try:  # numpy scalars and the like
        return mpf(float(value))
    except TypeError as exc:  # pragma: no cover - defensive
        raise TypeError(f"cannot convert {value!r} to a number") from exc


def _frac(value) -> Fraction:
    """Exact rational value of a float / int / str / Fraction / mpf (for exact ranks)."""
    if isinstance(value, mpf):
        man, exp = value.man_exp
        return Fraction(man) * Fraction(2) ** exp
    if isinstance(value, (int, float, str, Fraction)):
        return Fraction(value)
    return Fraction(float(value))


def _end(value) -> str:
    raw = getattr(value, "value", value)
    if not isinstance(raw, str):
        raw = getattr(value, "name", str(value))
    key = str(raw).strip().lower().replace("-", "_").replace(" ", "_")
    if key not in _ALIASES:
        raise ValueError(f"unknown end condition {value!r}")
    return _ALIASES[key]


def _kind(att) -> str:
    if isinstance(att, dict):
        kind = att.get("type", att.get("kind", "spring_mass"))
    else:
        kind = getattr(att, "kind", None) or getattr(att, "type", None) or "spring_mass"
    kind = str(getattr(kind, "value", kind))
    if kind not in DAMPED_KINDS:
        raise ValueError(f"unsupported attachment type {kind!r}")
    return kind


def _segments(beam) -> list:
    """``(length, EI, mass_per_length)`` of each beam segment from the left end (raw values)."""
    segments = _opt(beam, "segments")
    if segments:
        return [(_get(s, "length"), _get(s, "EI"), _get(s, "mass_per_length")) for s in segments]
    return [(_get(beam, "length"), _get(beam, "EI"), _get(beam, "mass_per_length"))]


def _loss_factors(beam) -> list:
    """Raw ``loss_factor`` (default 0) of each beam segment: the beam's own for a uniform
    beam, each segment's for a stepped one (a beam-level value beside segments is refused:
    which one would hold is a guess)."""
    segments = _opt(beam, "segments")
    if segments:
        if _opt(beam, "loss_factor") not in (None, 0, 0.0):  # a Scene's Beam carries a 0
            raise ValueError("loss_factor on a stepped [beam]: give it on each [[beam.segments]]")
        return [_opt(s, "loss_factor", 0) for s in segments]
    return [_opt(beam, "loss_factor", 0)]


#: Optional segment keys of a general (Timoshenko, axially loaded, founded) segment, default 0.
GENERAL_KEYS = ("kappa_GA", "rho_I", "axial_force", "foundation_k", "foundation_kG")


def _general_values(beam) -> list:
    """Raw ``{key: value}`` of :data:`GENERAL_KEYS` (default 0) of each beam segment: the
    beam's own for a uniform beam, each segment's for a stepped one (a nonzero beam-level
    value beside segments is refused, as for ``loss_factor``)."""
    segments = _opt(beam, "segments")
    if segments:
        stray = [key for key in GENERAL_KEYS if _opt(beam, key) not in (None, 0, 0.0)]
        if stray:
            raise ValueError(f"{stray} on a stepped [beam]: give them on each [[beam.segments]]")
        return [{key: _opt(s, key, 0) for key in GENERAL_KEYS} for s in segments]
    return [{key: _opt(beam, key, 0) for key in GENERAL_KEYS}]


def _attachments(scene) -> list:
    try:
        return list(_get(scene, "attachments") or ())
    except (KeyError, AttributeError):
        return []


def _stages(kind: str, att) -> list:
    """Raw ``[(k_1, m_1), ..., (k_n, m_n)]`` of a spring-mass (n = 1) or an oscillator chain."""
    if kind == "spring_mass":
        return [(_get(att, "k"), _get(att, "m"))]
    ks, ms = list(_get(att, "k")), list(_get(att, "m"))
    if not ks or len(ks) != len(ms):
        raise ValueError(f"oscillator_chain needs k and m lists of one length: {ks}, {ms}")
    return list(zip(ks, ms, strict=True))


def _dampers(kind: str, att, n: int) -> list:
    """Raw dashpot constants ``c_i`` parallel to the springs of a spring-mass or chain (0 if
    absent)."""
    c = _opt(att, "c")
    if kind == "spring_mass":
        return [0 if c is None else c]
    if c is None:
        return [0] * n
    cs = list(c)
    if len(cs) != n:
        raise ValueError(f"oscillator_chain c needs {n} values like k, got {cs}")
    return cs


@dataclass
class _Node:
    """A point of the beam: an end, a segment boundary or an attachment point (all
    quantities dimensionless, see the module docstring)."""

    xi: mpf
    fix_w: bool = False  # W = 0 (clamped / pinned end, support)
    fix_t: bool = False  # W' = 0 (clamped / sliding end)
    hinge: object = None  # None: no hinge; else the hinge stiffness Kh (0: free hinge)
    k: mpf = mpf(0)  # springs to ground
    m: mpf = mpf(0)  # point masses
    kt: mpf = mpf(0)  # rotational springs to ground
    j: mpf = mpf(0)  # rotary inertias
    chains: list = field(default_factory=list)  # [(K_i, M_i), ...] per spring-mass / chain
    c: mpf = mpf(0)  # grounded dashpots, C = c L / sqrt(EI0 mbar0)
    chain_c: list = field(default_factory=list)  # [C_i, ...] per chain, parallel to chains


@dataclass(frozen=True)
class _General:
    """The general terms of a segment, dimensionless with EI0, mbar0 of the first segment and
    the total length L: ``G = kappa_GA L^2 / EI0`` (0: no shear deformation), ``r = rho_I /
    (mbar0 L^2)``, ``P = axial_force L^2 / EI0``, ``kg = foundation_kG L^2 / EI0``, ``kw =
    foundation_k L^4 / EI0``.  With ``beta^4 = mbar0 w^2 L^4 / EI0`` the energies per
    dimensionless length are ``1/2 [e psi'^2 + G (y' - psi)^2 + (P + kg) y'^2 + kw y^2]`` and
    ``1/2 beta^4 [mu y^2 + r psi^2]`` (y = Y / L, ' = d / dxi)."""

    G: mpf
    r: mpf
    P: mpf
    kg: mpf
    kw: mpf


@dataclass
class _Model:
    left: str
    right: str
    nodes: list  # _Node per point, ascending; nodes[0] and nodes[-1] are the ends
    seg: list  # dimensionless segment lengths (all > 0), len = number of nodes - 1
    seg_e: list  # EI of each segment / EI of the first
    seg_a: list  # (mu_s / e_s)^(1/4): the segment's beta is beta * seg_a[s]
    w_scale: mpf  # w = beta^2 * w_scale
    min_seg: mpf
    min_x: mpf  # smallest seg_a[s] * seg[s]
    k_max: mpf  # largest K = k L^3 / EI0 of a spring (0 without)
    kr_max: mpf  # largest rotational / hinge stiffness k L / EI0 (0 without)
    length: mpf  # L (m)
    seg_mu: list = None  # mbar of each segment / mbar of the first
    seg_eta: list = None  # loss factor of each segment
    ei0: mpf = None  # EI of the first segment (N m^2)
    point_nodes: list = None  # node index of each extra point given to _build
    seg_gen: list = None  # per segment: None (Euler-Bernoulli) or its _General terms

    @property
    def general(self) -> bool:
        """A segment with shear, rotary inertia, axial force or a foundation."""
        return any(g is not None for g in self.seg_gen or ())

    @property
    def damped(self) -> bool:
        """A dashpot (c > 0) or a loss factor (eta > 0) anywhere."""
        return any(eta != 0 for eta in self.seg_eta) or any(
            node.c != 0 or any(c != 0 for cs in node.chain_c for c in cs) for node in self.nodes
        )

    @property
    def masses(self) -> list:
        """Per node: the (K, M) stages of every spring-mass and chain hung there."""
        return [[stage for chain in node.chains for stage in chain] for node in self.nodes]


def _positive(name: str, *values) -> None:
    if not all(v > 0 for v in values):
        raise ValueError(f"{name} must be positive: {values}")


def _snap(x, edges: list, length):
    """``x`` moved onto a segment boundary or an end within a relative 1e-14 of it: the
    float sums of the segment lengths a scene states its positions with."""
    for edge in edges:
        if abs(x - edge) * _SNAP <= length:  # mpf or Fraction
            return edge
    return x


def _build(scene, points=()) -> _Model:
    """Nondimensionalise ``scene`` at the current mp precision.

    Units: L = total length, EI0 and mbar0 those of the first segment; then
    K = k L^3 / EI0, M = m / (mbar0 L), Kt = k_theta L / EI0, J = J / (mbar0 L^3),
    C = c L / sqrt(EI0 mbar0) (then i w c L^3 / EI0 = i (w / w_scale) C).  ``points``
    (m): extra nodes (the inputs and outputs of :func:`frf`).
    """
    beam = _get(scene, "beam")
    raw = _segments(beam)
    seg_len = [_num(s[0]) for s in raw]
    seg_ei = [_num(s[1]) for s in raw]
    seg_mu = [_num(s[2]) for s in raw]
    seg_eta = [_num(v) for v in _loss_factors(beam)]
    _positive("segment length, EI and mass_per_length", *seg_len, *seg_ei, *seg_mu)
    if not all(eta >= 0 for eta in seg_eta):
        raise ValueError(f"loss_factor must be >= 0: {seg_eta}")
    length = mpmath.fsum(seg_len)
    ei0, mu0 = seg_ei[0], seg_mu[0]
    seg_gen = [_general_terms(v, ei0, mu0, length) for v in _general_values(beam)]
    left = _end(_get(beam, "left"))
    right = _end(_get(beam, "right"))
    bounds, x = [], mpf(0)
    for ell in seg_len[:-1]:
        x += ell
        bounds.append(x)
    found: dict = {}

    def node_at(x):
        if x not in found:
            found[x] = _Node(x / length)
        return found[x]

    node_at(mpf(0)), node_at(length)
    for b in bounds:
        node_at(b)
    snapped = []
    for p in points:
        x = _snap(_num(p), [mpf(0)] + bounds + [length], length)
        if not (0 <= x <= length):
            raise ValueError(f"point {x} outside [0, L]")
        node_at(x)
        snapped.append(x)
    c_unit = length / mpmath.sqrt(ei0 * mu0)
    k_max = kr_max = mpf(0)
    for att in _attachments(scene):
        kind = _kind(att)
        x = _snap(_num(_get(att, "x")), [mpf(0)] + bounds + [length], length)
        if not (0 <= x <= length):
            raise ValueError(f"{kind} position {x} outside [0, L]")
        node = node_at(x)
        if kind in ("spring_mass", "oscillator_chain"):
            chain = [(_num(k), _num(m)) for k, m in _stages(kind, att)]
            _positive(f"{kind} k and m", *(v for stage in chain for v in stage))
            damp = [_num(c) for c in _dampers(kind, att, len(chain))]
            if not all(c >= 0 for c in damp):
                raise ValueError(f"{kind} c must be >= 0: {damp}")
            node.chains.append([(k * length**3 / ei0, m / (mu0 * length)) for k, m in chain])
            node.chain_c.append([c * c_unit for c in damp])
            k_max = max([k_max] + [k for k, _ in node.chains[-1]])
        elif kind == "mass":
            m, j = _num(_get(att, "m")), _num(_opt(att, "J", 0))
            if m < 0 or j < 0:
                raise ValueError(f"mass needs m >= 0 and J >= 0: {m}, {j}")
            node.m += m / (mu0 * length)
            node.j += j / (mu0 * length**3)
        elif kind == "spring":
            k = _num(_get(att, "k"))
            _positive("spring k", k)
            node.k += k * length**3 / ei0
            k_max = max(k_max, node.k)
        elif kind == "rotational_spring":
            k = _num(_get(att, "k"))
            _positive("rotational_spring k", k)
            node.kt += k * length / ei0
            kr_max = max(kr_max, node.kt)
        elif kind == "support":
            node.fix_w = True
        elif kind == "dashpot":
            c = _num(_get(att, "c"))
            if not c >= 0:
                raise ValueError(f"dashpot c must be >= 0: {c}")
            node.c += c * c_unit
        else:  # hinge
            k = _num(_opt(att, "k", 0))
            if not (0 < x < length):
                raise ValueError(f"a hinge must be strictly inside the beam, got x = {x}")
            if node.hinge is not None or k < 0:
                raise ValueError(f"one hinge per point, k >= 0 (x = {x}, k = {k})")
            node.hinge = k * length / ei0
            kr_max = max(kr_max, node.hinge)
    xs = sorted(found)
    nodes = [found[x] for x in xs]
    for node in nodes:
        if node.hinge is not None and (node.kt != 0 or node.j != 0):
            raise ValueError(
                f"rotational spring or rotary inertia at the hinge at x = {node.xi * length}: "
                "ambiguous (which side?)"
            )
    nodes[0].fix_w |= left in ("clamped", "pinned")
    nodes[0].fix_t |= left in ("clamped", "sliding")
    nodes[-1].fix_w |= right in ("clamped", "pinned")
    nodes[-1].fix_t |= right in ("clamped", "sliding")
    # material of each mesh segment: the beam segment it lies in
    seg, seg_e, seg_a, mesh_mu, mesh_eta, mesh_gen = [], [], [], [], [], []
    edges = [mpf(0)] + bounds
    for a, b in zip(xs, xs[1:], strict=False):
        s = max(i for i, e in enumerate(edges) if e <= a)
        e_rel, mu_rel = seg_ei[s] / ei0, seg_mu[s] / mu0
        seg.append((b - a) / length)
        seg_e.append(e_rel)
        seg_a.append(mpf(1) if e_rel == mu_rel else mpmath.root(mu_rel / e_rel, 4))
        mesh_mu.append(mu_rel)
        mesh_eta.append(seg_eta[s])
        mesh_gen.append(seg_gen[s])
    w_scale = mpmath.sqrt(ei0 / mu0) / length**2
    min_x = min(a * ell for a, ell in zip(seg_a, seg, strict=True))
    return _Model(
        left,
        right,
        nodes,
        seg,
        seg_e,
        seg_a,
        w_scale,
        min(seg),
        min_x,
        k_max,
        kr_max,
        length,
        mesh_mu,
        mesh_eta,
        ei0,
        [xs.index(x) for x in snapped],
        mesh_gen,
    )


def _general_terms(values: dict, ei0, mu0, length):
    """The :class:`_General` terms of a segment from its raw keys, or None when all are 0
    (an Euler-Bernoulli segment, on the original closed-form path)."""
    kga, rho_i, p, kw, kg = (_num(values[key]) for key in GENERAL_KEYS)
    if kga < 0 or rho_i < 0 or kw < 0 or kg < 0:
        raise ValueError(
            f"kappa_GA, rho_I, foundation_k, foundation_kG must be >= 0: {kga}, {rho_i}, {kw}, {kg}"
        )
    if kga > 0 and not kga + p + kg > 0:
        raise ValueError(f"kappa_GA + axial_force + foundation_kG must be > 0: {kga + p + kg}")
    if kga == rho_i == p == kw == kg == 0:
        return None
    return _General(
        kga * length**2 / ei0,
        rho_i / (mu0 * length**2),
        p * length**2 / ei0,
        kg * length**2 / ei0,
        kw * length**4 / ei0,
    )


def _undamped_model(scene) -> _Model:
    """:func:`_build` for the undamped functions, which refuse a damped scene (c > 0 or
    loss_factor > 0) rather than drop its damping."""
    model = _build(scene)
    if model.damped:
        raise ValueError(
            "the scene has damping (c > 0 or loss_factor > 0): use damped_frequencies / frf"
        )
    return model


def _extra_dps(x) -> int:
    """Digits lost to cancellation for a segment of dimensionless wave length x = beta l."""
    if x >= 1:
        return 0
    if not x > 0:
        raise ValueError("trial frequency must be positive")
    return int(4 * math.ceil(-float(mpmath.log10(x)))) + 5


def _work_dps(model: _Model, dps: int, beta) -> int:
    extra = _extra_dps(beta * model.min_x)
    extra += int(3 * math.ceil(max(0.0, -float(mpmath.log10(model.min_seg)))))
    return dps + _GUARD_DPS + extra


# ------------------------------------------------------------------ general segments
#
# A segment with any of GENERAL_KEYS is integrated in its state Z = (y, psi, m, q) =
# (Y / L, psi, M L / EI_s, Q L^2 / EI_s), ' = d / dxi, M = EI psi', Q = -(kGA (Y' - psi) +
# (P + k_G) Y') the total transverse force.  Stationary energy (see _General) at beta^4,
# with t = P + kg, g = G + t, the Euler-Lagrange equations in first-order form are
#
#     y' = (G / g) psi - (e / g) q                    (G = 0: y' = psi)
#     psi' = m / c
#     m' = ((G t / g - r beta^4) psi + (G / g) e q) / e   (G = 0: m' = q + (t - r beta^4) psi / e)
#     q' = (mu beta^4 - kw) y / e
#
# (c = 1 + i eta: the loss factor multiplies EI, kappa_GA, foundation_k, foundation_kG, not P;
# m and q are scaled by the real EI_s, so that a segment's rows meet its neighbours' with the
# factor 1).  Without the general terms this is the Euler-Bernoulli equation y^(4) = (mu / e)
# beta^4 y, and e m, e q are the e W'', e W''' of the closed-form path, so the node
# conditions of _assemble and the nodal forces of the count apply unchanged.  A general
# segment is cut into pieces (blank nodes) short enough that exp(A h) stays well conditioned
# (|lambda| h <= _PIECE_REACH) and, for the Wittrick-Williams count, that its clamped-clamped
# fundamental provably exceeds the trial frequency (_cc_bound), so that its J0 is 0.  The
# global determinant does not depend on the cut (a blank node's rows are z_next - exp(A h) z:
# the Schur complement gives back exp(A (h1 + h2))), so it is one entire function of w.

_PIECE_REACH = 3.0  # largest |lambda| h of a piece (exp(A h) grows like exp(|lambda| h))
_CC_MARGIN = 1.25  # a piece's clamped-clamped bound must exceed beta^4 by this factor


def _field_matrix(gen: _General, e, mu, eta, b4):
    """The 4x4 ``A`` of ``Z' = A Z`` of a general segment at ``beta^4 = b4`` (complex with a
    loss factor eta), current precision."""
    c = 1 if eta == 0 else mpc(1, eta)
    G, kw, t = gen.G * c, gen.kw * c, gen.P + gen.kg * c
    R = gen.r * b4
    A = mpmath.matrix(4, 4)
    A[1, 2] = 1 / c
    A[3, 0] = (mu * b4 - kw) / e
    if gen.G == 0:
        A[0, 1] = 1
        A[2, 1] = (t - R) / e
        A[2, 3] = 1
    else:
        g = G + t
        A[0, 1] = G / g
        A[0, 3] = -e / g
        A[2, 1] = (G * t / g - R) / e
        A[2, 3] = G / g
    return A


def _expm(A, h) -> list:
    """``exp(A h)`` of a 4x4 matrix (nested lists) at the current precision: the Taylor series
    reduced by Cayley-Hamilton, ``A^n = a0 I + a1 A + a2 A^2 + a3 A^3`` with the coefficients'
    recurrence from the characteristic polynomial (Newton's identities on the traces of the
    powers), summed with 10 guard digits until the terms are below 2^-prec of the sum.  Used
    with ``|lambda| h <= _PIECE_REACH`` (terms up to ~e^3 of the result: no real loss); checked
    against ``mpmath.expm`` in the tests."""
    with mp.workdps(mp.dps + 10):
        n = 4
        a = [[A[i, j] * h for j in range(n)] for i in range(n)]

        def mul(x, y):
            return [
                [mpmath.fsum(x[i][k] * y[k][j] for k in range(n)) for j in range(n)]
                for i in range(n)
            ]

        a2 = mul(a, a)
        a3 = mul(a2, a)
        powers = [None, a, a2, a3]
        s1 = mpmath.fsum(a[i][i] for i in range(n))
        s2 = mpmath.fsum(a2[i][i] for i in range(n))
        s3 = mpmath.fsum(a3[i][i] for i in range(n))
        s4 = mpmath.fsum(a2[i][k] * a2[k][i] for i in range(n) for k in range(n))
        p1 = -s1
        p2 = -(s2 + p1 * s1) / 2
        p3 = -(s3 + p1 * s2 + p2 * s1) / 3
        p4 = -(s4 + p1 * s3 + p2 * s2 + p3 * s1) / 4
        norms = [1.0] + [float(max(abs(v) for row in x for v in row)) for x in powers[1:]]
        coef = [mpf(1), mpf(0), mpf(0), mpf(0)]  # of A^n (n = 0)
        total = list(coef)
        eps = 2.0 ** (-mp.prec)
        factor, small, k = mpf(1), 0, 0
        while small < 4:
            k += 1
            c0, c1, c2, c3 = coef
            coef = [-p4 * c3, c0 - p3 * c3, c1 - p2 * c3, c2 - p1 * c3]
            factor /= k
            for i in range(n):
                total[i] += factor * coef[i]
            size = float(factor) * sum(float(abs(c)) * m for c, m in zip(coef, norms, strict=True))
            scale = sum(float(abs(c)) * m for c, m in zip(total, norms, strict=True))
            small = small + 1 if size <= eps * scale else 0
            if k > 100000:  # pragma: no cover - defensive
                raise RuntimeError("exp(A h) series does not converge")
        out = [[total[0] * (i == j) for j in range(n)] for i in range(n)]
        for p in range(1, n):
            for i in range(n):
                for j in range(n):
                    out[i][j] += total[p] * powers[p][i][j]
    return [[+v for v in row] for row in out]


def _wavenumber_bound(gen: _General, e, mu, eta, b4) -> float:
    """Upper bound of |lambda| over the eigenvalues of A: det(lambda - A) is a quadratic in
    lambda^2, z^2 + B z + C (B, C below, by SymPy), and |z| <= |B| + sqrt |C|."""
    c = complex(1, float(eta))
    b4 = complex(b4)
    e, mu = float(e), float(mu)
    G, kw, t = float(gen.G) * c, float(gen.kw) * c, float(gen.P) + float(gen.kg) * c
    R, Mw = float(gen.r) * b4, mu * b4 - kw
    if gen.G == 0:
        B, C = (R - t) / (c * e), -Mw / (c * e)
    else:
        g = G + t
        B = (G * R - G * t + Mw * c * e + R * t) / (c * e * g)
        C = Mw * (R - G) / (c * e * g)
    return math.sqrt(abs(B) + math.sqrt(abs(C)))


def _cc_bound(gen: _General, e, mu, h: float) -> float:
    """A lower bound of beta^4 of the clamped-clamped fundamental of an undamped piece of
    dimensionless length h (0 if none is proved).  With y, psi = 0 at both ends, s = (pi/h)^2:

    * G = 0 (psi = y'): int y''^2 >= 4 s int y'^2 (clamped-clamped buckling) and int y^2 <=
      int y'^2 / s give U >= (4 e s + t) int y'^2 and T <= (mu / s + r) int y'^2;
    * G > 0: G (a - b)^2 >= G (1 - eps) a^2 - G (1 / eps - 1) b^2 (0 < eps < 1, eps < g / G
      so that c_w = G (1 - eps) + t > 0) and int psi'^2 >= s int psi^2 give U >= c_psi int
      psi^2 + c_w s int y^2, c_psi = e s - G (1 / eps - 1), against T = mu int y^2 + r int
      psi^2

    (U, T the potential and kinetic energies over beta^4; the foundation only adds to U)."""
    e, mu, r = float(e), float(mu), float(gen.r)
    G, t = float(gen.G), float(gen.P) + float(gen.kg)
    s = (math.pi / h) ** 2
    if G == 0:
        c1 = 4 * e * s + t
        return c1 / (mu / s + r) if c1 > 0 else 0.0
    eps = 0.5 if t >= 0 else (G + t) / (2 * G)
    c_w = G * (1 - eps) + t
    c_psi = e * s - G * (1 / eps - 1)
    if c_psi < 0 or c_w <= 0:
        return 0.0
    return min(c_w * s / mu, c_psi / r if r > 0 else math.inf)


def _mesh_pieces(model: _Model, b4, count: bool) -> list:
    """Number of pieces of each segment at beta^4 = b4 (1 for an Euler-Bernoulli segment):
    |lambda| h <= _PIECE_REACH, and for the count (real b4) a clamped-clamped bound above
    _CC_MARGIN b4, rounded up to a power of 2 (F of the count, interpolated on while a root
    is polished, jumps where the cut changes; the bracket is the count's anyway)."""
    out = []
    for j, gen in enumerate(model.seg_gen):
        if gen is None:
            out.append(1)
            continue
        e, mu, eta, ell = model.seg_e[j], model.seg_mu[j], model.seg_eta[j], float(model.seg[j])
        lam = _wavenumber_bound(gen, e, mu, eta, b4)
        n = max(1, math.ceil(ell * lam / _PIECE_REACH))
        if count:
            target = _CC_MARGIN * float(b4)
            while not _cc_bound(gen, e, mu, ell / n) > target:
                n = max(n + 1, math.ceil(n * 1.25))
            n = 1 << (n - 1).bit_length()  # a power of 2: the cut changes seldom with beta
        out.append(n)
    return out


def _refine(model: _Model, pieces: list) -> _Model:
    """``model`` with segment j cut into ``pieces[j]`` equal pieces (blank nodes between)."""
    if all(n == 1 for n in pieces):
        return model
    nodes, index = [model.nodes[0]], [0]
    lists = {name: [] for name in ("seg", "seg_e", "seg_a", "seg_mu", "seg_eta", "seg_gen")}
    for j, n in enumerate(pieces):
        h = model.seg[j] / n
        for i in range(n):
            for name, values in lists.items():
                values.append(h if name == "seg" else getattr(model, name)[j])
            if i < n - 1:
                nodes.append(_Node(model.nodes[j].xi + h * (i + 1)))
        nodes.append(model.nodes[j + 1])
        index.append(len(nodes) - 1)
    seg, seg_a = lists["seg"], lists["seg_a"]
    points = None if model.point_nodes is None else [index[i] for i in model.point_nodes]
    return replace(
        model,
        nodes=nodes,
        min_seg=min(seg),
        min_x=min(a * ell for a, ell in zip(seg_a, seg, strict=True)),
        point_nodes=points,
        **lists,
    )


def _general_dps(model: _Model, b4) -> int:
    """Extra digits for the general segments' rows: their state's entries differ by powers
    of the wave number (no cancellation across a piece, |lambda| h <= _PIECE_REACH)."""
    lam = max(
        [1.0]
        + [
            _wavenumber_bound(gen, model.seg_e[j], model.seg_mu[j], model.seg_eta[j], b4)
            for j, gen in enumerate(model.seg_gen)
            if gen is not None
        ]
    )
    return int(math.ceil(3 * math.log10(lam))) + 5


def _general_stiffness_matrix(gen: _General, e, mu, b4, h) -> list:
    """Exact dynamic stiffness (4x4, nested lists) of an undamped general piece of length h,
    DOFs (y0, psi0, y1, psi1), the nodal forces e (q0, -m0, -q1, m1) (the boundary terms
    [e m dpsi - e q dy] of the energy), from T = exp(A h): with d = (y, psi), f = (m, q),
    d1 = T11 d0 + T12 f0, f1 = T21 d0 + T22 f0."""
    T = _expm(_field_matrix(gen, e, mu, 0, b4), h)

    def block(r, c):
        return [[T[r + i][c + j] for j in range(2)] for i in range(2)]

    def mul(a, b):
        return [[a[i][0] * b[0][j] + a[i][1] * b[1][j] for j in range(2)] for i in range(2)]

    t11, t12, t21, t22 = block(0, 0), block(0, 2), block(2, 0), block(2, 2)
    det = t12[0][0] * t12[1][1] - t12[0][1] * t12[1][0]
    if det == 0:
        raise _Degenerate
    inv = [[t12[1][1] / det, -t12[0][1] / det], [-t12[1][0] / det, t12[0][0] / det]]
    x = [[-v for v in row] for row in mul(inv, t11)]  # f0 = x d0 + inv d1
    u = [[a + b for a, b in zip(ra, rb, strict=True)] for ra, rb in zip(t21, mul(t22, x))]
    v = mul(t22, inv)  # f1 = u d0 + v d1
    rows = [x[1] + inv[1], [-a for a in x[0] + inv[0]], [-a for a in u[1] + v[1]], u[0] + v[0]]
    return [[e * a for a in row] for row in rows]


def _general_stiffness(model: _Model, j: int, beta, cache: dict):
    """The stiffness entries (k00, k01, k02, k03, k11, k13) of the general piece j (a uniform
    piece is symmetric under reflection, like the closed form), its J0 = 0 proved by
    :func:`_cc_bound`."""
    gen, e, mu, h = model.seg_gen[j], model.seg_e[j], model.seg_mu[j], model.seg[j]
    key = (gen, e, mu, h)
    if key not in cache:
        b4 = beta**4
        if not _cc_bound(gen, e, mu, float(h)) > float(b4):
            raise AssertionError("a general piece too long for the count (J0 > 0 possible)")
        with mp.workdps(mp.dps + _extra_dps(beta * model.seg_a[j] * h) + 10):
            K = _general_stiffness_matrix(gen, e, mu, b4, h)
            ks = (K[0][0], K[0][1], K[0][2], K[0][3], K[1][1], K[1][3])
        cache[key] = tuple(+v for v in ks)
    return cache[key]


def general_segment_stiffness_matrix(segment: dict, beta, ell) -> list:
    """The 4x4 dynamic stiffness of an undamped general segment of dimensionless length
    ``ell`` at ``beta`` (nested lists, current mp precision; for tests), the segment given
    as ``{"EI", "mass_per_length", key: value for GENERAL_KEYS}`` with L = EI0 = mbar0 = 1."""
    gen = _general_terms({key: segment.get(key, 0) for key in GENERAL_KEYS}, 1, 1, 1)
    if gen is None:
        gen = _General(mpf(0), mpf(0), mpf(0), mpf(0), mpf(0))
    e, mu = _num(segment.get("EI", 1)), _num(segment.get("mass_per_length", 1))
    return _general_stiffness_matrix(gen, e, mu, _num(beta) ** 4, _num(ell))


def field_matrix(segment: dict, b4, eta=0) -> list:
    """The 4x4 ``A`` (nested lists) of a segment given like
    :func:`general_segment_stiffness_matrix` at ``beta^4 = b4`` (for tests)."""
    gen = _general_terms({key: segment.get(key, 0) for key in GENERAL_KEYS}, 1, 1, 1)
    if gen is None:
        gen = _General(mpf(0), mpf(0), mpf(0), mpf(0), mpf(0))
    e, mu = _num(segment.get("EI", 1)), _num(segment.get("mass_per_length", 1))
    A = _field_matrix(gen, e, mu, _num(eta), _cnum(b4))
    return [[A[i, j] for j in range(4)] for i in range(4)]


class _GeneralRows:
    """A basis (:class:`_TrigBasis` or :class:`_KrylovBasis`) with the rows of the general
    segments replaced: their unknowns are the state (y, psi, m, q) at the segment's left end,
    the right end ``exp(A l)`` times it (derivative factors 1, ``e`` the real EI_s / EI0)."""

    def __init__(self, model: _Model, base, b4):
        self.base = base
        self.b4 = base.b4
        self.bs = list(base.bs)
        self.e = list(base.e)
        self.T = {}
        cache: dict = {}
        for s, gen in enumerate(model.seg_gen):
            if gen is None:
                continue
            self.bs[s] = 1
            self.e[s] = model.seg_e[s]
            key = (gen, model.seg_e[s], model.seg_mu[s], model.seg_eta[s], model.seg[s])
            if key not in cache:
                cache[key] = _expm(_field_matrix(gen, *key[1:4], b4), model.seg[s])
            self.T[s] = cache[key]

    def row(self, side, order: int, cols: list) -> dict:
        seg, at_end = side
        T = self.T.get(seg)
        if T is None:
            return self.base.row(side, order, cols)
        base = cols[seg]
        if not at_end:
            return {base + order: mpf(1)}
        return {base + i: v for i, v in enumerate(T[order]) if v != 0}

    def stiffness(self, k, c):
        return self.base.stiffness(k, c)

    def mass_scale(self, k, k_next, m):
        return self.base.mass_scale(k, k_next, m)


def _rigid_constraints(scene) -> tuple:
    """Rigid motions ``W(x) = a + b x + sum_h c_h (x - x_h)_+`` (kinks c_h at the free
    hinges x_h): the hinge positions and the exact linear constraints on (a, b, c...)
    from the ends, supports, springs and rotational springs to ground, foundations,
    axial forces and Pasternak layers (the shear stiffness and rotary inertia hold none:
    a rigid motion has psi = W', no shear strain)."""
    beam = _get(scene, "beam")
    left, right = _end(_get(beam, "left")), _end(_get(beam, "right"))
    edges = [Fraction(0)]
    for seg in _segments(beam):
        edges.append(edges[-1] + _frac(seg[0]))
    length = edges[-1]
    atts = [(_kind(a), a) for a in _attachments(scene)]

    def at(a):
        return _snap(_frac(_get(a, "x")), edges, length)

    hinges = sorted(at(a) for kind, a in atts if kind == "hinge" and _num(_opt(a, "k", 0)) == 0)

    def value(x):
        return _rigid_value(x, hinges)

    def slope(x):
        return [Fraction(0), Fraction(1)] + [Fraction(1 if x > h else 0) for h in hinges]

    rows = []
    for x, end in ((Fraction(0), left), (length, right)):
        if end in ("clamped", "pinned"):
            rows.append(value(x))
        if end in ("clamped", "sliding"):
            rows.append(slope(x))
    for kind, a in atts:
        if kind in ("support", "spring"):
            rows.append(value(at(a)))
        elif kind == "rotational_spring":
            rows.append(slope(at(a)))
    # general segments: a foundation (k_w > 0) holds the motion at every point of its
    # segment (W = 0 at its ends and at its free hinges: W is straight between them); an
    # axial force or a Pasternak layer (P + k_G != 0) its slope (at a point of each piece
    # between the free hinges), since 1/2 (P + k_G) W'^2 is then the energy of a rotation
    for (a, b), values in zip(zip(edges, edges[1:]), _general_values(beam), strict=True):
        kinks = [h for h in hinges if a < h < b]
        if _frac(values["foundation_k"]) != 0:
            rows.extend(value(x) for x in [a, *kinks, b])
        if _frac(values["axial_force"]) + _frac(values["foundation_kG"]) != 0:
            ends = [a, *kinks, b]
            rows.extend(slope((x + y) / 2) for x, y in zip(ends, ends[1:]))
    return hinges, rows


def _rigid_value(x, hinges: list) -> list:
    """Coefficients of (a, b, c...) in W(x) = a + b x + sum_h c_h (x - x_h)_+ (exact)."""
    return [Fraction(1), x] + [x - h if x > h else Fraction(0) for h in hinges]


def _null_space(rows: list, n: int) -> list:
    """Exact basis of {v : rows v = 0} (Fractions), by reduced row echelon form."""
    rows = [list(r) for r in rows]
    pivots, r = [], 0
    for c in range(n):
        p = next((i for i in range(r, len(rows)) if rows[i][c] != 0), None)
        if p is None:
            continue
        rows[r], rows[p] = rows[p], rows[r]
        pv = rows[r][c]
        rows[r] = [v / pv for v in rows[r]]
        for i in range(len(rows)):
            if i != r and rows[i][c] != 0:
                f = rows[i][c]
                rows[i] = [a - f * b for a, b in zip(rows[i], rows[r], strict=True)]
        pivots.append(c)
        r += 1
    basis = []
    for free in (c for c in range(n) if c not in pivots):
        v = [Fraction(0)] * n
        v[free] = Fraction(1)
        for i, c in enumerate(pivots):
            v[c] = -rows[i][free]
        basis.append(v)
    return basis


def rigid_body_mode_count(scene) -> int:
    """Dimension of the rigid motions (straight pieces, kinks only at free hinges) that the
    ends, supports, springs and rotational springs to ground allow."""
    hinges, rows = _rigid_constraints(scene)
    return len(_null_space(rows, 2 + len(hinges)))


# ------------------------------------------------------------- global determinant


def _scaled_row(seg_index: int, at_end: bool, order: int, trig, cols) -> dict:
    """Row of W^(order)(s) / beta^order in the basis cos, sin, exp(-beta s), exp(beta (s - l))."""
    c, s, e = trig[seg_index]
    base = cols[seg_index]
    sign = -1 if order % 2 else 1
    if not at_end:
        vals = ((1, 0, -1, 0)[order], (0, 1, 0, -1)[order], sign, e)
    else:
        vals = ((c, -s, -c, s)[order], (s, c, -s, -c)[order], sign * e, 1)
    return {base + i: mpf(v) for i, v in enumerate(vals) if v != 0}


def _add(row: dict, other: dict, factor) -> None:
    for col, val in other.items():
        row[col] = row.get(col, 0) + factor * val


def _sparse_det(rows: list, ncols: int):
    """Determinant by Gaussian elimination with partial pivoting on dict rows."""
    if len(rows) != ncols:
        raise AssertionError("global matrix is not square")
    col_rows = [set() for _ in range(ncols)]
    for r, row in enumerate(rows):
        for col in row:
            col_rows[col].add(r)
    det = mpf(1)
    perm = [0] * ncols
    for col in range(ncols):
        cands = col_rows[col]
        if not cands:
            return mpf(0)
        piv = max(cands, key=lambda r: abs(rows[r][col]))
        prow = rows[piv]
        pval = prow[col]
        if pval == 0:
            return mpf(0)
        det *= pval
        perm[col] = piv
        for cc in prow:
            col_rows[cc].discard(piv)
        others = list(col_rows[col])
        col_rows[col] = set()
        for r in others:
            row = rows[r]
            f = row.pop(col) / pval
            for cc, v in prow.items():
                if cc == col:
                    continue
                if cc in row:
                    row[cc] -= f * v
                else:
                    row[cc] = -f * v
                    col_rows[cc].add(r)
    # sign of the row permutation
    seen = [False] * ncols
    parity = 0
    for i in range(ncols):
        if not seen[i]:
            j, length = i, 0
            while not seen[j]:
                seen[j] = True
                j = perm[j]
                length += 1
            parity += length - 1
    return -det if parity % 2 else det


def _global_det(model: _Model, beta):
    """Determinant of the global system at dimensionless frequency beta > 0 (current mp)."""
    rows, ncol, _w_rows, _mass_cols = _global_rows(model, beta)
    return _sparse_det(rows, ncol)


class _TrigBasis:
    """The undamped path's basis: cos, sin, exp(-b s), exp(b (s - l)) in each segment
    (real beta > 0), rows of the scaled derivatives W^(n) / beta_s^n."""

    def __init__(self, model: _Model, beta):
        self.bs = [beta * a for a in model.seg_a]  # derivative factors beta_s
        self.trig = []
        gens = model.seg_gen or [None] * len(model.seg)
        for ell, b, gen in zip(model.seg, self.bs, gens, strict=True):
            if gen is not None:  # a general segment: its rows come from _GeneralRows
                self.trig.append(None)
                continue
            x = b * ell
            self.trig.append((mpmath.cos(x), mpmath.sin(x), mpmath.exp(-x)))
        self.e = model.seg_e  # EI of each segment / EI0
        self.b4 = beta**4

    def row(self, side, order: int, cols: list) -> dict:
        return _scaled_row(side[0], side[1], order, self.trig, cols)

    @staticmethod
    def stiffness(k, c):
        """A spring with its parallel dashpot (undamped: the spring)."""
        return k

    def mass_scale(self, k, k_next, m):
        """Divisor of a mass's equation (positive)."""
        return k + k_next + m * self.b4


@dataclass
class _System:
    """The global linear system and where its equations and unknowns sit."""

    rows: list  # sparse rows (dicts column -> value)
    ncol: int
    w_rows: list  # per node: the row of W there
    mass_cols: list  # per node: the columns of its hanging masses
    cols: list  # first column of each segment
    shear: dict  # node -> (row index, factor f): the row is f * (shear equation)
    moment: dict  # node -> (row index, factor) (not at a hinge or a fixed W')
    mass_eqs: list  # per hanging mass, in column order: (row index, factor)


def _global_rows(model: _Model, beta):
    """Rows of the global system, the column count, the deflection row at each node and
    the mass columns of each node (undamped path; see :func:`_assemble`)."""
    basis = _TrigBasis(model, beta)
    if model.general:  # (model cut into pieces by _refine)
        basis = _GeneralRows(model, basis, beta**4)
    system = _assemble(model, basis)
    return system.rows, system.ncol, system.w_rows, system.mass_cols


def _assemble(model: _Model, basis) -> _System:
    """The global system in ``basis`` (:class:`_TrigBasis` or :class:`_KrylovBasis`).

    Columns: the hanging masses of node 0, the 4 coefficients of segment 0, the
    masses of node 1, ... Rows, node by node (node 0, the last node, then the
    interior ones), in the order W, W', moment, shear; then one row per hanging
    mass.  Node conditions, in the jump form ``[f] = f(x+) - f(x-)`` with a missing
    side contributing 0 (the row is negated at the right end)::

        W fixed:     W(x-) = 0, W(x+) = 0          else  [W] = 0,  e [W'''] + (K - M b4) W
                                                          + sum_c K1_c (W - u1_c) = 0
        W' fixed:    W'(x) = 0                     hinge: e_L W''(x-) = Kh [W'],
                                                          e_R W''(x+) = Kh [W']
        otherwise:   [W'] = 0,  e [W''] - (Kt - J b4) W' = 0

    every derivative being d^n W / dxi^n = beta_s^n * (scaled row), each row divided
    by the largest of its segment factors (so a uniform beam gets the rows of
    W^(n) / beta^n).  In the damped basis the derivative factors are 1, ``e`` is
    ``e (1 + i eta)``, a spring ``K`` with a parallel dashpot ``C`` is ``K + i W C``
    (``W = w / w_scale``) and the divisors are constants, so that every entry stays
    entire in ``w``.  The ``shear``, ``moment`` and ``mass_eqs`` entries of the result
    say where a load enters (:func:`frf`).
    """
    nseg = len(model.seg)
    bs = basis.bs
    e_seg = basis.e
    masses = model.masses
    cols, mass_cols, ncol = [], [], 0
    for j in range(nseg + 1):
        mass_cols.append(list(range(ncol, ncol + len(masses[j]))))
        ncol += len(masses[j])
        if j < nseg:
            cols.append(ncol)
            ncol += 4
    b4 = basis.b4
    rows = []
    shear_eq, moment_eq = {}, {}

    def row_of(side, order):
        return basis.row(side, order, cols)

    def combine(terms, sign=1) -> dict:
        """sum of factor * W^(order) / (largest factor) over terms (side, order, factor)."""
        scale = max(abs(f) for _s, _o, f in terms if f != 0)
        row: dict = {}
        for side, order, f in terms:
            if f != 0:
                _add(row, row_of(side, order), sign * f / scale)
        return row, scale

    for j in [0, nseg] + list(range(1, nseg)):
        node = model.nodes[j]
        left = (j - 1, True) if j > 0 else None
        right = (j, False) if j < nseg else None
        sides = [s for s in (left, right) if s is not None]
        ref = right if right is not None else left
        sign = 1 if right is not None else -1

        def jump(order, ei_weighted=True, left=left, right=right):
            """Terms of [e W^(order)] (or [W^(order)]), right side minus left side."""
            terms = []
            for side, s in ((right, 1), (left, -1)):
                if side is not None:
                    f = s * bs[side[0]] ** order
                    terms.append((side, order, f * e_seg[side[0]] if ei_weighted else f))
            return terms

        # order 0
        if node.fix_w:
            rows.extend(row_of(side, 0) for side in sides)
        elif len(sides) == 2:
            rows.append(combine(jump(0, False))[0])
        # order 1
        if node.fix_t:
            rows.append(row_of(ref, 1))
        elif len(sides) == 2 and node.hinge is None:
            rows.append(combine(jump(1, False))[0])
        # order 2: moments
        if node.hinge is not None:
            kink = jump(1, False)
            for side in (left, right):
                f = bs[side[0]] ** 2 * e_seg[side[0]]
                terms = [(side, 2, f)] + [(s, o, -node.hinge * g) for s, o, g in kink]
                rows.append(combine(terms)[0])
        elif not node.fix_t:
            row, scale = combine(jump(2), sign)
            coef = node.kt - node.j * b4
            if coef != 0:
                _add(row, row_of(ref, 1), -sign * coef * bs[ref[0]] / scale)
            moment_eq[j] = (len(rows), sign / scale)
            rows.append(row)
        # order 3: shear
        if not node.fix_w:
            row, scale = combine(jump(3), sign)
            w_row = row_of(ref, 0)
            coef = basis.stiffness(node.k, node.c) - node.m * b4
            if coef != 0:
                _add(row, w_row, sign * coef / scale)
            for chain, cs, uc in zip(
                node.chains, node.chain_c, _chain_cols(node, mass_cols[j]), strict=True
            ):
                k1 = basis.stiffness(chain[0][0], cs[0])
                _add(row, w_row, sign * k1 / scale)
                row[uc] = row.get(uc, 0) - sign * k1 / scale
            shear_eq[j] = (len(rows), sign / scale)
            rows.append(row)
    w_rows, mass_eqs = [], []
    for j in range(nseg + 1):
        w_row = row_of((j, False) if j < nseg else (nseg - 1, True), 0)
        w_rows.append(w_row)
        node = model.nodes[j]
        for chain, cs, uc in zip(
            node.chains, node.chain_c, _chain_cols(node, mass_cols[j]), strict=True
        ):
            # stage i: -K_i u_{i-1} + (K_i + K_{i+1} - M_i b4) u_i - K_{i+1} u_{i+1} = 0, u_0 = W
            for i, (k, m) in enumerate(chain):
                k_next = chain[i + 1][0] if i + 1 < len(chain) else 0
                scale = basis.mass_scale(k, k_next, m)
                k = basis.stiffness(k, cs[i])
                if i + 1 < len(chain):
                    k_next = basis.stiffness(k_next, cs[i + 1])
                row = {}
                if i == 0:
                    _add(row, w_row, -k / scale)
                else:
                    row[uc + i - 1] = -k / scale
                row[uc + i] = (k + k_next - m * b4) / scale
                if k_next:
                    row[uc + i + 1] = -k_next / scale
                mass_eqs.append((len(rows), 1 / scale))
                rows.append(row)
    return _System(rows, ncol, w_rows, mass_cols, cols, shear_eq, moment_eq, mass_eqs)


def _chain_cols(node: _Node, cols: list) -> list:
    """Column of the first mass of each chain hung at ``node`` (its masses follow)."""
    firsts, i = [], 0
    for chain in node.chains:
        firsts.append(cols[i])
        i += len(chain)
    return firsts


# ------------------------------------------------------ Wittrick-Williams counting


class _Degenerate(Exception):
    """A pivot was exactly zero: retry at a slightly different trial frequency."""


def _segment_stiffness(beta, beta2, beta3, ell):
    """Exact dynamic stiffness of a segment, DOFs (W0, W0', W1, W1') in xi units.

    Energy form ``int (W''^2 - beta^4 W^2) dxi``; the symmetric 4x4 matrix is::

        [[k00,  k01,  k02,  k03],
         [k01,  k11, -k03,  k13],
         [k02, -k03,  k00, -k01],
         [k03,  k13, -k01,  k11]]

    (closed form of B A^-1, checked against a numerical solve in the tests).
    Returns ((k00, k01, k02, k03, k11, k13), number of clamped-clamped natural
    frequencies of the segment strictly below beta, delta).  All entries are divided
    by cosh(x) top and bottom, so nothing overflows.
    """
    x = beta * ell
    extra = _extra_dps(x)
    with mp.workdps(mp.dps + extra):
        c, s = mpmath.cos_sin(x)
        t = mpmath.exp(-x)
        t2 = t * t
        h = 2 * t / (1 + t2)  # 1 / cosh x
        th = (1 - t2) / (1 + t2)  # tanh x
        delta = h - c  # (1 - cos x cosh x) / cosh x
        if delta == 0:
            raise _Degenerate
        inv = 1 / delta
        b1, b2, b3 = beta * inv, beta2 * inv, beta3 * inv
        ks = (
            b3 * (s + c * th),
            b2 * s * th,
            -b3 * (s * h + th),
            b2 * (1 - c * h),
            b1 * (s - c * th),
            b1 * (th - s * h),
        )
    if extra:
        ks = tuple(+v for v in ks)
        delta = +delta
    i = int(mpmath.floor(x / mp.pi))
    j0 = i - (1 - (-1) ** i * (1 if delta > 0 else -1)) // 2
    return ks, j0, delta


def segment_stiffness_matrix(beta, ell):
    """The 4x4 segment dynamic stiffness (nested lists, current mp precision); for tests."""
    ks, _, _ = _segment_stiffness(beta, beta**2, beta**3, ell)
    k00, k01, k02, k03, k11, k13 = ks
    return [
        [k00, k01, k02, k03],
        [k01, k11, -k03, k13],
        [k02, -k03, k00, -k01],
        [k03, k13, -k01, k11],
    ]


def _condense_chain(chain, b4):
    """Eliminate the masses of one chain (from its tip), the beam point held.

    Returns (number of negative pivots, product of the pivots over their positive
    envelopes, the stiffness the chain adds to the beam point's W).  The pivots are
    ``p_i = K_i + q_i`` with ``q_n = -M_n b4``, ``q_i = -M_i b4 + K_{i+1} q_{i+1} / p_{i+1}``
    (a Sturm sequence of the chain's tridiagonal ``K - w^2 M``); the beam point gets
    ``K_1 q_1 / p_1`` (for one stage ``-K M b4 / (K - M b4)``), free of cancellation.
    """
    neg, prod = 0, mpf(1)
    q = piv = None
    for i in range(len(chain) - 1, -1, -1):
        k, m = chain[i]
        mb = m * b4
        if q is None:
            q, envelope = -mb, k + mb
        else:
            k_next = chain[i + 1][0]
            q, envelope = -mb + k_next * q / piv, k + k_next + mb
        piv = k + q
        if piv == 0:
            raise _Degenerate
        if piv < 0:
            neg += 1
        prod *= piv / envelope
    return neg, prod, chain[0][0] * q / piv


def _eliminate(block: list, coupling, scales: list):
    """Symmetric Gaussian elimination of a node block (small, dense) with its coupling
    rows to the next node's (W, W').  Returns (negative pivots, product of pivot / scale,
    the carry ``G^T D^-1 G`` as (c00, c01, c11))."""
    n = len(block)
    d = [list(r) for r in block]
    g = [list(r) for r in coupling] if coupling is not None else None
    neg, prod = 0, mpf(1)
    c00 = c01 = c11 = mpf(0)
    for p in range(n):
        piv = d[p][p]
        if piv == 0:
            raise _Degenerate
        if piv < 0:
            neg += 1
        prod *= piv / scales[p]
        for r in range(p + 1, n):
            f = d[r][p] / piv
            if f != 0:
                for c in range(p + 1, n):
                    d[r][c] -= f * d[p][c]
                if g is not None:
                    g[r][0] -= f * g[p][0]
                    g[r][1] -= f * g[p][1]
        if g is not None:
            g0, g1 = g[p]
            c00 += g0 * g0 / piv
            c01 += g0 * g1 / piv
            c11 += g1 * g1 / piv
    return neg, prod, (c00, c01, c11)


def _chain(model: _Model, beta):
    """Wittrick-Williams: (number of natural frequencies strictly below beta > 0, F).

    J = J0 + s{K}: J0 sums the clamped-clamped frequencies of the segments below
    their own beta (the mass DOFs and massless springs contribute none), s{K} is the
    number of negative pivots of the symmetric Gaussian elimination of the dynamic
    stiffness matrix, eliminating node by node along the beam (the masses of every
    chain hung at a node first, from the chain's tip, then the node's W and W', or
    W, W'(x-), W'(x+) at a hinge; a fixed W or W' is not a DOF).

    F = det(K) * prod_j delta_j (delta_j = (1 - cos x_j cosh x_j) / cosh x_j) is
    the determinant of the dynamic stiffness with the segment poles removed,
    divided by a positive power-law envelope (beta^4 per node block, k + m beta^4
    per mass); it is only used as a cheap function to interpolate on while
    polishing, the bracket being decided by the count.  A general piece (the model cut by
    :func:`_refine` with the counts of :func:`_mesh_pieces`) has J0 = 0 and no pole below
    beta: its stiffness from exp(A h), delta 1.
    """
    nseg = len(model.seg)
    prod = mpf(1)
    beta2 = beta * beta
    beta3 = beta2 * beta
    b4 = beta4 = beta2 * beta2
    neg = 0
    # Schur complement carried from the previous node onto (W, W') of this node
    c00 = c01 = c11 = mpf(0)
    prev = None
    gens = model.seg_gen or [None] * nseg
    pieces: dict = {}  # the stiffness of the general pieces, computed once per kind of piece
    for j in range(nseg + 1):
        node = model.nodes[j]
        if j < nseg and gens[j] is not None:  # a general piece: J0 = 0 (_mesh_pieces)
            ks = _general_stiffness(model, j, beta, pieces)
        elif j < nseg:
            a, e = model.seg_a[j], model.seg_e[j]
            if a == 1:
                ks, n0, delta = _segment_stiffness(beta, beta2, beta3, model.seg[j])
            else:
                b = beta * a
                ks, n0, delta = _segment_stiffness(b, b * b, b * b * b, model.seg[j])
            if e != 1:
                ks = tuple(e * v for v in ks)
            neg += n0
            prod *= delta
        d00, d01, d11 = -c00, -c01, -c11
        if prev is not None:  # end block of segment j-1
            d00 += prev[0]
            d01 -= prev[1]
            d11 += prev[4]
        if node.k != 0 or node.m != 0:
            d00 += node.k - node.m * b4
        if node.kt != 0 or node.j != 0:
            d11 += node.kt - node.j * b4
        for chain in node.chains:
            if len(chain) == 1:  # one spring-mass (the common case, inline)
                k, m = chain[0]
                piv = k - m * b4
                if piv == 0:
                    raise _Degenerate
                if piv < 0:
                    neg += 1
                prod *= piv / (k + m * b4)
                d00 -= k * m * b4 / piv  # k - k^2 / piv: the mass condensed onto W
            else:
                n_chain, p_chain, condensed = _condense_chain(chain, b4)
                neg += n_chain
                prod *= p_chain
                d00 += condensed
        # coupling rows (node j dof) -> (W, W') of node j+1
        g = None if j == nseg else ((ks[2], ks[3]), (-ks[3], ks[5]))
        if node.hinge is not None:  # DOFs W (unless fixed), W'(x-), W'(x+)
            kh = node.hinge
            block = [[d00 + ks[0], d01, ks[1]], [d01, d11 + kh, -kh], [ks[1], -kh, ks[4] + kh]]
            coupling = [g[0], (mpf(0), mpf(0)), g[1]]
            scales = [beta3, beta, beta]
            keep = [1, 2] if node.fix_w else [0, 1, 2]
            n_node, p_node, (c00, c01, c11) = _eliminate(
                [[block[r][c] for c in keep] for r in keep],
                [coupling[r] for r in keep],
                [scales[r] for r in keep],
            )
            neg += n_node
            prod *= p_node
            prev = ks
            continue
        if j < nseg:  # start block of segment j
            d00 += ks[0]
            d01 += ks[1]
            d11 += ks[4]
        free = (() if node.fix_w else (0,)) + (() if node.fix_t else (1,))
        if free == (0, 1):
            det = d00 * d11 - d01 * d01
            if det == 0:
                raise _Degenerate
            prod *= det / beta4
            if det < 0:
                neg += 1
            elif d00 < 0:
                neg += 2
            if g is not None:
                # carry = G^T S^-1 G with S^-1 = [[d11, -d01], [-d01, d00]] / det
                (g00, g01), (g10, g11) = g
                y00 = (d11 * g00 - d01 * g10) / det
                y01 = (d11 * g01 - d01 * g11) / det
                y10 = (d00 * g10 - d01 * g00) / det
                y11 = (d00 * g11 - d01 * g01) / det
                c00 = g00 * y00 + g10 * y10
                c01 = g00 * y01 + g10 * y11
                c11 = g01 * y01 + g11 * y11
        elif len(free) == 1:
            dd = d00 if free[0] == 0 else d11
            if dd == 0:
                raise _Degenerate
            prod *= dd / (beta3 if free[0] == 0 else beta)
            if dd < 0:
                neg += 1
            if g is not None:
                g0, g1 = g[free[0]]
                c00, c01, c11 = g0 * g0 / dd, g0 * g1 / dd, g1 * g1 / dd
        else:
            c00 = c01 = c11 = mpf(0)
        prev = ks if j < nseg else None
    return neg, prod


def _chain_safe(model: _Model, beta):
    eps = mpf(2) ** (-mp.prec + 30)
    for attempt in range(8):
        try:
            return _chain(model, beta * (1 - eps * 4**attempt) if attempt else beta)
        except _Degenerate:
            continue
    raise RuntimeError(f"Wittrick-Williams count degenerate near beta={beta}")


# ------------------------------------------------------------------ root finding


def _beta_of(model: _Model, w):
    return mpmath.sqrt(w / model.w_scale)


def _anderson_bjorck(f, a, fa, b, fb, tol):
    """Root of f in the bracket [a, b] (fa, fb of opposite signs) to within tol.

    Anderson-Bjorck regula falsi with a bisection step whenever the bracket has
    not halved in three steps, and a step of tol / 2 across the root once the
    iterates converge from one side.
    """
    width, stall = abs(b - a), 0
    for _ in range(2000):
        if abs(b - a) <= tol or fa == 0 or fb == 0:
            break
        if stall >= 3:
            z, stall, width = (a + b) / 2, 0, abs(b - a) / 2
        else:
            z = b - fb * (b - a) / (fb - fa)
            if abs(z - b) < tol / 2:
                z = b + (tol / 2 if a > b else -tol / 2)
            elif not min(a, b) < z < max(a, b):
                z = (a + b) / 2
        fz = f(z)
        if (fz > 0) == (fb > 0):
            m = 1 - fz / fb
            fa = fa * (m if m > 0 else mpf(0.5))
        else:
            a, fa = b, fb
        b, fb = z, fz
        if abs(b - a) <= width / 2:
            width, stall = abs(b - a), 0
        else:
            stall += 1
    if fa == 0:
        return a
    if fb == 0:
        return b
    return (a + b) / 2


def _polish(lo, jlo, hi, dps: int, chain_fn, det_fn):
    """The one natural frequency in [lo, hi) (the count is jlo at lo, jlo + 1 at hi).

    1. Anderson-Bjorck on G = +|F| below the root, -|F| above it, the side
       being decided by the Wittrick-Williams count (cheap, always bracketed).
    2. The global determinant has the last word: it must change sign over
       [r (1 - d), r (1 + d)] (intersected with the slightly widened bracket),
       d = 1e-(dps + 4); if it does not (F and the count lose accuracy when the
       root coincides with a natural frequency of a part of the structure that
       the elimination clamps), d is widened step by step and the root of the
       determinant is then found by Anderson-Bjorck inside that window.
    """
    while lo == 0:  # the root is > 0: move the lower end off zero
        mid = hi / 2
        if chain_fn(mid)[0] > jlo:
            hi = mid
        else:
            lo = mid
    tol = lo * mpf(10) ** (-(dps + 8))

    def g(z):
        count, value = chain_fn(z)
        return -abs(value) if count > jlo else abs(value)

    root = _anderson_bjorck(g, lo, g(lo), hi, g(hi), tol)

    edge = mpf(10) ** (-(dps + 4))
    w_min, w_max = lo * (1 - edge), hi * (1 + edge)
    digits = dps + 4
    while True:
        d = mpf(10) ** (-digits)
        a, b = max(w_min, root * (1 - d)), min(w_max, root * (1 + d))
        fa, fb = det_fn(a), det_fn(b)
        if fa == 0:
            return a
        if fb == 0:
            return b
        if (fa > 0) != (fb > 0):
            if digits >= dps + 4:
                return root
            return _anderson_bjorck(det_fn, a, fa, b, fb, tol)
        if a == w_min and b == w_max:
            raise RuntimeError(
                f"global determinant does not change sign on [{lo}, {hi}] although the "
                "Wittrick-Williams count isolates one root there"
            )
        digits -= 3


class _Solver:
    """Scene at working precision with the count, chain and determinant evaluators."""

    def __init__(self, scene, dps: int, model: _Model | None = None):
        self.model = _undamped_model(scene) if model is None else model
        self.nrigid = rigid_body_mode_count(scene)
        self.dps = dps
        self._cache: dict = {}
        self._meshes: dict = {}

    def mesh(self, beta) -> _Model:
        """The model, its general segments cut for the count at beta (:func:`_mesh_pieces`;
        the global determinant does not depend on the cut)."""
        if not self.model.general:
            return self.model
        key = tuple(_mesh_pieces(self.model, beta**4, count=True))
        if key not in self._meshes:
            self._meshes[key] = _refine(self.model, key)
        return self._meshes[key]

    def chain(self, beta):
        key = mpf(beta)
        if key not in self._cache:
            model = self.mesh(beta)
            with mp.workdps(_work_dps(model, 2 * self.dps, beta)):
                self._cache[key] = _chain_safe(model, +beta)
        return self._cache[key]

    def count(self, beta) -> int:
        return self.chain(beta)[0]

    def det(self, beta):
        # stiff springs: the K / beta^3 shear terms cancel against the mass rows
        model = self.mesh(beta)
        stiff = max(model.k_max / beta**3, model.kr_max / beta)
        extra = int(math.ceil(float(mpmath.log10(stiff)))) if stiff > 1 else 0
        if model.general:
            extra += _general_dps(model, beta**4)
        with mp.workdps(_work_dps(model, self.dps, beta) + extra):
            return _global_det(model, +beta)

    def check_stable(self) -> None:
        """With a compression somewhere, no natural frequency squared below 0: the count at
        a tiny beta must be the number of rigid-body modes (else ValueError: buckled)."""
        gens = [g for g in self.model.seg_gen or () if g is not None]
        if any(g.P + g.kg < 0 for g in gens):
            tiny = mpf(10) ** -3
            if self.count(tiny) != self.nrigid:
                raise ValueError(
                    f"{self.count(tiny)} natural frequencies below beta = 1e-3 besides the "
                    f"{self.nrigid} rigid-body modes: the compression buckles the beam"
                )

    def solve(self, lo, jlo, hi, jhi, want_lo: int, want_hi: int) -> list:
        """Betas of the eigenvalues with indices in [want_lo, want_hi) inside [lo, hi)."""
        out = []
        stack = [(lo, jlo, hi, jhi)]
        rel = mpf(10) ** (-(self.dps + 5))
        while stack:
            a, ja, b, jb = stack.pop()
            if jb <= ja or jb <= want_lo or ja >= want_hi:
                continue
            if jb - ja == 1:
                out.append(_polish(a, ja, b, self.dps, self.chain, self.det))
                continue
            if b - a <= rel * b:
                mult = min(jb, want_hi) - max(ja, want_lo)
                out.extend([(a + b) / 2] * mult)
                continue
            mid = (a + b) / 2
            jm = self.count(mid)
            stack.append((mid, jm, b, jb))
            stack.append((a, ja, mid, jm))
        return sorted(out)


def frequencies(scene, n_modes: int, dps: int = 40) -> list:
    """Lowest ``n_modes`` natural frequencies (rad/s, ascending, with multiplicity).

    Zero-frequency rigid-body modes are included as exact zeros.
    """
    if n_modes <= 0:
        return []
    with mp.workdps(dps + _GUARD_DPS):
        solver = _Solver(scene, dps)
        solver.check_stable()
        result = [b * b * solver.model.w_scale for b in _lowest(solver, n_modes)]
    with mp.workdps(dps):
        return [+w for w in result]


def _lowest(solver: _Solver, n_modes: int) -> list:
    """The betas of the lowest ``n_modes`` natural frequencies (rigid-body zeros first)."""
    nrigid = solver.nrigid
    if n_modes <= nrigid:
        return [mpf(0)] * n_modes
    # an upper bound off the rational multiples of pi, where bare-beam roots sit
    hi = mp.pi * (n_modes + 1) * (1 + mpmath.sqrt(2) / 100)
    grow = 2
    if solver.model.general:  # shear lowers the roots, and a count far above them is dear
        hi, grow = hi / 4, mpf("1.25")
    jhi = solver.count(hi)
    while jhi < n_modes:
        hi *= grow
        jhi = solver.count(hi)
    return [mpf(0)] * nrigid + solver.solve(mpf(0), nrigid, hi, jhi, nrigid, n_modes)


def band(scene, w_lo, w_hi, dps: int = 40) -> list:
    """All natural frequencies in [w_lo, w_hi] (rad/s, ascending, with multiplicity).

    Roots within a relative ~1e-dps of either edge may or may not be included.
    """
    with mp.workdps(dps + _GUARD_DPS):
        solver = _Solver(scene, dps)
        solver.check_stable()
        model, nrigid = solver.model, solver.nrigid
        w_lo, w_hi = _num(w_lo), _num(w_hi)
        if w_hi < w_lo or w_hi <= 0:
            return []
        hi = _beta_of(model, w_hi) * (1 + mpf(10) ** (-(dps + 10)))
        zeros = []
        if w_lo <= 0:
            lo, jlo = mpf(0), nrigid
            zeros = [mpf(0)] * nrigid
        else:
            lo = _beta_of(model, w_lo) * (1 - mpf(10) ** (-(dps + 10)))
            jlo = solver.count(lo)
        jhi = solver.count(hi)
        betas = solver.solve(lo, jlo, hi, jhi, jlo, jhi)
        result = zeros + [b * b * model.w_scale for b in betas]
    with mp.workdps(dps):
        return [+w for w in result]


def count_below(scene, w, dps: int = 40) -> int:
    """Number of natural frequencies strictly below ``w`` > 0 (Wittrick-Williams)."""
    with mp.workdps(dps + _GUARD_DPS):
        solver = _Solver(scene, dps)
        beta = _beta_of(solver.model, _num(w))
        if not beta > 0:
            raise ValueError("count_below needs w > 0")
        return solver.count(beta)


def _null_vectors(model: _Model, beta, m: int):
    """The ``m`` right singular vectors of the global matrix with the smallest singular
    values, and the mass columns of each node."""
    rows, ncol, w_rows, mass_cols = _global_rows(model, beta)
    A = mpmath.matrix(len(rows), ncol)
    for r, row in enumerate(rows):
        for col, val in row.items():
            A[r, col] = val
    _u, s, V = mpmath.svd_r(A)
    order = sorted(range(ncol), key=lambda i: s[i])[:m]
    return [[V[i, c] for c in range(ncol)] for i in order], w_rows, mass_cols


def _shape_mesh(model: _Model, beta) -> _Model:
    """The model with its general segments cut for the global system at beta."""
    return _refine(model, _mesh_pieces(model, beta**4, count=False)) if model.general else model


def mode_at_attachments(scene, w, dps: int = 40):
    """Mode shape at a natural frequency ``w``: for every hanging mass (the mass of each
    spring-mass, each mass of each oscillator chain; sorted by x, stable) the beam's
    deflection at its attachment point and the mass's displacement, from the null vector
    (SVD) of the global matrix. Arbitrary scale; floats."""
    with mp.workdps(dps + _GUARD_DPS):
        model = _undamped_model(scene)
        beta = _beta_of(model, _num(w))
        model = _shape_mesh(model, beta)
        with mp.workdps(mp.dps + (_general_dps(model, beta**4) if model.general else 0)):
            (v,), w_rows, mass_cols = _null_vectors(model, beta, 1)
        beam, masses = [], []
        for j, cols in enumerate(mass_cols):
            deflection = sum(val * v[col] for col, val in w_rows[j].items())
            for col in cols:
                beam.append(float(deflection))
                masses.append(float(v[col]))
    return beam, masses


def global_determinant(scene, w, dps: int = 40):
    """Determinant of the scaled global system at frequency ``w`` > 0 (rad/s).

    Entire in ``w`` up to a positive factor; its zeros are the natural
    frequencies.  Only its sign and zeros are meaningful.
    """
    with mp.workdps(dps + _GUARD_DPS):
        solver = _Solver(scene, dps)
        beta = _beta_of(solver.model, _num(w))
        if not beta > 0:
            raise ValueError("global_determinant needs w > 0")
        det = solver.det(beta)
    with mp.workdps(dps):
        return +det


def eigenspace(scene, w, m: int, xs, dps: int = 40):
    """Basis of the eigenspace at a natural frequency ``w`` (rad/s) of multiplicity ``m``:
    the right singular vectors of the global matrix for its ``m`` smallest singular values,
    each evaluated as ``[W(x) for x in xs] + [u_i for every hanging mass]`` (the mass of
    each spring-mass and each mass of each oscillator chain in chain order, the attachments
    sorted by x, stable; point masses move with the beam and are not listed; deflections in
    the units of the scene). Floats, arbitrary basis and scale; independent of any transfer
    matrix (but exp(A s) in a general segment). For ``w = 0`` pass the rigid-body count as
    ``m``: the basis is that of the rigid motions (straight pieces, kinks at free hinges) the
    ends, supports, springs, foundations and axial forces allow.
    """
    with mp.workdps(dps + _GUARD_DPS):
        model = _undamped_model(scene)
        if _num(w) == 0:
            return _rigid_space(scene, m, xs)
        beta = _beta_of(model, _num(w))
        model = _shape_mesh(model, beta)
        if model.general:
            mp.dps += _general_dps(model, beta**4)
        vectors, _w_rows, mass_cols = _null_vectors(model, beta, m)
        nseg = len(model.seg)
        starts = [node.xi for node in model.nodes]
        bases = []
        for x in xs:
            xi = _num(x) / model.length
            j = min(max(k for k in range(nseg) if starts[k] <= xi), nseg - 1)
            sloc, b = xi - starts[j], beta * model.seg_a[j]
            base = 4 * j + sum(len(cols) for cols in mass_cols[: j + 1])
            gen = model.seg_gen[j]
            if gen is not None:  # y(s) = row 0 of exp(A s) times the state at the piece's start
                A = _field_matrix(gen, model.seg_e[j], model.seg_mu[j], 0, beta**4)
                funcs = tuple(_expm(A, sloc)[0])
            else:
                funcs = (
                    mpmath.cos(b * sloc),
                    mpmath.sin(b * sloc),
                    mpmath.exp(-b * sloc),
                    mpmath.exp(b * (sloc - model.seg[j])),
                )
            bases.append((base, funcs))
        out = []
        for v in vectors:
            row = [float(mpmath.fdot(funcs, v[base : base + 4])) for base, funcs in bases]
            row += [float(v[c]) for cols in mass_cols for c in cols]
            out.append(row)
    return out


def _hanging_mass_positions(scene) -> list:
    """x of every hanging mass, in the order of :func:`eigenspace`."""
    out = []
    for att in _attachments(scene):
        kind = _kind(att)
        if kind in ("spring_mass", "oscillator_chain"):
            out += [_frac(_get(att, "x"))] * len(_stages(kind, att))
    return sorted(out)


def _rigid_space(scene, m, xs):
    """The rigid motions (hanging masses moving with their beam point) the scene allows."""
    hinges, rows = _rigid_constraints(scene)
    basis = _null_space(rows, 2 + len(hinges))
    if len(basis) != m:
        raise ValueError(f"{m} rigid-body modes asked for, the scene allows {len(basis)}")
    points = [_frac(x) for x in xs] + _hanging_mass_positions(scene)

    def motion(v, x):
        kinks = zip(v[2:], hinges, strict=True)
        return v[0] + v[1] * x + sum(c * (x - h) for c, h in kinks if x > h)

    return [[float(motion(v, x)) for x in points] for v in basis]


# ============================================================ damping and forced response


def _krylov(z, x) -> list:
    """Krylov (Cauchy) functions of a segment of dimensionless length ``x`` for
    ``lam^4 = z`` (any complex z): ``K_j = sum_k z^k x^(4k+j) / (4k+j)!``, j = 0..3, i.e.
    ``S = (cosh + cos) / 2``, ``T = (sinh + sin) / (2 lam)``, ``U = (cosh - cos) / (2 lam^2)``,
    ``V = (sinh - sin) / (2 lam^3)`` of ``lam x``.  Entire in z: no branch of the fourth
    root matters.  Power series while ``|lam x| <= 2`` (no cancellation there), else the
    closed forms with the principal root (exact for any root)."""
    y = z * x**4
    if abs(y) <= 16:
        eps = mpf(2) ** (-mp.prec - 8)
        out = []
        for j in range(4):
            term = x**j / math.factorial(j)
            total, biggest, n = term, abs(term), j
            while True:
                term = term * y / ((n + 1) * (n + 2) * (n + 3) * (n + 4))
                n += 4
                total += term
                size = abs(term)
                biggest = max(biggest, size)
                if size <= eps * biggest:
                    break
            out.append(total)
        return out
    lam = mpmath.root(z, 4)
    t = lam * x
    ch, sh, c, s = mpmath.cosh(t), mpmath.sinh(t), mpmath.cos(t), mpmath.sin(t)
    return [(ch + c) / 2, (sh + s) / (2 * lam), (ch - c) / (2 * lam**2), (sh - s) / (2 * lam**3)]


class _KrylovBasis:
    """The damped path's basis: the unknowns of a segment are its initial values
    ``(W, W', W'', W''')`` (xi derivatives, W in metres) at its left end; at its right end
    ``W^(n)(l) = sum_j a_j K_(j-n)(l)`` with ``K_(-m) = z K_(4-m)`` (the Krylov transfer),
    ``z = W^2 mu_s / (e_s (1 + i eta_s))``, ``W = w / w_scale``.  Every entry is entire in w."""

    def __init__(self, model: _Model, omega):
        self.omega = omega
        self.b4 = omega * omega  # (w / w_scale)^2 = beta^4
        self.bs = [1] * len(model.seg)  # raw derivatives: no scaling by powers of beta
        self.e = [
            e if eta == 0 else e * mpc(1, eta)
            for e, eta in zip(model.seg_e, model.seg_eta, strict=True)
        ]
        self.phi = []
        gens = model.seg_gen or [None] * len(model.seg)
        for ell, e, mu, gen in zip(model.seg, self.e, model.seg_mu, gens, strict=True):
            if gen is not None:  # a general segment: its rows come from _GeneralRows
                self.phi.append(None)
                continue
            z = self.b4 * mu / e
            k = _krylov(z, ell)
            phi = [[k[j - n] if j >= n else z * k[j - n + 4] for j in range(4)] for n in range(4)]
            self.phi.append(phi)

    def row(self, side, order: int, cols: list) -> dict:
        seg, at_end = side
        base = cols[seg]
        if not at_end:
            return {base + order: mpf(1)}
        return {base + j: v for j, v in enumerate(self.phi[seg][order]) if v != 0}

    def stiffness(self, k, c):
        """``K + i W C``: a spring with its parallel dashpot."""
        return k if c == 0 else k + mpc(0, 1) * self.omega * c

    @staticmethod
    def mass_scale(k, k_next, m):
        """A constant divisor (positive), so that the row stays entire in w."""
        return k + k_next + m


def _dashpot_rank(scene) -> int:
    """Rank of the grounded dashpots (c > 0) on the rigid motions: how many rigid-body
    modes they restrain (exact, Fractions)."""
    hinges, rows = _rigid_constraints(scene)
    basis = _null_space(rows, 2 + len(hinges))
    if not basis:
        return 0
    beam = _get(scene, "beam")
    edges = [Fraction(0)]
    for seg in _segments(beam):
        edges.append(edges[-1] + _frac(seg[0]))
    damp = []
    for att in _attachments(scene):
        if _kind(att) == "dashpot" and _num(_get(att, "c")) > 0:
            x = _snap(_frac(_get(att, "x")), edges, edges[-1])
            value = _rigid_value(x, hinges)
            damp.append([sum(a * b for a, b in zip(value, v, strict=True)) for v in basis])
    n = len(basis)
    return n - len(_null_space(damp, n)) if damp else 0


#: With a loss factor, a zero at w_d < -AXIS_TOL |w| is one of the w_d > 0 model's
#: continuation and not reported; within it, it is on the imaginary axis and reported (the
#: rule of mstmm.damped.AXIS_TOL, stated here again: this model imports nothing of mstmm).
AXIS_TOL = mpf("1e-9")
_TURN = mpf("0.5")  # largest change of arg accepted between neighbouring samples (rad)
_MAX_DEPTH = 44  # bisections of a contour piece before a zero is declared on the contour
_PIECES = 12  # initial pieces per contour edge


class _OnContour(ArithmeticError):
    """The function vanishes on (or numerically next to) the contour."""


class _Uncertified(RuntimeError):
    """The roots found and the argument-principle count disagree."""


def _arg_piece(f, a, fa, b, fb, depth: int, samples: list | None):
    mid = (a + b) / 2
    fm = f(mid)
    if fm == 0:
        raise _OnContour(mid)
    if samples is not None:
        samples.append((mid, fm))
    d1, d2 = mpmath.arg(fm / fa), mpmath.arg(fb / fm)
    if abs(d1) < _TURN and abs(d2) < _TURN:
        return d1 + d2
    if depth >= _MAX_DEPTH:
        raise _OnContour(mid)
    return _arg_piece(f, a, fa, mid, fm, depth + 1, samples) + _arg_piece(
        f, mid, fm, b, fb, depth + 1, samples
    )


def _arg_change(f, z0, z1, samples: list | None = None):
    """Continuous change of ``arg f`` along the segment ``z0 -> z1`` (radians): the segment
    cut into :data:`_PIECES`, each piece halved until the argument turns by less than
    :data:`_TURN` over each half (a zero at distance d from the contour turns it by ~pi
    over a length ~d, which forces the halving down to d).  Numerical, not interval-
    rigorous: two zeros conspiring within one sample spacing could hide each other."""
    pts = [z0 + (z1 - z0) * k / _PIECES for k in range(_PIECES + 1)]
    vals = [f(z) for z in pts]
    if any(v == 0 for v in vals):
        raise _OnContour(z0)
    if samples is not None:
        samples.extend(zip(pts, vals, strict=True))
    return mpmath.fsum(
        _arg_piece(f, a, fa, b, fb, 0, samples)
        for a, fa, b, fb in zip(pts, vals, pts[1:], vals[1:], strict=False)
    )


def _path_change(f, corners: list, samples: list | None = None):
    return mpmath.fsum(_arg_change(f, a, b, samples) for a, b in zip(corners, corners[1:]))


def _whole(value, what: str) -> int:
    n = int(mpmath.nint(value))
    if abs(value - n) > mpf("0.05"):
        raise _OnContour(f"{what} = {value} is not an integer")
    return n


class _DampedSolver:
    """A scene with the damped characteristic function and its argument-principle counts.

    ``F(w)``: determinant of the global system in the Krylov basis (entire in w; with a loss
    factor the analytic continuation of the w_d > 0 model, see :func:`damped_frequencies`);
    ``G(w) = F(w) / (w / w_scale)^a0``, a0 the order of the zero of F at w = 0 (2 per
    rigid-body mode, 1 less per rigid mode a grounded dashpot restrains), entire and
    nonzero at 0.
    """

    def __init__(self, scene, dps: int, points=()):
        self.scene = scene
        self.dps = dps
        self.model = model = _build(scene, points)
        self.nrigid = rigid_body_mode_count(scene)
        self.a0 = 2 * self.nrigid - _dashpot_rank(scene)
        self.viscous = all(eta == 0 for eta in model.seg_eta)  # F(-conj w) = conj F(w)
        self.undamped = not model.damped
        self.scale = model.w_scale
        gens = model.seg_gen or [None] * len(model.seg)
        self.reach = float(  # general segments: multiple shooting, no growth across them
            mpmath.fsum(
                a * ell for a, ell, g in zip(model.seg_a, model.seg, gens, strict=True) if g is None
            )
        )
        c_all = [node.c for node in model.nodes] + [
            c for node in model.nodes for cs in node.chain_c for c in cs
        ]
        self.c_max = max(c_all + [mpf(0)])

    def wp(self, omega, extra: int = 0) -> int:
        """Working digits at dimensionless frequency omega: the Krylov functions cancel by up
        to exp(2 |lam| l) across the system, stiff springs and dashpots by their ratio to
        the beam's stiffness."""
        r = float(abs(omega)) ** 0.5  # |beta|
        growth = int(2 * r * self.reach / math.log(10)) + 1
        m = self.model
        stiff = max(
            float(m.k_max) / (1 + r**3),
            float(m.kr_max) / (1 + r),
            float(self.c_max) * r * r / (1 + r**3),
        )
        digits = int(math.ceil(math.log10(stiff))) if stiff > 1 else 0
        if m.general:
            digits += _general_dps(m, omega * omega)
        return self.dps + _GUARD_DPS + growth + digits + extra

    def mesh(self, omega) -> _Model:
        """The model, its general segments cut for the global system at omega (any cut gives
        the same determinant, see the notes on general segments)."""
        if not self.model.general:
            return self.model
        return _refine(self.model, _mesh_pieces(self.model, omega * omega, count=False))

    def basis(self, model: _Model, omega):
        """The Krylov basis at omega, with :class:`_GeneralRows` on the general segments."""
        basis = _KrylovBasis(model, omega)
        return _GeneralRows(model, basis, omega * omega) if model.general else basis

    def F(self, w, extra: int = 0):
        """Characteristic function at w (rad/s, complex)."""
        omega = w / self.scale
        with mp.workdps(self.wp(omega, extra)):
            model = self.mesh(w / self.scale)
            system = _assemble(model, self.basis(model, w / self.scale))
            return _sparse_det(system.rows, system.ncol)

    def G(self, w):
        """F / (w / w_scale)^a0; at w = 0 (a sample of a contour through the origin), its
        value a relative 1e-12 up the imaginary axis (G is analytic and nonzero there)."""
        if self.a0 == 0:
            return self.F(w)
        if w == 0:
            w = mpc(0, self.scale * mpf(10) ** -12)
        omega = w / self.scale
        small = max(0, int(math.ceil(-float(mpmath.log10(abs(omega))))))
        extra = self.a0 * small
        value = self.F(w, extra)
        with mp.workdps(self.wp(omega, extra)):
            return value / omega**self.a0

    # ----------------------------------------------------------------- counts

    def zero_count(self, x0, x1, y0, y1) -> int:
        """Zeros of F in the rectangle x0 < w_d < x1, y0 < sigma < y1 (with multiplicity)."""
        corners = [mpc(x0, y0), mpc(x1, y0), mpc(x1, y1), mpc(x0, y1), mpc(x0, y0)]
        return _whole(_path_change(self.F, corners) / (2 * mp.pi), "winding number")

    def _half_path(self, width, lo, hi, samples=None):
        """Change of arg G along (0, lo) -> (width, lo) -> (width, hi) -> (0, hi): by the
        symmetry G(-conj w) = conj G(w) (viscous damping only) it is pi times the number of
        zeros of G in -width < w_d < width, lo < sigma < hi."""
        corners = [mpc(0, lo), mpc(width, lo), mpc(width, hi), mpc(0, hi)]
        return _whole(_path_change(self.G, corners, samples) / mp.pi, "symmetric count")

    def axis_zeros(self, width, lo, hi) -> int:
        """Zeros of G on the imaginary axis lo < sigma < hi (viscous damping only): the count
        in a strip |w_d| < eps, eps shrunk until it equals the number of sign changes of the
        real function G(i sigma) i^a0 (an odd multiplicity changes the sign: sign changes <=
        zeros on the axis <= zeros in the strip).  If it never does (an even multiplicity:
        exactly critical damping; or zeros within 1e-(dps/2) of the axis) the strip's count
        is taken."""
        phase = mpc(0, 1) ** self.a0
        eps = width / 64
        points: dict = {}
        for _ in range(4):
            samples: list = []
            strip = self._half_path(eps, lo, hi, samples)
            for z, _v in samples:
                if z.imag not in points and lo < z.imag < hi:
                    points[z.imag] = None
            for sigma in points:
                if points[sigma] is None:
                    points[sigma] = (self.G(mpc(0, sigma)) * phase).real
            values = [points[s] for s in sorted(points)]
            changes = sum(1 for a, b in zip(values, values[1:]) if (a > 0) != (b > 0))
            if changes == strip:
                return strip
            eps = eps / mpf(10) ** max(2, self.dps // 8)
        return strip

    def reported_count(self, width, lo, hi) -> int:
        """Reported roots (:func:`damped_frequencies`' convention) with 0 <= w_d < width,
        lo < sigma < hi, rigid-body zeros included when lo < 0 < hi."""
        rigid = self.nrigid if lo < 0 < hi else 0
        if self.viscous:
            n_sym = self._half_path(width, lo, hi)
            n_axis = self.axis_zeros(width, lo, hi)
            if (n_sym + n_axis) % 2:
                raise _OnContour(f"odd symmetric count {n_sym} + {n_axis}")
            return (n_sym + n_axis) // 2 + rigid
        corners = [mpc(0, lo), mpc(width, lo), mpc(width, hi), mpc(0, hi), mpc(0, lo)]
        return _whole(_path_change(self.G, corners) / (2 * mp.pi), "winding number") + rigid

    # ------------------------------------------------------------------- roots

    def _deflated(self, found, line):
        """F divided by (w - r)^m for the roots found (and their mirrors -conj r with viscous
        damping), so that a seed does not converge onto a root already taken."""
        factors = []
        for r, m, _axis in found:
            factors.append((r, m))
            if self.viscous and r.real != 0:
                factors.append((-r.conjugate(), m))

        def f(w):
            value = self.F(w)
            for r, m in factors:
                value /= (w - r) ** m
            return value

        return f

    def _secant(self, f, z0, line):
        """Secant iteration from the seed z0 (on the real axis / imaginary axis when
        ``line`` says so, where F is real and the iterates stay exactly on the line)."""
        tol = mpf(10) ** (-(self.dps + 6))
        step = mpf(10) ** -7
        z1 = z0 * (1 + step) if line else z0 * (1 + mpc(step, step))
        f0, f1 = f(z0), f(z1)
        for _ in range(200):
            if f1 == 0:
                return z1
            den = f1 - f0
            if den == 0:
                raise _Uncertified(f"secant stalled at {z1}")
            z2 = z1 - f1 * (z1 - z0) / den
            if line == "real":
                z2 = mpc(z2.real, 0)
            elif line == "axis":
                z2 = mpc(0, z2.imag)
            if abs(z2 - z1) <= tol * abs(z2):
                return self._verified(f, z2)
            z0, f0, z1, f1 = z1, f1, z2, f(z2)
        raise _Uncertified(f"secant did not converge from {z0}")

    def _verified(self, f, z):
        """``z`` if the Newton step there, with a central-difference derivative, is below
        1e-(dps + 3) |z|: a small secant step alone can come from a large difference of
        values rather than from a root."""
        h = abs(z) * mpf(10) ** (-(self.dps // 3))
        value = f(z)
        slope = (f(z + h) - f(z - h)) / (2 * h)
        if value != 0 and not abs(value) <= mpf(10) ** (-(self.dps + 3)) * abs(z * slope):
            raise _Uncertified(f"the secant method stopped at {z}, not a simple root")
        return z

    def _newton_multiple(self, z, m: int):
        """Modified Newton ``z - m F / F'`` for a root of multiplicity m, at m times the digits
        (the root of F ~ c (w - r)^m is only defined to 1/m of them)."""
        extra = (m - 1) * (self.dps + 10)
        tol = mpf(10) ** (-(self.dps + 6))
        with mp.workdps(mp.dps + extra):
            z = mpc(z)
            for _ in range(100):
                h = abs(z) * mpf(10) ** (-(self.dps + extra) // 2)
                f0 = self.F(z, extra)
                if f0 == 0:
                    return z
                d = (self.F(z + h, extra) - self.F(z - h, extra)) / (2 * h)
                step = m * f0 / d
                z -= step
                if abs(step) <= tol * abs(z):
                    return +z
        raise _Uncertified(f"Newton did not converge to the {m}-fold root near {z}")

    def _local_count(self, root, others: list) -> int:
        """Zeros of F in a small square around ``root`` (half-width |root| / 1000, or a third
        of the distance to the nearest of ``others``)."""
        rad = min([abs(root) / 1000] + [abs(o - root) / 3 for o in others if o != root])
        return self.zero_count(root.real - rad, root.real + rad, root.imag - rad, root.imag + rad)

    def _refine_multiple(self, root, m: int, line):
        root = self._newton_multiple(root, m)
        if line == "real":
            return mpc(root.real, 0)
        if line == "axis":
            return mpc(0, root.imag)
        return root

    def polish(self, seeds: list) -> list:
        """Roots from the seeds: ``[root, multiplicity, on the imaginary axis]``, each a zero
        of F to ~1e-(dps + 6) relative.  Seeds equal to 1e-9 relative form a cluster whose
        multiplicity the argument principle confirms around the polished root; a seed that
        converges onto a root already found although F was deflated by it raises that
        root's multiplicity if a count around it says so, else it is dropped, as is a seed
        the secant method does not converge from (the final count decides)."""
        clusters: list = []
        for z in seeds:
            if clusters and abs(z - clusters[-1][0]) <= mpf("1e-9") * abs(z):
                clusters[-1][1] += 1
            else:
                clusters.append([z, 1])
        found: list = []
        close = mpf(10) ** (-(self.dps // 2))
        for index, (z, m) in enumerate(clusters):
            if self.undamped:
                line = "real"
                z = mpc(z.real, 0)
            elif self.viscous and z.real == 0:
                line = "axis"
            else:
                line = None
            try:
                if m == 1:
                    try:
                        root = self._secant(self._deflated(found, line), z, line)
                    except _Uncertified:
                        if line != "axis":
                            raise
                        line = None  # the FE model called it overdamped, but it is not
                        root = self._secant(self._deflated(found, None), z + abs(z) / 100, None)
                else:
                    root = self._refine_multiple(z, m, line)
                if self.viscous and line is None and abs(root.real) <= close * abs(root):
                    line = "axis"  # an overdamped root the FE model saw as a close pair
                    root = self._secant(self._deflated(found, line), mpc(0, root.imag), line)
            except _Uncertified:
                continue
            if self.viscous and root.real < 0:
                root = -root.conjugate()
            elif root.real < -AXIS_TOL * abs(root):
                continue  # a zero of the w_d > 0 model's continuation, not reported
            others = [o[0] for o in found] + [c[0] for i, c in enumerate(clusters) if i != index]
            same = next((o for o in found if abs(o[0] - root) <= close * abs(root)), None)
            if same is not None:
                local = self._local_count(same[0], others)
                if local > same[1]:
                    same[0] = self._refine_multiple(same[0], local, line)
                    same[1] = local
                continue
            if m > 1 and self._local_count(root, others) != m:
                raise _Uncertified(f"{m} seeds at {root} but another number of zeros around it")
            found.append([root, m, line == "axis"])
        return found

    def roots(self, need: int, n_elements=None) -> list:
        """The lowest ``need`` non-zero reported roots, certified (see
        :func:`damped_frequencies`); FE seeds, the mesh doubled when the count disagrees."""
        n_el = n_elements or max(24, 4 * need + 16)
        n_seeds = need + max(4, need // 2)
        failures = []
        for _attempt in range(3):
            if self.model.general:  # no FE model of them: the undamped roots as seeds
                seeds = self._undamped_seeds(n_seeds)
                what = f"{n_seeds} undamped seeds"
            else:
                spectrum = _fem().damped_spectrum(self.scene, n_el)
                seeds = [mpc(complex(w)) for w in spectrum.roots]
                what = f"{n_el} elements"
            try:
                return self._certified(need, seeds)
            except (_Uncertified, _OnContour) as exc:
                failures.append(f"{what}: {exc}")
                n_el *= 2
                n_seeds *= 2
        raise RuntimeError("damped roots not certified: " + "; ".join(failures))

    def _undamped_seeds(self, n: int) -> list:
        """The lowest n nonzero natural frequencies of the scene without its dashpots and
        loss factors (undamped reference, 15 digits), as seeds of a general scene (an
        overdamped root has no such seed: the count then refuses the result)."""
        nodes = [
            replace(node, c=mpf(0), chain_c=[[mpf(0)] * len(cs) for cs in node.chain_c])
            for node in self.model.nodes
        ]
        model = replace(self.model, nodes=nodes, seg_eta=[mpf(0)] * len(self.model.seg))
        with mp.workdps(15 + _GUARD_DPS):
            solver = _Solver(self.scene, 15, model)
            solver.check_stable()
            betas = _lowest(solver, solver.nrigid + n)[solver.nrigid :]
            return [mpc(b * b * model.w_scale) for b in betas]

    def _certified(self, need: int, seeds: list) -> list:
        if len(seeds) < need + 1:
            raise _Uncertified(f"the FE model has only {len(seeds)} roots")
        # seeds up to the first one clearly past the need-th in w_d, then 30 % more
        edge = max(seeds[need - 1].real, 0)
        beyond = [s.real for s in seeds[need:] if s.real > edge * (1 + mpf("1e-3"))]
        if not beyond:
            raise _Uncertified("no FE root beyond the wanted ones")
        upto = beyond[0] * mpf("1.3")
        while True:  # widened while the seeds do not give a root beyond the wanted ones
            chosen = [s for s in seeds if s.real <= upto]
            found = sorted(self.polish(chosen), key=lambda r: _order_key(r[0]))
            flat = [r for r in found for _ in range(r[1])]
            if len(flat) > need:
                last = flat[need - 1][0].real
                tie = last * (1 + mpf(10) ** (-(self.dps // 2)))
                later = [r[0].real for r in flat if r[0].real > tie]
                if later:
                    break
            if len(chosen) == len(seeds):
                raise _Uncertified(f"{len(flat)} roots polished, {need + 1} needed")
            upto *= mpf("1.5")
        width = (last + later[0]) / 2 if last > 0 else later[0] / 2
        inside = [r for r in found if r[0].real < width]
        sigma = [r[0].imag for r in inside] + [s.imag for s in seeds if s.real < width]
        hi = mpf("1.5") * max(sigma + [mpf(0)]) + width / 4
        lo = -width * mpf("0.1372")
        if self.viscous:
            expected = sum(m * (1 if axis else 2) for _r, m, axis in inside)
            got = self._half_path(width, lo, hi)
        else:
            expected = sum(m for _r, m, _a in inside)
            # the left edge on the imaginary axis, or just left of the roots on it (a loss
            # factor leaves a grounded oscillator's roots there: w_d = 0 is reported)
            axis = [abs(r) for r, _m, _a in inside if r.real <= 0 and r != 0]
            x0 = -AXIS_TOL * min(axis) if axis else mpf(0)
            corners = [mpc(x0, lo), mpc(width, lo), mpc(width, hi), mpc(x0, hi), mpc(x0, lo)]
            got = _whole(_path_change(self.G, corners) / (2 * mp.pi), "winding number")
        if got != expected:
            raise _Uncertified(
                f"{got} zeros in the rectangle w_d < {mpmath.nstr(width, 8)}, "
                f"{mpmath.nstr(lo, 5)} < sigma < {mpmath.nstr(hi, 8)} (symmetric with viscous "
                f"damping), {expected} found"
            )
        self.certificate = (width, lo, hi)
        return [r[0] for r in found for _ in range(r[1])][:need]


def _order_key(w):
    """Rigid-body zeros, then overdamped roots (w_d = 0) by sigma, then by w_d (sigma)."""
    if w == 0:
        return (0, mpf(0), mpf(0))
    if abs(w.real) <= AXIS_TOL * abs(w):  # on the axis to its accuracy
        return (1, w.imag, mpf(0))
    return (2, w.real, w.imag)


def _fem():
    """The finite-element model (``tests/reference_fem.py``, imported when first needed):
    only its roots' seeds are used."""
    import reference_fem

    return reference_fem


def _cnum(value):
    """Exact conversion of a real or complex number to mpf / mpc (current precision)."""
    if isinstance(value, mpc):
        return +value
    if isinstance(value, complex):
        return mpc(value)
    try:
        return _num(value)
    except TypeError:
        return mpc(complex(value))


def damped_global_determinant(scene, w, dps: int = 40):
    """Characteristic function ``F(w)`` of the damped scene at complex ``w`` (rad/s).

    The determinant of the global system (the same node conditions as
    :func:`global_determinant`) in the Krylov basis: the unknowns of each segment are
    ``W, W', W'', W'''`` at its left end, the right end follows by the Krylov functions
    ``S, T/lam, U/lam^2, V/lam^3`` of ``lam^4 = mbar w^2 / EI*`` (entire in lam^4), the
    mass equations multiplied out, the dashpots as ``k + i w c``, a segment's EI as
    ``EI (1 + i eta)``, rows divided by constants only.  So ``F`` is entire in w (no poles,
    no branch), its zeros are the natural frequencies, the zero at w = 0 has order a0 =
    2 per rigid-body mode less one per rigid mode a grounded dashpot restrains.  With a
    loss factor it is the analytic continuation of the w_d > 0 model.  Arbitrary scale.
    """
    with mp.workdps(dps + _GUARD_DPS):
        solver = _DampedSolver(scene, dps)
        value = solver.F(_cnum(w))
    with mp.workdps(dps):
        return +mpc(value)


def damped_zero_count(scene, w_d_min, w_d_max, sigma_min, sigma_max, dps: int = 30) -> int:
    """Zeros (with multiplicity) of :func:`damped_global_determinant` in the open rectangle
    ``w_d_min < w_d < w_d_max``, ``sigma_min < sigma < sigma_max`` of the w-plane
    (``w = w_d + i sigma``, rad/s), by the argument principle: the change of arg F around
    the rectangle, sampled adaptively (:func:`_arg_change`).  Every zero counts, those at
    w = 0 (a0 of them) and, with viscous damping, the mirror images ``-conj w`` too.
    ``ArithmeticError`` if a zero lies on (or within ~1e-13 of a side's length of) the edge.
    """
    with mp.workdps(dps + _GUARD_DPS):
        solver = _DampedSolver(scene, dps)
        return solver.zero_count(*(_num(v) for v in (w_d_min, w_d_max, sigma_min, sigma_max)))


def damped_count(scene, w_d_max, sigma_min, sigma_max, dps: int = 30) -> int:
    """Number of reported natural frequencies (the convention of
    :func:`damped_frequencies`, with multiplicity) with ``0 <= w_d < w_d_max`` and
    ``sigma_min < sigma < sigma_max`` (rad/s), by the argument principle; the
    rigid-body zeros count when ``sigma_min < 0 < sigma_max``.

    With viscous damping only (F(-conj w) = conj F(w)): ``(N_sym + N_axis) / 2``, N_sym
    the zeros of ``G = F / w^a0`` in ``|w_d| < w_d_max`` (from the change of arg along the
    right half of the contour), N_axis those on the imaginary axis
    (:meth:`_DampedSolver.axis_zeros`).  With a loss factor: the zeros of G in the
    rectangle itself, whose left side is the imaginary axis (ArithmeticError if a zero
    lies on it).  Choose ``sigma_min < 0`` when roots on the real axis (undamped modes)
    are meant to count: a side through a root raises ArithmeticError.
    """
    with mp.workdps(dps + _GUARD_DPS):
        solver = _DampedSolver(scene, dps)
        args = (_num(w_d_max), _num(sigma_min), _num(sigma_max))
        return solver.reported_count(*args)


def damped_frequencies(scene, n_modes: int, dps: int = 30, n_elements: int | None = None):
    """Lowest ``n_modes`` complex natural frequencies ``w = w_d + i sigma`` (rad/s, mpc) of a
    damped scene, with multiplicity, for time dependence ``exp(i w t)`` (``sigma > 0``: a
    decaying mode).

    Model: a dashpot ``c`` parallel to a spring (``k -> k + i w c``, spring-masses and
    oscillator chains), grounded dashpots ``EI [W'''] = -(i w c) W``, and a loss factor
    ``EI -> EI (1 + i eta)`` per segment.  The roots are the zeros of
    :func:`damped_global_determinant`.  Reported: the roots with ``w_d >= 0``.  With viscous
    damping only the zeros come in pairs ``w, -conj w`` and one of each pair is reported;
    an overdamped root lies on the imaginary axis (``w_d = 0``, reported once per zero).  A
    loss factor is a frequency-domain model: EI (1 + i eta) is taken for w_d > 0 (where
    it dissipates), the function continued analytically; its zeros in the right half plane
    (and on the imaginary axis) are reported, the pairing does not hold there.  The
    ``rigid_body_mode_count`` rigid-body modes are reported as exact zeros (0j), whatever
    the dashpots (F's zero at 0 has order 2 n_rigid - r, r the rigid motions the grounded
    dashpots restrain: each of those also has an overdamped root, not a zero).

    Order: rigid-body zeros, overdamped roots by ascending sigma, then ascending w_d (then
    sigma).  With all c = 0 and eta = 0 the roots are those of :func:`frequencies` (real,
    sigma exactly 0).

    What is guaranteed.  Seeds are the finite-element roots of ``tests/reference_fem.py``
    (``n_elements``, default ``4 n + 16``, at least 24; only a starting point).  Each is
    polished by the secant method on F (deflated by the roots already found; on the real
    axis for an undamped scene and on the imaginary axis for an overdamped seed, where F
    is real and the iterates stay exactly on the line) to ~1e-(dps + 6) relative, and
    kept only if a Newton step there is below 1e-(dps + 3) of the root; identical seeds
    (exact multiple roots) by Newton with the multiplicity at m times the digits, the
    multiplicity confirmed by a count in a small square around the root.  A seed that
    does not converge, or lands again on a root already found, is dropped (or raises
    that root's multiplicity if a count around it says so).  Then the argument principle
    must find exactly as many zeros in the rectangle ``-0.14 W < sigma < S``,
    ``0 <= w_d < W`` (with viscous damping ``|w_d| < W``, mirror images included, by the
    symmetry), as were polished there: W halfway between the n-th root's w_d and the
    next larger one, S = 1.5 times the largest decay rate of the roots and FE seeds with
    ``w_d < W``, plus W / 4.  Otherwise the mesh is doubled (twice), then RuntimeError.
    So no root with ``w_d < W`` is missed, unless its sigma exceeds S (the count does not
    look there; the FE model, all of whose eigenvalues were seeds, has none there either)
    or the contour sampling was fooled (two zeros within one sample spacing of the
    contour, see :func:`_arg_change`; the sampling is adaptive but not interval-rigorous).
    The test suite withholds seeds and checks that the count catches each one.
    """
    if n_modes <= 0:
        return []
    with mp.workdps(dps + _GUARD_DPS):
        solver = _DampedSolver(scene, dps)
        nrigid = solver.nrigid
        roots = solver.roots(n_modes - nrigid, n_elements) if n_modes > nrigid else []
        result = [mpc(0)] * nrigid + roots
    with mp.workdps(dps):
        return [+mpc(w) for w in result[:n_modes]]


_INPUTS = {("force", "x"), ("moment", "x"), ("force", "mass")}
_OUTPUTS = {("displacement", "x"), ("rotation", "x"), ("displacement", "mass")}


def _io(spec, allowed: set, what: str) -> tuple:
    try:
        quantity, where, at = spec
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{what} must be (quantity, 'x' or 'mass', x or j): {spec!r}") from exc
    if (quantity, where) not in allowed:
        raise ValueError(f"{what} {spec!r}: expected one of {sorted(allowed)}")
    if where == "mass" and (int(at) != at or at < 0):
        raise ValueError(f"hanging mass index must be an integer >= 0: {at!r}")
    return quantity, where, at


def frf(scene, input, output, omegas, dps: int = 30) -> list:
    """Receptance (complex, SI units) of ``output`` to a unit harmonic ``input`` at each
    frequency of ``omegas`` (rad/s, real or complex), time dependence ``exp(i w t)``, by a
    direct solve of the global system of :func:`damped_global_determinant` (Krylov basis)
    with the load in its right-hand side.  Undamped or damped scenes.

    Inputs: ``("force", "x", x)``, a point force on the beam, ``EI [W'''] = F`` (a tip
    force on a cantilever gives ``W = F x^2 (3 L - x) / (6 EI)``); ``("moment", "x", x)``, a
    couple doing positive work on a positive rotation W', ``EI [W''] = -C``;
    ``("force", "mass", j)``, a force on hanging mass j, ``(k + i w c - m w^2) u - (k + i w
    c) W = F``.  Outputs: ``("displacement", "x", x)`` (m/N or 1/N), ``("rotation", "x", x)``
    (W'), ``("displacement", "mass", j)``.  Hanging masses: the attachments sorted by x
    (stable), each spring-mass its mass, each chain its masses from the beam outwards;
    point masses (kind ``mass``) move with the beam and are not listed.  A force at a
    fixed W (clamped / pinned end, support) or a moment at a fixed W' goes into the
    reaction (response 0).  A moment or rotation at a hinge is ambiguous: ValueError.
    Exactly at a natural frequency the system is singular (ZeroDivisionError).
    """
    src = _io(input, _INPUTS, "input")
    dst = _io(output, _OUTPUTS, "output")
    if isinstance(omegas, (int, float, complex, mpf, mpc)):
        omegas = [omegas]
    points = [spec[2] for spec in (src, dst) if spec[1] == "x"]
    out = []
    with mp.workdps(dps + _GUARD_DPS):
        solver = _DampedSolver(scene, dps, points)
        model = solver.model
        n_hung = sum(len(stages) for stages in model.masses)
        nodes = []  # index in point_nodes of the input, of the output (None: a hanging mass)
        for quantity, where, point in (src, dst):
            if where == "mass":
                if point >= n_hung:
                    raise ValueError(f"hanging mass {point} of {n_hung}")
                nodes.append(None)
                continue
            k = -1 if nodes else 0  # the input's point comes first
            j = model.point_nodes[k]
            if quantity in ("moment", "rotation") and model.nodes[j].hinge is not None:
                raise ValueError(f"{quantity} at the hinge at x = {point}: ambiguous")
            nodes.append(k)
        length, ei0 = model.length, model.ei0
        for w in omegas:
            omega = _cnum(w) / model.w_scale
            with mp.workdps(solver.wp(omega)):
                mesh = solver.mesh(_cnum(w) / model.w_scale)  # general segments cut
                basis = solver.basis(mesh, _cnum(w) / model.w_scale)
                system = _assemble(mesh, basis)
                n = system.ncol
                A = mpmath.matrix(n, n)
                for r, row in enumerate(system.rows):
                    for col, val in row.items():
                        A[r, col] = val
                b = mpmath.matrix(n, 1)
                quantity, where, point = src
                if where == "mass":
                    row, factor = system.mass_eqs[point]
                    b[row] = factor * length**3 / ei0
                else:
                    j = mesh.point_nodes[nodes[0]]
                    eqs = system.shear if quantity == "force" else system.moment
                    if j in eqs:
                        row, factor = eqs[j]
                        sign = 1 if quantity == "force" else -1
                        b[row] = sign * factor * length ** (3 if quantity == "force" else 2) / ei0
                x = mpmath.lu_solve(A, b)
                quantity, where, point = dst
                if where == "mass":
                    col = [c for cols in system.mass_cols for c in cols][point]
                    value = x[col]
                else:
                    j = mesh.point_nodes[nodes[1]]
                    nseg = len(mesh.seg)
                    side = (j, False) if j < nseg else (nseg - 1, True)
                    order = 0 if quantity == "displacement" else 1
                    row = basis.row(side, order, system.cols)
                    value = mpmath.fsum(v * x[c] for c, v in row.items()) / length**order
            out.append(mpc(value))
    with mp.workdps(dps):
        return [+v for v in out]

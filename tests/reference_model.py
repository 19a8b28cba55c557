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

Public API: :func:`frequencies`, :func:`band`, :func:`global_determinant`,
:func:`count_below`, :func:`rigid_body_mode_count`, :func:`eigenspace`,
:func:`mode_at_attachments`, :func:`segment_stiffness_matrix`, :data:`KINDS`.

Scenes are dicts in the TOML layout or objects with the same attributes:
``beam`` with ``left``, ``right`` and either ``length``, ``EI``,
``mass_per_length`` or ``segments`` (each ``length``, ``EI``,
``mass_per_length``, from the left end); ``attachments``, each with ``type``
(dict) or ``kind`` (object), default ``spring_mass``, and ``x`` plus: ``k``, ``m``
(spring_mass); ``m``, ``J`` = 0 (mass); ``k`` (spring, rotational_spring);
nothing (support); ``k`` = 0 (hinge, strictly inside); lists ``k``, ``m``
(oscillator_chain, beam to tip).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction

import mpmath
from mpmath import mp, mpf

__all__ = [
    "KINDS",
    "band",
    "count_below",
    "eigenspace",
    "frequencies",
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
    if kind not in KINDS:
        raise ValueError(f"unsupported attachment type {kind!r}")
    return kind


def _segments(beam) -> list:
    """``(length, EI, mass_per_length)`` of each beam segment from the left end (raw values)."""
    segments = _opt(beam, "segments")
    if segments:
        return [(_get(s, "length"), _get(s, "EI"), _get(s, "mass_per_length")) for s in segments]
    return [(_get(beam, "length"), _get(beam, "EI"), _get(beam, "mass_per_length"))]


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


def _build(scene) -> _Model:
    """Nondimensionalise ``scene`` at the current mp precision.

    Units: L = total length, EI0 and mbar0 those of the first segment; then
    K = k L^3 / EI0, M = m / (mbar0 L), Kt = k_theta L / EI0, J = J / (mbar0 L^3).
    """
    beam = _get(scene, "beam")
    raw = _segments(beam)
    seg_len = [_num(s[0]) for s in raw]
    seg_ei = [_num(s[1]) for s in raw]
    seg_mu = [_num(s[2]) for s in raw]
    _positive("segment length, EI and mass_per_length", *seg_len, *seg_ei, *seg_mu)
    length = mpmath.fsum(seg_len)
    ei0, mu0 = seg_ei[0], seg_mu[0]
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
            node.chains.append([(k * length**3 / ei0, m / (mu0 * length)) for k, m in chain])
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
    seg, seg_e, seg_a = [], [], []
    edges = [mpf(0)] + bounds
    for a, b in zip(xs, xs[1:], strict=False):
        s = max(i for i, e in enumerate(edges) if e <= a)
        e_rel, mu_rel = seg_ei[s] / ei0, seg_mu[s] / mu0
        seg.append((b - a) / length)
        seg_e.append(e_rel)
        seg_a.append(mpf(1) if e_rel == mu_rel else mpmath.root(mu_rel / e_rel, 4))
    w_scale = mpmath.sqrt(ei0 / mu0) / length**2
    min_x = min(a * ell for a, ell in zip(seg_a, seg, strict=True))
    return _Model(
        left, right, nodes, seg, seg_e, seg_a, w_scale, min(seg), min_x, k_max, kr_max, length
    )


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


def _rigid_constraints(scene) -> tuple:
    """Rigid motions ``W(x) = a + b x + sum_h c_h (x - x_h)_+`` (kinks c_h at the free
    hinges x_h): the hinge positions and the exact linear constraints on (a, b, c...)
    from the ends, supports, springs and rotational springs to ground."""
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
        return [Fraction(1), x] + [x - h if x > h else Fraction(0) for h in hinges]

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
    return hinges, rows


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


def _global_rows(model: _Model, beta):
    """Rows of the global system, the column count, the deflection row at each node and
    the mass columns of each node.

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
    W^(n) / beta^n).
    """
    nseg = len(model.seg)
    bs = [beta * a for a in model.seg_a]
    trig = []
    for ell, b in zip(model.seg, bs, strict=True):
        x = b * ell
        trig.append((mpmath.cos(x), mpmath.sin(x), mpmath.exp(-x)))
    masses = model.masses
    cols, mass_cols, ncol = [], [], 0
    for j in range(nseg + 1):
        mass_cols.append(list(range(ncol, ncol + len(masses[j]))))
        ncol += len(masses[j])
        if j < nseg:
            cols.append(ncol)
            ncol += 4
    b4 = beta**4
    rows = []

    def row_of(side, order):
        return _scaled_row(side[0], side[1], order, trig, cols)

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
                    terms.append((side, order, f * model.seg_e[side[0]] if ei_weighted else f))
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
                f = bs[side[0]] ** 2 * model.seg_e[side[0]]
                terms = [(side, 2, f)] + [(s, o, -node.hinge * g) for s, o, g in kink]
                rows.append(combine(terms)[0])
        elif not node.fix_t:
            row, scale = combine(jump(2), sign)
            coef = node.kt - node.j * b4
            if coef != 0:
                _add(row, row_of(ref, 1), -sign * coef * bs[ref[0]] / scale)
            rows.append(row)
        # order 3: shear
        if not node.fix_w:
            row, scale = combine(jump(3), sign)
            w_row = row_of(ref, 0)
            coef = node.k - node.m * b4
            if coef != 0:
                _add(row, w_row, sign * coef / scale)
            for chain, uc in zip(node.chains, _chain_cols(node, mass_cols[j]), strict=True):
                k1 = chain[0][0]
                _add(row, w_row, sign * k1 / scale)
                row[uc] = row.get(uc, 0) - sign * k1 / scale
            rows.append(row)
    w_rows = []
    for j in range(nseg + 1):
        w_row = _scaled_row(*((j, False) if j < nseg else (nseg - 1, True)), 0, trig, cols)
        w_rows.append(w_row)
        node = model.nodes[j]
        for chain, uc in zip(node.chains, _chain_cols(node, mass_cols[j]), strict=True):
            # stage i: -K_i u_{i-1} + (K_i + K_{i+1} - M_i b4) u_i - K_{i+1} u_{i+1} = 0, u_0 = W
            for i, (k, m) in enumerate(chain):
                k_next = chain[i + 1][0] if i + 1 < len(chain) else 0
                scale = k + k_next + m * b4
                row = {}
                if i == 0:
                    _add(row, w_row, -k / scale)
                else:
                    row[uc + i - 1] = -k / scale
                row[uc + i] = (k + k_next - m * b4) / scale
                if k_next:
                    row[uc + i + 1] = -k_next / scale
                rows.append(row)
    return rows, ncol, w_rows, mass_cols


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
    polishing, the bracket being decided by the count.
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
    for j in range(nseg + 1):
        node = model.nodes[j]
        if j < nseg:
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

    def __init__(self, scene, dps: int):
        self.model = _build(scene)
        self.nrigid = rigid_body_mode_count(scene)
        self.dps = dps
        self._cache: dict = {}

    def chain(self, beta):
        key = mpf(beta)
        if key not in self._cache:
            with mp.workdps(_work_dps(self.model, 2 * self.dps, beta)):
                self._cache[key] = _chain_safe(self.model, +beta)
        return self._cache[key]

    def count(self, beta) -> int:
        return self.chain(beta)[0]

    def det(self, beta):
        # stiff springs: the K / beta^3 shear terms cancel against the mass rows
        stiff = max(self.model.k_max / beta**3, self.model.kr_max / beta)
        extra = int(math.ceil(float(mpmath.log10(stiff)))) if stiff > 1 else 0
        with mp.workdps(_work_dps(self.model, self.dps, beta) + extra):
            return _global_det(self.model, +beta)

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
        nrigid = solver.nrigid
        if n_modes <= nrigid:
            result = [mpf(0)] * n_modes
        else:
            # an upper bound off the rational multiples of pi, where bare-beam roots sit
            hi = mp.pi * (n_modes + 1) * (1 + mpmath.sqrt(2) / 100)
            jhi = solver.count(hi)
            while jhi < n_modes:
                hi *= 2
                jhi = solver.count(hi)
            betas = solver.solve(mpf(0), nrigid, hi, jhi, nrigid, n_modes)
            result = [mpf(0)] * nrigid + [b * b * solver.model.w_scale for b in betas]
    with mp.workdps(dps):
        return [+w for w in result]


def band(scene, w_lo, w_hi, dps: int = 40) -> list:
    """All natural frequencies in [w_lo, w_hi] (rad/s, ascending, with multiplicity).

    Roots within a relative ~1e-dps of either edge may or may not be included.
    """
    with mp.workdps(dps + _GUARD_DPS):
        solver = _Solver(scene, dps)
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


def mode_at_attachments(scene, w, dps: int = 40):
    """Mode shape at a natural frequency ``w``: for every hanging mass (the mass of each
    spring-mass, each mass of each oscillator chain; sorted by x, stable) the beam's
    deflection at its attachment point and the mass's displacement, from the null vector
    (SVD) of the global matrix. Arbitrary scale; floats."""
    with mp.workdps(dps + _GUARD_DPS):
        model = _build(scene)
        beta = _beta_of(model, _num(w))
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
    matrix. For ``w = 0`` pass the rigid-body count as ``m``: the basis is that of the rigid
    motions (straight pieces, kinks at free hinges) the ends, supports and springs allow.
    """
    with mp.workdps(dps + _GUARD_DPS):
        model = _build(scene)
        if _num(w) == 0:
            return _rigid_space(scene, m, xs)
        beta = _beta_of(model, _num(w))
        vectors, _w_rows, mass_cols = _null_vectors(model, beta, m)
        nseg = len(model.seg)
        starts = [node.xi for node in model.nodes]
        bases = []
        for x in xs:
            xi = _num(x) / model.length
            j = min(max(k for k in range(nseg) if starts[k] <= xi), nseg - 1)
            sloc, b = xi - starts[j], beta * model.seg_a[j]
            base = 4 * j + sum(len(cols) for cols in mass_cols[: j + 1])
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

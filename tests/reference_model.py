"""Independent high-precision reference model for the tests of ``mstmm``.

Natural frequencies of a uniform Euler-Bernoulli beam carrying spring-mass
attachments, computed WITHOUT transfer matrices, with mpmath:

* the frequencies are the zeros of the determinant of a *global* linear system
  (4 coefficients per beam segment plus one displacement per mass), assembled
  from the end conditions, the continuity / shear-jump conditions at the
  attachment points and the equations of motion of the masses
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

The tests check this against the tip-mass cantilever
``1 + cos b cosh b + mu b (cos b sinh b - sin b cosh b) = 0`` (stiff-spring
limit) and against ``tests/data/reference.json``.

Nondimensionalisation
---------------------
``xi = x / L``, ``beta = lam L`` with ``lam^4 = mbar w^2 / EI``, so
``w = beta^2 sqrt(EI / mbar) / L^2``; ``K = k L^3 / EI`` and
``M = m / (mbar L)`` (then ``m w^2 L^3 / EI = M beta^4``).

Spring-masses at a clamped or pinned end see a fixed point (W = 0 there): each
is a decoupled oscillator and ``sqrt(k/m)`` is a natural frequency of the
system (it is counted and returned like any other).

What is guaranteed about not missing roots
------------------------------------------
* Counting.  ``J(beta)`` = number of natural frequencies (with multiplicity,
  rigid-body modes included) strictly below ``beta`` is computed by the
  Wittrick-Williams algorithm: J = J0 + s{K}, J0 = clamped-clamped
  frequencies of the segments below beta (closed form), s{K} = number of
  negative pivots of the exact dynamic stiffness matrix (segments' closed
  form + springs + masses), eliminated node by node.  It is exact as long as
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
* Rigid-body modes are counted from the end conditions (dimension of the
  rigid motions ``a + b x`` they allow: free-free 2, pinned-free 1,
  sliding-free / free-sliding / sliding-sliding 1, else 0) and returned as
  exact zeros; the tests check that this equals ``J(0+)``.
* Working precision: ``dps + 20`` digits for the global determinant, plus
  digits for short segments, low frequency and stiff springs
  (log10(K / beta^3)); results agree between dps = 30 and dps = 50 to a few
  1e-32 on stiff, soft, heavy, close-positioned and 50-attachment scenes.

Public API: :func:`frequencies`, :func:`band`, :func:`global_determinant`,
:func:`count_below`, :func:`rigid_body_mode_count`, :func:`segment_stiffness_matrix`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

import mpmath
from mpmath import mp, mpf

__all__ = [
    "band",
    "count_below",
    "frequencies",
    "global_determinant",
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


# --------------------------------------------------------------------------- input


def _get(obj, name):
    if isinstance(obj, dict):
        return obj[name]
    return getattr(obj, name)


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


def _end(value) -> str:
    raw = getattr(value, "value", value)
    if not isinstance(raw, str):
        raw = getattr(value, "name", str(value))
    key = str(raw).strip().lower().replace("-", "_").replace(" ", "_")
    if key not in _ALIASES:
        raise ValueError(f"unknown end condition {value!r}")
    return _ALIASES[key]


@dataclass
class _Model:
    left: str
    right: str
    seg: list  # dimensionless segment lengths (all > 0), len = number of nodes - 1
    masses: list  # per node: list of (K, M)
    w_scale: mpf  # w = beta^2 * w_scale
    min_seg: mpf
    k_max: mpf  # largest K = k L^3 / EI (0 without attachments)


def _build(scene) -> _Model:
    """Nondimensionalise ``scene`` at the current mp precision."""
    beam = _get(scene, "beam")
    length = _num(_get(beam, "length"))
    ei = _num(_get(beam, "EI"))
    mbar = _num(_get(beam, "mass_per_length"))
    if not (length > 0 and ei > 0 and mbar > 0):
        raise ValueError("length, EI and mass_per_length must be positive")
    left = _end(_get(beam, "left"))
    right = _end(_get(beam, "right"))
    try:
        atts = list(_get(scene, "attachments"))
    except (KeyError, AttributeError):
        atts = []
    groups: dict = {}
    for att in atts:
        kind = att.get("type", "spring_mass") if isinstance(att, dict) else "spring_mass"
        if kind != "spring_mass":
            raise ValueError(f"unsupported attachment type {kind!r}")
        x = _num(_get(att, "x"))
        k = _num(_get(att, "k"))
        m = _num(_get(att, "m"))
        if not (0 <= x <= length):
            raise ValueError(f"attachment position {x} outside [0, L]")
        if not (k > 0 and m > 0):
            raise ValueError("spring-mass needs k > 0 and m > 0")
        groups.setdefault(x, []).append((k * length**3 / ei, m / (mbar * length)))
    xs = sorted(x for x in groups if 0 < x < length)
    nodes = [mpf(0)] + xs + [length]
    seg = [(nodes[j + 1] - nodes[j]) / length for j in range(len(nodes) - 1)]
    masses = [groups.get(x, []) for x in nodes]
    w_scale = mpmath.sqrt(ei / mbar) / length**2
    k_max = max((k for group in masses for k, _m in group), default=mpf(0))
    return _Model(left, right, seg, masses, w_scale, min(seg), k_max)


def _extra_dps(x) -> int:
    """Digits lost to cancellation for a segment of dimensionless wave length x = beta l."""
    if x >= 1:
        return 0
    if not x > 0:
        raise ValueError("trial frequency must be positive")
    return int(4 * math.ceil(-float(mpmath.log10(x)))) + 5


def _work_dps(model: _Model, dps: int, beta) -> int:
    extra = _extra_dps(beta * model.min_seg)
    extra += int(3 * math.ceil(max(0.0, -float(mpmath.log10(model.min_seg)))))
    return dps + _GUARD_DPS + extra


def rigid_body_mode_count(scene) -> int:
    """Dimension of the rigid motions ``Y = a + b x`` allowed by the end conditions."""
    beam = _get(scene, "beam")
    left, right = _end(_get(beam, "left")), _end(_get(beam, "right"))
    rows = []  # constraints on (a, b) with x/L = 0 at the left end and 1 at the right end
    rows += {"clamped": [(1, 0), (0, 1)], "pinned": [(1, 0)], "sliding": [(0, 1)]}.get(left, [])
    rows += {"clamped": [(1, 1), (0, 1)], "pinned": [(1, 1)], "sliding": [(0, 1)]}.get(right, [])
    rank = 0
    if rows:
        rank = 1
        first = rows[0]
        if any(first[0] * r[1] - first[1] * r[0] != 0 for r in rows[1:]):
            rank = 2
    return 2 - rank


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
    the mass columns of each node."""
    nseg = len(model.seg)
    trig = []
    for ell in model.seg:
        x = beta * ell
        trig.append((mpmath.cos(x), mpmath.sin(x), mpmath.exp(-x)))
    # columns: masses of node 0, seg 0, masses of node 1, seg 1, ..., seg n-1, masses of node n
    cols, mass_cols, ncol = [], [], 0
    for j in range(nseg + 1):
        mass_cols.append(list(range(ncol, ncol + len(model.masses[j]))))
        ncol += len(model.masses[j])
        if j < nseg:
            cols.append(ncol)
            ncol += 4
    b3 = beta**3
    b4 = beta**4
    rows = []

    def node_point(j):  # (segment, at_end) where the deflection at node j is evaluated
        return (j, False) if j < nseg else (nseg - 1, True)

    def shear_forces(row, j, sign):
        # row += sign * sum_i (K_i / beta^3) (W(x_j) - u_i)
        seg_j, at_end = node_point(j)
        w_row = _scaled_row(seg_j, at_end, 0, trig, cols)
        for (k, _m), uc in zip(model.masses[j], mass_cols[j], strict=True):
            _add(row, w_row, sign * k / b3)
            row[uc] = row.get(uc, 0) - sign * k / b3

    for order in _END_ROWS[model.left]:
        row = _scaled_row(0, False, order, trig, cols)
        if order == 3:
            shear_forces(row, 0, +1)
        rows.append(row)
    for order in _END_ROWS[model.right]:
        row = _scaled_row(nseg - 1, True, order, trig, cols)
        if order == 3:
            shear_forces(row, nseg, -1)
        rows.append(row)
    for j in range(1, nseg):
        for order in range(4):
            row = _scaled_row(j, False, order, trig, cols)
            _add(row, _scaled_row(j - 1, True, order, trig, cols), -1)
            if order == 3:
                shear_forces(row, j, +1)
            rows.append(row)
    for j in range(nseg + 1):
        seg_j, at_end = node_point(j)
        w_row = _scaled_row(seg_j, at_end, 0, trig, cols)
        for (k, m), uc in zip(model.masses[j], mass_cols[j], strict=True):
            scale = k + m * b4
            row = {}
            _add(row, w_row, -k / scale)
            row[uc] = (k - m * b4) / scale
            rows.append(row)
    w_rows = [_scaled_row(*node_point(j), 0, trig, cols) for j in range(nseg + 1)]
    return rows, ncol, w_rows, mass_cols


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


def _chain(model: _Model, beta):
    """Wittrick-Williams: (number of natural frequencies strictly below beta > 0, F).

    J = J0 + s{K}: J0 sums the clamped-clamped frequencies of the segments below
    beta (the mass DOFs and massless springs contribute none), s{K} is the number
    of negative pivots of the symmetric Gaussian elimination of the dynamic
    stiffness matrix, eliminating node by node along the beam (mass DOFs of a
    node first, then its W and W').

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
        if j < nseg:
            ks, n0, delta = _segment_stiffness(beta, beta2, beta3, model.seg[j])
            neg += n0
            prod *= delta
        d00, d01, d11 = -c00, -c01, -c11
        if prev is not None:  # end block of segment j-1
            d00 += prev[0]
            d01 -= prev[1]
            d11 += prev[4]
        if j < nseg:  # start block of segment j
            d00 += ks[0]
            d01 += ks[1]
            d11 += ks[4]
        for k, m in model.masses[j]:
            piv = k - m * b4
            if piv == 0:
                raise _Degenerate
            if piv < 0:
                neg += 1
            prod *= piv / (k + m * b4)
            d00 -= k * m * b4 / piv  # k - k^2 / piv: the mass condensed onto W
        if j == 0:
            free = _END_FREE_DOFS[model.left]
        elif j == nseg:
            free = _END_FREE_DOFS[model.right]
        else:
            free = (0, 1)
        if j == nseg:
            g = None
        else:
            # coupling rows (node j dof) -> (W, W') of node j+1
            g = ((ks[2], ks[3]), (-ks[3], ks[5]))
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
        stiff = self.model.k_max / beta**3
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


def mode_at_attachments(scene, w, dps: int = 40):
    """Mode shape at a natural frequency ``w``: the beam's deflection at each attachment and
    each mass's displacement (attachments sorted by x), from the null vector (SVD) of the
    global matrix. Arbitrary scale; floats."""
    with mp.workdps(dps + _GUARD_DPS):
        model = _build(scene)
        beta = _beta_of(model, _num(w))
        rows, ncol, w_rows, mass_cols = _global_rows(model, beta)
        A = mpmath.matrix(len(rows), ncol)
        for r, row in enumerate(rows):
            for col, val in row.items():
                A[r, col] = val
        _u, _s, V = mpmath.svd_r(A)
        v = [V[V.rows - 1, i] for i in range(ncol)]
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
    each evaluated as ``[W(x) for x in xs] + [u_i for every mass]`` (masses sorted by x as
    the scene's attachments; deflections in the units of the scene). Floats, arbitrary
    basis and scale; independent of any transfer matrix. For ``w = 0`` pass the rigid-body
    count as ``m``: the basis is that of the rigid motions ``a + b x`` allowed by the ends.
    """
    with mp.workdps(dps + _GUARD_DPS):
        model = _build(scene)
        length = _num(_get(_get(scene, "beam"), "length"))
        masses = sum(len(g) for g in model.masses)
        if _num(w) == 0:
            return _rigid_space(scene, m, xs, masses)
        beta = _beta_of(model, _num(w))
        rows, ncol, _w_rows, mass_cols = _global_rows(model, beta)
        A = mpmath.matrix(len(rows), ncol)
        for r, row in enumerate(rows):
            for col, val in row.items():
                A[r, col] = val
        _u, s, V = mpmath.svd_r(A)
        order = sorted(range(ncol), key=lambda i: s[i])[:m]
        nodes = [mpf(0)]
        for ell in model.seg:
            nodes.append(nodes[-1] + ell)
        out = []
        for i in order:
            v = [V[i, c] for c in range(ncol)]
            row = []
            for x in xs:
                xi = _num(x) / length
                j = min(max(k for k in range(len(model.seg)) if nodes[k] <= xi), len(model.seg) - 1)
                sloc = xi - nodes[j]
                base = 4 * j + sum(len(g) for g in model.masses[: j + 1])
                basis = (
                    mpmath.cos(beta * sloc),
                    mpmath.sin(beta * sloc),
                    mpmath.exp(-beta * sloc),
                    mpmath.exp(beta * (sloc - model.seg[j])),
                )
                row.append(float(sum(b * v[base + t] for t, b in enumerate(basis))))
            row += [float(v[c]) for cols in mass_cols for c in cols]
            out.append(row)
    return out


def _rigid_space(scene, m, xs, masses):
    """The rigid motions a + b x (masses moving with the beam point) the ends allow."""
    beam = _get(scene, "beam")
    length = float(_num(_get(beam, "length")))
    left, right = _end(_get(beam, "left")), _end(_get(beam, "right"))
    atts = sorted(float(_num(_get(a, "x"))) for a in _get(scene, "attachments"))
    basis = []
    if left not in ("clamped", "pinned") and right not in ("clamped", "pinned"):
        basis.append(lambda x: 1.0)  # translation
    if (left, right) in (("free", "free"),):
        basis.append(lambda x: x / length - 0.5)  # rotation about the middle
    if left == "pinned" and right in ("free",):
        basis.append(lambda x: x / length)
    if right == "pinned" and left in ("free",):
        basis.append(lambda x: 1.0 - x / length)
    if len(basis) != m:
        raise ValueError(f"{m} rigid-body modes asked for, the ends allow {len(basis)}")
    return [[f(float(x)) for x in xs] + [f(x) for x in atts] for f in basis]

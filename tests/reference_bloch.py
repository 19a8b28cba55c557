"""Independent high-precision reference (mpmath only) for periodic beams: Bloch-Floquet.

A *cell* is a scene (dict in the TOML layout, or an ``mstmm.scene.Scene``-like object with
the same attributes): its ``beam`` (uniform, or ``segments``; each with ``length``, ``EI``,
``mass_per_length`` and optional ``loss_factor``, ``kappa_GA``, ``rho_I``, ``axial_force``,
``foundation_k``, ``foundation_kG``) repeated with period ``L`` = its length, and its
``attachments`` at ``0 <= x < L`` (``x`` within 1e-14 L of ``L`` is the next cell's ``x = 0``).
The beam's ``left`` / ``right`` are ignored.  Kinds: ``spring_mass`` (k, m, optional c),
``mass`` (m, optional J), ``spring`` (k, to ground), ``rotational_spring`` (k, to ground),
``support`` (W = 0 there, rotation free), ``oscillator_chain`` (lists k, m, optional c; beam
-> m1 -> m2 ...), ``dashpot`` (c, to ground).  Nothing here calls ``src/mstmm`` numerics; the
scene-reading helpers, the general-segment bounds (:func:`reference_model._cc_bound`,
``_wavenumber_bound``) and the regula falsi come from ``tests/reference_model.py``.

Conventions (SI)
----------------
State ``z = (W, psi, M, Q)``: deflection (m), section rotation (rad; ``W'`` for
Euler-Bernoulli), ``M = EI psi'`` (N m), ``Q`` (N) the total transverse force,
``Q = -(kappa_GA (W' - psi) + (axial_force + foundation_kG) W')`` (``Q = EI W'''`` for a
plain Euler-Bernoulli segment).  Along a segment (time dependence ``exp(i omega t)``)::

    W' = (G psi - Q) / g       (G = kappa_GA, g = G + t, t = axial_force + foundation_kG;
                                G = 0: W' = psi)
    psi' = M / EI
    M' = (G t / g - rho_I omega^2) psi + (G / g) Q      (G = 0: M' = Q + (t - rho_I omega^2) psi)
    Q' = (mbar omega^2 - k_w) W

(a loss factor eta multiplies EI, kappa_GA, foundation_k, foundation_kG by ``1 + i eta``).
At a point, a force ``F`` on the beam (positive along W) gives ``Q(x+) - Q(x-) = F`` and a
couple ``C`` (positive on psi) ``M(x+) - M(x-) = -C``; so with the attachment's dynamic
stiffness ``D`` (force = ``-D W``, couple = ``-D_r psi``)::

    Q+ = Q- - D W,  M+ = M- + D_r psi
    D:   spring k;  mass -m w^2;  dashpot i w c;
         spring_mass -k* m w^2 / (k* - m w^2) with k* = k + i w c;
         oscillator_chain condensed from its tip (q_n = -m_n w^2, p_i = k*_i + q_i,
         q_(i-1) = -m_(i-1) w^2 + k*_i q_i / p_i, D = k*_1 q_1 / p_1)
    D_r: rotational_spring k;  mass -J w^2

``T`` maps the state at ``x = 0-`` (left of the attachments at 0) to ``x = L-`` (left of the
next cell's).  Bloch waves ``z(x + L) = lam z(x)``, ``lam = exp(i k L)``, satisfy ``T z = lam z``;
``det T = 1`` and the eigenvalues come in pairs ``lam, 1/lam``; ``mu = lam + 1/lam`` solves
``mu^2 - a mu + (b - 2) = 0`` (``a = tr T``, ``b`` the sum of the 2x2 principal minors).

A cell with ``support``\\ s has no 4x4 transfer: :func:`cell_pencil` gives ``(P, R)``, of
size ``4 + s``, with unknowns ``v = (z0, r_1..r_s)`` (``r_j`` the reaction force of support
j on the beam, N): the first 4 rows of ``P v`` are ``z(L-)`` (``T``'s rows, reactions
included), the last s rows the deflections at the supports (must vanish); ``R =
diag(1, 1, 1, 1, 0, ...)``, so Bloch waves satisfy ``P v = lam R v``.  ``det(P - lam R)``
is ``lam (lam^2 - mu lam + 1)`` up to a factor: one Bloch pair, ``mu_1 = None`` (its
``lam = 0, inf``).  Translational attachments on a support act on the reaction only; a
spring_mass or chain hung on a support is a decoupled resonator (a flat band: its own
frequencies are eigenvalues of both closed cells, counted by :func:`band_edges`).

API (omega in rad/s, real; complex omega and damping in :func:`cell_transfer`,
:func:`cell_pencil`, :func:`characteristic`, :func:`bloch_mu`, :func:`bloch_k` only):

* :func:`cell_transfer` ``(cell, omega, dps=40) -> mpmath.matrix`` 4x4 ``T`` (SI state above);
  ValueError for a cell with a support.
* :func:`cell_pencil` ``(cell, omega, dps=40) -> (P, R)``: the pencil (any cell; no support:
  ``P = T``, ``R = I``).
* :func:`characteristic` ``(cell, omega, dps=40) -> [c0, c1, c2, c3, c4]``: ``det(P - lam R) =
  sum c_j lam^j`` up to a factor, normalised so that ``c4 = 1`` (``det(T - lam I)``), or
  ``c3 = 1`` for a support cell (``c4 = 0`` exactly).  Palindromic: ``c0 = c4``, ``c1 = c3``.
* :func:`bloch_mu` ``(cell, omega, dps=40) -> (mu1, mu2)``: the roots of ``c4 mu^2 + c3 mu +
  (c2 - 2 c4) = 0``; ``|mu1| >= |mu2|`` (mu1 the more evanescent: ``2 cosh`` for a bare
  beam), ties by Im; mpf when real, mpc otherwise; support cell: ``(None, -c2 / c3)``.
* :func:`bloch_k` ``(cell, omega, dps=40) -> (k1, k2)`` (rad/m, mpc): ``k L = acos(mu / 2)``
  (principal: Re in [0, pi]).  Undamped at real omega, ``T`` is real, so ``k`` and
  ``-conj(k)`` are both wavenumbers and ``k`` is returned folded to ``Re k L in [0, pi]``,
  ``Im k >= 0`` (a complex-conjugate pair mu2 = conj(mu1) gives twice the same folded k).
  Damped or complex omega: no such symmetry; the principal ``acos`` is returned as it is
  (``Re k L in [0, pi]``, Im k of either sign; ``-k`` is the other member of the pair).
  Support cell: ``(None, k)``.
* :func:`band_edges` ``(cell, w_lo, w_hi, dps=40) -> [(omega, kind, multiplicity)]``: every
  omega in ``[w_lo, w_hi)`` (0 itself excluded) with ``lam = 1`` (kind ``"periodic"``, k = 0)
  or ``lam = -1`` (``"antiperiodic"``, k L = pi), ascending, with multiplicity.  Undamped only.
* :func:`edge_count` ``(cell, omega, kind, dps=40) -> int``: how many of them (with
  multiplicity, 0 included) lie strictly below omega.

Band edges: method and guarantees
---------------------------------
The periodic / antiperiodic frequencies are the eigenvalues of the cell closed on itself
(``d(L) = +d(0)`` or ``-d(0)``, d = (W, psi) and force balance at the joint), a real
symmetric problem.  Wittrick-Williams: ``J(omega) = J0 + s{K}``.  The cell is cut at its
attachment points and segment boundaries, and every span into equal pieces short enough that
each has no clamped-clamped frequency below omega (Euler-Bernoulli: ``lam h <= 3 < 4.73``;
general segments: ``|lam| h <= 3`` and ``reference_model._cc_bound`` > 1.25 beta^4, proved by
an energy bound), so ``J0`` is only the attachments' own: the negative pivots of each
chain's masses eliminated from its tip with the beam point held (a Sturm count).  Each
piece's exact 4x4 dynamic stiffness comes from its transfer matrix (Euler-Bernoulli: the
Krylov power series, all terms positive when undamped; general: ``exp(A h)`` from the even /
odd split of A, :func:`_general_transfer`).  The interior nodes are eliminated left to right (their
negative pivots counted), giving the cell's end stiffness ``D`` (4x4 on W0, psi0, W1,
psi1), and ``K = D_LL + D_RR +- (D_LR + D_RL)`` + the attachments at x = 0, whose negative
eigenvalues (pivots) complete ``s{K}`` (a fixed W is no unknown).  ``J(0+)`` is the
rigid-body count (1: periodic, no spring, support or foundation; else 0).

Isolation: bisection on ``J`` until each interval holds one root, or until its relative width
is below 1e-(dps + 3): then a root of multiplicity ``J(b) - J(a)`` at its midpoint (exactly
what a double root such as a bare beam's is; a symmetric problem's multiple eigenvalue is
split by rounding by O(eps), not sqrt(eps), so the count resolves it at full precision).
A simple root is polished by Anderson-Bjorck on ``+-|det K_total|`` (the product of all
pivots on a mesh fixed for the interval, entire there; the sign from the count), then
certified by the count: one below / one above within a relative 1e-(dps + 2), else by
bisection on the count alone.  Precision: ``dps + 20`` digits plus ``4 log10(1 / (lam h))``
for short pieces at low frequency and ``3 log10(1 / h_min)`` for short spans.  The count is
wrong only for a trial omega within ~1e-(dps + 15) of an eigenvalue (or of one of a
sub-structure the elimination clamps); an exactly zero pivot retries at a minutely lower
omega.  Roots are good to ~1e-(dps + 2) relative (tests: dps 30 vs 45 agree to 1e-31).

Limitations: only the k = 0 and k L = pi frequencies are returned; a band edge where the two
mu's coalesce inside (-2, 2) (a "complex band" opening, mu complex) is neither and is not
reported (``bloch_mu`` shows it).  No hinges.  A compressed cell must not be buckled
(checked: ValueError).  ``T`` has poles at the resonances of its attachments (``k* = m
w^2`` of a spring_mass): exactly there ZeroDivisionError.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass, field
from pathlib import Path

import mpmath
from mpmath import mp, mpc, mpf

_HERE = str(Path(__file__).resolve().parent)
if _HERE not in sys.path:
    sys.path.insert(0, _HERE)

from reference_model import (  # noqa: E402
    GENERAL_KEYS,
    _anderson_bjorck,
    _cc_bound,
    _cnum,
    _General,
    _get,
    _num,
    _opt,
    _wavenumber_bound,
)

__all__ = [
    "CELL_KINDS",
    "band_edges",
    "bloch_k",
    "bloch_mu",
    "cell_pencil",
    "cell_transfer",
    "characteristic",
    "edge_count",
]

#: Attachment kinds a cell may carry (``dashpot`` and ``c`` keys: damped functions only).
CELL_KINDS = (
    "spring_mass",
    "mass",
    "spring",
    "rotational_spring",
    "support",
    "oscillator_chain",
    "dashpot",
)

_GUARD = 20
_SNAP = mpf(10) ** -14
_REACH = 3.0  # largest |lam| h of a piece
_CC_MARGIN = 1.25
_KINDS = {"periodic": 1, "antiperiodic": -1}


class _Degenerate(ZeroDivisionError):
    """An exactly zero pivot: retry at a minutely different trial frequency."""


# --------------------------------------------------------------------------- the cell


@dataclass
class _Seg:
    """A beam segment, dimensionless (L the cell length, EI0 / mbar0 the first segment's)."""

    e: mpf  # EI / EI0
    mu: mpf  # mbar / mbar0
    eta: mpf  # loss factor
    gen: _General | None  # general terms (reference_model scaling), None: Euler-Bernoulli


@dataclass
class _Node:
    xi: mpf
    fix_w: bool = False
    k: mpf = field(default_factory=lambda: mpf(0))  # springs to ground, K = k L^3 / EI0
    m: mpf = field(default_factory=lambda: mpf(0))  # point masses, m / (mbar0 L)
    c: mpf = field(default_factory=lambda: mpf(0))  # dashpots, c L / sqrt(EI0 mbar0)
    kt: mpf = field(default_factory=lambda: mpf(0))  # rotational springs, k L / EI0
    j: mpf = field(default_factory=lambda: mpf(0))  # rotary inertia, J / (mbar0 L^3)
    chains: list = field(default_factory=list)  # [[(K, M, C), ...] beam -> tip] per chain


@dataclass
class _Cell:
    length: mpf
    ei0: mpf
    mu0: mpf
    w_scale: mpf  # omega = beta^2 w_scale
    segs: list  # _Seg
    nodes: list  # _Node, ascending xi, nodes[0] at 0 (the joint)
    spans: list  # (h, segment index) from node j to node j + 1 (the last one to xi = 1)
    foundation: bool  # a Winkler foundation somewhere

    @property
    def damped(self) -> bool:
        return any(s.eta != 0 for s in self.segs) or any(
            n.c != 0 or any(st[2] != 0 for ch in n.chains for st in ch) for n in self.nodes
        )

    @property
    def supports(self) -> int:
        return sum(1 for n in self.nodes if n.fix_w)


def _kind(att) -> str:
    if isinstance(att, dict):
        kind = att.get("type", att.get("kind", "spring_mass"))
    else:
        kind = getattr(att, "kind", None) or getattr(att, "type", None) or "spring_mass"
    kind = str(getattr(kind, "value", kind))
    if kind not in CELL_KINDS:
        raise ValueError(f"unsupported attachment type in a cell: {kind!r}")
    return kind


def _raw_segments(beam) -> list:
    """Per segment ``{length, EI, mass_per_length, loss_factor, GENERAL_KEYS...}`` (raw)."""
    keys = ("loss_factor",) + GENERAL_KEYS
    segments = _opt(beam, "segments")
    if segments:
        items = list(segments)
    else:
        items = [beam]
    out = []
    for s in items:
        d = {name: _get(s, name) for name in ("length", "EI", "mass_per_length")}
        d.update({key: _opt(s, key, 0) for key in keys})
        out.append(d)
    return out


def _build(cell) -> _Cell:
    """Nondimensionalise a cell at the current precision (see the module docstring)."""
    beam = _get(cell, "beam")
    raw = _raw_segments(beam)
    lens = [_num(s["length"]) for s in raw]
    eis = [_num(s["EI"]) for s in raw]
    mus = [_num(s["mass_per_length"]) for s in raw]
    if not all(v > 0 for v in lens + eis + mus):
        raise ValueError("segment length, EI and mass_per_length must be > 0")
    length = mpmath.fsum(lens)
    ei0, mu0 = eis[0], mus[0]
    segs = []
    foundation = False
    for s, ei, mb in zip(raw, eis, mus):
        eta = _num(s["loss_factor"])
        kga, rho, p, kw, kg = (_num(s[key]) for key in GENERAL_KEYS)
        if eta < 0 or kga < 0 or rho < 0 or kw < 0 or kg < 0:
            raise ValueError("loss_factor, kappa_GA, rho_I, foundation_k/kG must be >= 0")
        if kga > 0 and not kga + p + kg > 0:
            raise ValueError("kappa_GA + axial_force + foundation_kG must be > 0")
        foundation |= kw > 0
        gen = None
        if not (kga == rho == p == kw == kg == 0):
            gen = _General(
                kga * length**2 / ei0,
                rho / (mu0 * length**2),
                p * length**2 / ei0,
                kg * length**2 / ei0,
                kw * length**4 / ei0,
            )
        segs.append(_Seg(ei / ei0, mb / mu0, eta, gen))
    bounds, x = [], mpf(0)
    for ell in lens[:-1]:
        x += ell
        bounds.append(x / length)
    found: dict = {mpf(0): _Node(mpf(0))}
    for b in bounds:
        found.setdefault(b, _Node(b))
    try:
        atts = list(_get(cell, "attachments") or ())
    except (KeyError, AttributeError):
        atts = []
    c_unit = length / mpmath.sqrt(ei0 * mu0)
    for att in atts:
        kind = _kind(att)
        xi = _num(_get(att, "x")) / length
        if abs(xi - 1) <= _SNAP:
            xi = mpf(0)
        for edge in [mpf(0)] + bounds:
            if abs(xi - edge) <= _SNAP:
                xi = edge
        if not 0 <= xi < 1:
            raise ValueError(f"{kind} at x = {_get(att, 'x')}: outside [0, L)")
        node = found.setdefault(xi, _Node(xi))
        if kind in ("spring_mass", "oscillator_chain"):
            ks, ms, cs = _get(att, "k"), _get(att, "m"), _opt(att, "c", 0)
            if kind == "spring_mass":
                ks, ms, cs = [ks], [ms], [cs]
            else:
                ks, ms = list(ks), list(ms)
                cs = [0] * len(ks) if cs in (0, None) else list(cs)
            if not ks or not len(ks) == len(ms) == len(cs):
                raise ValueError(f"{kind}: k, m (and c) must be lists of one length")
            chain = []
            for k, m, c in zip(ks, ms, cs):
                k, m, c = _num(k), _num(m), _num(c)
                if not (k > 0 and m > 0 and c >= 0):
                    raise ValueError(f"{kind} needs k > 0, m > 0, c >= 0: {k}, {m}, {c}")
                chain.append((k * length**3 / ei0, m / (mu0 * length), c * c_unit))
            node.chains.append(chain)
        elif kind == "mass":
            m, j = _num(_get(att, "m")), _num(_opt(att, "J", 0))
            if m < 0 or j < 0:
                raise ValueError(f"mass needs m >= 0 and J >= 0: {m}, {j}")
            node.m += m / (mu0 * length)
            node.j += j / (mu0 * length**3)
        elif kind == "spring":
            node.k += _num(_get(att, "k")) * length**3 / ei0
        elif kind == "rotational_spring":
            node.kt += _num(_get(att, "k")) * length / ei0
        elif kind == "dashpot":
            node.c += _num(_get(att, "c")) * c_unit
        else:
            node.fix_w = True
    xs = sorted(found)
    nodes = [found[x] for x in xs]
    edges = [mpf(0)] + bounds
    spans = []
    for a, b in zip(xs, xs[1:] + [mpf(1)]):
        s = max(i for i, e in enumerate(edges) if e <= a)
        spans.append((b - a, s))
    return _Cell(
        length, ei0, mu0, mpmath.sqrt(ei0 / mu0) / length**2, segs, nodes, spans, foundation
    )


# ------------------------------------------------------------------ field transfer


def _krylov(l4, h) -> list:
    """``f_j = sum_n l4^n h^(4n+j) / (4n+j)!``, j = 0..3 (entire in l4; used for |l4 h^4| <=
    81, where the series converges fast; all terms positive for l4 > 0)."""
    x = l4 * h**4
    eps = mpf(2) ** (-mp.prec - 8)
    out = []
    for j in range(4):
        term = h**j / math.factorial(j)
        total, n = term, j
        while True:
            term = term * x / ((n + 1) * (n + 2) * (n + 3) * (n + 4))
            n += 4
            total += term
            if abs(term) <= eps * abs(total):
                break
        out.append(total)
    return out


def _eb_transfer(seg: _Seg, b4, h) -> list:
    """4x4 transfer (nested lists) of an Euler-Bernoulli piece, state (y, psi, m, q) =
    (W / L, psi, M L / EI0, Q L^2 / EI0), over the dimensionless length h."""
    ec = seg.e if seg.eta == 0 else seg.e * mpc(1, seg.eta)
    l4 = seg.mu * b4 / ec
    f0, f1, f2, f3 = _krylov(l4, h)
    return [
        [f0, f1, f2 / ec, f3 / ec],
        [l4 * f3, f0, f1 / ec, f2 / ec],
        [ec * l4 * f2, ec * l4 * f3, f0, f1],
        [ec * l4 * f1, ec * l4 * f2, l4 * f3, f0],
    ]


def _field_a(seg: _Seg, b4) -> list:
    """``A`` of ``z' = A z`` (state as :func:`_eb_transfer`) of a general segment."""
    gen = seg.gen
    c = 1 if seg.eta == 0 else mpc(1, seg.eta)
    G, kw, t = gen.G * c, gen.kw * c, gen.P + gen.kg * c
    R = gen.r * b4
    A = [[mpf(0)] * 4 for _ in range(4)]
    A[1][2] = 1 / (seg.e * c)
    A[3][0] = seg.mu * b4 - kw
    if gen.G == 0:
        A[0][1] = mpf(1)
        A[2][1] = t - R
        A[2][3] = mpf(1)
    else:
        g = G + t
        A[0][1] = G / g
        A[0][3] = -1 / g
        A[2][1] = G * t / g - R
        A[2][3] = G / g
    return A


def _mul(a, b) -> list:
    n, m, p = len(a), len(b), len(b[0])
    return [[mpmath.fsum(a[i][k] * b[k][j] for k in range(m)) for j in range(p)] for i in range(n)]


def _general_transfer(seg: _Seg, b4, h) -> list:
    """``exp(A h)`` of a general segment (|lambda| h <= 3 here).  A couples only (y, m) with
    (psi, q): in that order ``A = [[0, X], [Y, 0]]``, so ``exp(A h) = [[C(XY), X S(YX)],
    [Y S(XY), C(YX)]]`` with ``C(M) = sum M^n h^2n / (2n)!``, ``S(M) = sum M^n h^(2n+1) /
    (2n+1)!``; XY and YX (2x2) share their trace e1 and determinant e2, and by Cayley-Hamilton
    ``M^n = alpha_n I + beta_n M`` (alpha_(n+1) = -e2 beta_n, beta_(n+1) = alpha_n + e1
    beta_n): four scalar series, no matrix powers."""
    h = mpmath.mpmathify(h)
    A = _field_a(seg, b4)
    X = [[A[0][1], A[0][3]], [A[2][1], A[2][3]]]  # rows y, m; columns psi, q
    Y = [[A[1][0], A[1][2]], [A[3][0], A[3][2]]]  # rows psi, q; columns y, m
    XY, YX = _mul(X, Y), _mul(Y, X)
    e1 = XY[0][0] + XY[1][1]
    e2 = XY[0][0] * XY[1][1] - XY[0][1] * XY[1][0]
    eps = mpf(2) ** (-mp.prec - 8)
    scale = 1 + max(abs(v) for row in XY + YX for v in row) * h * h
    alpha, beta = mpf(1), mpf(0)
    w, v = mpf(1), h  # h^2n / (2n)!, h^(2n+1) / (2n+1)!
    c0 = c1 = s0 = s1 = mpf(0)
    for n in range(100000):
        c0 += w * alpha
        c1 += w * beta
        s0 += v * alpha
        s1 += v * beta
        size = (abs(w) + abs(v)) * (abs(alpha) + abs(beta) * scale)
        if n > 2 and size <= eps:
            break
        alpha, beta = -e2 * beta, alpha + e1 * beta
        w = w * h * h / ((2 * n + 1) * (2 * n + 2))
        v = v * h * h / ((2 * n + 2) * (2 * n + 3))
    cxy = [[c0 * (i == j) + c1 * XY[i][j] for j in range(2)] for i in range(2)]
    cyx = [[c0 * (i == j) + c1 * YX[i][j] for j in range(2)] for i in range(2)]
    xs = _mul(X, [[s0 * (i == j) + s1 * YX[i][j] for j in range(2)] for i in range(2)])
    ys = _mul(Y, [[s0 * (i == j) + s1 * XY[i][j] for j in range(2)] for i in range(2)])
    E, O = (0, 2), (1, 3)
    out = [[mpf(0)] * 4 for _ in range(4)]
    for i in range(2):
        for j in range(2):
            out[E[i]][E[j]] = cxy[i][j]
            out[O[i]][O[j]] = cyx[i][j]
            out[E[i]][O[j]] = xs[i][j]
            out[O[i]][E[j]] = ys[i][j]
    return out


def _pieces(cell: _Cell, h, s: int, b4, count: bool) -> int:
    """Equal pieces of a span of length h in segment s at beta^4 = b4: |lam| h <= 3, and for
    the count a proved clamped-clamped fundamental above 1.25 b4 (a power of 2)."""
    seg = cell.segs[s]
    if seg.gen is None:
        ec = abs(complex(seg.e * (1 if seg.eta == 0 else mpc(1, seg.eta))))
        lam = (abs(complex(seg.mu * b4)) / ec) ** 0.25
    else:
        lam = _wavenumber_bound(seg.gen, seg.e, seg.mu, seg.eta, b4)
    n = max(1, math.ceil(float(h) * lam / _REACH))
    if count and seg.gen is not None:
        target = _CC_MARGIN * float(b4)
        while not _cc_bound(seg.gen, seg.e, seg.mu, float(h) / n) > target:
            n = max(n + 1, math.ceil(n * 1.25))
    return 1 << (n - 1).bit_length()


def _piece_transfer(cell: _Cell, s: int, b4, h) -> list:
    seg = cell.segs[s]
    if seg.gen is None:
        return _eb_transfer(seg, b4, h)
    with mp.workdps(mp.dps + 10):
        T = _general_transfer(seg, b4, h)
    return [[+v for v in row] for row in T]


def _span_transfer(cell: _Cell, h, s: int, b4) -> list:
    n = _pieces(cell, h, s, b4, count=False)
    T = _piece_transfer(cell, s, b4, h / n)
    out = T
    while n > 1:  # n is a power of 2
        out = _mul(out, out)
        n //= 2
    return out


def _growth_digits(cell: _Cell, b4) -> int:
    """Digits the characteristic coefficients may lose to cancellation (2 log10 |T|), plus
    those lost at low frequency (mu - 2 ~ (lam L)^4)."""
    total = 0.0
    small = math.inf
    for h, s in cell.spans:
        seg = cell.segs[s]
        if seg.gen is None:
            ec = abs(complex(seg.e * (1 if seg.eta == 0 else mpc(1, seg.eta))))
            lam = (abs(complex(seg.mu * b4)) / ec) ** 0.25
        else:
            lam = _wavenumber_bound(seg.gen, seg.e, seg.mu, seg.eta, b4)
        total += lam * float(h)
        small = min(small, lam)
    digits = 2 * total / math.log(10) + 5
    if small < 1:
        digits += 4 * math.log10(1 / max(small, 1e-300)) + 5
    return int(math.ceil(digits))


# ------------------------------------------------------------------ point conditions


def _chain_stiffness(chain, b4, w):
    """Dynamic stiffness of a chain at the beam point (condensed from its tip, the beam point
    held), and its pivots (a Sturm sequence of the chain when undamped)."""

    def spring(i):
        k, _m, c = chain[i]
        return k if c == 0 else k + mpc(0, 1) * w * c

    q = piv = None
    pivots = []
    for i in range(len(chain) - 1, -1, -1):
        q = -chain[i][1] * b4 if q is None else -chain[i][1] * b4 + spring(i + 1) * q / piv
        piv = spring(i) + q
        if piv == 0:
            raise _Degenerate
        pivots.append(piv)
    return spring(0) * q / piv, pivots


def _node_stiffness(node: _Node, b4, w):
    """(D, D_r, chain pivots) of a node at beta^4 = b4, beta^2 = w (dimensionless)."""
    d = node.k - node.m * b4
    if node.c != 0:
        d = d + mpc(0, 1) * w * node.c
    pivots = []
    for chain in node.chains:
        dc, piv = _chain_stiffness(chain, b4, w)
        d += dc
        pivots += piv
    return d, node.kt - node.j * b4, pivots


# ------------------------------------------------------------------ transfer / pencil


def _pencil_nd(cell: _Cell, b4, w) -> list:
    """The dimensionless pencil ``P`` ((4 + s) x (4 + s), nested lists)."""
    s = cell.supports
    n = 4 + s
    Z = [[mpf(int(i == j)) for j in range(n)] for i in range(4)]
    cons = []
    for node, (h, seg) in zip(cell.nodes, cell.spans):
        d, dr, _ = _node_stiffness(node, b4, w)
        if node.fix_w:
            cons.append(list(Z[0]))
            Z[3][4 + len(cons) - 1] += 1
        elif d != 0:
            Z[3] = [a - d * b for a, b in zip(Z[3], Z[0])]
        if dr != 0:
            Z[2] = [a + dr * b for a, b in zip(Z[2], Z[1])]
        Z = _mul(_span_transfer(cell, h, seg, b4), Z)
    return Z + cons


def _det(M) -> mpf:
    """Determinant by Gaussian elimination with partial pivoting (nested lists, copied)."""
    a = [list(r) for r in M]
    n = len(a)
    det = mpf(1)
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(a[r][c]))
        if a[p][c] == 0:
            return mpf(0)
        if p != c:
            a[c], a[p] = a[p], a[c]
            det = -det
        det *= a[c][c]
        for r in range(c + 1, n):
            f = a[r][c] / a[c][c]
            if f != 0:
                for k in range(c + 1, n):
                    a[r][k] -= f * a[c][k]
    return det


def _coefficients(P) -> list:
    """``c_j`` of ``det(P - lam R) = sum c_j lam^j`` (R = diag(1, 1, 1, 1, 0..)): the sum over
    the subsets S of the 4 state indices of ``(-lam)^|S| det P`` with S's rows and columns
    deleted."""
    n = len(P)
    c = [mpf(0)] * 5
    for mask in range(16):
        drop = [i for i in range(4) if mask >> i & 1]
        keep = [i for i in range(n) if i not in drop]
        minor = _det([[P[i][j] for j in keep] for i in keep]) if keep else mpf(1)
        c[len(drop)] += (-1) ** len(drop) * minor
    return c


def _scales(cell: _Cell):
    L, ei = cell.length, cell.ei0
    return [L, mpf(1), ei / L, ei / L**2]


def _omega_nd(cell: _Cell, omega):
    w = _cnum(omega) / cell.w_scale  # beta^2
    return w, w * w


def _with_cell(cell, omega, dps, fn):
    with mp.workdps(dps + _GUARD):
        c = _build(cell)
        w, b4 = _omega_nd(c, omega)
        extra = _growth_digits(c, b4)
    with mp.workdps(dps + _GUARD + extra):
        c = _build(cell)
        w, b4 = _omega_nd(c, omega)
        return c, fn(c, b4, w)


def cell_pencil(cell, omega, dps: int = 40):
    """``(P, R)`` (mpmath matrices, SI; see the module docstring) at omega (rad/s, complex
    allowed): Bloch waves ``P v = lam R v``, ``v = (W, psi, M, Q at x = 0-, reactions)``."""
    c, P = _with_cell(cell, omega, dps, _pencil_nd)
    with mp.workdps(dps + _GUARD):
        sc = _scales(c)
        n = len(P)
        col = sc + [c.ei0 / c.length**2] * (n - 4)  # reactions: force units
        row = sc + [c.length] * (n - 4)  # constraints: W units
    with mp.workdps(dps):
        Pm = mpmath.matrix(n, n)
        Rm = mpmath.matrix(n, n)
        for i in range(n):
            for j in range(n):
                Pm[i, j] = +(P[i][j] * row[i] / col[j])
            Rm[i, i] = mpf(1) if i < 4 else mpf(0)
        return Pm, Rm


def cell_transfer(cell, omega, dps: int = 40):
    """4x4 transfer matrix ``T`` (mpmath.matrix, SI state (W, psi, M, Q)) of the cell at
    omega (rad/s, complex allowed): ``z(L-) = T z(0-)``.  ValueError for a support cell
    (use :func:`cell_pencil`)."""
    with mp.workdps(dps + _GUARD):
        if _build(cell).supports:
            raise ValueError("a cell with a support has no 4x4 transfer: use cell_pencil")
    P, _R = cell_pencil(cell, omega, dps)
    return P


def characteristic(cell, omega, dps: int = 40) -> list:
    """``[c0, .., c4]``: ``det(P - lam R)`` normalised to ``c4 = 1`` (no support: it is
    ``det(T - lam I)``) or to ``c3 = 1`` (support cell, ``c4 = 0``)."""

    def fn(c, b4, w):
        coef = _coefficients(_pencil_nd(c, b4, w))
        lead = coef[4] if c.supports == 0 else coef[3]
        if c.supports:
            coef[4] = mpf(0)  # det of the strictly lower triangular support block
        return [v / lead for v in coef]

    _c, coef = _with_cell(cell, omega, dps, fn)
    with mp.workdps(dps):
        return [_real(v) for v in coef]


def _real(v):
    """+v at the current precision, as mpf when its imaginary part is exactly zero."""
    if isinstance(v, mpc) and v.imag == 0:
        return +v.real
    return +v


def _is_real(v) -> bool:
    return not isinstance(v, mpc) or v.imag == 0


def _mu_roots(coef):
    """Roots of ``c4 mu^2 + c3 mu + (c2 - 2 c4)``, the larger modulus first (no cancellation:
    the smaller one from the product of the roots)."""
    c2, c3, c4 = coef[2], coef[3], coef[4]
    if c4 == 0:
        return None, -c2 / c3
    a, b = -c3 / c4, (c2 - 2 * c4) / c4  # mu^2 - a mu + b = 0
    if _is_real(a) and _is_real(b):
        a, b = mpmath.re(a), mpmath.re(b)
        disc = a * a - 4 * b
        if disc < 0:
            r = mpmath.sqrt(-disc)
            return mpc(a / 2, r / 2), mpc(a / 2, -r / 2)
        r = mpmath.sqrt(disc)
        m1 = (a + r) / 2 if a >= 0 else (a - r) / 2
        return m1, (b / m1 if m1 != 0 else mpf(0))
    r = mpmath.sqrt(a * a - 4 * b)
    m1 = (a + r) / 2 if abs(a + r) >= abs(a - r) else (a - r) / 2
    m2 = b / m1 if m1 != 0 else mpc(0)
    if abs(m2) > abs(m1) or (abs(m2) == abs(m1) and mpmath.im(m2) > mpmath.im(m1)):
        m1, m2 = m2, m1
    return m1, m2


def bloch_mu(cell, omega, dps: int = 40):
    """``(mu1, mu2)``, ``mu = lam + 1/lam`` of the two Bloch pairs at omega (rad/s, complex
    allowed); ``|mu1| >= |mu2|``; ``(None, mu)`` for a support cell."""

    def fn(c, b4, w):
        coef = _coefficients(_pencil_nd(c, b4, w))
        if c.supports:
            coef[4] = mpf(0)
        return _mu_roots(coef)

    _c, (m1, m2) = _with_cell(cell, omega, dps, fn)
    with mp.workdps(dps):
        return (None if m1 is None else _real(m1)), _real(m2)


def bloch_k(cell, omega, dps: int = 40):
    """``(k1, k2)`` (rad/m, mpc) of ``mu1, mu2`` (:func:`bloch_mu`): ``k L = acos(mu / 2)``,
    folded (see the module docstring); ``(None, k)`` for a support cell."""
    with mp.workdps(dps + _GUARD):
        c = _build(cell)
        folded = not c.damped and not isinstance(_cnum(omega), mpc)
        length = c.length
    mus = bloch_mu(cell, omega, dps + 10)
    out = []
    with mp.workdps(dps + 10):
        for mu in mus:
            if mu is None:
                out.append(None)
                continue
            kl = mpc(mpmath.acos(mu / 2))  # principal: Re in [0, pi]
            if folded:
                kl = mpc(kl.real, abs(kl.imag))
            out.append(kl / length)
    with mp.workdps(dps):
        return tuple(None if k is None else +k for k in out)


# ------------------------------------------------------------- Wittrick-Williams count


def _stiffness_from_transfer(T) -> list:
    """4x4 dynamic stiffness on (y0, psi0, y1, psi1) of a piece with transfer T, the nodal
    forces (q0, -m0, -q1, m1)."""
    t11 = [[T[0][0], T[0][1]], [T[1][0], T[1][1]]]
    t12 = [[T[0][2], T[0][3]], [T[1][2], T[1][3]]]
    t21 = [[T[2][0], T[2][1]], [T[3][0], T[3][1]]]
    t22 = [[T[2][2], T[2][3]], [T[3][2], T[3][3]]]
    det = t12[0][0] * t12[1][1] - t12[0][1] * t12[1][0]
    if det == 0:
        raise _Degenerate
    y = [[t12[1][1] / det, -t12[0][1] / det], [-t12[1][0] / det, t12[0][0] / det]]
    x = [[-v for v in row] for row in _mul(y, t11)]  # f0 = x d0 + y d1
    u = [[a + b for a, b in zip(ra, rb)] for ra, rb in zip(t21, _mul(t22, x))]
    v = _mul(t22, y)  # f1 = u d0 + v d1
    return [
        x[1] + y[1],
        [-a for a in x[0] + y[0]],
        [-a for a in u[1] + v[1]],
        u[0] + v[0],
    ]


def _eliminate(A: list, elim: list):
    """Symmetric Gaussian elimination of the indices ``elim`` (in order) of A (copied):
    (negative pivots, product of pivots, the Schur complement on the other indices)."""
    a = [list(r) for r in A]
    n = len(a)
    alive = list(range(n))
    neg, prod = 0, mpf(1)
    for p in elim:
        piv = a[p][p]
        if piv == 0:
            raise _Degenerate
        neg += piv < 0
        prod *= piv
        alive.remove(p)
        for r in alive:
            f = a[r][p] / piv
            if f != 0:
                for c in alive:
                    a[r][c] -= f * a[p][c]
    return neg, prod, [[a[r][c] for c in alive] for r in alive]


def _mesh(cell: _Cell, b4) -> list:
    """Pieces per span for the count at beta^4 = b4."""
    return [_pieces(cell, h, s, b4, count=True) for h, s in cell.spans]


def _count_dps(cell: _Cell, mesh: list, b4, dps: int) -> int:
    extra = 0
    hmin = min(h / n for (h, _s), n in zip(cell.spans, mesh))
    for (h, s), n in zip(cell.spans, mesh):
        seg = cell.segs[s]
        lam = (float(seg.mu * b4) / float(seg.e)) ** 0.25 * float(h) / n
        if lam < 1:
            extra = max(extra, int(4 * math.ceil(-math.log10(max(lam, 1e-300)))) + 5)
    extra += int(3 * math.ceil(max(0.0, -math.log10(float(hmin)))))
    return dps + _GUARD + extra


def _ring(cell: _Cell, mesh: list, b4, sign: int):
    """(J, F): eigenvalues of the closed cell (d(L) = sign d(0)) strictly below beta^4 = b4
    (every piece of ``mesh`` has J0 = 0), and F the product of all pivots (det of the
    assembled dynamic stiffness; no poles for this mesh)."""
    w = mpmath.sqrt(b4)
    neg, prod = 0, mpf(1)
    node_d = []
    for node in cell.nodes:
        d, dr, pivots = _node_stiffness(node, b4, w)
        for p in pivots:
            neg += p < 0
            prod *= p
        node_d.append((d, dr))
    cache: dict = {}

    def dofs(node):
        return [1] if node.fix_w else [0, 1]

    joint = cell.nodes[0]
    jd = dofs(joint)
    acc = None  # over (joint copy at x = 0) + (current node)
    first = True
    for idx, ((h, s), n) in enumerate(zip(cell.spans, mesh)):
        key = (s, h / n)
        if key not in cache:
            cache[key] = _stiffness_from_transfer(_piece_transfer(cell, s, b4, h / n))
        K = cache[key]
        for p in range(n):
            left = cell.nodes[idx] if p == 0 else None
            right_fixed = p == n - 1 and cell.nodes[(idx + 1) % len(cell.nodes)].fix_w
            ld = dofs(left) if left is not None else [0, 1]
            rd = [1] if right_fixed else [0, 1]
            Kr = [[K[i][j] for j in ld + [2 + q for q in rd]] for i in ld + [2 + q for q in rd]]
            if first:
                acc = Kr
                first = False
                continue
            nj, nl, nr = len(jd), len(ld), len(rd)
            big = [[mpf(0)] * (nj + nl + nr) for _ in range(nj + nl + nr)]
            for i in range(nj + nl):
                for j in range(nj + nl):
                    big[i][j] = acc[i][j]
            for i in range(nl + nr):
                for j in range(nl + nr):
                    big[nj + i][nj + j] += Kr[i][j]
            if left is not None:
                d, dr = node_d[idx]
                for i, q in enumerate(ld):
                    big[nj + i][nj + i] += d if q == 0 else dr
            nn, pp, acc = _eliminate(big, list(range(nj, nj + nl)))
            neg += nn
            prod *= pp
    nj = len(jd)
    K = [
        [
            acc[i][j] + acc[nj + i][nj + j] + sign * (acc[i][nj + j] + acc[nj + i][j])
            for j in range(nj)
        ]
        for i in range(nj)
    ]
    d, dr = node_d[0]
    for i, q in enumerate(jd):
        K[i][i] += d if q == 0 else dr
    nn, pp, _ = _eliminate(K, list(range(nj)))
    return neg + nn, prod * pp


def _rigid(cell: _Cell, sign: int) -> int:
    """Zero-frequency eigenvalues of the closed cell: the translation (periodic only) unless
    a spring, support or foundation holds it."""
    if sign < 0 or cell.foundation:
        return 0
    if any(n.fix_w or n.k != 0 for n in cell.nodes):
        return 0
    return 1


class _Edges:
    def __init__(self, cell, dps: int):
        self.raw = cell
        self.dps = dps
        with mp.workdps(dps + _GUARD):
            c = _build(cell)
        if c.damped:
            raise ValueError("band_edges is for undamped cells (no c, no loss_factor)")
        self._cells: dict = {}

    def cell(self, wp: int) -> _Cell:
        if wp not in self._cells:
            with mp.workdps(wp):
                self._cells[wp] = _build(self.raw)
        return self._cells[wp]

    def b4(self, cell: _Cell, omega):
        w = omega / cell.w_scale
        return w * w

    def evaluate(self, omega, sign: int, mesh=None):
        """(J, F) at omega (rad/s, mpf), retried slightly lower on an exact zero pivot."""
        base = self.cell(self.dps + _GUARD)
        with mp.workdps(self.dps + _GUARD):
            b4 = self.b4(base, omega)
            m = _mesh(base, b4) if mesh is None else mesh
            wp = _count_dps(base, m, b4, self.dps)
        cell = self.cell(wp)
        with mp.workdps(wp):
            eps = mpf(2) ** (-mp.prec + 30)
            for attempt in range(8):
                om = omega * (1 - eps * 4**attempt) if attempt else omega
                try:
                    return _ring(cell, m, self.b4(cell, om), sign)
                except _Degenerate:
                    continue
        raise RuntimeError(f"Wittrick-Williams count degenerate near omega = {omega}")

    def count(self, omega, sign: int) -> int:
        if omega <= 0:
            return 0
        return self.evaluate(omega, sign)[0]

    def polish(self, a, ja, b, sign: int):
        """The one root in [a, b) (count ja at a, ja + 1 at b)."""
        dps = self.dps
        while a == 0:
            mid = b / 2
            if self.count(mid, sign) > ja:
                b = mid
            else:
                a = mid
        base = self.cell(dps + _GUARD)
        with mp.workdps(dps + _GUARD):
            mesh = _mesh(base, self.b4(base, b))

        def g(z):
            j, f = self.evaluate(z, sign, mesh)
            return -abs(f) if j > ja else abs(f)

        tol = a * mpf(10) ** (-(dps + 8))
        root = _anderson_bjorck(g, a, g(a), b, g(b), tol)
        d = mpf(10) ** (-(dps + 2))
        lo, hi = max(a, root * (1 - d)), min(b, root * (1 + d))
        if self.count(lo, sign) == ja and self.count(hi, sign) == ja + 1:
            return root
        while (b - a) > b * mpf(10) ** (-(dps + 3)):  # fall back on the count alone
            mid = (a + b) / 2
            if self.count(mid, sign) > ja:
                b = mid
            else:
                a = mid
        return (a + b) / 2

    def roots(self, w_lo, w_hi, sign: int) -> list:
        dps = self.dps
        with mp.workdps(dps + _GUARD):
            w_lo, w_hi = _num(w_lo), _num(w_hi)
            base = self.cell(dps + _GUARD)
            n0 = _rigid(base, sign)
            if any(s.gen is not None and s.gen.P + s.gen.kg < 0 for s in base.segs):
                tiny = base.w_scale * mpf(10) ** -9
                if self.count(tiny, sign) > n0:
                    raise ValueError("compressed cell: negative eigenvalues (buckled)")
            if w_hi <= w_lo or w_hi <= 0:
                return []
            ja = self.count(w_lo, sign) if w_lo > 0 else n0
            a = w_lo if w_lo > 0 else mpf(0)
            stack = [(a, ja, w_hi, self.count(w_hi, sign))]
            out = []
            while stack:
                a, ja, b, jb = stack.pop()
                if jb <= ja:
                    continue
                if jb - ja == 1:
                    out.append((self.polish(a, ja, b, sign), 1))
                elif b - a <= b * mpf(10) ** (-(dps + 3)):
                    out.append(((a + b) / 2, jb - ja))
                else:
                    mid = (a + b) / 2
                    jm = self.count(mid, sign)
                    stack.append((mid, jm, b, jb))
                    stack.append((a, ja, mid, jm))
            return sorted(out)


def band_edges(cell, w_lo, w_hi, dps: int = 40) -> list:
    """``[(omega, kind, multiplicity)]``: the frequencies (rad/s, mpf, ascending) in
    ``[w_lo, w_hi)`` (0 excluded) where ``lam = 1`` (``"periodic"``) or ``lam = -1``
    (``"antiperiodic"``); see the module docstring.  Undamped cells only."""
    solver = _Edges(cell, dps)
    out = []
    for kind, sign in _KINDS.items():
        out += [(w, kind, m) for w, m in solver.roots(w_lo, w_hi, sign)]
    out.sort(key=lambda r: (r[0], r[1]))
    with mp.workdps(dps):
        return [(+w, kind, m) for w, kind, m in out]


def edge_count(cell, omega, kind: str, dps: int = 40) -> int:
    """Eigenvalues (with multiplicity, zero modes included) of the cell closed periodically
    (``kind = "periodic"``) or antiperiodically strictly below omega > 0 (rad/s)."""
    solver = _Edges(cell, dps)
    with mp.workdps(dps + _GUARD):
        return solver.count(_num(omega), _KINDS[kind])

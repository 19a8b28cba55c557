"""The argument principle (Delves & Lyness 1967; Kravanja & Van Barel 2000): the number of
zeros of an analytic function inside a closed contour is the winding number of its values
along the contour. Here the contour is a rectangle of the ``w`` plane (:func:`winding`,
each edge sampled adaptively by :func:`edge_winding`) or a circle (:func:`circle`), whose
moments also place the zeros inside it (:func:`cluster`; :func:`multiplicity`: the zeros in
a small square).

``f`` is log f, not f (:class:`LogF`): a beam's characteristic function spans hundreds of
orders of magnitude along a tall edge, its logarithm does not.
"""

from __future__ import annotations

import math
from typing import Protocol

import numpy as np

__all__ = [
    "LogF",
    "OnContour",
    "circle",
    "cluster",
    "edge_winding",
    "multiplicity",
    "winding",
    "wrap",
]

#: Largest phase step (radians) between neighbouring samples of the contour.
PHASE_STEP = math.pi / 4
#: Largest departure of log f at a step's midpoint from the mean of its ends (a zero
#: near the contour bends log f sharply; far from every zero it is smooth, however fast
#: |f| grows along a tall edge).
BEND = 0.5
#: Samples of the contour are refined down to this relative length at most.
FINEST = 1e-13
#: A winding number this far from an integer is not trusted (the sampling is refined).
WINDING_SLACK = 0.05


class LogF(Protocol):
    """log f of an analytic f: ``log|f| + i arg f`` (arg mod 2 pi), NaN where f has no
    value (an overflow), ``-inf`` where f = 0 (:class:`mstmm.damped._Function`)."""

    def __call__(self, ws: np.ndarray) -> np.ndarray:
        """log f at every point of ``ws`` (complex, rad/s)."""

    def one(self, w: complex) -> complex:
        """log f at one point."""


class OnContour(Exception):
    """A zero lies on (or within round-off of) the contour."""


def wrap(a):
    """Angles wrapped into (-pi, pi]."""
    return np.angle(np.exp(1j * np.asarray(a)))


def _growth(s: np.ndarray, c: float) -> np.ndarray:
    """The basis of the smooth growth of log|f| up a tall edge, at heights ``s`` above its
    bottom (``c``: the box's width): a beam's exponents grow as sqrt(w), its scalings as
    powers of w."""
    s = np.asarray(s, dtype=float)
    return np.stack([np.ones_like(s), np.sqrt(s + c), np.log(s + c), s / c], axis=-1)


def edge_winding(
    f: LogF,
    a: complex,
    b: complex,
    n0: int = 32,
    nodes: np.ndarray | None = None,
    tall: float = 0.0,
) -> float:
    """The change of arg f along the segment from a to b (radians), sampled adaptively
    until no step of the phase exceeds PHASE_STEP and log f at the midpoint of every step
    is within BEND of the mean of its ends (a zero near the segment, at a distance below a
    third of the step or so, bends it further; the rise of |f| along a tall edge far from
    every zero does not, and costs no samples);
    ``nodes`` (fractions of the segment) are sampled from the start: one between any two
    roots near the segment, so that no two of them share a step (their phase swings would
    add to 2 pi and wrap to nothing). ``tall`` (a vertical edge of a box this wide, far
    taller): the smooth growth of log|f| with the height (fitted by least squares on the
    samples well above the bottom, :func:`_growth`) is taken out of log|f| before the
    bends are measured, so that it costs no samples; the phase is untouched (the count
    is the same sum of phase steps, only where to sample changes). Raises
    :class:`OnContour` when a zero sits on the segment."""
    t = np.linspace(0.0, 1.0, n0 + 1)
    if nodes is not None and len(nodes):
        t = np.unique(np.concatenate([t, np.clip(nodes, 0.0, 1.0)]))
    g = f(a + (b - a) * t)
    checked = np.zeros(t.size - 1, dtype=bool)
    bottom = min(a.imag, b.imag)

    def height(u):
        return np.abs((a + (b - a) * u).imag - bottom)

    coef = None
    if tall > 0.0:
        far = (height(t) >= 4.0 * tall) & np.isfinite(g.real)
        if np.count_nonzero(far) >= 8:
            coef = np.linalg.lstsq(_growth(height(t[far]), tall), g.real[far], rcond=None)[0]

    def log_abs(u, gu):
        """log|f| at the fractions u (values gu) less the fitted growth."""
        return gu.real if coef is None else gu.real - _growth(height(u), tall) @ coef

    while True:
        if not np.all(np.isfinite(g)):
            near = a + (b - a) * t[~np.isfinite(g)][0]
            what = "f has no value (overflow)" if np.isnan(g).any() else "f = 0"
            raise OnContour(f"{what} on the contour near {near}")
        dphi = wrap(np.diff(g.imag))
        bad = np.abs(dphi) > PHASE_STEP
        if t.size > 2:
            # log|f| over a step against what its neighbours' slopes predict: a zero close
            # to the segment (a double one turns the phase by a whole turn, which wraps
            # to nothing) breaks the trend
            dlog = np.diff(log_abs(t, g))
            h = np.diff(t)
            slope = dlog / h
            trend = np.empty_like(slope)
            trend[1:-1] = 0.5 * (slope[:-2] + slope[2:])
            trend[0], trend[-1] = slope[1], slope[-2]
            bad |= np.abs(dlog - h * trend) > 2.0 * BEND
        if not bad.any():
            # each step once more through its midpoint: a step whose phase turned by a
            # whole turn more than it shows (a zero close by) splits in two there
            todo = np.flatnonzero(~checked)
            if todo.size == 0:
                return float(np.sum(dphi))
            mid = 0.5 * (t[todo] + t[todo + 1])
            gm = f(a + (b - a) * mid)
            h1 = wrap(gm.imag - g.imag[todo])
            h2 = wrap(g.imag[todo + 1] - gm.imag)
            # a half that turns too far, or halves that do not add up to the step: a
            # zero close by (its swing may have wrapped by a whole turn)
            hidden = np.abs(h1 + h2 - dphi[todo]) > 1.0
            hidden |= (np.abs(h1) > PHASE_STEP) | (np.abs(h2) > PHASE_STEP)
            lg = log_abs(t, g)
            hidden |= np.abs(log_abs(mid, gm) - 0.5 * (lg[todo] + lg[todo + 1])) > BEND
            hidden |= np.abs(0.5 * (h1 - h2)) > BEND
            hidden |= ~np.isfinite(gm)
            checked[todo] = True
            if not hidden.any():
                return float(np.sum(dphi))
            bad = np.zeros(t.size - 1, dtype=bool)
            bad[todo[hidden]] = True
        idx = np.flatnonzero(bad)
        width = t[idx + 1] - t[idx]
        if np.any(width * abs(b - a) < FINEST * max(abs(a), abs(b))):
            near = a + (b - a) * t[idx[0]]
            raise OnContour(f"a zero within round-off of the contour near {near}")
        mid = 0.5 * (t[idx] + t[idx + 1])
        gm = f(a + (b - a) * mid)
        t = np.insert(t, idx + 1, mid)
        g = np.insert(g, idx + 1, gm)
        checked = np.insert(checked, idx + 1, False)
        # both halves of every split step are checked again: the left half of the k-th
        # split step now sits at idx[k] + k (each insertion before it shifted it by one)
        checked[idx + np.arange(idx.size)] = False


def winding(
    f: LogF,
    box: tuple[float, float, float, float],
    n0: int = 32,
    bottom: np.ndarray | None = None,
) -> int:
    """Number of zeros of f in the rectangle ``box = (x0, x1, y0, y1)`` of the w plane
    (w_d from x0 to x1, sigma from y0 to y1), with multiplicity, by the argument principle;
    ``bottom``: w_d values sampled from the start along the bottom edge (between the roots
    near the real axis). Raises :class:`OnContour` when a zero lies on its boundary."""
    x0, x1, y0, y1 = box
    corners = [complex(x0, y0), complex(x1, y0), complex(x1, y1), complex(x0, y1)]
    # a tall box: its sides sampled at heights growing geometrically from the bottom,
    # where the zeros are (f changes on the scale of the distance to them)
    rise = np.zeros(0)
    if y1 - y0 > 8.0 * (x1 - x0):
        rise = (x1 - x0) * 2.0 ** np.arange(int(math.log2((y1 - y0) / (x1 - x0))) + 1) / (y1 - y0)
    total = 0.0
    for i in range(4):
        nodes = None
        if i == 0 and bottom is not None:
            nodes = (np.asarray(bottom, dtype=float) - x0) / (x1 - x0)
        elif i in (1, 3):
            nodes = rise if i == 1 else 1.0 - rise
        tall = x1 - x0 if i in (1, 3) and rise.size else 0.0
        total += edge_winding(f, corners[i], corners[(i + 1) % 4], n0, nodes, tall)
    n = total / (2.0 * math.pi)
    if abs(n - round(n)) > WINDING_SLACK:
        raise OnContour(f"winding number {n:.3f} is not an integer")
    return int(round(n))


#: Samples of a circle for the moments of a cluster (doubled until the phase is resolved).
CLUSTER_SAMPLES = 64


def circle(f: LogF, centre: complex, r: float) -> tuple[np.ndarray, int] | None:
    """log f at equispaced points of the circle |w - centre| = r (their phase unwrapped)
    and the winding number; None when no sampling up to 4096 points resolves the phase
    (a zero on or next to the circle)."""
    n = CLUSTER_SAMPLES
    while n <= 4096:
        theta = 2.0 * np.pi * np.arange(n) / n
        g = f(centre + r * np.exp(1j * theta))
        if not np.all(np.isfinite(g)):
            return None
        steps = wrap(np.diff(np.append(g.imag, g.imag[0])))
        if np.max(np.abs(steps)) < 0.5 * np.pi:
            turns = float(np.sum(steps)) / (2.0 * np.pi)
            if abs(turns - round(turns)) < WINDING_SLACK:
                phase = g.imag[0] + np.concatenate([[0.0], np.cumsum(steps[:-1])])
                return g.real + 1j * phase, int(round(turns))
        n *= 2
    return None


def _power_sums(g: np.ndarray, m: int, r: float) -> np.ndarray:
    """``s_j = sum (z_i - centre)^j``, j = 1..m, over the m zeros inside the circle whose
    log f samples are ``g``: with ``h = log f - m log(w - centre)`` (periodic on the
    circle), ``s_j = -j r^j mean(e^(i j theta) h)`` (integration by parts of
    ``(1 / 2 pi i) \u222e (w - centre)^j f'/f dw``; the trapezoidal rule is spectrally
    accurate for a periodic analytic integrand: Delves & Lyness 1967)."""
    n = g.size
    theta = 2.0 * np.pi * np.arange(n) / n
    h = g - m * (np.log(r) + 1j * theta)
    return np.array([-j * r**j * np.mean(np.exp(1j * j * theta) * h) for j in range(1, m + 1)])


def _zeros_from_sums(s: np.ndarray) -> np.ndarray:
    """The m numbers whose power sums are ``s`` (Newton's identities, then the roots of
    their monic polynomial)."""
    m = s.size
    e = [1.0 + 0j]
    for k in range(1, m + 1):
        e.append(sum((-1) ** (i - 1) * e[k - i] * s[i - 1] for i in range(1, k + 1)) / k)
    coeffs = [(-1) ** k * e[k] for k in range(m + 1)]
    return np.roots(coeffs) if m > 1 else np.array([s[0]])


def cluster(f: LogF, centre: complex, r0: float, unit: float) -> list[tuple[complex, int]] | None:
    """The zeros of f in a disc around ``centre`` (radius ``r0`` at least), each with its
    multiplicity. The disc grows (x4) while it holds the same number m of zeros, up to a
    hundredth of |centre|, since the moments of the cluster are the better conditioned
    the wider the circle; their power sums (:func:`_power_sums`) at the widest and at a
    quarter of it give the zeros, and zeros whose spread is within what the two circles
    disagree on form one multiple root at their mean (the mean of a cluster is well
    conditioned where its members are not: a defective double root, critical damping, is
    found to full accuracy; ``unit``: the frequency unit, the scale of a centre near 0). None
    when the disc cannot be resolved."""
    scale = max(abs(centre), 1e-3 * unit)
    first = circle(f, centre, r0)
    if first is None or first[1] <= 0:
        return None
    m = first[1]
    if m == 1:  # one simple zero: its place from the first circle (no conditioning to gain)
        return [(complex(centre + _power_sums(first[0], 1, r0)[0]), 1)]
    if m > 8:
        return None
    radii, rings = [r0], [first[0]]
    r = r0
    while 4.0 * r <= 1e-2 * scale:
        ring = circle(f, centre, 4.0 * r)
        if ring is None or ring[1] != m:
            break
        r *= 4.0
        radii.append(r)
        rings.append(ring[0])
    wide = centre + _zeros_from_sums(_power_sums(rings[-1], m, radii[-1]))
    if m == 1:
        return [(complex(wide[0]), 1)]
    mean = complex(np.mean(wide))
    if len(rings) > 1:
        narrow = centre + _zeros_from_sums(_power_sums(rings[-2], m, radii[-2]))
        disagree = abs(complex(np.mean(narrow)) - mean) + max(
            float(np.max(np.abs(np.sort_complex(narrow) - np.sort_complex(wide)))), 0.0
        )
    else:
        disagree = 1e-8 * scale
    spread = float(np.max(np.abs(wide - mean)))
    if spread <= 10.0 * disagree + 1e-12 * scale:
        return [(mean, m)]
    return [(complex(z), 1) for z in wide]


def multiplicity(f: LogF, w: complex, unit: float) -> int:
    """The zeros of f in a small square around w (its multiplicity when w is a root; 0 when
    it is not one after all; ``unit``: the frequency unit, the scale of a w near 0)."""
    h = 1e-7 * max(abs(w), 1e-3 * unit)
    for _ in range(4):
        try:
            return winding(f, (w.real - h, w.real + h, w.imag - h, w.imag + h), n0=8)
        except OnContour:
            h *= 3.1
    return 0

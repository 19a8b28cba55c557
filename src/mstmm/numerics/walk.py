"""The walk along the beam: renormalisation of the minors, segment factors, the pieces
between segment ends, and the event table (components in x order)."""

import math

import numpy as np
from numba import njit

from .layout import (
    EVENT_WIDTH,
    HEAD,
    SEGMENT_WIDTH,
)


@njit(cache=True, inline="always")
def renormalise(v):
    """Divide v by a power of two near its largest entry; return the natural log taken out.
    (The largest real or imaginary part: for a complex v, abs would cost a hypot each.)"""
    big = 0.0
    for a in range(v.shape[0]):
        big = max(big, abs(v[a].real), abs(v[a].imag))
    if big == 0.0 or not math.isfinite(big):
        return 0.0
    e = math.frexp(big)[1]
    f = math.ldexp(1.0, -e)
    for a in range(v.shape[0]):
        v[a] *= f
    return e * 0.6931471805599453


@njit(cache=True, inline="always")
def scale_minors(v, f):
    """v <- C2(diag(1, 1, f, f)) v: the minors of a state whose M and Q are scaled by f."""
    for a in range(1, 5):
        v[a] *= f
    v[5] *= f * f


@njit(cache=True, inline="always")
def segment_scale(p, seg):
    """(e, a) of segment seg: its EI over the first's, and beta_s / beta =
    (mbar_s / mbar_0 / e)^(1/4) (docs/components.md, section 3)."""
    i = HEAD + SEGMENT_WIDTH * seg
    e = p[i + 1] / p[1]
    return e, math.sqrt(math.sqrt(p[i + 2] / p[2] / e))


@njit(cache=True, inline="always")
def next_piece(p, seg, x):
    """End of the next beam piece towards x inside segment seg, and the segment after it
    (seg itself once x is reached)."""
    n_seg = int(p[3])
    if seg < n_seg - 1:
        x_end = p[HEAD + SEGMENT_WIDTH * seg]
        if x_end <= x:
            return x_end, seg + 1
    return x, seg


@njit(cache=True)
def insertion_order(keys, out):
    """out <- indices 0..n-1 in the stable ascending order of keys (insertion sort: the
    keys are sorted or nearly so, and it compiles in a fraction of np.argsort's time)."""
    n = keys.shape[0]
    for i in range(n):
        out[i] = i
    for i in range(1, n):
        j = i
        while j > 0 and keys[out[j - 1]] > keys[out[j]]:
            tmp = out[j - 1]
            out[j - 1] = out[j]
            out[j] = tmp
            j -= 1


@njit(cache=True, inline="always")
def event_row(p, r):
    """Start of the r-th row of the event table: rows are sorted by x (stable), as
    ``catalog.layout`` writes them and ``study.parameter_matrix`` keeps them."""
    return HEAD + SEGMENT_WIDTH * int(p[3]) + EVENT_WIDTH * r


@njit(cache=True)
def event_order(p):
    """Start of each row of the event table, in x order."""
    n_ev = int(p[4])
    rows = np.empty(n_ev, dtype=np.int64)
    for r in range(n_ev):
        rows[r] = event_row(p, r)
    return rows

"""The walk along the beam: renormalisation of the minors, segment factors, the pieces
between segment ends, and the event table (components in x order)."""

import math

import numpy as np
from numba.core import cgutils, types
from numba.extending import intrinsic, overload

from mstmm.jit import njit

from .layout import (
    COL_EI,
    COL_MBAR,
    EVENT_WIDTH,
    HEAD,
    SEGMENT_WIDTH,
    X_END,
)


@njit(cache=True, inline="always")
def largest(v):
    """v's largest real or imaginary part (for a complex v, abs would cost a hypot each)."""
    big = 0.0
    for a in range(v.shape[0]):
        big = max(big, abs(v[a].real), abs(v[a].imag))
    return big


@njit(cache=True, inline="always")
def scale_out(v, big):
    """Divide v by a power of two near ``big`` (its largest entry); return the natural log
    taken out."""
    if big == 0.0 or not math.isfinite(big):
        return 0.0
    e = math.frexp(big)[1]
    f = math.ldexp(1.0, -e)
    for a in range(v.shape[0]):
        v[a] *= f
    return e * 0.6931471805599453


@njit(cache=True, inline="always")
def renormalise(v):
    """Divide v by a power of two near its largest entry; return the natural log taken out."""
    return scale_out(v, largest(v))


@njit(cache=True)
def renormalise_end(v):
    """``renormalise``, compiled once and called: at the start and end of a walk, where an
    inlined copy would cost its compile time and save nothing."""
    return scale_out(v, largest(v))


#: ``renormalise_lazy`` leaves v alone while its largest entry lies in [2^-20, 2^20]: one
#: event's step changes it by a factor far from the 2^1000 of room left on either side.
LAZY_LOW = 2.0**-20
LAZY_HIGH = 2.0**20


@njit(cache=True, inline="always")
def renormalise_lazy(v):
    """``renormalise`` only when v's largest entry has left [LAZY_LOW, LAZY_HIGH] (the
    walks' per-event step: powers of two are exact either way, so the result is the
    same; the frexp and the divisions of every step were a fifth of a walk)."""
    big = largest(v)
    if LAZY_LOW <= big <= LAZY_HIGH:
        return 0.0
    return scale_out(v, big)


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
    e = p[i + COL_EI] / p[1]
    return e, math.sqrt(math.sqrt(p[i + COL_MBAR] / p[2] / e))


@njit(cache=True, inline="always")
def next_piece(p, seg, x):
    """End of the next beam piece towards x inside segment seg, and the segment after it
    (seg itself once x is reached)."""
    n_seg = int(p[3])
    if seg < n_seg - 1:
        x_end = p[HEAD + SEGMENT_WIDTH * seg + X_END]
        if x_end <= x:
            return x_end, seg + 1
    return x, seg


@njit(cache=True)
def stable_order(keys, out):
    """out <- indices 0..n-1 in the stable ascending order of keys: a bottom-up merge sort
    (O(n log n): the components' own frequencies come in x order, and an insertion sort
    cost 27 ms for 10,000 of them; plain loops compile in a fraction of np.argsort's
    time)."""
    n = keys.shape[0]
    for i in range(n):
        out[i] = i
    work = np.empty(n, dtype=np.int64)
    src = out
    dst = work
    swapped = False
    width = 1
    while width < n:
        for lo in range(0, n, 2 * width):
            mid = min(lo + width, n)
            hi = min(lo + 2 * width, n)
            i = lo
            j = mid
            for t in range(lo, hi):
                if i < mid and (j >= hi or keys[src[i]] <= keys[src[j]]):
                    dst[t] = src[i]
                    i += 1
                else:
                    dst[t] = src[j]
                    j += 1
        src, dst = dst, src
        swapped = not swapped
        width *= 2
    if swapped:
        for i in range(n):
            out[i] = src[i]


@njit(cache=True)
def own_table(values, xs, order):
    """(2, n): the own frequencies ``values`` in ``order`` (ascending, stable), and for
    each how many at the same x share it exactly (components listed in x order, so the
    stable order keeps them together): c components with one own frequency at one point
    have a root of multiplicity c - 1 there, their differences leaving the beam at rest."""
    n = order.shape[0]
    table = np.empty((2, n))
    i = 0
    while i < n:
        j = i
        while (
            j + 1 < n
            and values[order[j + 1]] == values[order[i]]
            and xs[order[j + 1]] == xs[order[i]]
        ):
            j += 1
        for t in range(i, j + 1):
            table[0, t] = values[order[t]]
            table[1, t] = j - i + 1
        i = j + 1
    return table


@njit(cache=True, inline="always")
def event_row(p, r):
    """Start of the r-th row of the event table: rows are sorted by x (stable), as
    ``catalog.layout`` writes them and ``study.parameter_matrix`` keeps them."""
    return HEAD + SEGMENT_WIDTH * int(p[3]) + EVENT_WIDTH * r


@njit(cache=True, inline="always")
def event_at(p, r, n_ev):
    """(row, x) of the r-th event of the walk along the beam; past the last one (r = n_ev)
    row 0 and x = L, the walk's end."""
    if r < n_ev:
        row = event_row(p, r)
        return row, p[row + 1]
    return 0, p[0]


#: What a step of the walk meets at its stop (``walk_next``).
STOP_EVENT = 0  # a component (its row of the event table)
STOP_SEGMENT = 1  # a segment's end: the walk goes on in the next segment
STOP_EXTRA = 2  # the caller's own stop (the frequency response's load and outputs)
STOP_END = 3  # x = L


@njit(cache=True, inline="always")
def walk_next(p, r, seg, pos, n_ev, extra):
    """One step of the walk along the beam, the one every characteristic function, the
    count, the mode-shape march, the frequency response and the Bloch cell take: from
    ``pos`` (SI) in segment ``seg``, the walk's next event being its r-th, to the next
    stop: that event's x, the end of segment seg, or ``extra`` (the caller's own stop,
    if pos <= extra and it comes first; math.inf for none). Returns ``(s, stop, what,
    row, r, seg)``: the piece from pos to ``stop`` lies in segment ``s`` (stop - pos is
    0 where two stops coincide), ``what`` is met at ``stop`` (``STOP_*``; ``row`` the
    event's row of p when it is STOP_EVENT), and ``(r, seg)`` is the walk's state past
    it. The caller takes the piece and moves pos to stop (or leaves pos, merging a short
    piece into the next), then handles what it met, until STOP_END."""
    row, x = event_at(p, r, n_ev)
    target, after = next_piece(p, seg, x)
    if pos <= extra < target:
        return seg, extra, STOP_EXTRA, row, r, seg
    if after != seg:
        return seg, target, STOP_SEGMENT, row, r, after
    if r == n_ev:
        return seg, target, STOP_END, row, r, seg
    return seg, target, STOP_EVENT, row, r + 1, seg


@njit(cache=True)
def event_order(p):
    """Start of each row of the event table, in x order."""
    n_ev = int(p[4])
    rows = np.empty(n_ev, dtype=np.int64)
    for r in range(n_ev):
        rows[r] = event_row(p, r)
    return rows


def borrowed(array):
    """``array`` viewed without a reference (its meminfo null): what a walk hands to the
    kernel's inlined events. An array passed to an inlined function is a new variable
    there, and numba increments and decrements its reference count around every call
    (atomic operations: a fifth of a 1000-component walk; its pruning pass cannot remove
    them across the events' branches). A null meminfo makes them no-ops. The view must
    not outlive ``array``: the walks hold both until they return. In plain Python (the
    interpreted tier) it is ``array`` itself."""
    return array


@intrinsic
def _unreferenced(typingctx, array):
    def codegen(context, builder, sig, args):
        src = context.make_array(sig.args[0])(context, builder, args[0])
        out = context.make_array(sig.return_type)(context, builder)
        for name in ("nitems", "itemsize", "data", "shape", "strides"):
            setattr(out, name, getattr(src, name))
        out.meminfo = cgutils.get_null_value(out.meminfo.type)
        out.parent = cgutils.get_null_value(out.parent.type)
        return out._getvalue()

    return array(array), codegen


@overload(borrowed)
def _borrowed(array):
    return lambda array: _unreferenced(array)


def nothing_like(array, ndim: int):
    """An empty array of ``array``'s dtype with ``ndim`` dimensions (1, 2 or 3), made
    without an allocation (its meminfo null: no reference counts either): what a walk
    holds in a work array's place until it needs the array (an allocation costs about
    14 ns, the reference counts of a view about as much). In plain Python, an empty
    array."""
    return np.empty((0,) * ndim, dtype=array.dtype)


def _nothing_intrinsic(ndim: int):
    @intrinsic
    def nothing(typingctx, array):
        def codegen(context, builder, sig, args):
            src = context.make_array(sig.args[0])(context, builder, args[0])
            out = context.make_array(sig.return_type)(context, builder)
            zero = context.get_constant(types.intp, 0)
            context.populate_array(
                out,
                data=src.data,
                shape=cgutils.pack_array(builder, [zero] * ndim),
                strides=cgutils.pack_array(builder, [src.itemsize] * ndim),
                itemsize=src.itemsize,
                meminfo=cgutils.get_null_value(out.meminfo.type),
                parent=cgutils.get_null_value(out.parent.type),
            )
            return out._getvalue()

        return array.copy(ndim=ndim, layout="C", readonly=False)(array), codegen

    return nothing


_NOTHING = {n: _nothing_intrinsic(n) for n in (1, 2, 3)}


@overload(nothing_like)
def _nothing_like(array, ndim):
    if not isinstance(ndim, types.IntegerLiteral):
        return None
    make = _NOTHING[ndim.literal_value]
    return lambda array, ndim: make(array)

"""The root search: Brent's refinement, the scan of the count in blocks, bisection of
clusters, the rigid-body dimension (``lowest``: every root certified by the count)."""

import math

import numpy as np

from mstmm.jit import njit

from .layout import (
    NODES_PER_MODE,
    OSC_SIDE,
    OWN_RESOLUTION,
    POLE_GUARD,
    PROBE_REACH,
)


@njit(cache=True)
def evaluate(delta, omegas, p, mant, logs):
    """mant[i], logs[i] = delta(omegas[i], p): the scan loop."""
    for i in range(omegas.shape[0]):
        mant[i], logs[i] = delta(omegas[i], p)


@njit(cache=True, inline="always")
def at_scale(m, g, ref):
    """The value (mantissa m, log g) times exp(-ref), the exponent clipped to [-700, 700]:
    finite, and never zero where the value is not (a bracket across which the scale moves
    by more than e^745 flushed one end to zero, and Brent took it for the root)."""
    return m * math.exp(max(-700.0, min(g - ref, 700.0)))


@njit(cache=True)
def scaled(delta, omega, p, ref):
    """mantissa * exp(log - ref), clipped (``at_scale``): continuous in omega, exact sign."""
    m, g = delta(omega, p)
    return at_scale(m, g, ref)


@njit(cache=True, inline="always")
def own_range(own, inv2, w, j0, j1, t, log):
    """``own_product`` over own[j0:j1], onto (t, log): eight factors at a time (the
    compiler vectorises them), renormalised after each eight."""
    j = j0
    while j < j1:
        c = 1.0
        for i in range(j, min(j + 8, j1)):
            o = own[i]
            c *= (o - w) * (o + w) * inv2[i]
        t *= c
        a = abs(t)
        if a > 1e200 or a < 1e-200:
            if t == 0.0 or not math.isfinite(t):
                return t, log
            e = math.frexp(t)[1]
            t = math.ldexp(t, -e)
            log += e * 0.6931471805599453
        j += 8
    return t, log


@njit(cache=True)
def own_product(poles, w, skip_lo, skip_hi):
    """The product of 1 - w^2/own_j^2 = (own_j - w)(own_j + w)/own_j^2 over the own
    frequencies own_j = poles[0, j] outside j in [skip_lo, skip_hi] (``pole_data``), as
    (mantissa, log): the pole factors the characteristic function multiplies out (``refine_from``).
    The difference own_j - w is exact next to own_j, so each factor is good to a few ulp
    however close w comes."""
    own = poles[0]
    inv2 = poles[1]
    t, log = own_range(own, inv2, w, 0, max(skip_lo, 0), 1.0, 0.0)
    t, log = own_range(own, inv2, w, max(skip_hi + 1, 0), own.shape[0], t, log)
    return t, log


@njit(cache=True)
def pole_data(table):
    """(3, n) from ``oscillator_frequencies``' table: the positive own frequencies
    (ascending), 1/own^2 (``own_product``), and for each the most components at one point
    that have it (over its equal values: ``isolate`` writes their multiple root at it)."""
    keep = table[0] > 0.0
    n = int(np.count_nonzero(keep))
    poles = np.empty((3, n))
    poles[0] = table[0][keep]
    poles[1] = 1.0 / (poles[0] * poles[0])
    same = table[1][keep]
    i = 0
    while i < n:
        j = i
        most = same[i]
        while j + 1 < n and poles[0, j + 1] == poles[0, i]:
            j += 1
            most = max(most, same[j])
        poles[2, i : j + 1] = most
        i = j + 1
    return poles


@njit(cache=True)
def divided(delta, x, p, poles, skip_lo, skip_hi):
    """delta(x) over ``own_product`` (mantissa, log)."""
    m, g = delta(x, p)
    if poles.shape[1] == 0:
        return m, g
    pm, pg = own_product(poles, x, skip_lo, skip_hi)
    if pm == 0.0:  # not on [a, b] (``refine_from`` skips every factor vanishing there)
        return m, g
    return m / pm, g - pg


@njit(cache=True)
def divide(m, g, x, poles, skip_lo, skip_hi):
    """A known value (m, g) of delta at x over ``own_product``."""
    if poles.shape[1] == 0 or x != x:
        return m, g
    pm, pg = own_product(poles, x, skip_lo, skip_hi)
    if pm == 0.0:  # a point outside [a, b] on an own frequency: no value
        return np.nan, g
    return m / pm, g - pg


@njit(cache=True)
def refine(delta, a, b, p, rtol, maxiter):
    """Brent's method on a sign change in [a, b]; returns (root, iterations, converged)."""
    ma, ga = delta(a, p)
    mb, gb = delta(b, p)
    return refine_from(
        delta,
        a,
        ma,
        ga,
        b,
        mb,
        gb,
        np.nan,
        0.0,
        0.0,
        np.nan,
        0.0,
        0.0,
        np.empty((3, 0)),
        p,
        rtol,
        maxiter,
    )


@njit(cache=True, inline="always")
def brent_step(a, b, c, fa, fb, fc, d, e, m, tol):
    """Brent's step from b, the best end of the bracket [b, c] (a: the previous b; m = (c -
    b) / 2; d, e: the last two steps): inverse quadratic interpolation through a, b, c (a
    secant when a == c) where it falls well inside the bracket and shrinks fast enough,
    else bisection. Returns the new (d, e)."""
    if abs(e) >= tol and abs(fa) > abs(fb):
        s = fb / fa
        if a == c:
            pp = 2.0 * m * s
            q = 1.0 - s
        else:
            q = fa / fc
            r = fb / fc
            pp = s * (2.0 * m * q * (q - r) - (b - a) * (r - 1.0))
            q = (q - 1.0) * (r - 1.0) * (s - 1.0)
        if pp > 0.0:
            q = -q
        else:
            pp = -pp
        if 2.0 * pp < min(3.0 * m * q - abs(tol * q), abs(e * q)):
            return pp / q, d
    return m, m


@njit(cache=True)
def refine_from(delta, a, ma, ga, b, mb, gb, xl, ml, gl, xr, mr, gr, poles, p, rtol, maxiter):
    """Brent's method on a sign change in [a, b] whose values (mantissa, log) are known
    (the scan's): returns (root, iterations, converged).

    It runs on delta divided by the pole factors 1 - w^2/own_j^2 of the components' own
    frequencies (``poles``, ``pole_data``; none: empty), all but those inside [a, b] and the
    nearest one on either side: none of the others vanishes on [a, b], so the roots and signs
    there are delta's, but the function is far closer to linear next to a root that
    hundreds of own frequencies crowd (their factors, multiplied out, make delta a
    polynomial of that degree), while the nearest pole's factor kept makes the root of a
    weakly coupled component a near-linear one. xl < a and xr > b (nan: none) are nodes
    just outside the bracket, with their values: the first step interpolates (inverse
    quadratic) through the bracket and the one beside the end where the function is
    smaller, which steers it at once to the root's side of a humped bracket (two close
    nodes beside a component's own frequency give the slope there). From then on it is
    Brent's method as printed (safeguarded by bisection)."""
    # skipped: every own frequency in [a, b] and the nearest outside it on either side
    skip_lo = np.searchsorted(poles[0], min(a, b), side="left") - 1
    skip_hi = np.searchsorted(poles[0], max(a, b), side="right")
    ma, ga = divide(ma, ga, a, poles, skip_lo, skip_hi)
    mb, gb = divide(mb, gb, b, poles, skip_lo, skip_hi)
    ref = max(ga, gb)
    fa = at_scale(ma, ga, ref)
    fb = at_scale(mb, gb, ref)
    if fa == 0.0:
        return a, 0, True
    if fb == 0.0:
        return b, 0, True
    if (fa > 0.0) == (fb > 0.0):
        return 0.5 * (a + b), 0, False
    x3 = xr
    m3 = mr
    g3 = gr
    if abs(fa) < abs(fb):  # b is the end where the function is smaller
        x3 = xl
        m3 = ml
        g3 = gl
        a, b = b, a
        fa, fb = fb, fa
    c = a
    fc = fa
    if x3 == x3:
        m3, g3 = divide(m3, g3, x3, poles, skip_lo, skip_hi)
        f3 = at_scale(m3, g3, ref)
        if f3 == f3 and (f3 > 0.0) == (fb > 0.0) and abs(f3) > abs(fb) and f3 != fc and x3 != b:
            a = x3
            fa = f3
    d = b - c
    e = d
    for it in range(maxiter):
        if (fb > 0.0) == (fc > 0.0):
            c = a
            fc = fa
            d = b - a
            e = d
        if abs(fc) < abs(fb):
            a = b
            b = c
            c = a
            fa = fb
            fb = fc
            fc = fa
        tol = 2.0 * 2.220446049250313e-16 * abs(b) + 0.5 * rtol * abs(b)
        m = 0.5 * (c - b)
        if abs(m) <= tol or fb == 0.0:
            return b, it, True
        d, e = brent_step(a, b, c, fa, fb, fc, d, e, m, tol)
        a = b
        fa = fb
        if abs(d) > tol:
            b += d
        else:
            b += tol if m > 0.0 else -tol
        mb, gb = divided(delta, b, p, poles, skip_lo, skip_hi)
        fb = at_scale(mb, gb, ref)
    return b, maxiter, False


#: Layout of the search state shared by ``lowest_start``, ``lowest_run`` and
#: ``lowest_block``: the search has covered (0, state[STATE_W]], whose count is
#: state[STATE_COUNT]; state[STATE_K] roots are written; state[STATE_LAST] is the
#: true multiplicity of the last root written (it may exceed the copies written
#: when the lowest ``modes`` end inside a multiple root); state[STATE_CERTIFIED] is 1
#: while the count certifies every root written, 0 once it could not (the search then
#: goes on without it, and state[STATE_FAILED] is the frequency where it stopped).
STATE_W = 0
STATE_COUNT = 1
STATE_K = 2
STATE_LAST = 3
STATE_CERTIFIED = 4
STATE_FAILED = 5
STATE_SIZE = 6
#: Deferred refinement: where the caller gives ``state`` more room than STATE_SIZE, each
#: root a block writes from a sign change is written as nan, and its bracket, PENDING_WIDTH
#: numbers at state[STATE_SIZE + PENDING_WIDTH k:] (``node_bracket``), is left for
#: ``entries.entry_refine_pending`` to refine after the search, the roots in parallel:
#: Brent on an O(N) walk was most of a search among N = 10,000 components, one root after
#: another. (A parallel refinement called from inside the cached search was tried and
#: withdrawn, numba/numba#8578: this one is an entry called from Python.)
PENDING_WIDTH = 12
#: Blocks in a row that may end without a new root before the search gives up, where the
#: count cannot certify them (a beam has a natural frequency in every stretch of a few pi
#: of beta = lam L; below a foundation's cut-on it has none, which the count proves: those
#: blocks are skipped, ``skip_empty``).
MAX_STALLED_BLOCKS = 4
#: Doublings of the frequency over a stretch the count proves empty (``skip_empty``).
MAX_SKIPS = 200
#: Flag of a root in ``flags``: 0 trusted; 1 the count holds exactly one root in a piece
#: of round-off width across which the function does not change sign, or Brent's
#: method did not converge (the caller checks it again, and reports it NOT TRUSTED
#: if nothing confirms it).
UNTRUSTED = 1


@njit(cache=True)
def push_halves(lo, hi, nlo, nhi, top, a, mid, b, na, nm, nb):
    """Push the pieces (mid, b) and (a, mid) with their counts on a bisection stack (the
    lower one pops first); returns the new top."""
    lo[top] = mid
    hi[top] = b
    nlo[top] = nm
    nhi[top] = nb
    lo[top + 1] = a
    hi[top + 1] = mid
    nlo[top + 1] = na
    nhi[top + 1] = nm
    return top + 2


@njit(cache=True, inline="always")
def pending_room(state, modes):
    """Whether ``state`` has room for the brackets of ``modes`` roots (PENDING_WIDTH): the
    caller defers their refinement."""
    return state.shape[0] >= STATE_SIZE + PENDING_WIDTH * modes


@njit(cache=True)
def write_root(out, flags, k, modes, root, flag, copies, state):
    """Write ``copies`` copies of a root (up to ``modes`` values) with its flag; its
    multiplicity becomes state[STATE_LAST]. Returns the new k. A root written (not nan)
    clears the pending bracket its slot may hold from a block run again (PENDING_WIDTH)."""
    room = pending_room(state, modes)
    for _ in range(copies):
        if k < modes:
            out[k] = root
            flags[k] = flag
            if room and root == root:
                state[STATE_SIZE + PENDING_WIDTH * k] = np.nan
            k += 1
    state[STATE_LAST] = copies
    return k


@njit(cache=True)
def shared_inside(poles, a, b):
    """Whether [a, b] holds an own frequency that several components at one point share
    (``pole_data``)."""
    own = poles[0]
    shared = poles[2]
    j = np.searchsorted(own, a, side="left")
    while j < own.shape[0] and own[j] <= b:
        if shared[j] >= 2.0:
            return True
        j += 1
    return False


@njit(cache=True)
def snap_shared(poles, x):
    """x, or the own frequency w next to it that c >= 2 components at one point share when
    x lies within OWN_RESOLUTION sqrt(c) of w: there they have a root of multiplicity
    c - 1, and neither the count nor the function resolves roots (``isolate``)."""
    own = poles[0]
    shared = poles[2]
    j = np.searchsorted(own, x)
    for i in (j - 1, j):
        if 0 <= i < own.shape[0]:
            c = shared[i]
            if c >= 2.0 and abs(x - own[i]) <= OWN_RESOLUTION * math.sqrt(c) * own[i]:
                return own[i]
    return x


@njit(cache=True)
def near_pole(own, x):
    """The own frequency (``own`` ascending) within POLE_GUARD of x, where the count is
    not defined (a component there stands like a support); NaN when none is."""
    j = np.searchsorted(own, x)
    for i in (j - 1, j):
        if 0 <= i < own.shape[0] and abs(x - own[i]) <= POLE_GUARD * own[i]:
            return own[i]
    return math.nan


@njit(cache=True)
def off_pole(poles, x, a, b):
    """x, or where the count may be taken instead of x when x lies within POLE_GUARD of
    an own frequency w (``near_pole``): w (1 -+ POLE_GUARD), the one nearer x inside
    (a, b); NaN when neither is (the piece (a, b) is round-off wide around w)."""
    w = near_pole(poles[0], x)
    if math.isnan(w):
        return x
    below = w * (1.0 - POLE_GUARD)
    above = w * (1.0 + POLE_GUARD)
    first, second = (below, above) if x <= w else (above, below)
    if a < first < b:
        return first
    if a < second < b:
        return second
    return math.nan


@njit(cache=True)
def counts_off_poles(count, osc, omegas, p, out):
    """out[i] = count(omegas[i], p), taken at w (1 - POLE_GUARD) for an omegas[i] within
    POLE_GUARD of an own frequency w (``near_pole``), as the search's own counts are."""
    own = pole_data(osc(p))[0]
    for i in range(omegas.shape[0]):
        w = near_pole(own, omegas[i])
        out[i] = count(omegas[i] if math.isnan(w) else w * (1.0 - POLE_GUARD), p)


@njit(cache=True)
def sign_across(delta, a, b, eps, p):
    """Whether the function changes sign between a (1 - eps) and b (1 + eps)."""
    return (delta(a * (1.0 - eps), p)[0] > 0.0) != (delta(b * (1.0 + eps), p)[0] > 0.0)


@njit(cache=True)
def push_piece(sx, sn, top, a, ma, ga, b, mb, gb, xo, mo, go, na, nb):
    """Push the piece (a, b) of ``isolate`` with the function at its ends, a third point
    (xo, mo, go) and the counts at its ends. Returns the new top."""
    sx[top, 0] = a
    sx[top, 1] = ma
    sx[top, 2] = ga
    sx[top, 3] = b
    sx[top, 4] = mb
    sx[top, 5] = gb
    sx[top, 6] = xo
    sx[top, 7] = mo
    sx[top, 8] = go
    sn[top, 0] = na
    sn[top, 1] = nb
    return top + 1


@njit(cache=True)
def isolate(
    delta, count, a, ma, ga, b, mb, gb, na, nb, poles, p, out, flags, k, modes, state, rtol
):
    """Roots in (a, b) by bisection on the count N(b) - N(a), lowest first, each polished
    by Brent once alone on a sign change; a count jump that stays > 1 down to round-off
    width is a multiple root. (ma, ga), (mb, gb): the function at a and b. Each midpoint
    gets the count and the function (every midpoint ends a piece Brent may need, and its
    parent's other end is a third point for Brent's first step). The count at a midpoint
    is clamped into [na, nb], so that a count off by one at round-off distance from a
    root cannot add or lose a root.

    An own frequency w that c >= 2 components at one point share (``poles``,
    ``pole_data``) is left to the count (Brent's method never runs
    on a piece holding it), and a root found within OWN_RESOLUTION sqrt(c) of w is written
    at w: those components have a root of multiplicity c - 1 exactly at w (their
    differences leave the beam at rest), and next to it the count and the function, each
    multiplying c pole factors at round-off there, can put one of its copies a little
    beside it. Any other simple root that the function never changes sign across, or on
    which Brent does not converge, is written flagged UNTRUSTED. Writes out[k:] and
    flags[k:] (with multiplicity, up to modes) and the true multiplicity of the last root
    written into state[STATE_LAST]; returns the new k, or -1 if the bisection stack
    overflows."""
    cap = 256
    sx = np.empty((cap, 9))  # a, ma, ga, b, mb, gb, and a third point xo, mo, go
    sn = np.empty((cap, 2), dtype=np.int64)  # na, nb
    top = push_piece(sx, sn, 0, a, ma, ga, b, mb, gb, np.nan, 0.0, 0.0, na, nb)
    while top > 0 and k < modes:
        top -= 1
        a, ma, ga, b, mb, gb, xo, mo, go = sx[top]
        na = sn[top, 0]
        nb = sn[top, 1]
        if nb <= na:
            continue
        # never the count at an own frequency (``off_pole``): a piece too narrow to
        # halve away from one holds its roots there to round-off
        mid = off_pole(poles, 0.5 * (a + b), a, b)
        if b - a <= 8.9e-16 * b or math.isnan(mid):
            root = snap_shared(poles, 0.5 * (a + b))
            flag = 0
            if nb - na == 1 and root == 0.5 * (a + b) and not sign_across(delta, a, b, 1e-12, p):
                # a simple root that the function never changed sign across: the count
                # and the function disagree here
                flag = UNTRUSTED
            k = write_root(out, flags, k, modes, root, flag, nb - na, state)
            continue
        if nb - na == 1 and (ma > 0.0) != (mb > 0.0) and not shared_inside(poles, a, b):
            # (a piece holding an own frequency several components share goes on by the
            # count: their multiple root there changes the sign too when odd)
            xl = xo if xo < a else np.nan
            xr = xo if xo > b else np.nan
            root, its, ok = refine_from(
                delta, a, ma, ga, b, mb, gb, xl, mo, go, xr, mo, go, poles, p, rtol, 200
            )
            root = snap_shared(poles, root)
            k = write_root(out, flags, k, modes, root, 0 if ok else UNTRUSTED, 1, state)
            continue
        if top + 2 > cap:
            return -1
        # the count may dip or jump by one within an ulp or so of an oscillator
        # frequency (k - m w^2 at round-off); clamped, the piece keeps its total
        nm = min(max(count(mid, p), na), nb)
        mm, gm = delta(mid, p)
        # the upper half (mid, b) first, so that the lower one pops first
        top = push_piece(sx, sn, top, mid, mm, gm, b, mb, gb, a, ma, ga, nm, nb)
        top = push_piece(sx, sn, top, a, ma, ga, mid, mm, gm, b, mb, gb, na, nm)
    return k


@njit(cache=True)
def rigid_dimension(L, knots, h, cx, ct, n):
    """Dimension of the rigid motions left free by n constraints, exactly (no threshold).

    A rigid motion is continuous and piecewise linear on [0, L] with kinks only at the h
    free hinges knots[0] <= ... <= knots[h-1]: with the nodes 0, knots..., L it is its
    values v_0..v_{h+1} there (hat basis), dimension 2 + h. Constraint c sits at cx[c]
    (SI), ct[c] = 1 for Y = 0, 2 for theta = 0; it acts in the piece i = the number of
    knots < cx[c] (on a hinge it acts on its left side), on (v_i, v_{i+1}) only: a Y at x
    as the row (n_{i+1} - x, x - n_i), a theta as (-1, 1). Per piece, by exact float
    comparisons: two Y at different x, or a Y and a theta, have a 2 x 2 determinant
    (n_{i+1} - n_i)(x_2 - x_1) resp. n_{i+1} - n_i, nonzero: both node values are 0. Else
    the rows are one up to scale: a Y at a node zeroes that node's value; a Y inside links
    v_{i+1} = c v_i, c = -(n_{i+1} - x)/(x - n_i) != 0; a theta links v_{i+1} = v_i. The
    constraints then say: along each run of linked nodes the values are one times nonzero
    factors, zero if one of them is zeroed; so the dimension is the number of such runs
    (connected components of the link graph, a path) holding no zeroed node.
    Degenerate pieces (n_i = n_{i+1}: a hinge at an end, two hinges at one x) are the
    same point: v_i = v_{i+1} (a link), plus a slope of their own (one more dimension,
    unless a theta constraint acts on it: only at x = 0 with a hinge there); a Y there
    zeroes the node. This is the dimension of the null space of the exact constraints
    on W(x) = a + b x + sum_j c_j (x - k_j)_+ with the same assignment of constraints to
    pieces (``tests/reference_model.rigid_body_mode_count``)."""
    m = h + 1
    n_y = np.zeros(m, dtype=np.int64)
    y_at = np.zeros(m)
    two_y = np.zeros(m, dtype=np.bool_)
    theta = np.zeros(m, dtype=np.bool_)
    for c in range(n):
        i = 0
        while i < h and cx[c] > knots[i]:
            i += 1
        if ct[c] == 2:
            theta[i] = True
        elif n_y[i] == 0:
            n_y[i] = 1
            y_at[i] = cx[c]
        elif cx[c] != y_at[i]:
            two_y[i] = True
    zero = np.zeros(m + 1, dtype=np.bool_)
    link = np.zeros(m, dtype=np.bool_)
    dim = 0
    for i in range(m):
        a = 0.0 if i == 0 else knots[i - 1]
        b = L if i == h else knots[i]
        if a == b:
            link[i] = True
            zero[i] = zero[i] or n_y[i] > 0
            if not theta[i]:
                dim += 1
        elif two_y[i] or (n_y[i] > 0 and theta[i]):
            zero[i] = True
            zero[i + 1] = True
        elif n_y[i] > 0 and y_at[i] == a:
            zero[i] = True
        elif n_y[i] > 0 and y_at[i] == b:
            zero[i + 1] = True
        else:
            link[i] = n_y[i] > 0 or theta[i]
    i = 0
    while i <= m:
        dead = zero[i]
        while i < m and link[i]:
            i += 1
            dead = dead or zero[i]
        if not dead:
            dim += 1
        i += 1
    return dim


@njit(cache=True)
def lowest_start(count, rigid_modes, p, modes, out, flags, state, certify):
    """Start the search of the lowest ``modes``: the rigid-body zeros into out, the
    state at the bottom of the scan (lowest node beta = 1e-3). With ``certify`` the
    count there must hold exactly the rigid-body modes (else no elastic root below is
    excluded); where it does not, the search goes on uncertified from the lowest node
    (state[STATE_CERTIFIED] = 0). Returns the number of values written."""
    L = p[0]
    EI = p[1]
    mbar = p[2]
    scale = math.sqrt(EI / mbar) / (L * L)  # omega = scale * beta^2
    rigid = rigid_modes(p)
    state[STATE_K] = 0
    k = write_root(out, flags, 0, modes, 0.0, 0, rigid, state)
    state[STATE_K] = k
    state[STATE_CERTIFIED] = 1.0 if certify else 0.0
    state[STATE_FAILED] = 0.0
    w_lo = scale * 1e-6
    if k < modes and certify:
        # settle the bottom where the count holds exactly the rigid-body modes: lower
        # when an elastic root (a very soft oscillator) lies below it, higher when the
        # count has not yet registered a rigid-body mode (its -omega^2 pivot drowns in
        # round-off at very low frequency next to a constrained end); a count of exactly
        # the rigid-body modes at the bottom proves that no elastic root lies below it
        w = w_lo
        n = count(w, p)
        while n > rigid and w > 1e-300:
            w *= 1e-3
            n = count(w, p)
        while n < rigid and w < 1e300:
            w *= 2.0
            n = count(w, p)
        if n == rigid:
            w_lo = w
        else:
            state[STATE_CERTIFIED] = 0.0
            state[STATE_FAILED] = w_lo
    state[STATE_W] = w_lo
    state[STATE_COUNT] = rigid
    return k


@njit(cache=True)
def right_of_zero(delta, x, p):
    """The first point right of x (x (1 + eps), eps from 1e-15 up to 1e-8) where the
    function is not exactly zero, and its value there (x and 0 if there is none)."""
    eps = 1e-15
    while eps <= 1e-8:
        y = x * (1.0 + eps)
        m, g = delta(y, p)
        if m != 0.0:
            return y, m, g
        eps *= 8.0
    return x, 0.0, 0.0


#: Rows of the scan's node table (``lowest_block``): the node, the function there
#: (mantissa, log), its bracket's left point with the function there, and 1.0 for a
#: node of the uniform grid.
NODE_W = 0
NODE_M = 1
NODE_G = 2
NODE_WL = 3
NODE_ML = 4
NODE_GL = 5
NODE_UNIFORM = 6
NODE_ROWS = 7


@njit(cache=True)
def set_node(delta, nd, i, x, m, g, is_uniform, p):
    """Node i of the scan table ``nd`` at x with value (m, g); its bracket's left point
    is the node itself, or just right of it where the function is exactly zero there (a
    root at a component's own frequency: the next bracket starts where it has a sign)."""
    nd[NODE_W, i] = x
    nd[NODE_M, i] = m
    nd[NODE_G, i] = g
    nd[NODE_UNIFORM, i] = 1.0 if is_uniform else 0.0
    nd[NODE_WL, i] = x
    nd[NODE_ML, i] = m
    nd[NODE_GL, i] = g
    if m == 0.0:
        nd[NODE_WL, i], nd[NODE_ML, i], nd[NODE_GL, i] = right_of_zero(delta, x, p)


@njit(cache=True, inline="always")
def sign_change(nd, i):
    """1 if the function changes sign between node i - 1 (its bracket's left point) and
    node i."""
    return 1 if (nd[NODE_ML, i - 1] > 0.0) != (nd[NODE_M, i] > 0.0) else 0


@njit(cache=True)
def node_bracket(nd, i, n, r):
    """r <- the bracket of the sign change between nodes i - 1 and i (of n) as
    ``refine_from`` takes it: its ends (x, mantissa, log) and the nodes beside it as its
    third points (x nan: none)."""
    left = i >= 2 and nd[NODE_WL, i - 1] == nd[NODE_W, i - 1]
    right = i + 1 < n
    il = i - 2 if left else i
    ir = i + 1 if right else i
    r[0] = nd[NODE_WL, i - 1]
    r[1] = nd[NODE_ML, i - 1]
    r[2] = nd[NODE_GL, i - 1]
    r[3] = nd[NODE_W, i]
    r[4] = nd[NODE_M, i]
    r[5] = nd[NODE_G, i]
    r[6] = nd[NODE_W, il] if left else np.nan
    r[7] = nd[NODE_M, il]
    r[8] = nd[NODE_G, il]
    r[9] = nd[NODE_W, ir] if right else np.nan
    r[10] = nd[NODE_M, ir]
    r[11] = nd[NODE_G, ir]


@njit(cache=True)
def bracket_root(delta, r, poles, p, rtol):
    """The root of the bracket r (``node_bracket``) by ``refine_from``; returns (root,
    flag)."""
    root, its, ok = refine_from(
        delta, r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8], r[9], r[10], r[11],
        poles, p, rtol, 200,
    )  # fmt: skip
    return root, 0 if ok else UNTRUSTED


@njit(cache=True)
def write_changes(delta, nd, i0, j0, n, poles, p, rtol, out, flags, k, modes, state):
    """Write the root of every sign change between nodes i0 and j0 (refined only now, and
    only while fewer than ``modes`` are written; or left pending, PENDING_WIDTH). Returns
    the new k."""
    r = np.empty(PENDING_WIDTH)
    defer = pending_room(state, modes)
    for i in range(i0 + 1, j0 + 1):
        if k >= modes:
            break
        if sign_change(nd, i) == 1:
            if defer:
                node_bracket(nd, i, n, state[STATE_SIZE + PENDING_WIDTH * k :])
                k = write_root(out, flags, k, modes, np.nan, 0, 1, state)
                continue
            node_bracket(nd, i, n, r)
            root, flag = bracket_root(delta, r, poles, p, rtol)
            k = write_root(out, flags, k, modes, root, flag, 1, state)
    return k


@njit(cache=True)
def pair_probe(xa, ma, ga, xb, mb, gb, lo, hi):
    """A probe beside two close nodes xa < xb (the two sides of a component's own
    frequency) across which the function does not change sign: their secant's root r,
    when it lies outside [xa, xb] and within PROBE_REACH of the gap to the neighbouring
    node (lo below, hi above), gives the probe x = r + (r - nearer node), where a linear
    function has the opposite sign: a root that a weakly coupled component holds just
    outside its two nodes then has a sign change of its own instead of sharing a bracket
    with its neighbour's root. Returns the probe, or nan."""
    ref = max(ga, gb)
    fa = at_scale(ma, ga, ref)
    fb = at_scale(mb, gb, ref)
    if fa == fb or fa == 0.0 or fb == 0.0 or (fa > 0.0) != (fb > 0.0):
        return np.nan
    r = xb - fb * (xb - xa) / (fb - fa)
    if r > xb:
        d = r - xb
        if d < PROBE_REACH * (hi - xb):
            return xb + 2.0 * d
    elif r < xa:
        d = xa - r
        if d < PROBE_REACH * (xa - lo):
            return xa - 2.0 * d
    return np.nan


@njit(cache=True)
def lowest_block(
    delta, count, osc_frequencies, p, modes, out, flags, state, quota, certify, w_stop, rtol
):
    """Up to ``quota`` more roots above state[STATE_W], certified by ONE count.

    Scans the characteristic function (pole-free: each sign change brackets an odd
    number of roots) on a grid uniform in beta (NODES_PER_MODE per pi) plus a node on
    each side of every oscillator frequency, until ``quota`` sign changes are found (or
    (quota + 2) pi of beta are covered), and stops at that node, or at ``w_stop`` (a
    band's top) if that comes first. Two close nodes (the sides of an own frequency)
    without a sign change between them get a probe where their secant says a root lies
    just outside them (``pair_probe``). With ``certify``, the count at the last node
    proves the whole block when N(top) - N(bottom) equals the number of sign changes:
    then each brackets exactly one simple root and no root lies elsewhere. A piece where
    the two disagree is halved at the node nearest its middle by the count, down to
    neighbouring nodes whose roots ``isolate`` finds by count bisection: so a spurious
    sign change (a function that has lost its digits) is dropped and a root without one
    (a double root) is found. Without ``certify`` the sign-change roots are written
    unchecked. Brent's method refines a sign change only when its root is written (the
    block may hold more roots than ``modes`` asks for); a root on which it does not
    converge is flagged UNTRUSTED. Writes out[k:] and flags[k:] (up to ``modes``),
    advances ``state``; returns the new k, or -1 with the state unchanged (a count that
    decreases, a bisection that overflows)."""
    L = p[0]
    EI = p[1]
    mbar = p[2]
    scale = math.sqrt(EI / mbar) / (L * L)
    w_a = state[STATE_W]
    n_a = int(state[STATE_COUNT])
    k = int(state[STATE_K])
    b_a = math.sqrt(w_a / scale)
    h = math.pi / NODES_PER_MODE
    b_cap = b_a + (quota + 2) * math.pi
    # a node on each side of every component's own frequency, OSC_SIDE apart: a root
    # exactly there (a decoupled oscillator, identical ones) sits between two nodes where
    # the function has a clean sign, never on a node whose sign is round-off (Brent would
    # take that node for the root of a bracket holding another one)
    table = osc_frequencies(p)
    own = table[0]
    poles = pole_data(table)  # for Brent's method and ``isolate``
    osc = np.empty(2 * own.shape[0])
    for i in range(own.shape[0]):
        osc[2 * i] = own[i] * (1.0 - OSC_SIDE)
        osc[2 * i + 1] = own[i] * (1.0 + OSC_SIDE)
    osc = osc[(osc > w_a) & (osc < scale * b_cap * b_cap * (1.0 + 1e-15))]
    # room for the uniform nodes, every side node and a probe per pair of them
    size = int(math.ceil((b_cap - b_a) / h)) + 4 + osc.shape[0] + osc.shape[0] // 2 + 1
    nd = np.empty((NODE_ROWS, size))
    w = nd[NODE_W]
    m0, g0 = delta(w_a, p)
    set_node(delta, nd, 0, w_a, m0, g0, True, p)
    n = 1
    j = 1
    io = 0
    found = 0
    skipped = 0
    while n + 1 < size:
        bu = b_a + j * h
        wu = scale * bu * bu
        if io < osc.shape[0] and osc[io] < wu:
            x = osc[io]
            io += 1
            is_uniform = False
        else:
            x = wu
            j += 1
            is_uniform = True
        at_stop = x >= w_stop
        if at_stop:
            x = w_stop
            is_uniform = True
        if x <= w[n - 1]:
            if not is_uniform:
                # a side node of an own frequency equal (or within OSC_SIDE) to one
                # before: k equal oscillators hold up to k - 1 roots there that need not
                # change the sign, so the scan counts them towards the quota (else it
                # would run on for quota sign changes elsewhere)
                skipped += 1
            continue
        m, g = delta(x, p)
        if m == 0.0:
            x *= 1.0 + 4.4e-16
            m, g = delta(x, p)
        set_node(delta, nd, n, x, m, g, is_uniform, p)
        found += sign_change(nd, n)
        n += 1
        if (
            not is_uniform
            and not at_stop
            and n >= 3
            and nd[NODE_UNIFORM, n - 2] == 0.0
            and x - w[n - 2] <= 4.0 * OSC_SIDE * x
            and nd[NODE_WL, n - 2] == w[n - 2]
            and sign_change(nd, n - 1) == 0
        ):
            # the next node: a side node or the next uniform one
            hi = scale * (b_a + j * h) ** 2
            if io < osc.shape[0]:
                hi = min(hi, osc[io])
            hi = min(hi, w_stop)
            xp = pair_probe(w[n - 2], nd[NODE_M, n - 2], nd[NODE_G, n - 2], x, m, g, w[n - 3], hi)
            if xp == xp:
                mp, gp = delta(xp, p)
                if mp != 0.0 and xp > x:
                    set_node(delta, nd, n, xp, mp, gp, False, p)
                    found += sign_change(nd, n)
                    n += 1
                elif mp != 0.0:
                    # below the pair: nodes n - 2 and n - 1 move up by one
                    found -= sign_change(nd, n - 2)
                    for i in range(n, n - 2, -1):
                        nd[:, i] = nd[:, i - 1]
                    set_node(delta, nd, n - 2, xp, mp, gp, False, p)
                    n += 1
                    found += sign_change(nd, n - 3) + sign_change(nd, n - 2)
        if at_stop or found + skipped // 2 >= quota or (is_uniform and bu >= b_cap):
            break
    top = n - 1
    if not certify:
        k = write_changes(delta, nd, 0, top, n, poles, p, rtol, out, flags, k, modes, state)
        state[STATE_W] = w[top]
        state[STATE_COUNT] = n_a + found
        state[STATE_K] = k
        return k
    n_b = count(w[top], p)
    if n_b < n_a:
        return -1
    changes = np.zeros(n, dtype=np.int64)  # sign changes in (w[0], w[i]]
    for i in range(1, n):
        changes[i] = changes[i - 1] + sign_change(nd, i)
    cap = 128
    si = np.empty(cap, dtype=np.int64)
    sj = np.empty(cap, dtype=np.int64)
    sni = np.empty(cap, dtype=np.int64)
    snj = np.empty(cap, dtype=np.int64)
    si[0] = 0
    sj[0] = top
    sni[0] = n_a
    snj[0] = n_b
    depth = 1
    while depth > 0 and k < modes:
        depth -= 1
        i0 = si[depth]
        j0 = sj[depth]
        ni = sni[depth]
        nj = snj[depth]
        if nj - ni == changes[j0] - changes[i0]:
            k = write_changes(delta, nd, i0, j0, n, poles, p, rtol, out, flags, k, modes, state)
            continue
        if j0 - i0 == 1:
            k = isolate(
                delta,
                count,
                w[i0],
                nd[NODE_M, i0],
                nd[NODE_G, i0],
                w[j0],
                nd[NODE_M, j0],
                nd[NODE_G, j0],
                ni,
                nj,
                poles,
                p,
                out,
                flags,
                k,
                modes,
                state,
                rtol,
            )
            if k < 0:
                return -1
            continue
        if depth + 2 > cap:
            return -1
        cut = (i0 + j0) // 2
        nm = min(max(count(w[cut], p), ni), nj)
        depth = push_halves(si, sj, sni, snj, depth, i0, cut, j0, ni, nm, nj)
    state[STATE_W] = w[top]
    state[STATE_COUNT] = n_b
    state[STATE_K] = k
    return k


@njit(cache=True)
def lowest_run(
    delta, count, osc_frequencies, p, modes, out, flags, state, k_stop, certify, w_stop, rtol
):
    """Blocks of ``lowest_block`` until k_stop values are written (k_stop <= modes) or
    the search reaches ``w_stop`` (the top of a band; inf for the lowest modes). A block
    the count cannot certify runs again without it, and so does the rest of the search
    (state[STATE_CERTIFIED] = 0, state[STATE_FAILED] = where it stopped). Returns the new
    k, or -1 when MAX_STALLED_BLOCKS blocks in a row found nothing (the count or the
    function is broken here)."""
    k = int(state[STATE_K])
    certify = certify and state[STATE_CERTIFIED] == 1.0
    stalled = 0
    while 0 <= k < k_stop and state[STATE_W] < w_stop:
        k_before = k
        k = lowest_block(
            delta,
            count,
            osc_frequencies,
            p,
            modes,
            out,
            flags,
            state,
            k_stop - k,
            certify,
            w_stop,
            rtol,
        )
        if k < 0 and certify:
            certify = False
            state[STATE_CERTIFIED] = 0.0
            state[STATE_FAILED] = state[STATE_W]
            k = k_before
            continue
        if k < 0:
            return -1
        if k == k_before and certify:
            # no root in the block, and the count proves it: not a stall (a foundation,
            # grounded springs: no root below their cut-on, which may lie many blocks up);
            # jump by doubling while the count stays
            skip_empty(count, p, state, w_stop)
            continue
        stalled = stalled + 1 if k == k_before else 0
        if stalled > MAX_STALLED_BLOCKS:
            return -1
    return k


@njit(cache=True)
def skip_empty(count, p, state, w_stop):
    """Advance state[STATE_W] over frequencies the count proves empty: doubled while the
    count there equals state[STATE_COUNT] (and stays below ``w_stop``), then halved by
    bisection on the count to within pi of beta = lam L below the next root."""
    w = state[STATE_W]
    n = int(state[STATE_COUNT])
    hi = w_stop
    for _ in range(MAX_SKIPS):
        w2 = 2.0 * w
        if not w2 < w_stop:
            break
        if count(w2, p) != n:
            hi = w2
            break
        w = w2
    if math.isfinite(hi):
        scale = math.sqrt(p[1] / p[2]) / (p[0] * p[0])
        for _ in range(MAX_SKIPS):
            if math.sqrt(hi / scale) - math.sqrt(w / scale) <= math.pi:
                break
            mid = 0.5 * (w + hi)
            if count(mid, p) == n:
                w = mid
            else:
                hi = mid
    state[STATE_W] = w


@njit(cache=True)
def lowest(delta, count, osc_frequencies, rigid_modes, p, modes, out, flags, state, certify, rtol):
    """The lowest ``modes`` frequencies (rad/s, repeated by multiplicity) into ``out``, a
    flag for each in ``flags`` (0 trusted, UNTRUSTED), the search state in ``state``.

    ``lowest_start`` then ``lowest_run`` with the whole remaining quota (one count
    certifies the scan when every root is a sign change). Returns the number of values
    written (``modes`` unless the search stalled); state[STATE_LAST] is the true
    multiplicity of the last root (the count's, even when fewer copies fit in ``out``),
    state[STATE_CERTIFIED] whether the count certified them all."""
    lowest_start(count, rigid_modes, p, modes, out, flags, state, certify)
    return lowest_run(
        delta, count, osc_frequencies, p, modes, out, flags, state, modes, certify, np.inf, rtol
    )

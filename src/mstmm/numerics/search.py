"""The root search: Brent's refinement, the scan of the count in blocks, bisection of
clusters, the rigid-body dimension (``lowest``: every root certified by the count)."""

import math

import numpy as np
from numba import njit

from .layout import (
    NODES_PER_MODE,
    OSC_SIDE,
)


@njit(cache=True)
def evaluate(delta, omegas, p, mant, logs):
    """mant[i], logs[i] = delta(omegas[i], p): the scan loop."""
    for i in range(omegas.shape[0]):
        mant[i], logs[i] = delta(omegas[i], p)


@njit(cache=True)
def scaled(delta, omega, p, ref):
    """mantissa * exp(log - ref), clipped to stay finite: continuous in omega, exact sign."""
    m, g = delta(omega, p)
    return m * math.exp(min(g - ref, 700.0))


@njit(cache=True)
def refine(delta, a, b, p, rtol, maxiter):
    """Brent's method on a sign change in [a, b]; returns (root, iterations, converged)."""
    ma, ga = delta(a, p)
    mb, gb = delta(b, p)
    ref = max(ga, gb)
    fa = ma * math.exp(ga - ref)
    fb = mb * math.exp(gb - ref)
    if fa == 0.0:
        return a, 0, True
    if fb == 0.0:
        return b, 0, True
    if (fa > 0.0) == (fb > 0.0):
        return 0.5 * (a + b), 0, False
    c = a
    fc = fa
    d = b - a
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
                e = d
                d = pp / q
            else:
                d = m
                e = d
        else:
            d = m
            e = d
        a = b
        fa = fb
        if abs(d) > tol:
            b += d
        else:
            b += tol if m > 0.0 else -tol
        fb = scaled(delta, b, p, ref)
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
#: Blocks in a row that may end without a new root before the search gives up
#: (a beam has a natural frequency in every stretch of a few pi of beta = lam L).
MAX_STALLED_BLOCKS = 4
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


@njit(cache=True)
def write_root(out, flags, k, modes, root, flag, copies, state):
    """Write ``copies`` copies of a root (up to ``modes`` values) with its flag; its
    multiplicity becomes state[STATE_LAST]. Returns the new k."""
    for _ in range(copies):
        if k < modes:
            out[k] = root
            flags[k] = flag
            k += 1
    state[STATE_LAST] = copies
    return k


@njit(cache=True)
def isolate(delta, count, a, b, na, nb, p, out, flags, k, modes, state, rtol):
    """Roots in (a, b) by bisection on the count N(b) - N(a), lowest first, each polished
    by Brent once alone on a sign change; a count jump that stays > 1 down to round-off
    width is a multiple root. The count at a midpoint is clamped into [na, nb], so that
    a count off by one at round-off distance from a root cannot add or lose a root.
    A simple root that the function never changes sign across, or on which Brent does
    not converge, is written flagged UNTRUSTED. Writes out[k:] and flags[k:] (with
    multiplicity, up to modes) and the true multiplicity of the last root written into
    state[STATE_LAST]; returns the new k, or -1 if the bisection stack overflows."""
    cap = 256
    sa = np.empty(cap)
    sb = np.empty(cap)
    sna = np.empty(cap, dtype=np.int64)
    snb = np.empty(cap, dtype=np.int64)
    sa[0] = a
    sb[0] = b
    sna[0] = na
    snb[0] = nb
    top = 1
    while top > 0 and k < modes:
        top -= 1
        a = sa[top]
        b = sb[top]
        na = sna[top]
        nb = snb[top]
        if nb <= na:
            continue
        if b - a <= 8.9e-16 * b:
            flag = 0
            if nb - na == 1:
                # a simple root that the function never changed sign across: the count
                # and the function disagree here
                ma = delta(a * (1.0 - 1e-12), p)[0]
                mb = delta(b * (1.0 + 1e-12), p)[0]
                if (ma > 0.0) == (mb > 0.0):
                    flag = UNTRUSTED
            k = write_root(out, flags, k, modes, 0.5 * (a + b), flag, nb - na, state)
            continue
        if nb - na == 1:
            ma = delta(a, p)[0]
            mb = delta(b, p)[0]
            if (ma > 0.0) != (mb > 0.0):
                root, its, ok = refine(delta, a, b, p, rtol, 200)
                k = write_root(out, flags, k, modes, root, 0 if ok else UNTRUSTED, 1, state)
                continue
        if top + 2 > cap:
            return -1
        mid = 0.5 * (a + b)
        # the count may dip or jump by one within an ulp or so of an oscillator
        # frequency (k - m w^2 at round-off); clamped, the piece keeps its total
        nm = min(max(count(mid, p), na), nb)
        top = push_halves(sa, sb, sna, snb, top, a, mid, b, na, nm, nb)
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
        m = delta(y, p)[0]
        if m != 0.0:
            return y, m
        eps *= 8.0
    return x, 0.0


@njit(cache=True)
def lowest_block(
    delta, count, osc_frequencies, p, modes, out, flags, state, quota, certify, w_stop, rtol
):
    """Up to ``quota`` more roots above state[STATE_W], certified by ONE count.

    Scans the characteristic function (pole-free: each sign change brackets an odd
    number of roots) on a grid uniform in beta (NODES_PER_MODE per pi) plus a node on
    each side of every oscillator frequency, with Brent on each sign change, until ``quota`` sign
    changes are found (or (quota + 2) pi of beta are covered), and stops at the next
    uniform node, or at ``w_stop`` (a band's top) if that comes first. With ``certify``,
    the count at that node proves the whole block when N(top) - N(bottom) equals the
    number of sign changes: then each brackets exactly one simple root and no root lies
    elsewhere. A piece where the two disagree is halved at a uniform node by the count
    (never at an oscillator frequency, where multiple roots sit and the count is at
    round-off), down to single pieces whose roots ``isolate`` finds by count bisection:
    so a spurious sign change (a function that has lost its digits) is dropped and a
    root without one (a double root) is found. Without ``certify`` the sign-change roots
    are written unchecked. A root on which Brent does not converge is flagged UNTRUSTED.
    Writes out[k:] and flags[k:] (up to ``modes``), advances ``state``; returns the new
    k, or -1 with the state unchanged (a count that decreases, a bisection that
    overflows)."""
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
    own = osc_frequencies(p)
    osc = np.empty(2 * own.shape[0])
    for i in range(own.shape[0]):
        osc[2 * i] = own[i] * (1.0 - OSC_SIDE)
        osc[2 * i + 1] = own[i] * (1.0 + OSC_SIDE)
    osc = osc[(osc > w_a) & (osc < scale * b_cap * b_cap * (1.0 + 1e-15))]
    size = int(math.ceil((b_cap - b_a) / h)) + 3 + osc.shape[0]
    w = np.empty(size)
    uniform = np.zeros(size, dtype=np.bool_)
    change = np.zeros(size, dtype=np.int64)  # change[i]: a sign change in (w[i-1], w[i]]
    root = np.empty(size)
    root_flag = np.zeros(size, dtype=np.int64)
    w[0] = w_a
    uniform[0] = True
    m_prev = delta(w_a, p)[0]
    a_left = w_a
    if m_prev == 0.0:
        a_left, m_prev = right_of_zero(delta, w_a, p)
    n = 1
    j = 1
    io = 0
    found = 0
    while n < size:
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
            continue
        m = delta(x, p)[0]
        if m == 0.0:
            x *= 1.0 + 4.4e-16
            m = delta(x, p)[0]
        w[n] = x
        uniform[n] = is_uniform
        if (m > 0.0) != (m_prev > 0.0):
            r, its, ok = refine(delta, a_left, x, p, rtol, 200)
            change[n] = 1
            root[n] = r
            root_flag[n] = 0 if ok else UNTRUSTED
            found += 1
        a_left = x
        m_prev = m
        if m == 0.0:
            # a root exactly at this node (one at a component's own frequency): the next
            # bracket starts just right of it, where the function has a sign again
            a_left, m_prev = right_of_zero(delta, x, p)
        n += 1
        if at_stop or (is_uniform and (found >= quota or bu >= b_cap)):
            break
    top = n - 1
    if not certify:
        for i in range(1, n):
            if change[i] == 1:
                k = write_root(out, flags, k, modes, root[i], root_flag[i], 1, state)
        state[STATE_W] = w[top]
        state[STATE_COUNT] = n_a + found
        state[STATE_K] = k
        return k
    n_b = count(w[top], p)
    if n_b < n_a:
        return -1
    changes = np.zeros(n, dtype=np.int64)  # sign changes in (w[0], w[i]]
    for i in range(1, n):
        changes[i] = changes[i - 1] + change[i]
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
            for i in range(i0 + 1, j0 + 1):
                if change[i] == 1:
                    k = write_root(out, flags, k, modes, root[i], root_flag[i], 1, state)
            continue
        # cut at the uniform node nearest the middle
        cut = -1
        mid = (i0 + j0) // 2
        for d in range(j0 - i0):
            if i0 < mid + d < j0 and uniform[mid + d]:
                cut = mid + d
                break
            if i0 < mid - d < j0 and uniform[mid - d]:
                cut = mid - d
                break
        if cut < 0:
            k = isolate(delta, count, w[i0], w[j0], ni, nj, p, out, flags, k, modes, state, rtol)
            if k < 0:
                return -1
            continue
        if depth + 2 > cap:
            return -1
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
        stalled = stalled + 1 if k == k_before else 0
        if stalled > MAX_STALLED_BLOCKS:
            return -1
    return k


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

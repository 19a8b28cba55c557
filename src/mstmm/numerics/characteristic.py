"""A topology's characteristic functions, written once as ordinary code (issue 21).

The segment walk with its events, the stable second-compound chain (``delta_chain``, one
walk bound as ``delta_stable`` and, complex, ``delta_damped``: ``generic`` holds what
differs), the Wittrick-Williams count (``count_below``), the paper's
tree algorithm (``u_bar_paper``, paper Eq. (4)), the components' own frequencies and the
rigid motions. What differs between topologies is what SymPy prints into a kernel module
from each kind's declared physics (``mstmm.derive.emit``): the per-component functions
``event_chain``, ``event_count``, ``event_descriptor``, ... (one branch
per kind present). The ends are data (the parameter vector's head, read through the
tables of ``layout``: ``KNOWN``, ``UNKNOWN``, ``START_PAIR``, ``END_PAIR``), so one kernel
serves every end pair of its kinds.

:func:`bind_characteristic`, called at the end of a kernel module, compiles a copy of each
function below with the kernel's namespace as its globals: numba resolves the printed
functions by name at compile time (no function values, so the copy caches on disk), and
caches the copy beside the kernel's file under its signature (``_tagged``). The placeholders
below name what a kernel provides; they are never called.
"""

import math
import types

import numpy as np
from numba import prange

from mstmm.jit import njit

from . import generic
from .beam import (
    clamped_clamped_count,
    node_stiffness_step,
)
from .count import field_count, neg2, pair_count, pair_stiffness
from .layout import (
    COL_ETA,
    END_PAIR,
    HEAD,
    KNOWN,
    LEFT_END,
    MERGE_LENGTH,
    PENALTY,
    RICCATI_STEP,
    RIGHT_END,
    SEGMENT_WIDTH,
    START_PAIR,
    UNKNOWN,
)
from .linalg import lu_logdet
from .paper import apply_columns, segment_transfer
from .search import rigid_dimension
from .segment import (
    any_general,
    is_general,
    segment_compound,
    segment_constraints,
)
from .shapes import QMASS_ROWS
from .walk import (
    STOP_END,
    STOP_EVENT,
    borrowed,
    event_order,
    nothing_like,
    own_table,
    renormalise_end,
    renormalise_lazy,
    scale_minors,
    stable_order,
    walk_next,
)

__all__ = ["bind_characteristic", "UNDAMPED", "DAMPED"]

def _printed(*args):
    raise NotImplementedError("printed per topology into its kernel module")


def _bound(*args):
    raise NotImplementedError("generic's real or complex twin, bound into a kernel module")


#: v <- the pole-free compound step of the component of kind ``tag`` whose data block
#: starts at ``o`` (units L = EI_0 = mbar_0 = 1, w1 = (lam_0 L)^2, b4 = w1^2); returns the
#: log of a factor it took out (0 in a real kernel; complex, with the dashpots, in a damped
#: one).
event_chain = _printed
#: Zc <- the minors after the component; returns the negative pivots it adds to the count.
event_count = _printed
#: The component's descriptor (Cz, Cq, A, B, qmass; paper Eqs. (2)-(3)), real and complex.
event_descriptor = _printed
event_descriptor_c = _printed
#: Its mass matrix on [Y, theta] and its couplings' participation row (3 x 2); its own
#: frequencies; its unknowns; its constraints on rigid motions (stiffness, damping).
event_inertia = _printed
event_internal = _printed
event_nq = _printed
event_rigid = _printed
event_damps = _printed
#: What differs between the real and the complex chain: ``generic.REAL`` or
#: ``generic.COMPLEX``, put into a kernel's namespace by ``bind_characteristic``.
chain_frequency = work = stiffness = segment_factors = beam_step = _bound


def delta_chain(w, p):
    """Reduced determinant from the second-compound chain at the frequency w (rad/s), as
    (mantissa, log): a kernel's ``delta_stable`` (w = omega real) and, in a damped kernel,
    its ``delta_damped`` (w = w_d + i sigma complex, mantissa and log complex;
    mantissa * exp(log) is an entire function of w whose zeros are the damped natural
    frequencies, time dependence exp(i w t), sigma > 0 a decaying mode).

    One walk for both (``generic``: numba compiles each for its type): beta = lam_0 L
    (complex for a complex w: any branch, the chain depends on beta^4 = w1^2 only); each
    segment's EI (times 1 + i eta, its loss factor, in complex arithmetic); each
    component's pole-free compound step (with its dashpots, k -> k + i w c), the kernel's
    printed ``event_chain``; the beam functions' exp(-x) scaling and the renormalisation
    go into the log."""
    L = p[0]
    EI = p[1]
    mbar = p[2]
    w1, b4, beta = chain_frequency(w, L, EI, mbar)
    v = work(6)
    v[:] = 0.0
    v[START_PAIR[int(p[LEFT_END])]] = 1.0
    vb = borrowed(v)  # what the events get (no reference counts)
    pb = borrowed(p)
    log = 0.0 * v[0]  # 0, real or complex
    pos = 0.0
    seg = 0
    general = any_general(p)
    # a general segment's A, A^2, A^3 (of segment ``ready_f``) and its steps' work space,
    # allocated only where the beam has one: an allocation costs about 14 ns, and the
    # paper example's walk about 250 ns
    F = nothing_like(v, 3)
    U = nothing_like(v, 2)
    E = nothing_like(v, 2)
    w6 = nothing_like(v, 1)
    if general:
        F = work((4, 4, 4))
        U = work((4, 4))
        E = work((6, 6))
        w6 = work(6)
    # what the general pieces get: views without reference counts (``borrowed``), as the
    # events; a call with six counted arrays cost about a tenth of the every-term walk
    Fb = borrowed(F)
    Ub = borrowed(U)
    Eb = borrowed(E)
    wb = borrowed(w6)
    ready_f = -1
    # an Euler-Bernoulli segment's factors (of segment ``ready``): U_s = D U(beta_s) D^-1,
    # D = diag(1, 1, e, e) (docs/components.md)
    ready = 0
    e, f, bs = segment_factors(p, 0, beta, EI, mbar)
    n_ev = int(p[4])
    inv_L = 1.0 / L  # a multiplication per piece instead of a division
    r = 0
    while True:  # the walk along the beam (``walk_next``): a piece, then what it meets
        s, stop, what, row, r, seg = walk_next(pb, r, seg, pos, n_ev, math.inf)
        rho = (stop - pos) * inv_L
        if rho > 0.0:
            if general and is_general(p, s):  # exp(A h) of its field matrix
                stiff = stiffness(p[HEAD + SEGMENT_WIDTH * s + COL_ETA])
                step, ready_f = segment_compound(vb, pb, s, b4, stiff, rho, Fb, ready_f, Ub, Eb, wb)
                log += step
            else:
                if s != ready:
                    e, f, bs = segment_factors(p, s, beta, EI, mbar)
                    ready = s
                if e != 1.0:
                    scale_minors(vb, f)
                log += beam_step(vb, bs, rho)
                if e != 1.0:
                    scale_minors(vb, e)
            pos = stop
        if what == STOP_EVENT:
            tag = int(p[row])
            o = int(p[row + 2])
            log += event_chain(tag, pb, o, vb, w1, b4, L, EI, mbar)
            log += renormalise_lazy(v)
        elif what == STOP_END:
            break
    log += renormalise_end(v)
    return v[END_PAIR[int(p[RIGHT_END])]], log


#: The names a kernel binds the chain under (``bind_characteristic``).
delta_stable = delta_damped = delta_chain


def count_below(omega, p):
    """Number of natural frequencies below omega (with multiplicity), Wittrick-Williams.

    The state subspace admitted left of each node is carried as its minors Zc (the
    stable chain's Pluecker coordinates) from a free end, the left end's constraints
    added as a stiffness PENALTY; each piece adds the negative pivots of eliminating its
    near node (``pair_count``) and its clamped-clamped count J0, each component its own
    (the kernel's printed ``event_count``: a node stiffness, its own frequencies, a
    constraint as PENALTY, a hinge's split rotation). At x = L the right end's
    constraints join as PENALTY."""
    L = p[0]
    EI = p[1]
    mbar = p[2]
    beta = L * math.sqrt(math.sqrt(mbar * omega * omega / EI))
    b4 = (beta * beta) ** 2
    S = np.zeros((2, 2))
    U = np.zeros((4, 4))
    Zc = np.zeros(6)
    Zb = borrowed(Zc)  # what the events get (no reference counts)
    pb = borrowed(p)
    F = np.empty((4, 4, 4))  # a general segment's A, A^2, A^3 (of segment ``ready``)
    Fb = borrowed(F)
    ready = -1
    # an Euler-Bernoulli segment's factors (of segment ``ready_s``)
    ready_s = 0
    e, f, bs = segment_factors(p, 0, beta, EI, mbar)
    Zc[0] = 1.0  # the free end: Y and theta admitted
    left = KNOWN[int(p[LEFT_END])]
    if 0 in left or 1 in left:  # Y or theta held: a PENALTY stiffness each
        kY = PENALTY if 0 in left else 0.0
        kT = PENALTY if 1 in left else 0.0
        node_stiffness_step(Zc, kY, kT)
    renormalise_end(Zc)
    count = 0
    pos = 0.0
    seg = 0
    n_ev = int(p[4])
    inv_L = 1.0 / L  # a multiplication per piece instead of a division
    r = 0
    while True:  # the walk along the beam (``walk_next``); a piece up to MERGE_LENGTH
        # merges into the next one
        s, stop, what, row, r, seg = walk_next(pb, r, seg, pos, n_ev, math.inf)
        rho = (stop - pos) * inv_L
        if rho > MERGE_LENGTH and is_general(p, s):
            n_field, ready = field_count(Zb, pb, s, b4, rho, Fb, ready)  # pieces of J0 = 0
            count += n_field
            pos = stop
        elif rho > MERGE_LENGTH:
            # across the piece in steps of beta_s rho <= RICCATI_STEP (a long piece's
            # transfer matrix is rank-one to working precision): the pivots of each
            # near node and J0 of each step, with the segment's own properties
            if s != ready_s:
                e, f, bs = segment_factors(p, s, beta, EI, mbar)
                ready_s = s
            pieces = max(1, int(math.ceil(bs * rho / RICCATI_STEP)))
            if e != 1.0:
                scale_minors(Zc, f)
            for _ in range(pieces):
                count += pair_count(Zc, U, bs, rho / pieces)
                count += clamped_clamped_count(bs * rho / pieces)
            if e != 1.0:
                scale_minors(Zc, e)
            pos = stop
        if what == STOP_EVENT:
            tag = int(p[row])
            o = int(p[row + 2])
            count += event_count(tag, pb, o, Zb, b4, L, EI, mbar)
            renormalise_lazy(Zc)
        elif what == STOP_END:
            break
    detS = pair_stiffness(Zc, S)
    s00 = S[0, 0]
    s11 = S[1, 1]
    for d in KNOWN[int(p[RIGHT_END])]:
        if d < 2:  # Y or theta held by the end: a PENALTY stiffness
            S[d, d] += PENALTY

    d0 = S[0, 0] - s00
    d1 = S[1, 1] - s11
    return count + neg2(S[0, 0], S[1, 1], detS + d0 * s11 + d1 * s00 + d0 * d1)


def shape_event(p, row, b4, Cz, Cq, A, B, qmass):
    """The descriptor of the component at event row ``row`` (``event_descriptor``)."""
    return event_descriptor(
        int(p[row]), p, int(p[row + 2]), b4, p[0], p[1], p[2], Cz, Cq, A, B, qmass
    )


def shape_inertia(p, row, Mp):
    """The mass matrix on [Y, theta] of the component at event row ``row`` and the
    participation row of its couplings into Mp (3 x 2, ``event_inertia``); 1 if it holds
    one, else 0."""
    return event_inertia(int(p[row]), p, int(p[row + 2]), p[0], p[1], p[2], Mp)


def u_bar_paper(omega, p):
    """U_bar of paper Eq. (4) after the boundary reduction (units L = EI_0 = mbar_0 = 1).

    The tree algorithm: the state is carried as a linear combination (W, 4 x columns) of
    the unknowns: the left end's two, then each component's q (paper Eq. (2): Z+ = A Z +
    B q); each component adds its geometric equations Cz Z + Cq q = 0 (paper Eq. (3)) as
    rows; at x = L the main transfer equation Z_L = W u is reduced by the right end's
    conditions (its two unknowns as the last columns). Rows: main TE, then geometric."""
    L = p[0]
    EI = p[1]
    mbar = p[2]
    beta = L * math.sqrt(math.sqrt(mbar * omega * omega / EI))
    b4 = (beta * beta) ** 2
    n_ev = int(p[4])
    nq_total, most = shape_sizes(p)
    size = 4 + nq_total
    A = np.zeros((size, size))
    W = np.zeros((4, size))
    left = UNKNOWN[int(p[LEFT_END])]
    W[left[0], 0] = 1.0
    W[left[1], 1] = 1.0
    U = np.zeros((4, 4))
    col = np.zeros(4)
    nb = max(1, most)
    Cz = np.zeros((nb, 4))
    Cq = np.zeros((nb, nb))
    Ad = np.zeros((4, 4))
    B = np.zeros((4, nb))
    qmass = np.zeros((QMASS_ROWS, nb))
    pos = 0.0
    seg = 0
    ncols = 2
    nrow = 4
    r = 0
    while True:  # the walk along the beam (``walk_next``)
        s, stop, what, row, r, seg = walk_next(p, r, seg, pos, n_ev, math.inf)
        rho = (stop - pos) / L
        if rho > 0.0:
            segment_transfer(p, s, beta, rho, U)
            apply_columns(U, W, ncols, col)
            pos = stop
        if what == STOP_END:
            break
        if what != STOP_EVENT:
            continue
        nc, nq = shape_event(p, row, b4, Cz, Cq, Ad, B, qmass)
        for i in range(nc):
            for j in range(ncols):
                A[nrow + i, j] = (
                    Cz[i, 0] * W[0, j]
                    + Cz[i, 1] * W[1, j]
                    + Cz[i, 2] * W[2, j]
                    + Cz[i, 3] * W[3, j]
                )
            for j in range(nq):
                A[nrow + i, ncols + j] = Cq[i, j]
        apply_columns(Ad, W, ncols, col)
        for j in range(nq):
            for i in range(4):
                W[i, ncols + j] = B[i, j]
        ncols += nq
        nrow += nc
    for i in range(4):
        for j in range(ncols):
            A[i, j] = W[i, j]
    right = UNKNOWN[int(p[RIGHT_END])]
    A[right[0], ncols] = -1.0
    A[right[1], ncols + 1] = -1.0
    return A


def delta_paper(omega, p):
    """det U_bar of paper Eq. (4), as (mantissa, log)."""
    return lu_logdet(u_bar_paper(omega, p))


def oscillator_frequencies(p):
    """Row 0: the components' own frequencies (rad/s, ascending), where roots crowd; row 1:
    for each, how many components at its point have it too (``own_table``)."""
    rows = event_order(p)
    total, most = event_unknowns(p, rows)
    out = np.empty(total)
    xs = np.empty(total)
    n = 0
    for r in range(rows.shape[0]):
        m = event_internal(int(p[rows[r]]), p, int(p[rows[r] + 2]), p[0], p[1], p[2], out, n)
        xs[n:m] = p[rows[r] + 1]
        n = m
    order = np.empty(n, dtype=np.int64)
    stable_order(out[:n], order)
    return own_table(out[:n], xs[:n], order)


def evaluate_damped(ws, p, mant, logs):
    """mant[i], logs[i] = delta_damped(ws[i], p): a contour or a grid in one call."""
    for i in range(ws.shape[0]):
        mant[i], logs[i] = delta_damped(ws[i], p)


def evaluate_damped_parallel(ws, p, mant, logs):
    """``evaluate_damped`` in parallel over the points (compiled on first use: the search
    calls it for batches that cost more than starting the threads)."""
    for i in prange(ws.shape[0]):
        mant[i], logs[i] = delta_damped(ws[i], p)


def event_unknowns(p, rows):
    """Total unknowns of the components' full descriptors, and the most of one."""
    total = 0
    most = 0
    for r in range(rows.shape[0]):
        nq = event_nq(int(p[rows[r]]), p, int(p[rows[r] + 2]))
        total += nq
        most = max(most, nq)
    return total, most


def shape_sizes(p):
    """Unknowns of the components' full descriptors: (total, most of one)."""
    return event_unknowns(p, event_order(p))


def rigid_flag(p, row, dampers):
    """The rigid-motion constraint of the component at event row ``row`` (``event_rigid``;
    with ``dampers``, ``event_damps`` where that is none)."""
    flag = event_rigid(int(p[row]), p, int(p[row + 2]))
    if flag == 0 and dampers:
        flag = event_damps(int(p[row]), p, int(p[row + 2]))
    return flag


def shape_event_c(p, row, w1, Cz, Cq, A, B, qmass):
    """The descriptor of the component at event row ``row`` in complex arithmetic, at the
    complex frequency w1 (units of the kernel: b4 = w1^2; ``event_descriptor_c``)."""
    return event_descriptor_c(
        int(p[row]), p, int(p[row + 2]), w1, p[0], p[1], p[2], Cz, Cq, A, B, qmass
    )


def rigid_body_modes(p):
    """Number of zero natural frequencies: the rigid motions Y = a + b x (plus a kink at
    each free hinge) that the ends and the components leave free (they store no energy:
    supports and springs need Y = 0 where they are, rotational springs theta = 0)."""
    return rigid_motions(p, False)


def rigid_motions(p, dampers):
    """Dimension of the rigid motions the ends and components leave free; with
    ``dampers``, grounded dashpots count as Y = 0 too (the rigid motions that store no
    energy and dissipate none). Exact: ``rigid_dimension`` on the components' positions."""
    rows = event_order(p)
    n_ev = rows.shape[0]
    knots = np.empty(n_ev)
    room = n_ev + 4 + int(p[3]) * (2 * n_ev + 4)
    cx = np.empty(room)
    ct = np.empty(room, dtype=np.int64)
    h = 0
    n = 0
    for r in range(n_ev):
        flag = rigid_flag(p, rows[r], dampers)
        if flag == 3:
            knots[h] = p[rows[r] + 1]
            h += 1
        elif flag != 0:
            cx[n] = p[rows[r] + 1]
            ct[n] = flag
            n += 1
    for x, known in ((0.0, KNOWN[int(p[LEFT_END])]), (p[0], KNOWN[int(p[RIGHT_END])])):
        for d in known:
            if d < 2:  # Y (1) or theta (2) held by the end
                cx[n] = x
                ct[n] = d + 1
                n += 1
    n = segment_constraints(p, knots, h, cx, ct, n)
    return rigid_dimension(p[0], knots, h, cx, ct, n)


#: The characteristic functions of an undamped kernel, of a damped one (both get ``COMMON``).
COMMON = (
    "event_unknowns",
    "shape_sizes",
    "rigid_flag",
    "shape_event_c",
    "rigid_body_modes",
    "rigid_motions",
)
UNDAMPED = COMMON + (
    "delta_stable",
    "count_below",
    "shape_event",
    "shape_inertia",
    "u_bar_paper",
    "delta_paper",
    "oscillator_frequencies",
)
DAMPED = COMMON + ("delta_damped", "evaluate_damped", "evaluate_damped_parallel")
#: Compiled with numba's parallel target.
_PARALLEL = ("evaluate_damped_parallel",)


def _tagged(name: str, namespace: dict):
    """A copy of this module's function ``name`` with ``namespace`` as its globals, its
    qualified name ``kernel_<signature>.<name>`` (the signature covers everything the
    kernel's printed functions are made from, the topology included): numba caches the
    copy with the kernel, stamped with its file (``cache.UserCacheLocator``), as it
    caches the kernel's own functions."""
    f = globals()[name]
    copy = types.FunctionType(f.__code__, namespace, name, f.__defaults__, f.__closure__)
    copy.__qualname__ = f"kernel_{namespace['SIGNATURE'][:20]}.{name}"
    return copy


#: The events of the hot loops (``delta_chain``, ``count_below``): inlined into them by
#: numba (a compiled call costs about 20 ns, a fifth of a component's step; the walks
#: hand them ``borrowed`` arrays, whose reference counts cost nothing).
HOT_EVENTS = ("event_chain", "event_count")


def bind_characteristic(namespace: dict, names: tuple[str, ...]) -> None:
    """Compile a kernel module's printed functions (``event_<what>``: plain Python as
    SymPy prints them; those of :data:`HOT_EVENTS` inlined into their callers), and
    define the functions ``names`` of this module in its ``namespace``, each compiled (on
    first call, or loaded from numba's cache) with them and the real or complex twins of
    ``generic`` (complex: a damped kernel's ``names``, which hold ``delta_damped``).
    """
    for name, f in list(namespace.items()):
        if name.startswith("event_") and isinstance(f, types.FunctionType):
            if f.__module__ == namespace["__name__"]:
                inline = "always" if name in HOT_EVENTS else "never"
                namespace[name] = njit(cache=True, inline=inline)(f)
    namespace.update(generic.COMPLEX if "delta_damped" in names else generic.REAL)
    for name in names:
        namespace[name] = njit(cache=True, parallel=name in _PARALLEL)(_tagged(name, namespace))

"""Characteristic functions of the MSTMM topology ``clamped_free`` (generated, do not edit).

What: the natural frequencies of an Euler-Bernoulli beam of uniform or stepped segments
(clamped at x = 0, free at x = L) carrying no point components are the zeros of

* ``delta_paper``: det U_bar(omega), paper Eqs. (1)-(4): the tree algorithm with every
  component's unknowns and geometric equations (its descriptor), the boundary reduction,
  an LU determinant (units L = EI_0 = mbar_0 = 1);
* ``delta_stable`` (default): the same roots from the second-compound chain in
  units L = 1, EI_0 = 1, reduced beam functions (series below x = 1.5),
  every component's pole factor multiplied out exactly once, renormalised (by powers of
  two) whenever its largest minor leaves [2^-20, 2^20].

Both return ``(mantissa, log)`` with value ``mantissa * exp(log)``.
``count_below`` is the number of natural frequencies below omega (Wittrick-Williams:
clamped-piece counts plus the negative pivots of the dynamic stiffness, eliminated node
by node on the minors of the state subspace; each component adds its own), independent
of both.
One event loop walks the components in x order, one branch per kind present, printed
from each kind's descriptor (paper Eqs. (2)-(3)); ``shape_event_c`` gives the descriptors
in complex arithmetic (the frequency response, damped mode shapes).

Parameter vector p (SI): [L, EI_0, mbar_0, n_seg, n_ev, (x_end, EI, mbar, eta) per segment, (tag, x, offset) per component sorted by x, data blocks]
Regenerate: python -m mstmm.derive --topology clamped_free --out DIR
Derived by mstmm.derive with SymPy 1.14.0.
"""

from mstmm.numerics import *  # noqa: F403 (the shared numerics)

TOPOLOGY = "clamped_free"
SIGNATURE = "7ad3a826a41a74a96d3fb4324711e79a14d43d4d"
#: Component kinds of this kernel; a component's tag is its kind's index here.
KINDS = ()
#: What each kind's damping connects (``mstmm.derive.descriptor.DAMPERS``), for the proved
#: decay bound of damped roots (``mstmm.decay_bound``).
DAMPERS = {}
LEFT_UNKNOWN = (2, 3)
RIGHT_UNKNOWN = (0, 1)
LEFT_KNOWN = (0, 1)
START_PAIR = 5
END_PAIR = 5
RIGHT_KNOWN = (2, 3)
#: The ends for the shared mode-shape march: the left end's unknowns, the right end's knowns.
SHAPE_ENDS = np.array(LEFT_UNKNOWN + RIGHT_KNOWN, dtype=np.int64)
#: sha1 of the shared numerics' sources (``mstmm.numerics``) this kernel was printed with.
NUMERICS = "4f89994b47d1a5f1b37f429e12445b33a08d3f19"


@njit(cache=True)
def event_descriptor(tag, p, o, b4, L, EI, mbar, Cz, Cq, A, B, qmass):
    """The component's descriptor: Cz Z + Cq q = 0, Z+ = A Z + B q, qmass[0] the mass
    of each q, qmass[1] the share of it a rigid translation carries, qmass[2] what
    a unit force on it adds to minus its row (units L = EI = mbar = 1; paper
    Eqs. (2)-(3)); returns (constraints, unknowns)."""
    return 0, 0


@njit(cache=True)
def event_inertia(tag, p, o, L, EI, mbar, Mp):
    """Fill Mp with the mass matrix the component holds on [Y, theta] (units L = EI =
    mbar = 1; the b4 part of its A); return 1, or 0 where it holds none."""
    return 0


@njit(cache=True)
def event_internal(tag, p, o, L, EI, mbar, out, n):
    """Append the component's own frequencies (rad/s; scan nodes) to out[n:]; return n."""
    return n


@njit(cache=True)
def event_descriptor_c(tag, p, o, w1, L, EI, mbar, Cz, Cq, A, B, qmass):
    """The component's descriptor in complex arithmetic at the complex frequency w1 (units
    L = EI = mbar = 1, b4 = w1^2); returns (constraints, unknowns)."""
    return 0, 0


@njit(cache=True)
def event_nq(tag, p, o):
    """Unknowns of the component (full descriptor)."""
    return 0


@njit(cache=True)
def event_rigid(tag, p, o):
    """Kinematic constraint on rigid motions: 0 none, 1 Y = 0, 2 theta = 0, 3 free kink."""
    return 0


@njit(cache=True)
def event_damps(tag, p, o):
    """Constraint of a damper on rigid motions at w = 0: 0 none, 1 Y = 0, 2 theta = 0."""
    return 0


@njit(cache=True)
def delta_stable(omega, p):
    """Reduced determinant from the second-compound chain, as (mantissa, log).

    The hot loop is written out here (the segment walk, each kind's compound step printed
    in place): a call with array arguments would cost reference counting per event."""
    L = p[0]
    EI = p[1]
    mbar = p[2]
    beta = L * math.sqrt(math.sqrt(mbar * omega * omega / EI))
    b4 = (beta * beta) ** 2
    v = np.zeros(6)
    v[START_PAIR] = 1.0
    log = 0.0
    pos = 0.0
    seg = 0
    general = any_general(p)
    F = np.empty((4, 4, 4))  # a general segment's A, A^2, A^3 (of segment ``ready``)
    ready = -1
    U = np.empty((4, 4))  # work space of its steps
    E = np.empty((6, 6))
    w = np.empty(6)
    n_seg = int(p[3])
    n_ev = int(p[4])
    base = HEAD + SEGMENT_WIDTH * n_seg
    inv_L = 1.0 / L  # a multiplication per piece instead of a division
    for r in range(n_ev + 1):
        x = L
        row = 0
        if r < n_ev:
            row = base + EVENT_WIDTH * r
            x = p[row + 1]
        while True:  # the beam up to x, piece by piece (segment boundaries)
            target = x
            after = seg
            if seg < n_seg - 1 and p[HEAD + SEGMENT_WIDTH * seg] <= x:
                target = p[HEAD + SEGMENT_WIDTH * seg]
                after = seg + 1
            rho = (target - pos) * inv_L
            if rho > 0.0:
                if general and is_general(p, seg):  # exp(A h) of its field matrix
                    step, ready = segment_compound(v, p, seg, b4, 1.0, rho, F, ready, U, E, w)
                    log += step
                elif n_seg == 1:
                    log += beam_compound_step(v, beta, rho)
                else:  # U_s = D U(beta_s) D^-1, D = diag(1, 1, e, e) (docs/components.md)
                    i = HEAD + SEGMENT_WIDTH * seg
                    e = p[i + 1] / EI
                    f = 1.0 / e
                    v[1] *= f
                    v[2] *= f
                    v[3] *= f
                    v[4] *= f
                    v[5] *= f * f
                    log += beam_compound_step(v, beta * math.sqrt(math.sqrt(p[i + 2] / mbar * f)), rho)
                    v[1] *= e
                    v[2] *= e
                    v[3] *= e
                    v[4] *= e
                    v[5] *= e * e
                pos = target
            if after == seg:
                break
            seg = after
        if r == n_ev:
            break
        tag = int(p[row])
        o = int(p[row + 2])
        pass
        log += renormalise_lazy(v)
    log += renormalise(v)
    return v[END_PAIR], log


@njit(cache=True)
def count_below(omega, p):
    """Number of natural frequencies below omega (with multiplicity), Wittrick-Williams.

    The state subspace admitted left of each node is carried as its minors Zc (the
    stable chain's Pluecker coordinates) from a free end, the left end's constraints
    added as a stiffness PENALTY; each piece adds the negative pivots of eliminating its
    near node (``pair_count``) and its clamped-clamped count J0, each component its own
    (printed in place from its descriptor: a node stiffness, its own frequencies, a
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
    F = np.empty((4, 4, 4))  # a general segment's A, A^2, A^3 (of segment ``ready``)
    ready = -1
    Zc[0] = 1.0  # the free end: Y and theta admitted
    for d in LEFT_KNOWN:
        if d == 0:
            node_stiffness_step(Zc, PENALTY, 0.0)
        elif d == 1:
            node_stiffness_step(Zc, 0.0, PENALTY)
    renormalise(Zc)
    count = 0
    pos = 0.0
    seg = 0
    n_seg = int(p[3])
    n_ev = int(p[4])
    base = HEAD + SEGMENT_WIDTH * n_seg
    inv_L = 1.0 / L  # a multiplication per piece instead of a division
    for r in range(n_ev + 1):
        x = L
        row = 0
        if r < n_ev:
            row = base + EVENT_WIDTH * r
            x = p[row + 1]
        while True:  # the beam up to x, piece by piece (segment boundaries)
            target = x
            after = seg
            if seg < n_seg - 1 and p[HEAD + SEGMENT_WIDTH * seg] <= x:
                target = p[HEAD + SEGMENT_WIDTH * seg]
                after = seg + 1
            rho = (target - pos) * inv_L
            if rho > MERGE_LENGTH and is_general(p, seg):
                n_field, ready = field_count(Zc, p, seg, b4, rho, F, ready)  # pieces of J0 = 0
                count += n_field
                pos = target
            elif rho > MERGE_LENGTH:
                # across the piece in steps of beta_s rho <= RICCATI_STEP (a long piece's
                # transfer matrix is rank-one to working precision): the pivots of each
                # near node and J0 of each step, with the segment's own properties
                i = HEAD + SEGMENT_WIDTH * seg
                e = p[i + 1] / EI
                bs = beta * math.sqrt(math.sqrt(p[i + 2] / mbar / e))
                pieces = max(1, int(math.ceil(bs * rho / RICCATI_STEP)))
                if e != 1.0:
                    scale_minors(Zc, 1.0 / e)
                for _ in range(pieces):
                    count += pair_count(Zc, U, bs, rho / pieces)
                    count += clamped_clamped_count(bs * rho / pieces)
                if e != 1.0:
                    scale_minors(Zc, e)
                pos = target
            if after == seg:
                break
            seg = after
        if r == n_ev:
            break
        tag = int(p[row])
        o = int(p[row + 2])
        pass
        renormalise_lazy(Zc)
    detS = pair_stiffness(Zc, S)
    s00 = S[0, 0]
    s11 = S[1, 1]

    d0 = S[0, 0] - s00
    d1 = S[1, 1] - s11
    return count + neg2(S[0, 0], S[1, 1], detS + d0 * s11 + d1 * s00 + d0 * d1)


@njit(cache=True)
def shape_event(p, row, b4, Cz, Cq, A, B, qmass):
    """The descriptor of the component at event row ``row`` (``event_descriptor``)."""
    return event_descriptor(
        int(p[row]), p, int(p[row + 2]), b4, p[0], p[1], p[2], Cz, Cq, A, B, qmass
    )


@njit(cache=True)
def shape_inertia(p, row, Mp):
    """The mass matrix on [Y, theta] of the component at event row ``row`` into Mp
    (``event_inertia``); 1 if it holds one, else 0."""
    return event_inertia(int(p[row]), p, int(p[row + 2]), p[0], p[1], p[2], Mp)


@njit(cache=True)
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
    rows = event_order(p)
    n_ev = rows.shape[0]
    nq_total, most = shape_sizes(p)
    size = 4 + nq_total
    A = np.zeros((size, size))
    W = np.zeros((4, size))
    W[LEFT_UNKNOWN[0], 0] = 1.0
    W[LEFT_UNKNOWN[1], 1] = 1.0
    U = np.zeros((4, 4))
    col = np.zeros(4)
    nb = max(1, most)
    Cz = np.zeros((nb, 4))
    Cq = np.zeros((nb, nb))
    Ad = np.zeros((4, 4))
    B = np.zeros((4, nb))
    qmass = np.zeros((3, nb))
    pos = 0.0
    seg = 0
    ncols = 2
    nrow = 4
    for r in range(n_ev + 1):
        x = p[rows[r] + 1] if r < n_ev else L
        while True:
            target, after = next_piece(p, seg, x)
            rho = (target - pos) / L
            if rho > 0.0:
                segment_transfer(p, seg, beta, rho, U)
                apply_columns(U, W, ncols, col)
                pos = target
            if after == seg:
                break
            seg = after
        if r == n_ev:
            break
        nc, nq = shape_event(p, rows[r], b4, Cz, Cq, Ad, B, qmass)
        for i in range(nc):
            for j in range(ncols):
                A[nrow + i, j] = (Cz[i, 0] * W[0, j] + Cz[i, 1] * W[1, j] + Cz[i, 2] * W[2, j]
                                  + Cz[i, 3] * W[3, j])
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
    A[RIGHT_UNKNOWN[0], ncols] = -1.0
    A[RIGHT_UNKNOWN[1], ncols + 1] = -1.0
    return A


@njit(cache=True)
def delta_paper(omega, p):
    """det U_bar of paper Eq. (4), as (mantissa, log)."""
    return lu_logdet(u_bar_paper(omega, p))


@njit(cache=True)
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

@njit(cache=True)
def event_unknowns(p, rows):
    """Total unknowns of the components' full descriptors, and the most of one."""
    total = 0
    most = 0
    for r in range(rows.shape[0]):
        nq = event_nq(int(p[rows[r]]), p, int(p[rows[r] + 2]))
        total += nq
        most = max(most, nq)
    return total, most

@njit(cache=True)
def shape_sizes(p):
    """Unknowns of the components' full descriptors: (total, most of one)."""
    return event_unknowns(p, event_order(p))


@njit(cache=True)
def rigid_flag(p, row, dampers):
    """The rigid-motion constraint of the component at event row ``row`` (``event_rigid``;
    with ``dampers``, ``event_damps`` where that is none)."""
    flag = event_rigid(int(p[row]), p, int(p[row + 2]))
    if flag == 0 and dampers:
        flag = event_damps(int(p[row]), p, int(p[row + 2]))
    return flag


@njit(cache=True)
def shape_event_c(p, row, w1, Cz, Cq, A, B, qmass):
    """The descriptor of the component at event row ``row`` in complex arithmetic, at the
    complex frequency w1 (units of the kernel: b4 = w1^2; ``event_descriptor_c``)."""
    return event_descriptor_c(
        int(p[row]), p, int(p[row + 2]), w1, p[0], p[1], p[2], Cz, Cq, A, B, qmass
    )


@njit(cache=True)
def rigid_body_modes(p):
    """Number of zero natural frequencies: the rigid motions Y = a + b x (plus a kink at
    each free hinge) that the ends and the components leave free (they store no energy:
    supports and springs need Y = 0 where they are, rotational springs theta = 0)."""
    return rigid_motions(p, False)


@njit(cache=True)
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
    for x, known in ((0.0, LEFT_KNOWN), (p[0], RIGHT_KNOWN)):
        for d in known:
            if d < 2:  # Y (1) or theta (2) held by the end
                cx[n] = x
                ct[n] = d + 1
                n += 1
    n = segment_constraints(p, knots, h, cx, ct, n)
    return rigid_dimension(p[0], knots, h, cx, ct, n)

"""Characteristic functions of the MSTMM topology ``clamped_free__spring_mass`` (generated, do not edit).

What: the natural frequencies of an Euler-Bernoulli beam of uniform or stepped segments
(clamped at x = 0, free at x = L) carrying point components of the kinds spring_mass are the zeros of

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
Those functions are ordinary code (``mstmm.numerics.characteristic``, bound below): their
walk along the beam calls this module's ``event_<what>`` at each component, one branch per
kind present, printed by SymPy from each kind's declared physics (paper Eqs. (2)-(3)).

Parameter vector p (SI): [L, EI_0, mbar_0, n_seg, n_ev, (x_end, EI, mbar, eta) per segment, (tag, x, offset) per component sorted by x, data blocks]; tag 0 = spring_mass: k (N/m), m (kg), c (N s/m)
Regenerate: python -m mstmm.derive --topology clamped_free__spring_mass --out DIR
Derived by mstmm.derive with SymPy 1.14.0.
"""

from mstmm.numerics import *  # noqa: F403 (the shared numerics)

TOPOLOGY = "clamped_free__spring_mass"
SIGNATURE = "a2aa61880bea0e030d6a9cf19b15b177397eef9d"
#: Component kinds of this kernel; a component's tag is its kind's index here.
KINDS = ('spring_mass',)
#: What each kind's damping connects (``mstmm.derive.descriptor.DAMPERS``), for the proved
#: decay bound of damped roots (``mstmm.decay_bound``).
DAMPERS = {'spring_mass': 'carried'}
LEFT_UNKNOWN = (2, 3)
RIGHT_UNKNOWN = (0, 1)
LEFT_KNOWN = (0, 1)
START_PAIR = 5
END_PAIR = 5
RIGHT_KNOWN = (2, 3)
#: The ends for the shared mode-shape march: the left end's unknowns, the right end's knowns.
SHAPE_ENDS = np.array(LEFT_UNKNOWN + RIGHT_KNOWN, dtype=np.int64)
#: sha1 of the shared numerics' sources (``mstmm.numerics``) this kernel was printed with.
NUMERICS = "fbd1bdd9baa320299b5d3655e018a8fb9e3b2165"


@njit(cache=True, inline="always")
def event_chain(tag, p, o, v, w1, b4, L, EI, mbar):
    """v <- the component's pole-free compound step on the minors (the event of
    ``delta_stable``; units L = EI = mbar = 1, w1 = (lam_0 L)^2, b4 = w1^2,
    docs/components.md); returns the log of a factor taken out (none: 0)."""
    if tag == 0:  # spring_mass
        val_k = p[o + 0] * (L * L * L / EI)
        val_m = p[o + 1] * (1.0 / (L * mbar))
        v0 = v[0]
        v1 = v[1]
        v2 = v[2]
        v3 = v[3]
        v4 = v[4]
        v5 = v[5]
        t0 = 1.0/val_k
        t1 = b4*val_m
        t2 = t1*v0
        t3 = t1*v1
        t4 = t0*t1
        v[0] = t0*t2 - v0
        v[1] = t0*t3 - v1
        v[2] = t4*v2 - v2
        v[3] = t4*v3 - v3
        v[4] = t2 + t4*v4 - v4
        v[5] = t3 + t4*v5 - v5
    return 0.0


@njit(cache=True, inline="always")
def event_count(tag, p, o, Zc, b4, L, EI, mbar):
    """Zc <- the minors of the node's state subspace past the component; returns the
    negative pivots it adds to the Wittrick-Williams count (the event of
    ``count_below``)."""
    if tag == 0:  # spring_mass
        count = 0
        val_k = p[o + 0] * (L * L * L / EI)
        val_m = p[o + 1] * (1.0 / (L * mbar))
        pivot = -b4*val_m/val_k + 1.0
        v0 = Zc[0]
        v1 = Zc[1]
        v2 = Zc[2]
        v3 = Zc[3]
        v4 = Zc[4]
        v5 = Zc[5]
        t0 = 1.0/val_k
        t1 = b4*val_m
        t2 = t1*v0
        t3 = t1*v1
        t4 = t0*t1
        Zc[0] = t0*t2 - v0
        Zc[1] = t0*t3 - v1
        Zc[2] = t4*v2 - v2
        Zc[3] = t4*v3 - v3
        Zc[4] = t2 + t4*v4 - v4
        Zc[5] = t3 + t4*v5 - v5
        if pivot < 0.0:
            count += 1
        return count
    return 0


@njit(cache=True)
def event_descriptor(tag, p, o, b4, L, EI, mbar, Cz, Cq, A, B, qmass):
    """The component's descriptor: Cz Z + Cq q = 0, Z+ = A Z + B q, qmass[0] the mass
    of each q, qmass[1] the share of it a rigid translation carries, qmass[2] what
    a unit force on it adds to minus its row (units L = EI = mbar = 1; paper
    Eqs. (2)-(3)); returns (constraints, unknowns)."""
    if tag == 0:  # spring_mass
        val_k = p[o + 0] * (L * L * L / EI)
        val_m = p[o + 1] * (1.0 / (L * mbar))
        t0 = 1.0/val_k
        t1 = b4*val_m
        A[0, 0] = 1.0
        A[0, 1] = 0.0
        A[0, 2] = 0.0
        A[0, 3] = 0.0
        A[1, 0] = 0.0
        A[1, 1] = 1.0
        A[1, 2] = 0.0
        A[1, 3] = 0.0
        A[2, 0] = 0.0
        A[2, 1] = 0.0
        A[2, 2] = 1.0
        A[2, 3] = 0.0
        A[3, 0] = 0.0
        A[3, 1] = 0.0
        A[3, 2] = 0.0
        A[3, 3] = 1.0
        Cz[0, 0] = 1.0
        Cz[0, 1] = 0.0
        Cz[0, 2] = 0.0
        Cz[0, 3] = 0.0
        Cq[0, 0] = t0*t1 - 1.0
        B[0, 0] = 0.0
        B[1, 0] = 0.0
        B[2, 0] = 0.0
        B[3, 0] = t1
        qmass[0, 0] = val_m
        qmass[1, 0] = val_m
        qmass[2, 0] = t0
        return 1, 1
    return 0, 0


@njit(cache=True)
def event_inertia(tag, p, o, L, EI, mbar, Mp):
    """Fill Mp with the mass matrix the component holds on [Y, theta] (units L = EI =
    mbar = 1; the b4 part of its A); return 1, or 0 where it holds none."""
    if tag == 0:  # spring_mass
        return 0
    return 0


@njit(cache=True)
def event_internal(tag, p, o, L, EI, mbar, out, n):
    """Append the component's own frequencies (rad/s; scan nodes) to out[n:]; return n."""
    if tag == 0:  # spring_mass
        val_k = p[o + 0] * (L * L * L / EI)
        val_m = p[o + 1] * (1.0 / (L * mbar))
        b4 = val_k/val_m
        if b4 > 0.0 and math.isfinite(b4):
            out[n] = math.sqrt(b4 * EI / mbar) / (L * L)
            n += 1
        return n
    return n


@njit(cache=True)
def event_descriptor_c(tag, p, o, w1, L, EI, mbar, Cz, Cq, A, B, qmass):
    """The component's descriptor in complex arithmetic at the complex frequency w1 (units
    L = EI = mbar = 1, b4 = w1^2); returns (constraints, unknowns)."""
    if tag == 0:  # spring_mass
        val_k = p[o + 0] * (L * L * L / EI)
        val_m = p[o + 1] * (1.0 / (L * mbar))
        b4 = w1 * w1
        t0 = 1.0/val_k
        t1 = b4*val_m
        A[0, 0] = 1.0
        A[0, 1] = 0.0
        A[0, 2] = 0.0
        A[0, 3] = 0.0
        A[1, 0] = 0.0
        A[1, 1] = 1.0
        A[1, 2] = 0.0
        A[1, 3] = 0.0
        A[2, 0] = 0.0
        A[2, 1] = 0.0
        A[2, 2] = 1.0
        A[2, 3] = 0.0
        A[3, 0] = 0.0
        A[3, 1] = 0.0
        A[3, 2] = 0.0
        A[3, 3] = 1.0
        Cz[0, 0] = 1.0
        Cz[0, 1] = 0.0
        Cz[0, 2] = 0.0
        Cz[0, 3] = 0.0
        Cq[0, 0] = t0*t1 - 1.0
        B[0, 0] = 0.0
        B[1, 0] = 0.0
        B[2, 0] = 0.0
        B[3, 0] = t1
        qmass[0, 0] = val_m
        qmass[1, 0] = val_m
        qmass[2, 0] = t0
        return 1, 1
    return 0, 0


@njit(cache=True)
def event_nq(tag, p, o):
    """Unknowns of the component (full descriptor)."""
    if tag == 0:  # spring_mass
        return 1
    return 0


@njit(cache=True)
def event_rigid(tag, p, o):
    """Kinematic constraint on rigid motions: 0 none, 1 Y = 0, 2 theta = 0, 3 free kink."""
    if tag == 0:  # spring_mass
        return 0
    return 0


@njit(cache=True)
def event_damps(tag, p, o):
    """Constraint of a damper on rigid motions at w = 0: 0 none, 1 Y = 0, 2 theta = 0."""
    if tag == 0:  # spring_mass
        return 0
    return 0


# The characteristic functions: ordinary code (``mstmm.numerics.characteristic``), compiled
# with the printed functions above.
bind_characteristic(globals(), UNDAMPED)

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
Those functions are ordinary code (``mstmm.numerics.characteristic``, bound below): their
walk along the beam calls this module's ``event_<what>`` at each component, one branch per
kind present, printed by SymPy from each kind's declared physics (paper Eqs. (2)-(3)).

Parameter vector p (SI): [L, EI_0, mbar_0, n_seg, n_ev, (x_end, EI, mbar, eta) per segment, (tag, x, offset) per component sorted by x, data blocks]
Regenerate: python -m mstmm.derive --topology clamped_free --out DIR
Derived by mstmm.derive with SymPy 1.14.0.
"""

from mstmm.numerics import *  # noqa: F403 (the shared numerics)

TOPOLOGY = "clamped_free"
SIGNATURE = "95ac0279952db0ab028bbb8e3f85d13fc6646ab7"
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
NUMERICS = "fbd1bdd9baa320299b5d3655e018a8fb9e3b2165"


@njit(cache=True, inline="always")
def event_chain(tag, p, o, v, w1, b4, L, EI, mbar):
    """v <- the component's pole-free compound step on the minors (the event of
    ``delta_stable``; units L = EI = mbar = 1, w1 = (lam_0 L)^2, b4 = w1^2,
    docs/components.md); returns the log of a factor taken out (none: 0)."""
    return 0.0


@njit(cache=True, inline="always")
def event_count(tag, p, o, Zc, b4, L, EI, mbar):
    """Zc <- the minors of the node's state subspace past the component; returns the
    negative pivots it adds to the Wittrick-Williams count (the event of
    ``count_below``)."""
    return 0


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


# The characteristic functions: ordinary code (``mstmm.numerics.characteristic``), compiled
# with the printed functions above.
bind_characteristic(globals(), UNDAMPED)

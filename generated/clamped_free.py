"""Per-component functions of the MSTMM topology ``clamped_free`` (generated, do not edit).

An Euler-Bernoulli beam of uniform or stepped segments (clamped at x = 0, free at x = L)
carrying no point components. Printed by SymPy from the declared physics of its kinds
(paper Eqs. (2)-(3)): each ``event_<what>`` of ``mstmm.numerics.characteristic``, one
branch per kind, and the ends' constants. ``bind_characteristic`` compiles them with the
characteristic functions, ordinary code: ``delta_stable`` (default) and ``delta_paper``,
whose zeros are the natural frequencies, and ``count_below``, their number below omega.

Parameter vector p (SI): [L, EI_0, mbar_0, n_seg, n_ev, (x_end, EI, mbar, eta) per segment, (tag, x, offset) per component sorted by x, data blocks]
Regenerate: python -m mstmm.derive --topology clamped_free --out DIR
Derived by mstmm.derive with SymPy 1.14.0.
"""

from mstmm.numerics import *  # noqa: F403 (the shared numerics)

TOPOLOGY = "clamped_free"
SIGNATURE = "c867596f2e78821b0b8bb8ef75b1d2a6fa9f727d"
NUMERICS = "ee57f791484e2900f26d75be3a76b4cc949c46a2"
KINDS = ()
DAMPERS = {}

LEFT_UNKNOWN = (2, 3)
RIGHT_UNKNOWN = (0, 1)
LEFT_KNOWN = (0, 1)
RIGHT_KNOWN = (2, 3)
START_PAIR = 5
END_PAIR = 5


def event_chain(tag, p, o, v, w1, b4, L, EI, mbar):
    return 0.0


def event_count(tag, p, o, Zc, b4, L, EI, mbar):
    return 0


def event_descriptor(tag, p, o, b4, L, EI, mbar, Cz, Cq, A, B, qmass):
    return (0, 0)


def event_inertia(tag, p, o, L, EI, mbar, Mp):
    return 0


def event_internal(tag, p, o, L, EI, mbar, out, n):
    return n


def event_descriptor_c(tag, p, o, w1, L, EI, mbar, Cz, Cq, A, B, qmass):
    return (0, 0)


def event_nq(tag, p, o):
    return 0


def event_rigid(tag, p, o):
    return 0


def event_damps(tag, p, o):
    return 0


bind_characteristic(globals(), UNDAMPED)

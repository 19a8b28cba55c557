"""Per-component functions of the MSTMM topology ``clamped_free`` (generated, do not edit).

A beam (clamped at x = 0, free at x = L) carrying no point components: each kind's branch
of the events of ``mstmm.numerics.characteristic``, printed by SymPy from its declared
physics (paper Eqs. (2)-(3)), and the ends' constants; the last line compiles them with
the characteristic functions (``delta_stable`` (default) and ``delta_paper``, whose zeros
are the natural frequencies, and ``count_below``, their number below omega).

Parameter vector p (SI): [L, EI_0, mbar_0, n_seg, n_ev, (x_end, EI, mbar, eta) per segment, (tag, x, offset) per component sorted by x, data blocks]
Regenerate: python -m mstmm.derive --topology clamped_free --out DIR
Derived by mstmm.derive with SymPy 1.14.0.
"""

from mstmm.numerics import *  # noqa: F403 (the shared numerics)

TOPOLOGY = "clamped_free"
SIGNATURE = "098a08a490e69efadd068a155458ca36e3ac07cf"
NUMERICS = "642e01055a886f68563aae4981d0ffd144f43c2d"
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

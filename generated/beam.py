"""Per-component functions of the MSTMM topology ``beam`` (generated, do not edit).

A beam carrying no point components, at any end conditions (they are data: the parameter
vector's head): each kind's branch of the events of ``mstmm.numerics.characteristic``,
printed by SymPy from its declared physics (paper Eqs. (2)-(3)); the last line compiles
them with the characteristic functions (``delta_stable`` (default) and ``delta_paper``,
whose zeros are the natural frequencies, and ``count_below``, their number below omega).

Parameter vector p (SI): [L, EI_0, mbar_0, n_seg, n_ev, left end, right end (codes of ('clamped', 'pinned', 'free', 'sliding')), (x_end, EI, mbar, eta, *terms) per segment (SEGMENT_COLUMNS), (tag, x, offset) per component sorted by x, data blocks (DATA_BLOCKS)]
Regenerate: python -m mstmm.derive --topology beam --out DIR
Derived by mstmm.derive with SymPy 1.14.0.
"""

from mstmm.numerics import *  # noqa: F403 (the shared numerics)

TOPOLOGY = "beam"
SIGNATURE = "4ebea725bf9087b7a0148e670c5f4c9284e91c0f"
NUMERICS = "3f566c926c26546959f05aabdc05d55976564909"
KINDS = ()
DAMPERS = {}
#: The parameter layout this kernel reads (``catalog.layout``): a segment row's columns
#: (name, SI unit, exponents of L, EI_0, mbar_0 that make it dimensionless) and each
#: kind's data block after x (key, SI unit, shape).
SEGMENT_COLUMNS = (('x_end', 'm', (-1, 0, 0)),
 ('EI', 'N m^2', (0, -1, 0)),
 ('mass_per_length', 'kg/m', (0, 0, -1)),
 ('loss_factor', '1', (0, 0, 0)),
 ('kappa_GA', 'N', (2, -1, 0)),
 ('rho_I', 'kg m', (-2, 0, -1)),
 ('axial_force', 'N', (2, -1, 0)),
 ('foundation_k', 'N/m^2', (4, -1, 0)),
 ('foundation_kG', 'N', (2, -1, 0)))
DATA_BLOCKS = {}

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


def own_masses(kind, v):
    """The own mass of each unknown a damper of ``kind`` moves (the Schur complement
    of its mass matrix; units L = EI_0 = mbar_0 = 1) from its values ``v`` in those
    units: the proved decay bound's m_a (``mstmm.decay_bound``)."""
    return ()


bind_characteristic(globals(), UNDAMPED)

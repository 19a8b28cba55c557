"""Per-component functions of the MSTMM topology ``beam__spring_mass`` (generated, do not edit).

A beam carrying point components of the kinds spring_mass, at any end conditions (they are
data: the parameter vector's head): each kind's branch of the events of
``mstmm.numerics.characteristic``, printed by SymPy from its declared physics (paper Eqs.
(2)-(3)); the last line compiles them with the characteristic functions (``delta_stable``
(default) and ``delta_paper``, whose zeros are the natural frequencies, and
``count_below``, their number below omega).

Parameter vector p (SI): [L, EI_0, mbar_0, n_seg, n_ev, left end, right end (codes of ('clamped', 'pinned', 'free', 'sliding')), (x_end, EI, mbar, eta, *terms) per segment (SEGMENT_COLUMNS), (tag, x, offset) per component sorted by x, data blocks (DATA_BLOCKS)]; tag 0 = spring_mass: k (N/m), m (kg), c (N s/m)
Regenerate: python -m mstmm.derive --topology beam__spring_mass --out DIR
Derived by mstmm.derive with SymPy 1.14.0.
"""

from mstmm.numerics import *  # noqa: F403 (the shared numerics)

TOPOLOGY = "beam__spring_mass"
SIGNATURE = "fbb6c6da5d6299ad7759da5a22a396591468c62a"
NUMERICS = "3f566c926c26546959f05aabdc05d55976564909"
KINDS = ('spring_mass',)
DAMPERS = {'spring_mass': 'carried'}
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
DATA_BLOCKS = {'spring_mass': (('k', 'N/m', 'scalar'), ('m', 'kg', 'scalar'), ('c', 'N s/m', 'scalar'))}

def event_chain(tag, p, o, v, w1, b4, L, EI, mbar):
    if tag == 0:
        val_k = p[o]*(L**3/EI)
        val_m = p[o + 1]*(1.0/(L*mbar))
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


def event_count(tag, p, o, Zc, b4, L, EI, mbar):
    if tag == 0:
        count = 0
        val_k = p[o]*(L**3/EI)
        val_m = p[o + 1]*(1.0/(L*mbar))
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


def event_descriptor(tag, p, o, b4, L, EI, mbar, Cz, Cq, A, B, qmass):
    if tag == 0:
        val_k = p[o]*(L**3/EI)
        val_m = p[o + 1]*(1.0/(L*mbar))
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
        qmass[3, 0] = 0.0
        qmass[4, 0] = 0.0
        return (1, 1)
    return (0, 0)


def event_inertia(tag, p, o, L, EI, mbar, Mp):
    if tag == 0:
        return 0
    return 0


def event_internal(tag, p, o, L, EI, mbar, out, n):
    if tag == 0:
        val_k = p[o]*(L**3/EI)
        val_m = p[o + 1]*(1.0/(L*mbar))
        b4 = val_k/val_m
        if (b4 > 0.0) and (b4 < math.inf):
            out[n] = math.sqrt(EI)*math.sqrt(b4)/(L**2*math.sqrt(mbar))
            n += 1
        return n
    return n


def event_descriptor_c(tag, p, o, w1, L, EI, mbar, Cz, Cq, A, B, qmass):
    if tag == 0:
        val_k = p[o]*(L**3/EI)
        val_m = p[o + 1]*(1.0/(L*mbar))
        b4 = w1*w1
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
        qmass[3, 0] = 0.0
        qmass[4, 0] = 0.0
        return (1, 1)
    return (0, 0)


def event_nq(tag, p, o):
    if tag == 0:
        return 1
    return 0


def event_rigid(tag, p, o):
    if tag == 0:
        return 0
    return 0


def event_damps(tag, p, o):
    if tag == 0:
        return 0
    return 0


def own_masses(kind, v):
    """The own mass of each unknown a damper of ``kind`` moves (the Schur complement
    of its mass matrix; units L = EI_0 = mbar_0 = 1) from its values ``v`` in those
    units: the proved decay bound's m_a (``mstmm.decay_bound``)."""
    if kind == 'spring_mass':
        val_m = v['m']
        return (val_m,)
    return ()


bind_characteristic(globals(), UNDAMPED)

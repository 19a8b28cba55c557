"""The parameter vector's layout and the numerical constants every kernel shares.

``p = [L, EI_0, mbar_0, n_seg, n_ev, left end, right end, (x_end, EI, mbar, eta, *terms) per
segment, (tag, x, offset) per component sorted by x, data blocks]``
(``mstmm.catalog.layout``). A segment row's columns are named (``catalog.SEGMENT_COLUMNS``);
its terms (``mstmm.physics.segment``) are read through the tables below: each term's role,
whether the loss factor multiplies it, and the exponents of (L, EI_0, mbar_0) that make it
dimensionless."""

import numpy as np

from mstmm import catalog
from mstmm.physics import segment as terms

#: Parameter layout: head, then segment rows, then event rows (tag, x, offset).
HEAD = catalog.HEAD
SEGMENT_WIDTH = catalog.SEGMENT_WIDTH
EVENT_WIDTH = catalog.EVENT_WIDTH
#: Where the head holds the ends' codes (``catalog.END_CODES``), and per code: the state
#: indices ([Y, theta, M, Q]) the end holds at zero (``KNOWN``) and leaves unknown
#: (``UNKNOWN``); the pair of minors the stable chain starts from at a left end of that
#: kind (its unknowns) and ends on at a right end (its knowns), as indices of the 2x2
#: minors in lexicographic order. The ends are data: one kernel serves every end pair.
LEFT_END = catalog.LEFT_END
RIGHT_END = catalog.RIGHT_END
#: The pairs (i, j), i < j, of state indices: the rows and columns of a second compound.
PAIRS = catalog.PAIRS
KNOWN = tuple(catalog.KNOWN_ZERO[end] for end in catalog.END_CODES)
UNKNOWN = tuple(catalog.unknown(end) for end in catalog.END_CODES)
START_PAIR = tuple(PAIRS.index(pair) for pair in UNKNOWN)
END_PAIR = tuple(PAIRS.index(pair) for pair in KNOWN)
#: The named columns of a segment row.
X_END = catalog.SEGMENT_COLUMNS["x_end"]
COL_EI = catalog.SEGMENT_COLUMNS["EI"]
COL_MBAR = catalog.SEGMENT_COLUMNS["mass_per_length"]
COL_ETA = catalog.SEGMENT_COLUMNS["loss_factor"]
TERMS = catalog.TERMS_COLUMN
N_TERMS = len(terms.terms())
#: Each term's role code (``physics.segment.ROLE_CODES``), loss flag and unit scale.
TERM_ROLE = np.array([terms.ROLE_CODES[t.role] for t in terms.terms()] + [-1], dtype=np.int64)
TERM_LOSS = np.array([t.loss for t in terms.terms()] + [False], dtype=np.bool_)
TERM_SCALE = np.array([[float(e) for e in t.scale] for t in terms.terms()] + [[0.0] * 3])
SHEAR = terms.ROLE_CODES["shear"]
ROTARY = terms.ROLE_CODES["rotary"]
TENSION = terms.ROLE_CODES["tension"]
ROTATIONAL = terms.ROLE_CODES["rotational"]
FOUNDATION = terms.ROLE_CODES["foundation"]
#: Stiffness (units L = EI = 1) standing for a constrained degree of freedom in the count.
PENALTY = 1e60
#: A piece shorter than this (units of L) is merged into its node by the count: its
#: stiffness (~12/rho^3) must stay far below PENALTY.
MERGE_LENGTH = 1e-15
#: Longest piece (in lam*l) carried by one step of the count.
RICCATI_STEP = 1.0
#: Scan nodes per pi of beta = lam L in ``lowest`` (beam modes are about pi apart).
NODES_PER_MODE = 8
#: The scan's nodes beside a component's own frequency w0 are w0 (1 -+ OSC_SIDE).
OSC_SIDE = 1e-9
#: Two close nodes without a sign change get a probe (``search.pair_probe``) when their
#: secant puts a root outside them within this fraction of the gap to the next node.
PROBE_REACH = 0.25
#: A root found within OWN_RESOLUTION sqrt(c) (relative) of an own frequency that c >= 2
#: components share is written at it (``search.isolate``): c identical components at one
#: point have a root of multiplicity c - 1 exactly there, and within about 1e-14 sqrt(c)
#: to 2.5e-13 sqrt(c) of it (measured, 2 to 10,000 spring-masses) the count and the
#: function, multiplying c pole factors at round-off, can misplace one of its copies.
OWN_RESOLUTION = 2e-13
#: The count is never taken within POLE_GUARD (relative) of a component's own frequency
#: (``search.off_pole``): exactly there a component stands like a support (its pole-free
#: step has a zero pivot), and the count drops by up to one per component that has it
#: (144 instead of 1500 for 1,500 identical spring-masses at spaced points).
POLE_GUARD = 4e-15

"""A rotational (Winkler) foundation: torsion springs from the ground to the sections
along the segment, ``k_r psi^2 / 2`` of energy per length (psi the rotation of the
section; a rubber bearing layer that resists the rotation of a slab strip, or the
rotational stiffness of soil under a wide footing).

The worked example of docs/components.md for a segment term: a contributor adds it by
dropping this one file into ``src/mstmm/physics/terms/`` (tests/test_new_term.py does
exactly that in a copy of the package and checks it against a 30-digit model of the
differential equations written from the energies).
"""

NAME = "foundation_kr"
UNIT = "N"  # N m of moment per rad per m of length
CHECK = "nonnegative"
DOC = "rotational foundation stiffness per length k_r"
LIMIT = ("foundation_kr length^2/EI", 0.0, 1e12)
LOSS = True
POTENTIAL = {("psi", "psi"): 1}

"""A Pasternak shear layer on the foundation: ``k_G w'^2 / 2`` per length, the layer's
shear coupling neighbouring springs (a tension that the loss factor damps)."""

NAME = "foundation_kG"
UNIT = "N"
CHECK = "nonnegative"
DOC = "Pasternak shear layer k_G"
LIMIT = ("foundation_kG length^2/EI", 0.0, 1e12)
LOSS = True
SYMBOL = "k_G"
ORDER = 5
POTENTIAL = {("w'", "w'"): 1}

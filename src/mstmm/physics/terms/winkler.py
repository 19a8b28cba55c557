"""A Winkler foundation: springs to the ground along the segment, ``k w^2 / 2`` per
length."""

NAME = "foundation_k"
UNIT = "N/m^2"
CHECK = "nonnegative"
DOC = "Winkler foundation stiffness per length"
LIMIT = ("foundation_k length^4/EI", 0.0, 1e20)
LOSS = True
SYMBOL = "k_w"
ORDER = 4
POTENTIAL = {("w", "w"): 1}

"""An axial force P (tension positive): the work ``P w'^2 / 2`` per length of the
rotation of the beam's axis; a compression lowers the frequencies and buckles the beam
(``mstmm.buckling``). A load, not a stiffness: the loss factor leaves it alone."""

NAME = "axial_force"
UNIT = "N"
CHECK = "finite"
DOC = "axial force P, tension positive"
# (length / the bending boundary layer sqrt(EI/|P|))^2: 1e12 is a taut string of 1e6
# boundary layers, or a compression 1e11 times the buckling load
LIMIT = ("|axial_force| length^2/EI", 0.0, 1e12)
LOSS = False
SYMBOL = "P"
ORDER = 3
POTENTIAL = {("w'", "w'"): 1}

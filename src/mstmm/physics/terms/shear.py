"""Timoshenko shear stiffness: the section's rotation psi is its own field, and the shear
strain ``w' - psi`` stores ``kappa_GA (w' - psi)^2 / 2`` per length (0: no shear
deformation, Euler-Bernoulli's ``psi = w'``)."""

NAME = "kappa_GA"
UNIT = "N"
CHECK = "nonnegative"
DOC = "Timoshenko shear stiffness kappa G A (0: Euler-Bernoulli)"
# a shear stiffness this soft (kappa G A over E I/L^2): waves 1e3 times slower than
# bending ones; stiffer is fine (Euler-Bernoulli is the limit)
LIMIT = ("kappa_GA length^2/EI", 1e-6, float("inf"))
LOSS = True
SYMBOL = "kGA"
ORDER = 1
POTENTIAL = {("w'", "w'"): 1, ("w'", "psi"): -1, ("psi", "psi"): 1}

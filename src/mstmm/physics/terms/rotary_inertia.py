"""Rotary inertia of the sections: ``rho_I (d psi/dt)^2 / 2`` of kinetic energy per length."""

NAME = "rho_I"
UNIT = "kg m"
CHECK = "nonnegative"
DOC = "rotary inertia per length rho I"
# (radius of gyration / length)^2: 1 is already a block, not a beam
LIMIT = ("rho_I/(mass_per_length length^2)", 0.0, 1e6)
LOSS = False
SYMBOL = "rhoI"
ORDER = 2
KINETIC = {("psi", "psi"): 1}

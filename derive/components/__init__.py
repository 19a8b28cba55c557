"""Component library: one module per component kind, each a set of symbolic transfer matrices.

* :mod:`.beam` -- Euler-Bernoulli beam segment, paper Eq. (1), and its second compound.
* :mod:`.spring_mass` -- spring and lumped mass on ``[Y, Q]``, paper Eq. (1), and the
  spring-mass branch condensed onto the beam without poles.
* :mod:`.rigid_body` -- massless rigid body with two inputs (``U_I1``, ``U_I2``,
  ``H_I1``, ``H_I2``), paper Eqs. (2)-(3).
"""

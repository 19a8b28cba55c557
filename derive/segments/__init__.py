"""Segment kinds: one module per beam theory, each its field transfer matrix (paper Eq. (1))
and its count's clamped-clamped term J0.

* :mod:`.euler_bernoulli` -- the slender beam of the paper: its differential equation
  (``field``), its closed-form transfer matrix and compound (the fast path every kernel
  prints), J0 from ``1 - cos x cosh x``;
* :mod:`.general` -- Timoshenko, axial force, Winkler-Pasternak foundation, every term
  optional: its differential equation (``field``); its transfer matrix is ``exp(A l)``
  and its count's pieces have J0 = 0 by a proved bound (``mstmm.numerics.field``).
  Issue 22 wires it into scenes.
"""

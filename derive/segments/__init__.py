"""Segment kinds: one module per beam theory, each its field transfer matrix (paper Eq. (1))
and its count's clamped-clamped term J0.

* :mod:`.euler_bernoulli` -- the slender beam of the paper.
"""

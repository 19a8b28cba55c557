"""Rotation clamp: the rotation held at x, Y free (test kind, tests/test_declared_physics.py).

Declared by the freedom it holds, nothing else: its descriptor (a reaction moment), its
count (a stiffness penalty on theta) and its constraint on rigid motions are derived.
"""

from __future__ import annotations

from mstmm.catalog import Key

KIND = "rotation_clamp"
DOC = "rotation held at x, displacement free (test kind)"
KEYS = (Key("x", "m", check="interior", doc="position from the left end"),)
CONSTRAINS = ("theta",)

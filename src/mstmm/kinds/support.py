"""Rigid point support inside the span: Y = 0 there; slope and moment continuous.

Declared by the freedom it holds (``CONSTRAINS``); derived from it
(``descriptor.constraint``): ``q = [R]`` (the reaction, units EI_0 / L^2), ``Cz = e_Y``,
``Cq = 0``, ``A = I``, ``B = e_Q``; its compound step is the constrained map
``v+ = (i_{e_Y} v) ^ e_Q`` (the pole factor Cq = 0 taken out); the count holds Y with a
stiffness PENALTY; rigid motions need Y = 0 there.
"""

from __future__ import annotations

from mstmm.catalog import Key

KIND = "support"
DOC = "rigid point support at x: Y = 0, slope and moment continuous"
KEYS = (Key("x", "m", check="position", doc="position from the left end"),)
#: The freedom of the beam it holds.
CONSTRAINS = ("Y",)
#: Its marker and colour in plots (matplotlib).
MARKER = ("^", "k")
#: Name of its unknown in Z_all (the reaction).
UNKNOWNS = "R"

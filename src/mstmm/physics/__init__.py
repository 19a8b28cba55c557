"""Physics declared once, SymPy-free at run time (issue 42).

* :mod:`.energy`: a point kind's :class:`~mstmm.physics.energy.Energy` (its K, C, M over
  ``[Y, theta, q...]``; ``src/mstmm/kinds/`` declares the kinds);
* :mod:`.segment`: a segment term's declaration and the rules derived from it (the terms
  themselves are the files of ``mstmm/physics/terms/``);
* :mod:`.scales`: the unit scales every declaration's keys share.

``mstmm.derive`` derives the kernels from these declarations; the runtime reads them
without SymPy.
"""

from .energy import MOVES, Energy

__all__ = ["MOVES", "Energy"]

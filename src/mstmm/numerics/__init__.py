"""The numerics every kernel shares, as ordinary code: the drivers take a topology's
characteristic functions as first-class functions (``delta``, ``count``, ``event``, ...), so
they compile once per machine and serve every topology. The beam functions they use are
printed by SymPy (``mstmm.generated.euler_bernoulli``) and compiled in ``beam``; a kernel
module star-imports this package.

The modules: ``layout`` (the parameter vector), ``walk`` (the segment walk and the event
table), ``chain`` (kinds of stages in series), ``generic`` (what differs between the
real and the complex walk), ``linalg`` (a pivot, a small solve), ``count``
(Wittrick-Williams), ``field`` (a segment's field matrix from its differential
equation), ``segment`` (a piece's transfer, whichever the segment's kind), ``paper``
(the paper's determinant), ``characteristic`` (a topology's characteristic functions,
bound to the functions its kernel prints), ``search`` (the certified scan), ``shapes``
(mode shapes), ``frf`` (frequency response), ``bloch`` (a periodic cell's Bloch
conditions), ``doubling`` (N identical cells by doubling), ``entries`` (the drivers
called from Python).
"""

from . import cache  # noqa: F401  (numba's cache of these modules follows all of them)
from .beam import *  # noqa: F403
from .bloch import *  # noqa: F403
from .chain import *  # noqa: F403
from .characteristic import *  # noqa: F403
from .count import *  # noqa: F403
from .doubling import *  # noqa: F403
from .entries import *  # noqa: F403
from .field import *  # noqa: F403
from .frf import *  # noqa: F403
from .layout import *  # noqa: F403
from .linalg import *  # noqa: F403
from .paper import *  # noqa: F403
from .search import *  # noqa: F403
from .segment import *  # noqa: F403
from .shapes import *  # noqa: F403
from .walk import *  # noqa: F403

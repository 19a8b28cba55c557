"""Benchmarks of mstmm: ``python -m benchmarks`` (see ``benchmarks/__main__.py``).

In these processes kernels always run compiled: "warm" means numba's machine
code, not the interpreted first-solve tier (``mstmm.interpret``), which the
fresh-process measurements (subprocesses, default settings) show on their own.
Nor do they hand the shared drivers to helper processes (``mstmm.compiling``: a driver
would run as Python while its helper compiles it, and a warm-up would not compile it);
the first-run measurements turn the helpers on in their subprocesses.
"""

import os
import sys
from pathlib import Path

os.environ.setdefault("MSTMM_COMPILE_HELPERS", "0")

#: tests/, on the path: the references the benchmarks check against and compete with
#: (``reference_model``, ``reference_fem``: the finite-element model) live there, and
#: import no mstmm.
TESTS = Path(__file__).resolve().parent.parent / "tests"
if str(TESTS) not in sys.path:
    sys.path.insert(0, str(TESTS))

from mstmm import interpret  # noqa: E402

interpret.set_budget(0.0)

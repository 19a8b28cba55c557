"""Benchmarks of mstmm: ``python -m benchmarks`` (see ``benchmarks/__main__.py``).

In these processes kernels always run compiled: "warm" means numba's machine
code, not the interpreted first-solve tier (``mstmm.interpret``), which the
fresh-process measurements (subprocesses, default settings) show on their own.
Nor do they hand the shared drivers to helper processes (``mstmm.compiling``: a driver
would run as Python while its helper compiles it, and a warm-up would not compile it);
the first-run measurements turn the helpers on in their subprocesses.
"""

import os

os.environ.setdefault("MSTMM_COMPILE_HELPERS", "0")

from mstmm import interpret  # noqa: E402

interpret.set_budget(0.0)

"""Benchmarks of mstmm: ``python -m benchmarks`` (see ``benchmarks/__main__.py``).

In these processes kernels always run compiled: "warm" means numba's machine
code, not the interpreted first-solve tier (``mstmm.interpret``), which the
fresh-process measurements (subprocesses, default settings) show on their own.
"""

from mstmm import interpret

interpret.set_budget(0.0)

"""``njit`` for mstmm's compiled functions: one specialization per argument type.

numba types a call from one compiled function to another while it is still inferring
the caller's variables: a variable set to ``0`` before a loop that later holds an int64
is first ``Literal[int](0)``, and numba compiles the callee for that literal before it
compiles it again for int64. A literal constant argument (``piece_matrix(p, 0, ...)``)
gets its own specialization too. On a machine with nothing compiled, such duplicates were
7.5 s of 40 s (segment_compound, piece_matrix, field_count, field_prepare, carry, ...).

The dispatchers made here compile a nested call for the arguments' non-literal types
(``numba.types.unliteral``); the caller's literal arguments convert to them. No function of
mstmm specializes on a literal value: a flag that selects code is a runtime branch.
"""

from __future__ import annotations

import os

import numba
from numba import njit as _numba_njit
from numba import types
from numba.core.dispatcher import Dispatcher

__all__ = ["njit"]

# mstmm's parallel loops (sweeps, the frequency response, dispersion, damped contours)
# run on numba's threads: with GNU OpenMP (numba's
# "omp" layer, picked first where libgomp is found) a process that forks after one of
# them kills its children ("Terminating: fork() called from a process already using GNU
# OpenMP"): a multiprocessing pool of solves after a parameter sweep. A
# fork-safe layer (TBB if installed, else numba's workqueue) unless the user chose one.
if "NUMBA_THREADING_LAYER" not in os.environ:
    numba.config.THREADING_LAYER = "forksafe"


def _get_call_template(self, args, kws):
    """``Dispatcher.get_call_template`` for the arguments' non-literal types."""
    args = tuple(types.unliteral(a) for a in args)
    kws = {k: types.unliteral(v) for k, v in kws.items()}
    return Dispatcher.get_call_template(self, args, kws)


def _unliteral(dispatcher):
    # inline="always" functions are inlined as IR at their call sites: no dispatch to patch
    if isinstance(dispatcher, Dispatcher) and dispatcher.targetoptions.get("inline") != "always":
        dispatcher.get_call_template = _get_call_template.__get__(dispatcher)
    return dispatcher


def njit(*args, **kwargs):
    """``numba.njit``, its dispatchers compiling nested calls for non-literal types."""
    if len(args) == 1 and not kwargs and callable(args[0]):
        return _unliteral(_numba_njit(args[0]))
    decorate = _numba_njit(*args, **kwargs)
    return lambda f: _unliteral(decorate(f))

"""mstmm.derive: the symbolic stage (SymPy only; never imported on the solve path).

Stages, each a module, input -> output:

1. ``descriptor`` -- a kind's declared energy (``mstmm/kinds/<kind>.py``) -> its
   descriptor, point matrix and pole-free compound step; ``segments/`` the beam
   segment kinds (Eq. (1) and its compound forms), ``rigid_body`` the massless rigid
   body; ``special`` the reduced beam functions that keep them exact at small
   arguments.
2. ``assemble`` -- a chain of components -> the overall transfer equation
   ``U_all Z_all = 0`` (paper Eqs. (2)-(4)).
3. ``reduce`` -- end conditions -> the square ``U_bar`` (paper, after Eq. (4)).
4. ``printer`` + ``emit`` -- a topology -> the numba kernel source (template
   ``templates/kernel.py.tmpl``), signed with a content hash.

It reads the runtime's SymPy-free ground floor (``mstmm.catalog``: end conditions,
kinds, topologies, layout; ``mstmm.sign``: a kernel's SIGNATURE) and nothing else of
the runtime: stages run one way, model -> derive -> printed source.

Public entry points (imported lazily, SymPy with them): :func:`symbolic`
(inspect a scene's ``U_all``, ``U_bar`` and, when small, its determinant),
:func:`component_matrices` (the library of paper Eq. (1)-(3)) and
:func:`kernel_source`.
"""

from __future__ import annotations

from importlib import import_module

__all__ = [
    "MAX_DETERMINANT_SIZE",
    "Derivation",
    "component_matrices",
    "kernel_source",
    "symbolic",
    "symbols",
]

#: Where each public name lives: importing this package must not import SymPy.
_LAZY = {
    "MAX_DETERMINANT_SIZE": "derivation",
    "Derivation": "derivation",
    "component_matrices": "derivation",
    "symbolic": "derivation",
    "kernel_source": "emit",
}


def __getattr__(name: str):
    if name in _LAZY:
        return getattr(import_module(f"{__name__}.{_LAZY[name]}"), name)
    if name == "symbols":
        return import_module(f"{__name__}.symbols")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

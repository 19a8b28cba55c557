"""mstmm.derive: the symbolic stage (SymPy only; never imported on the solve path).

Stages, each a module, input -> output:

1. ``components/`` -- component kinds -> symbolic transfer matrices
   (beam segment Eq. (1), spring, lumped mass, massless rigid body, and the
   compound forms of the stable formulation); ``special`` the reduced beam
   functions that keep them exact at small arguments.
2. ``assemble`` -- a chain of components -> the overall transfer equation
   ``U_all Z_all = 0`` (paper Eqs. (2)-(4)).
3. ``reduce`` -- end conditions -> the square ``U_bar`` (paper, after Eq. (4)).
4. ``printer`` + ``emit`` -- a topology -> the numba kernel source (template
   ``templates/kernel.py.tmpl``), signed with a content hash.

SymPy-free parts, imported by the runtime: ``catalog`` (end conditions, kinds,
topologies) and ``sign`` (a kernel's SIGNATURE). Nothing here imports the runtime
package ``mstmm``.

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

"""The kernel's intermediate representation: what a kernel is, before it is printed.

Declarations -> IR -> printer, as FFCx lowers a form to its IR and SymPy's codegen builds
a ``Routine`` before any printer runs. :func:`mstmm.derive.emit.lower` makes a
:class:`KernelIR` from a topology (every SymPy decision: each kind's descriptor with its
full mass matrix and its couplings, the values it reads and their unit scales, each
event function's branches as SymPy's codegen AST); :func:`mstmm.derive.emit.print_kernel`
prints one and decides nothing. The parameter layout the kernel reads (the segment
columns with their scales, each kind's data block, the ends' codes) is part of the IR and
printed into the module, where ``mstmm.kernels`` reads it back at load.

Tests and users inspect the IR (``lower(Topology(...))``): a kind's mass matrix, the
statements of a branch, the layout, without printing or compiling anything.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import sympy as sp


@dataclass(frozen=True)
class KindIR:
    """One kind present in a kernel: its tag (its index in the kernel's ``KINDS``), its
    declaration's file, its descriptor in units L = EI = mbar = 1 (paper Eqs. (2)-(3):
    ``Cz``, ``Cq``, ``A``, ``B`` and the mass of its unknowns), the mass matrix it holds
    on [Y, theta] with the participation row of its couplings (3 x 2; zero for a kind of
    stages, whose stages are condensed at run time), its damper class
    (``descriptor.DAMPERS``), the own mass of each unknown its damping moves (a ``carried``
    damper's; SymPy expressions of its values ``val_<key>`` in units L = EI = mbar = 1, a
    stage's for a kind of stages: ``descriptor.own_masses``) and its data block (key, SI
    unit, shape)."""

    name: str
    tag: int
    file: Path
    staged: bool
    descriptor: object
    inertia: sp.Matrix
    damper: str
    own_masses: tuple
    data_block: tuple


@dataclass(frozen=True)
class FunctionIR:
    """One printed function ``event_<what>(tag, ...)``: its parameters, the body of each
    kind's branch (SymPy codegen statements, keyed by tag; a kind with no branch is
    absent), what it returns where no branch does (None: nothing, for the stages'
    functions), and whether it computes in complex arithmetic."""

    name: str
    params: tuple[str, ...]
    branches: tuple[tuple[int, tuple], ...]
    tail: sp.Basic | None
    complex_: bool


@dataclass(frozen=True)
class KernelIR:
    """Everything a kernel module holds, before printing: its key and signature, whether
    it is damped, its kinds, its functions, the layout it reads (``segment_columns``,
    ``data_blocks``, ``end_codes``), and its header's text."""

    key: str
    signature: str
    numerics: str
    damped: bool
    kinds: tuple[KindIR, ...]
    functions: tuple[FunctionIR, ...]
    segment_columns: tuple
    data_blocks: dict
    end_codes: tuple[str, ...]
    about: str
    parameter_doc: str
    regenerate: str
    bind: str

    @property
    def dampers(self) -> dict[str, str]:
        """The damper class of each kind that damps (read at run time by the proved decay
        bound, ``mstmm.decay_bound``: the runtime has no SymPy)."""
        return {k.name: k.damper for k in self.kinds if k.damper != "none"}

    @property
    def own_masses(self) -> dict[str, tuple]:
        """The own masses of each ``carried`` damper's unknowns, by kind (printed as the
        kernel's ``own_masses``, read by the proved decay bound)."""
        return {k.name: k.own_masses for k in self.kinds if k.own_masses}

    def kind(self, name: str) -> KindIR:
        """The :class:`KindIR` of kind ``name``."""
        for k in self.kinds:
            if k.name == name:
                return k
        raise KeyError(name)

    def function(self, name: str) -> FunctionIR:
        """The :class:`FunctionIR` named ``name`` (``event_chain``, ...)."""
        for f in self.functions:
            if f.name == name:
                return f
        raise KeyError(name)

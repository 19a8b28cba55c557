"""The kernel's IR (derive/ir.py): declarations -> IR -> printer, the IR inspectable.

Checked against what the declarations say (a point mass's mass matrix is diag(m, J) in
kernel units, a kind's data block is its KEYS), against the layout the runtime writes
(``catalog``), and the printer against the committed kernels (it decides nothing: the
IR printed is the kernel).
"""

from __future__ import annotations

import sympy as sp
from mstmm.derive import emit
from mstmm.derive.bundled import BUNDLED_TOPOLOGIES, generated_dir

from mstmm import catalog
from mstmm.catalog import Topology


def test_the_printed_ir_is_the_committed_kernel():
    for topology in BUNDLED_TOPOLOGIES:
        committed = (generated_dir() / f"{topology.kernel_key}.py").read_text()
        assert emit.print_kernel(emit.lower(topology)) == committed


def test_a_point_mass_holds_m_and_J_on_Y_and_theta():
    """``mass`` declares T = (m Ydot^2 + J thetadot^2) / 2: its mass matrix on [Y, theta] is
    diag(m, J) in units mbar_0 L and mbar_0 L^3 (the values' symbols, already scaled), no
    coupling row."""
    kernel = emit.lower(Topology("pinned", "free", ("mass",)))
    mass = kernel.kind("mass")
    m, J = sp.Symbol("val_m", real=True), sp.Symbol("val_J", real=True)
    assert sp.simplify(mass.inertia - sp.Matrix([[m, 0], [0, J], [0, 0]])) == sp.zeros(3, 2)
    assert mass.tag == 0 and mass.file == catalog.kind_file("mass") and not mass.staged
    assert [key for key, _, _ in mass.data_block] == ["m", "J"]


def test_the_layout_in_the_ir_is_the_one_the_runtime_writes():
    kinds = ("oscillator_chain", "spring_mass", "support")
    kernel = emit.lower(Topology("clamped", "clamped", kinds))
    assert kernel.segment_columns == catalog.segment_columns()
    assert kernel.data_blocks == catalog.data_blocks(kinds)
    assert kernel.end_codes == catalog.END_CODES
    assert [k.name for k in kernel.kinds] == list(kinds)
    assert [k.tag for k in kernel.kinds] == [0, 1, 2]
    # a kind of stages has its stages' functions; its chain condensed at run time
    assert kernel.kind("oscillator_chain").staged
    assert {"event_stages", "event_stages_c"} <= {f.name for f in kernel.functions}


def test_the_ends_are_not_in_the_ir():
    """One kernel for every end pair: the IR of two topologies that differ by their ends
    alone is the same IR."""
    a = emit.lower(Topology("clamped", "free", ("spring",)))
    b = emit.lower(Topology("sliding", "pinned", ("spring",)))
    assert a.key == b.key == "beam__spring" and a.signature == b.signature
    assert emit.print_kernel(a) == emit.print_kernel(b)


def test_a_bare_beam_has_no_branch_and_a_damped_kernel_computes_in_complex():
    bare = emit.lower(Topology("free", "free"))
    assert bare.kinds == () and all(f.branches == () for f in bare.functions)
    damped = emit.lower(Topology("pinned", "pinned", ("dashpot", "spring_mass"), damped=True))
    assert damped.damped and all(f.complex_ for f in damped.functions)
    assert damped.dampers == {"dashpot": "grounded", "spring_mass": "carried"}
    assert {f.name for f in damped.functions}.isdisjoint({"event_count", "event_descriptor"})

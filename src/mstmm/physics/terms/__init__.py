"""Segment terms: one module per term (``mstmm.physics.segment``), found by listing this
folder. Each declares its key and its energy per unit length; docs/components.md."""

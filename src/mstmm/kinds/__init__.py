"""Point component kinds: one module per kind, found by listing this folder
(:func:`mstmm.catalog.kinds`). A kind module declares ``KIND``, ``KEYS``, ``COUNT``,
``DOC`` and its ``energy`` (or, a constraint, its ``descriptor``): docs/components.md.
The declarations are SymPy-free; SymPy is imported inside ``energy`` only.
"""

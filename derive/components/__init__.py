"""Point component kinds: one module per kind, found by listing this folder
(:func:`mstmm.derive.catalog.kinds`). A kind module declares ``KIND``, ``KEYS``, ``COUNT``,
``DOC`` and its ``descriptor`` (docs/components.md); nothing else lives here.
"""

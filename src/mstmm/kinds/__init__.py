"""Point component kinds: one module per kind, found by listing this folder
(:func:`mstmm.catalog.kinds`). A kind module declares ``KIND``, ``KEYS``, ``DOC`` and its
physics, one of ``energy``, ``stage``, ``CONSTRAINS``, ``RELEASES``
(``mstmm.catalog.PHYSICS``): docs/components.md.
The declarations are SymPy-free; SymPy is imported inside ``energy`` only.
"""

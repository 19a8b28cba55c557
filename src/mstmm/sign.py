"""The signature of a kernel: what decides its content, hashed (SymPy-free).

``SIGNATURE = sha1(kernel key (kinds, damped) | derive/ sources and the catalog | the files of the
topology's kinds | the shared numerics' sources and the physics they read (the segment
terms) | SymPy version | KERNEL_FORMAT)``. Each
kernel's digest covers only what it is printed from: adding or editing a kind changes the
signature of the topologies that hold it and of no other, and leaves the shared beam
functions (``generated/euler_bernoulli.py``, whose ``DIGEST`` is :func:`derive_digest`)
and numba's caches of everything else valid. The numerics (``mstmm.numerics``) are in
it because a kernel's compiled code inlines some of them: numba's cache of the kernel
file must go when they change.
A committed kernel is used only when its ``SIGNATURE`` equals this; a cached one
carries it in its file name, so numba's on-disk cache (keyed on the file) stays
valid (DESIGN.md, tool-chain facts). The SymPy version is read from the package
metadata: nothing here imports SymPy.
"""

from __future__ import annotations

import hashlib
import importlib.metadata
import importlib.util
from pathlib import Path

from .catalog import Topology, kind_file

#: Bump when the meaning of a kernel's functions changes without any derive/ file changing.
KERNEL_FORMAT = 3

_DIGEST: str | None = None


def _derive_digest() -> str:
    """sha1 of every source and template of the derive package (found without importing
    it: no SymPy) and of the catalog (units and layout, which the printed code reads)."""
    h = hashlib.sha1()
    spec = importlib.util.find_spec("mstmm.derive")
    for folder in spec.submodule_search_locations or ():
        root = Path(folder).resolve()
        for path in sorted(root.rglob("*")):
            if path.suffix in (".py", ".tmpl") and "__pycache__" not in path.parts:
                h.update(path.relative_to(root).as_posix().encode())
                h.update(path.read_bytes())
    h.update((Path(__file__).resolve().parent / "catalog.py").read_bytes())
    return h.hexdigest()


def derive_digest() -> str:
    """sha1 of every source and template of the derive package and of the catalog
    (computed once): what the shared beam functions and every kernel are printed by;
    the kinds (``mstmm/kinds``) are not in it."""
    global _DIGEST
    if _DIGEST is None:
        _DIGEST = _derive_digest()
    return _DIGEST


def numerics_digest() -> str:
    """sha1 of the sources of the shared numerics (``mstmm.numerics``) and of the physics
    they read (``mstmm.physics`` and its segment terms: the numerics compile the terms'
    tables in, and a kernel inlines them), found without importing them."""
    h = hashlib.sha1()
    for package in ("mstmm.numerics", "mstmm.physics", "mstmm.physics.terms"):
        spec = importlib.util.find_spec(package)
        for folder in spec.submodule_search_locations or ():
            for path in sorted(Path(folder).glob("*.py")):
                h.update(path.name.encode())
                h.update(path.read_bytes())
    return h.hexdigest()


def signature(topology: Topology) -> str:
    """sha1 of the topology, the derive/ sources and the catalog, the files of the topology's
    own kinds (built in or registered), the shared numerics, the SymPy version and the
    kernel format."""
    kinds = [hashlib.sha1(kind_file(name).read_bytes()).hexdigest() for name in topology.kinds]
    text = "|".join(
        [
            topology.kernel_key,
            derive_digest(),
            numerics_digest(),
            *kinds,
            importlib.metadata.version("sympy"),
            str(KERNEL_FORMAT),
        ]
    )
    return hashlib.sha1(text.encode()).hexdigest()

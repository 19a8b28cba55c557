"""The signature of a kernel: what decides its content, hashed (SymPy-free).

``SIGNATURE = sha1(topology key | derive/ sources | SymPy version | KERNEL_FORMAT)``.
A committed kernel is used only when its ``SIGNATURE`` equals this; a cached one
carries it in its file name, so numba's on-disk cache (keyed on the file) stays
valid (DESIGN.md, tool-chain facts). The SymPy version is read from the package
metadata: nothing here imports SymPy.
"""

from __future__ import annotations

import hashlib
import importlib.metadata
from pathlib import Path

from .catalog import Topology

#: Bump when the meaning of a kernel's functions changes without any derive/ file changing.
KERNEL_FORMAT = 1

_DIGEST: str | None = None


def _derive_digest() -> str:
    """sha1 of every source and template of the derive package."""
    h = hashlib.sha1()
    root = Path(__file__).resolve().parent
    for path in sorted(root.rglob("*")):
        if path.suffix in (".py", ".tmpl") and "__pycache__" not in path.parts:
            h.update(path.relative_to(root).as_posix().encode())
            h.update(path.read_bytes())
    return h.hexdigest()


def signature(topology: Topology) -> str:
    """sha1 of the topology, the derive/ sources, the SymPy version and the kernel format."""
    global _DIGEST
    if _DIGEST is None:
        _DIGEST = _derive_digest()
    text = "|".join(
        [topology.key, _DIGEST, importlib.metadata.version("sympy"), str(KERNEL_FORMAT)]
    )
    return hashlib.sha1(text.encode()).hexdigest()

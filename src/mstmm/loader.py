"""A kernel module loaded from its file under its module name (:mod:`mstmm.kernels` loads
the kernels of its cache so; :mod:`mstmm.compiling`'s helper processes load a kernel by the
name and path this process gives them)."""

from __future__ import annotations

import importlib
import importlib.util
import sys
from pathlib import Path
from types import ModuleType

__all__ = ["KernelError", "load", "load_file"]


class KernelError(RuntimeError):
    """A kernel could not be generated, written or loaded."""


def load_file(path: Path, module_name: str) -> ModuleType:
    """The module of the file ``path``, executed as ``module_name`` (registered in
    ``sys.modules`` first: numba caches a module under its name)."""
    spec = importlib.util.spec_from_file_location(module_name, path)
    if spec is None or spec.loader is None:
        raise KernelError(f"cannot load kernel {path}")
    module = importlib.util.module_from_spec(spec)
    # numba caches a module under its name: register it before executing it
    sys.modules[module_name] = module
    try:
        spec.loader.exec_module(module)
    except BaseException:
        del sys.modules[module_name]
        raise
    return module


def load(path: str, name: str) -> ModuleType:
    """The kernel module ``name``: a bundled one (``mstmm.generated.*``) imported, any other
    loaded from its file ``path``."""
    if name.startswith("mstmm.generated."):
        return importlib.import_module(name)
    return load_file(Path(path), name)

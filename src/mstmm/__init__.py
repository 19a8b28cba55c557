"""mstmm: exact natural frequencies and mode shapes of beams carrying attached elements.

Transfer matrix method of linear multibody systems (MSTMM; Abbas, Chen, Wang,
Rui). The pipeline: a scene (TOML) -> ``mstmm.derive`` (SymPy: component
matrices, overall transfer equation, boundary reduction, numba source) ->
a generated kernel -> root search and mode shapes (this package; SymPy is
never imported on this path).

>>> import mstmm
>>> scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
>>> sol = mstmm.solve(scene, modes=5)

The public names are imported on first use (PEP 562): ``import mstmm`` is cheap (no
numpy, no numba), so that the command line can set up its handling of Ctrl-C and
SIGTERM before the heavy modules load.
"""

import importlib as _importlib
import sys as _sys
import types as _types
from typing import TYPE_CHECKING as _TYPE_CHECKING
from typing import Any as _Any

__version__ = "0.1.0"

#: Public name -> the submodule that defines it (``interpret`` is the submodule itself).
_EXPORTS = {
    "Bands": "bands",
    "bands": "bands",
    "Kernel": "kernels",
    "load_kernel": "kernels",
    "frf": "response",
    "Scene": "scene",
    "SceneError": "scene",
    "load_scene": "scene",
    "scene_from_dict": "scene",
    "example_path": "scenes",
    "Solution": "solve",
    "solve": "solve",
    "sweep": "study",
    "Topology": "topology",
    "parameter_vector": "topology",
    "topology_of": "topology",
}

__all__ = [
    "Bands",
    "Kernel",
    "Scene",
    "SceneError",
    "Solution",
    "Topology",
    "bands",
    "example_path",
    "frf",
    "interpret",
    "kernel_for",
    "load_kernel",
    "load_scene",
    "parameter_vector",
    "scene_from_dict",
    "solve",
    "sweep",
    "topology_of",
]

if _TYPE_CHECKING:  # what the names are, for type checkers and editors
    from . import interpret
    from .bands import Bands, bands
    from .kernels import Kernel, load_kernel
    from .response import frf
    from .scene import Scene, SceneError, load_scene, scene_from_dict
    from .scenes import example_path
    from .solve import Solution, solve
    from .study import sweep
    from .topology import Topology, parameter_vector, topology_of


def __getattr__(name: str) -> _Any:
    """A public name, imported from its submodule the first time it is asked for."""
    if name == "interpret":
        return _importlib.import_module(".interpret", __name__)
    where = _EXPORTS.get(name)
    if where is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(_importlib.import_module(f".{where}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    """The public names, the submodules loaded so far and the module's own dunders."""
    loaded = [n for n, v in globals().items() if isinstance(v, _types.ModuleType) and n[0] != "_"]
    return sorted({*__all__, *loaded, *(n for n in globals() if n.startswith("__"))})


def kernel_for(scene: "Scene") -> "Kernel":
    """The compiled kernel of a scene's topology; call it with any parameter vector."""
    from .kernels import load_kernel
    from .topology import topology_of

    return load_kernel(topology_of(scene))


class _Package(_types.ModuleType):
    """``mstmm`` itself: ``mstmm.solve`` and ``mstmm.bands`` stay the functions when their
    submodules (of the same names) are imported, as they were when this package imported
    them eagerly (the import system sets a submodule as an attribute of its package)."""

    def __setattr__(self, name: str, value: _Any) -> None:
        if isinstance(value, _types.ModuleType) and _EXPORTS.get(name) == name:
            return  # the function of that name is looked up by __getattr__
        super().__setattr__(name, value)


_sys.modules[__name__].__class__ = _Package

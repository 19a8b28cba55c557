"""mstmm: exact natural frequencies and mode shapes of beams carrying attached elements.

Transfer matrix method of linear multibody systems (MSTMM; Abbas, Chen, Wang,
Rui). The pipeline: a scene (TOML) -> ``mstmm.derive`` (SymPy: component
matrices, overall transfer equation, boundary reduction, numba source) ->
a generated kernel -> root search and mode shapes (this package; SymPy is
never imported on this path).

>>> import mstmm
>>> scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
>>> sol = mstmm.solve(scene, modes=5)
"""

from . import interpret
from .bands import Bands, bands
from .kernels import Kernel, load_kernel
from .response import frf
from .scene import Scene, SceneError, load_scene, scene_from_dict
from .scenes import example_path
from .solve import Solution, solve
from .study import sweep
from .topology import Topology, parameter_vector, topology_of

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

__version__ = "0.1.0"


def kernel_for(scene: Scene) -> Kernel:
    """The compiled kernel of a scene's topology; call it with any parameter vector."""
    return load_kernel(topology_of(scene))

"""Where mstmm writes at run time: the user cache, never the installed package's folder.

Kernels derived at run time and numba's machine code of every mstmm function (the shared
numerics, the bundled kernels, the derived ones) live under one directory:
``MSTMM_CACHE``, else ``$XDG_CACHE_HOME/mstmm``, else ``~/.cache/mstmm``. An install,
reinstall, upgrade or uninstall of the package thus leaves nothing of ours behind in
``site-packages``, and a read-only installation works as a writable one.
"""

from __future__ import annotations

import os
from pathlib import Path


def cache_dir() -> Path:
    """Directory of kernels derived at run time (``MSTMM_CACHE`` overrides)."""
    env = os.environ.get("MSTMM_CACHE")
    if env:
        return Path(env)
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(Path.home(), ".cache")
    return Path(base) / "mstmm"

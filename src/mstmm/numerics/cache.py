"""numba's on-disk cache of the shared numerics, invalidated by any of their sources.

numba stamps a cached function with its own file's content only: a function of
``frf.py`` that inlines one of ``walk.py`` (or of the printed
``mstmm.generated.euler_bernoulli``) would keep machine code compiled against the old
``walk.py`` after an edit. These locators stamp every function of this package with one
hash of all its sources and the printed beam functions (:func:`digest`), so that a change
in any of them recompiles all. They find the same cache directories as numba's own
(``NUMBA_CACHE_DIR``, ``__pycache__`` beside the file, the user-wide cache), in that order.
"""

from __future__ import annotations

import hashlib
import importlib.util
from pathlib import Path

from numba.core import caching

_HERE = Path(__file__).resolve().parent
_DIGEST: list[tuple[tuple, str]] = []


def sources() -> list[Path]:
    """The files whose content the numerics' machine code depends on."""
    printed = importlib.util.find_spec("mstmm.generated.euler_bernoulli")
    files = sorted(_HERE.glob("*.py")) + [_HERE.parent / "jit.py"]
    if printed is not None and printed.origin:
        files.append(Path(printed.origin))
    return files


def digest() -> str:
    """sha1 of every source of the shared numerics (again only when a file changed)."""
    files = sources()
    key = tuple((str(p), p.stat().st_mtime_ns, p.stat().st_size) for p in files)
    if not _DIGEST or _DIGEST[0][0] != key:
        h = hashlib.sha1()
        for path in files:
            h.update(path.name.encode())
            h.update(path.read_bytes())
        _DIGEST[:] = [(key, h.hexdigest())]
    return _DIGEST[0][1]


class _Stamped:
    """A numba locator for this package's functions, stamped with :func:`digest`."""

    def get_source_stamp(self):
        return digest()

    @classmethod
    def from_function(cls, py_func, py_file):
        if Path(py_file).resolve().parent != _HERE:
            return None
        return super().from_function(py_func, py_file)


class UserProvidedLocator(_Stamped, caching.UserProvidedCacheLocator):
    """``NUMBA_CACHE_DIR``, when set."""


class InTreeLocator(_Stamped, caching.InTreeCacheLocator):
    """``__pycache__`` beside the file, when writable."""


class UserWideLocator(_Stamped, caching.UserWideCacheLocator):
    """The user-wide cache directory (an installation that is not writable)."""


class _BesideKernel:
    """A numba locator for the copies ``characteristic.bind_characteristic`` makes of a
    kernel's characteristic functions: cached beside the kernel's file and stamped with
    it, as the kernel's printed functions are (a kernel's file changes whenever anything
    it is made from does: its signature covers the numerics' sources), so that an empty
    kernel cache is a cold start and nothing accumulates in this package's folder."""

    @classmethod
    def from_function(cls, py_func, py_file):
        kernel = py_func.__globals__.get("__file__")
        copy = py_func.__qualname__.startswith("kernel_")
        if not copy or not kernel or Path(py_file).resolve().parent != _HERE:
            return None
        return super().from_function(py_func, kernel)


class KernelUserProvidedLocator(_BesideKernel, caching.UserProvidedCacheLocator):
    """``NUMBA_CACHE_DIR``, when set."""


class KernelInTreeLocator(_BesideKernel, caching.InTreeCacheLocator):
    """``__pycache__`` beside the kernel's file, when writable."""


class KernelUserWideLocator(_BesideKernel, caching.UserWideCacheLocator):
    """The user-wide cache directory (a kernel folder that is not writable)."""


_OURS = (
    KernelUserProvidedLocator,
    KernelInTreeLocator,
    KernelUserWideLocator,
    UserProvidedLocator,
    InTreeLocator,
    UserWideLocator,
)
if not any(c in caching.CacheImpl._locator_classes for c in _OURS):
    caching.CacheImpl._locator_classes[0:0] = list(_OURS)

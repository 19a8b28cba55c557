"""numba's on-disk cache of mstmm's functions: in the user cache, stamped by all their sources.

Two rules numba's own locators do not follow:

- **Nothing is written into the installed package.** numba caches a function beside
  its file (``__pycache__``) when that folder is writable: inside ``site-packages``, where
  ``pip uninstall`` leaves the files behind and the folder left over shadows a later
  editable install as a namespace package. Every function of mstmm (the shared numerics,
  the bundled kernels in ``mstmm.generated``, the kernels derived at run time and their
  copies of the characteristic functions) is cached under ``<cache>/numba``
  (:func:`mstmm.cachedir.cache_dir`); ``NUMBA_CACHE_DIR`` takes its place when the user
  set it, and a temporary folder when neither can be written.
- **Keyed by content, not by path.** numba names a file's cache folder after the folder's
  path and stamps it with the file's modification time: a reinstall into another
  environment, or a copy of the package, would compile everything again (the shared
  numerics alone take about 40 s on a 2-core machine). Here the numerics' folder is named
  after :func:`digest` and every other file's after a hash of its content, which is also
  its stamp: the same sources anywhere share their machine code, and different ones never
  share a folder.
- **One stamp for the numerics.** numba stamps a cached function with its own file's
  content only: a function of ``frf.py`` that inlines one of ``walk.py`` (or of the
  printed ``mstmm.generated.euler_bernoulli``) would keep machine code compiled against
  the old ``walk.py`` after an edit. The numerics' functions carry one hash of all
  their sources (:func:`digest`), so that a change in any of them recompiles all. The
  copies ``characteristic.bind_characteristic`` makes of a kernel's characteristic
  functions (qualified ``kernel_<signature>.<name>``) are cached with the kernel and
  stamped with its file, as the kernel's printed functions are (a kernel's file changes
  whenever anything it is made from does: its signature covers the numerics' sources).
"""

from __future__ import annotations

import functools
import hashlib
import importlib.util
import os
import tempfile
from pathlib import Path

from numba.core import caching, config

from mstmm.cachedir import cache_dir
from mstmm.physics import segment as segment_terms

_HERE = Path(__file__).resolve().parent
_DIGEST: list[str] = []


def sources() -> list[Path]:
    """The files whose content the numerics' machine code depends on."""
    printed = importlib.util.find_spec("mstmm.generated.euler_bernoulli")
    root = _HERE.parent
    files = sorted(_HERE.glob("*.py")) + [root / "jit.py", root / "catalog.py"]
    files += sorted((root / "physics").glob("*.py")) + segment_terms.files()
    if printed is not None and printed.origin:
        files.append(Path(printed.origin))
    return files


def digest() -> str:
    """sha1 of every source of the shared numerics (read once a process: an installed
    package does not change under a running solve)."""
    if not _DIGEST:
        h = hashlib.sha1()
        for path in sources():
            h.update(path.name.encode())
            h.update(path.read_bytes())
        _DIGEST.append(h.hexdigest())
    return _DIGEST[0]


def _content(path: str) -> str:
    """sha1 of a file's content (a kernel's or a module's: what its machine code is
    compiled from, besides the numerics it calls, which its own content names: a kernel's
    signature covers them), read once per version of the file (a kernel's ~20 functions
    each make a locator)."""
    st = os.stat(path)
    return _hashed(path, st.st_mtime_ns, st.st_size)


@functools.lru_cache(maxsize=256)
def _hashed(path: str, mtime_ns: int, size: int) -> str:
    return hashlib.sha1(Path(path).read_bytes()).hexdigest()


def numba_dir() -> Path:
    """Where numba's machine code of mstmm's functions goes: ``NUMBA_CACHE_DIR`` if the
    user set one, else ``<cache>/numba``."""
    if config.CACHE_DIR:
        return Path(config.CACHE_DIR)
    return cache_dir() / "numba"


def _ours(py_func) -> bool:
    """Whether ``py_func`` is mstmm's: the package's modules, a derived kernel's module
    (``mstmm_kernel_*``), and the numerics' copies bound into either."""
    module = getattr(py_func, "__module__", None) or ""
    return module == "mstmm" or module.startswith(("mstmm.", "mstmm_kernel_"))


class UserCacheLocator(caching._SourceFileBackedLocatorMixin, caching._CacheLocator):
    """Every function of mstmm, in :func:`numba_dir` (a temporary folder if that cannot be
    written), stamped with :func:`digest` for the numerics and with its file otherwise."""

    def __init__(self, py_func, py_file: str, numerics: bool, base: Path):
        self._py_file = py_file
        self._lineno = py_func.__code__.co_firstlineno
        self._stamp = digest() if numerics else _content(py_file)
        name = "numerics" if numerics else Path(py_file).stem
        self._cache_path = str(base / f"{name}_{self._stamp[:20]}")

    def get_cache_path(self) -> str:
        return self._cache_path

    def get_source_stamp(self):
        return self._stamp

    @classmethod
    def from_function(cls, py_func, py_file):
        if not _ours(py_func) or not os.path.exists(py_file):
            return None
        numerics = Path(py_file).resolve().parent == _HERE
        if numerics and py_func.__qualname__.startswith("kernel_"):
            kernel = py_func.__globals__.get("__file__")
            if not kernel:
                return None
            py_file, numerics = kernel, False  # cached with its kernel, stamped with it
        uid = os.getuid() if hasattr(os, "getuid") else 0
        fallback = Path(tempfile.gettempdir()) / f"mstmm-numba-{uid}"
        for base in (numba_dir(), fallback):
            self = cls(py_func, py_file, numerics, base)
            try:
                self.ensure_cache_path()
            except OSError:
                continue
            return self
        return None


if UserCacheLocator not in caching.CacheImpl._locator_classes:
    caching.CacheImpl._locator_classes.insert(0, UserCacheLocator)

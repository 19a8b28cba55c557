"""The shared numerics are ordinary code (``mstmm.numerics``): linted, imported as a
package, and cached by numba with one stamp over all their sources (a change in any of
them recompiles every function that may have inlined it)."""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

import numpy as np

import mstmm
from mstmm import numerics
from mstmm.numerics import cache
from mstmm.sign import numerics_digest


def _sources_digest(files) -> str:
    h = hashlib.sha1()
    for path in files:
        h.update(path.name.encode())
        h.update(path.read_bytes())
    return h.hexdigest()


def test_the_stamp_covers_every_module_and_the_printed_beam_functions():
    folder = Path(numerics.__file__).parent
    names = {p.name for p in cache.sources()}
    assert {p.name for p in folder.glob("*.py")} <= names
    assert "euler_bernoulli.py" in names
    assert cache.digest() == _sources_digest(cache.sources())
    # the kernels' signature covers the numerics' own sources and the physics they compile
    # in (the segment terms' tables)
    physics = folder.parent / "physics"
    assert {p.name for p in physics.glob("*.py")} <= names
    assert {p.name for p in (physics / "terms").glob("*.py")} - {"__init__.py"} <= names
    files = [*sorted(folder.glob("*.py")), *sorted(physics.glob("*.py"))]
    files += sorted((physics / "terms").glob("*.py"))
    assert numerics_digest() == _sources_digest(files)


def test_numerics_functions_are_cached_with_the_package_stamp():
    from mstmm.numerics import entries, walk

    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    kernel = mstmm.kernel_for(scene)
    p = mstmm.parameter_vector(scene)
    kernel.lowest(p, 3)  # compiles (or loads) the driver
    for dispatcher in (entries.entry_lowest, walk.event_order):
        impl = dispatcher._cache._impl
        assert isinstance(impl.locator, cache.UserCacheLocator)
        assert impl.locator.get_source_stamp() == cache.digest()
        # in the user cache, never beside the installed sources
        assert Path(impl.locator.get_cache_path()).is_relative_to(cache.numba_dir())


_LOCATORS = """
import importlib, pkgutil, sys
import mstmm.frame  # first: what a frame's solve imports (the band factorization's module
                    # once made its functions before the locator was installed)
import mstmm
from mstmm.numerics import cache
from numba.core.dispatcher import Dispatcher
checked, wrong = 0, []
for info in pkgutil.walk_packages(mstmm.__path__, "mstmm."):
    if info.name.startswith("mstmm.generated.") or info.name.endswith("__main__"):
        continue
    try:
        module = importlib.import_module(info.name)
    except ImportError:  # an optional dependency (dask) missing
        continue
    for value in vars(module).values():
        if isinstance(value, Dispatcher) and getattr(value._cache, "_impl", None):
            if getattr(value, "__module__", "") == module.__name__:
                checked += 1
                if not isinstance(value._cache._impl.locator, cache.UserCacheLocator):
                    wrong.append(f"{info.name}.{value.__name__}")
print(checked, wrong)
"""


def test_every_cached_function_of_the_package_goes_to_the_user_cache():
    """Every module of mstmm, imported in a fresh process after ``mstmm.frame``: each numba
    function with an on-disk cache is in the user cache (a module that makes its
    functions before the user-cache locator is installed writes machine code beside the
    installed sources)."""
    import subprocess
    import sys

    out = subprocess.run(
        [sys.executable, "-c", _LOCATORS], capture_output=True, text=True, check=True
    ).stdout.split(" ", 1)
    assert int(out[0]) > 50
    assert out[1].strip() == "[]"


def test_a_kernel_module_sees_the_numerics_it_star_imports():
    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    module = mstmm.kernel_for(scene).module
    assert module.renormalise is numerics.walk.renormalise
    assert module.NUMERICS == numerics_digest()
    v = np.array([3.0, -5.0, 0.5])
    log = numerics.walk.renormalise.py_func(v)
    assert np.isclose(log, np.log(8.0)) and np.allclose(v, [3 / 8, -5 / 8, 0.5 / 8])


_BOUND = """
import json, sys
import numpy as np
import mstmm
out = {}
for name in ("bare_cantilever", "wu_chou_1998"):
    scene = mstmm.load_scene(mstmm.example_path(name))
    module = mstmm.kernel_for(scene).module
    p = mstmm.parameter_vector(scene)
    values = [module.delta_stable(w, p) for w in (3.0, 170.0, 900.0)]
    counts = [int(module.count_below(w, p)) for w in (3.0, 170.0, 900.0)]
    hits = sum(sum(f.stats.cache_hits.values()) for f in (module.delta_stable, module.count_below))
    qual = module.delta_stable.py_func.__qualname__
    out[name] = [[list(map(float, v)) for v in values], counts, hits, qual, module.SIGNATURE]
print(json.dumps(out))
"""


def test_bound_characteristic_functions_cache_per_kernel():
    """A kernel's characteristic functions are ``mstmm.numerics.characteristic`` compiled
    with the kernel's printed functions: numba caches each copy under the kernel's
    signature, so a second process loads both kernels' copies from disk (no
    ``dynamic globals``) and neither gets the other's machine code (the bare beam's values
    differ from the loaded beam's)."""
    import json
    import subprocess
    import sys

    env = dict(os.environ, MSTMM_INTERPRET_BUDGET="0")
    runs = []
    for _ in range(2):
        done = subprocess.run(
            [sys.executable, "-c", _BOUND], env=env, capture_output=True, text=True, check=True
        )
        runs.append(json.loads(done.stdout))
    first, second = runs
    for name, (values, counts, hits, qual, sig) in second.items():
        assert (values, counts) == tuple(first[name][:2]), name  # the same machine code
        assert hits == 2, name  # both functions loaded from numba's cache
        assert qual == f"kernel_{sig[:20]}.delta_stable"
    assert first["bare_cantilever"][0] != first["wu_chou_1998"][0]
    # below 3, 170, 900 rad/s: the bare cantilever (first roots 225.8, 1415 rad/s) has
    # 0, 0, 1 natural frequencies, the paper's loaded beam 0, 1, 4 (its README table)
    assert first["bare_cantilever"][1] == [0, 0, 1]
    assert first["wu_chou_1998"][1] == [0, 1, 4]


def test_a_nested_call_compiles_one_specialization_per_type_not_per_literal():
    """``mstmm.jit.njit``: a callee called with a literal (``0``) and with a variable
    that numba first types as that literal compiles once, for int64 (issue 21: such
    duplicates were 7.5 s of the first run on a machine with nothing compiled)."""
    from numba import types

    from mstmm.jit import njit

    @njit
    def callee(a, i):
        return a[i] * 2.0

    @njit
    def caller(a):
        s = callee(a, 0)  # a literal argument
        j = 0  # Literal[int](0) until the loop makes it int64
        for k in range(a.shape[0]):
            s += callee(a, j)
            j = k
        return s

    a = np.array([1.0, 2.0, 3.0])
    # s = 2 a[0] + 2 (a[0] + a[0] + a[1]): the loop reads j before it takes k
    assert caller(a) == 2.0 * (a[0] + a[0] + a[0] + a[1])
    assert callee.signatures == [(types.Array(types.float64, 1, "C"), types.int64)]

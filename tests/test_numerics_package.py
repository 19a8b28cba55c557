"""The shared numerics are ordinary code (``mstmm.numerics``): linted, imported as a
package, and cached by numba with one stamp over all their sources (a change in any of
them recompiles every function that may have inlined it)."""

from __future__ import annotations

import hashlib
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
    # the kernels' signature covers the numerics' own sources
    assert numerics_digest() == _sources_digest(sorted(folder.glob("*.py")))


def test_numerics_functions_are_cached_with_the_package_stamp():
    from mstmm.numerics import entries, walk

    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    kernel = mstmm.kernel_for(scene)
    p = mstmm.parameter_vector(scene)
    kernel.lowest(p, 3)  # compiles (or loads) the driver
    for dispatcher in (entries.entry_lowest, walk.event_order):
        impl = dispatcher._cache._impl
        assert isinstance(impl.locator, cache._Stamped)
        assert impl.locator.get_source_stamp() == cache.digest()


def test_a_kernel_module_sees_the_numerics_it_star_imports():
    scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
    module = mstmm.kernel_for(scene).module
    assert module.renormalise is numerics.walk.renormalise
    assert module.NUMERICS == numerics_digest()
    v = np.array([3.0, -5.0, 0.5])
    log = numerics.walk.renormalise.py_func(v)
    assert np.isclose(log, np.log(8.0)) and np.allclose(v, [3 / 8, -5 / 8, 0.5 / 8])

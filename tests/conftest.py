"""Shared fixtures: a private kernel cache for the whole test session, the references."""

from __future__ import annotations

import json
import os
import shutil
import tempfile
from pathlib import Path

import pytest

DATA = Path(__file__).parent / "data"

# Tests never touch the user's kernel cache: set before mstmm resolves it. The process that
# starts the session makes it; pytest-xdist's workers (started after this file is read
# in the controller) and the subprocesses the tests start inherit it through the
# environment, so every topology is derived and compiled once per session, not once per
# worker. Only the process that made it removes it, when the whole session ends.
_OWN_CACHE = "MSTMM_TEST_CACHE" not in os.environ
if _OWN_CACHE:
    os.environ["MSTMM_TEST_CACHE"] = tempfile.mkdtemp(prefix="mstmm-test-cache-")
CACHE = os.environ["MSTMM_TEST_CACHE"]
os.environ["MSTMM_CACHE"] = CACHE
# numba's machine code of the shared numerics, compiled once per session too: also for the
# subprocesses a test starts with a kernel cache of its own (mstmm puts it in
# <MSTMM_CACHE>/numba unless NUMBA_CACHE_DIR says otherwise; a test of a cold machine sets
# its own).
os.environ.setdefault("NUMBA_CACHE_DIR", os.path.join(CACHE, "numba"))
# No compile helpers (mstmm.compiling) but where a test asks for them: a test session is
# the busy machine they are designed to yield on (a worker on every core), where each new
# kernel's helper started a process, got almost no CPU, and was left behind.
# tests/test_compiling.py and tests/test_install.py turn them on for what they check.
os.environ.setdefault("MSTMM_COMPILE_HELPERS", "0")


# The reference models' slow calls answered from their stored answers (tests/stored.py).
import stored  # noqa: E402

stored.install()
_MISSES = Path(CACHE) / "stored_misses"
_missed = [0, 0.0]


def pytest_sessionfinish(session: pytest.Session) -> None:
    if stored.misses and not stored.RECORD:  # this process's count (a worker's too)
        with open(_MISSES, "a") as fh:
            fh.write(f"{stored.misses} {stored.missed_seconds:.1f}\n")
    if _OWN_CACHE:  # the controller, after its workers: the session's count and seconds
        text = _MISSES.read_text() if _MISSES.exists() else ""
        rows = [line.split() for line in text.splitlines()]
        _missed[:] = [sum(int(n) for n, _ in rows), sum(float(s) for _, s in rows)]
        shutil.rmtree(CACHE, ignore_errors=True)


def pytest_terminal_summary(terminalreporter) -> None:
    misses, seconds = _missed
    if misses:
        terminalreporter.write_line(
            f"{misses} reference-model calls were not in tests/data/stored_references.jsonl.gz"
            f" and ran the model for {seconds:.0f} s (some are expected: tests/stored.py; many"
            " mean the store is stale: python tests/make_stored.py)"
        )


@pytest.fixture(scope="session")
def reference() -> dict[str, list[float]]:
    """Exact frequencies of ../shared/reference (copied into tests/data), rad/s."""
    raw = json.loads((DATA / "reference.json").read_text())
    return {name: [float(w) for w in entry["omega"]] for name, entry in raw.items()}


@pytest.fixture(scope="session")
def data_dir() -> Path:
    return DATA


@pytest.fixture
def fresh_process(monkeypatch):
    """mstmm.interpret's state as in a process that has loaded no machine code yet."""
    from mstmm import interpret, kernels

    monkeypatch.setattr(interpret._Process, "compiled", False)
    monkeypatch.setattr(interpret._Process, "spent", 0.0)
    monkeypatch.setattr(interpret._Process, "budget", interpret.DEFAULT_BUDGET)
    # the budget of a warm machine, whether or not this session compiled the kernel yet
    monkeypatch.setattr(interpret, "COLD_BUDGET", interpret.DEFAULT_BUDGET)
    for kernel in kernels._LOADED.values():
        monkeypatch.setattr(kernel, "warmed", set())


@pytest.fixture(params=["interpreted", "compiled"])
def tier(request, monkeypatch) -> str:
    """Run the test with the kernel's root search interpreted, then compiled."""
    from mstmm import interpret

    if request.param == "interpreted":
        request.getfixturevalue("fresh_process")
    else:
        monkeypatch.setattr(interpret._Process, "compiled", True)
    return request.param


# Property tests: deterministic in CI (same examples every run), random locally.
from hypothesis import settings  # noqa: E402

settings.register_profile("ci", derandomize=True, print_blob=True)
if os.environ.get("CI"):
    settings.load_profile("ci")


#: Exhaustive sweeps and property runs, by node id (a prefix: every parametrisation): the
#: nightly command ``python -m pytest -m exhaustive -n auto`` runs them (README, "Tests");
#: the default run (CI) keeps a representative case of each: the damped roots of every
#: scene of tests/test_damped.py, the other repeated cells, the other extreme cases, the
#: other damped FE scenes, the receptances of tests/test_frf.py's fixed cases, the withheld
#: seed at 0.04, the random general scenes, each kind's first end pair below, and the
#: damped L-frame and portal (the closed two-bay frame nightly).
EXHAUSTIVE = (
    "tests/test_damped.py::test_property_random_damped_scenes_against_the_reference",
    "tests/test_repeated.py::test_roots_against_the_reference[chain_sliding_free]",
    "tests/test_repeated.py::test_roots_where_the_count_or_the_function_loses_digits[grounded",
    "tests/test_repeated.py::test_roots_where_the_count_or_the_function_loses_digits[long_cells",
    "tests/test_extremes.py::test_default_formulation_matches_reference[many_1000]",
    "tests/test_fem_damped.py::test_damped_roots_against_the_reference[every_kind]",
    "tests/test_frf.py::test_property_reciprocity",
    "tests/test_reference_damped.py::test_the_count_catches_a_withheld_seed[0.0]",
    "tests/test_general_reference.py::test_random_compressed_timoshenko_scenes",
    "tests/test_sympy_range.py::",
    "tests/test_frame_damped.py::test_damped_frames_against_the_reference_model_and_the_fe_count[two_bay]",
)


#: Files that meet the same slow kernel (every kind in every scene: about 15 s of numba
#: per function set), run by one worker so that it is compiled once, not by both at the
#: same moment; every other file is a group of its own (``--dist loadgroup``, pyproject).
SAME_WORKER = {
    "tests/test_kind_properties.py": "every_kind",
    "tests/test_segment_properties.py": "every_kind",
    # the frames' compiled members (about 25 s of numba, 45 s with the damped ones)
    "tests/test_plane_frames.py": "frames",
    "tests/test_frame_damped.py": "frames",
    "tests/test_frame_banded.py": "frames",
}


@pytest.hookimpl(tryfirst=True)  # before pytest-xdist reads the groups
def pytest_collection_modifyitems(config: pytest.Config, items: list) -> None:
    """Mark :data:`EXHAUSTIVE` and every kind scene's end pairs past its first (the
    default path of ``tests/test_kinds.py``: each kind keeps its first pair, as
    ``PAPER_CASES`` does); put each test in its file's group (:data:`SAME_WORKER`)."""
    for item in items:
        path = item.nodeid.split("::")[0]
        item.add_marker(pytest.mark.xdist_group(SAME_WORKER.get(path, path)))
        exhaustive = item.nodeid.startswith(EXHAUSTIVE)
        if item.nodeid.startswith("tests/test_kinds.py::test_kind_scene_default_path["):
            exhaustive = item.callspec.params["case"] not in item.module.PAPER_CASES
        if exhaustive:
            item.add_marker(pytest.mark.exhaustive)

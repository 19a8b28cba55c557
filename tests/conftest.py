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


def pytest_sessionfinish(session: pytest.Session) -> None:
    if _OWN_CACHE:
        shutil.rmtree(CACHE, ignore_errors=True)


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

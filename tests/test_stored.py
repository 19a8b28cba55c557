"""The stored answers of the reference models (tests/stored.py) are the models' answers:
written by this version of the models, and what the models compute again for them."""

from __future__ import annotations

import pytest
import stored
from mpmath import mp

HEADER, ENTRIES = stored.read_store()
REGENERATE = "write it again: python tests/make_stored.py"


def _close(a, b, path="value") -> None:
    """Equal structure and equal numbers (mpf to 1e-20 relative: the models work at 30 or
    more digits; another mpmath may round their last digits otherwise)."""
    if isinstance(a, (list, tuple)):
        assert type(a) is type(b) and len(a) == len(b), path
        for i, (x, y) in enumerate(zip(a, b, strict=True)):
            _close(x, y, f"{path}[{i}]")
    elif isinstance(a, dict):
        assert a.keys() == b.keys(), path
        for k in a:
            _close(a[k], b[k], f"{path}[{k!r}]")
    elif isinstance(a, (mp.mpf, mp.mpc)):
        assert isinstance(b, type(a)), (path, b)
        with mp.workdps(40):
            assert abs(a - b) <= mp.mpf("1e-20") * max(abs(a), abs(b)), (path, a, b)
    elif hasattr(a, "tolist"):  # an array
        _close(a.tolist(), b.tolist(), path)
    else:
        assert a == b or (a != a and b != b), (path, a, b)


def test_the_store_is_written_by_this_version_of_the_models():
    assert HEADER.get("model") == stored.model_digest(), REGENERATE
    assert HEADER["entries"] == len(ENTRIES) > 0


def test_every_stored_function_is_in_the_store_and_nothing_else():
    names = {f"{m}.{n}" for m, ns in stored.STORED.items() for n in ns}
    assert {e["function"] for e in ENTRIES.values()} <= names


def _cheapest() -> list[dict]:
    best: dict[str, dict] = {}
    for e in ENTRIES.values():
        if e["function"] not in best or e["seconds"] < best[e["function"]]["seconds"]:
            best[e["function"]] = e
    return [best[name] for name in sorted(best)]


@pytest.mark.parametrize("entry", _cheapest(), ids=lambda e: e["function"])
def test_the_cheapest_call_of_each_function_is_what_the_model_computes(entry):
    """The key is the call's encoded arguments; the value is what the model returns."""
    assert stored.key_of(entry["function"], entry["arguments"]) == entry["key"]
    then, now = stored.recompute(entry)
    _close(then, now)


CHUNKS = 16


@pytest.mark.exhaustive
@pytest.mark.parametrize("chunk", range(CHUNKS))
def test_every_stored_call_is_what_the_model_computes(chunk):
    """Nightly (``-m exhaustive``): every stored call recomputed, a sixteenth per case."""
    for key in sorted(ENTRIES)[chunk::CHUNKS]:
        then, now = stored.recompute(ENTRIES[key])
        _close(then, now, ENTRIES[key]["function"])

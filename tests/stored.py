"""The independent models' answers, stored: the reference model's slow calls looked up
instead of recomputed.

The mpmath reference models (``reference_model``, ``reference_bloch``) are the tests'
independent truth; they are also slow (30-40 digits, global assembly): about 560 s of the
default test run's 1,250 s on a warm machine went into them, the same calls on the same
inputs every run. :func:`install` (``tests/conftest.py``) wraps the slow public functions of
:data:`STORED`: a call whose exact inputs (every argument encoded exactly, the defaults
applied) were stored by ``tests/make_stored.py`` returns the
stored answer, bit for bit what the model returned for them; any other call runs the model.

What keeps the store honest:

* It is keyed by the models' source: a store written by another version of
  ``reference_model.py`` or ``reference_bloch.py`` (:func:`model_digest`) is not used at all,
  and ``tests/test_stored.py`` fails until the store is written again.
* It holds only what the models computed (``tests/make_stored.py`` runs the test suite with
  ``MSTMM_STORED=record``): never a value of the code under test. An input that comes from
  the code under test (a root found, a sample point) is part of the key, so a changed
  result misses the store and runs the model.
* ``tests/test_stored.py`` recomputes the cheapest stored call of every function in the
  default run and every stored call in the nightly run (``-m exhaustive``), and compares.

A session that ran the model for calls the store lacks says how many in pytest's summary
(``MSTMM_STORED_MISSED=<file>`` lists them). Some are expected: an input that comes
from the code under test (a root it found) misses when it differs in one bit from the
recording run's (a cold CI run of f117c64 ran 461 calls past the store of 14,139, 432 of them
``count_below`` at about 6 ms each). Many mean the store is stale: write it again.
"""

from __future__ import annotations

import dataclasses
import functools
import gzip
import hashlib
import importlib
import inspect
import json
import os
import threading
import time
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np
from mpmath import mp

HERE = Path(__file__).resolve().parent
STORE = HERE / "data" / "stored_references.jsonl.gz"
#: Where a recording session's processes write their calls (merged by make_stored.py).
PARTIAL = HERE / "data" / "stored_partial"
#: The slow functions looked up, by model module.
STORED = {
    "reference_model": (
        "frequencies",
        "band",
        "count_below",
        "global_determinant",
        "eigenspace",
        "mode_at_attachments",
        "damped_frequencies",
        "damped_count",
        "damped_zero_count",
        "damped_global_determinant",
        "frf",
    ),
    "reference_bloch": ("band_edges", "bloch_mu", "bloch_k", "edge_count"),
}
#: The files whose source keys the store: the models (the encoding is checked by
#: tests/test_stored.py recomputing stored calls from their stored arguments).
SOURCES = ("reference_model.py", "reference_bloch.py")

RECORD = os.environ.get("MSTMM_STORED") == "record"
#: A file to list the calls the store lacked in (function and arguments, a line each).
MISSED = os.environ.get("MSTMM_STORED_MISSED")
#: Calls answered from the store and calls the models ran, this session.
hits = 0
misses = 0
#: The seconds the models ran for the calls the store lacked, this session.
missed_seconds = 0.0
_lock = threading.Lock()
_inside = threading.local()  # a stored function's own calls of another run it directly
_table: dict[str, dict] | None = None
_partial = None


def model_digest() -> str:
    h = hashlib.sha1()
    for name in SOURCES:
        h.update((HERE / name).read_bytes())
    return h.hexdigest()


class Unstorable(TypeError):
    """A value the encoding does not cover: the call runs the model."""


def encode(value: Any) -> Any:
    """JSON of ``value``, exact: floats by repr, mpf by its raw (sign, mantissa, exponent,
    bits), dataclasses (a scene) by the fields they compare, tuples tagged apart from
    lists."""
    if value is None or isinstance(value, (bool, str)):
        return value
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        f = float(value)
        return f if np.isfinite(f) else {"float": repr(f)}
    if isinstance(value, (complex, np.complexfloating)):
        return {"complex": [encode(value.real), encode(value.imag)]}
    if isinstance(value, mp.mpf):
        s, man, e, bc = value._mpf_
        return {"mpf": [s, hex(man), e, bc]}  # inf and nan too: (0, 0, -456, -2), ...
    if isinstance(value, mp.mpc):
        return {"mpc": [encode(value.real), encode(value.imag)]}
    if isinstance(value, Fraction):
        return {"fraction": [value.numerator, value.denominator]}
    if isinstance(value, np.ndarray):
        return {"ndarray": [value.dtype.str, encode(value.tolist())]}
    if isinstance(value, mp.matrix):
        rows = [[value[i, j] for j in range(value.cols)] for i in range(value.rows)]
        return {"mp.matrix": encode(rows)}
    if isinstance(value, list):
        return [encode(v) for v in value]
    if isinstance(value, tuple):
        return {"tuple": [encode(v) for v in value]}
    if isinstance(value, dict):
        if not all(isinstance(k, str) for k in value):
            raise Unstorable(f"a dict with keys {list(value)!r}")
        return {"dict": {k: encode(v) for k, v in value.items()}}
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        cls = type(value)
        # what the dataclass compares: not a scene's ``source`` (the file it was read
        # from: a clone elsewhere is the same scene), ``repeat``, ``cell``, ``graded``
        compared = [f for f in dataclasses.fields(value) if f.compare]
        fields = {f.name: encode(getattr(value, f.name)) for f in compared}
        return {"dataclass": [f"{cls.__module__}:{cls.__qualname__}", fields]}
    raise Unstorable(f"cannot store a {type(value).__name__}")


def decode(data: Any) -> Any:
    """The value :func:`encode` was given (mpf exactly, at whatever precision it had)."""
    if isinstance(data, list):
        return [decode(v) for v in data]
    if not isinstance(data, dict):
        return data
    ((tag, body),) = data.items()
    if tag == "float":
        return float(body)
    if tag == "complex":
        return complex(decode(body[0]), decode(body[1]))
    if tag == "mpf":
        s, man, e, bc = body
        return mp.make_mpf((s, int(man, 16), e, bc))
    if tag == "mpc":
        return mp.make_mpc((decode(body[0])._mpf_, decode(body[1])._mpf_))
    if tag == "fraction":
        return Fraction(*body)
    if tag == "ndarray":
        return np.array(decode(body[1]), dtype=np.dtype(body[0]))
    if tag == "mp.matrix":
        return mp.matrix(decode(body))
    if tag == "tuple":
        return tuple(decode(v) for v in body)
    if tag == "dict":
        return {k: decode(v) for k, v in body.items()}
    if tag == "dataclass":
        module, _, qualname = body[0].partition(":")
        cls = importlib.import_module(module)
        for part in qualname.split("."):
            cls = getattr(cls, part)
        fields = {k: decode(v) for k, v in body[1].items()}
        init = {f.name for f in dataclasses.fields(cls) if f.init}
        return cls(**{k: v for k, v in fields.items() if k in init})
    raise Unstorable(f"unknown tag {tag!r}")


def key_of(name: str, arguments: Any) -> str:
    """A call's key: the function and its arguments. Not mpmath's global precision: the
    models work at the ``dps`` they are given (test modules set the global one as they
    are imported, so it depends on which files a worker ran before); a stored call is
    recomputed at mpmath's default precision by tests/test_stored.py."""
    text = json.dumps([name, arguments], sort_keys=True, separators=(",", ":"))
    return hashlib.sha1(text.encode()).hexdigest()


@functools.cache  # read once per process: the lookups and tests/test_stored.py share it
def read_store(path: Path = STORE) -> tuple[dict, dict[str, dict]]:
    """The store's header and its entries by key, their arguments whole (empty without a
    store; not to be changed by callers). An argument of more than :data:`SHARED`
    characters is stored once, on a line of its own, and named by its digest where a call
    has it (thousands of calls share a scene)."""
    if not path.exists():
        return {}, {}
    shared, entries = {}, {}
    with gzip.open(path, "rt") as fh:
        header = json.loads(fh.readline())
        for line in fh:
            e = json.loads(line)
            if "ref" in e:
                shared[e["ref"]] = e["value"]
            else:
                entries[e["key"]] = e
    for e in entries.values():
        named = e["arguments"]["dict"]
        for k, v in named.items():
            if isinstance(v, dict) and "ref" in v:
                named[k] = shared[v["ref"]]
    return header, entries


#: Arguments longer than this (JSON characters) are stored once (:func:`read_store`).
SHARED = 400


def split_shared(entry: dict) -> tuple[dict, dict[str, Any]]:
    """``entry`` with its long arguments named by digest, and those arguments."""
    named, shared = {}, {}
    for k, v in entry["arguments"]["dict"].items():
        text = json.dumps(v, sort_keys=True, separators=(",", ":"))
        if len(text) > SHARED:
            ref = hashlib.sha1(text.encode()).hexdigest()
            shared[ref] = v
            v = {"ref": ref}
        named[k] = v
    return dict(entry, arguments={"dict": named}), shared


def _entries() -> dict[str, dict]:
    global _table
    if _table is None:
        header, table = read_store()
        _table = table if header.get("model") == model_digest() else {}
    return _table


def _bound(f, args, kwargs) -> dict:
    call = inspect.signature(f).bind(*args, **kwargs)
    call.apply_defaults()
    return dict(call.arguments)


def _record(entry: dict) -> None:
    global _partial
    with _lock:
        if _partial is None:
            PARTIAL.mkdir(exist_ok=True)
            _partial = open(PARTIAL / f"{os.getpid()}.jsonl", "a")  # noqa: SIM115
        _partial.write(json.dumps(entry, separators=(",", ":")) + "\n")
        _partial.flush()


def stored(f, name: str):
    """``f`` looked up in the store (or, recording, run and written to it)."""

    @functools.wraps(f)
    def lookup(*args, **kwargs):
        global hits, misses
        if getattr(_inside, "depth", 0):
            return f(*args, **kwargs)
        try:
            arguments = encode(_bound(f, args, kwargs))
            key = key_of(name, arguments)
        except Unstorable:
            return f(*args, **kwargs)
        entry = None if RECORD else _entries().get(key)
        if entry is not None:
            try:
                value = decode(entry["value"])
            except Unstorable:
                pass
            else:
                hits += 1
                return value
        global missed_seconds
        misses += 1
        t0 = time.perf_counter()
        _inside.depth = 1
        try:
            value = f(*args, **kwargs)
        finally:
            _inside.depth = 0
        if not RECORD:
            seconds = time.perf_counter() - t0
            missed_seconds += seconds
            if MISSED:
                with _lock, open(MISSED, "a") as fh:
                    fh.write(json.dumps([name, seconds, arguments]) + "\n")
        if RECORD:
            try:
                encoded = encode(value)
            except Unstorable:
                return value
            entry = {"key": key, "function": name, "prec": mp.prec, "arguments": arguments}
            entry.update(value=encoded, seconds=round(time.perf_counter() - t0, 4))
            _record(entry)
        return value

    lookup.live = f
    return lookup


def install() -> None:
    """Wrap the functions of :data:`STORED` in their modules (before any test module
    imports them by name; inside a stored function the models' own calls of another run
    as they are)."""
    for module_name, names in STORED.items():
        module = importlib.import_module(module_name)
        for name in names:
            f = getattr(module, name)
            if not hasattr(f, "live"):  # not installed yet
                setattr(module, name, stored(f, f"{module_name}.{name}"))


def recompute(entry: dict) -> tuple[Any, Any]:
    """(stored value, the model's value now, at mpmath's default precision) of one
    entry, both decoded."""
    module_name, _, name = entry["function"].rpartition(".")
    f = getattr(importlib.import_module(module_name), name)
    f = getattr(f, "live", f)
    kwargs = decode(entry["arguments"])
    prec = mp.prec
    mp.prec = 53  # mpmath's default; the entry was made at entry["prec"]
    _inside.depth = 1  # the model's own calls run the model too
    try:
        now = f(**kwargs)
    finally:
        mp.prec = prec
        _inside.depth = 0
    return decode(entry["value"]), now

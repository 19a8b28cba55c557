"""Write ``tests/data/stored_references.jsonl.gz``: every slow reference-model call the
default test run makes, with the model's answer (``tests/stored.py``).

Runs the default test run (``python -m pytest -n auto``) with ``MSTMM_STORED=record``:
every call of a function of ``stored.STORED`` runs the model and is written down; then
the calls are merged (one entry per key; two processes that made the same call must
have got the same answer), sorted by key, under a header naming the models' source digest.
Run it after changing ``reference_model.py`` or ``reference_bloch.py`` (their test then
says so) or when pytest's summary reports calls the store lacks. Takes as long as a test
run without the store (about 20 minutes on 2 cores); extra arguments go to pytest.
``--add`` keeps the stored calls and adds those of the run (a few test files, after one
of them changed what it asks the models):

    python tests/make_stored.py
    python tests/make_stored.py --add tests/test_roots.py
"""

from __future__ import annotations

import gzip
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import stored  # noqa: E402


def merge(parts: list[Path]) -> dict[str, dict]:
    entries: dict[str, dict] = {}
    for part in parts:
        for line in part.read_text().splitlines():
            if not line.strip():
                continue
            entry = json.loads(line)
            seen = entries.setdefault(entry["key"], entry)
            if seen["value"] != entry["value"]:
                raise SystemExit(f"{entry['function']}: two answers for one call ({part})")
    return entries


def write(entries: dict[str, dict], model: str | None = None, path: Path = stored.STORE) -> None:
    """The header (``model``: the models' digest, by default of their source now), each
    long argument once (``stored.read_store``), then the calls, sorted by key."""
    import mpmath

    header = {"model": model or stored.model_digest(), "mpmath": mpmath.__version__}
    header["entries"] = len(entries)
    calls, shared = [], {}
    for key in sorted(entries):
        entry, long = stored.split_shared(entries[key])
        calls.append(entry)
        shared.update(long)
    lines = [header] + [{"ref": r, "value": shared[r]} for r in sorted(shared)] + calls
    tmp = path.with_suffix(".tmp")
    # mtime 0: the same entries give the same bytes
    with open(tmp, "wb") as raw, gzip.GzipFile(fileobj=raw, mode="wb", mtime=0) as fh:
        for line in lines:
            fh.write((json.dumps(line, separators=(",", ":")) + "\n").encode())
    os.replace(tmp, path)


def main(argv: list[str]) -> int:
    add = "--add" in argv
    argv = [a for a in argv if a != "--add"]
    shutil.rmtree(stored.PARTIAL, ignore_errors=True)
    # CI=true: hypothesis draws CI's examples (tests/conftest.py), the calls CI makes
    env = dict(os.environ, MSTMM_STORED="record", CI="true")
    command = [sys.executable, "-m", "pytest", "-q", "-n", "auto", "-p", "no:cacheprovider"]
    command += ["--ignore", str(HERE / "test_stored.py")]  # the store being written
    run = subprocess.run([*command, *argv], cwd=HERE.parent, env=env)
    parts = sorted(stored.PARTIAL.glob("*.jsonl"))
    if run.returncode != 0:
        print(f"the test run failed (status {run.returncode}): the store is not written")
        return 1
    entries = merge(parts)
    if add:  # the store's calls kept (one model: its digest must be today's)
        header, kept = stored.read_store()
        if header.get("model") != stored.model_digest():
            print("the store was written by another version of the models: write it whole")
            return 1
        entries = {**kept, **entries}
    write(entries)
    shutil.rmtree(stored.PARTIAL, ignore_errors=True)
    size = stored.STORE.stat().st_size
    print(f"{stored.STORE}: {len(entries)} calls, {size / 1e6:.1f} MB")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))

"""The figures README.md and docs/*.md quote, as the benchmarks measured them: docs/figures.json.

Each benchmark the pages quote records its figures here under its own key
(:func:`record` merges by key, so running one benchmark leaves the others'
figures alone); ``python -m benchmarks.readme`` writes the figure blocks of
README.md and docs/*.md from this file, wherever each block stands, and
``tests/test_readme_figures.py`` checks that the pages hold exactly what it would
write. A figure is never typed by hand.
"""

from __future__ import annotations

import json
import math
import os
import platform
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FIGURES = ROOT / "docs" / "figures.json"


def load(path: Path = FIGURES) -> dict:
    """Every recorded section (``{}`` when the file does not exist)."""
    return json.loads(path.read_text()) if path.exists() else {}


def finite(value):
    """``value`` with every NaN or infinite float replaced by None (strict JSON: a failed
    measurement is null, never a number)."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [finite(v) for v in value]
    return value


def save(data: dict, path: Path = FIGURES) -> Path:
    """Write ``data`` to ``path`` (sections sorted, strict JSON), atomically."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")  # then renamed: never half-written
    text = json.dumps(finite(dict(sorted(data.items()))), indent=1, allow_nan=False)
    tmp.write_text(text + "\n")
    os.replace(tmp, path)
    return path


def record(section: str, values: dict, path: Path = FIGURES, command: str | None = None) -> Path:
    """Store ``values`` as ``section`` of ``path`` (other sections kept), atomically.

    The entry also says when, by which command and on what it was measured.
    """
    data = load(path)
    data[section] = {
        **values,
        "measured": {
            "date": time.strftime("%Y-%m-%d %H:%M:%S %Z"),
            "command": command or "python -m " + Path(sys.argv[0]).stem,
            "machine": f"{platform.machine()}, {os.cpu_count()} cores, "
            f"Python {platform.python_version()}",
        },
    }
    return save(data, path)

"""The figures the README quotes, as the benchmarks measured them: ``docs/figures.json``.

Each benchmark the README quotes records its figures here under its own key
(:func:`record` merges by key, so running one benchmark leaves the others'
figures alone); ``python -m benchmarks.readme`` writes the README's figure
blocks from this file, and ``tests/test_readme_figures.py`` checks that the
README holds exactly what it would write. A figure is never typed by hand.
"""

from __future__ import annotations

import json
import os
import platform
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FIGURES = ROOT / "docs" / "figures.json"


def load(path: Path = FIGURES) -> dict:
    """Every recorded section (``{}`` when the file does not exist)."""
    return json.loads(path.read_text()) if path.exists() else {}


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
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".figures-", suffix=".json")
    try:
        with os.fdopen(fd, "w") as fh:
            json.dump(dict(sorted(data.items())), fh, indent=1, sort_keys=False)
            fh.write("\n")
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path

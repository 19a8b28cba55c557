"""The README's example output: ``mstmm solve`` in a fresh process, as a user sees it.

Run: ``python -m benchmarks.example``.

Runs ``mstmm solve`` (the bundled paper example, lowest ten) once to fill the
kernel and numba caches, then again in a fresh process, and records that
second run's standard output verbatim, time line included, in
``docs/figures.json`` (key ``example``); ``python -m benchmarks.readme`` quotes
it. The machine-readable twin (``--format json``) gives the time of the
in-process work for the prose around it.

``python -m benchmarks.example --front-page`` records the README's other examples
instead (key ``front_page``: each command of :data:`FRONT_PAGE` as a user types it, run
from the repository root, its standard output verbatim, after a first run that fills
the caches); ``python -m benchmarks.readme`` quotes them (blocks ``front-NAME``).
"""

from __future__ import annotations

import json
import subprocess
import sys

from . import figures

COMMAND = ("solve",)

#: The README's other examples: name -> the arguments of ``mstmm`` (no argument holds a
#: space).
FRONT_PAGE = {
    name: tuple(args.split())
    for name, args in {
        "damped": "solve examples/tmd_den_hartog.toml --modes 4",
        "frf": "frf examples/tmd_den_hartog.toml --input force:x=5.0"
        " --output displacement:x=5.0 --band 5 15 --points 5 --format table",
        "bands": "bands examples/metamaterial.toml --band 0 6000",
        "sweep": "sweep examples/wu_chou_1998.toml --vary attachments[2].k=LOG:1e3:1e9:200"
        " --modes 5",
        "frame": "solve examples/frames/nafems_fv2.toml --modes 16",
    }.items()
}


def _mstmm(*args: str) -> str:
    cmd = [sys.executable, "-m", "mstmm", *args]
    return subprocess.run(cmd, check=True, capture_output=True, text=True, cwd=figures.ROOT).stdout


def _typed(args: tuple[str, ...]) -> str:
    """``args`` as a user types them in a shell (a bracketed field quoted)."""
    return " ".join(f"'{a}'" if "[" in a else a for a in args)


def front_page() -> dict:
    """Each front-page command's fresh-process output (caches filled by a first run)."""
    out = {}
    for name, args in FRONT_PAGE.items():
        _mstmm(*args)
        out[name] = {"command": "mstmm " + _typed(args), "output": _mstmm(*args)}
    return out


def measure() -> dict:
    """The fresh-process output of ``mstmm solve`` and its JSON timings."""
    _mstmm(*COMMAND)  # kernel and numba's on-disk cache in place, as for a returning user
    output = _mstmm(*COMMAND)
    data = json.loads(_mstmm(*COMMAND, "--format", "json"))
    return {
        "command": "mstmm " + " ".join(COMMAND),
        "output": output,
        "timings": data["timings"],
        "kernel_mode": data.get("kernel_mode", ""),
    }


def main(argv: list[str] | None = None) -> None:
    if "--front-page" in (sys.argv[1:] if argv is None else argv):
        fig = front_page()
        for ex in fig.values():
            print(f"$ {ex['command']}\n{ex['output']}", end="")
        cmd = "python -m benchmarks.example --front-page"
        print(f"recorded in {figures.record('front_page', fig, command=cmd)}")
        return
    fig = measure()
    print(f"$ {fig['command']}\n{fig['output']}", end="")
    print(f"recorded in {figures.record('example', fig, command='python -m benchmarks.example')}")


if __name__ == "__main__":
    main()

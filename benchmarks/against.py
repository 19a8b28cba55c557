"""This checkout against another revision of mstmm, interleaved: ``python -m benchmarks.against``.

Answers "did it get slower?" with one ratio measured in one run: the same timing snippet
runs in this interpreter's mstmm and in another interpreter whose mstmm is the older
revision (``--other-python``, e.g. a venv with ``pip install -e <old checkout> --no-deps``),
alternating rounds so that both see the same machine load. Each round times
``kernel.lowest(p, modes)`` of the paper example, warm (compiled, frequencies only), as
the median of ``--repeats`` calls; the report gives each side's median over the rounds
and their ratio.

    git worktree add /tmp/old 33cf287
    python -m venv /tmp/oldvenv && /tmp/oldvenv/bin/pip install -e /tmp/old
    python -m benchmarks.against --other-python /tmp/oldvenv/bin/python --record
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys

from . import figures

SNIPPET = """
import json, sys, time
import numpy as np
import mstmm
from mstmm import interpret
interpret.set_budget(0.0)
scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
kernel = mstmm.kernel_for(scene)
p = mstmm.parameter_vector(scene)
modes, repeats = int(sys.argv[1]), int(sys.argv[2])
found = kernel.lowest(p, modes)
omega = found.omega if hasattr(found, "omega") else found[0]
times = []
for _ in range(repeats):
    t = time.perf_counter()
    kernel.lowest(p, modes)
    times.append(time.perf_counter() - t)
print(json.dumps({"median": float(np.median(times)), "omega": [float(w) for w in omega],
                  "where": mstmm.__file__}))
"""


def _time(python: str, modes: int, repeats: int) -> dict:
    out = subprocess.run(
        [python, "-c", SNIPPET, str(modes), str(repeats)],
        capture_output=True,
        text=True,
        check=True,
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--other-python", required=True, help="interpreter of the older mstmm")
    ap.add_argument("--label", default="33cf287", help="name of the older revision")
    ap.add_argument("--modes", type=int, default=5)
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--repeats", type=int, default=2000)
    ap.add_argument("--record", action="store_true", help="store in docs/figures.json")
    args = ap.parse_args(argv)
    here, other = [], []
    for _ in range(args.rounds):
        here.append(_time(sys.executable, args.modes, args.repeats))
        other.append(_time(args.other_python, args.modes, args.repeats))
    if here[0]["where"] == other[0]["where"]:
        raise SystemExit("both interpreters import the same mstmm: nothing to compare")
    t_here = statistics.median(r["median"] for r in here)
    t_other = statistics.median(r["median"] for r in other)
    agree = max(
        abs(a - b) / b for a, b in zip(here[0]["omega"], other[0]["omega"], strict=True) if b
    )
    result = {
        "modes": args.modes,
        "this_seconds": t_here,
        "other_seconds": t_other,
        "other_label": args.label,
        "ratio": t_here / t_other,
        "largest_difference": agree,
        "rounds": args.rounds,
        "repeats": args.repeats,
    }
    print(
        f"paper example, lowest {args.modes}, warm: this checkout {t_here * 1e6:.1f} us,"
        f" {args.label} {t_other * 1e6:.1f} us (ratio {t_here / t_other:.2f};"
        f" {args.rounds} interleaved rounds of {args.repeats}); frequencies agree to {agree:.1e}"
    )
    if args.record:
        figures.record("against", result, command="python -m benchmarks.against")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

"""Write kernels: ``python -m mstmm.derive --bundled`` regenerates the committed ones.

``python -m mstmm.derive --topology KEY --out DIR`` writes one kernel as
``DIR/KEY.py``; ``--bundled`` writes the kernels of every bundled scene into
the ``generated/`` folder of this source tree.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from mstmm.catalog import Topology

from .bundled import BUNDLED_TOPOLOGIES, generated_dir
from .emit import write_kernel, write_numerics


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m mstmm.derive", description=__doc__)
    group = ap.add_mutually_exclusive_group(required=True)
    group.add_argument(
        "--topology",
        help="kernel key, e.g. beam__spring_mass (a topology key such as"
        " clamped_free__spring_mass names its kernel too)",
    )
    group.add_argument("--bundled", action="store_true", help="regenerate generated/")
    ap.add_argument("--out", type=Path, help="output directory (with --topology)")
    args = ap.parse_args(argv)
    if args.bundled:
        print(write_numerics(generated_dir()))
        for topology in BUNDLED_TOPOLOGIES:
            print(write_kernel(topology, generated_dir(), name=f"{topology.kernel_key}.py"))
        return 0
    if args.out is None:
        ap.error("--topology needs --out")
    topology = Topology.from_key(args.topology)
    print(write_kernel(topology, args.out, name=f"{topology.kernel_key}.py"))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

"""``python -m benchmarks.frames``: plane frames (issue 43), run time against size.

A regular building frame of ``storeys`` x ``bays`` (columns and floor beams of steel
sections, fixed feet; optionally a roof tuned mass damper acting horizontally), its lowest
``modes`` natural frequencies certified, cold (first call in the process: compiles or
loads the members' functions) and warm (median of ``--rounds``), with and without shapes.
Prints one line per size; ``--json FILE`` writes them.
"""

from __future__ import annotations

import argparse
import json
import statistics
import time

from mstmm.frame import frame_from_dict, solve_frame


def building(storeys: int, bays: int, h: float = 3.5, span: float = 6.0, tmd: dict | None = None):
    """A frame scene table: columns (EI 5.25e7, EA 3.15e9, 120 kg/m) and floor beams (EI
    6.3e7, EA 2.52e9, 2000 kg/m with the slab), fixed feet, a TMD at the roof's left node."""
    nodes, members = [], []
    for i in range(storeys + 1):
        for j in range(bays + 1):
            node = {"name": f"N{i}_{j}", "x": span * j, "y": h * i}
            if i == 0:
                node["support"] = "fixed"
            nodes.append(node)
    column = {"EI": 2.1e11 * 2.5e-4, "EA": 2.1e11 * 1.5e-2, "mass_per_length": 120.0}
    beam = {"EI": 2.1e11 * 3.0e-4, "EA": 2.1e11 * 1.2e-2, "mass_per_length": 2000.0}
    for i in range(storeys):
        for j in range(bays + 1):
            members.append({"start": f"N{i}_{j}", "end": f"N{i + 1}_{j}", **column})
        for j in range(bays):
            members.append({"start": f"N{i + 1}_{j}", "end": f"N{i + 1}_{j + 1}", **beam})
    attachments = []
    if tmd:
        node = f"N{storeys}_0"
        attachments.append({"type": "spring_mass", "node": node, "direction": [1.0, 0.0], **tmd})
    return {"name": f"building_{storeys}x{bays}", "nodes": nodes, "members": members,
            "attachments": attachments}  # fmt: skip


def run(storeys: int, bays: int, modes: int, rounds: int) -> dict:
    frame = frame_from_dict(building(storeys, bays))
    t = time.perf_counter()
    solve_frame(frame, modes, shapes=False)
    cold = time.perf_counter() - t
    warm, shaped = [], []
    for _ in range(rounds):
        t = time.perf_counter()
        sol = solve_frame(frame, modes, shapes=False)
        warm.append(time.perf_counter() - t)
        t = time.perf_counter()
        solve_frame(frame, modes)
        shaped.append(time.perf_counter() - t)
    return {
        "storeys": storeys, "bays": bays, "members": len(frame.members), "modes": modes,
        "first_hz": float(sol.f[0]), "cold_s": cold, "warm_s": statistics.median(warm),
        "with_shapes_s": statistics.median(shaped),
    }  # fmt: skip


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--sizes", default="2x1,5x2,10x3,20x3", help="storeys x bays, comma-separated"
    )
    parser.add_argument("--modes", type=int, default=20)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--json")
    args = parser.parse_args(argv)
    rows = []
    for size in args.sizes.split(","):
        storeys, bays = (int(v) for v in size.split("x"))
        row = run(storeys, bays, args.modes, args.rounds)
        rows.append(row)
        print(
            f"{storeys:>3} storeys x {bays} bays ({row['members']:>3} members): lowest"
            f" {args.modes} certified, cold {row['cold_s']:.3f} s, warm {row['warm_s']:.3f} s,"
            f" with shapes {row['with_shapes_s']:.3f} s (f1 = {row['first_hz']:.6g} Hz)",
            flush=True,
        )
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

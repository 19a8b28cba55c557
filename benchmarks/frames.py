"""``python -m benchmarks.frames``: plane frames (issue 43), run time against size.

A regular building frame of ``storeys`` x ``bays`` (columns and floor beams of steel
sections, fixed feet, two tuned mass dampers on the roof acting horizontally, 1 % of the
building's mass each, tuned to its first mode by Den Hartog's rule), its lowest ``modes``
natural frequencies certified, cold (first call in the process: loads the members'
compiled functions) and warm (median of ``--rounds``), with and without shapes. Prints one
line per size; ``--json FILE`` writes them.

``--damped``: the last size with Den Hartog's dashpot in each roof TMD (and, a second
row, a loss factor of 0.02 in every member as well): its lowest ``modes`` damped roots
certified (:mod:`mstmm.frame.damped`), warm, and the ratio to the undamped run.

``--fem``: the same building by the finite-element model a user would write instead
(textbook rod and Hermite beam elements, consistent masses, as ``tests/reference_frame_fem.py``,
assembled sparse and solved by shift-invert Lanczos, ``scipy.sparse.linalg.eigsh``), with
``n`` elements a member for n = 1, 2, 4, ..., and Richardson's extrapolation of each pair
(``h^4``, the Hermite elements' order: the low modes are bending): the worst relative error
of the lowest ``modes`` against mstmm's, and the run time. The exact answer is mstmm's,
checked on frames against the 30-digit reference model (``tests/test_plane_frames.py``).
"""

from __future__ import annotations

import argparse
import json
import math
import statistics
import sys
import time

import numpy as np

from mstmm.frame import frame_from_dict, solve_frame


def building(
    storeys: int,
    bays: int,
    h: float = 3.5,
    span: float = 6.0,
    tmd: dict | None = None,
    distinct: bool = False,
):
    """A frame scene table: columns (EI 5.25e7, EA 3.15e9, 120 kg/m) and floor beams (EI
    6.3e7, EA 2.52e9, 2000 kg/m with the slab), fixed feet; ``tmd`` (``k``, ``m``): a TMD
    at each of the roof's end nodes, acting along X. ``distinct``: every member its own
    section (EI 0.1 % apart from one member to the next), so that none shares its
    stiffness with another (the solver computes each distinct section once a frequency)."""
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
    if distinct:
        members = [{**m, "EI": m["EI"] * (1 + 1e-3 * i)} for i, m in enumerate(members)]
    attachments = []
    for j in (0, bays) if tmd else ():
        node = f"N{storeys}_{j}"
        attachments.append({"type": "spring_mass", "node": node, "direction": [1.0, 0.0], **tmd})
    return {"name": f"building_{storeys}x{bays}", "nodes": nodes, "members": members,
            "attachments": attachments}  # fmt: skip


def with_dampers(storeys: int, bays: int, distinct: bool = False) -> dict:
    """The building with its two roof TMDs: each 1 % of the frame's mass, tuned to the
    bare frame's first frequency by Den Hartog's rule (``f = 1 / (1 + mu)``, mu the pair's
    mass over the first mode's effective mass)."""
    bare = solve_frame(frame_from_dict(building(storeys, bays, distinct=distinct)), 1)
    mass = bare.frame.mass
    m = 0.01 * mass
    mu = 2 * m / bare.modes[0].effective_mass[0]
    w = bare.omega[0] / (1 + mu)
    return building(storeys, bays, tmd={"k": m * w * w, "m": m}, distinct=distinct)


def damped(storeys: int, bays: int, modes: int, rounds: int, undamped_s: float) -> list[dict]:
    """The building's damped roots (Den Hartog's dashpots; then a loss factor too): warm
    median of ``rounds``, and its ratio to the undamped warm time ``undamped_s``."""
    table = with_dampers(storeys, bays)
    frame = frame_from_dict(table)
    mu = 2 * table["attachments"][0]["m"] / solve_frame(frame, 1).modes[0].effective_mass[0]
    zeta = math.sqrt(3 * mu / (8 * (1 + mu) ** 3))
    for a in table["attachments"]:
        a["c"] = 2 * zeta * math.sqrt(a["k"] * a["m"])
    rows = []
    for eta in (0.0, 0.02):
        point = {**table, "members": [{**m, "loss_factor": eta} for m in table["members"]]}
        frame = frame_from_dict(point)
        solve_frame(frame, modes, shapes=False)
        times = []
        for _ in range(rounds):
            t = time.perf_counter()
            sol = solve_frame(frame, modes, shapes=False)
            times.append(time.perf_counter() - t)
        warm = statistics.median(times)
        rows.append({
            "storeys": storeys, "bays": bays, "modes": modes, "zeta_tmd": zeta,
            "loss_factor": eta, "warm_s": warm, "ratio": warm / undamped_s,
            "count_checked": bool(sol.count_checked),
            "first": [sol.omega[0].real, sol.omega[0].imag],
        })  # fmt: skip
    return rows


def fem_frequencies(table: dict, modes: int, n: int) -> np.ndarray:
    """The lowest ``modes`` natural frequencies (rad/s) of a building table by finite
    elements, ``n`` a member (``tests/reference_frame_fem.py``'s elements), sparse."""
    import scipy.sparse as sp
    from reference_frame_fem import _element
    from scipy.sparse.linalg import eigsh

    xy = {nd["name"]: (nd["x"], nd["y"]) for nd in table["nodes"]}
    fixed = {nd["name"] for nd in table["nodes"] if nd.get("support") == "fixed"}
    index: dict = {}

    def dof(key) -> int:
        return index.setdefault(key, len(index))

    rows, cols, kv, mv = [], [], [], []
    for i, mem in enumerate(table["members"]):
        (xa, ya), (xb, yb) = xy[mem["start"]], xy[mem["end"]]
        L = math.hypot(xb - xa, yb - ya)
        k, m = _element(
            mem["EI"], mem["EA"], mem["mass_per_length"], L / n, (xb - xa) / L, (yb - ya) / L
        )
        for e in range(n):
            keys = []
            for at in (e, e + 1):
                node = mem["start"] if at == 0 else mem["end"] if at == n else None
                keys += [(node, j) if node else (i, at, j) for j in range(3)]
            g = np.array([dof(key) for key in keys])
            rows.append(np.repeat(g, 6))
            cols.append(np.tile(g, 6))
            kv.append(k.ravel())
            mv.append(m.ravel())
    for a in table["attachments"]:  # a spring_mass along X at a node
        g = np.array([dof((a["node"], 0)), dof(("tmd", a["node"]))])
        rows.append(np.repeat(g, 2))
        cols.append(np.tile(g, 2))
        kv.append(a["k"] * np.array([1.0, -1.0, -1.0, 1.0]))
        mv.append(np.array([0.0, 0.0, 0.0, a["m"]]))
    size = len(index)
    shape = (size, size)
    r, c = np.concatenate(rows), np.concatenate(cols)
    K = sp.csc_matrix((np.concatenate(kv), (r, c)), shape=shape)
    M = sp.csc_matrix((np.concatenate(mv), (r, c)), shape=shape)
    free = np.array([g for key, g in index.items() if key[0] not in fixed])
    K, M = K[free][:, free], M[free][:, free]
    lam = eigsh(K, k=modes, M=M, sigma=0.0, which="LM", return_eigenvectors=False)
    return np.sqrt(np.sort(lam))


def fem_run(storeys: int, bays: int, modes: int, exact: np.ndarray, largest: int) -> list[dict]:
    """The finite-element model with 1, 2, 4, ... elements a member up to ``largest``:
    each mesh's time and worst relative error, and Richardson's extrapolation over the
    last two meshes (``h^2``: the rod's linear elements lead) and the last three (``h^2``
    then ``h^4``, the Hermite elements'), timed as the meshes they need."""
    table = with_dampers(storeys, bays)
    out: list[dict] = []
    meshes: list[tuple[np.ndarray, float]] = []

    def error(w: np.ndarray) -> float:
        return float(np.max(np.abs(w - exact) / exact))

    n = 1
    while n <= largest:
        t = time.perf_counter()
        w = fem_frequencies(table, modes, n)
        meshes.append((w, time.perf_counter() - t))
        row = {"elements": n, "s": meshes[-1][1], "error": error(w)}
        if len(meshes) >= 2:
            (w1, s1), (w2, s2) = meshes[-2:]
            row["richardson2"] = error((4 * w2 - w1) / 3)
            row["richardson2_s"] = s1 + s2
        if len(meshes) >= 3:
            (w0, s0), (w1, s1), (w2, s2) = meshes[-3:]
            r1, r2 = (4 * w1 - w0) / 3, (4 * w2 - w1) / 3
            row["richardson3"] = error((16 * r2 - r1) / 15)
            row["richardson3_s"] = s0 + s1 + s2
        out.append(row)
        n *= 2
    return out


def accuracy(modes: int = 12) -> list[dict]:
    """The worst relative error of the lowest ``modes`` frequencies of the test frames
    (``tests/reference_frame.py``: an L-frame, a portal, a tree, two bays and two storeys,
    FV2 with its centre held and free) against the 30-digit reference model's roots, and
    whether every multiplicity agrees."""
    import mpmath
    from reference_frame import as_table, frequencies, nafems_fv2, sample_frames

    cases = {**sample_frames(), "FV2 held": nafems_fv2(True), "FV2 free": nafems_fv2()}
    out = []
    for name, rf in cases.items():
        n = 16 if name.startswith("FV2") else modes
        sol = solve_frame(frame_from_dict(as_table(rf)), n, shapes=False)
        with mpmath.workdps(30):
            ref = [(float(w), m) for w, m in frequencies(rf, n, 30)]
        exact = np.array([w for w, m in ref for _ in range(m)])[:n]
        mult = [m for _, m in ref for _ in range(m)][:n]
        got = sol.omega[:n]
        out.append({
            "frame": name, "modes": n,
            "worst": float(np.max(np.abs(got - exact) / exact)),
            "multiplicities": sol.multiplicity[:n].tolist() == mult,
        })  # fmt: skip
    return out


def run(storeys: int, bays: int, modes: int, rounds: int, distinct: bool = False) -> dict:
    frame = frame_from_dict(with_dampers(storeys, bays, distinct))
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
        "distinct": distinct, "rounds": rounds,
        "first_hz": float(sol.f[0]), "cold_s": cold, "warm_s": statistics.median(warm),
        "with_shapes_s": statistics.median(shaped),
    }  # fmt: skip


def _print(row: dict, modes: int) -> None:
    each = ", every member its own section" if row["distinct"] else ""
    print(
        f"{row['storeys']:>3} storeys x {row['bays']} bays ({row['members']:>3} members{each}):"
        f" lowest {modes} certified, cold {row['cold_s']:.3f} s, warm {row['warm_s']:.3f} s,"
        f" with shapes {row['with_shapes_s']:.3f} s (f1 = {row['first_hz']:.6g} Hz)",
        flush=True,
    )


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--sizes", default="2x1,5x2,10x3,20x3", help="storeys x bays, comma-separated"
    )
    parser.add_argument("--modes", type=int, default=20)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--json")
    parser.add_argument("--accuracy", action="store_true", help="also the accuracy report")
    parser.add_argument(
        "--record", action="store_true", help="record the results in docs/figures.json"
    )
    parser.add_argument("--damped", action="store_true", help="also the damped building")
    parser.add_argument(
        "--fem", type=int, default=0, metavar="N",
        help="also the finite-element model of the last size, up to N elements a member",
    )  # fmt: skip
    args = parser.parse_args(argv)
    rows = []
    for size in args.sizes.split(","):
        storeys, bays = (int(v) for v in size.split("x"))
        row = run(storeys, bays, args.modes, args.rounds)
        rows.append(row)
        _print(row, args.modes)
    distinct = run(*(rows[-1][k] for k in ("storeys", "bays")), args.modes, args.rounds, True)
    _print(distinct, args.modes)
    accurate = accuracy() if args.accuracy else []
    for a in accurate:
        print(f"  {a['frame']:<20} lowest {a['modes']}: worst relative error {a['worst']:.1e},"
              f" multiplicities {'exact' if a['multiplicities'] else 'WRONG'}")  # fmt: skip

    damped_rows = []
    if args.damped:
        storeys, bays = rows[-1]["storeys"], rows[-1]["bays"]
        damped_rows = damped(storeys, bays, args.modes, args.rounds, rows[-1]["warm_s"])
        for d in damped_rows:
            print(
                f"  damped (TMD zeta {d['zeta_tmd']:.3f}, members' loss factor"
                f" {d['loss_factor']:g}): lowest {args.modes} certified"
                f" {d['count_checked']}, warm {d['warm_s']:.3f} s, {d['ratio']:.1f}x the"
                " undamped", flush=True,
            )  # fmt: skip
    if args.fem:
        storeys, bays = rows[-1]["storeys"], rows[-1]["bays"]
        exact = solve_frame(frame_from_dict(with_dampers(storeys, bays)), args.modes, shapes=False)
        mstmm_s = rows[-1]["warm_s"]
        for row in fem_run(storeys, bays, args.modes, exact.omega[: args.modes], args.fem):
            line = (
                f"  FE {row['elements']:>3} elements a member: {row['s']:8.3f} s, worst error"
                f" {row['error']:.1e} ({row['s'] / mstmm_s:,.0f}x mstmm's warm time)"
            )
            for key, what in (("richardson2", "two meshes"), ("richardson3", "three")):
                if key in row:
                    line += (
                        f"; Richardson over {what} {row[key]:.1e} in {row[key + '_s']:.3f} s"
                        f" ({row[key + '_s'] / mstmm_s:,.0f}x)"
                    )
            print(line, flush=True)
            rows[-1].setdefault("fem", []).append(row)
    if args.record:
        from . import figures

        result = {"sizes": rows, "distinct": distinct, "accuracy": accurate}
        if damped_rows:
            result["damped"] = damped_rows
        cmd = "python -m benchmarks.frames " + " ".join(argv if argv is not None else sys.argv[1:])
        print(f"recorded in {figures.record('frames', result, command=cmd)}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

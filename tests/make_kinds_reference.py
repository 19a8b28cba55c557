"""Write ``tests/data/kinds_reference.json``: random scenes mixing every component kind and
their lowest frequencies from the independent mpmath reference model.

The reference model (``tests/reference_model.py``: global assembly plus its own
Wittrick-Williams count) is far too slow to run on hundreds of scenes in CI, so this script
runs it once and the property test (``tests/test_kind_properties.py``) compares ``mstmm``
with the stored numbers. Deterministic: the scenes come from a fixed seed, so re-running
the script rewrites the same file (the frequencies are printed with 20 significant digits).

Every scene holds all seven kinds (spring_mass, mass, spring, rotational_spring, support,
hinge, oscillator_chain), so the solver meets only one topology per end pair (16 kernel
compiles for the whole test). Each end pair gets the same number of scenes.

    python tests/make_kinds_reference.py                 # all scenes (long: run it with nice)
    python tests/make_kinds_reference.py --scenes 2      # a quick look, to standard output
    python tests/make_kinds_reference.py --jobs 2        # two worker processes
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import reference_model  # noqa: E402

OUT = HERE / "data" / "kinds_reference.json"
SEED = 20240613
MODES = 20
DPS = 30
DIGITS = 20
SCENES_PER_END_PAIR = 13  # 16 end pairs: 208 scenes
ENDS = ("clamped", "pinned", "free", "sliding")
KINDS = reference_model.KINDS  # all seven, in this order (the draws depend on it)
FIXES_Y = ("clamped", "pinned")  # a support there is rejected by the scene validator
GRID = 64  # positions on a grid of L / GRID (dyadic: sums and products exact in floats)


def log_uniform(rng: np.random.Generator, lo: float, hi: float) -> float:
    return float(10.0 ** rng.uniform(np.log10(lo), np.log10(hi)))


def beam(rng: np.random.Generator, left: str, right: str) -> tuple[dict, float, float, float]:
    """A uniform or stepped beam (1..4 segments, EI ratios up to 1e2): the beam table, the
    total length L and EI, mass per length of the first segment (the scales of the
    dimensionless values below)."""
    # L in 0.5..40 m with a short binary mantissa: the positions L i / GRID and the sums of
    # the segment lengths are exact in floats, so components on one point coincide exactly
    length = 2.0 ** int(rng.integers(-1, 3)) * int(rng.integers(4, 41)) / 4
    nseg = int(rng.integers(1, 5))
    cuts = np.sort(rng.choice(np.arange(1, GRID), size=nseg - 1, replace=False))
    edges = [0, *cuts.tolist(), GRID]
    ei0 = log_uniform(rng, 1e3, 1e9)
    mbar0 = log_uniform(rng, 1.0, 1e3)
    table: dict = {"left": left, "right": right}
    if nseg == 1:
        table.update(length=length, EI=ei0, mass_per_length=mbar0)
    else:
        segments = []
        for i, (a, b) in enumerate(zip(edges, edges[1:])):
            ei = ei0 if i == 0 else ei0 * log_uniform(rng, 1e-1, 1e1)
            mbar = mbar0 if i == 0 else mbar0 * log_uniform(rng, 0.3, 3.0)
            segments.append({"length": length * (b - a) / GRID, "EI": ei, "mass_per_length": mbar})
        table["segments"] = segments
        ratio = max(s["EI"] for s in segments) / min(s["EI"] for s in segments)
        assert ratio <= 1e2
    return table, length, ei0, mbar0


def draw_scene(rng: np.random.Generator, left: str, right: str) -> dict:
    """One scene: every kind at least once, 7..50 components, some of them sharing points
    (with each other, the ends and the segment boundaries)."""
    table, length, ei0, mbar0 = beam(rng, left, right)
    n = int(rng.integers(7, 51))
    kinds = list(KINDS) + [KINDS[i] for i in rng.integers(0, len(KINDS), size=n - len(KINDS))]
    rng.shuffle(kinds)
    bounds = []
    if "segments" in table:
        x = 0.0
        for seg in table["segments"][:-1]:
            x += seg["length"]
            bounds.append(x)
    used: list[float] = []

    def position(interior: bool) -> float:
        """A point on the grid, a used point (coincident components), an end or a segment
        boundary."""
        u = rng.uniform()
        if u < 0.3 and used:
            x = used[int(rng.integers(len(used)))]
        elif u < 0.4 and bounds:
            x = bounds[int(rng.integers(len(bounds)))]
        elif u < 0.5 and not interior:
            x = (0.0, length)[int(rng.integers(2))]
        else:
            x = length * int(rng.integers(1 if interior else 0, GRID if interior else GRID + 1))
            x /= GRID
        if interior and not 0.0 < x < length:
            x = length * int(rng.integers(1, GRID)) / GRID
        return x

    def stiffness() -> float:  # kappa = k L^3 / EI in 1e-2..1e4
        return log_uniform(rng, 1e-2, 1e4) * ei0 / length**3

    def mass() -> float:  # mu = m / (mbar L) in 1e-2..1e1
        return log_uniform(rng, 1e-2, 1e1) * mbar0 * length

    def rotational() -> float:  # k_theta L / EI in 1e-2..1e4
        return log_uniform(rng, 1e-2, 1e4) * ei0 / length

    hinges: set[float] = set()
    turning: set[float] = set()  # points with a rotational spring or a rotary inertia
    supports: set[float] = set()
    attachments = []
    for kind in kinds:
        for _attempt in range(100):
            x = position(interior=kind == "hinge")
            att: dict = {"type": kind, "x": x}
            if kind == "spring_mass":
                att.update(k=stiffness(), m=mass())
            elif kind == "mass":
                j = 0.0 if rng.uniform() < 0.3 else log_uniform(rng, 1e-3, 1e1)
                att.update(m=mass(), J=j * mbar0 * length**3)
            elif kind == "spring":
                att.update(k=stiffness())
            elif kind == "rotational_spring":
                att.update(k=rotational())
            elif kind == "hinge":
                att.update(k=0.0 if rng.uniform() < 0.5 else rotational())
            elif kind == "oscillator_chain":
                stages = int(rng.integers(1, 5))
                ks = [stiffness() for _ in range(stages)]
                att.update(k=ks, m=[mass() for _ in range(stages)])
            turns = kind == "rotational_spring" or (kind == "mass" and att["J"] > 0)
            at_fixed_end = (x == 0.0 and left in FIXES_Y) or (x == length and right in FIXES_Y)
            if kind == "hinge" and (x in hinges or x in turning):
                continue  # one hinge per point; a rotational component at a hinge: rejected
            if turns and x in hinges:
                continue
            if kind == "support" and (at_fixed_end or x in supports):
                continue  # a support where the end already fixes Y: rejected
            break
        else:  # pragma: no cover - 100 draws on a 64-point grid always find a point
            raise RuntimeError(f"no admissible position for {kind}")
        (hinges if kind == "hinge" else turning if turns else set()).add(x)
        if kind == "support":
            supports.add(x)
        used.append(x)
        attachments.append(att)
    name = f"{left}_{right}_{len(attachments)}"
    return {"name": name, "beam": table, "attachments": attachments}


def scenes() -> list[dict]:
    """All scenes, from one seeded generator, in a fixed order."""
    rng = np.random.default_rng(SEED)
    out = []
    for _round in range(SCENES_PER_END_PAIR):
        for left in ENDS:
            for right in ENDS:
                sc = draw_scene(rng, left, right)
                sc["name"] = f"s{len(out):03d}_{sc['name']}"
                out.append(sc)
    return out


def reference(scene: dict) -> tuple[dict, float]:
    """The reference entry of one scene (its lowest MODES frequencies: rad/s, strings of
    DIGITS significant digits, rigid-body zeros as "0"; its rigid-body count) and the
    seconds it took."""
    start = time.perf_counter()
    omega = reference_model.frequencies(scene, MODES, dps=DPS)
    rigid = reference_model.rigid_body_mode_count(scene)
    assert sum(1 for w in omega if w == 0) == rigid
    text = [
        "0" if w == 0 else reference_model.mpmath.nstr(w, DIGITS, strip_zeros=False) for w in omega
    ]
    entry = {"scene": scene, "omega": text, "rigid_body_modes": rigid}
    return entry, time.perf_counter() - start


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenes", type=int, default=None, help="only the first N scenes")
    parser.add_argument("--jobs", type=int, default=1, help="worker processes (default 1)")
    parser.add_argument("--out", type=Path, default=OUT, help=f"output (default {OUT})")
    args = parser.parse_args(argv)
    todo = scenes()
    whole = args.scenes is None
    if not whole:
        todo = todo[: args.scenes]
    start = time.perf_counter()
    entries = []
    with ProcessPoolExecutor(max_workers=args.jobs) as pool:
        for entry, seconds in pool.map(reference, todo):
            entries.append(entry)
            print(
                f"{entry['scene']['name']}: {seconds:.1f} s "
                f"(total {time.perf_counter() - start:.0f} s)",
                file=sys.stderr,
                flush=True,
            )
    print(f"all: {time.perf_counter() - start:.0f} s", file=sys.stderr)
    data = {
        "about": (
            "Generated by tests/make_kinds_reference.py (seed, counts and ranges there) "
            "with tests/reference_model.py: lowest modes (rad/s, rigid-body zeros as 0)."
        ),
        "seed": SEED,
        "modes": MODES,
        "dps": DPS,
        "scenes": entries,
    }
    text = json.dumps(data, indent=1) + "\n"
    if whole:
        args.out.write_text(text)
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

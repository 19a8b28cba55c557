"""Write ``tests/data/segments_reference.json``: random scenes whose segments carry the
terms beyond Euler-Bernoulli (Timoshenko shear and rotary inertia, axial force, Winkler
and Pasternak foundations; issue 22), with every component kind, and their lowest
frequencies from the independent mpmath reference model.

Like ``make_kinds_reference.py`` (whose beams and components it draws: every end pair the
same number of times, 1..4 segments, every kind in every scene, one of each, so that the
solver meets the topologies of ``tests/test_kind_properties.py`` again), each segment then
takes each term with probability 1/2, in dimensionless ranges wide enough to cross the
Timoshenko cut-off and the foundation's within the lowest modes: ``kappa_GA L^2 / EI`` in
1e1..1e4, ``rho_I / (mbar L^2)`` in 1e-5..1e-2, ``foundation_k L^4 / EI`` in 1..1e3,
``foundation_kG L^2 / EI`` in 1e-1..1e1, an axial force of -0.5..+20 ``EI / L^2`` (a
compression the reference finds buckled is drawn again as a tension). Deterministic (a
fixed seed); the frequencies are stored with 20 significant digits.

    python tests/make_segments_reference.py --jobs 2
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

import make_kinds_reference as kinds  # noqa: E402
import reference_model  # noqa: E402

OUT = HERE / "data" / "segments_reference.json"
SEED = 20261126
MODES = 12
DPS = 25
DIGITS = 20
SCENES_PER_END_PAIR = 13  # 16 end pairs: 208 scenes


def terms(rng: np.random.Generator, ei: float, mbar: float, length: float) -> dict:
    """A segment's terms beyond Euler-Bernoulli, each present with probability 1/2."""
    out: dict = {}
    if rng.uniform() < 0.5:
        out["kappa_GA"] = kinds.log_uniform(rng, 1e1, 1e4) * ei / length**2
    if rng.uniform() < 0.5:
        out["rho_I"] = kinds.log_uniform(rng, 1e-5, 1e-2) * mbar * length**2
    if rng.uniform() < 0.5:
        out["axial_force"] = float(rng.uniform(-0.5, 20.0)) * ei / length**2
    if rng.uniform() < 0.5:
        out["foundation_k"] = kinds.log_uniform(rng, 1.0, 1e3) * ei / length**4
    if rng.uniform() < 0.5:
        out["foundation_kG"] = kinds.log_uniform(rng, 1e-1, 1e1) * ei / length**2
    return out


def draw_scene(rng: np.random.Generator, left: str, right: str) -> dict:
    """A scene of ``make_kinds_reference`` with one component of each kind (the first of
    each in its list) and the segment terms drawn here."""
    sc = kinds.draw_scene(rng, left, right)
    first: dict = {}
    for att in sc["attachments"]:
        first.setdefault(att["type"], att)
    sc["attachments"] = [first[k] for k in kinds.KINDS]
    beam = sc["beam"]
    length = sum(s["length"] for s in beam["segments"]) if "segments" in beam else beam["length"]
    for seg in beam.get("segments", [beam]):
        seg.update(terms(rng, seg["EI"], seg["mass_per_length"], length))
    sc["name"] = f"{left}_{right}"
    return sc


def scenes() -> list[dict]:
    """All scenes, from one seeded generator, in a fixed order."""
    rng = np.random.default_rng(SEED)
    out = []
    for _round in range(SCENES_PER_END_PAIR):
        for left in kinds.ENDS:
            for right in kinds.ENDS:
                sc = draw_scene(rng, left, right)
                sc["name"] = f"g{len(out):03d}_{sc['name']}"
                out.append(sc)
    return out


def _tensioned(scene: dict) -> dict:
    """The scene with every compression turned into the same tension."""
    beam = scene["beam"]
    for seg in beam.get("segments", [beam]):
        if seg.get("axial_force", 0.0) < 0.0:
            seg["axial_force"] = -seg["axial_force"]
    return scene


def reference(scene: dict) -> tuple[dict, float]:
    """The reference entry of one scene (lowest MODES frequencies as strings of DIGITS
    significant digits, rigid-body zeros as "0"; the rigid-body count) and its seconds."""
    start = time.perf_counter()
    try:
        omega = reference_model.frequencies(scene, MODES, dps=DPS)
    except ValueError as exc:  # buckled under its compression: draw it in tension
        if "buckled" not in str(exc):
            raise
        scene = _tensioned(scene)
        omega = reference_model.frequencies(scene, MODES, dps=DPS)
    rigid = reference_model.rigid_body_mode_count(scene)
    assert sum(1 for w in omega if w == 0) == rigid
    text = [
        "0" if w == 0 else reference_model.mpmath.nstr(w, DIGITS, strip_zeros=False) for w in omega
    ]
    return {"scene": scene, "omega": text, "rigid_body_modes": rigid}, time.perf_counter() - start


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenes", type=int, default=None, help="only the first N scenes")
    parser.add_argument("--jobs", type=int, default=1, help="worker processes (default 1)")
    parser.add_argument("--out", type=Path, default=OUT, help=f"output (default {OUT})")
    args = parser.parse_args(argv)
    todo = scenes()[: args.scenes] if args.scenes else scenes()
    start = time.perf_counter()
    with ProcessPoolExecutor(args.jobs) as pool:
        done = list(pool.map(reference, todo))
    entries = [e for e, _ in done]
    data = {"seed": SEED, "modes": MODES, "dps": DPS, "scenes": entries}
    text = json.dumps(data, indent=1) + "\n"
    if args.scenes:
        print(text[:2000])
    else:
        args.out.write_text(text)
    slowest = max(s for _, s in done)
    print(
        f"{len(entries)} scenes in {time.perf_counter() - start:.0f} s (slowest {slowest:.1f} s)",
        file=sys.stderr,
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

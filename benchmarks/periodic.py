"""Periodic structures (issue 23): the dispersion of a cell, its certified band edges
against the mpmath reference, and a finite beam's attenuation against Im k.

Run: ``python -m benchmarks.periodic [--record]`` (about a minute).

* **dispersion**: the cell of ``examples/metamaterial.toml`` (a spring-mass per cell),
  ``mstmm.bands(cell, points=10000, edges=False)`` warm, both cores, median of rounds;
  and the edges with their count over the default band;
* **edges**: the cells of ``tests/test_bands_reference.py`` (every kind, supports,
  chains, segment physics, random cells, and Timoshenko cells up to three times their
  cut-off, where two pairs propagate) against ``tests/reference_bloch.py`` (mpmath, its
  own count): the worst relative error of an edge, edges missed or spurious, and the
  proved meetings of two pairs (band ends inside the zone) where mpmath's two mu turn
  from real to a complex pair within 1e-9;
* **low frequencies**: the wavenumbers of the metamaterial's cell at omega = 1e-6 ..
  1e3 rad/s (a point a decade) against ``tests/reference_bloch.py`` (30 digits): the
  relative error of k at each, where both roots of the cell's quadratic crowd at mu = 2;
* **attenuation**: a free-free beam of 60 cells (``repeat = 60``, the cell of
  ``tests/test_bands.py``) driven at one end at a frequency in the gap (``mstmm.frf``):
  the decay per cell of the response against the cell's Im k L.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import numpy as np

from . import figures

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "examples" / "metamaterial.toml"


def _rounds(f, rounds: int = 7) -> float:
    f()
    times = []
    for _ in range(rounds):
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def dispersion() -> dict:
    from mstmm.bands import bands, cell_of

    cell = cell_of(EXAMPLE)
    n = 10_000
    seconds = _rounds(lambda: bands(cell, points=n, edges=False))
    b = bands(cell)
    return {
        "cell": cell.name,
        "frequencies": n,
        "seconds": seconds,
        "edges_seconds": _rounds(lambda: bands(cell, points=2), 3),
        "edges": len(b.edges),
        "gaps": [list(g) for g in b.gaps],
        "count_checked": bool(b.count_checked),
    }


def edges_against_reference() -> dict:
    sys.path.insert(0, str(ROOT / "tests"))
    import math

    import reference_bloch as ref
    from test_bands_reference import ABOVE, CASES, DPS, W_BRAGG

    import mstmm
    from mstmm.bands import bands

    worst, n_edges, missed, checked = 0.0, 0, 0, True
    meetings, confirmed = 0, 0
    for name, data in CASES + ABOVE:
        beam = data["beam"]
        cut = math.sqrt(beam["kappa_GA"] / beam["rho_I"]) if (name, data) in ABOVE else 0.0
        hi = 3.0 * cut if cut else 1.6 * W_BRAGG
        got = bands(mstmm.scene_from_dict({"name": name} | data), band=(0.0, hi), points=2)
        checked = checked and got.count_checked
        want = ref.band_edges(data, 0.0, hi, dps=DPS)
        mine = [e for e in got.edges if e.omega > 0.0 and e.kind != "coalescence"]
        missed += abs(len(mine) - len(want))
        for e, (w, kind, mult) in zip(mine, want):
            if e.kind != kind or e.multiplicity != mult:
                missed += 1
            worst = max(worst, abs(e.omega - float(w)) / float(w))
        n_edges += len(want)
        for e in got.edges:  # mpmath's two mu: real on one side, a complex pair on the other
            if e.kind == "coalescence" and e.certified:
                meetings += 1
                sides = [ref.bloch_mu(data, e.omega * (1.0 + h), dps=DPS) for h in (-1e-9, 1e-9)]
                pair = [abs(complex(m[0]).imag) > 0.0 for m in sides]
                confirmed += int(pair[0] != pair[1])
    return {
        "cells": len(CASES) + len(ABOVE),
        "above_cut_off": len(ABOVE),
        "edges": n_edges,
        "worst": worst,
        "missed_or_spurious": missed,
        "meetings": meetings,
        "meetings_confirmed": confirmed,
        "count_checked": checked,
    }


def attenuation() -> dict:
    sys.path.insert(0, str(ROOT / "tests"))
    from test_bands import W_BRAGG, cell, resonator

    import mstmm
    from mstmm.bands import bands

    # the cell of tests/test_bands.py: near its gap's lower edge both pairs decay with
    # real mu, far apart (deeper in, as in examples/metamaterial.toml's whole gap, they
    # meet, turn complex and equally attenuated, and the response beats)
    one = cell(resonator(0.35, 0.1, 0.3 * W_BRAGG))
    lo, hi = bands(one, band=(0.15 * W_BRAGG, 0.6 * W_BRAGG), points=2).gaps[0]
    w = lo + 0.09 * (hi - lo)
    slow = float(np.min(bands(one, omegas=[w], edges=False).attenuation))
    n = 60
    d = mstmm.scene.scene_to_dict(one)
    d["repeat"] = n
    big = mstmm.scene_from_dict(d)
    L = one.beam.length
    js = np.arange(10, 26)
    H = mstmm.frf(big, "force:x=0", [f"displacement:x={float(j * L)!r}" for j in js], [w])[0, 0]
    decay = -np.log(np.abs(H[1:]) / np.abs(H[:-1]))
    return {
        "cells": n,
        "omega": w,
        "im_k_L": slow,
        "error": float(np.max(np.abs(decay / slow - 1.0))),
    }


def low_frequencies() -> dict:
    sys.path.insert(0, str(ROOT / "tests"))
    import reference_bloch as ref

    import mstmm
    from mstmm.bands import bands, cell_of

    cell = cell_of(mstmm.load_scene(EXAMPLE))
    ws = np.logspace(-6, 3, 10)
    k = bands(cell, omegas=ws, edges=False).k
    errors = []
    for i, w in enumerate(ws):
        want = sorted((complex(z) for z in ref.bloch_k(cell, float(w), dps=30)), key=abs)
        got = sorted(k[i], key=lambda z: min(abs(z - x) for x in want[:1]))
        errors.append(max(abs(g - x) / abs(x) for g, x in zip(got, want)))
    return {"omega": ws.tolist(), "error": [float(e) for e in errors]}


def measure() -> dict:
    return {
        "dispersion": dispersion(),
        "edges": edges_against_reference(),
        "low_frequencies": low_frequencies(),
        "attenuation": attenuation(),
    }


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--record", action="store_true", help="write docs/figures.json")
    args = ap.parse_args(argv)
    fig = measure()
    d, e, a = fig["dispersion"], fig["edges"], fig["attenuation"]
    lf = fig["low_frequencies"]
    print(
        f"dispersion of {d['cell']} at {d['frequencies']} frequencies:"
        f" {d['seconds'] * 1e3:.2f} ms warm; edges of the default band"
        f" {d['edges_seconds'] * 1e3:.2f} ms ({d['edges']} edges, count {d['count_checked']})"
    )
    print(
        f"edges of {e['cells']} cells against mpmath: {e['edges']} edges, worst"
        f" {e['worst']:.1e}, {e['missed_or_spurious']} missed or spurious,"
        f" count {e['count_checked']}"
    )
    print(
        "wavenumbers of the metamaterial's cell against mpmath, relative error: "
        + ", ".join(f"{e:.1e} at {w:.0e}" for w, e in zip(lf["omega"], lf["error"]))
        + " rad/s"
    )
    print(
        f"finite beam of {a['cells']} cells in the gap: decay per cell within"
        f" {a['error']:.1e} of Im k L = {a['im_k_L']:.4f}"
    )
    if args.record:
        path = figures.record("periodic", fig, command="python -m benchmarks.periodic --record")
        print(f"recorded in {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

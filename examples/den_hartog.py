"""A tuned mass damper by Den Hartog's rule, checked by its frequency response.

    python examples/den_hartog.py [--mu 0.02] [-o den_hartog.png]

The simply supported beam of ``examples/tmd_den_hartog.toml`` (without its damper) has
its first mode at ``w1`` with modal mass ``M1`` (here ``mbar L / 2``, the mode scaled to 1
at mid-span, where the damper sits). For a mass ratio ``mu = m / M1`` Den Hartog's optimum
absorber has frequency ratio ``1 / (1 + mu)`` and damping ratio
``sqrt(3 mu / (8 (1 + mu)^3))``. The script designs it from the beam (w1 and M1 from
``mstmm.solve`` and its mode shape, not typed), solves the damped natural frequencies,
and computes the receptance at mid-span before and after. The classic result, checked
here: the two resonance peaks of the tuned beam are nearly equal in height and far below
the bare beam's (whose peak only its small loss factor bounds).
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np

import mstmm
from mstmm.response import frf
from mstmm.scene import scene_to_dict

HERE = Path(__file__).resolve().parent
SCENE = HERE / "tmd_den_hartog.toml"


def design(mu: float, scene: mstmm.Scene | None = None) -> dict:
    """Den Hartog's absorber for the first mode of the bare beam, at mid-span."""
    scene = scene or mstmm.load_scene(SCENE)
    bare = scene.replace(attachments=())
    undamped = bare.replace(beam=dict(scene_to_dict(bare)["beam"], loss_factor=0.0))
    sol = mstmm.solve(undamped, modes=1)
    w1 = float(sol.omega[0])
    shape = sol.shapes[0]
    x_mid = 0.5 * undamped.beam.length
    y_mid = float(np.interp(x_mid, shape.x, shape.Y))
    M1 = shape.modal_mass / y_mid**2  # the modal mass of the mode scaled to 1 at mid-span
    m = mu * M1
    wa = w1 / (1.0 + mu)
    zeta = math.sqrt(3.0 * mu / (8.0 * (1.0 + mu) ** 3))
    damper = {"type": "spring_mass", "x": x_mid, "m": m, "k": m * wa**2, "c": 2 * zeta * m * wa}
    tuned = scene.replace(attachments=[damper])
    return {"bare": bare, "tuned": tuned, "w1": w1, "M1": M1, "zeta": zeta, "damper": damper}


def peaks(scene: mstmm.Scene, lo: float, hi: float, x: float, n: int = 4001) -> list:
    """The local maxima of |H| (mid-span receptance) in [lo, hi] rad/s, each refined by a
    golden-section search: (omega, |H|) pairs."""
    where = f"force:x={x!r}", f"displacement:x={x!r}"
    w = np.linspace(lo, hi, n)
    h = np.abs(frf(scene, *where, w))
    out = []
    for i in np.flatnonzero((h[1:-1] > h[:-2]) & (h[1:-1] >= h[2:])) + 1:
        a, b = w[i - 1], w[i + 1]
        g = (math.sqrt(5.0) - 1.0) / 2.0
        for _ in range(60):
            c, d = b - g * (b - a), a + g * (b - a)
            hc, hd = np.abs(frf(scene, *where, np.array([c, d])))
            a, b = (a, d) if hc > hd else (c, b)
        wm = 0.5 * (a + b)
        out.append((wm, float(np.abs(frf(scene, *where, np.array([wm])))[0])))
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mu", type=float, default=0.02, help="mass ratio (default: %(default)s)")
    ap.add_argument("-o", "--out", type=Path, help="write the before/after plot here")
    args = ap.parse_args(argv)
    d = design(args.mu)
    w1, x = d["w1"], d["damper"]["x"]
    print(f"bare beam: w1 = {w1:.6g} rad/s, modal mass at mid-span M1 = {d['M1']:.6g} kg")
    print(
        f"damper: m = {d['damper']['m']:.6g} kg, k = {d['damper']['k']:.6g} N/m,"
        f" c = {d['damper']['c']:.6g} N s/m (zeta = {d['zeta']:.4g})"
    )
    roots = mstmm.solve(d["tuned"], modes=3, shapes=False)
    for w, z in zip(roots.omega, roots.zeta):
        print(f"  damped root {w.real:.6g} + {w.imag:.6g} i rad/s, zeta = {z:.4g}")
    lo, hi = 0.6 * w1, 1.4 * w1
    before = peaks(d["bare"], lo, hi, x)
    after = peaks(d["tuned"], lo, hi, x)
    top = max(h for _, h in before)
    p1, p2 = (h for _, h in after[:2])
    print(
        f"mid-span receptance peaks: bare {top:.4g} m/N; tuned {p1:.4g} and {p2:.4g} m/N"
        f" (ratio {p1 / p2:.4f}; {top / max(p1, p2):.1f}x lower)"
    )
    if args.out:
        from matplotlib.figure import Figure

        from mstmm.plot import frf_figure, save

        fig = Figure(figsize=(8.0, 6.0), layout="constrained")
        axes = fig.subplots(2, 1, sharex=True)
        w = np.linspace(lo, hi, 3000)
        for scene, label in ((d["bare"], "bare beam"), (d["tuned"], f"with TMD, mu = {args.mu}")):
            frf_figure(scene, f"force:x={x!r}", [f"displacement:x={x!r}"], w, ax=axes, label=label)
        save(fig, args.out)
        print(args.out)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

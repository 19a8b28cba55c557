"""The structure and its mode shapes: ``mode_shapes(sol, path)``.

One panel per mode, on equal axes (a tall frame stays tall): the undeformed members in
grey, each mode's deformed members drawn from their own fields (``u, w`` marched along
each member, turned to X, Y) scaled so that the largest displacement is a tenth of the
structure's size, supports and node masses marked, the title the frequency and the
multiplicity. A damped mode (complex, :mod:`.damped`) is drawn at the instant its largest
joint translation peaks (its real part: the mode is scaled so that translation is real),
its title the damped frequency and the damping ratio. Needs matplotlib (``mstmm[plot]``).
"""

from __future__ import annotations

import math
from os import PathLike

import numpy as np

from mstmm.plot import _figure, _finish

from .solve import FrameSolution

__all__ = ["mode_shapes"]

#: Points drawn along each member.
POINTS = 21
#: The largest displacement drawn, as a fraction of the structure's size.
AMPLITUDE = 0.1
#: Support markers: held freedoms -> (marker, size).
SUPPORT_MARKERS = {"xyt": ("s", 8), "xy": ("^", 9), "n": ("o", 7), "nt": ("D", 7)}


def _extent(sol: FrameSolution) -> tuple[float, float, float, float]:
    xs = [n.x for n in sol.frame.nodes.values()]
    ys = [n.y for n in sol.frame.nodes.values()]
    return min(xs), max(xs), min(ys), max(ys)


def _curves(
    sol: FrameSolution, j: int
) -> list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]:
    """Per member: the undeformed X, Y and the displacement along X, Y in mode j."""
    out = []
    for mm in sol.assembly.members:
        L, c, s = sol.frame.geometry(mm.member)
        a = sol.frame.nodes[mm.member.start]
        f = sol.member_fields(j, mm.member.name, POINTS)
        x = f["x"]
        X, Y = a.x + c * x, a.y + s * x
        u, w = np.real(f["u"]), np.real(f["w"])  # a damped mode: at its peak's instant
        out.append((X, Y, c * u - s * w, s * u + c * w))
    return out


def mode_shapes(
    sol: FrameSolution, path: str | PathLike | None = None, modes: int | None = None
) -> object:
    """A figure of the lowest ``modes`` mode shapes (default: all of ``sol``'s, at most 6),
    saved to ``path`` when given; returns the matplotlib figure."""
    if sol.frame.motion == "out_of_plane":
        raise ValueError("plots of a grillage's modes (out of the plane) are not built yet")
    count = min(len(sol.modes), modes if modes is not None else 6)
    if count == 0:
        raise ValueError("no mode shapes to draw: solve with shapes=True")
    x0, x1, y0, y1 = _extent(sol)
    size = max(x1 - x0, y1 - y0)
    columns = min(count, 3)
    rows = math.ceil(count / columns)
    aspect = min(3.0, max(0.4, (y1 - y0 + 0.3 * size) / (x1 - x0 + 0.3 * size)))
    fig = _figure((3.6 * columns, 3.6 * aspect * rows + 0.4))
    axes = np.atleast_1d(fig.subplots(rows, columns)).ravel()
    for j, ax in enumerate(axes):
        ax.set_axis_off()
        if j >= count:
            continue
        curves = _curves(sol, j)
        biggest = max(float(np.max(np.hypot(dx, dy))) for _, _, dx, dy in curves)
        scale = AMPLITUDE * size / biggest if biggest > 0 else 0.0
        for X, Y, dx, dy in curves:
            ax.plot(X, Y, color="0.75", lw=1.0)
            ax.plot(X + scale * dx, Y + scale * dy, color="C0", lw=1.6)
        for node in sol.frame.nodes.values():
            if node.held in SUPPORT_MARKERS:
                marker, ms = SUPPORT_MARKERS[node.held]
                ax.plot(node.x, node.y, marker, color="k", ms=ms)
            if node.mass:
                ax.plot(node.x, node.y, "o", color="C3", ms=6)
        mult = int(sol.multiplicity[j])
        title = f"mode {j + 1}: {sol.f[j]:.5g} Hz"
        if getattr(sol, "damped", False):
            title += f", zeta {sol.zeta[j]:.3g}"
        ax.set_title(title + (f" (x{mult})" if mult > 1 else ""), fontsize=9)
        ax.set_aspect("equal")
        pad = 0.15 * size
        ax.set_xlim(x0 - pad, x1 + pad)
        ax.set_ylim(y0 - pad, y1 + pad)
    fig.suptitle(f"{sol.frame.name}: mode shapes (grey: at rest)", fontsize=10)
    return _finish(fig, path)

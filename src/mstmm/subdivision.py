"""Every zero a rectangle's count says it holds (step 4 of the damped search,
:mod:`mstmm.damped`): the rectangle counted by the argument principle
(:func:`count_box`), the zeros it holds beyond those known searched by the secant method
from a few points in it, else the rectangle split in four and each quarter whose count
exceeds its known zeros searched again (:func:`fill`).

``problem`` is the search's state (:class:`mstmm.damped._Problem`): ``f`` (log f,
:class:`mstmm.contour.LogF`), ``unit`` (the frequency unit, rad/s), ``nodes`` (the
undamped roots), ``roots`` and ``notes`` (what it found and what to tell),
``known(box)``, ``inside(w, box)`` and ``add(w, multiplicity, how, converged)``.
"""

from __future__ import annotations

import numpy as np

from .contour import OnContour, winding
from .secant import newton

__all__ = ["count_box", "fill"]


def fill(problem, box, count: int, depth: int = 0) -> None:
    """Find the roots the count says are in ``box`` but not yet known: the secant method
    from a few points of the box (on f, then on f^(1/m) for m the zeros left: a multiple
    root), each root's multiplicity from a small count around it; else split the box in
    four and search each quarter whose count exceeds its known roots. A box as small as
    round-off allows with m zeros left is a root of multiplicity m (``how = "count"``)."""
    f = problem.f
    left = count - problem.known(box)
    if left <= 0:
        return
    x0, x1, y0, y1 = box
    centre = complex(0.5 * (x0 + x1), 0.5 * (y0 + y1))
    size = max(x1 - x0, y1 - y0)
    if size <= 1e-12 * max(abs(centre), problem.unit * 1e-6) or depth > 60:
        problem.add(centre, left, "count", converged=depth <= 60)
        return
    if left == 1 or depth > 4:
        dx, dy = 0.25 * (x1 - x0), 0.25 * (y1 - y0)
        starts = (centre, centre - dx - dy, centre + dx + dy, centre - dx + dy)
        for start in starts:
            for m in dict.fromkeys((1, left)):
                w, ok = newton(f, start, multiplicity=m, scale=problem.unit)
                if ok and problem.inside(w, box):
                    problem.add(w, 0, "search")  # its multiplicity from a circle round it
            if problem.known(box) >= count:
                return
    # split in four (lines a little off the middle: not through a symmetric root)
    xm = x0 + 0.5123 * (x1 - x0)
    ym = y0 + 0.4877 * (y1 - y0)
    for q in ((x0, xm, y0, ym), (xm, x1, y0, ym), (x0, xm, ym, y1), (xm, x1, ym, y1)):
        n = count_box(problem, q)
        if n is not None:
            fill(problem, q, n, depth + 1)


def count_box(problem, box) -> int | None:
    """``winding`` on ``box``, its edges nudged when a zero sits on one; the bottom edge
    sampled between every two undamped roots and every two roots found."""
    x0, x1, y0, y1 = box
    known = np.sort(
        np.concatenate([problem.nodes, [r.omega.real for r in problem.roots if r.omega != 0]])
    )
    between = 0.5 * (known[1:] + known[:-1]) if known.size > 1 else known
    bottom = np.concatenate([known, between])
    for k in range(6):
        try:
            return winding(problem.f, (x0, x1, y0, y1), bottom=bottom)
        except OnContour:
            d = 1e-3 * (k + 1) * max(x1 - x0, y1 - y0)
            x0, x1, y0, y1 = x0 - 0.7 * d, x1 + 0.3 * d, y0 - 0.5 * d, y1 + 0.9 * d
    problem.notes.append(
        "the argument principle could not be evaluated on the rectangle w_d in"
        f" [{float(box[0]):.6g}, {float(box[1]):.6g}], sigma in [{float(box[2]):.6g},"
        f" {float(box[3]):.6g}] rad/s"
    )
    return None

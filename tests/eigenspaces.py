"""Mode shapes against the reference model's null space: the comparison the tests share.

Shapes are compared as subspaces: rows [Y at sample points, Y of every hanging mass],
the sine of the largest principal angle between our span and the span of the
reference's null vectors (``reference_model.eigenspace``) at the exact root.
"""

from __future__ import annotations

import numpy as np
import reference_model as ref


def sin_angle(ours, theirs) -> float:
    """Sine of the largest principal angle between the spans of two sets of row vectors."""
    qa, _ = np.linalg.qr(np.asarray(ours, dtype=float).T)
    qb, _ = np.linalg.qr(np.asarray(theirs, dtype=float).T)
    return float(np.linalg.norm(qa - qb @ (qb.T @ qa), 2))


def vectors(shapes, every: int = 5):
    """Rows [Y at every ``every``-th sample point and at the attachments, Y of each mass]."""
    x = shapes[0].x
    keep = np.unique(np.concatenate([np.arange(0, len(x), every), [len(x) - 1]]))
    keep = np.union1d(keep, np.searchsorted(x, shapes[0].mass_x))
    return x[keep], [np.concatenate([s.Y[keep], s.mass_Y]) for s in shapes]


def groups(sol):
    """Index ranges of the shapes that share one eigenspace."""
    out, i = [], 0
    while i < len(sol.shapes):
        m = sol.shapes[i].multiplicity
        out.append((i, i + m))
        i += m
    return out


def check_against_reference(sc, sol, tol, exact=None):
    """Every eigenspace of ``sol`` against the reference null space at the exact root."""
    exact = exact or ref.frequencies(sc, len(sol.omega), dps=30)
    worst = 0.0
    for a, b in groups(sol):
        xs, ours = vectors(sol.shapes[a:b])
        centre = sum(exact[a:b]) / (b - a)
        theirs = ref.eigenspace(sc, centre, b - a, xs, dps=30)
        worst = max(worst, sin_angle(ours, theirs))
    assert worst <= tol, worst
    for s in sol.shapes:
        for arr in (s.Y, s.theta, s.M, s.Q, s.mass_Y):
            assert np.all(np.isfinite(arr))
    return worst


def check_shapes(sc, sol) -> None:
    """What every default solve must give, without a reference: one finite shape per
    frequency, eigenspaces of the sizes the multiplicities say, and each hanging mass
    obeying its equation of motion (k - m w^2) Y_m = k Y_beam at its point."""
    assert sol.shapes is not None and len(sol.shapes) == len(sol.omega)
    for a, b in groups(sol):
        assert all(s.multiplicity == b - a for s in sol.shapes[a:b])
    for s, w in zip(sol.shapes, sol.omega, strict=True):
        assert s.omega == w
        for arr in (s.Y, s.theta, s.M, s.Q, s.mass_Y):
            assert np.all(np.isfinite(arr))
        assert max(np.max(np.abs(s.Y)), np.max(np.abs(s.mass_Y), initial=0.0)) == 1.0
        idx = np.searchsorted(s.x, s.mass_x)
        for att, yb, ym in zip(sc.attachments, s.Y[idx], s.mass_Y, strict=True):
            residual = (att.k - att.m * w**2) * ym - att.k * yb
            assert abs(residual) <= 1e-7 * (att.k + att.m * w**2), (w, residual)

"""A zero of an analytic function polished by the secant method on log f (one start,
:func:`newton`; many at once, :func:`newton_many`)."""

from __future__ import annotations

import cmath
import math

import numpy as np

from .contour import LogF, wrap

__all__ = ["NEWTON_TOL", "newton", "newton_many"]

#: Newton stops at a step this small relative to |w| (or to the frequency unit near 0).
NEWTON_TOL = 4e-16


def newton(
    f: LogF,
    w: complex,
    multiplicity: int = 1,
    scale: float = 1.0,
    maxiter: int = 80,
    tol: float = NEWTON_TOL,
) -> tuple[complex, bool]:
    """The secant method on ``f^(1/m)`` from w (and a point 1e-7 beside it): each step
    ``w2 = w1 - (w1 - w0) / (1 - (f0 / f1)^(1/m))`` with ``f0 / f1 = exp(log f0 - log f1)``,
    so the scale of f never matters; superlinear for a simple root and needs no
    derivative (a difference across the root of the singular log f would be garbage).
    Converged when the step falls below ``tol`` relative (``NEWTON_TOL``: to round-off),
    or stops shrinking below 1e-11 relative (round-off of f). Returns (root, converged)."""
    mag = max(abs(w), 1e-3 * scale)
    w0 = w + 1e-7 * mag
    g0 = f.one(w0)
    w1, g1 = complex(w), f.one(w)
    prev = math.inf
    for _ in range(maxiter):
        if math.isnan(g1.real) or math.isnan(g0.real):
            return w1, False  # f has no value there (overflow): no root found
        if not math.isfinite(g1.real):
            return w1, True  # f = 0 exactly
        if not math.isfinite(g0.real):
            return w0, True
        dg = complex(g0.real - g1.real, float(wrap(g0.imag - g1.imag))) / multiplicity
        if dg.real > 700.0:
            return w1, False
        denom = 1.0 - cmath.exp(dg)
        if denom == 0:
            return w1, False
        step = -(w1 - w0) / denom
        if not cmath.isfinite(step):
            return w1, False
        mag = max(abs(w1), 1e-3 * scale)
        size = abs(step)
        if size <= tol * mag:
            return w1 + step, True
        if size <= 1e-11 * mag and size >= 0.5 * prev:
            return w1, True
        w0, g0 = w1, g1
        w1 = w1 + step
        g1 = f.one(w1)
        prev = size
    return w1, prev <= 1e-10 * max(abs(w1), 1e-3 * scale)


def newton_many(
    f: LogF, ws: np.ndarray, scale: float = 1.0, maxiter: int = 80, tol: float = NEWTON_TOL
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`newton` (multiplicity 1) from every start in ``ws`` at once: each step
    evaluates f at all the starts still moving in one call (on every core for a large
    scene). Returns (roots, converged), arrays."""
    w1 = np.array(ws, dtype=np.complex128).ravel()
    n = w1.size
    w0 = w1 + 1e-7 * np.maximum(np.abs(w1), 1e-3 * scale)
    g = f(np.concatenate([w0, w1])) if n else np.zeros(0, dtype=np.complex128)
    g0, g1 = g[:n], g[n:]
    out = w1.copy()
    ok = np.zeros(n, dtype=bool)
    done = np.zeros(n, dtype=bool)
    prev = np.full(n, math.inf)
    for _ in range(maxiter):
        void = ~done & (np.isnan(g1.real) | np.isnan(g0.real))  # no value: no root found
        out[void] = w1[void]
        done |= void
        exact1 = ~done & (g1.real == -math.inf)  # f = 0 exactly
        exact0 = ~done & ~exact1 & (g0.real == -math.inf)
        out[exact1], out[exact0] = w1[exact1], w0[exact0]
        ok |= exact1 | exact0
        done |= exact1 | exact0
        live = np.flatnonzero(~done)
        if live.size == 0:
            break
        dg = g0[live].real - g1[live].real + 1j * wrap(g0[live].imag - g1[live].imag)
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            denom = 1.0 - np.exp(np.minimum(dg.real, 700.0) + 1j * dg.imag)
            step = -(w1[live] - w0[live]) / denom
        mag = np.maximum(np.abs(w1[live]), 1e-3 * scale)
        size = np.abs(step)
        bad = (dg.real > 700.0) | (denom == 0) | ~np.isfinite(step)
        conv = ~bad & (size <= tol * mag)
        stall = ~bad & ~conv & (size <= 1e-11 * mag) & (size >= 0.5 * prev[live])
        out[live[bad]] = w1[live[bad]]
        out[live[conv]] = w1[live[conv]] + step[conv]
        out[live[stall]] = w1[live[stall]]
        ok[live[conv | stall]] = True
        done[live[bad | conv | stall]] = True
        go = ~(bad | conv | stall)
        move = live[go]
        w0[move], g0[move] = w1[move], g1[move]
        w1[move] = w1[move] + step[go]
        prev[move] = size[go]
        if move.size:
            g1[move] = f(w1[move])
    left = ~done
    out[left] = w1[left]
    ok[left] = prev[left] <= 1e-10 * np.maximum(np.abs(w1[left]), 1e-3 * scale)
    return out, ok

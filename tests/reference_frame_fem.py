"""Independent finite-element model of plane frames (numpy and scipy only, never mstmm).

A check on ``tests/reference_frame.py`` (exact dynamic stiffness) by another method: each
member of a :class:`reference_frame.Frame` is cut into ``n`` equal elements with the
textbook matrices in its own axes, a linear rod (``EA / h [[1, -1], [-1, 1]]``, consistent
mass ``mbar h / 6 [[2, 1], [1, 2]]``) and a cubic Hermite beam (``EI / h^3`` with 12, 6h,
4h^2, 2h^2; consistent mass ``mbar h / 420`` with 156, 22h, 54, 13h, 4h^2, 3h^2), turned to
the global axes (X, Y, Theta per node) and assembled. Supports drop the freedoms they hold,
node masses go on the diagonal, and a pinned member end gets a rotation of its own, as in
the exact model. The frequencies are the square roots of the lowest eigenvalues of
``K x = w^2 M x`` (``scipy.linalg.eigh``); they converge from above, as ``h^2`` where the
rod's linear elements matter and ``h^4`` where only bending does.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.linalg


def _element(EI: float, EA: float, mbar: float, h: float, c: float, s: float):
    """An element's stiffness and mass (6 x 6, global axes) over (X, Y, Theta) at each end."""
    k = np.zeros((6, 6))
    m = np.zeros((6, 6))
    axial = [0, 3]
    bend = [1, 2, 4, 5]
    k[np.ix_(axial, axial)] = EA / h * np.array([[1.0, -1.0], [-1.0, 1.0]])
    m[np.ix_(axial, axial)] = mbar * h / 6.0 * np.array([[2.0, 1.0], [1.0, 2.0]])
    k[np.ix_(bend, bend)] = (
        EI
        / h**3
        * np.array(
            [
                [12.0, 6 * h, -12.0, 6 * h],
                [6 * h, 4 * h * h, -6 * h, 2 * h * h],
                [-12.0, -6 * h, 12.0, -6 * h],
                [6 * h, 2 * h * h, -6 * h, 4 * h * h],
            ]
        )
    )
    m[np.ix_(bend, bend)] = (
        mbar
        * h
        / 420.0
        * np.array(
            [
                [156.0, 22 * h, 54.0, -13 * h],
                [22 * h, 4 * h * h, 13 * h, -3 * h * h],
                [54.0, 13 * h, 156.0, -22 * h],
                [-13 * h, -3 * h * h, -22 * h, 4 * h * h],
            ]
        )
    )
    r = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])  # local = r @ global
    T = np.zeros((6, 6))
    T[:3, :3] = r
    T[3:, 3:] = r
    return T.T @ k @ T, T.T @ m @ T


def assemble(frame, n_elements: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(K, C, M)`` over the free freedoms with ``n_elements`` elements per member (K
    complex: a member's loss factor eta makes its elements' ``K (1 + i eta)``); each
    absorber of the frame (``(node, k, m, c, (dx, dy))``) adds its mass's freedom, its
    spring and its dashpot."""
    index: dict = {}

    def dof(key) -> int:
        if key not in index:
            index[key] = len(index)
        return index[key]

    elements = []
    for i, mem in enumerate(frame.members):
        (xa, ya), (xb, yb) = frame.nodes[mem.a], frame.nodes[mem.b]
        dx, dy = float(xb) - float(xa), float(yb) - float(ya)
        length = math.hypot(dx, dy)
        c, s = dx / length, dy / length
        k, m = _element(float(mem.EI), float(mem.EA), float(mem.mbar), length / n_elements, c, s)
        k = k * (1.0 + 1j * getattr(mem, "eta", 0.0))  # a loss factor: K (1 + i eta)
        for e in range(n_elements):
            ends = []
            for j, at in ((0, e), (1, e + 1)):
                if at == 0 or at == n_elements:
                    node = mem.a if at == 0 else mem.b
                    keys = [(node, 0), (node, 1)]
                    pinned = mem.pinned[0 if at == 0 else 1]
                    keys.append((i, "pin", j) if pinned else (node, 2))
                else:
                    keys = [(i, at, 0), (i, at, 1), (i, at, 2)]
                ends += keys
            elements.append((k, m, [dof(key) for key in ends]))
    held = {(name, "xyt".index(d)) for name, ds in frame.held.items() for d in ds}
    absorbers = getattr(frame, "absorbers", ())
    for j in range(len(absorbers)):
        dof(("absorber", j))
    n = len(index)
    K = np.zeros((n, n), dtype=complex)
    C = np.zeros((n, n))
    M = np.zeros((n, n))
    for k, m, dofs in elements:
        K[np.ix_(dofs, dofs)] += k
        M[np.ix_(dofs, dofs)] += m
    for name, (mass, inertia) in frame.masses.items():
        for j, value in ((0, mass), (1, mass), (2, inertia)):
            if (name, j) in index:
                M[index[(name, j)], index[(name, j)]] += float(value)
    for j, (node, k, mass, c, (dx, dy)) in enumerate(absorbers):
        q = index[("absorber", j)]
        row = np.zeros(n)
        row[q] = 1.0
        row[index[(node, 0)]] -= float(dx)
        row[index[(node, 1)]] -= float(dy)
        K += float(k) * np.outer(row, row)
        C += float(c) * np.outer(row, row)
        M[q, q] += float(mass)
    free = [g for key, g in index.items() if key not in held]
    keep = np.ix_(free, free)
    return K[keep], C[keep], M[keep]


def frequencies(frame, n_modes: int, n_elements: int) -> np.ndarray:
    """The lowest ``n_modes`` natural frequencies (rad/s) with ``n_elements`` elements per
    member (undamped)."""
    K, _, M = assemble(frame, n_elements)
    K = K.real
    lam = scipy.linalg.eigh(K, M, eigvals_only=True, subset_by_index=[0, n_modes - 1])
    return np.sqrt(lam)


def damped_roots(frame, n_elements: int) -> np.ndarray:
    """Every damped root ``w = w_d + i sigma`` (rad/s, time dependence exp(i w t)) with
    ``w_d >= 0``: ``(K + i w C - w^2 M) x = 0`` as the linear pencil of ``lambda = i w``
    over ``[x, lambda x]`` (``scipy.linalg.eig``), sorted by w_d."""
    K, C, M = assemble(frame, n_elements)
    n = K.shape[0]
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-K, -C]])
    B = np.block([[np.eye(n), np.zeros((n, n))], [np.zeros((n, n)), M]])
    lam = scipy.linalg.eigvals(A, B)
    w = -1j * lam[np.isfinite(lam)]
    w = w[w.real >= -1e-9 * np.abs(w)]
    return w[np.argsort(w.real)]

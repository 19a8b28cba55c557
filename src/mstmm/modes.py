"""Mode shapes: the null vector of paper Eq. (5), found by a stabilised march along the beam.

The paper takes the right singular vector of ``U_bar(omega_n)`` for the smallest
singular value (Eq. (5)). Built from whole-segment transfer matrices, ``U_bar``
carries ``cosh(lam l)``: its null vector, and the state carried from ``Z_1``
along the beam, lose a digit per ``pi`` of ``lam L`` (garbage beyond the 12th
cantilever mode). Here the same null vector is found without that growth
(orthonormalisation march, Godunov/Conte):

1. the two-dimensional space of states allowed by the left end,
   ``W_0 = [e_i, e_j]`` (its unknowns), is carried node to node through pieces
   with ``lam l <= 1``, in units ``L = EI = 1``, and re-orthonormalised (QR,
   ``U W_k = W_{k+1} R_{k+1}``) after every piece and every attachment (the
   spring-mass enters pole-free: ``B00 I + B10 e_Q e_Y^T``, paper Eqs. (2)-(3));
2. at ``x = L`` the right end's conditions give a 2x2 matrix, singular at a
   natural frequency; its null vector (SVD, Eq. (5)) is ``c_K``;
3. back along the beam ``c_k = R_{k+1}^{-1} c_{k+1}`` (times ``B00`` across a branch,
   whose pole-free matrix is ``B00`` times the true jump) and the state at node k is
   ``W_k c_k``; the hanging mass moves by ``Y_m = Y / B00``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .kernels import Kernel
from .topology import KNOWN_ZERO, unknown

#: Longest piece (in lam*l) carried in one step of the march.
MARCH_STEP = 1.0


@dataclass(frozen=True)
class ModeShape:
    """Transverse displacement of the beam and of each hanging mass, max |Y| = 1."""

    omega: float
    x: np.ndarray
    Y: np.ndarray
    mass_x: np.ndarray
    mass_Y: np.ndarray
    #: smallest over largest singular value of the end's 2x2 matrix: how singular at omega
    singular_ratio: float


def _nodes(L: float, lam: float, xs: np.ndarray, sample: np.ndarray) -> np.ndarray:
    """Sample points, attachment points and enough points that every piece has lam*l <= 1."""
    base = np.unique(np.concatenate([[0.0, L], xs, sample]))
    pieces = [base[:1]]
    for a, b in zip(base[:-1], base[1:]):
        n = max(1, int(np.ceil(lam * (b - a) / MARCH_STEP)))
        pieces.append(np.linspace(a, b, n + 1)[1:])
    return np.concatenate(pieces)


def mode_shape(kernel: Kernel, p: np.ndarray, omega: float, n_points: int = 201) -> ModeShape:
    """The mode shape of the natural frequency ``omega`` (rad/s)."""
    p = np.ascontiguousarray(p, dtype=np.float64)
    L, EI, mbar = p[0], p[1], p[2]
    rec = p[3:].reshape(-1, 3) if kernel.topology.kinds else np.empty((0, 3))
    lam = (mbar * omega**2 / EI) ** 0.25
    D = np.array([1.0 / L, 1.0, L / EI, L**2 / EI])  # units L = EI = 1
    sample = np.linspace(0.0, L, n_points)
    nodes = _nodes(L, lam, rec[:, 0], sample)
    W = np.zeros((4, 2))
    W[list(unknown(kernel.topology.left)), [0, 1]] = 1.0
    frames = [W]  # W_k at every node (after its attachments)
    Rs = []  # R factors, one per step (pieces and attachments)
    scales = []  # factor each step's matrix carries beyond the true transfer (B00 at a branch)
    steps_at = []  # index of the node each step arrives at
    j = 0
    for k, x in enumerate(nodes):
        if k > 0:
            U = kernel.beam_transfer(lam, x - nodes[k - 1], EI) * D[:, None] / D[None, :]
            W, R = np.linalg.qr(U @ W)
            Rs.append(R)
            scales.append(1.0)
            steps_at.append(k)
        while j < len(rec) and rec[j, 0] <= x:
            B00 = 1.0 - rec[j, 2] * omega**2 / rec[j, 1]
            B10 = rec[j, 2] * omega**2 * L**3 / EI  # nondimensional shear per unit Y
            P = B00 * np.eye(4)
            P[3, 0] += B10
            W, R = np.linalg.qr(P @ W)
            Rs.append(R)
            scales.append(B00)  # P = B00 x (the condensed jump): pole-free
            steps_at.append(k)
            j += 1
        frames.append(W) if k > 0 else frames.__setitem__(0, W)
    end = W[list(KNOWN_ZERO[kernel.topology.right]), :]
    _u, sv, vt = np.linalg.svd(end)
    ratio = float(sv[-1] / sv[0]) if sv[0] > 0 else 0.0
    c = vt[-1]
    states = np.empty((len(nodes), 4))
    states[-1] = W @ c
    s = len(Rs) - 1
    for k in range(len(nodes) - 1, 0, -1):
        # undo the steps arriving at node k (attachments, then the piece), back to node k-1
        while s >= 0 and steps_at[s] == k:
            c = scales[s] * np.linalg.solve(Rs[s], c)
            s -= 1
        states[k - 1] = frames[k - 1] @ c
        # attachments at node k-1 were applied after its frame: their R's come first below
        while s >= 0 and steps_at[s] == k - 1:
            c = scales[s] * np.linalg.solve(Rs[s], c)
            s -= 1
    return _shape(omega, L, nodes, states, rec, sample, ratio)


def _shape(omega, L, nodes, states, rec, sample, ratio) -> ModeShape:
    Y_nodes = states[:, 0] * L
    Y = np.interp(sample, nodes, Y_nodes)  # sample points are nodes: exact values
    idx = np.searchsorted(nodes, rec[:, 0])
    B00 = 1.0 - rec[:, 2] * omega**2 / rec[:, 1]
    mass_Y = Y_nodes[idx] / B00 if len(rec) else np.empty(0)
    scale = max(np.max(np.abs(Y)), np.max(np.abs(mass_Y)) if len(rec) else 0.0)
    if scale > 0:
        both = np.concatenate([Y, mass_Y])
        sign = np.sign(both[np.argmax(np.abs(both))]) or 1.0
        Y, mass_Y = Y * sign / scale, mass_Y * sign / scale
    return ModeShape(float(omega), sample, Y, rec[:, 0].copy(), mass_Y, ratio)

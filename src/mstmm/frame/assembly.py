"""The frame's dynamic stiffness D(omega) over its free freedoms, and its count.

Freedoms: each node's free translations (X and Y, or the one a roller leaves) and its
rotation Theta (when something holds it: a rigid member end, a rotational spring, a
rotary inertia); a pinned member end's own rotation; each absorber's mass. Each member's
exact local dynamic stiffness (:mod:`mstmm.frame.member`: rod on ``u``, bending on ``w,
psi``) is turned to the global axes (``u = c X + s Y``, ``w = -s X + c Y``) and added;
node springs, node masses and absorbers add ``K - omega^2 M`` on their freedoms.

D is kept dimensionless: lengths in ``L_ref`` (the longest member), stiffnesses in
``EI_ref / L_ref`` (the stiffest member's EI), so that translations and rotations weigh
alike; frequencies in ``omega_ref = sqrt(EI_ref / (mbar_ref L_ref^4))``. A congruence
changes neither D's singular frequencies nor its inertia.

The count (Wittrick and Williams 1971): the natural frequencies below omega are
``J = sum of the members' J0 + the negative eigenvalues of D(omega)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mstmm.catalog import Topology, layout

from .member import member_bending, member_rod
from .model import Frame, Member

__all__ = ["Assembly", "Freedom"]


@dataclass(frozen=True)
class Freedom:
    """One free freedom: what it moves (``"node"``: ``vector`` over the node's (X, Y, Theta);
    ``"hinge"``: member ``owner``'s end ``end`` rotation; ``"absorber"``: absorber number
    ``owner``'s mass along its direction) and whether it is a translation."""

    kind: str
    owner: str | int
    vector: tuple[float, float, float] = (0.0, 0.0, 0.0)
    end: int = 0
    translation: bool = True


class Assembly:
    """A frame laid out for its dynamic stiffness: freedoms, each member's beam and maps."""

    def __init__(self, frame: Frame) -> None:
        self.frame = frame
        self.L_ref = max(frame.geometry(m)[0] for m in frame.members)
        self.EI_ref = max(s.EI for m in frame.members for s in m.segments)
        self.mbar_ref = max(s.mass_per_length for m in frame.members for s in m.segments)
        self.omega_ref = math.sqrt(self.EI_ref / (self.mbar_ref * self.L_ref**4))
        self.freedoms: list[Freedom] = []
        self.node_freedoms: dict[str, list[int]] = {}
        rotating = _rotating_nodes(frame)
        for name, node in frame.nodes.items():
            index = []
            if "n" in node.held:
                nx, ny = node.normal
                index.append(self._add(Freedom("node", name, (ny, -nx, 0.0))))
            else:
                for j, letter in enumerate("xy"):
                    if letter not in node.held:
                        v = (1.0, 0.0, 0.0) if j == 0 else (0.0, 1.0, 0.0)
                        index.append(self._add(Freedom("node", name, v)))
            if "t" not in node.held and name in rotating:
                index.append(self._add(Freedom("node", name, (0.0, 0.0, 1.0), translation=False)))
            self.node_freedoms[name] = index
        self.hinges: dict[tuple[str, int], int] = {}
        for m in frame.members:
            for end in (0, 1):
                if m.pinned[end]:
                    f = Freedom("hinge", m.name, end=end, translation=False)
                    self.hinges[(m.name, end)] = self._add(f)
        self.absorber_freedoms = [
            self._add(Freedom("absorber", i)) for i in range(len(frame.absorbers))
        ]
        self.n = len(self.freedoms)
        self.scale = np.array([self.L_ref if f.translation else 1.0 for f in self.freedoms])
        self.members = [self._member(m) for m in frame.members]

    def _add(self, freedom: Freedom) -> int:
        self.freedoms.append(freedom)
        return len(self.freedoms) - 1

    def _member(self, m: Member) -> MemberMap:
        """The member's beam (parameter vector, clamped ends), its rod data and its map from
        global freedoms to its six local ones ``[u_a, w_a, psi_a, u_b, w_b, psi_b]``."""
        L, c, s = self.frame.geometry(m)
        segments = [
            (sg.length, sg.EI, sg.mass_per_length, 0.0, *_physics(sg.physics)) for sg in m.segments
        ]
        p = layout(segments, [], Topology("clamped", "clamped", (), False))[0]
        index: list[int] = []
        rows: list[list[tuple[int, float]]] = []
        for end, node in ((0, m.start), (1, m.end)):
            u: list[tuple[int, float]] = []
            w: list[tuple[int, float]] = []
            psi: list[tuple[int, float]] = []
            for g in self.node_freedoms[node]:
                X, Y, T = self.freedoms[g].vector
                if X or Y:
                    u.append((g, c * X + s * Y))
                    w.append((g, -s * X + c * Y))
                elif not m.pinned[end]:
                    psi.append((g, T))
            if m.pinned[end]:
                psi.append((self.hinges[(m.name, end)], 1.0))
            rows += [u, w, psi]
            index += [g for g, _ in u + w + psi]
        index = sorted(set(index))
        T = np.zeros((6, len(index)))
        for r, row in enumerate(rows):
            for g, f in row:
                T[r, index.index(g)] += f
        EA = np.array([sg.EA for sg in m.segments])
        mbar = np.array([sg.mass_per_length for sg in m.segments])
        h = np.array([sg.length for sg in m.segments])
        return MemberMap(m, L, p, np.asarray(index, dtype=np.int64), T, EA, mbar, h)

    def matrix(self, omega: float) -> tuple[np.ndarray, int]:
        """``(D, J0)``: the dimensionless dynamic stiffness at omega (rad/s) over the free
        freedoms, and the members' clamped-clamped frequencies below omega."""
        D = np.zeros((self.n, self.n))
        J0 = 0
        K4 = np.empty((4, 4))
        K2 = np.empty((2, 2))
        k = np.zeros((6, 6))
        for mm in self.members:
            beta = mm.L * (mm.p[2] * omega * omega / mm.p[1]) ** 0.25
            J0 += member_bending(mm.p, beta, K4)
            J0 += member_rod(mm.EA, mm.mbar, mm.h, omega, K2)
            EI0, L = mm.p[1], mm.L
            d = np.array([1.0, L, 1.0, L])
            k[:] = 0.0
            k[np.ix_(_BEND, _BEND)] = (EI0 / L**3) * d[:, None] * K4 * d[None, :]
            k[np.ix_(_ROD, _ROD)] = K2
            D[np.ix_(mm.index, mm.index)] += mm.T.T @ k @ mm.T
        w2 = omega * omega
        for name, node in self.frame.nodes.items():
            for g in self.node_freedoms[name]:
                for h in self.node_freedoms[name]:
                    a, b = self.freedoms[g].vector, self.freedoms[h].vector
                    kxx, kxy, kyy = node.springs
                    D[g, h] += a[0] * (kxx * b[0] + kxy * b[1]) + a[1] * (kxy * b[0] + kyy * b[1])
                    D[g, h] += a[2] * node.k_t * b[2]
                    D[g, h] -= w2 * (node.mass * (a[0] * b[0] + a[1] * b[1]) + node.J * a[2] * b[2])
        for m in self.frame.members:
            for end in (0, 1):
                k_h = m.hinge_k[end]
                if k_h:
                    node = m.end if end else m.start
                    own = self.hinges[(m.name, end)]
                    for g in self.node_freedoms[node]:
                        if not self.freedoms[g].translation:
                            D[own, own] += k_h
                            D[g, g] += k_h
                            D[own, g] -= k_h
                            D[g, own] -= k_h
        for i, ab in enumerate(self.frame.absorbers):
            q = self.absorber_freedoms[i]
            D[q, q] += ab.k - w2 * ab.m
            for g in self.node_freedoms[ab.node]:
                v = self.freedoms[g].vector
                dv = ab.direction[0] * v[0] + ab.direction[1] * v[1]
                if dv:
                    D[q, g] -= ab.k * dv
                    D[g, q] -= ab.k * dv
                    for h in self.node_freedoms[ab.node]:
                        u = self.freedoms[h].vector
                        D[g, h] += ab.k * dv * (ab.direction[0] * u[0] + ab.direction[1] * u[1])
        S = self.scale
        return (self.L_ref / self.EI_ref) * (S[:, None] * D * S[None, :]), J0

    def count(self, omega: float) -> int:
        """Natural frequencies below omega (rad/s), with their multiplicities."""
        D, J0 = self.matrix(omega)
        return J0 + int(np.count_nonzero(np.linalg.eigvalsh(D) < 0.0))

    def sure_count(self, omega: float) -> tuple[int, int]:
        """``(count, unsure)``: the count, and how many eigenvalues of D lie within its
        round-off (:data:`ROUNDOFF` times its largest) of 0, whose sign it cannot tell."""
        D, J0 = self.matrix(omega)
        e = np.linalg.eigvalsh(D)
        tau = ROUNDOFF * np.max(np.abs(e))
        return J0 + int(np.count_nonzero(e < 0.0)), int(np.count_nonzero(np.abs(e) <= tau))


@dataclass
class MemberMap:
    """A member as the assembly uses it: its length, beam parameter vector, the global
    freedoms it touches and the map T from them to its local freedoms, its rod data."""

    member: Member
    L: float
    p: np.ndarray
    index: np.ndarray
    T: np.ndarray
    EA: np.ndarray
    mbar: np.ndarray
    h: np.ndarray


#: An eigenvalue of D within this fraction of its largest is round-off (``sure_count``):
#: D is formed to about 100 ulp (each member's pieces eliminated, turned and added).
ROUNDOFF = 1e3 * np.finfo(float).eps
#: The local freedoms of the bending block and of the rod.
_BEND = np.array([1, 2, 4, 5])
_ROD = np.array([0, 3])


def _physics(physics: tuple[tuple[str, float], ...]) -> list[float]:
    """A segment's term values in the order of ``catalog.SEGMENT_KEYS`` after the loss factor."""
    from mstmm.catalog import SEGMENT_PHYSICS

    values = dict(physics)
    return [values.get(key, 0.0) for key, _, _ in SEGMENT_PHYSICS]


def _rotating_nodes(frame: Frame) -> set[str]:
    """Nodes whose rotation is a freedom: a rigid member end, a rotational spring, a hinge
    spring or a rotary inertia ties it (else nothing acts on it and it is left out)."""
    out = {n for n, node in frame.nodes.items() if node.k_t or node.J}
    for m in frame.members:
        for end, node in ((0, m.start), (1, m.end)):
            if not m.pinned[end] or m.hinge_k[end]:
                out.add(node)
    return out

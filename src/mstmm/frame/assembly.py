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
from functools import cached_property

import numpy as np

from mstmm.catalog import SEGMENT_PHYSICS, Topology, layout

from .banded import backward, band_matvec, inverse_iteration, ldl, reverse_band, row_norm
from .member import assemble_members
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
        out_of_plane = frame.motion == "out_of_plane"
        for name, node in frame.nodes.items():
            index = []
            if out_of_plane:  # W, ThetaX, ThetaY
                if "z" not in node.held:
                    index.append(self._add(Freedom("node", name, (1.0, 0.0, 0.0))))
                for j, letter in ((1, "a"), (2, "b")):
                    if letter not in node.held and name in rotating:
                        v = (0.0, 1.0, 0.0) if j == 1 else (0.0, 0.0, 1.0)
                        index.append(self._add(Freedom("node", name, v, translation=False)))
            elif "n" in node.held:
                nx, ny = node.normal
                index.append(self._add(Freedom("node", name, (ny, -nx, 0.0))))
            else:
                for j, letter in enumerate("xy"):
                    if letter not in node.held:
                        v = (1.0, 0.0, 0.0) if j == 0 else (0.0, 1.0, 0.0)
                        index.append(self._add(Freedom("node", name, v)))
            if not out_of_plane and "t" not in node.held and name in rotating:
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
        self._layouts: dict[tuple, np.ndarray] = {}
        self.members = [self._member(m) for m in frame.members]
        S = self.scale * math.sqrt(self.L_ref / self.EI_ref)
        K, C, M = self._lumped()
        self.K_lumped = S[:, None] * K * S[None, :]
        self.C_lumped = S[:, None] * C * S[None, :]
        self.M_lumped = S[:, None] * M * S[None, :]
        self.pattern = _pattern(self)
        self.perm, self.bandwidth = _band_order(self.pattern)
        self.pos = np.empty(self.n, dtype=np.int64)
        self.pos[self.perm] = np.arange(self.n)
        self.packed = self._packed()
        #: ``(count, J0, log|det D|)`` by omega wherever a factorization found them
        #: (:meth:`factor`, :meth:`sure_count`; log|det D| nan where an orthogonal
        #: reduction counted): a bracket's ends are counted once, and the root finder's
        #: determinant reuses them.
        self.factors: dict[float, tuple[int, int, float]] = {}
        self.K_band = self.to_band(self.K_lumped)
        self.M_band = self.to_band(self.M_lumped)

    @cached_property
    def C_band(self) -> np.ndarray:
        """The dashpots' C (dimensionless) in band rows: only a damped frame asks."""
        return self.to_band(self.C_lumped)

    @cached_property
    def general_band(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(rows, cols, src)``: LAPACK's general band storage (kl = ku = bandwidth, as
        ``zgbtrf`` takes it) of D from its upper band rows B in one gather, ``ab[rows,
        cols] = B.ravel()[src]`` (``A[i, i + k]`` and ``A[i + k, i]``)."""
        n, b = self.n, self.bandwidth
        i, k = np.nonzero(np.arange(n)[:, None] + np.arange(b + 1)[None, :] < n)
        rows = np.concatenate([2 * b - k, 2 * b + k])
        return rows, np.concatenate([i + k, i]), np.concatenate([i * (b + 1) + k] * 2)

    def _add(self, freedom: Freedom) -> int:
        self.freedoms.append(freedom)
        return len(self.freedoms) - 1

    def _member(self, m: Member) -> MemberMap:
        """The member's beam (parameter vector, clamped ends), its rod data and its map from
        global freedoms to its six local ones ``[u_a, w_a, psi_a, u_b, w_b, psi_b]``."""
        L, c, s = self.frame.geometry(m)
        segments = [
            (sg.length, sg.EI, sg.mass_per_length, sg.loss_factor, *_physics(sg.physics))
            for sg in m.segments
        ]
        key = tuple(segments)
        if key not in self._layouts:  # members of one section share their beam
            self._layouts[key] = layout(segments, [], Topology("clamped", "clamped", (), False))[0]
        p = self._layouts[key]
        index: list[int] = []
        rows: list[list[tuple[int, float]]] = []
        for end, node in ((0, m.start), (1, m.end)):
            u: list[tuple[int, float]] = []
            w: list[tuple[int, float]] = []
            psi: list[tuple[int, float]] = []
            for g in self.node_freedoms[node]:
                X, Y, T = self.freedoms[g].vector
                if self.frame.motion == "out_of_plane":  # (W, ThetaX, ThetaY)
                    if X:
                        w.append((g, X))
                    else:  # the twist about local x, and psi = dw/dx = -(rotation about y)
                        u.append((g, c * Y + s * T))
                        psi.append((g, s * Y - c * T))
                elif X or Y:
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
        if self.frame.motion == "out_of_plane":  # the rod is the member's torsion
            EA = np.array([sg.GJ for sg in m.segments])
            mbar = np.array([sg.rho_Ip for sg in m.segments])
        else:
            EA = np.array([sg.EA for sg in m.segments])
            mbar = np.array([sg.mass_per_length for sg in m.segments])
        h = np.array([sg.length for sg in m.segments])
        eta = np.array([sg.loss_factor for sg in m.segments])
        torsion = self.frame.motion == "out_of_plane"
        index = np.asarray(index, dtype=np.int64)
        return MemberMap(m, L, p, index, T, EA, mbar, h, torsion, eta)

    def _lumped(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(K, C, M)`` of everything but the members, over the free freedoms (SI): node
        springs and masses, hinge springs, absorbers (``D = members + K - omega^2 M``; the
        absorbers' dashpots C enter the frequency response only)."""
        K = np.zeros((self.n, self.n))
        C = np.zeros((self.n, self.n))
        M = np.zeros((self.n, self.n))
        out_of_plane = self.frame.motion == "out_of_plane"
        for name, node in self.frame.nodes.items():
            kxx, kxy, kyy = node.springs
            for g in self.node_freedoms[name]:
                for h in self.node_freedoms[name]:
                    a, b = self.freedoms[g].vector, self.freedoms[h].vector
                    K[g, h] += a[0] * (kxx * b[0] + kxy * b[1]) + a[1] * (kxy * b[0] + kyy * b[1])
                    if out_of_plane:  # mass on W, J about X and about Y
                        M[g, h] += node.mass * a[0] * b[0] + node.J * (a[1] * b[1] + a[2] * b[2])
                    else:
                        K[g, h] += a[2] * node.k_t * b[2]
                        M[g, h] += node.mass * (a[0] * b[0] + a[1] * b[1]) + node.J * a[2] * b[2]
        for m in self.frame.members:
            for end in (0, 1):
                k_h = m.hinge_k[end]
                if k_h:
                    own = self.hinges[(m.name, end)]
                    for g in self.node_freedoms[m.end if end else m.start]:
                        if not self.freedoms[g].translation:
                            K[np.ix_([own, g], [own, g])] += k_h * np.array([[1, -1], [-1, 1]])
        for i, ab in enumerate(self.frame.absorbers):
            q = self.absorber_freedoms[i]
            # k (q - d . U)^2 / 2: the row [1, -d . v_g] on (q, g)
            row = {q: 1.0}
            for g in self.node_freedoms[ab.node]:
                v = self.freedoms[g].vector
                dv = ab.direction[0] * v[0] + ab.direction[1] * v[1]
                if dv:
                    row[g] = -dv
            for g, a in row.items():
                for h, b in row.items():
                    K[g, h] += ab.k * a * b
                    C[g, h] += ab.c * a * b
            M[q, q] += ab.m
        return K, C, M

    def _packed(self) -> tuple:
        """The members as :func:`member.assemble_members` reads them: each distinct member
        type (beam parameters, rod segments and length) once, each member's type, its map
        T with D's units, and its freedoms by their band positions."""
        units = self.L_ref / self.EI_ref
        types: dict[tuple, int] = {}
        kind = np.empty(len(self.members), dtype=np.int64)
        first: list[MemberMap] = []
        for i, mm in enumerate(self.members):
            key = (mm.L, mm.p.tobytes(), mm.EA.tobytes(), mm.mbar.tobytes(), mm.h.tobytes())
            if key not in types:
                types[key] = len(first)
                first.append(mm)
            kind[i] = types[key]
        P = np.concatenate([mm.p for mm in first])
        p_off = np.cumsum([0] + [len(mm.p) for mm in first]).astype(np.int64)
        EA = np.concatenate([mm.EA for mm in first])
        mbar = np.concatenate([mm.mbar for mm in first])
        h = np.concatenate([mm.h for mm in first])
        #: each rod segment's loss factor (on EA or GJ), as ``packed``'s rods are laid out
        self.rod_eta = np.concatenate([mm.eta for mm in first])
        r_off = np.cumsum([0] + [len(mm.h) for mm in first]).astype(np.int64)
        L = np.array([mm.L for mm in first])
        T = np.zeros((len(self.members), 6, 6))
        idx = np.full((len(self.members), 6), -1, dtype=np.int64)
        for i, mm in enumerate(self.members):
            n = len(mm.index)
            idx[i, :n] = self.pos[mm.index]
            T[i, :, :n] = mm.T * self.scale[mm.index][None, :] * math.sqrt(units)
        return P, p_off, EA, mbar, h, r_off, L, kind, T, idx

    def to_band(self, A: np.ndarray) -> np.ndarray:
        """A dense symmetric A over the freedoms as upper band rows in :attr:`perm`'s order
        (``B[i, k] = A_p[i, i + k]``, :mod:`.banded`)."""
        b, n = self.bandwidth, self.n
        Ap = A[np.ix_(self.perm, self.perm)]
        B = np.zeros((n, b + 1))
        for k in range(min(b + 1, n)):
            B[: n - k, k] = np.diagonal(Ap, k)
        return B

    def dense(self, B: np.ndarray) -> np.ndarray:
        """Band rows B back to the dense symmetric matrix over the freedoms."""
        n = self.n
        Ap = np.zeros((n, n))
        for k in range(min(self.bandwidth + 1, n)):
            i = np.arange(n - k)
            Ap[i, i + k] = B[: n - k, k]
            Ap[i + k, i] = B[: n - k, k]
        A = np.empty((n, n))
        A[np.ix_(self.perm, self.perm)] = Ap
        return A

    def banded(self, omega: float) -> tuple[np.ndarray, int]:
        """``(B, J0)``: the dimensionless dynamic stiffness at omega (rad/s) as upper band
        rows in :attr:`perm`'s order, and the members' clamped-clamped frequencies below
        omega."""
        B = self.K_band - (omega * omega) * self.M_band
        J0 = assemble_members(*self.packed, omega, B)
        return B, J0

    def matrix(self, omega: float) -> tuple[np.ndarray, int]:
        """``(D, J0)``: :meth:`banded` as a dense matrix over the freedoms."""
        B, J0 = self.banded(omega)
        return self.dense(B), J0

    def quadratic(self, B: np.ndarray, X: np.ndarray) -> np.ndarray:
        """``X^T D X`` (k x k) for D in band rows B and the columns of X over the freedoms."""
        Xp = np.ascontiguousarray(X[self.perm])
        Y = np.empty_like(Xp)
        y = np.empty(self.n)
        for j in range(Xp.shape[1]):
            band_matvec(B, np.ascontiguousarray(Xp[:, j]), y)
            Y[:, j] = y
        return Xp.T @ Y

    def count(self, omega: float) -> int:
        """Natural frequencies below omega (rad/s), with their multiplicities."""
        return self.state(omega)[0]

    def state(self, omega: float) -> tuple[int, int]:
        """``(count, J0)`` at omega (rad/s): the count and the members' part of it."""
        return self.factor(omega)[:2]

    def factor(self, omega: float) -> tuple[int, int, float]:
        """``(count, J0, log|det D|)`` at omega (rad/s): the count from the pivots of
        :func:`.banded.ldl` where their backward error is below D's round-off (the
        freedoms in band order, or else in reverse), else from an orthogonal band
        reduction (``log|det D|`` is then nan)."""
        if omega in self.factors:
            return self.factors[omega]
        B, J0 = self.banded(omega)
        if self.n == 0:
            return J0, J0, 0.0
        W = self._work()
        tau = self.roundoff(B)
        for order in self._orders(B):
            negatives, G, logdet = ldl(order, 0.0, W)
            if backward(G, self.bandwidth) <= tau:
                out = (J0 + negatives, J0, logdet)
                break
        else:
            out = (J0 + self.eigenvalues_in(B, -np.inf, 0.0), J0, math.nan)
        self.factors[omega] = out
        return out

    def _orders(self, B: np.ndarray):
        """B, then (only if asked for) B with its freedoms in reverse order: the factors
        then eliminate from the other end, other leading blocks, other pivots."""
        yield B
        yield reverse_band(B, np.empty_like(B))

    def within(self, B: np.ndarray, tau: float, W: np.ndarray) -> int | None:
        """How many eigenvalues of D (band rows B, in the order to factor) lie in
        ``[-tau, tau)``: the counts of ``D - tau I`` and ``D + tau I`` apart, each
        factorization exact for a D within tau / 4; None where their pivots grew past it."""
        below, G_below, _ = ldl(B, -tau, W)
        above, G_above, _ = ldl(B, tau, W)
        if 4.0 * backward(max(G_below, G_above), self.bandwidth) <= tau:
            return above - below
        return None

    def sure_count(self, omega: float) -> tuple[int, int, int]:
        """``(count, J0, unsure)``: the count, its members' part, and how many eigenvalues
        of D lie within its round-off tau (:data:`ROUNDOFF` times its norm, or the
        factors' own backward error where that is larger), whose sign it cannot tell.

        Three factorizations (:func:`.banded.ldl`) of ``D - s I``, ``s = -tau, 0, tau``,
        each exact for a D within tau / 4 (tau at least 8 times the middle one's
        backward error): the eigenvalues in ``[-tau, tau)`` are the
        difference of the outer two's counts. Where a factorization's pivots grow past
        that (or make tau more than :data:`SURE_GROWTH` times the round-off), the same in
        the reverse order, and then an orthogonal band reduction (LAPACK ``dsbevx``)."""
        B, J0 = self.banded(omega)
        if self.n == 0:
            return J0, J0, 0
        W = self._work()
        roundoff = self.roundoff(B)
        for order in self._orders(B):
            negatives, G, logdet = ldl(order, 0.0, W)
            tau = max(roundoff, 8.0 * backward(G, self.bandwidth))
            if tau > SURE_GROWTH * roundoff:
                continue
            unsure = self.within(order, tau, W)
            if unsure is not None:
                self.factors[omega] = (J0 + negatives, J0, logdet)
                return J0 + negatives, J0, unsure
        return self._sure_count_orthogonal(B, J0)

    def _sure_count_orthogonal(self, B: np.ndarray, J0: int) -> tuple[int, int, int]:
        """:meth:`sure_count` by one band reduction: the eigenvalues up to the round-off."""
        from scipy.linalg import eig_banded

        tau = self.roundoff(B)
        e = eig_banded(
            self.lapack(B), eigvals_only=True, select="v",
            select_range=(-np.finfo(float).max, tau), check_finite=False,
        )  # fmt: skip
        negative = int(np.count_nonzero(e < 0.0))
        return J0 + negative, J0, int(np.count_nonzero(np.abs(e) <= tau))

    def _work(self) -> np.ndarray:
        return np.empty((self.n, self.bandwidth + 1))

    @staticmethod
    def roundoff(B: np.ndarray) -> float:
        """The size below which an eigenvalue of D (band rows B) is round-off:
        :data:`ROUNDOFF` times its norm (the largest row sum, a bound on the largest
        eigenvalue)."""
        return ROUNDOFF * float(row_norm(B))

    def lapack(self, B: np.ndarray) -> np.ndarray:
        """Band rows B as LAPACK's upper band storage."""
        b, n = self.bandwidth, self.n
        ab = np.zeros((b + 1, n))
        for k in range(min(b + 1, n)):
            ab[b - k, k:] = B[: n - k, k]
        return ab

    def eigenvalues_in(self, B: np.ndarray, lo: float, hi: float) -> int:
        """How many eigenvalues of D (band rows B) lie in [lo, hi) (``hi = 0``: its
        negative ones), by the band reduction to a tridiagonal and bisection (orthogonal:
        stable at any inertia), from LAPACK's half-open (lo, hi] by the ends' closest
        floats."""
        from scipy.linalg import eig_banded

        if self.n == 0:
            return 0
        big = np.finfo(float).max
        lo = -big if lo <= -big else float(np.nextafter(lo, -np.inf))
        e = eig_banded(
            self.lapack(B), eigvals_only=True, select="v",
            select_range=(lo, float(np.nextafter(hi, -np.inf))),
            check_finite=False,
        )  # fmt: skip
        return int(len(e))

    def eigenvalue(self, B: np.ndarray, index: int) -> float:
        """The ``index``-th eigenvalue of D (band rows B) in ascending order."""
        from scipy.linalg import eig_banded

        e = eig_banded(
            self.lapack(B), eigvals_only=True, select="i", select_range=(index, index),
            check_finite=False,
        )  # fmt: skip
        return float(e[0])

    def null_vector(self, B: np.ndarray) -> np.ndarray | None:
        """The unit eigenvector of D's eigenvalue nearest 0 (D in band rows B, at a simple
        root), over the freedoms, by inverse iteration with :func:`.banded.ldl`'s factors
        (in band order, or else in reverse); None where both factors' pivots grew or the
        iteration leaves a residual above D's round-off (:meth:`near_zero` then)."""
        W = self._work()
        tau = self.roundoff(B)
        for order in self._orders(B):
            _, G, _ = ldl(order, 0.0, W)
            if not backward(G, self.bandwidth) <= tau:
                continue
            x = inverse_iteration(W, 3)
            if order is not B:
                x = x[::-1].copy()
            y = np.empty_like(x)
            band_matvec(B, x, y)
            if np.linalg.norm(y - (x @ y) * x) <= NULL_RESIDUAL * tau:
                X = np.empty(self.n)
                X[self.perm] = x
                return X
        return None

    def near_zero(self, B: np.ndarray, k: int) -> tuple[np.ndarray, np.ndarray]:
        """The k eigenvalues of D (band rows B) of least magnitude and their eigenvectors
        (columns, over the freedoms)."""
        from scipy.linalg import eig_banded

        neg = self.eigenvalues_in(B, -np.inf, 0.0)
        first, last = max(0, neg - k), min(self.n - 1, neg + k - 1)
        e, V = eig_banded(
            self.lapack(B), select="i", select_range=(first, last), check_finite=False
        )
        keep = np.argsort(np.abs(e))[:k]
        X = np.empty((self.n, len(keep)))
        X[self.perm] = V[:, keep]
        return e[keep], X


def _pattern(asm: Assembly) -> np.ndarray:
    """Which freedoms D couples (n x n booleans): members, springs, masses, absorbers."""
    A = (np.abs(asm.K_lumped) + np.abs(asm.M_lumped)) > 0.0
    for mm in asm.members:
        A[np.ix_(mm.index, mm.index)] = True
    A[np.arange(asm.n), np.arange(asm.n)] = True
    return A


def _band_order(A: np.ndarray) -> tuple[np.ndarray, int]:
    """A reordering of the freedoms that makes a pattern A banded (reverse Cuthill-McKee),
    and its half-bandwidth."""
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import reverse_cuthill_mckee

    if len(A) == 0:
        return np.zeros(0, dtype=np.int64), 0
    perm = np.asarray(reverse_cuthill_mckee(csr_matrix(A), symmetric_mode=True), dtype=np.int64)
    i, j = np.nonzero(A[np.ix_(perm, perm)])
    return perm, int(np.max(np.abs(i - j)))


@dataclass
class MemberMap:
    """A member as the assembly uses it: its length, beam parameter vector, the global
    freedoms it touches and the map T from them to its local freedoms, its rod data
    (``torsion``: out of the plane the rod is its torsion, EA its GJ and mbar its
    rho_Ip)."""

    member: Member
    L: float
    p: np.ndarray
    index: np.ndarray
    T: np.ndarray
    EA: np.ndarray
    mbar: np.ndarray
    h: np.ndarray
    torsion: bool = False
    eta: np.ndarray | None = None  # each segment's loss factor


#: An eigenvalue of D within this fraction of its largest is round-off (``sure_count``):
#: D is formed to about 100 ulp (each member's pieces eliminated, turned and added).
ROUNDOFF = 1e3 * np.finfo(float).eps
#: :meth:`Assembly.null_vector` accepts a vector whose residual is this many times D's
#: round-off at most (inverse iteration at a root: the residual is the round-off's size).
NULL_RESIDUAL = 10.0
#: :meth:`Assembly.sure_count` takes the factors' own backward error as its tau up to
#: this many times the round-off (a wider tau makes the root's windows wider).
SURE_GROWTH = 4.0


def _physics(physics: tuple[tuple[str, float], ...]) -> list[float]:
    """A segment's term values in the order of ``catalog.SEGMENT_KEYS`` after the loss factor."""
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

"""Independent finite-element model of a beam carrying spring-mass attachments.

A check on, and a benchmark competitor for, the transfer-matrix solver (the tests and the
benchmarks import this one module as ``reference_fem``, with tests/ on ``sys.path``; it
imports numpy and scipy, never mstmm): the
uniform or stepped Euler-Bernoulli beam is cut into cubic Hermite elements
(nodal DOFs ``Y`` and ``theta``, consistent mass matrix, the properties of the
segment each element lies in; a segment with a shear stiffness ``kappa_GA > 0``
into Timoshenko elements, see "Beyond Euler-Bernoulli" below), and every attachment
kind of the scene format
(:data:`KINDS`) acts on its node: a spring-mass or oscillator chain adds its
masses as DOFs joined by its springs; a point mass ``m`` and rotary inertia
``J`` go on the node's ``Y`` / ``theta`` mass; a spring and a rotational spring
to ground on its ``Y`` / ``theta`` stiffness; a support removes its ``Y``; a
hinge duplicates its ``theta`` (``theta-``, ``theta+``) with the hinge spring
``k`` (absent or 0: none) between them.  A rotational spring or rotary inertia
at a hinge is rejected (ambiguous).  The end conditions remove DOFs:

========  ==================
clamped   ``Y = theta = 0``
pinned    ``Y = 0``
sliding   ``theta = 0``
free      nothing removed
========  ==================

The mesh is uniform with ``n_elements`` elements, except that a node sits
exactly at every distinct attachment position and segment boundary (positions
within ``1e-14 L`` of a boundary or an end are moved onto it): the nearest interior uniform
node is moved onto the attachment when it is closer than ``1e-3`` of the
uniform element size, otherwise the uniform element is split there.

The FE eigenvalues ``omega**2`` are upper bounds of the exact ones; their
error, and that of the frequencies, is ``c4 h**4 + c6 h**6 + ...`` (measured:
the error ratio of meshes ``n`` and ``2 n`` is 16.0, after Richardson 64), and
:func:`richardson` removes the ``h**4`` term using a mesh and its bisection.

Round-off.  The textbook ``scipy.linalg.eigh(K, M)`` loses the low
eigenvalues to round-off of order ``eps * cond(K) ~ eps * 200 n**4`` (relative
error ~1e-5 at 64 elements with ``subset_by_index``, worse than the
discretization error beyond ~20 elements; available as ``solver="eigh"`` for
comparison).  The default solvers therefore work on the shift-inverted
problem, ``(K - sigma M)^{-1} M`` with ``sigma < 0``, whose largest eigenvalues
are the wanted ones, and apply ``(K - sigma M)^{-1}`` by a banded Cholesky
factorization with iterative refinement whose residual uses ``K = G^T G``
(``G`` maps the DOFs to element curvatures, see :func:`_matrices`): the low
frequencies then come out to ~1e-15 relative for any mesh up to about 8000
elements, beyond which the refinement stops converging and a
:class:`FloatingPointError` is raised.

Beyond Euler-Bernoulli.  The optional segment keys (on ``[beam]`` for a uniform
beam, else on each segment; default 0: absent) ``kappa_GA`` (N), ``rho_I`` (kg m),
``axial_force`` ``P`` (N, tension > 0), ``foundation_k`` ``k_w`` (N/m^2) and
``foundation_kG`` ``k_G`` (N) enter through the energies per unit length (``w = Y``,
``psi`` the section rotation, the DOF ``theta`` on which rotational springs, rotary
inertias and hinges act)::

    potential  1/2 [EI psi'^2 + kGA (w' - psi)^2 + (P + k_G) w'^2 + k_w w^2]
    kinetic    1/2 [mbar w_t^2 + rho_I psi_t^2]

``kappa_GA = 0``: no shear deformation, ``psi = w'``, the Hermite element above with
the consistent geometric stiffness ``(P + k_G) integral N'^T N'``, the Winkler
stiffness ``k_w integral N^T N`` and the rotary inertia ``rho_I integral N'^T N'``
(a Rayleigh beam), all integrated exactly by Gauss quadrature.  ``kappa_GA > 0``: a
Timoshenko element with ``w`` cubic and ``psi`` quadratic on each element, the full
``P3 x P2`` pair: nodal DOFs ``Y``, ``psi`` (so the attachments act on nodes and a
hinge duplicates ``psi``) and three internal DOFs per element, the slopes ``s_i, s_j``
of ``w`` at its ends (``w`` is the Hermite cubic of ``Y_i, s_i, Y_j, s_j``; ``w'`` may
jump between elements, ``w`` and ``psi`` are continuous) and the amplitude ``b`` of the
bubble ``4 xi (1 - xi)`` of ``psi``; consistent mass (``mbar w^2 + rho_I psi^2``),
every term integrated exactly.  No shear locking: the space holds ``psi = w'`` with
``w`` any piecewise Hermite cubic, the Euler-Bernoulli element, which it tends to as
``kappa_GA -> infinity``.  The cleaner-looking interdependent interpolation element
(Reddy 1997: 4 DOFs, the exact static shape functions, shear strain constant on an
element) was measured (a scratch implementation, pinned-pinned, consistent mass) to
converge only as ``h**2`` in frequency (error ratio between meshes n and 2 n of 8 to 64
elements: 4.00 - 4.06 for kGA L^2 / EI = 10 and 100; 8.7 falling to 4.5 for 1e4, where
the h**2 term is small but wins on fine meshes): the piecewise constant shear strain
cannot approximate a varying shear force better than O(h).  A segment's
``loss_factor`` eta multiplies its ``EI``, ``kGA``, ``k_w``, ``k_G`` terms by
``1 + i eta`` but not the axial force (a load).

Measured convergence (pinned-pinned L = 2, EI = 3, mbar = 1.5, the six lowest
frequencies, tests/test_fem_general.py): the error ratio between meshes 16 and 32 and
between 32 and 64 elements is 15.36 - 16.05 for the Euler-Bernoulli element with a
tension, a compression, a Winkler or Pasternak foundation or rotary inertia, and 15.77 -
16.03 for the Timoshenko element (kGA L^2 / EI = 80) with and without ``rho_I`` and with
every term at once (the thickness-shear mode ``w = 0``, ``psi`` constant, is exact on any
mesh): ``O(h**4)`` for both, ``O(h**6)`` after :func:`richardson` (error ratio 39 - 68
between 16 and 32 elements, ~64 asymptotically), which reaches the closed forms within
1e-9 at 64 elements (measured <= 9.3e-10 over the six modes; stepped beams mixing both
elements and the terms: the same rates, tests/test_fem_general.py).  A Timoshenko
element has about 2.5 times the DOFs of a Hermite one (5 per element against 2).

Compression.  ``K = G^T diag(sign) G``: the rows ``sqrt(|P|) w'`` of a compression
``P < 0`` carry ``sign = -1`` (all other rows +1), so ``K`` is indefinite once the beam
buckles.  The solvers keep the shift ``sigma = -scale``: not buckled, every eigenvalue is
>= 0 > sigma and ``K - sigma M`` is positive definite (banded Cholesky, the residual of
the refinement through ``G^T (sign G y)``).  Buckled: either the Cholesky factorization
of ``K - sigma M`` fails (an eigenvalue below sigma) or an eigenvalue in ``(sigma, 0)``
comes out; both raise ValueError ("... buckled ...") from every function but
:func:`assemble` and :func:`damped_assemble` (:func:`count_below` and :func:`frf` first
compute the lowest eigenvalue when there is a compression).  A
Timoshenko segment with ``kappa_GA + P + k_G <= 0`` buckles in shear (on any mesh fine
enough).  Round-off: the Timoshenko element's shear rows scale with ``kGA``; the
smallest relative error reached (``solver="sparse"``, 4096 elements) is 3e-13 for
``kGA L^2 / EI = 1e5`` and 8e-11 for 1e7 (an almost Euler-Bernoulli beam: give
``kappa_GA = 0`` there).

Singular mass.  A Timoshenko element with ``rho_I = 0`` gives ``psi`` and ``b`` no
mass: their rows and columns of ``M`` are 0 (infinite eigenvalues).  The dense solver
then takes ``M = U^T U`` on the DOFs with mass only, the sparse one runs ARPACK on the
standard symmetric ``U (K - sigma M)^{-1} U^T``, :func:`damped_spectrum` drops the
infinite roots, ``n_modes`` is at most the number of DOFs with mass, and the ``"svd"``
and ``"eigh"`` solvers refuse such a scene (and ``"svd"`` a compression).

Solvers (``solver=``):

``"dense"``
    all eigenvalues of the symmetric ``U (K - sigma M)^{-1} U^T``
    (``M = U^T U``, ``U`` the banded Cholesky factor) by LAPACK
    (``scipy.linalg.eigh``); ``O(n**3)``.
``"sparse"``
    ARPACK shift-invert Lanczos (``scipy.sparse.linalg.eigsh``) on the same
    operator; ``O(n)`` per mode.
``"svd"``
    an independent check: the frequencies are the singular values of
    ``G R^{-1}`` (``M = R^T R``); round-off ~ ``eps * 14 n**2`` relative.
``"eigh"``
    the textbook baseline above.

Damping (the ``damped_*`` functions and :func:`frf`; the undamped ones refuse a scene
with c > 0 or a loss factor > 0): a dashpot ``c`` parallel to a spring-mass's spring
(``c``) or to each spring of a chain (``c``, a list) joins the same DOFs in a damping
matrix ``C``; a grounded ``dashpot`` (``x``, ``c``) acts on its node's ``Y``; a segment's
``loss_factor`` eta multiplies the stiffness of its elements by ``1 + i eta``
(``K* = G^T diag(sign + i eta) G``, eta 0 on the rows of the axial force).  With
``s = i w`` (time dependence ``exp(i w t)``) the roots solve ``(K* + s C + s^2 M) v = 0``:
:func:`damped_spectrum` takes every eigenvalue of
the shift-inverted state-space form (dense ``scipy.linalg.eigvals``), reports
``w = -i s = w_d + i sigma`` with ``w_d >= 0`` in the order of the reference model
(rigid-body zeros, overdamped roots by sigma, then by w_d); their error is ``O(h**4)``
too (error ratio 16.0 between meshes n and 2 n, 64 after :func:`damped_richardson`).
:func:`frf` solves ``(K* + i w C - w^2 M) X = F`` for a unit nodal force or moment.

``scene`` is duck-typed: an object with ``.beam.length``, ``.beam.EI``,
``.beam.mass_per_length`` (or ``.beam.segments``, each with ``.length``,
``.EI``, ``.mass_per_length``; optional, default 0: ``.loss_factor``, ``.kappa_GA``,
``.rho_I``, ``.axial_force``, ``.foundation_k``, ``.foundation_kG``, on the beam for a
uniform one, else on each segment), ``.beam.left``, ``.beam.right`` and
``.attachments`` (each with ``.kind``, default ``spring_mass``, ``.x`` and the
kind's values), e.g. ``mstmm.Scene``, or a mapping in the TOML layout::

    {"beam": {"length": 1.0, "EI": 1.0, "mass_per_length": 1.0,
              "left": "clamped", "right": "free", "kappa_GA": 50.0, "rho_I": 0.01},
     "attachments": [{"type": "spring_mass", "x": 0.5, "k": 1.0, "m": 1.0}]}
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.linalg
import scipy.sparse
import scipy.sparse.linalg

__all__ = [
    "DAMPED_KINDS",
    "KINDS",
    "assemble",
    "count_below",
    "damped_assemble",
    "damped_frequencies",
    "damped_richardson",
    "damped_spectrum",
    "frequencies",
    "frf",
    "mesh",
    "richardson",
]

#: The optional segment keys (on ``[beam]`` for a uniform beam, else on each segment),
#: default 0: Timoshenko shear stiffness kGA (N), rotary inertia per length (kg m), axial
#: force (N, tension > 0), Winkler foundation (N/m^2), Pasternak shear layer (N).
_PHYSICS = ("kappa_GA", "rho_I", "axial_force", "foundation_k", "foundation_kG")

#: DOFs (0 = ``Y``, 1 = ``theta``) removed at an end of each kind.
_REMOVED = {"clamped": (0, 1), "pinned": (0,), "sliding": (1,), "free": ()}

#: A uniform node closer than this fraction of the uniform element size to an
#: attachment is moved onto it instead of leaving a short element.
_SNAP = 1e-3

#: An attachment within this fraction of L of a segment boundary or an end is moved onto it.
_SNAP_EDGE = 1e-14

#: Attachment kinds (the scene format of ``tests/reference_model.py``).
KINDS = (
    "spring_mass",
    "mass",
    "spring",
    "rotational_spring",
    "support",
    "hinge",
    "oscillator_chain",
)

#: The kinds the damped functions also accept: a grounded viscous ``dashpot`` (``x``, ``c``).
DAMPED_KINDS = KINDS + ("dashpot",)

#: Eigenvalues below this fraction of the lowest elastic scale squared are the
#: rigid-body zeros (``|omega| < 1e-6`` of that scale).
_ZERO = 1e-12

_SOLVERS = ("dense", "sparse", "svd", "eigh")

#: Iterative refinement must bring the relative correction below this.
_REFINED = 1e-8
_TOO_FINE = (
    "iterative refinement of (K - sigma M) y = x does not converge (last relative "
    "correction {size:.1e}): the mesh is too fine for double precision "
    "(the limit is near 8000 elements)"
)


@dataclass(frozen=True)
class _Attachment:
    """One attachment: ``kind`` (see the module docstring), position ``x`` (m), stiffnesses
    ``k`` (the chain's springs, a spring's or hinge's k) and masses ``m`` (a chain's
    masses; a point mass's ``(m, J)``)."""

    kind: str
    x: float
    k: tuple[float, ...] = ()
    m: tuple[float, ...] = ()
    c: tuple[float, ...] = ()  # dashpots: parallel to a chain's springs, or a grounded one


@dataclass(frozen=True)
class _Model:
    length: float
    segments: tuple[tuple[float, float, float], ...]  # (length, EI, mbar) from the left
    left: str
    right: str
    attachments: tuple[_Attachment, ...]
    loss: tuple[float, ...] = ()  # loss factor of each segment (empty: none)
    # (kappa_GA, rho_I, axial_force, foundation_k, foundation_kG) of each segment (empty: 0)
    physics: tuple[tuple[float, float, float, float, float], ...] = ()

    @property
    def compressed(self) -> bool:
        """An axial compression anywhere: ``K`` may be indefinite (buckling)."""
        return any(p[2] < 0 for p in self.physics)

    @property
    def damped(self) -> bool:
        """A dashpot (c > 0) or a loss factor (eta > 0) anywhere."""
        return any(v > 0 for v in self.loss) or any(v > 0 for a in self.attachments for v in a.c)

    @property
    def boundaries(self) -> np.ndarray:
        """Positions of the segment boundaries, 0 and L included."""
        edges = np.concatenate([[0.0], np.cumsum([s[0] for s in self.segments])])
        edges[-1] = self.length
        return edges

    @property
    def scale(self) -> float:
        """Lowest elastic eigenvalue scale (rad/s)**2: a segment's ``EI/(mbar L^4)`` or a
        hanging stage's ``k/m``."""
        beam = [ei / (mbar * self.length**4) for _, ei, mbar in self.segments]
        hung = [
            k / m
            for a in self.attachments
            if a.kind == "chain"
            for k, m in zip(a.k, a.m, strict=True)
        ]
        return min(beam + hung)


def _get(obj: Any, key: str) -> Any:
    return obj[key] if isinstance(obj, Mapping) else getattr(obj, key)


def _opt(obj: Any, key: str, default: Any) -> Any:
    value = obj.get(key) if isinstance(obj, Mapping) else getattr(obj, key, None)
    return default if value is None else value


def _kind(item: Any) -> str:
    if isinstance(item, Mapping):
        kind = item.get("type", item.get("kind", "spring_mass"))
    else:
        kind = getattr(item, "kind", None) or getattr(item, "type", None) or "spring_mass"
    kind = str(getattr(kind, "value", kind))
    if kind not in DAMPED_KINDS:
        raise ValueError(f"unsupported attachment type {kind!r}; expected one of {DAMPED_KINDS}")
    return kind


def _attachment(item: Any, length: float, edges: np.ndarray) -> _Attachment:
    """Read and check one attachment; its position snaps onto a segment boundary or an end
    within ``1e-14 L`` (the float sums of the segment lengths)."""
    kind = _kind(item)
    x = float(_get(item, "x"))
    near = np.abs(edges - x) <= _SNAP_EDGE * length
    if np.any(near):
        x = float(edges[np.argmax(near)])
    if not 0.0 <= x <= length:
        raise ValueError(f"{kind} needs 0 <= x <= L = {length}, got x = {x}")
    if kind in ("spring_mass", "oscillator_chain"):
        ks, ms = _get(item, "k"), _get(item, "m")
        ks, ms = (tuple(float(v) for v in (q if kind != "spring_mass" else [q])) for q in (ks, ms))
        if not ks or len(ks) != len(ms) or not all(v > 0 for v in ks + ms):
            raise ValueError(f"{kind} needs k > 0, m > 0 (lists of one length): {ks}, {ms}")
        c = _opt(item, "c", None)
        if c is None:
            cs = (0.0,) * len(ks)
        else:
            cs = tuple(float(v) for v in ([c] if kind == "spring_mass" else c))
        if len(cs) != len(ks) or not all(v >= 0 for v in cs):
            raise ValueError(f"{kind} needs c >= 0 parallel to each spring: {cs}")
        return _Attachment("chain", x, ks, ms, cs)
    if kind == "dashpot":
        c = float(_get(item, "c"))
        if not c >= 0:
            raise ValueError(f"dashpot needs c >= 0, got {c}")
        return _Attachment(kind, x, (), (), (c,))
    if kind == "mass":
        m, inertia = float(_get(item, "m")), float(_opt(item, "J", 0.0))
        if not (m >= 0 and inertia >= 0):
            raise ValueError(f"mass needs m >= 0, J >= 0: {m}, {inertia}")
        return _Attachment(kind, x, (), (m, inertia))
    if kind == "support":
        return _Attachment(kind, x)
    k = float(_opt(item, "k", 0.0) if kind == "hinge" else _get(item, "k"))
    if not (k > 0 or (kind == "hinge" and k == 0)):
        raise ValueError(f"{kind} needs k > 0 (a hinge k >= 0), got {k}")
    if kind == "hinge" and not 0.0 < x < length:
        raise ValueError(f"a hinge must be strictly inside the beam, got x = {x}")
    return _Attachment(kind, x, (k,))


def _model(scene: Any) -> _Model:
    """Read the duck-typed ``scene`` (object or TOML-layout mapping) and check it."""
    beam = _get(scene, "beam")
    raw = _opt(beam, "segments", None)
    if raw:
        segments = tuple(
            tuple(float(_get(s, key)) for key in ("length", "EI", "mass_per_length")) for s in raw
        )
    else:
        segments = (tuple(float(_get(beam, key)) for key in ("length", "EI", "mass_per_length")),)
    for length, ei, mbar in segments:
        if not (length > 0 and ei > 0 and mbar > 0):
            raise ValueError(
                f"beam length, EI, mass_per_length must be > 0: {length}, {ei}, {mbar}"
            )
    if raw:
        if _opt(beam, "loss_factor", None) not in (None, 0, 0.0):  # a Scene's Beam has a 0
            raise ValueError("loss_factor on a stepped beam: give it on each segment")
        loss = tuple(float(_opt(s, "loss_factor", 0.0)) for s in raw)
    else:
        loss = (float(_opt(beam, "loss_factor", 0.0)),)
    if not all(v >= 0 for v in loss):
        raise ValueError(f"loss_factor must be >= 0: {loss}")
    if raw:
        for key in _PHYSICS:
            if _opt(beam, key, None) not in (None, 0, 0.0):  # a Scene's Beam has a 0
                raise ValueError(f"{key} on a stepped beam: give it on each segment")
    physics = tuple(
        tuple(float(_opt(s, key, 0.0)) for key in _PHYSICS) for s in (raw if raw else [beam])
    )
    for values in physics:
        named = dict(zip(_PHYSICS, values, strict=True))
        if not all(math.isfinite(v) for v in values) or any(
            named[key] < 0 for key in ("kappa_GA", "rho_I", "foundation_k", "foundation_kG")
        ):
            raise ValueError(
                f"kappa_GA, rho_I, foundation_k, foundation_kG must be >= 0 and axial_force "
                f"finite: {named}"
            )
    ends = (str(_get(beam, "left")), str(_get(beam, "right")))
    for end in ends:
        if end not in _REMOVED:
            raise ValueError(f"unknown end condition {end!r}; expected one of {sorted(_REMOVED)}")
    total = math.fsum(s[0] for s in segments)
    edges = np.concatenate([[0.0], np.cumsum([s[0] for s in segments])])
    edges[-1] = total
    try:
        items = _get(scene, "attachments")
    except (KeyError, AttributeError):
        items = ()
    attachments = tuple(_attachment(item, total, edges) for item in items or ())
    hinges = [a.x for a in attachments if a.kind == "hinge"]
    if len(set(hinges)) != len(hinges):
        raise ValueError(f"one hinge per point, got hinges at {sorted(hinges)}")
    for a in attachments:
        turns = a.kind == "rotational_spring" or (a.kind == "mass" and a.m[1] > 0)
        if turns and a.x in hinges:
            raise ValueError(
                f"rotational spring or rotary inertia at the hinge at x = {a.x}: ambiguous"
            )
    if not any(any(v != 0 for v in values) for values in physics):
        physics = ()  # plain Euler-Bernoulli: the matrices of the original model, bit for bit
    return _Model(total, segments, ends[0], ends[1], attachments, loss, physics)


def _undamped(model: _Model) -> _Model:
    """The undamped functions refuse a damped scene rather than drop its damping."""
    if model.damped:
        raise ValueError(
            "the scene has damping (c > 0 or loss_factor > 0): use the damped_* functions"
        )
    return model


def _nodes(model: _Model, n_elements: int, extra: tuple = ()) -> np.ndarray:
    """Uniform mesh with a node exactly at every attachment and segment boundary (and at
    the ``extra`` positions, snapped like the attachments)."""
    if int(n_elements) != n_elements or n_elements < 1:
        raise ValueError(f"n_elements must be a positive integer, got {n_elements!r}")
    n = int(n_elements)
    length = model.length
    h = length / n
    uniform = np.linspace(0.0, length, n + 1)
    uniform[-1] = length
    movable = np.ones(n + 1, dtype=bool)  # interior uniform nodes not yet moved
    movable[[0, -1]] = False
    inserted = []
    for x in sorted({a.x for a in model.attachments} | set(model.boundaries[1:-1]) | set(extra)):
        i = min(max(round(x / h), 0), n)
        if uniform[i] == x:
            movable[i] = False
        elif movable[i] and abs(uniform[i] - x) < _SNAP * h:
            uniform[i] = x
            movable[i] = False
        else:
            inserted.append(x)
    return np.unique(np.concatenate([uniform, inserted]))


def mesh(scene: Any, n_elements: int) -> np.ndarray:
    """Node positions (ascending, from 0 to L) of the mesh :func:`assemble` uses."""
    return _nodes(_model(scene), n_elements)


class _Springs:
    """Point stiffnesses and masses gathered as sparse triplets, and the rows of ``G``."""

    def __init__(self) -> None:
        self.k: list[tuple[int, int, float]] = []
        self.m: list[tuple[int, int, float]] = []
        self.c: list[tuple[int, int, float]] = []
        self.g: list[tuple[int, int, float]] = []  # (row, dof, value), rows from 0
        self.rows = 0

    def spring(self, p: int, q: int | None, k: float) -> None:
        """A spring ``k`` between DOFs p and q (q None: to ground)."""
        self.k.append((p, p, k))
        self.g.append((self.rows, p, math.sqrt(k)))
        if q is not None:
            self.k += [(q, q, k), (p, q, -k), (q, p, -k)]
            self.g.append((self.rows, q, -math.sqrt(k)))
        self.rows += 1

    def mass(self, p: int, m: float) -> None:
        self.m.append((p, p, m))

    def dashpot(self, p: int, q: int | None, c: float) -> None:
        """A dashpot ``c`` between DOFs p and q (q None: to ground)."""
        self.c.append((p, p, c))
        if q is not None:
            self.c += [(q, q, c), (p, q, -c), (q, p, -c)]


def _matrices(
    model: _Model, nodes: np.ndarray, scale: float = 1.0
) -> tuple[scipy.sparse.csr_matrix, scipy.sparse.csr_matrix, scipy.sparse.csr_matrix]:
    """``K``, ``M`` and a factor ``G`` with ``K = G^T diag(sign) G`` on ``nodes`` (``sign = 1``
    but on the rows of an axial compression: ``K = G^T G`` without one), after the end
    conditions (see :func:`_system`)."""
    system = _system(model, nodes, scale)
    return system.K, system.M, system.G


@dataclass(frozen=True)
class _Assembled:
    """The matrices of :func:`_system` and where the DOFs sit (indices after the end
    conditions; -1: removed)."""

    K: scipy.sparse.csr_matrix
    M: scipy.sparse.csr_matrix
    G: scipy.sparse.csr_matrix
    C: scipy.sparse.csr_matrix  # dashpots
    eta: np.ndarray  # loss factor of each row of G (0 for the springs' and the axial rows)
    y: np.ndarray  # Y of each node
    theta: np.ndarray  # theta of each node (-2 at a hinge: theta- and theta+ differ)
    masses: np.ndarray  # each hanging mass, attachments sorted by x (stable), chain outwards
    scale: float  # the rotation DOFs are scale * theta
    sign: np.ndarray | None = None  # sign of each row of G (None: all +1, K = G^T G)


#: Gauss-Legendre points and weights on [0, 1]: 3 points integrate the products of
#: quadratics (``w'``, ``psi``, ``w' - psi``) exactly, 4 those of cubics (``w``).
_GAUSS = {
    n: ((x + 1.0) / 2.0, w / 2.0)
    for n, (x, w) in ((n, np.polynomial.legendre.leggauss(n)) for n in (3, 4))
}


def _hermite(xi: np.ndarray, h: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Cubic Hermite ``N`` and ``dN/dx`` (DOFs ``Y_i, slope_i, Y_j, slope_j``) at the points
    ``xi`` of [0, 1] of elements of lengths ``h``: arrays (elements, points, 4)."""
    x, L = xi[None, :], h[:, None]
    one = np.ones_like(x * L)
    N = [1 - 3 * x**2 + 2 * x**3, L * (x - 2 * x**2 + x**3), 3 * x**2 - 2 * x**3, L * (x**3 - x**2)]
    dN = [(6 * x**2 - 6 * x) / L, 1 - 4 * x + 3 * x**2, (6 * x - 6 * x**2) / L, 3 * x**2 - 2 * x]
    return np.stack([f * one for f in N], axis=-1), np.stack([f * one for f in dN], axis=-1)


def _element_rows(h: np.ndarray, timoshenko: bool) -> dict[str, np.ndarray]:
    """For each field ``v``, the rows ``r`` (elements, Gauss points, element DOFs) giving
    ``sqrt(W_g h) v(xi_g)`` from the element's DOFs ``d``, so that ``integral f v^2 dx =
    f |r d|^2`` exactly for a constant ``f``: ``w`` (4 points), ``dw`` (``w'``), ``psi``
    (the section rotation) and, on a Timoshenko element, ``shear`` (``w' - psi``), 3 points.

    Euler-Bernoulli element: DOFs ``Y_i, theta_i, Y_j, theta_j``, ``w`` cubic Hermite,
    ``psi = w'``.  Timoshenko element: DOFs ``Y_i, psi_i, Y_j, psi_j, s_i, s_j, b``: ``w``
    the cubic Hermite of ``Y_i, s_i, Y_j, s_j`` (``s``: the slope ``w'`` at the element's
    ends, internal, discontinuous between elements), ``psi`` quadratic,
    ``(1 - xi) psi_i + xi psi_j + 4 xi (1 - xi) b``.
    """
    x4, w4 = _GAUSS[4]
    x3, w3 = _GAUSS[3]
    N4, _ = _hermite(x4, h)
    N3, dN3 = _hermite(x3, h)
    r4 = np.sqrt(w4[None, :, None] * h[:, None, None])
    r3 = np.sqrt(w3[None, :, None] * h[:, None, None])
    if not timoshenko:
        return {"w": r4 * N4, "dw": r3 * dN3, "psi": r3 * dN3}
    ne = h.size
    order = [0, 4, 2, 5]  # Hermite DOFs Y_i, s_i, Y_j, s_j in the element's 7
    w, dw = np.zeros((ne, 4, 7)), np.zeros((ne, 3, 7))
    w[:, :, order] = N4
    dw[:, :, order] = dN3
    psi = np.zeros((ne, 3, 7))
    psi[:, :, 1] = 1 - x3
    psi[:, :, 3] = x3
    psi[:, :, 6] = 4 * x3 * (1 - x3)
    return {"w": r4 * w, "dw": r3 * dw, "psi": r3 * psi, "shear": r3 * (dw - psi)}


def _system(model: _Model, nodes: np.ndarray, scale: float = 1.0) -> _Assembled:
    """``K``, ``M``, a factor ``G`` with ``K = G^T diag(sign) G`` and the dashpots' ``C`` on
    ``nodes``, after the end conditions.  With loss factors the complex stiffness is
    ``K* = G^T diag(sign + i eta) G`` (each element's rows carry its segment's eta, but
    the rows of the axial force, a load, none).

    DOF order as :func:`assemble`; the rotation DOFs are ``scale * theta``
    (``scale = 1``: physical ``theta``; the solvers use the uniform element
    length, which balances the element matrices).  ``G`` has two rows per
    Euler-Bernoulli element, ``sqrt(EI h)`` times the mean curvature ``(theta_j - theta_i) / h``
    and ``sqrt(EI h / 12)`` times the curvature change
    ``(12 (Y_i - Y_j) / h + 6 (theta_i + theta_j)) / h``, then two per Timoshenko element
    (the same of ``psi' = (psi_j - psi_i) / h + 4 (1 - 2 xi) b / h``), then the rows of the
    other energy terms at the Gauss points (:func:`_element_rows`): ``sqrt(kGA)`` times
    the shear strain ``w' - psi``, ``sqrt(k_w) w``, ``sqrt(k_G) w'``, ``sqrt(|P|) w'`` (sign
    -1 for a compression ``P < 0``), then one row ``sqrt(k) (p - q)`` per spring between
    DOFs p and q (q = 0 for a spring to ground): the strain energy is
    ``v^T G^T diag(sign) G v / 2``.  ``M`` is the consistent mass: ``mbar w^2`` and
    ``rho_I psi^2`` (``rho_I w'^2`` on an Euler-Bernoulli element) integrated exactly.
    """
    h = np.diff(nodes)
    ne = h.size
    at = [int(np.searchsorted(nodes, a.x)) for a in model.attachments]
    assert np.array_equal(nodes[at], [a.x for a in model.attachments])
    hinge = np.zeros(ne + 1, dtype=int)
    hung = np.zeros(ne + 1, dtype=int)
    for a, i in zip(model.attachments, at, strict=True):
        hinge[i] += a.kind == "hinge"
        hung[i] += len(a.m) if a.kind == "chain" else 0

    # Element properties: the segment holding the element's midpoint.
    seg = np.searchsorted(model.boundaries[1:-1], 0.5 * (nodes[:-1] + nodes[1:]))
    ei = np.array([s[1] for s in model.segments])[seg]
    mbar = np.array([s[2] for s in model.segments])[seg]
    physics = np.array(model.physics if model.physics else [(0.0,) * 5] * len(model.segments))
    kga, rhoi, axial, kw, kg = physics[seg].T
    timo = kga > 0
    eb = ~timo
    # Node i's DOFs: Y, theta (theta- and theta+ at a hinge), its hanging masses, then the
    # internal DOFs s_i, s_j, b of element i when it is a Timoshenko element.
    size = 2 + hinge + hung + 3 * np.append(timo, False)
    first = np.concatenate([[0], np.cumsum(size)[:-1]])
    ndof = int(size.sum())
    theta_left, theta_right = first + 1, first + 1 + hinge
    inner = first + 2 + hinge + hung  # element i's internal DOFs, when it has them

    one = np.ones_like(h[eb])
    he = h[eb]
    # Element matrices, shape (ne, 4, 4), DOF order Y_i, theta_i, Y_j, theta_j.
    ke = (
        np.array(
            [
                [12 * one, 6 * he, -12 * one, 6 * he],
                [6 * he, 4 * he**2, -6 * he, 2 * he**2],
                [-12 * one, -6 * he, 12 * one, -6 * he],
                [6 * he, 2 * he**2, -6 * he, 4 * he**2],
            ]
        ).transpose(2, 0, 1)
        * (ei[eb] / he**3)[:, None, None]
    )
    me = (
        np.array(
            [
                [156 * one, 22 * he, 54 * one, -13 * he],
                [22 * he, 4 * he**2, 13 * he, -3 * he**2],
                [54 * one, 13 * he, 156 * one, -22 * he],
                [-13 * he, -3 * he**2, -22 * he, 4 * he**2],
            ]
        ).transpose(2, 0, 1)
        * (mbar[eb] * he / 420.0)[:, None, None]
    )
    ge = np.array(
        [
            [0 * one, -one, 0 * one, one] * np.sqrt(ei[eb] / he),
            [2 / he, one, -2 / he, one] * np.sqrt(3 * ei[eb] / he),
        ]
    ).transpose(2, 0, 1)  # (ne, 2, 4)
    dofs_all = np.stack([first[:-1], theta_right[:-1], first[1:], theta_left[1:]], axis=1)
    dofs = dofs_all[eb]
    ne_eb = int(np.count_nonzero(eb))
    rows = np.broadcast_to(dofs[:, :, None], (ne_eb, 4, 4)).ravel()
    cols = np.broadcast_to(dofs[:, None, :], (ne_eb, 4, 4)).ravel()

    # The other energy terms, as rows (values (elements, rows, DOFs), DOFs, eta, sign).
    loss = np.array(model.loss if model.loss else (0.0,) * len(model.segments))[seg]
    stiff: list[tuple[np.ndarray, np.ndarray, np.ndarray, float]] = []
    mass: list[tuple[np.ndarray, np.ndarray]] = []
    for is_timo in (False, True):
        pick = timo if is_timo else eb
        if not np.any(pick):
            continue
        r = _element_rows(h[pick], is_timo)
        d = dofs_all[pick]
        if is_timo:
            d = np.concatenate([d, inner[:-1][pick, None] + np.arange(3)], axis=1)
            hp, root = h[pick], np.sqrt(ei[pick] * h[pick])
            bend = np.zeros((hp.size, 2, 7))
            bend[:, 0, 1], bend[:, 0, 3] = -root / hp, root / hp
            bend[:, 1, 6] = -8 * root / (np.sqrt(12.0) * hp)
            stiff.append((bend, d, loss[pick], 1.0))
            stiff.append((r["shear"] * np.sqrt(kga[pick])[:, None, None], d, loss[pick], 1.0))
            mass.append((r["w"] * np.sqrt(mbar[pick])[:, None, None], d))
        for f, field, eta, sign in (
            (kw, "w", loss, 1.0),
            (kg, "dw", loss, 1.0),
            (np.maximum(axial, 0.0), "dw", 0 * loss, 1.0),
            (np.maximum(-axial, 0.0), "dw", 0 * loss, -1.0),
        ):
            on = f[pick] > 0
            if np.any(on):
                values = r[field][on] * np.sqrt(f[pick][on])[:, None, None]
                stiff.append((values, d[on], eta[pick][on], sign))
        on = rhoi[pick] > 0
        if np.any(on):
            mass.append((r["psi"][on] * np.sqrt(rhoi[pick][on])[:, None, None], d[on]))

    point = _Springs()
    next_mass = first + 2 + hinge
    removed = [first[0] + d for d in _REMOVED[model.left]]
    removed += [first[-1] + d for d in _REMOVED[model.right]]
    hung_dofs = []  # (node, dof) of each hanging mass, in scene order
    for a, i in zip(model.attachments, at, strict=True):
        y = int(first[i])
        if a.kind == "chain":
            prev = y
            for k, m, c in zip(a.k, a.m, a.c, strict=True):
                dof = int(next_mass[i])
                next_mass[i] += 1
                point.spring(prev, dof, k)
                point.mass(dof, m)
                if c > 0:
                    point.dashpot(prev, dof, c)
                hung_dofs.append((int(i), dof))
                prev = dof
        elif a.kind == "dashpot":
            if a.c[0] > 0:
                point.dashpot(y, None, a.c[0])
        elif a.kind == "mass":
            point.mass(y, a.m[0])
            if a.m[1] > 0:
                point.mass(int(theta_left[i]), a.m[1])
        elif a.kind == "spring":
            point.spring(y, None, a.k[0])
        elif a.kind == "rotational_spring":
            point.spring(int(theta_left[i]), None, a.k[0])
        elif a.kind == "hinge":
            if a.k[0] > 0:
                point.spring(int(theta_left[i]), int(theta_right[i]), a.k[0])
        else:  # support
            removed.append(y)

    def triplets(entries):
        return [np.array([e[c] for e in entries], dtype=float if c == 2 else int) for c in range(3)]

    def stacked(blocks):
        """``(rows, cols, values, count)`` of the blocks' rows, numbered from 0."""
        r, c, v, count = [], [], [], 0
        for values, d, *_ in blocks:
            n_el, n_rows, n_dofs = values.shape
            number = count + np.arange(n_el * n_rows).reshape(n_el, n_rows)
            r.append(np.broadcast_to(number[:, :, None], values.shape).ravel())
            c.append(np.broadcast_to(d[:, None, :], values.shape).ravel())
            v.append(values.ravel())
            count += n_el * n_rows
        return r, c, v, count

    kr, kc, kv = triplets(point.k)
    mr, mc, mv = triplets(point.m)
    cr, cc, cv = triplets(point.c)
    K = _sparse([rows, kr], [cols, kc], [ke.ravel(), kv], (ndof, ndof))
    M = _sparse([rows, mr], [cols, mc], [me.ravel(), mv], (ndof, ndof))
    C = _sparse([cr], [cc], [cv], (ndof, ndof))
    sr, sc, sv, n_extra = stacked(stiff)
    extra_sign = np.concatenate(
        [np.full(v[0].shape[0] * v[0].shape[1], v[3]) for v in stiff] or [np.zeros(0)]
    )
    extra_eta = np.concatenate([np.repeat(v[2], v[0].shape[1]) for v in stiff] or [np.zeros(0)])
    if stiff:
        E = _sparse(sr, sc, sv, (n_extra, ndof))
        K = (K + E.T @ scipy.sparse.diags(extra_sign) @ E).tocsr()
    if mass:
        br, bc, bv, n_mass = stacked(mass)
        B = _sparse(br, bc, bv, (n_mass, ndof))
        M = (M + B.T @ B).tocsr()
    g_rows = np.broadcast_to(2 * np.arange(ne_eb)[:, None, None] + [[0], [1]], (ne_eb, 2, 4))
    g_cols = np.broadcast_to(dofs[:, None, :], (ne_eb, 2, 4))
    gr, gc, gv = triplets(point.g)
    G = _sparse(
        [g_rows.ravel(), *(2 * ne_eb + x for x in sr), 2 * ne_eb + n_extra + gr],
        [g_cols.ravel(), *sc, gc],
        [ge.ravel(), *sv, gv],
        (2 * ne_eb + n_extra + point.rows, ndof),
    )

    keep = np.setdiff1d(np.arange(ndof), removed)
    dof_scale = np.ones(ndof)
    dof_scale[theta_left] = 1.0 / scale
    dof_scale[theta_right] = 1.0 / scale
    for j in range(3):
        dof_scale[inner[:-1][timo] + j] = 1.0 / scale
    D = scipy.sparse.diags(dof_scale[keep])
    K = (D @ K[keep][:, keep] @ D).tocsr()
    M = (D @ M[keep][:, keep] @ D).tocsr()
    G = (G[:, keep] @ D).tocsr()
    C = (D @ C[keep][:, keep] @ D).tocsr()
    for A in (K, M, G, C):
        A.sort_indices()
    eta = np.concatenate([np.repeat(loss[eb], 2), extra_eta, np.zeros(point.rows)])
    sign = np.concatenate([np.ones(2 * ne_eb), extra_sign, np.ones(point.rows)])
    new = np.full(ndof, -1)
    new[keep] = np.arange(keep.size)
    theta = np.where(hinge > 0, -2, new[theta_left])
    hung = sorted(hung_dofs, key=lambda pair: pair[0])  # stable: scene order at one node
    masses = new[np.array([dof for _, dof in hung], dtype=int)]
    return _Assembled(
        K, M, G, C, eta, new[first], theta, masses, scale, sign if np.any(sign < 0) else None
    )


def _sparse(rows, cols, values, shape: tuple[int, int]) -> scipy.sparse.csr_matrix:
    """CSR matrix summing ``values`` at ``(rows, cols)``, each a list of pieces."""
    r, c = (np.concatenate([np.asarray(p, dtype=int).ravel() for p in x]) for x in (rows, cols))
    v = np.concatenate([np.asarray(p, dtype=float).ravel() for p in values])
    return scipy.sparse.coo_matrix((v, (r, c)), shape=shape).tocsr()


def assemble(
    scene: Any, n_elements: int
) -> tuple[scipy.sparse.csr_matrix, scipy.sparse.csr_matrix]:
    """Global stiffness ``K`` and mass ``M`` (sparse CSR) after the end conditions.

    DOF order: node by node left to right (nodes as :func:`mesh`), ``Y`` and
    ``theta`` (rad; ``theta-``, ``theta+`` at a hinge) of the node followed by
    the displacements of the masses hung there (scene order, each chain from
    the beam to its tip), then, when the element to the node's right is a Timoshenko
    element, its internal DOFs ``s_i``, ``s_j``, ``b`` (rad; see the module docstring);
    the DOFs the end conditions and supports fix are removed.
    """
    model = _undamped(_model(scene))
    K, M, _ = _matrices(model, _nodes(model, n_elements))
    return K, M


def _omega(lam: np.ndarray, model: _Model) -> np.ndarray:
    """Frequencies from eigenvalues ``omega**2``; round-off around rigid-body zeros becomes 0.
    An eigenvalue < 0 beyond that: ValueError (buckled)."""
    lam = np.sort(np.asarray(lam, dtype=float))
    tiny = np.abs(lam) < _ZERO * model.scale
    if np.any(lam[~tiny] < 0):
        raise ValueError(_BUCKLED.format(what=f"eigenvalue omega^2 = {lam[~tiny].min():.6g}"))
    return np.sqrt(np.where(tiny, 0.0, lam))


_BUCKLED = (
    "the beam is buckled: the axial compression exceeds the critical load ({what} < 0, "
    "the stiffness K is indefinite)"
)


def _upper_band(A: scipy.sparse.spmatrix) -> np.ndarray:
    """Upper band storage (``scipy.linalg.cholesky_banded``) of the symmetric ``A``."""
    coo = scipy.sparse.triu(A).tocoo()
    u = int(np.max(coo.col - coo.row))
    ab = np.zeros((u + 1, A.shape[0]))
    ab[u + coo.row - coo.col, coo.col] = coo.data
    return ab


def _band_to_sparse(cb: np.ndarray) -> scipy.sparse.csr_matrix:
    """The upper triangular ``U`` stored in band form ``cb``, as a sparse matrix."""
    u, n = cb.shape[0] - 1, cb.shape[1]
    return scipy.sparse.diags([cb[u - d, d:] for d in range(u + 1)], range(u + 1), (n, n)).tocsr()


class _ShiftInvert:
    """``x -> (K - sigma M)^{-1} x``, ``sigma < 0``: banded Cholesky and iterative refinement.

    The residual is computed as ``x - G^T (sign G y) + sigma M y``.  Its rounding
    errors are small relative perturbations of ``G`` (first and second
    differences of the DOFs), to which the low eigenvalues are insensitive
    (relative error ~ eps times the number of elements), while the rounding
    errors of a factorization of ``K`` act like perturbations of ``K`` itself,
    which the fourth-order operator amplifies by its condition number (~
    eps times the fourth power of the number of elements).  ``sign`` (None: all +1) is
    -1 on the rows of an axial compression; ``K - sigma M`` is then positive definite
    only if ``sigma`` is below the lowest eigenvalue: if its Cholesky factorization fails,
    the lowest eigenvalue is below ``sigma < 0``, the beam is buckled (ValueError).
    """

    def __init__(self, K, M, G, sigma: float, max_steps: int = 40, sign=None) -> None:
        self.M, self.G, self.GT, self.sigma = M, G, G.T.tocsr(), sigma
        self.sign = sign
        try:
            self.factor = (scipy.linalg.cholesky_banded(_upper_band(K - sigma * M)), False)
        except np.linalg.LinAlgError:
            if sign is None:
                raise
            raise ValueError(_BUCKLED.format(what=f"the lowest omega^2 < {sigma:.6g}")) from None
        self.max_steps = max_steps
        self.steps: list[int] = []  # refinement steps taken, per call

    def stiffness(self, y: np.ndarray) -> np.ndarray:
        """``K y`` through ``G``."""
        Gy = self.G @ y
        if self.sign is not None:
            Gy = Gy * (self.sign[:, None] if Gy.ndim == 2 else self.sign)
        return self.GT @ Gy

    def __call__(self, x: np.ndarray) -> np.ndarray:
        y = scipy.linalg.cho_solve_banded(self.factor, x)
        previous, steps = np.inf, 0
        while True:
            residual = x - self.stiffness(y) + self.sigma * (self.M @ y)
            d = scipy.linalg.cho_solve_banded(self.factor, residual)
            size = np.max(np.abs(d)) / max(np.max(np.abs(y)), np.finfo(float).tiny)
            if size < np.finfo(float).eps:
                y = y + d
                break
            if not size < 0.5 * previous:  # stagnated: round-off level, unless large
                if size > _REFINED:
                    raise FloatingPointError(_TOO_FINE.format(size=size))
                break
            y, previous, steps = y + d, size, steps + 1
            if steps > self.max_steps:
                if size > _REFINED:
                    raise FloatingPointError(_TOO_FINE.format(size=size))
                break
        self.steps.append(steps)
        return y


def _mass_factor(M: scipy.sparse.csr_matrix) -> scipy.sparse.csr_matrix:
    """``U`` (rows: the DOFs with mass, ``diag M > 0``) with ``M = U^T U``: the banded
    Cholesky factor of ``M`` restricted to those DOFs.  ``M`` is singular exactly when a
    Timoshenko element has no rotary inertia (``rho_I = 0``): its rotations ``psi`` and
    ``b`` have no mass, their rows and columns of ``M`` are 0 (infinite eigenvalues)."""
    massive = np.flatnonzero(M.diagonal() > 0)
    if massive.size == M.shape[0]:
        return _band_to_sparse(scipy.linalg.cholesky_banded(_upper_band(M)))
    U = _band_to_sparse(scipy.linalg.cholesky_banded(_upper_band(M[massive][:, massive])))
    P = scipy.sparse.csr_matrix(
        (np.ones(massive.size), (np.arange(massive.size), massive)), (massive.size, M.shape[0])
    )
    return (U @ P).tocsr()


def _eigenvalues(system: _Assembled, n_modes: int, solver: str, model: _Model) -> np.ndarray:
    """Lowest ``n_modes`` eigenvalues ``omega**2`` of ``K v = omega**2 M v``, ascending."""
    K, M, G, sign = system.K, system.M, system.G, system.sign
    ndof = K.shape[0]
    finite = int(np.count_nonzero(M.diagonal() > 0))  # eigenvalues (the others infinite)
    if int(n_modes) != n_modes or not 1 <= n_modes <= finite:
        raise ValueError(
            f"n_modes must be an integer in [1, {finite}] for this mesh, got {n_modes}"
        )
    n_modes = int(n_modes)
    # Shift below the spectrum: K - sigma M is positive definite even with rigid modes
    # (with a compression: unless the beam is buckled, see _ShiftInvert).
    sigma = -model.scale
    if solver == "dense":
        U = _mass_factor(M)  # M = U^T U
        S = U @ _ShiftInvert(K, M, G, sigma, sign=sign)(U.T.toarray())  # U (K - sM)^-1 U^T
        S = 0.5 * (S + S.T)
        n = S.shape[0]
        theta = scipy.linalg.eigh(S, subset_by_index=(n - n_modes, n - 1), eigvals_only=True)
        return np.sort(sigma + 1.0 / theta)
    if solver == "sparse":
        if n_modes >= finite - 1:  # ARPACK needs n_modes < n - 1
            return _eigenvalues(system, n_modes, "dense", model)
        op = _ShiftInvert(K, M, G, sigma, sign=sign)
        v0 = np.random.default_rng(0).standard_normal(finite)  # reproducible, generic
        if finite < ndof:  # the standard problem U (K - sigma M)^-1 U^T, M = U^T U
            U = _mass_factor(M)
            UT = U.T.tocsr()
            S = scipy.sparse.linalg.LinearOperator(
                (finite, finite), matvec=lambda x: U @ op(UT @ x), dtype=float
            )
            theta = scipy.sparse.linalg.eigsh(
                S, n_modes, which="LA", v0=v0, return_eigenvectors=False, tol=0
            )
            return np.sort(sigma + 1.0 / theta)
        opinv = scipy.sparse.linalg.LinearOperator(K.shape, matvec=op, dtype=float)
        lam = scipy.sparse.linalg.eigsh(
            K,
            n_modes,
            M,
            sigma=sigma,
            OPinv=opinv,
            which="LM",
            v0=v0,
            return_eigenvectors=False,
            tol=0,
        )
        return np.sort(lam)
    if solver == "svd":  # omega = singular values of G R^-1, M = R^T R
        if sign is not None or finite < ndof:
            raise ValueError(
                'solver="svd" needs K = G^T G and M positive definite: not with an axial '
                "compression nor a Timoshenko segment without rho_I (use dense or sparse)"
            )
        R = scipy.linalg.cholesky(M.toarray())
        s = scipy.linalg.svdvals(scipy.linalg.solve_triangular(R, G.toarray().T, trans="T"))
        s = np.sort(np.concatenate([s, np.zeros(max(ndof - s.size, 0))]))
        return s[:n_modes] ** 2
    if solver == "eigh":  # textbook: LAPACK on K, M (accuracy ~ eps * cond(K))
        if finite < ndof:
            raise ValueError(
                'solver="eigh" needs M positive definite: not with a Timoshenko segment '
                "without rho_I (use dense or sparse)"
            )
        return scipy.linalg.eigh(
            K.toarray(), M.toarray(), subset_by_index=(0, n_modes - 1), eigvals_only=True
        )
    raise ValueError(f"solver must be one of {_SOLVERS}, got {solver!r}")


def _solve(model: _Model, nodes: np.ndarray, n_modes: int, solver: str) -> np.ndarray:
    system = _system(model, nodes, scale=model.length / (nodes.size - 1))
    return _omega(_eigenvalues(system, n_modes, solver, model), model)


def frequencies(scene: Any, n_modes: int, n_elements: int, solver: str = "dense") -> np.ndarray:
    """Lowest ``n_modes`` FE natural frequencies (rad/s, ascending, rigid-body zeros included).

    ``solver`` is ``"dense"`` (LAPACK on the shift-inverted problem),
    ``"sparse"`` (ARPACK shift-invert), ``"svd"`` or ``"eigh"``; see the module
    docstring.  Eigenvalues within ``1e-12`` of the lowest elastic scale
    (``EI / (mbar L^4)`` or the smallest ``k / m``) are reported as 0.  A buckled beam
    (an axial compression beyond the critical load): ValueError.
    """
    model = _undamped(_model(scene))
    return _solve(model, _nodes(model, n_elements), n_modes, solver)


def richardson(
    scene: Any, n_modes: int, n_elements: int, solver: str = "dense", order: int = 4
) -> np.ndarray:
    """Frequencies extrapolated from the ``n_elements`` mesh and its bisection (rad/s).

    ``omega_R = omega_2n + (omega_2n - omega_n) / (2**order - 1)``.  The fine
    mesh bisects every element of the coarse one, so the two are similar and
    the ``h**order`` term cancels exactly (the fine mesh may differ from the one
    ``frequencies(scene, n_modes, 2 * n_elements)`` uses when attachments split
    elements).
    """
    if not order > 0:
        raise ValueError(f"order must be > 0, got {order!r}")
    model = _undamped(_model(scene))
    coarse = _nodes(model, n_elements)
    fine = np.sort(np.concatenate([coarse, 0.5 * (coarse[:-1] + coarse[1:])]))
    w = [_solve(model, nodes, n_modes, solver) for nodes in (coarse, fine)]
    return w[1] + (w[1] - w[0]) / (2.0**order - 1.0)


def count_below(scene: Any, omega: float, n_elements: int) -> int:
    """Number of FE frequencies strictly below ``omega`` (rad/s).

    Sylvester's law of inertia: the count of negative eigenvalues of
    ``K - omega^2 M``, read from its ``LDL^T`` factorization
    (``scipy.linalg.ldl``, Bunch-Kaufman).  The FE eigenvalues are upper bounds
    of the exact ones, so this is at most the exact count.  The count is
    exact for the FE model unless ``omega**2`` lies within round-off
    (``~ eps * cond(K)``, as for ``solver="eigh"``) of an FE eigenvalue.  With an axial
    compression the beam is first checked not to be buckled (the lowest eigenvalue, as
    :func:`frequencies`): ValueError if it is.
    """
    model = _undamped(_model(scene))
    nodes = _nodes(model, n_elements)
    system = _system(model, nodes, scale=model.length / (nodes.size - 1))
    if model.compressed:
        _omega(_eigenvalues(system, 1, "sparse", model), model)  # ValueError if buckled
    if not omega > 0:
        return 0
    A = (system.K - float(omega) ** 2 * system.M).toarray()
    _, D, _ = scipy.linalg.ldl(A, lower=True)
    return _negative_inertia(D)


def _negative_inertia(D: np.ndarray) -> int:
    """Negative eigenvalues of the block diagonal (1x1 and 2x2 blocks) ``D``."""
    n = D.shape[0]
    count = 0
    i = 0
    while i < n:
        if i + 1 < n and D[i + 1, i] != 0.0:
            a, b, c = D[i, i], D[i + 1, i], D[i + 1, i + 1]
            # a 2x2 Bunch-Kaufman pivot is indefinite (det < 0): one negative eigenvalue
            det = a * c - b * b
            count += 1 if det < 0 else (2 if a + c < 0 and det > 0 else 0)
            i += 2
        else:
            count += D[i, i] < 0
            i += 1
    return int(count)


# --------------------------------------------------------------------- damping


class _QuadraticSolve:
    """``X -> Q(s)^{-1} X`` for ``Q(s) = K* + s C + s^2 M``
    (``K* = G^T diag(sign + i eta) G``): dense LU and iterative refinement whose residual
    takes the stiffness through ``G`` (see :class:`_ShiftInvert`: the residual's round-off
    is then a small relative perturbation of the curvatures, not of ``K``, which the
    fourth-order operator would amplify by ``~n**4``)."""

    def __init__(self, system: _Assembled, s: complex, max_steps: int = 40) -> None:
        self.G, self.GT = system.G, system.G.T.tocsr()
        self.lossy = bool(np.any(system.eta > 0))
        sign = 1.0 if system.sign is None else system.sign
        self.factor = sign + 1j * system.eta if self.lossy else system.sign
        self.C, self.M, self.s = system.C, system.M, s
        Q = system.K + s * system.C + s * s * system.M
        if self.lossy:
            Q = Q + 1j * (self.GT @ scipy.sparse.diags(system.eta) @ self.G)
        self.real = not self.lossy and complex(s).imag == 0
        dense = Q.toarray()
        self.lu = scipy.linalg.lu_factor(dense.real if self.real else dense.astype(complex))
        self.max_steps = max_steps

    def apply(self, X: np.ndarray) -> np.ndarray:
        GX = self.G @ X
        if self.factor is not None:
            GX = GX * (self.factor[:, None] if X.ndim == 2 else self.factor)
        s = self.s.real if self.real else self.s
        return self.GT @ GX + s * (self.C @ X) + s * s * (self.M @ X)

    def __call__(self, B: np.ndarray) -> np.ndarray:
        X = scipy.linalg.lu_solve(self.lu, B)
        previous, steps = np.inf, 0
        while True:
            D = scipy.linalg.lu_solve(self.lu, B - self.apply(X))
            size = np.max(np.abs(D)) / max(np.max(np.abs(X)), np.finfo(float).tiny)
            if size < np.finfo(float).eps:
                return X + D
            if not size < 0.5 * previous or steps > self.max_steps:
                if size > _REFINED:
                    raise FloatingPointError(_TOO_FINE.format(size=size))
                return X
            X, previous, steps = X + D, size, steps + 1


def _order(w: np.ndarray) -> np.ndarray:
    """Indices sorting roots: overdamped (w_d = 0) by sigma first, then by w_d, sigma."""
    axis = w.real == 0
    return np.lexsort((w.imag, np.where(axis, 0.0, w.real), ~axis))


class DampedSpectrum(tuple):
    """``(roots, n_zero, n_rigid)``: every FE root with ``w_d >= 0`` other than the zeros
    (complex, rad/s, :func:`damped_frequencies`' order), the number of eigenvalues at
    ``w = 0`` and the rigid-body modes (``dim null K``)."""

    __slots__ = ()

    def __new__(cls, roots, n_zero, n_rigid):
        return super().__new__(cls, (roots, n_zero, n_rigid))

    roots = property(lambda self: self[0])
    n_zero = property(lambda self: self[1])
    n_rigid = property(lambda self: self[2])


def _spectrum(model: _Model, nodes: np.ndarray) -> DampedSpectrum:
    """All eigenvalues of the state-space form, shift-inverted.

    With ``s = i w``, ``(K* + s C + s^2 M) v = 0`` is ``A z = s B z``,
    ``A = [[0, I], [-K*, -C]]``, ``B = [[I, 0], [0, M]]``, ``z = (v, s v)``.  The
    eigenvalues ``mu`` of ``T = (A - s0 B)^{-1} B`` are ``1 / (s - s0)``; with
    ``Q = Q(s0)``, ``T = [[-X1, -X2], [I - s0 X1, -s0 X2]]``, ``X1 = Q^{-1} (C + s0 M)``,
    ``X2 = Q^{-1} M``.  The shift ``s0 = sqrt(scale)`` (real > 0, no eigenvalue there for a
    passive scene) makes the low eigenvalues the dominant ones of T (accurate relative
    to themselves, ~1e-13 at 128 elements); the Jordan blocks of the rigid-body zeros
    split by ~sqrt(eps) |s0|, below the 1e-6 tolerance that reports them as zeros.
    Without a loss factor everything is real: overdamped roots come out exactly on the
    imaginary axis, pairs exactly as ``w, -conj w``.

    DOFs without mass (the rotations of a Timoshenko element without ``rho_I``; no
    dashpot acts on them): the columns of T of their velocities are 0, those states are
    dropped (T is block triangular), and of the remaining ``n + n_m`` eigenvalues the
    ``2 n_m`` largest ``|mu|`` are kept (``n_m`` DOFs with mass), the others being the
    ``s = infinity`` of the massless DOFs.
    """
    h = model.length / (nodes.size - 1)
    system = _system(model, nodes, scale=h)
    n = system.K.shape[0]
    s0 = math.sqrt(model.scale)
    solve = _QuadraticSolve(system, s0)
    CM = (system.C + s0 * system.M).toarray()
    X1 = solve(CM)
    X2 = solve(system.M.toarray())
    T = np.block([[-X1, -X2], [np.eye(n) - s0 * X1, -s0 * X2]])
    massive = system.M.diagonal() > 0
    n_m = int(np.count_nonzero(massive))
    if n_m < n:
        states = np.concatenate([np.ones(n, dtype=bool), massive])
        T = T[states][:, states]
    mu = scipy.linalg.eigvals(T)
    if n_m < n:
        mu = mu[np.argsort(-np.abs(mu), kind="stable")[: 2 * n_m]]
    mu = mu[mu != 0]
    s = s0 + 1.0 / mu
    w = s.imag - 1j * s.real  # w = -i s, exactly
    zero = np.abs(w) < 1e-6 * s0
    w = w[~zero]
    w = w[w.real >= 0]
    n_rigid = int(
        np.count_nonzero(_solve(model, nodes, min(n_m, 2 + _hinges(model)), "dense") == 0)
    )
    return DampedSpectrum(w[_order(w)], int(np.count_nonzero(zero)), n_rigid)


def _hinges(model: _Model) -> int:
    return sum(a.kind == "hinge" for a in model.attachments)


def damped_spectrum(scene: Any, n_elements: int) -> DampedSpectrum:
    """Every FE root of the damped scene with ``w_d >= 0`` (rad/s), see :func:`_spectrum`."""
    model = _model(scene)
    return _spectrum(model, _nodes(model, n_elements))


def damped_assemble(scene: Any, n_elements: int):
    """``(K*, C, M)`` (sparse, complex ``K* = sum (1 + i eta_e) K_e`` + springs), the DOF
    order of :func:`assemble`; ``(K* + i w C - w^2 M) X = F`` in the frequency domain."""
    model = _model(scene)
    system = _system(model, _nodes(model, n_elements))
    K = system.K + 1j * (system.G.T @ scipy.sparse.diags(system.eta) @ system.G)
    return K.tocsr(), system.C, system.M


def damped_frequencies(scene: Any, n_modes: int, n_elements: int) -> np.ndarray:
    """Lowest ``n_modes`` complex FE natural frequencies ``w = w_d + i sigma`` (rad/s).

    Damping: a dashpot ``c`` parallel to each spring of a spring-mass / chain (``c``,
    a list for a chain) between its DOFs, grounded dashpots (kind ``dashpot``) on the
    node's ``Y``, and a loss factor per segment (``loss_factor``; on the beam for a
    uniform one): the element stiffness times ``(1 + i eta)``, for ``w_d > 0``.  The
    eigenvalues of the state-space form (:func:`_spectrum`, ``scipy.linalg.eigvals``)
    with ``w_d >= 0``, ordered: the ``dim null K`` rigid-body zeros, the overdamped
    roots (``w_d = 0``) by ascending sigma, then by ascending ``w_d``.
    """
    spectrum = damped_spectrum(scene, n_elements)
    out = np.concatenate([np.zeros(spectrum.n_rigid, dtype=complex), spectrum.roots])
    if not 1 <= n_modes <= out.size:
        raise ValueError(f"n_modes must be in [1, {out.size}] for this mesh, got {n_modes}")
    return out[:n_modes]


def damped_richardson(scene: Any, n_modes: int, n_elements: int, order: int = 4) -> np.ndarray:
    """:func:`damped_frequencies` extrapolated from the ``n_elements`` mesh and its
    bisection, ``w_R = w_2n + (w_2n - w_n) / (2**order - 1)`` (complex; the error of the
    damped roots is ``O(h**4)`` too, see tests/test_fem_damped.py).  The two meshes must
    order their roots alike (same overdamped ones): else ValueError."""
    model = _model(scene)
    coarse = _nodes(model, n_elements)
    fine = np.sort(np.concatenate([coarse, 0.5 * (coarse[:-1] + coarse[1:])]))
    w = []
    for nodes in (coarse, fine):
        spectrum = _spectrum(model, nodes)
        w.append(np.concatenate([np.zeros(spectrum.n_rigid, complex), spectrum.roots])[:n_modes])
    if w[0].size != n_modes or not np.array_equal(w[0].real == 0, w[1].real == 0):
        raise ValueError("the two meshes disagree on the overdamped roots")
    return w[1] + (w[1] - w[0]) / (2.0**order - 1.0)


def frf(scene: Any, input: tuple, output: tuple, omegas, n_elements: int) -> np.ndarray:
    """FE receptance of ``output`` to a unit harmonic ``input`` (``exp(i w t)``) at each
    ``omegas`` (rad/s): ``(K* + i w C - w^2 M) X = F`` solved directly (LU with the
    refinement of :class:`_QuadraticSolve`), a node placed at every input / output x.
    ``input``: ``("force", "x", x)`` on the node's Y, ``("moment", "x", x)`` on its theta
    (positive work on a positive rotation), ``("force", "mass", j)``; ``output``:
    ``("displacement", "x", x)``, ``("rotation", "x", x)``, ``("displacement", "mass", j)``
    (hanging masses by x, stable, chains outwards).  A load on a removed DOF gives 0; a
    moment or rotation at a hinge is ambiguous: ValueError.
    """
    model = _model(scene)
    specs = [tuple(input), tuple(output)]
    edges = model.boundaries
    extra = []
    for quantity, where, at in specs:
        if where == "x":
            x = float(at)
            near = np.abs(edges - x) <= _SNAP_EDGE * model.length
            extra.append(float(edges[np.argmax(near)]) if np.any(near) else x)
            if not 0.0 <= extra[-1] <= model.length:
                raise ValueError(f"{quantity} position {x} outside [0, L]")
    nodes = _nodes(model, n_elements, tuple(extra))
    system = _system(model, nodes, scale=model.length / (nodes.size - 1))
    if model.compressed:
        _omega(_eigenvalues(system, 1, "sparse", model), model)  # ValueError if buckled
    dofs, factors = [], []
    points = iter(extra)
    for quantity, where, at in specs:
        if where == "mass":
            if int(at) != at or not 0 <= at < system.masses.size:
                raise ValueError(f"hanging mass {at!r} of {system.masses.size}")
            dofs.append(int(system.masses[int(at)]))
            factors.append(1.0)
            continue
        i = int(np.searchsorted(nodes, next(points)))
        if quantity in ("force", "displacement"):
            dofs.append(int(system.y[i]))
            factors.append(1.0)
        elif quantity in ("moment", "rotation"):
            if system.theta[i] == -2:
                raise ValueError(f"{quantity} at the hinge at x = {nodes[i]}: ambiguous")
            dofs.append(int(system.theta[i]))
            factors.append(1.0 / system.scale)  # theta = DOF / scale; work C theta
        else:
            raise ValueError(f"unknown quantity {quantity!r}")
    out = []
    n = system.K.shape[0]
    for w in np.atleast_1d(np.asarray(omegas, dtype=complex)):
        if dofs[0] < 0 or dofs[1] < 0:
            out.append(0j)
            continue
        load = np.zeros(n, dtype=complex)
        load[dofs[0]] = factors[0]
        x = _QuadraticSolve(system, 1j * complex(w))(load)
        out.append(x[dofs[1]] * factors[1])
    return np.array(out)

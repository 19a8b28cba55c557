"""A point component in descriptor form, and what every generic stage derives from it.

A point component (docs/components.md, section 2) adds unknowns ``q`` (n_q) and
constraints on the beam state ``Z = [Y, theta, M, Q]`` (units L = EI_0 = mbar_0 = 1,
``b4 = beta^4`` the squared frequency)::

    Cz Z + Cq q = 0          (n_c rows: geometric equations, paper Eq. (3))
    Z+ = A Z + B q           (the jump it causes: paper Eq. (2))

From this, once and for every kind:

* the point matrix ``P = A - B Cq^-1 Cz`` and its pole factor ``det Cq`` (paper Eq. (1)
  style, for ``show`` and ``symbolic``);
* the pole-free compound step of the stable chain: for ``v = a ^ b`` and
  ``n_q = n_c = 1``, ``v+ = Cq C2(A) v + (A i_Cz v) ^ B`` with
  ``i_Cz (a ^ b) = (Cz a) b - (Cz b) a``; it equals ``Cq C2(P) v`` where Cq != 0 and
  is the constrained map where Cq = 0: the pole factor is taken out exactly once;
* the internal frequencies (zeros of ``det Cq`` in ``b4``), extra scan nodes.

A kind that stores or dissipates energy declares only that: its stiffness, damping and
mass matrices over ``[Y, theta, q...]`` (:class:`Energy`); :func:`from_energy` derives
its descriptor, so that the masses of the modal and effective masses, the count's
pivots, the own frequencies and the jumps all come from the one declaration.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from mstmm.physics.energy import MOVES, Energy  # noqa: F401 (declared at run time)

from .compound import PAIRS, second_compound

#: The squared frequency in the kernel's units: beta^4 = mbar_0 omega^2 L^4 / EI_0.
b4 = sp.Symbol("b4", nonnegative=True)
#: The frequency itself in those units, ``w1 = omega L^2 sqrt(mbar_0 / EI_0)`` (b4 = w1^2):
#: a dashpot's force is ``i w1 gamma`` times its displacement (time dependence exp(i w t));
#: complex in a damped kernel, where b4 is printed as w1^2.
w1 = sp.Symbol("w1")


@dataclass(frozen=True)
class Descriptor:
    """``Cz Z + Cq q = 0``, ``Z+ = A Z + B q``; ``qmass[j]`` is the mass (units mbar_0 L)
    moving with ``q[j]`` (0 for a reaction or a rotation)."""

    Cz: sp.Matrix
    Cq: sp.Matrix
    A: sp.Matrix
    B: sp.Matrix
    qmass: tuple
    #: The mass of each q that a rigid translation of the beam carries (the q's share of
    #: the participation in a base translation, and what makes it a hanging mass whose
    #: displacement a mode shape reports): ``qmass`` itself when not given (every q with
    #: a mass a translation), 0 for a rotary inertia.
    qpart: tuple | None = None
    #: What a unit force on each q adds to minus its row (the row is ``-f`` times the
    #: q's equation of motion ``D_q u = F``): 1 when the rows are minus the equations of
    #: motion (not given), ``1/kappa`` for a spring-mass's row divided by its coupling.
    #: The frequency response puts a force on a hanging mass through it.
    qforce: tuple | None = None
    #: The mass each q shares with the beam's own ``(Y, theta)``: ``(M_Yq, M_thetaq)`` of
    #: the kind's energy (an inerter between the beam and the q), 0 when not given. The
    #: modal mass adds ``2 (M_Yq Y + M_thetaq theta) q``.
    qcouple: tuple | None = None
    #: The mass matrix on the beam's own ``[Y, theta]`` (rows 0-1, 2 x 2) and the
    #: participation row the couplings add (row 2: the sum of ``M_(q, [Y, theta])`` over
    #: the q's a rigid translation carries), so that a base translation's participation is
    #: ``R^T M u``: 3 x 2. Not given: :func:`point_inertia` of ``A`` (a kind in descriptor
    #: form) and a zero row.
    inertia: sp.Matrix | None = None

    @property
    def n_q(self) -> int:
        return self.B.cols

    def __post_init__(self) -> None:
        if self.A.shape != (4, 4) or self.B.rows != 4 or self.Cz.cols != 4:
            raise ValueError("descriptor: A is 4x4, B has 4 rows, Cz 4 columns")
        if self.Cq.shape != (self.Cz.rows, self.B.cols) or len(self.qmass) != self.B.cols:
            raise ValueError("descriptor: Cq is n_c x n_q and qmass has n_q entries")
        if self.Cz.rows != self.B.cols:
            raise ValueError("descriptor: as many constraints as unknowns (n_c = n_q)")
        if self.qpart is None:
            object.__setattr__(self, "qpart", tuple(self.qmass))
        if len(self.qpart) != self.B.cols:
            raise ValueError("descriptor: qpart has n_q entries")
        if self.qforce is None:
            object.__setattr__(self, "qforce", (1,) * self.B.cols)
        if len(self.qforce) != self.B.cols:
            raise ValueError("descriptor: qforce has n_q entries")
        if self.qcouple is None:
            object.__setattr__(self, "qcouple", ((0, 0),) * self.B.cols)
        if len(self.qcouple) != self.B.cols or any(len(c) != 2 for c in self.qcouple):
            raise ValueError("descriptor: qcouple has n_q pairs (M_Yq, M_thetaq)")
        if self.inertia is not None and self.inertia.shape != (3, 2):
            raise ValueError("descriptor: inertia is 3 x 2 (M on [Y, theta], participation)")


def kind_source(module) -> str:
    """How a refusal names a kind: its name and its file."""
    where = getattr(module, "__file__", None) or module.__name__
    return f"kind {getattr(module, 'KIND', module.__name__)!r} ({where})"


def refusal(module, reason) -> ValueError:
    """The one-line ValueError that refuses a kind's declaration, naming its file."""
    return ValueError(f"{kind_source(module)}: {reason}")


def positive(expr) -> bool:
    """Whether ``expr`` is free of the frequency and positive for every positive value of
    its symbols (the scene keys, the units): a constant sign the derivation can rely on."""
    expr = sp.sympify(expr).doit()
    if expr.has(b4, w1):
        return False
    taken = expr.subs({s: sp.Dummy(positive=True) for s in expr.free_symbols})
    return sp.simplify(taken).is_positive is True


def _check_carried(e: Energy, qpart: tuple) -> None:
    """What the run time reads of each unknown's ``qpart`` (a hanging mass where it is
    positive: ``mass_Y``, ``displacement:mass=J``, a force on it reaching the beam's
    shear; a rotary inertia where it is 0 with a mass) must be what the energy says of
    it: an unknown a translation carries has a positive share, or no mass at all (a
    massless node); one a rotation carries has none."""
    for j, moves in enumerate(e.moves):
        share = qpart[j]
        if moves == "Y" and not positive(share):
            if share != 0 or any(sp.expand(v) != 0 for v in e.M[2 + j, :]):
                raise ValueError(
                    f"energy: q{j} moves with Y but the mass a rigid translation carries"
                    f" with it, (R^T M)_q{j} = {share}, is not positive"
                )
        if moves == "theta" and share != 0:
            raise ValueError(
                f"energy: q{j} moves with theta but a rigid translation carries mass with"
                f" it, (R^T M)_q{j} = {share}"
            )


def _rigid(e: Energy, dof: str) -> sp.Matrix:
    """The rigid motion of the beam carrying ``dof`` (``Y`` or ``theta``) over u."""
    return sp.Matrix([int(dof == "Y"), int(dof == "theta"), *(int(m == dof) for m in e.moves)])


def from_energy(e: Energy) -> Descriptor:
    """The descriptor of a kind declared by its energy (docs/components.md, section 2).

    With the dynamic stiffness ``D = K + i w1 C - b4 M`` (time dependence exp(i w t)):

    * the unknowns' equations of motion ``D_qb z + D_qq q = 0`` are the constraints
      (paper Eq. (3)), each row divided by its constant coupling to the beam (its first
      nonzero entry of ``K_qb``): a spring-mass's reads ``Y - (1 - mu b4/k) Y_m = 0``,
      free of any pole, and ``-Cq`` is its pivot ``D_qq / k`` in the count;
    * the force the kind puts on the beam is ``-R^T D u`` summed over the rigid motion R
      that carries Y (and the moment, over the one that carries theta): a spring's force
      on the beam and on its mass cancel in it, so the jump of Q is ``+ b4 mu Y_m``
      (paper Eq. (2)) without the difference ``k (Y_m - Y)`` of two large numbers.
      ``Q+ = Q + f``, ``M+ = M - m`` (the sign convention of paper Eq. (1)).
    """
    n_q = len(e.moves)
    D = (e.K + sp.I * w1 * e.C - b4 * e.M).applyfunc(sp.expand)
    f = _rigid(e, "Y").T * D
    m = _rigid(e, "theta").T * D
    A = sp.eye(4)
    B = sp.zeros(4, n_q)
    for c in range(2):
        A[3, c] = -f[c]
        A[2, c] = m[c]
    for j in range(n_q):
        B[3, j] = -f[2 + j]
        B[2, j] = m[2 + j]
    Cz, Cq = sp.zeros(n_q, 4), sp.zeros(n_q, n_q)
    qforce = []
    for i in range(n_q):
        coupling = [e.K[2 + i, c] for c in range(2) if e.K[2 + i, c] != 0]
        scale = coupling[0] if coupling else 1
        for c in range(2):
            Cz[i, c] = sp.expand(D[2 + i, c] / scale)
        for j in range(n_q):
            Cq[i, j] = sp.expand(D[2 + i, 2 + j] / scale)
        qforce.append(-1 / scale)  # row = (D_q u) / scale = -(-1/scale) D_q u
    qmass = tuple(e.M[2 + j, 2 + j] for j in range(n_q))
    qpart = tuple(sp.expand((_rigid(e, "Y").T * e.M)[2 + j]) for j in range(n_q))
    _check_carried(e, qpart)
    qcouple = tuple((sp.expand(e.M[0, 2 + j]), sp.expand(e.M[1, 2 + j])) for j in range(n_q))
    carried = sp.zeros(1, 2)
    for j in range(n_q):
        if e.moves[j] == "Y":
            carried += e.M[2 + j, :2]
    inertia = e.M[:2, :2].col_join(carried).applyfunc(sp.expand)
    A, B = A.applyfunc(sp.expand), B.applyfunc(sp.expand)
    return Descriptor(Cz, Cq, A, B, qmass, qpart, tuple(qforce), qcouple, inertia)


def _statically_condensed(e: Energy, X: sp.Matrix) -> sp.Matrix:
    """``T^T X T`` on ``[Y, theta]`` (simplified), ``T = [I; -K_qq^-1 K_qb]`` the motion of
    ``[Y, theta, q...]`` in which the unknowns follow the beam statically; for ``X = K``
    it is the static stiffness ``K_bb - K_bq K_qq^-1 K_qb``."""
    T = sp.eye(2)
    if e.moves:
        Kqq = e.K[2:, 2:]
        if sp.simplify(Kqq.det()) == 0:
            raise ValueError("energy: an unknown with no stiffness (a free mass) at omega = 0")
        T = T.col_join(-Kqq.inv() * e.K[2:, :2])
    return (T.T * X * T).applyfunc(sp.simplify)


def rigid_constraint(e: Energy) -> tuple:
    """The kinematic constraint a kind declared by its energy puts on the beam's rigid
    motions (``RIGID``): the static stiffness it adds on ``[Y, theta]`` with its unknowns
    free, ``Kc = K_bb - K_bq K_qq^-1 K_qb`` (a rigid motion stores no energy only where
    that vanishes): ``("Y",)`` for a grounded spring, ``("theta",)`` for a grounded
    rotational spring, ``()`` for a mass, a spring-mass or a torsional absorber (its
    unknowns follow the beam)."""
    Kc = _statically_condensed(e, e.K)
    if Kc[0, 1] != 0:
        raise ValueError("energy: a static stiffness coupling Y and theta has no RIGID flag")
    held = tuple(name for i, name in enumerate(("Y", "theta")) if Kc[i, i] != 0)
    if len(held) > 1:
        raise ValueError("energy: a static stiffness on both Y and theta has no RIGID flag")
    return held


def constraint(dofs: tuple) -> Descriptor:
    """A kind that holds freedoms of the beam (``CONSTRAINS``): one reaction per freedom,
    ``Y = 0`` with ``Q+ = Q + R`` (a support), ``theta = 0`` with ``M+ = M - R`` (the sign
    convention of paper Eq. (1), as :func:`from_energy`); ``Cq = 0``: its compound step is
    the constrained map."""
    index = {"Y": (0, 3, 1), "theta": (1, 2, -1)}
    n = len(dofs)
    Cz, B = sp.zeros(n, 4), sp.zeros(4, n)
    for j, dof in enumerate(dofs):
        at, reaction, sign = index[dof]
        Cz[j, at] = 1
        B[reaction, j] = sign
    return Descriptor(Cz=Cz, Cq=sp.zeros(n, n), A=sp.eye(4), B=B, qmass=(0,) * n)


def release(kappa) -> Descriptor:
    """A kind that lets the rotation jump by ``phi`` with a rotational spring ``kappa``
    across the jump (``RELEASES``, a hinge): ``M - kappa phi = 0`` (the moment on both
    sides is the spring's), ``theta+ = theta + phi``; ``kappa = 0`` a free hinge (its
    compound step is then the constrained map ``M = 0``)."""
    return Descriptor(Cz=unit(2).T, Cq=sp.Matrix([[-kappa]]), A=sp.eye(4), B=unit(1), qmass=(0,))


#: What a kind's damping connects, for the proved decay bound (``mstmm.decay_bound``):
#: nothing; the beam's Y to the ground; the beam to unknowns with a mass that a rigid
#: translation carries (or such unknowns to each other); anything else (a rotation, an
#: unknown without mass), where the proof does not apply.
DAMPERS = ("none", "grounded", "carried", "unproved")


def damper_class(e: Energy) -> str:
    """Which of :data:`DAMPERS` a kind's damping is, from its energy: where ``C`` is
    nonzero (symbolically: damping values are symbols) and what the unknowns it touches
    carry."""
    n = e.C.rows
    touched = {i for i in range(n) for j in range(n) if sp.expand(e.C[i, j]) != 0}
    if not touched:
        return "none"
    if 1 in touched:
        return "unproved"  # a rotational damper: the interpolation does not close
    qs = [i for i in touched if i >= 2]
    if not qs:
        return "grounded"
    if all(e.moves[i - 2] == "Y" and positive(_own_mass(e, i)) for i in qs):
        return "carried"
    return "unproved"


def _own_mass(e: Energy, i: int) -> sp.Expr:
    """The least kinetic energy (times 2) of the component's coordinates with ``u_i = 1``:
    the Schur complement of ``M_ii`` over the coordinates with a mass (0 when that block is
    singular). The proof's ``m >= m_a |q|^2`` needs it positive: ``M_qq`` for a hanging
    mass, ``m``, not ``m + b``, for the inerter absorber (``M_qq - b^2 / b``)."""
    n = e.M.rows
    rest = [r for r in range(n) if r != i and any(sp.expand(e.M[r, c]) != 0 for c in range(n))]
    if not rest:
        return e.M[i, i]
    R, m = e.M.extract(rest, rest), e.M.extract(rest, [i])
    if sp.simplify(R.det()) == 0:
        return sp.Integer(0)
    return sp.simplify(e.M[i, i] - (m.T * R.inv() * m)[0, 0])


def own_masses(e: Energy) -> tuple:
    """The own mass (:func:`_own_mass`) of each unknown a ``carried`` kind's damping moves,
    in the order of the unknowns (empty for any other class): the proved decay bound's
    ``2 c_j |q_a|^2 <= (2 c_j / m_a) m`` takes ``m_a`` from these, not from a key's unit
    (``mstmm.decay_bound``)."""
    if damper_class(e) != "carried":
        return ()
    n = e.C.rows
    qs = sorted({i for i in range(2, n) for j in range(n) if sp.expand(e.C[i, j]) != 0})
    return tuple(_own_mass(e, i) for i in qs)


def own_masses_of(module, values: dict) -> tuple:
    """A kind's :func:`own_masses` from its energy or its stage's (a stage's values for a
    kind of stages); none for a kind without a declared energy."""
    derived = _from_declared_energy(module, values, own_masses)
    return () if derived is None else derived


def damper_of(module, values: dict) -> str:
    """A kind's :func:`damper_class` from its energy or its stage's (``values`` with the
    damping values as symbols); a constraint has none; a kind in descriptor form says it
    with ``DAMPS`` (``("Y",)``: grounded), else ``unproved`` if it has damping keys."""
    derived = _from_declared_energy(module, values, damper_class)
    if derived is not None:
        return derived
    if hasattr(module, "CONSTRAINS") or hasattr(module, "RELEASES"):
        return "none"
    if tuple(getattr(module, "DAMPS", ())) == ("Y",):
        return "grounded"
    return "unproved" if any(k.damping for k in module.KEYS) else "none"


def damps_constraint(e: Energy) -> tuple:
    """The constraint a kind's damping puts on the beam's rigid motions at omega -> 0:
    its unknowns follow the beam statically and the damping of that motion, ``T^T C T``
    (:func:`_statically_condensed`), must vanish for a rigid motion to dissipate nothing:
    ``("Y",)`` for a grounded dashpot, ``()`` for a dashpot beside a spring-mass's spring
    (the mass follows the beam)."""
    Cc = _statically_condensed(e, e.C)
    if Cc[0, 1] != 0:
        raise ValueError("energy: a static damping coupling Y and theta has no DAMPS flag")
    return tuple(name for i, name in enumerate(("Y", "theta")) if Cc[i, i] != 0)


def _from_declared_energy(module, values: dict, derive):
    """``derive`` of the energy a kind declares (its own, or its stage's for a kind of
    stages), evaluated even inside the unevaluated derivation of ``show``; None for a
    kind that declares no energy (a constraint, a kind in descriptor form)."""
    declare = getattr(module, "energy", None) or getattr(module, "stage", None)
    if declare is None:
        return None
    with sp.evaluate(True):
        try:
            return derive(declare(values))
        except ValueError as err:
            raise refusal(module, err) from None


def damps_of(module, values: dict) -> tuple:
    """A kind's constraint on rigid motions at omega -> 0 by its damping: derived from its
    energy or its stage's (:func:`damps_constraint`), declared (``DAMPS``) only by a kind
    in descriptor form."""
    derived = _from_declared_energy(module, values, damps_constraint)
    return tuple(getattr(module, "DAMPS", ())) if derived is None else derived


def rigid_of(module, values: dict) -> tuple:
    """A kind's constraint on rigid motions: declared (``RIGID``), or derived from its
    physics: its energy (:func:`rigid_constraint`), the freedoms it holds, or a kink
    where a released rotation has no spring (``kink_if_free``)."""
    if hasattr(module, "CONSTRAINS"):
        return tuple(module.CONSTRAINS)
    if hasattr(module, "RELEASES"):
        return ("kink_if_free",)
    if hasattr(module, "RIGID") and not hasattr(module, "stage"):
        return tuple(module.RIGID)
    derived = _from_declared_energy(module, values, rigid_constraint)
    return () if derived is None else derived


def of(module, values: dict) -> Descriptor:
    """A kind's descriptor: declared (a constraint, or a kind in descriptor form), or
    derived from its declared energy (:func:`from_energy`; a kind of stages from the
    energy of its stages in series, :func:`chain_energy`; evaluated even inside the
    unevaluated derivation of ``show``: its matrices are small)."""
    try:
        if hasattr(module, "energy"):
            with sp.evaluate(True):
                return from_energy(module.energy(values))
        if hasattr(module, "stage"):
            with sp.evaluate(True):
                return from_energy(chain_energy(module, values))
    except ValueError as err:
        raise refusal(module, err) from None
    if hasattr(module, "CONSTRAINS"):
        return constraint(tuple(module.CONSTRAINS))
    if hasattr(module, "RELEASES"):
        return release(values[module.RELEASES[1]])
    return module.descriptor(values)


#: The chain condensed on the beam point by its elimination from the tip
#: (``mstmm.numerics.chain.chain_tip``): ``Y = u0 y``, ``Q+ = Q + g y``.
u0, g_tip = sp.symbols("chain_u0 chain_g")


def chain_reduced() -> Descriptor:
    """The descriptor of a kind of stages as its kernel's stable step and count use it:
    one unknown, the tip's ``y`` (``Cz = e_Y``, ``Cq = -u0``, ``B = g e_Q``), ``u0`` and
    ``g`` computed at run time from the stages (their number is data)."""
    return Descriptor(
        Cz=unit(0).T, Cq=sp.Matrix([[-u0]]), A=sp.eye(4), B=g_tip * unit(3), qmass=(0,)
    )


def stage_parts(e: Energy) -> tuple:
    """``(a, b, c, s1, m)`` of a stage declared over ``[u_(j-1), theta, u_j]``: its dynamic
    stiffness ``D = K + i w1 C - b4 M`` on ``[u_(j-1), u_j]`` is ``[[a, b], [b, c]]``,
    ``s1`` its column sum for ``u_j`` (the force a common translation of both nodes
    leaves: the inertia ``-b4 m``, without the difference of two stiffnesses) and ``m`` the
    node's mass. A stage must not touch theta, hold mass at ``u_(j-1)`` or ground it."""
    if len(e.moves) != 1 or e.moves[0] != "Y":
        raise ValueError("stage: one unknown u_j, carried by a translation")
    for X in (e.K, e.C, e.M):
        if any(X[1, c] != 0 for c in range(3)):
            raise ValueError("stage: its energy must not involve theta")
    if e.M[0, 0] != 0 or e.M[0, 2] != 0:
        raise ValueError("stage: its mass sits at its own node u_j")
    D = (e.K + sp.I * w1 * e.C - b4 * e.M).applyfunc(sp.expand)
    if sp.expand(D[0, 0] + D[2, 0]) != 0:
        raise ValueError("stage: a common translation of its nodes must not load u_(j-1)")
    s1 = sp.expand(D[0, 2] + D[2, 2])
    return D[0, 0], D[0, 2], D[2, 2], s1, e.M[2, 2]


def stage_values(values: dict, j: int) -> dict:
    """The values of stage j: the j-th entry of each of the kind's lists."""
    return {key: (v[j] if isinstance(v, (list, tuple)) else v) for key, v in values.items()}


def chain_energy(module, values: dict) -> Energy:
    """The energy of a kind of stages with its lists given (``show``, ``symbolic``): the
    stages' energies in series over ``[Y, theta, u_1 .. u_n]``."""
    n = len(values[module.SAME_LENGTH[0]])
    size = 2 + n
    K, C, M = sp.zeros(size, size), sp.zeros(size, size), sp.zeros(size, size)
    for j in range(n):
        e = module.stage(stage_values(values, j))
        at = (0 if j == 0 else 1 + j, 2 + j)  # u_(j-1), u_j
        for X, Y in ((K, e.K), (C, e.C), (M, e.M)):
            for r, R in ((0, at[0]), (2, at[1])):
                for c, Cc in ((0, at[0]), (2, at[1])):
                    X[R, Cc] += Y[r, c]
    return Energy(K, C, M, moves=("Y",) * n)


def point(A: sp.Matrix) -> Descriptor:
    """A component with no unknowns: ``Z+ = A Z``."""
    return Descriptor(sp.zeros(0, 4), sp.zeros(0, 0), A, sp.zeros(4, 0), ())


def unit(i: int) -> sp.Matrix:
    """The i-th unit column of the state space."""
    e = sp.zeros(4, 1)
    e[i] = 1
    return e


def point_matrix(d: Descriptor) -> tuple[sp.Matrix, sp.Expr]:
    """``P = A - B Cq^-1 Cz`` with its pole factor ``det Cq`` multiplied out: returns
    ``(det(Cq) P, det Cq)`` (for a constraint, ``Cq = 0``, P alone does not exist)."""
    if d.n_q == 0:
        return d.A, sp.Integer(1)
    det = sp.factor(d.Cq.det())
    adj = d.Cq.adjugate()
    return (det * d.A - d.B * adj * d.Cz).applyfunc(sp.expand), det


def _wedge(a: sp.Matrix, b: sp.Matrix) -> sp.Matrix:
    return sp.Matrix([a[i] * b[j] - a[j] * b[i] for i, j in PAIRS])


def _interior(v: sp.Matrix, c: sp.Matrix) -> sp.Matrix:
    """``i_c (a ^ b) = (c.a) b - (c.b) a`` as a linear map of the Pluecker vector v."""
    out = sp.zeros(4, 1)
    for a, (i, j) in enumerate(PAIRS):
        # e_i ^ e_j -> c_i e_j - c_j e_i
        out[j] += c[i] * v[a]
        out[i] -= c[j] * v[a]
    return out


def compound_step(d: Descriptor, v: sp.Matrix) -> sp.Matrix:
    """The pole-free compound step ``v -> v+`` of paper Eqs. (2)-(3) for one component."""
    C = second_compound(d.A)
    if d.n_q == 0:
        return C * v
    if d.n_q != 1:
        raise ValueError("the compound step needs n_q = n_c = 1 (reduce a chain first)")
    Cz = d.Cz.T
    return (d.Cq[0, 0] * C * v + _wedge(d.A * _interior(v, Cz), d.B[:, 0])).applyfunc(sp.expand)


def node_stiffness(d: Descriptor) -> tuple[sp.Expr, sp.Expr]:
    """``(k_Y, k_theta)`` of a component with no unknowns whose ``A = I + N`` only acts
    node-wise: ``Q+ = Q - k_Y Y``, ``M+ = M + k_theta theta`` (EI [W'''] = -k_Y W,
    EI [W''] = k_theta W')."""
    N = d.A - sp.eye(4)
    k_y, k_t = -N[3, 0], N[2, 1]
    N[3, 0] = 0
    N[2, 1] = 0
    if d.n_q or any(e != 0 for e in N):
        raise ValueError("not a node stiffness: A - I has entries besides (Q, Y), (M, theta)")
    return sp.expand(k_y), sp.expand(k_t)


def inertia_rows(d: Descriptor) -> sp.Matrix:
    """The 3 x 2 ``Descriptor.inertia`` of any descriptor: the mass matrix on the beam's own
    ``[Y, theta]`` and the participation row of the couplings (a kind declared by its
    energy: from its ``M``); a kind in descriptor form: :func:`point_inertia` of its ``A``
    and no couplings."""
    if d.inertia is not None:
        return d.inertia
    return point_inertia(d).col_join(sp.zeros(1, 2))


def point_inertia(d: Descriptor) -> sp.Matrix:
    """The mass matrix (units mbar_0 L, mbar_0 L^2, mbar_0 L^3) a component holds on the
    beam's own ``[Y, theta]`` in its ``A`` (a lumped mass and rotary inertia, paper Eq.
    (1)): ``Q+ = Q + b4 (M_YY Y + M_Yt theta)``, ``M+ = M - b4 (M_tY Y + M_tt theta)``, so
    ``M = [[A_QY, A_Qt], [-A_MY, -A_Mt]]`` differentiated by b4. The inertia of its
    unknowns ``q`` is ``qmass``, not this. ``A`` must be affine in b4, with b4 only in
    those four entries (an inertia force on Y or theta); else a ValueError."""
    A = d.A.applyfunc(sp.expand)
    dA = A.diff(b4)
    if dA.diff(b4) != sp.zeros(4, 4):
        raise ValueError("a component's A must be affine in b4 (its inertia a mass matrix)")
    for r in range(4):
        for c in range(4):
            if (r, c) not in ((3, 0), (3, 1), (2, 0), (2, 1)) and dA[r, c] != 0:
                raise ValueError(f"b4 in A[{r}, {c}]: not an inertia force on [Y, theta]")
    return sp.Matrix([[dA[3, 0], dA[3, 1]], [-dA[2, 0], -dA[2, 1]]])


def internal_b4(d: Descriptor) -> list[sp.Expr]:
    """The component's own squared frequencies (b4 where det Cq = 0), when they exist."""
    if d.n_q == 0:
        return []
    det = sp.expand(d.Cq.det())
    if not det.has(b4):
        return []
    return [r for r in sp.solve(det, b4)]

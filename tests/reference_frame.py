"""Independent high-precision reference model of plane frames (issue 43), in mpmath.

A frame is nodes in a plane and straight members between them; each member carries axial
(rod) motion and Euler-Bernoulli bending in the plane. Nothing here uses transfer
matrices or ``mstmm``:

* each member's exact dynamic stiffness in its own axes: the rod's
  ``EA mu / (L sin mu) [[cos mu, -1], [-1, cos mu]]`` (``mu = w L sqrt(mbar / EA)``) and
  the bending block of ``reference_model.segment_stiffness_matrix`` (the energy form,
  checked there against a numerical solve), scaled from xi = x / L units to SI;
* rotated to the global axes (X, Y, Theta per node) and assembled; a support holds node
  freedoms (their rows and columns are dropped); a node mass adds ``-w^2 m`` on X and Y and
  ``-w^2 J`` on Theta; a pinned member end gets a rotation of its own (the moment there is
  zero), so that no condensation changes the count;
* the natural frequencies below w are counted by Wittrick-Williams: ``J(w) = sum over
  members of their clamped-clamped frequencies below w (rod: floor(mu / pi); bending:
  i - (1 - (-1)^i sgn(1 - cos b cosh b)) / 2, i = floor(b / pi)) + s{K(w)}`` (negative
  pivots of K's LDL^T); each root is found by bisection on the count alone, so its
  multiplicity is the count's jump there, exactly (no determinant, no tolerance on a
  function value).

Sign convention: a member from node a to node b has its local x from a to b, local y
turned +90 degrees from it; Theta is counterclockwise, equal to dv/dx along a member.

Out of the plane (``Frame.motion = "out_of_plane"``, a grillage): each node moves along Z
(W) and turns about X and Y (ThetaX, ThetaY, right-handed); a member twists about its
local x (torsion: the rod's stiffness with GJ for EA and rho_Ip for mbar) and bends in its
local x-z plane. The textbook grillage transformation (e.g. Weaver and Gere, *Matrix
Analysis of Framed Structures*, the grid member): the node's rotation vector in the
member's axes is ``(c ThetaX + s ThetaY, -s ThetaX + c ThetaY)``, the first the twist,
the second the rotation about local y, which turns +z towards +x: the bending slope is
``dw/dx = -(-s ThetaX + c ThetaY)``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import mpmath
from mpmath import mp, mpf
from reference_model import _segment_stiffness, segment_stiffness_matrix


@dataclass(frozen=True)
class Member:
    """A straight member from node ``a`` to node ``b`` (SI): bending stiffness, axial
    stiffness, mass per length; ``pinned`` ends (a, b) carry no moment."""

    a: str
    b: str
    EI: float
    EA: float
    mbar: float
    pinned: tuple[bool, bool] = (False, False)
    GJ: float = 0.0
    rhoIp: float = 0.0
    #: The loss factor: EI and EA (GJ) times 1 + i eta (the model is then complex).
    eta: float = 0.0


@dataclass(frozen=True)
class Frame:
    """Nodes (name -> (x, y), m), members, the freedoms each supported node holds (name ->
    a string of ``x``, ``y``, ``t``) and node masses (name -> (m, J), kg and kg m^2)."""

    nodes: dict
    members: tuple
    held: dict = field(default_factory=dict)
    masses: dict = field(default_factory=dict)
    motion: str = "in_plane"
    #: Absorbers ``(node, k, m, c, (dx, dy))``: a mass m on a spring k and a dashpot c
    #: (N/m, kg, N s/m) at the node, moving along the unit vector (dx, dy) (out of the
    #: plane: along Z, the vector unused).
    absorbers: tuple = ()


def _freedoms(frame: Frame) -> tuple[dict, int]:
    """Index of each free global freedom: (node, 0..2) for X, Y, Theta and (member, end)
    for a pinned end's own rotation."""
    index: dict = {}
    letters = "zab" if frame.motion == "out_of_plane" else "xyt"  # out: W, ThetaX, ThetaY
    for name in frame.nodes:
        held = frame.held.get(name, "")
        for j, letter in enumerate(letters):
            if letter not in held:
                index[(name, j)] = len(index)
    for i, m in enumerate(frame.members):
        for end in (0, 1):
            if m.pinned[end]:
                index[(i, end)] = len(index)
    for j in range(len(frame.absorbers)):
        index[("absorber", j)] = len(index)
    return index, len(index)


def _rod(m: Member, L, w):
    """The rod's dynamic stiffness (2 x 2, SI) and its clamped-clamped count below w (None
    at a complex w)."""
    EA = m.EA * (1 + 1j * mpf(m.eta)) if m.eta else m.EA
    mu = w * L * mpmath.sqrt(mpf(m.mbar) / EA)
    c, s = mpmath.cos(mu), mpmath.sin(mu)
    f = EA * mu / (L * s)
    count = None if isinstance(w, mpmath.mpc) else int(mpmath.floor(mu / mp.pi))
    return [[f * c, -f], [-f, f * c]], count


def _basis(b, d: int, x):
    """The d-th derivatives at x of the bending solutions cos, sin, cosh, sinh of (b x)."""
    z = b * x
    f = b**d
    return [
        f * mpmath.cos(z + d * mp.pi / 2),
        f * mpmath.sin(z + d * mp.pi / 2),
        f * (mpmath.cosh(z) if d % 2 == 0 else mpmath.sinh(z)),
        f * (mpmath.sinh(z) if d % 2 == 0 else mpmath.cosh(z)),
    ]


def bending_energy(m: Member, L, w):
    """The bending dynamic stiffness (4 x 4 over v_a, theta_a, v_b, theta_b, SI) at any
    frequency, complex too, from the exact solutions of ``EI v^(4) = mbar w^2 v`` (cos,
    sin, cosh, sinh of b x): with ``A`` their end values and ``G_kl = [EI g_k^(2) g_l^(1) - EI
    g_k^(3) g_l]_0^L`` (by parts, ``int EI g_k^(2) g_l^(2) - mbar w^2 g_k g_l``), ``K = A^-T G
    A^-1``: the energy of the solution with the given end values. Another route than
    ``_bending`` (a closed form), which it equals at a real w."""
    EI = m.EI * (1 + 1j * mpf(m.eta)) if m.eta else m.EI
    b = mpmath.root(mpf(m.mbar) * w * w / EI, 4)
    A = mpmath.matrix(4, 4)
    for r, (d, x) in enumerate(((0, 0), (1, 0), (0, L), (1, L))):
        for k, v in enumerate(_basis(b, d, x)):
            A[r, k] = v
    G = mpmath.matrix(4, 4)
    for x, sign in ((L, 1), (0, -1)):
        g0, g1, g2, g3 = (_basis(b, d, x) for d in range(4))
        for k in range(4):
            for j in range(4):
                G[k, j] += sign * EI * (g2[k] * g1[j] - g3[k] * g0[j])
    Ai = A**-1
    K = Ai.T * G * Ai
    return [[(K[i, j] + K[j, i]) / 2 for j in range(4)] for i in range(4)]


def _bending(m: Member, L, w):
    """The bending dynamic stiffness (4 x 4 over v_a, theta_a, v_b, theta_b, SI) and its
    clamped-clamped count below w (``reference_model._segment_stiffness``)."""
    beta = L * mpmath.root(mpf(m.mbar) * w * w / m.EI, 4)
    K = segment_stiffness_matrix(beta, mpf(1))  # xi units: (W, dW/dxi), EI = L = 1
    d = [mpf(1), L, mpf(1), L]  # dW/dxi = L theta
    scale = m.EI / L**3
    K = [[scale * d[i] * K[i][j] * d[j] for j in range(4)] for i in range(4)]
    return K, _segment_stiffness(beta, beta**2, beta**3, mpf(1))[1]  # its count, J0


def dynamic_stiffness(frame: Frame, w) -> tuple:
    """``(K, J0)``: the assembled dynamic stiffness over the free freedoms at w (rad/s)
    (an mpmath matrix) and the members' clamped-clamped count below w."""
    w = mpmath.mpmathify(w)
    if any(m.eta for m in frame.members):  # complex stiffnesses: the complex path
        w = mpmath.mpc(w)
    index, n = _freedoms(frame)
    K = mpmath.zeros(n, n)
    J0 = 0
    for i, m in enumerate(frame.members):
        (xa, ya), (xb, yb) = frame.nodes[m.a], frame.nodes[m.b]
        dx, dy = mpf(xb) - xa, mpf(yb) - ya
        L = mpmath.sqrt(dx * dx + dy * dy)
        c, s = dx / L, dy / L
        out = frame.motion == "out_of_plane"
        if out:  # the twist: a rod of GJ and rho_Ip
            rod, ja = _rod(Member(m.a, m.b, m.EI, m.GJ, m.rhoIp, eta=m.eta), L, w)
        else:
            rod, ja = _rod(m, L, w)
        if isinstance(w, mpmath.mpc):  # a complex frequency: no count
            bend, J0 = bending_energy(m, L, w), None
        else:
            bend, jb = _bending(m, L, w)
            J0 += ja + jb
        # local freedoms (u_a, v_a, t_a, u_b, v_b, t_b) as global ones: (index, factor) pairs
        local = []
        for node in (m.a, m.b) if out else ():
            W, TX, TY = (index.get((node, j)) for j in range(3))
            local.append([(TX, c), (TY, s)])  # the twist
            local.append([(W, mpf(1))])  # w along Z
            local.append([(TX, s), (TY, -c)])  # dw/dx = -(rotation about local y)
        for end, node in ((0, m.a), (1, m.b)) if not out else ():
            X, Y = index.get((node, 0)), index.get((node, 1))
            local.append([(X, c), (Y, s)])  # u = c X + s Y
            local.append([(X, -s), (Y, c)])  # v = -s X + c Y
            t = index.get((i, end)) if m.pinned[end] else index.get((node, 2))
            local.append([(t, mpf(1))])
        k = [[mpf(0)] * 6 for _ in range(6)]
        for p, P in enumerate((0, 3)):
            for q, Q in enumerate((0, 3)):
                k[P][Q] += rod[p][q]
        for p, P in enumerate((1, 2, 4, 5)):
            for q, Q in enumerate((1, 2, 4, 5)):
                k[P][Q] += bend[p][q]
        for p in range(6):
            for q in range(6):
                if k[p][q] == 0:
                    continue
                for gi, fi in local[p]:
                    if gi is None:
                        continue
                    for gj, fj in local[q]:
                        if gj is not None:
                            K[gi, gj] += fi * k[p][q] * fj
    for name, (mass, inertia) in frame.masses.items():
        out = frame.motion == "out_of_plane"  # W; ThetaX and ThetaY
        for j, value in ((0, mass), (1, inertia if out else mass), (2, inertia)):
            g = index.get((name, j))
            if g is not None:
                K[g, g] -= w * w * value
    for j, (node, k, mass, c, (dx, dy)) in enumerate(frame.absorbers):
        q = index[("absorber", j)]
        z = k + 1j * w * c  # the spring and its dashpot: z (q - d . U)^2 / 2
        row = [(q, mpf(1))]
        along = ((0, 1),) if frame.motion == "out_of_plane" else ((0, dx), (1, dy))  # Z: W
        row += [(index[(node, a)], -f) for a, f in along if (node, a) in index]
        for gi, fi in row:
            for gj, fj in row:
                K[gi, gj] += z * fi * fj
        K[q, q] -= w * w * mass
    return K, J0


def damped_root(frame: Frame, w0: complex, dps: int = 30):
    """The damped natural frequency (mpc, rad/s) of the frame nearest w0: a zero of ``det
    K(w)`` by the secant method from w0 at ``dps`` digits (a start within a fraction of
    the roots' spacing, e.g. the value under test)."""
    with mp.workdps(dps):
        w0 = mpmath.mpc(w0)
        scale = mpmath.det(dynamic_stiffness(frame, w0 * (1 + mpf(10) ** -6))[0])

        def f(w):
            return mpmath.det(dynamic_stiffness(frame, w)[0]) / scale

        w = mpmath.findroot(f, (w0, w0 * (1 + mpf(10) ** -7)), solver="secant", verify=False)
        if abs(f(w)) > mpf(10) ** (12 - dps):  # |w - root| about 1e-6 |w| |f|
            raise ValueError(f"no root near {w0}: |det| = {abs(f(w))} at {w}")
        return w


def negative_pivots(K) -> int:
    """The number of negative eigenvalues of the symmetric K (Sylvester's law of inertia),
    from its block LDL^T with Bunch-Parlett pivoting: at each step the largest diagonal
    entry is the pivot if it is at least ``ALPHA`` times the largest off-diagonal one,
    else that off-diagonal entry's 2 x 2 block (whose determinant is then negative: one
    negative and one positive eigenvalue). Stable where elimination without pivoting is
    not: near a multiple root a tiny pivot would wipe out the rest (FV2's held centre)."""
    n = K.rows
    A = [[K[i, j] for j in range(n)] for i in range(n)]
    rest = list(range(n))
    negative = 0
    alpha = (1 + mpmath.sqrt(17)) / 8
    while rest:
        d = max(rest, key=lambda i: abs(A[i][i]))
        pairs = [(i, j) for a, i in enumerate(rest) for j in rest[a + 1 :]]
        p, q = max(pairs, key=lambda ij: abs(A[ij[0]][ij[1]])) if pairs else (d, d)
        if not pairs or abs(A[d][d]) >= alpha * abs(A[p][q]):
            pivot = A[d][d]
            if pivot == 0:  # the whole rest is zero: a root to working precision
                raise ZeroDivisionError("a singular K: move the trial frequency")
            negative += pivot < 0
            rest.remove(d)
            for i in rest:
                f = A[i][d] / pivot
                if f != 0:
                    for j in rest:
                        A[i][j] -= f * A[d][j]
            continue
        a, b, c = A[p][p], A[p][q], A[q][q]
        det = a * c - b * b  # < 0: |b| > |a|, |c| at this pivot
        negative += 1
        rest.remove(p)
        rest.remove(q)
        for i in rest:
            # [f_p, f_q] = [A_ip, A_iq] B^-1
            fp = (A[i][p] * c - A[i][q] * b) / det
            fq = (A[i][q] * a - A[i][p] * b) / det
            for j in rest:
                A[i][j] -= fp * A[p][j] + fq * A[q][j]
    return negative


def count_below(frame: Frame, w, dps: int = 30) -> int:
    """Natural frequencies of the frame below w (rad/s), by Wittrick-Williams."""
    with mp.workdps(dps):
        w = mpf(w)
        for _ in range(3):
            K, J0 = dynamic_stiffness(frame, w)
            try:
                return J0 + negative_pivots(K)
            except ZeroDivisionError:  # at a multiple root to working precision: the count
                w *= 1 + mpf(10) ** (5 - dps)  # just above it (far inside the bisection's
                # tolerance, 10^(8 - dps))
        raise ZeroDivisionError(f"zero pivots at {w} and just above it")


def frequencies(frame: Frame, n_modes: int, dps: int = 30) -> list[tuple]:
    """The distinct natural frequencies (rad/s, mpf) holding the lowest ``n_modes`` with
    their multiplicities: ``[(omega, multiplicity), ...]``, found by bisection on the count
    to a relative width of ``10^-(dps - 8)`` (the last may hold more than asked)."""
    with mp.workdps(dps):
        count = lambda w: count_below(frame, w, dps)  # noqa: E731
        hi = mpf(1)
        while count(hi) < n_modes:
            hi *= 2
        lo = hi / 2**60
        if count(lo) > 0:
            raise ValueError("a root below the lowest trial frequency (a rigid motion?)")
        tol = mpf(10) ** (8 - dps)
        found: list[tuple] = []

        def split(a, ca, b, cb) -> None:
            if cb == ca or (found and sum(m for _, m in found) >= n_modes):
                return
            if b - a <= tol * b:
                found.append(((a + b) / 2, cb - ca))
                return
            mid = (a + b) / 2
            cm = count(mid)
            split(a, ca, mid, cm)
            split(mid, cm, b, cb)

        split(lo, 0, hi, count(hi))
        return found


def nafems_fv2(held_centre: bool = False, axial_factor: float = 1.0) -> Frame:
    """NAFEMS FV2, the pin-ended double cross: eight arms of 5 m from the centre (0, 0),
    along the axes and the diagonals, square section 0.125 m, E = 200 GPa, rho = 8000
    kg/m^3; each arm's outer end pinned (x, y held). ``held_centre``: the centre's
    translations held too (the published values take the arms axially rigid, which holds
    it); ``axial_factor`` multiplies EA."""
    with mp.workdps(60):  # the data to 60 digits (12 is not a power of 2)
        E, rho, side, arm = mpf(200e9), mpf(8000), mpf(0.125), mpf(5)
        A = side * side
        EI = E * side**4 / 12
    nodes = {"O": (0.0, 0.0)}
    members = []
    held = {"O": "xy"} if held_centre else {}
    for k in range(8):
        name = f"P{k}"
        with mp.workdps(60):  # the arms' ends to 60 digits: each arm 5 m at any precision
            nodes[name] = (arm * mpmath.cos(k * mp.pi / 4), arm * mpmath.sin(k * mp.pi / 4))
        held[name] = "xy"
        members.append(Member("O", name, EI, E * A * axial_factor, rho * A))
    return Frame(nodes, tuple(members), held)


def sample_frames() -> dict:
    """An L-frame (clamped base, free tip), a portal frame (clamped feet, a heavier beam, a
    node mass with rotary inertia at a corner), a tree (three members at one node, one
    pinned to it at its end and pinned to the ground at the other) and a two-bay
    two-storey frame (closed loops, a roof mass)."""
    EI, EA, m = 2.0e3, 5.0e5, 3.0
    return {
        "L": Frame(
            {"A": (0, 0), "B": (0, 3.0), "C": (2.0, 3.0)},
            (Member("A", "B", EI, EA, m), Member("B", "C", EI, EA, m)),
            held={"A": "xyt"},
        ),
        "portal": Frame(
            {"A": (0, 0), "B": (0, 3.0), "C": (4.0, 3.0), "D": (4.0, 0)},
            (
                Member("A", "B", EI, EA, m),
                Member("B", "C", 2 * EI, EA, 1.5 * m),
                Member("D", "C", EI, EA, m),
            ),
            held={"A": "xyt", "D": "xyt"},
            masses={"C": (5.0, 0.7)},
        ),
        "tree": Frame(
            {"A": (0, 0), "B": (0, 2.0), "C": (1.5, 3.0), "D": (-1.0, 3.5)},
            (
                Member("A", "B", EI, EA, m),
                Member("B", "C", EI, EA, m, pinned=(True, False)),
                Member("B", "D", EI, EA, m),
            ),
            held={"A": "xyt", "C": "xy"},
        ),
        # two bays, two storeys: a closed frame with six loops' worth of redundancy
        "two_bay_two_storey": Frame(
            {
                **{f"G{j}": (4.0 * j, 0.0) for j in range(3)},
                **{f"F{j}": (4.0 * j, 3.0) for j in range(3)},
                **{f"R{j}": (4.0 * j, 6.0) for j in range(3)},
            },
            tuple(
                [Member(f"G{j}", f"F{j}", EI, EA, m) for j in range(3)]
                + [Member(f"F{j}", f"R{j}", 0.7 * EI, EA, m) for j in range(3)]
                + [Member(f"F{j}", f"F{j + 1}", 1.5 * EI, EA, 2 * m) for j in range(2)]
                + [Member(f"R{j}", f"R{j + 1}", 1.5 * EI, EA, 2 * m) for j in range(2)]
            ),
            held={f"G{j}": "xyt" for j in range(3)},
            masses={"R1": (10.0, 1.0)},
        ),
    }


def as_table(rf: Frame) -> dict:
    """A reference frame as a frame scene table (what a user writes)."""
    nodes = []
    for name, (x, y) in rf.nodes.items():
        node = {"name": name, "x": float(x), "y": float(y)}
        held = rf.held.get(name, "")
        if held:
            node["support"] = {"xyt": "fixed", "xy": "pinned", "zab": "fixed", "z": "pinned"}[held]
        if name in rf.masses:
            node["mass"], node["J"] = (float(v) for v in rf.masses[name])
        nodes.append(node)
    members = []
    for m in rf.members:
        member = {"start": m.a, "end": m.b, "EI": float(m.EI)}
        if rf.motion == "out_of_plane":
            member["GJ"], member["rho_Ip"] = float(m.GJ), float(m.rhoIp)
        else:
            member["EA"] = float(m.EA)
        member["mass_per_length"] = float(m.mbar)
        if m.eta:
            member["loss_factor"] = float(m.eta)
        for end, key in enumerate(("start_joint", "end_joint")):
            if m.pinned[end]:
                member[key] = "pinned"
        members.append(member)
    table = {"nodes": nodes, "members": members}
    if rf.absorbers:
        table["attachments"] = [
            {"type": "spring_mass", "node": node, "k": float(k), "m": float(m), "c": float(c)}
            for node, k, m, c, _ in rf.absorbers
        ]
        if rf.motion != "out_of_plane":
            for a, (*_, d) in zip(table["attachments"], rf.absorbers):
                a["direction"] = [float(d[0]), float(d[1])]
    if rf.motion == "out_of_plane":
        table["motion"] = "out_of_plane"
    return table

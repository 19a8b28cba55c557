"""Spring-mass branch: a point mass hung from the beam by a linear spring.

Paper Eq. (1) spring and lumped mass on ``[Y, Q]``; the branch hangs from a massless
rigid body on the beam; its tip (the free side of the mass) is ``Z = [Y_m, 0]``.
Declared by its energy (docs/components.md); its descriptor is derived:
``q = [Y_m]``, ``Cz = e_Y``, ``Cq = -(1 - mu b4 / kappa)``, ``A = I``, ``B = mu b4 e_Q``.
An optional dashpot ``c`` parallel to the spring makes its force ``(k + i w c)(Y_m - Y)``
(time dependence exp(i w t)).
SymPy is imported inside the functions: the catalog reads this file's keys without it.
"""

from __future__ import annotations

from mstmm.catalog import Key

KIND = "spring_mass"
DOC = "point mass m hung from the beam at x by a linear spring k"
KEYS = (
    Key("x", "m", check="position", doc="position from the left end"),
    Key("k", "N/m", doc="spring stiffness"),
    Key("m", "kg", doc="hanging mass"),
    Key(
        "c",
        "N s/m",
        check="nonnegative",
        default=0.0,
        doc="dashpot parallel to the spring",
        damping=True,
    ),
)
#: Its marker and colour in plots (matplotlib).
MARKER = ("v", "C4")
#: Name of its unknown in Z_all (the hanging mass's displacement, the branch tip).
UNKNOWNS = "Y_tip"


def energy(v: dict):
    """Over ``[Y, theta, Y_m]``: the spring ``kappa (Y_m - Y)^2 / 2``, its parallel dashpot
    ``gamma (Y_m' - Y')^2 / 2`` and the mass ``mu Y_m'^2 / 2``; a rigid translation carries
    the mass. Derived (``descriptor.from_energy``): ``Y - (1 - mu b4/kappa) Y_m = 0``
    (paper Eq. (3)) and ``Q+ = Q + mu b4 Y_m`` (Eq. (2)); with a dashpot the constraint is
    ``(1 + i w1 gamma/kappa)(Y - Y_m) + mu b4/kappa Y_m = 0``, free of poles."""
    import sympy as sp

    from mstmm.physics import Energy

    spring = sp.Matrix([[1, 0, -1], [0, 0, 0], [-1, 0, 1]])
    return Energy(
        K=v["k"] * spring, C=v.get("c", 0) * spring, M=sp.diag(0, 0, v["m"]), moves=("Y",)
    )


def spring(k):
    """Linear translational spring, paper Eq. (1): ``[[1, -1/k], [0, 1]]``."""
    import sympy as sp

    return sp.Matrix([[1, -1 / k], [0, 1]])


def mass(m, omega):
    """Lumped mass, paper Eq. (1): ``[[1, 0], [m w^2, 1]]``."""
    import sympy as sp

    return sp.Matrix([[1, 0], [m * omega**2, 1]])


def branch(k, m, omega):
    """Tip-to-beam transfer of the branch, ``U_spring U_mass`` (mass first, paper Eq. (2))."""
    return spring(k) * mass(m, omega)


def tip_column(k, m, omega):
    """State delivered at the rigid body per unit tip displacement: ``B [1, 0]^T``."""
    return branch(k, m, omega)[:, 0]


def condensed_compound(k, m, omega):
    """Pole-free second compound of the branch point, and the pole factor taken out.

    Eliminating the tip displacement with the geometric equation
    ``H_I1 Z_beam = H_I2 B [Y_m, 0]^T`` (paper Eq. (3)) gives the beam-to-beam
    matrix ``P = U_I1 + U_I2 [1, B10/B00]^T H_I1``, whose ``B10/B00 = k m w^2 / (k - m w^2)``
    has a pole at the oscillator frequency. ``C2(P)`` is linear in that ratio
    (``U_I2 H_I1`` has rank one), so ``B00 C2(P)`` is a polynomial: the pole is
    multiplied out exactly once, and the roots of the chain stay those of the
    paper's determinant, multiplicities included.
    """
    import sympy as sp

    from mstmm.derive import rigid_body
    from mstmm.derive.compound import second_compound

    col = tip_column(k, m, omega)
    B00, B10 = col[0], col[1]
    ratio = sp.Symbol("ratio")
    # the branch delivers [Y_beam, ratio * Y_beam] to the rigid body's second input
    delivered = sp.Matrix([1, ratio]) * rigid_body.H_I1()
    P = rigid_body.U_I1() + rigid_body.U_I2() * delivered
    C = second_compound(P).applyfunc(sp.expand)
    if any(sp.degree(e, ratio) > 1 for e in C if e.has(ratio)):
        raise ValueError("compound of the branch point is not linear in the impedance")
    pole_free = C.applyfunc(lambda e: sp.expand(B00 * e.coeff(ratio, 0) + B10 * e.coeff(ratio, 1)))
    return pole_free, B00

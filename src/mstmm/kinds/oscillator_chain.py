"""Oscillator chain: masses in series hanging from the beam (a multi-stage absorber).

``k = [k1, k2, ...]`` (beam -> m1, m1 -> m2, ...), ``m = [m1, m2, ...]``. Paper Eq. (1)'s
spring and lumped mass on ``[Y, Q]``, chained from the tip: the tip-to-beam transfer
``B = U_s1 U_m1 ... U_sn U_mn`` applied to the tip state ``[y_n, 0]`` gives
``[b00, b10] y_n`` at the beam point, so the chain condensed on the beam is a spring-mass
with ``B00 = b00``, ``B10 = b10`` (both polynomials in b4: no poles). As a reduced
descriptor: ``q = [y_n]``, ``Cz = e_Y``, ``Cq = -b00``, ``A = I``, ``B = b10 e_Q``.
For the count: the stiffness it adds to the node and its own natural frequencies with the
beam point held below omega (a Sturm count of the tridiagonal ``K - w^2 M``). For the mode
shapes the full descriptor keeps every mass displacement (n unknowns, n equations).
"""

from __future__ import annotations

from mstmm.catalog import Key

KIND = "oscillator_chain"
DOC = "masses m[i] in series hanging from the beam at x by springs k[i] (beam -> m1 -> m2 ...)"
KEYS = (
    Key("x", "m", check="position", doc="position from the left end"),
    Key("k", "N/m", shape="list", doc="spring stiffnesses, beam -> m1 first"),
    Key("m", "kg", shape="list", doc="masses, the one nearest the beam first"),
    Key(
        "c",
        "N s/m",
        shape="list",
        check="nonnegative",
        default=0.0,
        doc="dashpots parallel to the springs, beam -> m1 first (default none)",
        damping=True,
    ),
)
SAME_LENGTH = ("k", "m", "c")
COUNT = "stiffness"
#: Its marker and colour in plots (matplotlib).
MARKER = ("X", "C7")
#: Name of its unknowns in Z_all (the displacement of each mass).
UNKNOWNS = "Y_chain"
RIGID = ()

#: Computed before the descriptor, for the stable step and the count: the reduced tip
#: transfer and the number of the chain's own frequencies (beam point held) below omega.
PRELUDE = "b00, b10, own = oscillator_chain_tip(p, o, b4, L, EI, mbar)"
PRELUDE_NAMES = ("b00", "b10")
OWN = "own"
#: Unknowns of the full descriptor (mode shapes, paper formulation): every mass.
N_Q = "int(p[o])"
SHAPE = "oscillator_chain_shape(p, o, b4, L, EI, mbar, Cz, Cq, A, B, qmass)"
INTERNAL = "oscillator_chain_internal(p, o, L, EI, mbar, out, n)"
#: The same in a damped kernel (complex; k_i -> k_i + i w c_i), and the full descriptor in
#: complex arrays (the frequency response and damped shapes of every kernel).
PRELUDE_DAMPED = "b00, b10, chain_log = oscillator_chain_tip_c(p, o, w1, L, EI, mbar)"
#: The log of the factor the damped tip transfer took out (added to the chain's log).
LOG_DAMPED = "chain_log"
SHAPE_COMPLEX = "oscillator_chain_shape_c(p, o, w1, L, EI, mbar, Cz, Cq, A, B, qmass)"


def descriptor(v: dict):
    """The reduced descriptor: ``Y - b00 y_n = 0``, ``Q+ = Q + b10 y_n``."""
    import sympy as sp

    from mstmm.derive.descriptor import Descriptor, unit

    return Descriptor(
        Cz=unit(0).T, Cq=sp.Matrix([[-v["b00"]]]), A=sp.eye(4), B=v["b10"] * unit(3), qmass=(0,)
    )


def full_descriptor(v: dict):
    """Every mass kept (``symbolic``, ``show``): row i the motion of mass i,
    ``k_i (y_(i-1) - y_i) + k_(i+1) (y_(i+1) - y_i) + m_i b4 y_i = 0`` with ``y_0 = Y``,
    ``Q+ = Q + sum m_i b4 y_i`` (what the kernel's ``oscillator_chain_shape`` fills in);
    with dashpots ``k_i -> k_i + i w1 c_i``."""
    import sympy as sp

    from mstmm.derive.descriptor import Descriptor, b4, unit, w1

    cs = list(v.get("c") or [0] * len(v["k"]))
    ks = [k + sp.I * w1 * c for k, c in zip(v["k"], cs, strict=True)]
    ms = list(v["m"])
    n = len(ks)
    Cz = sp.zeros(n, 4)
    Cq = sp.zeros(n, n)
    Cz[0, 0] = ks[0]
    for i in range(n):
        k_out = ks[i + 1] if i + 1 < n else 0
        if i > 0:
            Cq[i, i - 1] = ks[i]
        if i + 1 < n:
            Cq[i, i + 1] = k_out
        Cq[i, i] = ms[i] * b4 - ks[i] - k_out
    B = sp.Matrix.hstack(*[ms[i] * b4 * unit(3) for i in range(n)])
    return Descriptor(Cz=Cz, Cq=Cq, A=sp.eye(4), B=B, qmass=tuple(ms))


FUNCTIONS = '''

@njit(cache=True)
def oscillator_chain_tip(p, o, b4, L, EI, mbar):
    """Tip-to-beam transfer [b00, b10] of the chain per unit tip displacement (scaled by a
    positive factor), and its own frequencies with the beam point held below b4 (Sturm
    count of K - b4 M, eliminated from the tip). Units L = EI = mbar = 1."""
    n = int(p[o])
    ks = o + 1
    ms = o + 2 + n
    kappa_scale = L**3 / EI
    mu_scale = 1.0 / (mbar * L)
    y = 1.0
    f = 0.0
    own = 0
    d = 1.0
    for i in range(n - 1, -1, -1):
        kappa = p[ks + i] * kappa_scale
        mu = p[ms + i] * mu_scale
        f += mu * b4 * y
        y -= f / kappa
        big = max(abs(y), abs(f))
        if big > 0.0:
            y /= big
            f /= big
        if i == n - 1:
            d = kappa - mu * b4
        else:
            k_out = p[ks + i + 1] * kappa_scale
            d = kappa + k_out - mu * b4 - k_out * k_out / d
        if d == 0.0:
            d = -5e-324
        if d < 0.0:
            own += 1
    return y, f, own


@njit(cache=True)
def oscillator_chain_own(p, o, b4, L, EI, mbar):
    """Own frequencies of the chain (beam point held) below b4."""
    return oscillator_chain_tip(p, o, b4, L, EI, mbar)[2]


@njit(cache=True)
def oscillator_chain_internal(p, o, L, EI, mbar, out, n):
    """Append the chain's own frequencies (beam point held; rad/s) to out[n:] by bisection
    on its Sturm count; returns the new n."""
    m = int(p[o])
    ks = o + 1
    ms = o + 2 + m
    top = 0.0
    for i in range(m):
        k_out = p[ks + i + 1] if i + 1 < m else 0.0
        top = max(top, 2.0 * (p[ks + i] + k_out) / p[ms + i])
    top *= 1.01
    to_b4 = mbar * L**4 / EI
    for j in range(m):
        lo = 0.0
        hi = top
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if mid <= lo or mid >= hi:
                break
            if oscillator_chain_own(p, o, mid * to_b4, L, EI, mbar) > j:
                hi = mid
            else:
                lo = mid
        out[n] = math.sqrt(0.5 * (lo + hi))
        n += 1
    return n


@njit(cache=True)
def oscillator_chain_shape(p, o, b4, L, EI, mbar, Cz, Cq, A, B, qmass):
    """The full descriptor: q = [y_1 .. y_n] (units L), row i the motion of mass i,
    kappa_i (y_(i-1) - y_i) + kappa_(i+1) (y_(i+1) - y_i) + mu_i b4 y_i = 0 with y_0 = Y,
    and Q+ = Q + sum mu_i b4 y_i (the springs' force on the beam, paper Eq. (2))."""
    n = int(p[o])
    ks = o + 1
    ms = o + 2 + n
    kappa_scale = L**3 / EI
    mu_scale = 1.0 / (mbar * L)
    for r in range(4):
        for c in range(4):
            A[r, c] = 1.0 if r == c else 0.0
    for i in range(n):
        for c in range(4):
            Cz[i, c] = 0.0
        for j in range(n):
            Cq[i, j] = 0.0
        for r in range(4):
            B[r, i] = 0.0
    for i in range(n):
        kappa = p[ks + i] * kappa_scale
        k_out = p[ks + i + 1] * kappa_scale if i + 1 < n else 0.0
        mu = p[ms + i] * mu_scale
        if i == 0:
            Cz[0, 0] = kappa
        else:
            Cq[i, i - 1] = kappa
        if i + 1 < n:
            Cq[i, i + 1] = k_out
        Cq[i, i] = mu * b4 - kappa - k_out
        B[3, i] = mu * b4
        qmass[0, i] = mu
        qmass[1, i] = mu
        qmass[2, i] = 1.0
    return n, n


@njit(cache=True)
def oscillator_chain_tip_c(p, o, w1, L, EI, mbar):
    """``oscillator_chain_tip`` with dashpots, complex: k_i -> kappa_i = k_i + i w1 c_i
    (units L = EI = mbar = 1, w1 the complex frequency). Each spring's transfer is
    multiplied by its kappa_i (``y -> kappa y - f``, ``f -> kappa f``): the pair is then
    prod(kappa_i) times the tip transfer, entire in w1 (the mass equations of the global
    system, free of the poles kappa_i = 0), and kept finite by a power of two whose log is
    returned: (b00, b10, log)."""
    n = int(p[o])
    ks = o + 1
    ms = o + 2 + n
    cs = o + 3 + 2 * n
    kappa_scale = L**3 / EI
    gamma_scale = L / math.sqrt(EI * mbar)
    mu_scale = 1.0 / (mbar * L)
    b4 = w1 * w1
    y = 1.0 + 0.0j
    f = 0.0j
    log = 0.0
    for i in range(n - 1, -1, -1):
        kappa = p[ks + i] * kappa_scale + 1j * w1 * p[cs + i] * gamma_scale
        mu = p[ms + i] * mu_scale
        f += mu * b4 * y
        y = kappa * y - f
        f = kappa * f
        big = max(abs(y), abs(f))
        if big > 0.0 and math.isfinite(big):
            e = math.frexp(big)[1]
            s = math.ldexp(1.0, -e)
            y *= s
            f *= s
            log += e * 0.6931471805599453
    return y, f, log


@njit(cache=True)
def oscillator_chain_shape_c(p, o, w1, L, EI, mbar, Cz, Cq, A, B, qmass):
    """``oscillator_chain_shape`` in complex arrays, with dashpots (k_i -> k_i + i w1 c_i)."""
    n = int(p[o])
    ks = o + 1
    ms = o + 2 + n
    cs = o + 3 + 2 * n
    kappa_scale = L**3 / EI
    gamma_scale = L / math.sqrt(EI * mbar)
    mu_scale = 1.0 / (mbar * L)
    b4 = w1 * w1
    for r in range(4):
        for c in range(4):
            A[r, c] = 1.0 if r == c else 0.0
    for i in range(n):
        for c in range(4):
            Cz[i, c] = 0.0
        for j in range(n):
            Cq[i, j] = 0.0
        for r in range(4):
            B[r, i] = 0.0
    for i in range(n):
        kappa = p[ks + i] * kappa_scale + 1j * w1 * p[cs + i] * gamma_scale
        k_out = 0.0j
        if i + 1 < n:
            k_out = p[ks + i + 1] * kappa_scale + 1j * w1 * p[cs + i + 1] * gamma_scale
        mu = p[ms + i] * mu_scale
        if i == 0:
            Cz[0, 0] = kappa
        else:
            Cq[i, i - 1] = kappa
        if i + 1 < n:
            Cq[i, i + 1] = k_out
        Cq[i, i] = mu * b4 - kappa - k_out
        B[3, i] = mu * b4
        qmass[0, i] = mu
        qmass[1, i] = mu
        qmass[2, i] = 1.0
    return n, n
'''

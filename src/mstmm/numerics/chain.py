"""A kind made of stages in series (``stage`` declared, docs/components.md): node ``j``
(``u_j``, ``u_0 = Y`` the beam point) hangs from node ``j - 1`` by stage ``j``, whose
dynamic stiffness over ``[u_(j-1), u_j]`` is ``[[a, b], [b, c]]`` (``D = K + i w C - b4 M``
of the stage's declared energy). The kernel's printed ``event_stages`` fills ``st`` (5 x n:
rows ``a, b, c, s1, m``; ``s1`` the column sum for ``u_j``, the inertia force a common
translation leaves, ``m`` the node's mass) at one frequency. The unknowns' dynamic
stiffness ``D_qq`` is tridiagonal; these functions eliminate it from the tip, so that the
number of stages is data, not code. Generic in the dtype: the same code serves the real
kernels and the complex ones.
"""

import math

import numpy as np

from mstmm.jit import njit


@njit(cache=True, inline="always")
def stage_array(p, o):
    """Room for the stages of the component whose data block is at ``o`` (its first
    value is their number), real."""
    return np.empty((5, int(p[o])), dtype=np.float64)


@njit(cache=True, inline="always")
def stage_array_c(p, o):
    """The same, complex."""
    return np.empty((5, int(p[o])), dtype=np.complex128)


@njit(cache=True)
def chain_tip(st):
    """The chain condensed on the beam point, free of its poles: eliminating ``u_n .. u_1``
    from the tip gives ``Y = u0 y`` and the force on the beam ``Q+ = Q + g y`` for a tip
    unknown ``y``; and the number of negative pivots of ``D_qq`` (its own frequencies below
    omega with the beam point held, a Sturm count; real kernels only). Returns
    ``(u0, g, log, own)``, renormalised by powers of two whose log is ``log``.

    With ``t_j`` the force stage j + 1 puts on node j (``t_n = 0``), node j's equation
    ``b_j u_(j-1) + c_j u_j + t_j = 0`` and ``c_j = s1_j - b_j`` give
    ``t_(j-1) = t_j + s1_j u_j`` (the inertia forces summed from the tip: no difference of
    two stiffnesses) and ``u_(j-1) = u_j - t_(j-1) / b_j``; each step is multiplied by
    ``-b_j`` (a spring's stiffness, positive), so ``u0`` is ``det D_qq`` times a positive
    factor and no pole appears. ``g = -t_0``."""
    n = st.shape[1]
    u = st[2, 0] * 0.0 + 1.0
    t = u * 0.0
    d = u
    own = 0
    log = 0.0
    for j in range(n - 1, -1, -1):
        b = st[1, j]
        if j == n - 1:
            d = st[2, j]
        else:
            d = st[2, j] + st[0, j + 1] - st[1, j + 1] * st[1, j + 1] / d
        if d.real == 0.0:
            d = d * 0.0 - 5e-324
        if d.real < 0.0:
            own += 1
        t += st[3, j] * u
        u = t - b * u
        t = -b * t
        big = max(abs(u), abs(t))
        if big > 0.0 and math.isfinite(big):
            e = math.frexp(big)[1]
            s = math.ldexp(1.0, -e)
            u *= s
            t *= s
            log += e * 0.6931471805599453
    return u, -t, log, own


@njit(cache=True)
def chain_own(st0, b4, st):
    """The chain's own frequencies below b4 (beam point held), from its stages at b4 = 0
    (``st0``, an undamped kernel's: ``D = K - b4 M``, the mass at each stage's node)."""
    for j in range(st0.shape[1]):
        st[0, j] = st0[0, j]
        st[1, j] = st0[1, j]
        st[2, j] = st0[2, j] - b4 * st0[4, j]
        st[3, j] = -b4 * st0[4, j]
        st[4, j] = st0[4, j]
    return chain_tip(st)[3]


@njit(cache=True)
def chain_own_many(st0, b4, counts):
    """counts[i] <- ``chain_own(st0, b4[i], ...)`` for every shift b4[i] at once: the same
    pivots in the same order (so the same counts, bit for bit), each stage's step done on
    all the shifts together (numpy's loops in the plain-Python tier)."""
    n = st0.shape[1]
    j = n - 1
    d = st0[2, j] - b4 * st0[4, j]
    for i in range(n - 1, -1, -1):
        if i < n - 1:
            b = st0[1, i + 1]
            d = (st0[2, i] - b4 * st0[4, i]) + st0[0, i + 1] - b * b / d
        d = np.where(d == 0.0, -5e-324, d)
        counts += (d < 0.0).astype(np.int64)
    return counts


#: Most bisection steps on one own frequency of a chain (the ulp of a normal double is
#: reached in about 60; a subnormal one takes more).
OWN_BISECTIONS = 200


@njit(cache=True)
def own_bound(st0):
    """A bound above every own b4 of the chain (Gershgorin on M^-1 K, with a margin)."""
    stages = st0.shape[1]
    top = 0.0
    for j in range(stages):
        row = abs(st0[2, j]) + abs(st0[1, j])
        if j + 1 < stages:
            row += abs(st0[0, j + 1]) + abs(st0[1, j + 1])
        if st0[4, j] > 0.0:
            top = max(top, row / st0[4, j])
    return 1.01 * top + 1e-300


@njit(cache=True)
def chain_internal(st0, L, EI, mbar, out, n):
    """Append the chain's own frequencies (beam point held; rad/s) to ``out[n:]``, by
    bisection on its Sturm count below a Gershgorin bound, to the last bit; ``st0`` its
    stages at b4 = 0. Returns the new ``n``.

    Every frequency is bisected at once (``chain_own_many``: one sweep of the stages per
    step for all of them), each exactly as alone: a chain of n stages costs
    OWN_BISECTIONS sweeps of n x n, not n bisections of as many sweeps each."""
    stages = st0.shape[1]
    top = own_bound(st0)
    lo = np.zeros(stages)
    hi = np.full(stages, top)
    active = np.arange(stages)  # the k still bisected
    for _ in range(OWN_BISECTIONS):
        mid = 0.5 * (lo[active] + hi[active])
        going = (mid > lo[active]) & (mid < hi[active])
        active = active[going]
        if active.size == 0:
            break
        mid = mid[going]
        counts = chain_own_many(st0, mid, np.zeros(active.size, dtype=np.int64))
        for e in range(active.size):
            if counts[e] > active[e]:
                hi[active[e]] = mid[e]
            else:
                lo[active[e]] = mid[e]
    for k in range(stages):
        out[n] = math.sqrt(0.5 * (lo[k] + hi[k]) * EI / mbar) / (L * L)
        n += 1
    return n


@njit(cache=True)
def chain_descriptor(st, Cz, Cq, A, B, qmass):
    """Every node kept (mode shapes, the paper's determinant, the frequency response):
    ``q = [u_1 .. u_n]``, row ``j`` minus node j's equation of motion
    ``-(b_j u_(j-1) + (c_j + a_(j+1)) u_j + b_(j+1) u_(j+1)) = 0`` (paper Eq. (3)), and
    the force on the beam ``Q+ = Q - sum s1_j u_j`` (Eq. (2)). Returns (constraints,
    unknowns)."""
    n = st.shape[1]
    for r in range(4):
        for k in range(4):
            A[r, k] = 1.0 if r == k else 0.0
    for i in range(n):
        for k in range(4):
            Cz[i, k] = 0.0
            B[k, i] = 0.0
        for k in range(n):
            Cq[i, k] = 0.0
    for j in range(n):
        Cq[j, j] -= st[2, j]
        if j == 0:
            Cz[0, 0] = -st[1, j]
        else:
            Cq[j, j - 1] = -st[1, j]
            Cq[j - 1, j] = -st[1, j]
            Cq[j - 1, j - 1] -= st[0, j]
        B[3, j] = -st[3, j]
        qmass[0, j] = st[4, j].real
        qmass[1, j] = st[4, j].real
        qmass[2, j] = 1.0
        qmass[3, j] = 0.0  # no mass shared with the beam's Y, theta (every row written:
        qmass[4, j] = 0.0  # the array is reused from one component to the next)
    return n, n

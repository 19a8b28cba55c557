"""Mode shapes against the reference model's null space: the comparison the tests share.

Shapes are compared as subspaces: rows [Y at sample points, Y of every hanging mass],
the sine of the largest principal angle between our span and the span of the
reference's null vectors (``reference_model.eigenspace``) at the exact root.
"""

from __future__ import annotations

import numpy as np
import reference_model as ref


def sin_angle(ours, theirs) -> float:
    """Sine of the largest principal angle between the spans of two sets of row vectors."""
    qa, _ = np.linalg.qr(np.asarray(ours, dtype=float).T)
    qb, _ = np.linalg.qr(np.asarray(theirs, dtype=float).T)
    return float(np.linalg.norm(qa - qb @ (qb.T @ qa), 2))


def vectors(shapes, every: int = 5):
    """Rows [Y at every ``every``-th sample point and at the attachments, Y of each mass]."""
    x = shapes[0].x
    keep = np.unique(np.concatenate([np.arange(0, len(x), every), [len(x) - 1]]))
    keep = np.union1d(keep, np.searchsorted(x, shapes[0].mass_x))
    return x[keep], [np.concatenate([s.Y[keep], s.mass_Y]) for s in shapes]


def groups(sol):
    """Index ranges of the shapes that share one eigenspace."""
    out, i = [], 0
    while i < len(sol.shapes):
        m = sol.shapes[i].multiplicity
        out.append((i, i + m))
        i += m
    return out


def check_against_reference(sc, sol, tol, exact=None):
    """Every eigenspace of ``sol`` against the reference null space at the exact root."""
    exact = exact or ref.frequencies(sc, len(sol.omega), dps=30)
    worst = 0.0
    for a, b in groups(sol):
        xs, ours = vectors(sol.shapes[a:b])
        centre = sum(exact[a:b]) / (b - a)
        theirs = ref.eigenspace(sc, centre, b - a, xs, dps=30)
        worst = max(worst, sin_angle(ours, theirs))
    assert worst <= tol, worst
    for s in sol.shapes:
        for arr in (s.Y, s.theta, s.M, s.Q, s.mass_Y):
            assert np.all(np.isfinite(arr))
    return worst


def hanging_chains(sc) -> list[list[tuple[float, float]]]:
    """[(k_1, m_1), ...] of every spring-mass (one stage) and oscillator chain, sorted by x
    (stable): the order of ``ModeShape.mass_x`` / ``mass_Y``."""
    chains = []
    for att in sc["attachments"]:
        kind = att.get("type", "spring_mass")
        if kind == "spring_mass":
            chains.append((att["x"], [(att["k"], att["m"])]))
        elif kind == "oscillator_chain":
            chains.append((att["x"], list(zip(att["k"], att["m"], strict=True))))
    return [stages for _x, stages in sorted(chains, key=lambda c: c[0])]


def check_shapes(sc, sol, tol: float = 1e-7) -> None:
    """What every default solve must give for a scene of any kinds: one finite shape per
    frequency (max |Y| over beam and masses = 1), eigenspaces of the sizes the
    multiplicities say (a root, or a cluster of roots within 1e-8), one ``mass_Y`` per
    hanging mass (each stage of a chain) at its attachment point, and every hanging mass
    obeying its equation of motion
    ``m_i w^2 u_i + k_i (u_{i-1} - u_i) + k_{i+1} (u_{i+1} - u_i) = 0`` (u_0 = Y of the beam
    at the attachment point)."""
    if not isinstance(sc, dict):
        from mstmm.scene import scene_to_dict

        sc = scene_to_dict(sc)
    chains = hanging_chains(sc)
    xs = sorted(a["x"] for a in sc["attachments"] for _ in range(_stage_count(a)))
    assert sol.shapes is not None and len(sol.shapes) == len(sol.omega)
    i = 0
    while i < len(sol.shapes):
        m = sol.shapes[i].multiplicity
        assert m >= 1 and all(s.multiplicity == m for s in sol.shapes[i : i + m])
        # one root of multiplicity m, or a cluster of m roots too close to separate: each
        # within 1e-8 (relative) of the next (mstmm.modes.clusters)
        gaps = np.diff(sol.omega[i : i + m])
        assert np.all(gaps <= 1e-8 * sol.omega[i + 1 : i + m])
        i += m
    for s, w in zip(sol.shapes, sol.omega, strict=True):
        assert s.omega == w
        for arr in (s.x, s.Y, s.theta, s.M, s.Q, s.mass_x, s.mass_Y):
            assert np.all(np.isfinite(arr))
        assert len(s.mass_Y) == len(s.mass_x) == len(xs)
        np.testing.assert_array_equal(s.mass_x, xs)
        assert max(np.max(np.abs(s.Y)), np.max(np.abs(s.mass_Y), initial=0.0)) == 1.0
        beam_y = s.Y[np.searchsorted(s.x, s.mass_x)]
        j = 0
        for stages in chains:
            u = [beam_y[j]] + list(s.mass_Y[j : j + len(stages)]) + [0.0]
            ks = [k for k, _m in stages] + [0.0]
            for n, (k, mass) in enumerate(stages, start=1):
                force = mass * w**2 * u[n] + k * (u[n - 1] - u[n]) + ks[n] * (u[n + 1] - u[n])
                scale = mass * w**2 + k + ks[n]  # the forces of a unit amplitude (max |Y| = 1)
                assert abs(force) <= tol * scale, (w, n, force, scale)
            j += len(stages)


def _stage_count(att) -> int:
    kind = att.get("type", "spring_mass")
    if kind == "spring_mass":
        return 1
    if kind == "oscillator_chain":
        return len(att["k"])
    return 0

"""What ``mstmm show`` prints of a frame: its topology and its overall equation.

The nodes (coordinates, supports, springs, masses), the members (each with its transfer
direction, start to end, its length and angle, its joints and its segments), the
freedoms of the overall equation ``D(omega) q = 0`` and the pattern of D (which freedoms
a member, a spring or an absorber couples) in the banded order the count uses.
"""

from __future__ import annotations

import math

import numpy as np

from .assembly import Assembly
from .model import Frame

__all__ = ["describe"]

#: The pattern of D is drawn up to this many freedoms.
PATTERN_MAX = 60


def _freedom_name(asm: Assembly, g: int) -> str:
    f = asm.freedoms[g]
    if f.kind == "hinge":
        return f"psi({f.owner} {'end' if f.end else 'start'})"
    if f.kind == "absorber":
        return f"q(absorber {f.owner} at {asm.frame.absorbers[int(f.owner)].node})"
    X, Y, T = f.vector
    if asm.frame.motion == "out_of_plane":
        return f"{'W' if X else 'ThetaX' if Y else 'ThetaY'}({f.owner})"
    if T:
        return f"Theta({f.owner})"
    if (X, Y) == (1.0, 0.0):
        return f"X({f.owner})"
    if (X, Y) == (0.0, 1.0):
        return f"Y({f.owner})"
    return f"t({f.owner}: [{X:.4g}, {Y:.4g}])"


def describe(frame: Frame) -> str:
    """The text ``mstmm show`` prints for a frame."""
    asm = Assembly(frame)
    grid = frame.motion == "out_of_plane"
    out = [
        f"{frame.name}: {len(frame.nodes)} nodes, {len(frame.members)} members,"
        f" {len(frame.absorbers)} absorber(s); {frame.mass:.6g} kg",
        "nodes (x, y in m; held freedoms; springs N/m, N m/rad; mass kg, J kg m^2):",
    ]
    for n in frame.nodes.values():
        extra = []
        if n.held:
            extra.append(f"holds {n.held}" + (f" (normal {n.normal})" if "n" in n.held else ""))
        if grid and n.springs[0]:
            extra.append(f"spring k_z = {n.springs[0]:g}")
        elif not grid and (any(n.springs) or n.k_t):
            extra.append(f"springs k_xx, k_xy, k_yy = {n.springs}, k_t = {n.k_t:g}")
        if n.mass or n.J:
            extra.append(f"mass {n.mass:g}, J {n.J:g}")
        out.append(f"  {n.name}: ({n.x:g}, {n.y:g})" + ("; " + "; ".join(extra) if extra else ""))
    out.append("members (transfer from start to end; local x along it, y turned +90 degrees):")
    for m in frame.members:
        L, c, s = frame.geometry(m)
        joints = "/".join("pinned" if p else "rigid" for p in m.pinned)
        segs = ", ".join(
            f"{sg.length:g} m: EI {sg.EI:g}, "
            + (f"GJ {sg.GJ:g}, rho_Ip {sg.rho_Ip:g}" if grid else f"EA {sg.EA:g}")
            + f", mbar {sg.mass_per_length:g}"
            + "".join(f", {k} {v:g}" for k, v in sg.physics if v)
            for sg in m.segments
        )
        out.append(
            f"  {m.name}: {m.start} -> {m.end}, L = {L:g} m at {math.degrees(math.atan2(s, c)):g}"
            f" deg, joints {joints}; {segs}"
        )
    for i, ab in enumerate(frame.absorbers):
        along = "Z" if grid else ab.direction
        out.append(
            f"  absorber {i}: at {ab.node} along {along}, k {ab.k:g}, m {ab.m:g}, c {ab.c:g}"
        )
    names = [_freedom_name(asm, g) for g in range(asm.n)]
    out.append(f"overall equation D(omega) q = 0, q ({asm.n} freedoms) =")
    out.append("  " + ", ".join(names))
    if grid:
        out.append(
            "D = sum over members of T_m^T k_m(omega) T_m + K - omega^2 M: k_m the member's"
            " exact dynamic stiffness (torsion GJ mu / (h sin mu) [[cos mu, -1], [-1, cos mu]]"
            " on the twist phi, mu = omega h sqrt(rho_Ip / GJ); bending from its beam's transfer"
            " on w, psi), T_m its turn to the global axes (phi = c ThetaX + s ThetaY, w = W,"
            " psi = s ThetaX - c ThetaY); K, M the springs, masses and absorbers"
        )
    else:
        out.append(
            "D = sum over members of T_m^T k_m(omega) T_m + K - omega^2 M: k_m the member's"
            " exact dynamic stiffness (rod EA mu / (h sin mu) [[cos mu, -1], [-1, cos mu]] on u;"
            " bending from its beam's transfer on w, psi), T_m its turn to the global axes"
            " (u = c X + s Y, w = -s X + c Y); K, M the springs, masses and absorbers"
        )
    out.append(
        "count: J(omega) = sum of the members' clamped-clamped counts J0 + negative"
        " eigenvalues of D(omega) (Wittrick-Williams)"
    )
    A = asm.pattern
    out.append(
        f"pattern of D ({asm.n}x{asm.n}, {int(A.sum())} entries nonzero), in the count's banded"
        f" order (half-bandwidth {asm.bandwidth}):"
    )
    if asm.n > PATTERN_MAX:
        out.append(f"  (drawn up to {PATTERN_MAX}x{PATTERN_MAX})")
    else:
        P = A[np.ix_(asm.perm, asm.perm)]
        out += ["  " + "".join("X" if v else "." for v in row) for row in P]
    return "\n".join(out) + "\n"

"""What ``mstmm solve`` prints of a frame's solution: a table, CSV or JSON text."""

from __future__ import annotations

import json

from .solve import FrameSolution

__all__ = ["frame_text"]


def frame_text(sol: FrameSolution, fmt: str, shapes: bool) -> str:
    """The solution as ``fmt`` (``table``, ``csv`` or ``json``); with ``shapes`` each
    mode's joint displacements (X, Y in m, Theta in rad; unit modal mass)."""
    if fmt == "json":
        data = sol.to_dict()
        if not shapes:
            data.pop("modes")
        return json.dumps(data, indent=1) + "\n"
    if fmt == "csv":
        lines = ["mode,omega (rad/s),f (Hz),multiplicity"]
        lines += [
            f"{j + 1},{w!r},{f!r},{m}"
            for j, (w, f, m) in enumerate(zip(sol.omega, sol.f, sol.multiplicity))
        ]
        if shapes:
            lines[0] += ",M_eff,X (kg),M_eff,Y (kg)"
            for j, mode in enumerate(sol.modes):
                lines[j + 1] += f",{mode.effective_mass[0]!r},{mode.effective_mass[1]!r}"
            names = list(sol.frame.nodes)
            head = ",".join(f"{n}.{c}" for n in names for c in ("X (m)", "Y (m)", "Theta (rad)"))
            lines += ["", "mode," + head]
            for j, mode in enumerate(sol.modes):
                row = ",".join(repr(v) for n in names for v in mode.nodes[n])
                lines.append(f"{j + 1},{row}")
        return "\n".join(lines) + "\n"
    members = len(sol.frame.members)
    lines = [
        f"{sol.frame.name}: {len(sol.frame.nodes)} nodes, {members} members;"
        f" {sol.omega.size} natural frequencies (multiplicities exact, by the count)",
        f"{'mode':>4}  {'f (Hz)':>18}  {'omega (rad/s)':>18}  {'mult':>4}",
    ]
    for j, (w, f, m) in enumerate(zip(sol.omega, sol.f, sol.multiplicity)):
        lines.append(f"{j + 1:>4}  {f:>18.12g}  {w:>18.12g}  {m:>4}")
    if shapes and sol.modes:
        lines.append("")
        lines.append(
            f"{'mode':>4}  {'node moving most':<20}  {'M_eff,X (kg)':>14}  {'M_eff,Y (kg)':>14}"
        )
        total = [0.0, 0.0]
        for j, mode in enumerate(sol.modes):
            name, (X, Y, _) = max(mode.nodes.items(), key=lambda kv: kv[1][0] ** 2 + kv[1][1] ** 2)
            if X * X + Y * Y <= 1e-24 * max(1.0, max(v[2] ** 2 for v in mode.nodes.values())):
                name = "(joints do not move)"
            mx, my = mode.effective_mass
            total[0] += mx
            total[1] += my
            lines.append(f"{j + 1:>4}  {name:<20}  {mx:>14.6g}  {my:>14.6g}")
        mass = sol.frame.mass
        lines.append(
            f"sum of effective masses: X {total[0]:.6g} kg ({100 * total[0] / mass:.1f} %),"
            f" Y {total[1]:.6g} kg ({100 * total[1] / mass:.1f} %) of {mass:.6g} kg"
        )
    return "\n".join(lines) + "\n"

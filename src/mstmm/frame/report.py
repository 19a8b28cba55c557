"""What ``mstmm solve`` prints of a frame's solution: a table, CSV or JSON text."""

from __future__ import annotations

import json

from mstmm.output import damped_csv, damped_rows

from .damped import DampedFrameSolution
from .solve import FrameSolution

__all__ = ["frame_text"]


def _axes(sol: FrameSolution) -> tuple[str, ...]:
    """The directions of the effective masses: X and Y in the plane, Z out of it."""
    return ("Z",) if sol.frame.motion == "out_of_plane" else ("X", "Y")


def _components(sol: FrameSolution) -> tuple[str, ...]:
    """A node's displacement components as the shapes list them."""
    if sol.frame.motion == "out_of_plane":
        return ("W (m)", "ThetaX (rad)", "ThetaY (rad)")
    return ("X (m)", "Y (m)", "Theta (rad)")


def frame_text(sol: FrameSolution | DampedFrameSolution, fmt: str, shapes: bool) -> str:
    """The solution as ``fmt`` (``table``, ``csv`` or ``json``); with ``shapes`` each
    mode's joint displacements (X, Y in m, Theta in rad; unit modal mass)."""
    if getattr(sol, "damped", False):
        return _damped_text(sol, fmt, shapes)
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
            axes = _axes(sol)
            lines[0] += "".join(f",M_eff,{a} (kg)" for a in axes)
            for j, mode in enumerate(sol.modes):
                lines[j + 1] += "".join(f",{m!r}" for m in mode.effective_mass[: len(axes)])
            names = list(sol.frame.nodes)
            head = ",".join(f"{n}.{c}" for n in names for c in _components(sol))
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
        axes = _axes(sol)
        lines.append(
            f"{'mode':>4}  {'node moving most':<20}"
            + "".join(f"  {'M_eff,' + a + ' (kg)':>14}" for a in axes)
        )
        total = [0.0] * len(axes)
        moving = 1 if len(axes) == 1 else 2  # the translations among a node's components
        for j, mode in enumerate(sol.modes):
            name, v = max(mode.nodes.items(), key=lambda kv: sum(c * c for c in kv[1][:moving]))
            rest = max(sum(c * c for c in u[moving:]) for u in mode.nodes.values())
            if sum(c * c for c in v[:moving]) <= 1e-24 * max(1.0, rest):
                name = "(joints do not move)"
            row = f"{j + 1:>4}  {name:<20}"
            for k in range(len(axes)):
                total[k] += mode.effective_mass[k]
                row += f"  {mode.effective_mass[k]:>14.6g}"
            lines.append(row)
        mass = sol.frame.mass
        lines.append(
            "sum of effective masses: "
            + ", ".join(f"{a} {t:.6g} kg ({100 * t / mass:.1f} %)" for a, t in zip(axes, total))
            + f" of {mass:.6g} kg"
        )
    return "\n".join(lines) + "\n"


def _damped_text(sol: DampedFrameSolution, fmt: str, shapes: bool) -> str:
    """A damped frame's roots (and with ``shapes`` its complex modes: the joints'
    displacements scaled so that the largest translation is 1)."""
    if fmt == "json":
        data = sol.to_dict()
        if not shapes:
            data.pop("modes")
        return json.dumps(data, indent=1) + "\n"
    names = list(sol.frame.nodes)
    if fmt == "csv":
        text = damped_csv(sol)
        if shapes and sol.modes:
            head = ",".join(
                f"{n}.{c} {part}" for n in names for c in _components(sol) for part in ("re", "im")
            )
            lines = ["", "mode," + head]
            for j, mode in enumerate(sol.modes):
                values = [complex(v) for n in names for v in mode.nodes[n]]
                lines.append(f"{j + 1}," + ",".join(f"{v.real!r},{v.imag!r}" for v in values))
            text += "\n".join(lines) + "\n"
        return text
    nodes, members = len(sol.frame.nodes), len(sol.frame.members)
    lines = damped_rows(sol, f"{sol.frame.name}: {nodes} nodes, {members} members; ")
    x0, x1, y0, y1 = sol.rectangle
    lines.append(
        f"argument principle checked: {sol.count_checked} (counted w_d < {x1:.6g} rad/s,"
        f" sigma < {y1:.6g} 1/s)"
    )
    if shapes and sol.modes:
        moving = 1 if sol.frame.motion == "out_of_plane" else 2
        lines += ["", f"{'mode':>4}  {'node moving most':<20}  {'complexity':>10}"]
        for j, mode in enumerate(sol.modes):
            name = max(names, key=lambda n: sum(abs(c) ** 2 for c in mode.nodes[n][:moving]))
            lines.append(f"{j + 1:>4}  {name:<20}  {mode.complexity:>10.4g}")
    return "\n".join(lines) + "\n"

"""Frequency response of a frame between any two points of its nodes and members.

``frf(frame, input, output, omega)``: the steady-state response (time dependence
``exp(i w t)``) of ``output`` to a unit harmonic ``input``, from the exact dynamic
stiffness: ``x = D(omega)^-1 f`` with ``D = members + K + i omega C - omega^2 M`` (the
members exact, with their loss factors, the absorbers' dashpots in C). Loads and responses:
``("force", where, (dx, dy))`` (N along the unit vector), ``("moment", where)`` (N m,
counterclockwise); ``("displacement", where, (dx, dy))`` (m), ``("rotation", where)``
(rad). ``where`` is a node's name or ``(member, x)``, a point x m along a member from its
start node: the member is cut there (:func:`mstmm.frame.reading.with_points`), which
adds a joint and leaves it exact. A component along a held freedom is 0.

On the command line (``mstmm frf frame.toml``) a point is ``QUANTITY:WHERE[=DIRECTION]``:
``force:N10_0=x``, ``displacement:col3@1.5=y``, ``force:B=30`` (30 degrees from X),
``rotation:arm@2``; on a grillage (out of the plane) ``force:C=z``, ``rotation:C=x``;
:func:`parse_point` reads it.
"""

from __future__ import annotations

import math
import re

import numpy as np

from mstmm.scene import SceneError

from .assembly import Assembly
from .damped import complex_matrix, loss_factor
from .model import Frame
from .reading import with_points

__all__ = ["frf", "parse_point"]

_TRANSLATIONS = ("force", "displacement")
_ROTATIONS = ("moment", "rotation")
_SPEC = re.compile(r"^(force|moment|displacement|rotation):([^=]+?)(?:=(.+))?$")


def parse_point(spec: str, role: str, source: str = "<frf>") -> tuple:
    """A load or response from its command-line form (see the module): ``(quantity,
    where)`` or ``(quantity, where, (dx, dy))``; ``where`` a node name or ``(member,
    x)``. Out of the plane (a grillage) a force or displacement is ``=z`` and a moment or
    rotation ``=x`` or ``=y`` (about X or Y). Raises :class:`SceneError` naming ``role``
    (``--input``, ``--output``)."""
    wanted = ("force", "moment") if role == "--input" else ("displacement", "rotation")
    m = _SPEC.match(spec.strip()) if isinstance(spec, str) else None
    if m is None or m.group(1) not in wanted:
        raise SceneError(
            source, role,
            f"expected {wanted[0]}:WHERE=DIRECTION or {wanted[1]}:WHERE (WHERE a node or"
            " MEMBER@X; DIRECTION x, y or an angle in degrees from X)", spec,
        )  # fmt: skip
    quantity, where, direction = m.groups()
    if "@" in where:
        member, _, x = where.rpartition("@")
        try:
            where = (member, float(x))
        except ValueError:
            raise SceneError(source, role, "MEMBER@X needs X in m", spec) from None
    if direction == "z" and quantity in _TRANSLATIONS:  # a grillage's, along Z
        return (quantity, where, (0.0, 0.0))
    if quantity in _ROTATIONS:
        if direction is None:
            return (quantity, where)
        if direction in ("x", "y"):  # a grillage's, about X or Y
            return (quantity, where, (1.0, 0.0) if direction == "x" else (0.0, 1.0))
        raise SceneError(source, role, f"a {quantity} is about x or y (a grillage) or none", spec)
    if direction is None:
        raise SceneError(source, role, f"a {quantity} needs =x, =y or =ANGLE (degrees)", spec)
    if direction in ("x", "y"):
        return (quantity, where, (1.0, 0.0) if direction == "x" else (0.0, 1.0))
    try:
        angle = math.radians(float(direction))
    except ValueError:
        raise SceneError(
            source, role, "DIRECTION must be x, y or an angle in degrees", spec
        ) from None
    return (quantity, where, (math.cos(angle), math.sin(angle)))


def _vector(asm: Assembly, spec: tuple, node: str, role: str) -> np.ndarray:
    """The freedoms' coefficients of a load or response spec at ``node`` (SI, unscaled)."""
    kind, _, *rest = spec
    source = asm.frame.source
    if node not in asm.node_freedoms:
        raise SceneError(source, role, "no node of this name", node)
    if kind not in _TRANSLATIONS + _ROTATIONS:
        raise SceneError(source, role, "force, moment, displacement or rotation", kind)
    if asm.frame.motion == "out_of_plane":  # over (W, ThetaX, ThetaY)
        if kind in _ROTATIONS and not rest:
            raise SceneError(source, role, f"a grillage's {kind} is about x or y (=x, =y)", kind)
        d = (1.0, 0.0, 0.0) if kind in _TRANSLATIONS else (0.0, *rest[0])
    elif kind in _TRANSLATIONS:
        dx, dy = rest[0]
        norm = math.hypot(dx, dy)
        if norm == 0.0:
            raise SceneError(source, role, "along Z is out of the plane (a grillage's)", spec)
        d = (dx / norm, dy / norm, 0.0)
    else:
        if rest:
            raise SceneError(source, role, f"a {kind} in the plane has no direction", spec)
        d = (0.0, 0.0, 1.0)
    v = np.zeros(asm.n)
    for g in asm.node_freedoms[node]:
        v[g] = float(np.dot(asm.freedoms[g].vector, d))
    return v


def frf(frame: Frame, input, output, omega) -> np.ndarray:
    """Receptance (m/N, rad/N, m/(N m), rad/(N m)) of ``output`` to ``input`` at each
    omega (rad/s), complex; NaN where D is singular (a natural frequency, undamped).
    ``output`` may be a list of responses: the result is then (frequencies x outputs)."""
    many = isinstance(output, list)
    outputs = output if many else [output]
    specs = [input, *outputs]
    roles = ["input"] + [f"output[{j}]" if many else "output" for j in range(len(outputs))]
    inside = [(s[1], r) for s, r in zip(specs, roles) if isinstance(s[1], tuple)]
    frame, cut = with_points(frame, [p for p, _ in inside], [r for _, r in inside])
    at = iter(cut)
    nodes = [next(at) if isinstance(s[1], tuple) else s[1] for s in specs]
    asm = Assembly(frame)
    f = _vector(asm, input, nodes[0], roles[0])
    G = np.array([_vector(asm, s, n, r) for s, n, r in zip(outputs, nodes[1:], roles[1:])])
    units = asm.L_ref / asm.EI_ref
    # D_SI = S^-1 D S^-1 / units (D dimensionless): x = units S D^-1 S f
    fs, Gs = asm.scale * f, G * asm.scale[None, :]
    w_all = np.atleast_1d(np.asarray(omega, dtype=float))
    out = np.empty((len(w_all), len(outputs)), dtype=complex)
    lossy = loss_factor(frame) > 0.0
    for j, w in enumerate(w_all):
        if lossy:  # the members' stiffnesses complex: the damped frame's D (dashpots in it)
            Dc = complex_matrix(asm, w)
        else:
            D, _ = asm.matrix(w)
            Dc = D + 1j * w * asm.C_lumped
        try:
            out[j] = units * (Gs @ np.linalg.solve(Dc, fs))
        except np.linalg.LinAlgError:
            out[j] = np.nan
    return out if many else out[:, 0]

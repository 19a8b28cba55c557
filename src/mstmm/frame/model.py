"""A plane frame as data: nodes, members between them, supports and what the nodes carry.

Sign convention (docs/frames.md): global axes X, Y in the plane, rotations Theta
counterclockwise. A member runs from its ``start`` node to its ``end`` node; its local
``x`` points from start to end, its local ``y`` is ``x`` turned +90 degrees; along it
``u`` is the axial displacement, ``w`` the transverse one (along local y) and ``psi`` the
section's rotation (``dw/dx`` without shear deformation), as the beam's ``[Y, theta]``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["Absorber", "Frame", "FrameSegment", "Member", "Node"]


@dataclass(frozen=True)
class FrameSegment:
    """One stretch of a member with uniform properties (SI), from its start: the beam's
    segment keys (``EI``, ``mass_per_length`` and the declared terms of
    ``catalog.SEGMENT_PHYSICS``, each 0 when absent) and the axial stiffness ``EA``; out of
    the plane (a grillage), ``EI`` is the bending stiffness about the member's in-plane
    axis, ``GJ`` its torsional stiffness (N m^2) and ``rho_Ip`` its polar mass moment of
    inertia per length (kg m)."""

    length: float
    EI: float
    EA: float
    mass_per_length: float
    physics: tuple[tuple[str, float], ...] = ()
    GJ: float = 0.0
    rho_Ip: float = 0.0
    #: The material's loss factor eta: EI, EA (GJ) and each term declared with a loss
    #: times (1 + i eta) (a damped frame: :mod:`mstmm.frame.damped`).
    loss_factor: float = 0.0


@dataclass(frozen=True)
class Member:
    """A straight member from node ``start`` to node ``end`` made of ``segments`` (from the
    start); ``pinned`` ends carry no moment into the node, unless a rotational spring
    ``hinge_k`` (N m/rad) joins the member's end to the node there."""

    name: str
    start: str
    end: str
    segments: tuple[FrameSegment, ...]
    pinned: tuple[bool, bool] = (False, False)
    hinge_k: tuple[float, float] = (0.0, 0.0)


@dataclass(frozen=True)
class Absorber:
    """A mass ``m`` on a spring ``k`` (and a parallel dashpot ``c``, N s/m) hung at
    ``node``, moving along the unit vector ``direction`` (a tuned mass damper on a roof
    acts horizontally)."""

    node: str
    k: float
    m: float
    direction: tuple[float, float]
    c: float = 0.0


@dataclass(frozen=True)
class Node:
    """A joint at (x, y): the freedoms a support holds (``"x"``, ``"y"``, ``"t"`` in the
    global axes, or ``"n"``: the translation along ``normal``, a roller), springs to
    ground (``(k_xx, k_xy, k_yy)`` N/m on the translations, ``k_t`` N m/rad on Theta) and a
    node mass with its rotary inertia."""

    name: str
    x: float
    y: float
    held: str = ""
    normal: tuple[float, float] = (0.0, 1.0)
    springs: tuple[float, float, float] = (0.0, 0.0, 0.0)
    k_t: float = 0.0
    mass: float = 0.0
    J: float = 0.0


@dataclass(frozen=True)
class Frame:
    """A plane frame: its nodes (by name, in file order), its members and its absorbers.
    ``source`` names the file it came from (messages name it). ``motion``: ``"in_plane"``
    (axial and bending in the plane: X, Y, Theta at the nodes) or ``"out_of_plane"`` (a
    grillage: torsion and bending out of the plane, W along Z and the rotations ThetaX,
    ThetaY about X and Y at the nodes)."""

    name: str
    nodes: dict[str, Node]
    members: tuple[Member, ...]
    absorbers: tuple[Absorber, ...] = ()
    source: str = "<frame>"
    motion: str = "in_plane"

    def geometry(self, member: Member) -> tuple[float, float, float]:
        """``(L, c, s)``: the member's length and its local x as (cos, sin) in the global axes."""
        a, b = self.nodes[member.start], self.nodes[member.end]
        dx, dy = b.x - a.x, b.y - a.y
        L = math.hypot(dx, dy)
        return L, dx / L, dy / L

    @property
    def mass(self) -> float:
        """Total mass (kg): members, node masses and absorbers."""
        total = sum(s.mass_per_length * s.length for m in self.members for s in m.segments)
        total += sum(n.mass for n in self.nodes.values())
        return total + sum(a.m for a in self.absorbers)

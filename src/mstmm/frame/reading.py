"""A frame scene (TOML, SI units) read as data into a :class:`~mstmm.frame.model.Frame`.

::

    name = "portal"
    [[nodes]]                  # every node: a name and its coordinates (m)
    name = "A"
    x = 0.0
    y = 0.0
    support = "fixed"          # free (default) | fixed | pinned | roller | sliding
    # normal = [0.0, 1.0]      # roller, sliding: the direction held (default +Y)
    # k_x, k_y, k_t            # springs to ground (N/m, N/m, N m/rad); mass (kg), J (kg m^2)
    [[members]]
    name = "column"            # optional (default "m<i>")
    start = "A"                # local x from start to end
    end = "B"
    EI = 2.1e7                 # and mass_per_length, EA, and any segment term of a beam
    EA = 4.2e9                 # (kappa_GA, rho_I, axial_force, foundation_k, ...), or
    mass_per_length = 50.0     # [[members.segments]] from the start with length each
    # start_joint = "pinned"   # rigid (default) | pinned; start_k: a spring at the pin
    [[attachments]]            # at a node, or along a member (x from its start)
    type = "spring_mass"       # mass (m, J), spring (k), rotational_spring (k), spring_mass
                               # (k, m and a dashpot c: frequency responses only)
    node = "B"                 # or member = "column" and x = 1.5
    direction = [1.0, 0.0]     # spring, spring_mass: along (default: the member's local y)
    k = 1e4
    m = 20.0

An attachment along a member makes a node there (``<member>@<x>``) that splits the
member. Every problem is a :class:`mstmm.scene.SceneError` naming the field
(``members[2].EI``, ``nodes[0].support``, ``attachments[1].node``).
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

from mstmm.scene import SceneError
from mstmm.scene.fields import _checked, _choice, _number, _reject_unknown, _require, _table
from mstmm.scene.reading import is_frame, read_table
from mstmm.scene.segments import _OPTIONAL_KEYS, _optional

from .model import Absorber, Frame, FrameSegment, Member, Node

__all__ = ["frame_from_dict", "frame_from_file", "is_frame", "load_frame", "with_points"]

#: What each support holds: global freedoms x, y, t (Theta), n (along ``normal``); out of
#: the plane z (W), a (ThetaX), b (ThetaY).
SUPPORTS = {"free": "", "fixed": "xyt", "pinned": "xy", "roller": "n", "sliding": "nt"}
SUPPORTS_OUT = {"free": "", "fixed": "zab", "pinned": "z"}
MOTIONS = ("in_plane", "out_of_plane")
_NODE_KEYS = ("name", "x", "y", "support", "normal", "k_x", "k_y", "k_t", "mass", "J")
_NODE_KEYS_OUT = ("name", "x", "y", "support", "k_z", "mass", "J")
_PROPERTY_KEYS = ("EI", "EA", "mass_per_length")
#: A grillage member's properties: EI about its in-plane axis, torsion GJ and rho_Ip.
_PROPERTY_KEYS_OUT = ("EI", "GJ", "rho_Ip", "mass_per_length")
_MEMBER_KEYS = (
    "name", "start", "end", *_PROPERTY_KEYS, "GJ", "rho_Ip", "segments",
    "start_joint", "end_joint", "start_k", "end_k", *_OPTIONAL_KEYS,
)  # fmt: skip
_SEGMENT_KEYS = ("length", *_PROPERTY_KEYS, "GJ", "rho_Ip", *_OPTIONAL_KEYS)
_ATTACHMENT_KEYS = {
    "mass": ("m", "J"),
    "spring": ("k",),
    "rotational_spring": ("k",),
    "spring_mass": ("k", "m", "c"),
}
#: Keys that may be left out (default 0).
_OPTIONAL_ATTACHMENT_KEYS = ("J", "c")
#: Relative mismatch allowed between a member's length and the sum of its segments'.
LENGTH_MATCH = 1e-9


def load_frame(path: str | os.PathLike[str]) -> Frame:
    """Read a frame scene file (one clear :class:`SceneError` for any problem)."""
    return frame_from_file(*read_table(path))


def frame_from_file(data: Any, source: str) -> Frame:
    """The frame of a file's TOML document (``scene.reading.read_table``): its name, else
    the file's stem."""
    name = os.path.splitext(os.path.basename(source))[0]
    return frame_from_dict(data, source, name)


def frame_from_dict(data: Mapping[str, Any], source: str = "<dict>", name: str = "frame") -> Frame:
    """A :class:`Frame` from a table of the format above."""
    _reject_unknown(data, ("name", "motion", "nodes", "members", "attachments"), "", source)
    if not isinstance(data.get("name", name), str):
        raise SceneError(source, "name", "must be a string", data["name"])
    motion = _choice(data.get("motion", "in_plane"), MOTIONS, "motion", source)
    nodes = _nodes(_array(data, "nodes", source), source, motion)
    members = _members(_array(data, "members", source), nodes, source, motion)
    reached = {n for m in members for n in (m.start, m.end)}
    for i, n in enumerate(nodes):
        if n not in reached:
            raise SceneError(source, f"nodes[{i}].name", "no member reaches this node", n)
    nodes, members, absorbers = _attachments(
        data.get("attachments", []), nodes, members, source, motion
    )
    return Frame(
        str(data.get("name", name)), nodes, tuple(members), tuple(absorbers), source, motion
    )


def _array(data: Mapping[str, Any], key: str, source: str) -> list:
    value = _require(data, key, "", source)
    if not isinstance(value, list) or not value:
        raise SceneError(source, key, f"must be a non-empty array of tables ([[{key}]])", value)
    return value


def _name(value: Any, path: str, source: str) -> str:
    if not isinstance(value, str) or not value or "@" in value:
        raise SceneError(source, path, "must be a non-empty string without '@'", value)
    return value


def _direction(value: Any, path: str, source: str) -> tuple[float, float]:
    if not isinstance(value, list) or len(value) != 2:
        raise SceneError(source, path, "must be two numbers [x, y]", value)
    x, y = (_number(v, f"{path}[{j}]", source) for j, v in enumerate(value))
    norm = math.hypot(x, y)
    if norm == 0.0:
        raise SceneError(source, path, "must not be the zero vector", value)
    return x / norm, y / norm


def _nodes(items: list, source: str, motion: str = "in_plane") -> dict[str, Node]:
    nodes: dict[str, Node] = {}
    where: dict[tuple[float, float], str] = {}
    for i, item in enumerate(items):
        prefix = f"nodes[{i}]"
        table = _table(item, prefix, source)
        out = motion == "out_of_plane"
        _reject_unknown(table, _NODE_KEYS_OUT if out else _NODE_KEYS, prefix, source)
        name = _name(_require(table, "name", prefix, source), f"{prefix}.name", source)
        if name in nodes:
            raise SceneError(source, f"{prefix}.name", "a second node of this name", name)
        x, y = (_number(_require(table, k, prefix, source), f"{prefix}.{k}", source) for k in "xy")
        if (x, y) in where:
            raise SceneError(
                source, f"{prefix}.x", f"node {where[(x, y)]!r} is already at this point", x
            )
        where[(x, y)] = name
        supports = SUPPORTS_OUT if out else SUPPORTS
        support = _choice(
            table.get("support", "free"), tuple(supports), f"{prefix}.support", source
        )
        normal = (0.0, 1.0)
        if "normal" in table:
            if support not in ("roller", "sliding"):
                raise SceneError(
                    source,
                    f"{prefix}.normal",
                    "only a roller or a sliding support has one",
                    support,
                )
            normal = _direction(table["normal"], f"{prefix}.normal", source)
        optional = {
            k: _checked(table.get(k, 0.0), "nonnegative", f"{prefix}.{k}", source)
            for k in ("k_x", "k_y", "k_z", "k_t", "mass", "J")
        }
        # out of the plane the springs' first slot is k_z on W (the freedoms' first)
        springs = (optional["k_z"], 0.0, 0.0) if out else (optional["k_x"], 0.0, optional["k_y"])
        nodes[name] = Node(
            name, x, y, supports[support], normal, springs, optional["k_t"], optional["mass"],
            optional["J"],
        )  # fmt: skip
    return nodes


def _segment(
    table: Mapping[str, Any], prefix: str, length: float, source: str, motion: str
) -> FrameSegment:
    out = motion == "out_of_plane"
    for key in ("EA",) if out else ("GJ", "rho_Ip"):
        if key in table:
            problem = (
                "not used out of the plane (a grillage member takes GJ and rho_Ip)"
                if out
                else "torsion is out of the plane: set motion = 'out_of_plane' (docs/frames.md)"
            )
            raise SceneError(source, f"{prefix}.{key}", problem, table[key])
    keys = _PROPERTY_KEYS_OUT if out else _PROPERTY_KEYS
    got = {
        k: _checked(_require(table, k, prefix, source), "nonnegative" if k == "rho_Ip" else
                    "positive", f"{prefix}.{k}", source)
        for k in keys
    }  # fmt: skip
    physics = _optional(table, prefix, source)
    eta = float(physics.pop("loss_factor", 0.0))
    return FrameSegment(
        length, got["EI"], got.get("EA", 0.0), got["mass_per_length"], tuple(physics.items()),
        got.get("GJ", 0.0), got.get("rho_Ip", 0.0), eta,
    )  # fmt: skip


def _members(
    items: list, nodes: dict[str, Node], source: str, motion: str = "in_plane"
) -> list[Member]:
    members: list[Member] = []
    names: set[str] = set()
    for i, item in enumerate(items):
        prefix = f"members[{i}]"
        table = _table(item, prefix, source)
        _reject_unknown(table, _MEMBER_KEYS, prefix, source)
        name = _name(table.get("name", f"m{i}"), f"{prefix}.name", source)
        if name in names:
            raise SceneError(source, f"{prefix}.name", "a second member of this name", name)
        names.add(name)
        ends = []
        for key in ("start", "end"):
            node = _require(table, key, prefix, source)
            if node not in nodes:
                raise SceneError(source, f"{prefix}.{key}", "no node of this name", node)
            ends.append(node)
        a, b = nodes[ends[0]], nodes[ends[1]]
        length = math.hypot(b.x - a.x, b.y - a.y)
        if length == 0.0:
            raise SceneError(source, f"{prefix}.end", "a member of zero length", ends[1])
        segments = _member_segments(table, prefix, length, source, motion)
        pinned, hinge = [], []
        for key in ("start", "end"):
            joint = _choice(
                table.get(f"{key}_joint", "rigid"), ("rigid", "pinned"), f"{prefix}.{key}_joint",
                source,
            )  # fmt: skip
            k = _checked(table.get(f"{key}_k", 0.0), "nonnegative", f"{prefix}.{key}_k", source)
            if joint == "pinned" and motion == "out_of_plane":
                raise SceneError(
                    source, f"{prefix}.{key}_joint",
                    "a released member end is in the plane only in this version", joint,
                )  # fmt: skip
            if k and joint != "pinned":
                raise SceneError(
                    source, f"{prefix}.{key}_k", f"a spring at a pin: set {key}_joint = 'pinned'", k
                )
            pinned.append(joint == "pinned")
            hinge.append(k)
        members.append(Member(name, ends[0], ends[1], segments, tuple(pinned), tuple(hinge)))
    return members


def _member_segments(
    table: Mapping[str, Any], prefix: str, length: float, source: str, motion: str
) -> tuple[FrameSegment, ...]:
    if "segments" not in table:
        return (_segment(table, prefix, length, source, motion),)
    for key in (*_PROPERTY_KEYS, "GJ", "rho_Ip", *_OPTIONAL_KEYS):
        if key in table:
            raise SceneError(
                source, f"{prefix}.{key}", "not with [[members.segments]]: give it per segment",
                table[key],
            )  # fmt: skip
    items = table["segments"]
    if not isinstance(items, list) or not items:
        raise SceneError(source, f"{prefix}.segments", "must be a non-empty array of tables", items)
    out = []
    for s, item in enumerate(items):
        sp = f"{prefix}.segments[{s}]"
        st = _table(item, sp, source)
        _reject_unknown(st, _SEGMENT_KEYS, sp, source)
        h = _checked(_require(st, "length", sp, source), "positive", f"{sp}.length", source)
        out.append(_segment(st, sp, h, source, motion))
    total = sum(s.length for s in out)
    if abs(total - length) > LENGTH_MATCH * length:
        raise SceneError(
            source, f"{prefix}.segments",
            f"the segments' lengths add up to {total!r} m, the member is {length!r} m long", total,
        )  # fmt: skip
    last = out[-1]
    rest = length - sum(s.length for s in out[:-1])
    return (*out[:-1], replace(last, length=rest))


def _attachments(
    items: Any, nodes: dict[str, Node], members: list[Member], source: str,
    motion: str = "in_plane",
):  # fmt: skip
    """Node attachments added to their nodes; member attachments split their member at a
    new node (out of the plane: springs and absorbers act along Z, no rotational spring).
    Returns (nodes, members, absorbers)."""
    out = motion == "out_of_plane"
    if not isinstance(items, list):
        raise SceneError(source, "attachments", "must be an array of tables", items)
    nodes = dict(nodes)
    absorbers: list[Absorber] = []
    by_name = {m.name: m for m in members}
    cuts: dict[str, list[tuple[float, str]]] = {}
    placed = []
    for i, item in enumerate(items):
        prefix = f"attachments[{i}]"
        table = _table(item, prefix, source)
        kind = _choice(_require(table, "type", prefix, source), tuple(_ATTACHMENT_KEYS),
                       f"{prefix}.type", source)  # fmt: skip
        keys = _ATTACHMENT_KEYS[kind]
        _reject_unknown(table, ("type", "node", "member", "x", "direction", *keys), prefix, source)
        values = {
            k: _checked(table.get(k, 0.0), "nonnegative", f"{prefix}.{k}", source)
            for k in keys
            if k in table or k in _OPTIONAL_ATTACHMENT_KEYS
        }
        for k in keys:
            if k not in values:
                raise SceneError(source, f"{prefix}.{k}", "missing")
        if ("node" in table) == ("member" in table):
            raise SceneError(source, prefix, "give either node or member (with x)")
        direction = None
        if out and (kind == "rotational_spring" or "direction" in table):
            what = "a rotational spring" if kind == "rotational_spring" else "a direction"
            raise SceneError(
                source, f"{prefix}.{'type' if kind == 'rotational_spring' else 'direction'}",
                f"{what} out of the plane is not built in this version (springs and absorbers"
                " act along Z)", table.get("direction", kind),
            )  # fmt: skip
        if out:
            direction = (1.0, 0.0)  # W is each node's first freedom: along Z
        if "direction" in table:
            if kind in ("mass", "rotational_spring"):
                raise SceneError(source, f"{prefix}.direction", f"a {kind} has no direction",
                                 table["direction"])  # fmt: skip
            direction = _direction(table["direction"], f"{prefix}.direction", source)
        if "node" in table:
            node = table["node"]
            if node not in nodes:
                raise SceneError(source, f"{prefix}.node", "no node of this name", node)
            if direction is None and kind in ("spring", "spring_mass"):
                raise SceneError(source, f"{prefix}.direction", "missing (at a node)")
        else:
            member = table["member"]
            if member not in by_name:
                raise SceneError(source, f"{prefix}.member", "no member of this name", member)
            m = by_name[member]
            L = _length(nodes, m)
            x = _checked(_require(table, "x", prefix, source), "interior", f"{prefix}.x", source, L)
            node = f"{member}@{x!r}"
            cuts.setdefault(member, []).append((x, node))
            if direction is None:
                a, b = nodes[m.start], nodes[m.end]
                direction = (-(b.y - a.y) / L, (b.x - a.x) / L)
        placed.append((kind, node, values, direction))
    members = [
        piece for m in members for piece in _split(m, sorted(set(cuts.get(m.name, []))), nodes)
    ]
    for kind, node, values, direction in placed:
        n = nodes[node]
        if kind == "mass":
            nodes[node] = _with(n, mass=n.mass + values["m"], J=n.J + values["J"])
        elif kind == "rotational_spring":
            nodes[node] = _with(n, k_t=n.k_t + values["k"])
        elif kind == "spring":  # k d d^T on the translations
            k, (dx, dy) = values["k"], direction
            kxx, kxy, kyy = n.springs
            nodes[node] = _with(
                n, springs=(kxx + k * dx * dx, kxy + k * dx * dy, kyy + k * dy * dy)
            )
        else:
            absorbers.append(Absorber(node, values["k"], values["m"], direction, values["c"]))
    return nodes, members, absorbers


def _with(node: Node, **changes) -> Node:
    values = {**node.__dict__, **changes}
    return Node(**values)


def _length(nodes: dict[str, Node], m: Member) -> float:
    a, b = nodes[m.start], nodes[m.end]
    return math.hypot(b.x - a.x, b.y - a.y)


def _split(m: Member, cuts: list[tuple[float, str]], nodes: dict[str, Node]) -> list[Member]:
    """The member cut at each (x, node name), the new nodes added to ``nodes``."""
    if not cuts:
        return [m]
    a, b = nodes[m.start], nodes[m.end]
    L = _length(nodes, m)
    for x, name in cuts:
        if name not in nodes:
            t = x / L
            nodes[name] = Node(name, a.x + t * (b.x - a.x), a.y + t * (b.y - a.y))
    stations = [0.0] + [x for x, _ in cuts] + [L]
    names = [m.start] + [n for _, n in cuts] + [m.end]
    out = []
    for j in range(len(stations) - 1):
        lo, hi = stations[j], stations[j + 1]
        segments = []
        start = 0.0
        for s in m.segments:
            end = start + s.length
            piece = min(end, hi) - max(start, lo)
            if piece > 0.0:
                segments.append(replace(s, length=piece))
            start = end
        pinned = (m.pinned[0] and j == 0, m.pinned[1] and j == len(stations) - 2)
        hinge = (m.hinge_k[0] if j == 0 else 0.0, m.hinge_k[1] if j == len(stations) - 2 else 0.0)
        name = m.name if len(stations) == 2 else f"{m.name}[{j}]"
        out.append(Member(name, names[j], names[j + 1], tuple(segments), pinned, hinge))
    return out


def with_points(
    frame: Frame, points: list[tuple[str, float]], roles: list[str] | None = None
) -> tuple[Frame, list[str]]:
    """The frame with a node at each ``(member, x)`` of ``points`` (x in m from the
    member's start node), and the names of those nodes (``<member>@<x>``, or the end
    node where x is an end). A member that attachments already cut is addressed by its
    scene name, x along the whole of it. The members stay exact: a cut adds a joint.
    Errors name the point's role (``roles``, aligned with ``points``)."""
    nodes = dict(frame.nodes)
    cuts: dict[str, list[tuple[float, str]]] = {}
    names = []
    for (member, x), role in zip(points, roles or ["point"] * len(points), strict=True):
        pieces = [m for m in frame.members if m.name == member] or [
            m for m in frame.members if m.name.startswith(f"{member}[") and m.name.endswith("]")
        ]
        if not pieces:
            raise SceneError(frame.source, role, "no member of this name", member)
        total = sum(_length(frame.nodes, m) for m in pieces)
        if not (isinstance(x, (int, float)) and 0.0 <= x <= total):
            raise SceneError(frame.source, role, f"x must lie on {member} (0 to {total:g} m)", x)
        offset = 0.0
        for m in pieces:
            L = _length(frame.nodes, m)
            if x <= offset + L or m is pieces[-1]:
                local = x - offset
                if local <= 0.0:
                    names.append(m.start)
                elif local >= L:
                    names.append(m.end)
                else:
                    name = f"{member}@{float(x)!r}"
                    cuts.setdefault(m.name, []).append((local, name))
                    names.append(name)
                break
            offset += L
    members = [
        piece
        for m in frame.members
        for piece in _split(m, sorted(set(cuts.get(m.name, []))), nodes)
    ]
    return Frame(
        frame.name, nodes, tuple(members), frame.absorbers, frame.source, frame.motion
    ), names

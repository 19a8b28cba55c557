"""The catalog of what decides a kernel's code: end conditions, component kinds, topologies,
and the parameter layout.

SymPy-free: the ground floor of the runtime (which names, validates and looks up kernels
with it) and of the derivation stages (``mstmm.derive`` reads the same definitions;
stages run one way: the runtime never imports ``mstmm.derive`` but to print a kernel for
a new topology). Two scenes share a kernel
when they have the same end conditions and the same *kinds* of components:
positions, values, segments and the number of components are run-time parameters,
because the kernel loops over an event table instead of unrolling it (DESIGN.md,
"Scale of the symbolic step"; docs/components.md).

A kind is one module (``src/mstmm/kinds/<kind>.py``, or any module given to
:func:`register_kind`) that declares ``KIND``, ``KEYS`` and its physics (:data:`PHYSICS`:
its energy, the energy of one stage, the freedom it constrains or the one it releases;
or, for an advanced kind, its descriptor and ``COUNT``);
this module only reads its plain-data declarations (``KEYS``, ``SAME_LENGTH``, ``DOC``).
"""

from __future__ import annotations

import importlib
import pkgutil
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from types import ModuleType

import numpy as np

from mstmm.physics import segment as segment_terms
from mstmm.physics.scales import UNIT_SCALES

#: State vector of planar bending, paper Eq. (1): displacement, rotation, moment, shear.
STATE = ("Y", "theta", "M", "Q")

#: Indices of the state variables that vanish at an end of each kind.
KNOWN_ZERO: dict[str, tuple[int, int]] = {
    "clamped": (0, 1),  # Y = theta = 0
    "pinned": (0, 2),  # Y = M = 0
    "free": (2, 3),  # M = Q = 0
    "sliding": (1, 3),  # theta = Q = 0
}

#: Each end condition's code in the parameter vector (``p[LEFT_END]``, ``p[RIGHT_END]``):
#: the ends are data, not code, so one kernel serves every end pair of its kinds.
END_CODES: tuple[str, ...] = tuple(KNOWN_ZERO)

#: Parameters of the beam at the head of the parameter vector (the first segment's EI
#: and mass per length are the reference units of the kernel).
BEAM_PARAMETERS = ("L", "EI", "mbar")

#: A segment's physics beyond Euler-Bernoulli: its terms (``mstmm/physics/terms/``, one
#: file each; ``mstmm.physics.segment``): scene key, check, unit, in column order. Each
#: defaults to 0, which means the term is absent (``kappa_GA`` 0: no shear deformation).
#: Tension is a positive ``axial_force``.
SEGMENT_PHYSICS: tuple[tuple[str, str, str], ...] = tuple(
    (t.name, t.check, t.unit) for t in segment_terms.terms()
)
#: The segment row's values, after x_end: the scene keys of a segment in their order.
SEGMENT_KEYS: tuple[str, ...] = (
    "EI",
    "mass_per_length",
    "loss_factor",
    *(key for key, _, _ in SEGMENT_PHYSICS),
)

#: Layout of the head of the parameter vector (docs/components.md, section 4): ``[L, EI_0, mbar_0,
#: n_seg, n_ev, left end, right end, (x_end, EI, mbar, eta, *terms) * n_seg, (tag, x, offset) *
#: n_ev, data...]`` (the ends as codes of :data:`END_CODES`; eta: the segment's loss factor, read
#: by damped kernels only; the terms of ``SEGMENT_PHYSICS``, all 0 for Euler-Bernoulli:
#: ``SEGMENT_COLUMNS``).
HEAD = 7
#: Where the head holds the ends' codes (:data:`END_CODES`).
LEFT_END = 5
RIGHT_END = 6
SEGMENT_WIDTH = 1 + len(SEGMENT_KEYS)
EVENT_WIDTH = 3
#: The column of each value in a segment row (the row of segment s starts at ``HEAD +
#: SEGMENT_WIDTH * s``): its right end, then :data:`SEGMENT_KEYS`. The numerics read these
#: names (``mstmm.numerics.layout``), never numeric offsets.
SEGMENT_COLUMNS: dict[str, int] = {"x_end": 0, **{k: 1 + j for j, k in enumerate(SEGMENT_KEYS)}}
#: The first column of the terms (``SEGMENT_PHYSICS``) in a segment row.
TERMS_COLUMN = SEGMENT_COLUMNS[SEGMENT_PHYSICS[0][0]] if SEGMENT_PHYSICS else SEGMENT_WIDTH


#: The pairs (i, j), i < j, of state indices in lexicographic order: the rows and columns
#: of a second compound (2x2 minors), as ``mstmm.derive.compound`` derives them and the
#: numerics index them (``mstmm.numerics.layout``).
PAIRS: tuple[tuple[int, int], ...] = tuple((i, j) for i in range(4) for j in range(i + 1, 4))


def unknown(kind: str) -> tuple[int, int]:
    """Indices of the state variables left unknown at an end of the given kind."""
    zero = KNOWN_ZERO[kind]
    return tuple(i for i in range(4) if i not in zero)  # type: ignore[return-value]


def shape_ends(left: str, right: str) -> tuple[int, ...]:
    """The ends the mode-shape march takes: the left end's unknowns, then the right end's
    knowns (state indices of [Y, theta, M, Q])."""
    return unknown(left) + KNOWN_ZERO[right]


def march_ends(p: Sequence[float]) -> tuple[int, ...]:
    """:func:`shape_ends` of the ends a parameter vector's head holds (the ends are data:
    one kernel serves every end pair)."""
    return shape_ends(END_CODES[int(p[LEFT_END])], END_CODES[int(p[RIGHT_END])])


@dataclass(frozen=True)
class Key:
    """One scene key of a component kind.

    ``check``: ``"position"`` (0 <= x <= L), ``"interior"`` (0 < x < L), ``"positive"``
    (> 0) or ``"nonnegative"`` (>= 0); ``default`` None means required; ``shape``
    ``"list"`` for a non-empty list of values (an oscillator chain's ``k`` and ``m``; a
    list key's default is repeated to the length of the kind's other lists). ``damping``:
    a damping value (a dashpot's ``c``): it enters only the kernels of damped scenes
    (complex arithmetic), and a scene with any nonzero one is damped.
    """

    name: str
    unit: str
    check: str = "positive"
    default: float | None = None
    shape: str = "scalar"
    doc: str = ""
    damping: bool = False

    def __post_init__(self) -> None:
        if self.unit not in UNIT_SCALES:
            raise ValueError(f"key {self.name!r}: unknown unit {self.unit!r}")
        if self.check not in ("position", "interior", "positive", "nonnegative"):
            raise ValueError(f"key {self.name!r}: unknown check {self.check!r}")
        if self.shape not in ("scalar", "list"):
            raise ValueError(f"key {self.name!r}: unknown shape {self.shape!r}")

    @property
    def scale(self) -> tuple[Fraction, Fraction, Fraction]:
        """Exponents of (L, EI_0, mbar_0) that make this key's value dimensionless."""
        return UNIT_SCALES[self.unit]


_REGISTRY: dict[str, ModuleType] = {}

#: What a kind declares of its physics, exactly one of: its energy over ``[Y, theta,
#: q...]``; the energy of one stage of a chain (``stage``); the freedoms of the beam it
#: holds (``CONSTRAINS``: a support); the freedom it lets jump and the key of the spring
#: across the jump (``RELEASES``: a hinge); or, for an advanced kind, its descriptor.
PHYSICS = ("energy", "stage", "CONSTRAINS", "RELEASES", "descriptor")


def count_rule(module: ModuleType) -> str:
    """How the Wittrick-Williams count sees a kind, from what it declares: a constraint
    (``CONSTRAINS``: its freedoms as a stiffness penalty), a split node (``RELEASES``: the
    rotation left of it eliminated first), else a stiffness (a node stiffness and the
    negative pivots of its unknowns); a kind in descriptor form says it (``COUNT``)."""
    if hasattr(module, "CONSTRAINS"):
        return "constraint"
    if hasattr(module, "RELEASES"):
        return "split"
    if hasattr(module, "descriptor"):
        return module.COUNT
    return "stiffness"


def _check_kind(module: ModuleType) -> None:
    for name in ("KIND", "KEYS", "DOC"):
        if not hasattr(module, name):
            raise ValueError(f"component kind module {module.__name__} has no {name}")
    physics = [name for name in PHYSICS if hasattr(module, name)]
    if len(physics) != 1:
        raise ValueError(
            f"component kind module {module.__name__} declares one of {', '.join(PHYSICS)}"
            f" (it has {', '.join(physics) or 'none'})"
        )
    if physics == ["descriptor"] and not hasattr(module, "COUNT"):
        raise ValueError(f"kind {module.KIND!r}: a kind in descriptor form declares COUNT")
    if getattr(module, "CONSTRAINS", ("Y",)) not in (("Y",), ("theta",)):
        raise ValueError(f"kind {module.KIND!r}: CONSTRAINS is ('Y',) or ('theta',)")
    released = getattr(module, "RELEASES", ("theta", "x"))
    if len(released) != 2 or released[0] != "theta":
        raise ValueError(f"kind {module.KIND!r}: RELEASES is ('theta', <key of its spring>)")
    names = [k.name for k in module.KEYS]
    if not names or names[0] != "x" or module.KEYS[0].check not in ("position", "interior"):
        raise ValueError(f"kind {module.KIND!r}: its first key must be the position x")
    if len(set(names)) != len(names) or "type" in names:
        raise ValueError(f"kind {module.KIND!r}: key names must be unique and not 'type'")
    if hasattr(module, "RELEASES") and released[1] not in names[1:]:
        raise ValueError(f"kind {module.KIND!r}: RELEASES names the key of its spring")
    rule = count_rule(module)
    if rule not in ("stiffness", "constraint", "split"):
        raise ValueError(f"kind {module.KIND!r}: COUNT must be stiffness|constraint|split")
    if getattr(module, "COUNT", rule) != rule:
        raise ValueError(
            f"kind {module.KIND!r}: its physics makes COUNT {rule!r}, not"
            f" {module.COUNT!r} (leave COUNT out)"
        )
    if not module.KIND.isidentifier() or "__" in module.KIND or module.KIND.startswith("_"):
        raise ValueError(f"kind name {module.KIND!r} must be an identifier without '__'")


def register_kind(module: ModuleType) -> None:
    """Add a component kind defined outside the package (its file enters the signature)."""
    _check_kind(module)
    kinds()
    _REGISTRY[module.KIND] = module


def kinds() -> dict[str, ModuleType]:
    """Every known kind: name -> its module (built-ins first, then registered ones)."""
    if not _REGISTRY:
        for name in builtin_kinds():
            module = importlib.import_module(f"{__package__}.kinds.{name}")
            _check_kind(module)
            _REGISTRY[name] = module
    return _REGISTRY


def builtin_kinds() -> tuple[str, ...]:
    """The kinds shipped with mstmm: every module in ``mstmm/kinds`` (found by
    listing the folder, so that adding a kind is adding its file), sorted by name."""
    from . import kinds as package

    return tuple(sorted(m.name for m in pkgutil.iter_modules(package.__path__)))


def kind(name: str) -> ModuleType:
    """The module of one kind; ValueError when unknown."""
    try:
        return kinds()[name]
    except KeyError:
        raise ValueError(f"unknown component kind {name!r}") from None


def damping_only(name: str) -> bool:
    """Whether a kind does nothing but damp (every key after x a damping value): a scene
    with one is damped, and its undamped twin leaves it out."""
    keys = kind(name).KEYS[1:]
    return bool(keys) and all(k.damping for k in keys)


def constrained(module: ModuleType) -> tuple[str, ...]:
    """The freedoms of the beam a kind holds (``CONSTRAINS``; ``("Y",)`` for a constraint
    in descriptor form), ``()`` for any other kind."""
    if hasattr(module, "CONSTRAINS"):
        return tuple(module.CONSTRAINS)
    return ("Y",) if count_rule(module) == "constraint" else ()


def splits_rotation(name: str) -> bool:
    """Whether a kind lets the rotation jump where it sits (a hinge: ``RELEASES``, the node
    gets a second rotation): a couple or a rotation there is ambiguous."""
    return count_rule(kind(name)) == "split"


def kind_file(name: str) -> Path:
    """The source file of a kind (hashed into a kernel's signature)."""
    return Path(kind(name).__file__).resolve()


@dataclass(frozen=True)
class Topology:
    """End conditions, the component kinds present, and whether the scene is damped (its
    kernel then works in complex arithmetic): everything the kernel code depends on."""

    left: str
    right: str
    kinds: tuple[str, ...] = ()
    damped: bool = False

    def __post_init__(self) -> None:
        for end in (self.left, self.right):
            if end not in KNOWN_ZERO:
                raise ValueError(f"unknown end condition {end!r}")
        for name in self.kinds:
            kind(name)
        if tuple(sorted(set(self.kinds))) != self.kinds:
            raise ValueError(f"kinds must be sorted and unique, got {self.kinds!r}")

    @property
    def key(self) -> str:
        """File-name-safe name of the topology, e.g. ``clamped_free__spring_mass``, or
        ``clamped_free_damped__dashpot__spring_mass`` for a damped scene."""
        ends = f"{self.left}_{self.right}" + ("_damped" if self.damped else "")
        return "__".join([ends, *self.kinds])

    @property
    def kernel_key(self) -> str:
        """The name of this topology's kernel: its kinds and whether it is damped, e.g.
        ``beam__spring_mass`` or ``damped__dashpot__spring_mass``. The ends are not in it:
        they are data (the parameter vector's head), and one kernel serves every end pair."""
        return "__".join(["damped" if self.damped else "beam", *self.kinds])

    @classmethod
    def from_key(cls, key: str) -> Topology:
        """Inverse of :attr:`key`; a :attr:`kernel_key` gives the topology of its kernel
        with clamped-free ends (any end pair has the same kernel)."""
        ends, *names = key.split("__")
        if ends in ("beam", "damped"):
            return cls("clamped", "free", tuple(names), ends == "damped")
        left, right, *damped = ends.split("_")
        if damped not in ([], ["damped"]):
            raise ValueError(f"not a topology key: {key!r}")
        return cls(left, right, tuple(names), bool(damped))

    @property
    def undamped(self) -> Topology:
        """The same structure without damping: the kinds that only damp (a dashpot) left
        out, real arithmetic (the start of the continuation of its roots)."""
        kinds = tuple(k for k in self.kinds if not damping_only(k))
        return Topology(self.left, self.right, kinds)

    def tag(self, name: str) -> int:
        """The tag of a kind in this topology's event table: its index in ``kinds``."""
        return self.kinds.index(name)


@dataclass(frozen=True)
class Component:
    """A point component as the layout reads it: kind, position (m) and its values
    (name -> float, or a tuple of floats for a list key), defaults filled in."""

    kind: str
    x: float
    values: Mapping[str, float | tuple[float, ...]]


def damped(segments: Sequence[tuple[float, ...]], components: Sequence[Component]) -> bool:
    """Whether a beam (segments ``(length, EI, mbar[, eta])``) carrying ``components`` is
    damped: a loss factor, a damping value (``Key.damping``) that is not zero, or a kind
    that only damps."""
    if any(len(seg) > 3 and float(seg[3]) != 0.0 for seg in segments):
        return True
    for name in {c.kind for c in components}:
        if damping_only(name):
            return True
    for c in components:  # on every solve: plain Python, no arrays
        for key in kind(c.kind).KEYS[1:]:
            if key.damping:
                v = value(c.kind, c.values, key)
                if any(float(a) != 0.0 for a in (v if key.shape == "list" else (v,))):
                    return True
    return False


def value(name: str, values: Mapping[str, float | Sequence[float]], key: Key):
    """A component's value of ``key``: given, or (a damping value left out) its default, a
    list's repeated to the length of the kind's first list."""
    if key.name in values or not (key.damping and key.default is not None):
        return values[key.name]
    if key.shape != "list":
        return key.default
    first = getattr(kind(name), "SAME_LENGTH", (None,))[0]
    return [key.default] * len(values.get(first, [0]))


def pack(name: str, values: Mapping[str, float | Sequence[float]]) -> list[float]:
    """A component's data block: its keys after x in declared order, a list preceded by
    its length (a damping value left out at its default)."""
    out: list[float] = []
    for key in kind(name).KEYS[1:]:
        v = value(name, values, key)
        if key.shape == "list":
            seq = [float(a) for a in v]  # type: ignore[union-attr]
            out.append(float(len(seq)))
            out.extend(seq)
        else:
            out.append(float(v))  # type: ignore[arg-type]
    return out


def layout(
    segments: Sequence[tuple[float, ...]],
    components: Sequence[Component],
    topology: Topology,
) -> tuple[np.ndarray, dict[str, int]]:
    """The parameter vector of a beam (segments ``(length, EI, mbar[, eta, kappa_GA, rho_I,
    P, k_w, k_G])`` from the left end, eta the loss factor and the rest the physics of
    ``SEGMENT_PHYSICS``, each default 0) carrying ``components`` (in scene order), and the
    index of every field in it.

    Field paths: ``beam.length`` (total), ``beam.EI``, ``beam.mass_per_length`` (first
    segment), ``beam.loss_factor`` and ``beam.<physics key>`` (a uniform beam's),
    ``beam.segments[s].<key>`` (every key of ``SEGMENT_KEYS``),
    ``attachments[i].x``, ``attachments[i].<key>`` and
    ``attachments[i].<key>[j]`` for a list key. The event rows are sorted by x (stable);
    their offsets point at each component's data block.
    """
    lengths = [float(s[0]) for s in segments]
    total = float(sum(lengths))
    n_seg = len(segments)
    n_ev = len(components)
    head = [total, float(segments[0][1]), float(segments[0][2]), float(n_seg), float(n_ev)]
    head += [float(END_CODES.index(topology.left)), float(END_CODES.index(topology.right))]
    seg_rows: list[float] = []
    end = 0.0
    for s, (length, *values) in enumerate(segments):
        end = total if s == n_seg - 1 else end + float(length)
        values += [0.0] * (len(SEGMENT_KEYS) - len(values))
        seg_rows += [end, *(float(v) for v in values)]
    data_start = HEAD + SEGMENT_WIDTH * n_seg + EVENT_WIDTH * n_ev
    fields = {"beam.length": 0, "beam.EI": 1, "beam.mass_per_length": 2}
    for j, name in enumerate(SEGMENT_KEYS[2:]):
        fields[f"beam.{name}"] = HEAD + 3 + j
    for s in range(n_seg):
        for j, name in enumerate(SEGMENT_KEYS):
            fields[f"beam.segments[{s}].{name}"] = HEAD + SEGMENT_WIDTH * s + 1 + j
    data: list[float] = []
    rows: list[tuple[float, int, list[float]]] = []
    for i, c in enumerate(components):
        offset = data_start + len(data)
        block = pack(c.kind, c.values)
        j = offset
        for key in kind(c.kind).KEYS[1:]:
            if key.shape == "list":
                n = int(block[j - offset])
                for a in range(n):
                    fields[f"attachments[{i}].{key.name}[{a}]"] = j + 1 + a
                j += 1 + n
            else:
                fields[f"attachments[{i}].{key.name}"] = j
                j += 1
        data += block
        rows.append((float(c.x), i, [float(topology.tag(c.kind)), float(c.x), float(offset)]))
    order = sorted(range(n_ev), key=lambda i: rows[i][0])
    ev_rows: list[float] = []
    for r, i in enumerate(order):
        fields[f"attachments[{rows[i][1]}].x"] = HEAD + SEGMENT_WIDTH * n_seg + EVENT_WIDTH * r + 1
        ev_rows += rows[i][2]
    p = np.asarray(head + seg_rows + ev_rows + data, dtype=np.float64)
    return p, fields


def segment_columns() -> tuple:
    """A segment row's columns as the kernel reads them (printed into it as
    ``SEGMENT_COLUMNS``; ``kernels.load_kernel`` refuses a kernel whose columns differ): ``(name, SI
    unit, exponents of (L, EI_0, mbar_0) that make it dimensionless)`` in order, the terms'
    (``physics.segment``) after ``x_end``, ``EI``, ``mass_per_length``, ``loss_factor``."""
    head = (("x_end", "m", (-1, 0, 0)), ("EI", "N m^2", (0, -1, 0)))
    head += (("mass_per_length", "kg/m", (0, 0, -1)), ("loss_factor", "1", (0, 0, 0)))
    terms = tuple(
        (t.name, t.unit, tuple(int(e) if e.denominator == 1 else str(e) for e in t.scale))
        for t in segment_terms.terms()
    )
    return head + terms


def data_blocks(kinds: tuple[str, ...]) -> dict:
    """Each kind's data block as the kernel reads it (printed into it as ``DATA_BLOCKS``):
    ``(key, SI unit, shape)`` after x, in declared order (``catalog.pack``)."""
    return {k: tuple((key.name, key.unit, key.shape) for key in kind(k).KEYS[1:]) for k in kinds}


def damping_columns(p: np.ndarray, kinds: Sequence[str]) -> np.ndarray:
    """Indices of every damping value in a parameter vector: each segment's loss factor
    and each component's damping keys (``Key.damping``, list entries included); ``kinds``
    are the topology's, which the event tags index. Scaling them together scales the
    damping (the continuation of ``mstmm.damped``)."""
    n_seg = int(p[3])
    cols = [HEAD + SEGMENT_WIDTH * s + 3 for s in range(n_seg)]
    table = np.asarray(p[event_rows(p)]).reshape(-1, EVENT_WIDTH)
    for tag, _, offset in table:
        j = int(offset)
        for key in kind(kinds[int(tag)]).KEYS[1:]:
            if key.shape == "list":
                n = int(p[j])
                if key.damping:
                    cols += range(j + 1, j + 1 + n)
                j += 1 + n
            else:
                if key.damping:
                    cols.append(j)
                j += 1
    return np.asarray(cols, dtype=np.int64)


def event_rows(p: np.ndarray) -> slice:
    """The columns of the event table in a parameter vector (rows of EVENT_WIDTH)."""
    n_seg = int(p[3])
    start = HEAD + SEGMENT_WIDTH * n_seg
    return slice(start, start + EVENT_WIDTH * int(p[4]))

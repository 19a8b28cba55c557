"""Scene files: a beam with its boundary conditions and the components it carries.

A scene is a TOML file (SI units), read as data and never evaluated::

    name = "wu_chou_1998"          # optional; default: the file stem
    [beam]
    left = "clamped"               # clamped | pinned | free | sliding
    right = "free"
    length = 1.0                   # a uniform beam: length (m), EI (N m^2) and
    EI = 63476.125002707834        # mass_per_length (kg/m), OR a stepped beam:
    mass_per_length = 15.3875      # [[beam.segments]] from the left end, each with
                                   # length, EI and mass_per_length (then none of the three here)
    kappa_GA = 2.1e9               # optional on [beam] or on each segment: Timoshenko shear
    rho_I = 0.004                  # stiffness (N) and rotary inertia per length (kg m),
    axial_force = 1e4              # axial force (N, tension positive), Winkler foundation
    foundation_k = 0.0             # (N/m^2) and Pasternak shear layer (N); all default 0
    foundation_kG = 0.0            # (kappa_GA 0: no shear deformation, Euler-Bernoulli)
    [[attachments]]                # zero or more components
    type = "spring_mass"           # any kind of mstmm.catalog.kinds()
    x = 0.1                        # m from the left end
    k = 190428.3750081235          # the kind's keys (src/mstmm/kinds/<kind>.py, KEYS)
    m = 3.0775

Every kind is read from its declared keys (``KEYS``: name, unit, check, default,
shape): there is no per-kind code here. A key of another kind is an unknown key; a
key without a default is required; a list key (an oscillator chain's ``k`` and ``m``)
is a non-empty list of numbers, and the keys a kind names in ``SAME_LENGTH`` have equal
lengths. Placement rules that hold for any kind that declares the same physics: a
constraint of Y (``CONSTRAINS``, a support) may not sit where an end or another
constraint already fixes Y (one message, "a redundant constraint"), nor two hinges at
one x; a component
that acts on the rotation (a key in N m/rad or kg m^2 with a value > 0) may not sit
at exactly the x of a hinge (``RELEASES``), whose two sides rotate apart.

A finite periodic structure (a metamaterial beam of N cells) is one cell and a count::

    repeat = 100                   # optional: N cells end to end (an integer, 1 to 10_000_000)
    [beam]                         # ONE cell (uniform or [[beam.segments]]); left and
    left = "clamped"               # right are the ends of the whole structure
    right = "free"
    length = 0.1
    EI = 63.5
    mass_per_length = 1.5
    [[attachments]]                # the attachments of ONE cell, 0 <= x < cell length
    type = "spring_mass"           # (x = cell length would be x = 0 of the next cell)
    x = 0.05
    k = {linear = [1e3, 2e3]}      # graded: cell j gets first + (last - first) j / (N - 1)
    m = {each = [0.01, 0.02, ...]} # or one value per cell (exactly N numbers)

The scene built is the expanded one, which every solver reads: a uniform beam of length
``N * length`` (or the cell's segments N times), cell ``j``'s attachments at ``x + j *
length`` (sorted by x as ever). Any scalar value of an attachment but ``x`` may be graded
(``linear``: the last cell gets exactly ``last``; one cell: ``first``); every graded value
passes the key's check (a failure names ``attachments[i].k (cell
j)``); placement and what float64 can carry are checked on the whole structure.
``Scene.repeat`` and ``Scene.cell`` (the validated cell, graded values at cell 0;
``Scene.graded`` says whether any value is graded) keep the cell; they take no part in
``==``.

Every problem found in a scene raises :class:`SceneError`, whose message is a
single line ``{source}: {field}: {problem} (got {value!r})``, where ``field`` is
the TOML path of the offending entry (``beam.EI``, ``beam.segments[1].EI``,
``attachments[2].k``, ``attachments[2].k[1]``; the index is the position in the
file, counted from 0) or ``-`` when the file as a whole is at fault.  For a
missing key there is no value and the ``(got ...)`` part is left out.

This package only reads; it writes nothing anywhere. Its modules, each importing only
those above it:

* ``errors``: :class:`SceneError` and how its message shows a value;
* ``paths``: the field paths messages name (a key, a component, a segment, a cell's);
* ``fields``: one entry of a table (a number passing a check, a choice, no unknown key);
* ``float64``: the range float64 can carry, and the check of a product of values;
* ``columns``: the components of parameter vectors by kind, and their keys' columns;
* ``segments``: :class:`Beam` and :class:`Segment`, their keys and physics limits;
* ``attachments``: :class:`Attachment`, read by its kind's declared keys;
* ``placement``, ``representable``, ``band``: where components may sit, what float64
  can carry, which bands can be searched;
* ``model``: :class:`Scene`, built from a table without ``repeat``;
* ``repeat``: ``repeat = N`` cells and graded values;
* ``reading``: :func:`load_scene` and :func:`scene_from_dict`.
"""

from __future__ import annotations

from typing import Any

from .attachments import Attachment, SpringMass, Value, attachment_types
from .band import MAX_BAND_MODES, check_band
from .errors import SceneError
from .fields import CHECKS
from .float64 import REPRESENTABLE_MAX, REPRESENTABLE_MIN
from .model import Scene, scene_to_dict
from .placement import check_placement
from .reading import load_scene, scene_from_dict
from .repeat import REPEAT_MAX
from .representable import check_representable
from .segments import BOUNDARY_KINDS, LOSS_FACTOR_MAX, PHYSICS_LIMITS, Beam, Segment

__all__ = [
    "ATTACHMENT_TYPES",  # noqa: F822 (module __getattr__: read from the registry)
    "BOUNDARY_KINDS",
    "CHECKS",
    "LOSS_FACTOR_MAX",
    "MAX_BAND_MODES",
    "PHYSICS_LIMITS",
    "REPEAT_MAX",
    "REPRESENTABLE_MAX",
    "REPRESENTABLE_MIN",
    "Attachment",
    "Beam",
    "Scene",
    "SceneError",
    "Segment",
    "SpringMass",
    "Value",
    "attachment_types",
    "check_band",
    "check_placement",
    "check_representable",
    "load_scene",
    "scene_from_dict",
    "scene_to_dict",
]


def __getattr__(name: str) -> Any:
    # ATTACHMENT_TYPES is read from the kind registry when asked for, so a kind
    # registered after this module was imported is listed (PEP 562).
    if name == "ATTACHMENT_TYPES":
        return attachment_types()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

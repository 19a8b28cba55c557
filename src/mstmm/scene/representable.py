"""Whether float64 arithmetic can carry a scene: every value of the beam, its segments and
its components, each value's dimensionless form and the products the numerics form
(:data:`~mstmm.scene.float64.REPRESENTABLE_MIN` to ``REPRESENTABLE_MAX``), then the
segments' physics limits (:data:`~mstmm.scene.segments.PHYSICS_LIMITS`).

``scene`` is a :class:`~mstmm.scene.Scene`, read as data (unannotated, as
:func:`mstmm.topology.topology_of` takes it): a scene is built a layer above."""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np

from mstmm import catalog

from ..topology import topology_of
from .columns import _KeyColumns, _kind_columns, _KindColumns
from .float64 import _check_product, _Factor
from .paths import _Names, _names, _Paths
from .segments import Beam, _check_physics

#: Products of the beam's parameters that the kernels and mode shapes form, as
#: exponents of (length, EI, mass_per_length) (the first segment's EI and mass per
#: length: the kernel's units).
_BEAM_PRODUCTS: tuple[tuple[str, tuple[int, int, int]], ...] = (
    ("length", (1, 0, 0)),
    ("EI", (0, 1, 0)),
    ("mass_per_length", (0, 0, 1)),
    ("length^4", (4, 0, 0)),
    ("EI/mass_per_length", (0, 1, -1)),
    ("the squared frequency scale EI/(mass_per_length length^4)", (-4, 1, -1)),
    ("EI/length^4", (-4, 1, 0)),
    ("mass_per_length length", (1, 0, 1)),
)
#: Stiffness and inertia units whose ratio within one component is a squared
#: frequency the numerics form (an oscillator's k/m).
_RATIOS = {"N/m": "kg", "N m/rad": "kg m^2"}
_BEAM_LABELS = ("length", "EI", "mass_per_length")


def _beam_factors(P: np.ndarray, beam: Beam, names: _Names) -> list[_Factor]:
    """The kernel's units: total length, the first segment's EI and mass per length."""
    paths = (
        ("beam.segments", names.segment(0, "EI"), names.segment(0, "mass_per_length"))
        if beam.segments
        else (names.length_path, "beam.EI", "beam.mass_per_length")
    )
    return [_Factor(n, P[:, [j]], (p,)) for j, (n, p) in enumerate(zip(_BEAM_LABELS, paths))]


def _beam_checks(
    P: np.ndarray, beam: Beam, head: Sequence[_Factor], names: _Names
) -> list[tuple[str, list[_Factor]]]:
    """The beam's values and products; for a stepped beam each segment's values and
    their ratios to the kernel's units."""
    checks = [
        (name, [f**e for f, e in zip(head, exponents) if e]) for name, exponents in _BEAM_PRODUCTS
    ]
    if beam.segments:
        n = len(beam.segments)
        rows = catalog.HEAD + catalog.SEGMENT_WIDTH * np.arange(n)
        paths = [
            _Paths(n, lambda s, k=k: names.segment(s, k))  # type: ignore[misc]
            for k in _BEAM_LABELS
        ]
        lengths = np.array([[s.length for s in beam.segments]], dtype=float)
        length = _Factor("length", lengths, paths[0])
        ei = _Factor("EI", P[:, rows + 1], paths[1])
        mu = _Factor("mass_per_length", P[:, rows + 2], paths[2])
        total = dataclasses.replace(head[0], label="(total length)")
        ei0 = dataclasses.replace(head[1], label="(first segment's EI)")
        mu0 = dataclasses.replace(head[2], label="(first segment's mass_per_length)")
        checks += [
            ("length", [length]),
            ("EI", [ei]),
            ("mass_per_length", [mu]),
            ("", [length, total**-1]),
            ("", [ei, ei0**-1]),
            ("", [mu, mu0**-1]),
            ("EI/mass_per_length", [ei, mu**-1]),
            ("", [mu, ei**-1, ei0, mu0**-1]),
        ]
    return checks


def _component_checks(
    P: np.ndarray, scene, head: Sequence[_Factor], names: _Names
) -> list[tuple[str, list[_Factor]]]:
    """Each key's value and its dimensionless form (``Key.scale``), the scale itself, and
    each stiffness/inertia ratio within a component with its dimensionless form;
    vectorised over the components of one kind.

    Positions are left out: the numerics use them only as x/L <= 1 and as differences,
    so a tiny x rounds towards the end it is next to, which is what it means."""
    checks: list[tuple[str, list[_Factor]]] = []

    def scaled(exponents) -> list[_Factor]:
        return [h ** float(e) for h, e in zip(head, exponents) if e]

    for g in _kind_columns(P, topology_of(scene).kinds):
        for kc in g.keys:
            zero_ok = kc.key.check == "nonnegative"
            f = _Factor(kc.key.name, P[:, kc.cols], _key_paths(g, kc, names), zero_ok=zero_ok)
            scale = scaled(kc.key.scale)
            checks += [(kc.key.name, [f])] + ([("", scale), ("", [f, *scale])] if scale else [])
        for stiff in g.keys:
            for inert in g.keys:
                if _RATIOS.get(stiff.key.unit) == inert.key.unit:
                    ratio = _ratio(g, stiff, inert, P, names)
                    scale = scaled([a - b for a, b in zip(stiff.key.scale, inert.key.scale)])
                    checks += [("", ratio), ("", [*ratio, *scale])] if ratio else []
    return checks


def _key_paths(g: _KindColumns, kc: _KeyColumns, names: _Names) -> _Paths:
    """The field path of each column of ``kc`` (list elements flattened)."""
    name, rows, owner, element = kc.key.name, g.rows, kc.owner, kc.element
    if element is None:
        return _Paths(len(kc.cols), lambda e: names.path(rows[owner[e]], name))
    return _Paths(len(kc.cols), lambda e: names.path(rows[owner[e]], f"{name}[{int(element[e])}]"))


def _ratio(
    g: _KindColumns, stiff: _KeyColumns, inert: _KeyColumns, P: np.ndarray, names: _Names
) -> list[_Factor]:
    """``stiff/inert`` of each component; for list keys, of each inertia with the
    stiffness on either side of it (an oscillator chain's k[j]/m[j], k[j+1]/m[j])."""
    if (stiff.element is None) != (inert.element is None):
        return []
    rows = g.rows
    if stiff.element is None:
        top, bottom = stiff.cols, inert.cols
        owner_top = owner_bottom = stiff.owner

        def top_path(e: int) -> str:
            return names.path(rows[owner_top[e]], stiff.key.name)

        def bottom_path(e: int) -> str:
            return names.path(rows[owner_bottom[e]], inert.key.name)

    else:
        # for each inertia element m[j] (component by component), k[j] then k[j + 1]
        m_flat = np.repeat(np.arange(len(inert.cols)), 2)
        owner = inert.owner[m_flat]
        j = inert.element[m_flat]  # type: ignore[index]
        i = j + np.tile([0, 1], len(inert.cols))
        keep = i < stiff.length[owner]
        m_flat, owner, j, i = m_flat[keep], owner[keep], j[keep], i[keep]
        top, bottom = stiff.cols[stiff.start[owner] + i], inert.cols[m_flat]

        def top_path(e: int) -> str:
            return names.path(rows[owner[e]], f"{stiff.key.name}[{int(i[e])}]")

        def bottom_path(e: int) -> str:
            return names.path(rows[owner[e]], f"{inert.key.name}[{int(j[e])}]")

    if not len(top):
        return []
    zero_ok = [k.key.check == "nonnegative" for k in (stiff, inert)]
    f_top = _Factor(stiff.key.name, P[:, top], _Paths(len(top), top_path), 1, zero_ok[0])
    f_bottom = _Factor(
        inert.key.name, P[:, bottom], _Paths(len(bottom), bottom_path), -1, zero_ok[1]
    )
    return [f_top, f_bottom]


def check_representable(
    P: np.ndarray,
    source: str,
    scene,
    point: str = "",
    labels: Sequence[int] | _Names | None = None,
) -> None:
    """Reject parameter vectors whose values or derived products float64 cannot carry.

    ``P`` holds parameter vectors of ``scene`` (one per row) whose event row ``r`` is
    ``scene.attachments[r]``, as :func:`mstmm.topology.parameter_vector` gives them (a
    sweep checks before it re-sorts the rows); ``scene`` gives the kinds the event tags
    index. ``labels[r]`` is the index attachment ``r`` is named by in messages (default
    ``r``; the place in the file when loading). Every
    beam and segment value, every component value but positions (zero allowed for
    nonnegative keys), each value's dimensionless form and the products the numerics
    form must lie in [:data:`REPRESENTABLE_MIN`, :data:`REPRESENTABLE_MAX`]. Raises
    :class:`SceneError` naming the field whose value is the most extreme contributor
    to the first product out of range, with that value; ``point`` (e.g. ``"point"``)
    makes the message say which row. Vectorised over the components of each kind.
    """
    P = np.atleast_2d(np.asarray(P, dtype=float))
    names = _names(labels, len(scene.attachments))
    head = _beam_factors(P, scene.beam, names)
    checks = _beam_checks(P, scene.beam, head, names)
    if scene.attachments:
        checks += _component_checks(P, scene, head, names)
    for name, factors in checks:
        _check_product(name, factors, source, point)
    _check_physics(P, scene.beam, names, source, point)

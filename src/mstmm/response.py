"""Frequency response: receptance, mobility and accelerance at any point, for any scene.

``frf(scene, input="force:x=0.5", output="displacement:x=1.0", omega=...)`` is the
steady-state response (time dependence ``exp(i w t)``) of ``output`` to a unit harmonic
``input``: the inhomogeneous transfer equation marched by the same stable scheme as the
mode shapes (``frf_march`` in ``generated/numerics.py``: the left end's admitted states
as an orthonormal basis, the load's particular state beside it, each component's
unknowns eliminated by pivoting, the right end's conditions at the end), so high
frequencies stay accurate. Undamped scenes give real receptances (infinite only exactly
at a natural frequency); damped ones complex.

Inputs: ``force:x=X`` (a point force, N, on the beam at X m: ``EI [W'''] = F``),
``moment:x=X`` (a couple, N m, doing positive work on a positive rotation:
``EI [W''] = -C``), ``force:mass=J`` (a force on hanging mass J). Outputs:
``displacement:x=X`` (``Y``, m), ``rotation:x=X`` (``theta``, rad),
``displacement:mass=J``. Hanging masses are numbered from 0 as ``ModeShape.mass_Y``
lists them: the attachments in x order (file order at equal x), each spring-mass its
mass, each chain its masses from the beam outwards; a ``mass`` fixed to the beam is not
one (its point is ``force:x=...``). Tuples ``("force", "x", 0.5)`` are accepted too.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from .kernels import Kernel, load_kernel
from .scene import Scene, SceneError
from .topology import parameter_vector, topology_of

#: Kinds of the numerics' march (``FRF_FORCE``, ``FRF_MOMENT``, ``FRF_MASS``).
_FORCE, _MOMENT, _MASS = 0, 1, 2
_INPUTS = {"force": _FORCE, "moment": _MOMENT}
_OUTPUTS = {"displacement": _FORCE, "y": _FORCE, "rotation": _MOMENT, "theta": _MOMENT}
#: ``receptance`` H, ``mobility`` i w H, ``accelerance`` -w^2 H.
QUANTITIES = ("receptance", "mobility", "accelerance")
_SPEC = re.compile(r"^\s*(\w+)\s*[:@]\s*(x|mass)\s*=\s*([^\s]+)\s*$", re.IGNORECASE)


@dataclass(frozen=True)
class Point:
    """An input or output: its quantity (``force``, ``moment``, ``displacement``,
    ``rotation``), where (``x`` or ``mass``) and the position (m) or mass index."""

    quantity: str
    where: str
    at: float

    def __str__(self) -> str:
        at = int(self.at) if self.where == "mass" else repr(float(self.at))
        return f"{self.quantity}:{self.where}={at}"


def parse_point(spec, role: str, source: str = "<frf>") -> Point:
    """A :class:`Point` from ``"force:x=0.5"``, ``"displacement:mass=2"`` or a tuple;
    ``role`` is ``"input"`` or ``"output"``. Raises :class:`SceneError`."""
    names = _INPUTS if role == "input" else _OUTPUTS
    if isinstance(spec, Point):
        quantity, where, at = spec.quantity, spec.where, spec.at
    elif isinstance(spec, (tuple, list)) and len(spec) == 3:
        quantity, where, at = spec
    elif isinstance(spec, str) and _SPEC.match(spec):
        quantity, where, at = _SPEC.match(spec).groups()
    else:
        raise SceneError(source, role, "must read QUANTITY:x=POSITION or QUANTITY:mass=INDEX", spec)
    quantity, where = str(quantity).lower(), str(where).lower()
    if quantity not in names:
        raise SceneError(source, role, f"quantity must be one of {sorted(names)}", quantity)
    if where not in ("x", "mass"):
        raise SceneError(source, role, "must be at x=POSITION or at mass=INDEX", where)
    if where == "mass" and names[quantity] != _FORCE:
        raise SceneError(source, role, f"a hanging mass has no {quantity}", spec)
    try:
        value = float(at)
    except (TypeError, ValueError):
        raise SceneError(source, role, "the position or index must be a number", at) from None
    if where == "mass" and (value != int(value) or value < 0):
        raise SceneError(source, role, "a mass index is a whole number from 0", at)
    if not math.isfinite(value):
        raise SceneError(source, role, "must be finite", at)
    if role == "output":  # y and theta are read as displacement and rotation
        quantity = "displacement" if names[quantity] == _FORCE else "rotation"
    return Point(quantity, where, value)


def _row(point: Point, role: str, scene: Scene, masses: list[int], source: str) -> list[float]:
    """``(kind, x, q index, scale)`` of a point for the march: scale takes SI loads to the
    kernel's units (force L^2/EI_0, couple L/EI_0) and its responses back (Y and a mass's
    displacement times L, a rotation as it is)."""
    beam = scene.beam
    L, EI = beam.length, beam.EI
    if point.where == "mass":
        j = int(point.at)
        if j >= len(masses):
            raise SceneError(
                source, role, f"the scene has {len(masses)} hanging masses (0..)", point.at
            )
        return [_MASS, 0.0, float(masses[j]), L * L / EI if role == "input" else L]
    x = float(point.at)
    if not 0.0 <= x <= L:
        raise SceneError(source, role, f"x must lie on the beam, in [0, {L:g}] m", x)
    kind = _INPUTS[point.quantity] if role == "input" else _OUTPUTS[point.quantity]
    if kind == _MOMENT and any(a.kind == "hinge" and a.x == x for a in scene.attachments):
        raise SceneError(
            source, role, "a couple or a rotation at a hinge is ambiguous (which side?)", x
        )
    if role == "input":
        scale = L * L / EI if kind == _FORCE else L / EI
    else:
        scale = L if kind == _FORCE else 1.0
    return [kind, x, -1.0, scale]


def hanging_masses(kernel: Kernel, p: np.ndarray) -> list[int]:
    """The q index (``frf``'s) of every hanging mass, in the order of ``mass=J``."""
    return [i for i, (_, mass) in enumerate(kernel.unknowns(p)) if mass > 0.0]


def frf(
    scene: Scene,
    input,
    output,
    omega,
    *,
    quantity: str = "receptance",
    kernel: Kernel | None = None,
    source: str = "<frf>",
    scheduler=None,
    chunk: int = 20_000,
) -> np.ndarray:
    """The frequency response of ``output`` to a unit harmonic ``input`` at each ``omega``
    (rad/s; real, or complex for the analytic continuation), complex, SI: receptance H (m/N,
    rad/N, m/(N m), rad/(N m)), ``mobility`` i w H or ``accelerance`` -w^2 H. ``input`` and
    ``output`` may be lists: the result then has shape ``(len(omega), len(inputs),
    len(outputs))``; with one of each it is ``(len(omega),)``. The frequencies run in
    parallel on all cores; ``scheduler`` (a Dask address or ``distributed.Client``) spreads
    them over a cluster in chunks of ``chunk`` (extra ``mstmm[dask]``)."""
    if quantity not in QUANTITIES:
        raise ValueError(f"quantity must be one of {QUANTITIES}, got {quantity!r}")
    many_in = isinstance(input, list)
    many_out = isinstance(output, list)
    ins = [parse_point(s, "input", source) for s in (input if many_in else [input])]
    outs = [parse_point(s, "output", source) for s in (output if many_out else [output])]
    if kernel is None:
        kernel = load_kernel(topology_of(scene))
    p = parameter_vector(scene)
    masses = hanging_masses(kernel, p)
    rows_in = np.array([_row(pt, "input", scene, masses, source) for pt in ins])
    rows_out = np.array([_row(pt, "output", scene, masses, source) for pt in outs])
    ws = np.atleast_1d(np.asarray(omega))
    if scheduler is None:
        H = kernel.frf(ws, p, rows_in, rows_out)
    else:
        from .study import dask_map

        pieces = [ws[i : i + chunk] for i in range(0, len(ws), chunk)]
        key = kernel.topology.key
        parts = dask_map(scheduler, frf_chunk, pieces, (key, p, rows_in, rows_out), "frf", False)
        H = np.concatenate(parts)
    if quantity == "mobility":
        H = H * (1j * ws)[:, None, None]
    elif quantity == "accelerance":
        H = H * (-(ws**2))[:, None, None]
    if not many_in and not many_out:
        return H[:, 0, 0]
    return H


def frf_chunk(key: str, omegas: np.ndarray, p, rows_in, rows_out) -> np.ndarray:
    """One chunk of frequencies on a Dask worker: the kernel of topology ``key``."""
    from .topology import Topology

    return load_kernel(Topology.from_key(key)).frf(omegas, p, rows_in, rows_out)

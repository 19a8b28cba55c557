"""Frequency response: receptance, mobility and accelerance at any point, for any scene.

``frf(scene, input="force:x=0.5", output="displacement:x=1.0", omega=...)`` is the
steady-state response (time dependence ``exp(i w t)``) of ``output`` to a unit harmonic
``input``: the inhomogeneous transfer equation marched by the same stable scheme as the
mode shapes (``frf_march`` in ``mstmm.numerics.frf``: the left end's admitted states
as an orthonormal basis, the load's particular state beside it, each component's
unknowns eliminated by pivoting, the right end's conditions at the end), so high
frequencies stay accurate. Undamped scenes give real receptances (infinite only exactly
at a natural frequency); damped ones complex.

Inputs: ``force:x=X`` (a point force, N, on the beam at X m: ``EI [W'''] = F``),
``moment:x=X`` (a couple, N m, doing positive work on a positive rotation:
``EI [W''] = -C``), ``force:mass=J`` (a force on hanging mass J), ``moment:inertia=J``
(a couple on rotary inertia J). Outputs: ``displacement:x=X`` (``Y``, m),
``rotation:x=X`` (``theta``, rad), ``displacement:mass=J``, ``rotation:inertia=J``.
Hanging masses are numbered from 0 as ``ModeShape.mass_Y`` lists them: the attachments
in x order (file order at equal x), each spring-mass its mass, each chain its masses from
the beam outwards; a ``mass`` fixed to the beam is not one (its point is
``force:x=...``). Rotary inertias are the unknowns a rigid rotation of the beam carries
(a kind's energy says so: a torsional absorber's rotation), numbered from 0 in the same
order. Tuples ``("force", "x", 0.5)`` are accepted too.
"""

from __future__ import annotations

import math
import re
import warnings
from dataclasses import dataclass

import numpy as np

from mstmm import catalog

from .kernels import Kernel, load_kernel
from .plain import plain
from .scene import Scene, SceneError, check_band
from .topology import parameter_vector, topology_of

#: Kinds of the numerics' march (``FRF_FORCE``, ``FRF_MOMENT``, ``FRF_MASS``).
_FORCE, _MOMENT, _MASS = 0, 1, 2
_INPUTS = {"force": _FORCE, "moment": _MOMENT}
_OUTPUTS = {"displacement": _FORCE, "y": _FORCE, "rotation": _MOMENT, "theta": _MOMENT}
#: ``receptance`` H, ``mobility`` i w H, ``accelerance`` -w^2 H.
QUANTITIES = ("receptance", "mobility", "accelerance")
_SPEC = re.compile(r"^\s*(\w+)\s*[:@]\s*(x|mass|inertia)\s*=\s*([^\s]+)\s*$", re.IGNORECASE)
#: Where a load or a response on a component's unknown sits, and the quantity it takes.
_CARRIED = {"mass": _FORCE, "inertia": _MOMENT}


@dataclass(frozen=True)
class Point:
    """An input or output: its quantity (``force``, ``moment``, ``displacement``,
    ``rotation``), where (``x``, ``mass`` or ``inertia``) and the position (m) or the
    index of the hanging mass or rotary inertia."""

    quantity: str
    where: str
    at: float

    def __str__(self) -> str:
        at = int(self.at) if self.where in _CARRIED else repr(float(self.at))
        return f"{self.quantity}:{self.where}={at}"


def as_quantity(quantity: str, ws: np.ndarray, H: np.ndarray) -> np.ndarray:
    """Receptances H (frequencies ``ws`` along its first axis) as ``quantity``:
    ``receptance`` H, ``mobility`` i w H, ``accelerance`` -w^2 H."""
    shape = (-1,) + (1,) * (H.ndim - 1)
    if quantity == "mobility":
        return H * (1j * ws).reshape(shape)
    if quantity == "accelerance":
        return H * (-(ws**2)).reshape(shape)
    return H


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
        raise SceneError(
            source,
            role,
            "must read QUANTITY:x=POSITION, QUANTITY:mass=INDEX or QUANTITY:inertia=INDEX",
            spec,
        )
    quantity, where = str(quantity).lower(), str(where).lower()
    if quantity not in names:
        raise SceneError(source, role, f"quantity must be one of {sorted(names)}", quantity)
    if where not in ("x", *_CARRIED):
        raise SceneError(source, role, "must be at x=POSITION, mass=INDEX or inertia=INDEX", where)
    if where == "mass" and names[quantity] != _FORCE:
        raise SceneError(source, role, f"a hanging mass has no {quantity}", spec)
    if where == "inertia" and names[quantity] != _MOMENT:
        raise SceneError(source, role, f"a rotary inertia has no {quantity}", spec)
    try:
        value = float(at)
    except (TypeError, ValueError):
        raise SceneError(source, role, "the position or index must be a number", at) from None
    if where in _CARRIED and (value != int(value) or value < 0):
        raise SceneError(source, role, f"an {where} index is a whole number from 0", at)
    if not math.isfinite(value):
        raise SceneError(source, role, "must be finite", at)
    if role == "output":  # y and theta are read as displacement and rotation
        quantity = "displacement" if names[quantity] == _FORCE else "rotation"
    return Point(quantity, where, value)


def _row(
    point: Point, role: str, scene: Scene, carried: dict[str, list[int]], source: str
) -> list[float]:
    """``(kind, x, q index, scale)`` of a point for the march: scale takes SI loads to the
    kernel's units (force L^2/EI_0, couple L/EI_0) and its responses back (Y and a mass's
    displacement times L, a rotation as it is). ``carried``: the q indices of the hanging
    masses (``mass``) and of the rotary inertias (``inertia``)."""
    beam = scene.beam
    L, EI = beam.length, beam.EI
    if point.where in _CARRIED:
        qs = carried[point.where]
        j = int(point.at)
        if j >= len(qs):
            what = "hanging masses" if point.where == "mass" else "rotary inertias"
            raise SceneError(source, role, f"the scene has {len(qs)} {what} (0..)", point.at)
        if point.where == "mass":
            return [_MASS, 0.0, float(qs[j]), L * L / EI if role == "input" else L]
        return [_MASS, 0.0, float(qs[j]), L / EI if role == "input" else 1.0]
    x = float(point.at)
    if not 0.0 <= x <= L:
        raise SceneError(source, role, f"x must lie on the beam, in [0, {L:g}] m", x)
    kind = _INPUTS[point.quantity] if role == "input" else _OUTPUTS[point.quantity]
    if kind == _MOMENT and any(
        a.x == x and catalog.splits_rotation(a.kind) for a in scene.attachments
    ):
        raise SceneError(
            source, role, "a couple or a rotation at a hinge is ambiguous (which side?)", x
        )
    if role == "input":
        scale = L * L / EI if kind == _FORCE else L / EI
    else:
        scale = L if kind == _FORCE else 1.0
    return [kind, x, -1.0, scale]


def carried_unknowns(kernel: Kernel, p: np.ndarray) -> dict[str, list[int]]:
    """The q indices (``frf``'s) of the hanging masses (``mass=J``: a rigid translation
    carries them) and of the rotary inertias (``inertia=J``: unknowns with an inertia that
    a translation does not carry, a rigid rotation does)."""
    out: dict[str, list[int]] = {"mass": [], "inertia": []}
    for i, (_, mass, inertia) in enumerate(kernel.unknowns(p)):
        if mass > 0.0:
            out["mass"].append(i)
        elif inertia > 0.0:
            out["inertia"].append(i)
    return out


#: At most this many responses (frequencies x inputs x outputs, 16 bytes each: 160 MB)
#: in one call of :func:`frf` or one ``mstmm frf``; more: several calls over narrower bands.
MAX_RESPONSES = 10_000_000
#: An infinite response: NaN in both parts.
_NAN = complex(math.nan, math.nan)


def checked_omega(scene: Scene, omega, source: str = "<frf>", field: str = "omega") -> np.ndarray:
    """``omega`` as a 1-D array, refused (:class:`SceneError`, a ValueError) when a value is
    NaN or infinite, a real one negative, or the largest beyond what ``mstmm solve
    --band`` accepts for the scene (:func:`mstmm.scene.check_band`)."""
    ws = np.atleast_1d(np.asarray(omega))
    if ws.ndim != 1 or ws.dtype.kind not in "iufc":
        raise SceneError(source, field, "must be a number or a 1-D array of numbers", omega)
    bad = ~np.isfinite(ws)
    if bad.any():
        k = int(np.argmax(bad))
        raise SceneError(source, field, f"must be finite (rad/s); index {k} is", plain(ws[k]))
    if np.isrealobj(ws) and (ws < 0).any():
        k = int(np.argmax(ws < 0))
        raise SceneError(source, field, f"must be >= 0 rad/s; index {k} is", plain(ws[k]))
    if ws.size:
        size = np.abs(ws)
        check_band(scene, (float(size.min()), float(size.max())), source, field)
    return ws


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
    (rad/s; real >= 0, or complex for the analytic continuation), complex, SI: receptance H
    (m/N, rad/N, m/(N m), rad/(N m)), ``mobility`` i w H or ``accelerance`` -w^2 H.
    ``input`` and ``output`` may be lists: the result then has shape ``(len(omega),
    len(inputs), len(outputs))``; with one of each it is ``(len(omega),)``. The frequencies
    run in parallel on all cores, in chunks of about 0.2 s (Ctrl-C is seen between them);
    ``scheduler`` (a Dask address or ``distributed.Client``) spreads them over a cluster in
    chunks of ``chunk`` (extra ``mstmm[dask]``).

    NaN where the response is infinite, with a warning: at omega = 0 on a scene with a
    rigid-body mode (the static problem is singular), and exactly at a natural frequency.
    Raises ValueError (:class:`SceneError`) on a bad point, quantity or omega (NaN,
    negative, beyond the bounds of ``mstmm solve --band``), or more than
    :data:`MAX_RESPONSES` responses."""
    many_in = isinstance(input, list)
    many_out = isinstance(output, list)
    ws = checked_omega(scene, omega, source)
    if scheduler is not None:
        job = _Job(scene, input, output, quantity, kernel, source, ws.size)
        from .study import dask_map

        pieces = [ws[i : i + chunk] for i in range(0, len(ws), chunk)]
        key = job.kernel.topology.key
        args = (key, job.p, job.rows_in, job.rows_out)
        parts = dask_map(scheduler, frf_chunk, pieces, args, "frf", False)
        H = job.scaled(ws, np.concatenate(parts) if parts else job.empty(0))
    else:
        H = np.empty((0, len(_listed(input)), len(_listed(output))), dtype=complex)
        for at, part in frf_chunks(
            scene, input, output, ws, quantity=quantity, kernel=kernel, source=source
        ):
            if at.start == 0:
                H = np.empty((ws.size, *part.shape[1:]), dtype=complex)
            H[at] = part
    if not many_in and not many_out:
        return H[:, 0, 0]
    return H


def _listed(spec) -> list:
    return spec if isinstance(spec, list) else [spec]


class _Job:
    """What every chunk of one frequency response shares: the kernel, the parameters and
    the rows of the points."""

    def __init__(self, scene, input, output, quantity, kernel, source, n):
        if quantity not in QUANTITIES:
            raise SceneError(source, "quantity", f"must be one of {list(QUANTITIES)}", quantity)
        ins = [parse_point(s, "input", source) for s in _listed(input)]
        outs = [parse_point(s, "output", source) for s in _listed(output)]
        if n * len(ins) * len(outs) > MAX_RESPONSES:
            raise SceneError(
                source,
                "omega",
                f"{n} frequencies x {len(ins)} input(s) x {len(outs)} output(s) is more than"
                f" {MAX_RESPONSES:.0e} responses: compute them in several calls",
                n,
            )
        self.quantity = quantity
        self.kernel = load_kernel(topology_of(scene)) if kernel is None else kernel
        self.p = parameter_vector(scene)
        carried = carried_unknowns(self.kernel, self.p)
        self.rows_in = np.array([_row(pt, "input", scene, carried, source) for pt in ins])
        self.rows_out = np.array([_row(pt, "output", scene, carried, source) for pt in outs])

    def empty(self, n: int) -> np.ndarray:
        return np.empty((n, len(self.rows_in), len(self.rows_out)), dtype=complex)

    def scaled(self, ws: np.ndarray, H: np.ndarray) -> np.ndarray:
        """Receptances H as the quantity asked for."""
        return as_quantity(self.quantity, ws, H)

    def march(self, ws: np.ndarray) -> np.ndarray:
        """The kernel's receptances at ``ws``; NaN at a frequency where its end matrix is
        exactly singular (the march divides by zero there: a natural frequency)."""
        try:
            return self.kernel.frf(ws, self.p, self.rows_in, self.rows_out)
        except (ZeroDivisionError, SystemError) as exc:
            cause = exc if isinstance(exc, ZeroDivisionError) else exc.__cause__ or exc.__context__
            if not isinstance(cause, ZeroDivisionError):
                raise
        if ws.size == 1:
            return np.full((1, len(self.rows_in), len(self.rows_out)), _NAN)
        half = ws.size // 2  # find the singular frequencies by halving
        return np.concatenate([self.march(ws[:half]), self.march(ws[half:])])


def frf_chunks(
    scene: Scene,
    input,
    output,
    omega,
    *,
    quantity: str = "receptance",
    kernel: Kernel | None = None,
    source: str = "<frf>",
):
    """:func:`frf` piece by piece: ``(slice of omega, responses)`` pairs in order, each
    responses of shape ``(frequencies, inputs, outputs)``, each chunk taking about
    :data:`mstmm.chunks.TARGET_SECONDS` (with the caller's own work on it: write it before
    asking for the next). Checks everything, and warns of a rigid-body mode at omega = 0,
    before the first chunk."""
    from .chunks import spans
    from .progress import counted

    ws = checked_omega(scene, omega, source)
    job = _Job(scene, input, output, quantity, kernel, source, ws.size)
    static = ws == 0.0
    rigid = bool(static.any()) and job.kernel.rigid_body_modes(job.p) > 0
    if rigid:
        what = "" if quantity == "receptance" else f"{quantity} is undefined: the "
        warnings.warn(
            f"at omega = 0 the {what}receptance is infinite (a rigid-body mode): NaN there"
            " (null in JSON)",
            RuntimeWarning,
            stacklevel=2,
        )
    singular: list[float] = []
    for at in counted(spans(ws.size), ws.size, "frf"):
        w = ws[at]
        H = job.empty(w.size)
        live = ~static[at] if rigid else np.ones(w.size, dtype=bool)
        H[~live] = _NAN
        if live.any():
            H[live] = job.march(w[live])
            hit = live & ~np.isfinite(H).all(axis=(1, 2))
            singular += [float(abs(v)) for v in w[hit]]
        yield at, job.scaled(w, H)
    if singular:
        warnings.warn(
            f"the response is infinite at {len(singular)} frequency(ies) exactly at a"
            " natural frequency (first: omega = {singular[0]:.17g} rad/s): NaN"
            " there (null in JSON)",
            RuntimeWarning,
            stacklevel=2,
        )


def frf_chunk(key: str, omegas: np.ndarray, p, rows_in, rows_out) -> np.ndarray:
    """One chunk of frequencies on a Dask worker: the kernel of topology ``key``."""
    from .topology import Topology

    return load_kernel(Topology.from_key(key)).frf(omegas, p, rows_in, rows_out)

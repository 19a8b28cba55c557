"""The undamped solve: certified natural frequencies and mode shapes of a real scene.

:func:`mstmm.solve` dispatches here for an undamped scene; the damped search
(:mod:`mstmm.damped`) starts from these roots of its undamped twin. Stages run one way:
``solve`` -> ``damped`` -> ``undamped``.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from . import compiling, interpret, repeated
from .buckling import Buckling, buckling
from .frames import Tabulated
from .kernels import Kernel, load_kernel
from .modes import ModeShape, beside, mode_shapes, too_close, unresolved
from .scan import TRUST, find_roots
from .scene import Scene
from .topology import parameter_vector, topology_of


@dataclass(repr=False)
class Solution(Tabulated):
    """Natural frequencies (rad/s, ascending, repeated by multiplicity) and what to trust."""

    scene: Scene
    omega: np.ndarray
    multiplicity: np.ndarray
    converged: np.ndarray
    formulation: str
    kernel_origin: str
    timings: dict[str, float]
    count_checked: bool = False
    shapes: list[ModeShape] | None = None
    warnings: list[str] = field(default_factory=list)
    #: How the kernel's root search ran: ``"compiled"`` (numba), ``"interpreted"``
    #: (plain Python, for a small first solve: :mod:`mstmm.interpret`) or ``"repeated
    #: cells"`` (N identical cells, their count and characteristic function by doubling
    #: the cell: :mod:`mstmm.repeated`).
    kernel_mode: str = "compiled"
    #: True when the lowest ``modes`` end inside a multiple root: its multiplicity
    #: (the true one, in :attr:`multiplicity`) exceeds the copies in :attr:`omega`.
    truncated: bool = False
    #: A scene with a segment in compression: its stability and buckling load factor
    #: (:mod:`mstmm.buckling`); when buckled, ``omega`` is empty. None: no compression.
    buckling: Buckling | None = None

    @property
    def hz(self) -> np.ndarray:
        """Frequencies in Hz."""
        return self.omega / (2.0 * math.pi)

    def to_dict(self, shapes: bool = False) -> dict:
        """JSON-ready summary; with ``shapes``, one entry per mode shape under ``mode_shapes``.

        Each shape gives ``omega`` (rad/s), ``hz``, the samples ``x`` (m) with ``Y`` (m),
        ``theta`` (rad), ``M`` (N m), ``Q`` (N), the carried masses ``mass_x``, ``mass_Y``
        (m), ``singular_ratio``, ``modal_mass`` (kg), ``participation``, ``effective_mass``
        (kg) and ``multiplicity``. Numbers are Python floats; a non-finite one stays as it
        is (the command line writes it as ``null``, with a warning).
        """
        out = {
            "scene": self.scene.name,
            "formulation": self.formulation,
            "omega": [float(w) for w in self.omega],
            "hz": [float(f) for f in self.hz],
            "multiplicity": [int(m) for m in self.multiplicity],
            "converged": [bool(c) for c in self.converged],
            "count_checked": bool(self.count_checked),
            "truncated": bool(self.truncated),
            "warnings": list(self.warnings),
            "kernel": self.kernel_origin,
            "kernel_mode": self.kernel_mode,
            "timings": {k: float(v) for k, v in self.timings.items()},
        }
        return self.buckling_and_shapes(out, shapes)


def _in_band(kernel: Kernel, p: np.ndarray, band: tuple[float, float]) -> int:
    """How many roots the count puts in ``band`` (a band solve's size for the tiers): as
    Python where the kernel is not loaded yet, like every small call of a first solve."""
    n = kernel.count_below(np.array([band[0], band[1]]), p)
    return max(int(n[1]) - int(n[0]), 1)


def solve_undamped(
    scene: Scene,
    modes: int | None = None,
    band: tuple[float, float] | None = None,
    *,
    formulation: str = "stable",
    shapes: bool = True,
    rtol: float = 0.0,
    kernel: Kernel | None = None,
) -> Solution:
    """:func:`mstmm.solve` of an undamped scene, its request already checked."""
    topology = topology_of(scene)
    if modes is None and band is None:
        modes = 10
    timings: dict[str, float] = {}
    cells = formulation == "stable" and repeated.qualifies(scene)
    if cells:  # a machine's first run compiles these drivers in helpers, not the search
        compiling.register(("repeated_search",) + (("mode_shapes",) if shapes else ()))
    t0 = time.perf_counter()
    if kernel is None:
        kernel = load_kernel(topology)
    p = parameter_vector(scene)
    t1 = time.perf_counter()
    timings["load"] = t1 - t0
    if 0.0 < kernel.derive_seconds <= timings["load"]:  # derived by this call
        timings["derive"] = kernel.derive_seconds
    # a small first solve of the stable formulation runs the kernel as Python
    # (mstmm.interpret); otherwise compile, or load from numba's cache, before timing
    stability = buckling(kernel, p)
    if stability is not None and stability.buckled:  # no root: a certified "buckled"
        timings["compile"] = timings["scan_refine"] = 0.0
        empty = np.zeros(0)
        return Solution(
            scene,
            empty,
            empty.astype(int),
            empty.astype(bool),
            formulation,
            kernel.origin,
            timings,
            False,
            [] if shapes else None,
            [stability.message()],
            buckling=stability,
        )
    # N identical cells: the count and the characteristic function by doubling the cell
    chain = repeated.chain_of(scene) if cells else None
    found = None
    if chain is not None:
        t2 = time.perf_counter()
        timings["compile"] = t2 - t1
        rigid = kernel.rigid_body_modes(p)
        found = repeated.find_roots(scene, chain, rigid, modes=modes, band=band)
    interpreted = False
    if found is None:
        chain = None
        expected = modes if modes is not None else _in_band(kernel, p, band)
        interpreted = formulation == "stable" and kernel.interprets(p, expected)
        if not interpreted:
            kernel.warm_up(p, formulation)
        t2 = time.perf_counter()
        timings["compile"] = t2 - t1
        found = find_roots(kernel, p, band=band, modes=modes, formulation=formulation, rtol=rtol)
        # a run as Python that outgrew its estimate went on compiled (interpret.Overrun)
        interpreted = interpreted and not interpret.machine_code_loaded()
    roots = found.roots
    t3 = time.perf_counter()
    timings["scan_refine"] = t3 - t2
    omega = np.array([r.omega for r in roots for _ in range(r.reported)], dtype=float)
    mult = np.array([r.multiplicity for r in roots for _ in range(r.reported)], dtype=int)
    conv = np.array([r.converged for r in roots for _ in range(r.reported)], dtype=bool)
    truncated = bool(roots) and roots[-1].reported < roots[-1].multiplicity
    warnings = [
        f"omega = {r.omega:.17g} rad/s: refinement did not converge, or neither the count"
        f" nor the stable function confirms a root within {max(TRUST, 4.0 * rtol):.0e}"
        " of it; this value is not trusted"
        for r in roots
        if not r.converged
    ] + found.notes
    if not found.count_checked:
        warnings.append("the roots disagree with the Wittrick-Williams count: some may be missing")
    if truncated:
        r = roots[-1]
        warnings.append(
            f"the last root, omega = {r.omega:.17g} rad/s, has multiplicity {r.multiplicity}:"
            f" only {r.reported} of its copies fit in the {len(omega)} modes asked for"
        )
    shape_list = None
    if shapes:
        shape_list = mode_shapes(kernel, p, omega)
        warnings += unresolved(shape_list)
        if chain is not None:
            count = chain.count_below
        else:
            count = lambda w: kernel.count_below(w, p)  # noqa: E731
        warnings += too_close(shape_list, *beside(count, omega))
        timings["shapes"] = time.perf_counter() - t3
    return Solution(
        scene,
        omega,
        mult,
        conv,
        formulation,
        kernel.origin,
        timings,
        found.count_checked,
        shape_list,
        warnings,
        "repeated cells" if chain is not None else "interpreted" if interpreted else "compiled",
        truncated,
        stability,
    )

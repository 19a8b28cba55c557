"""Plots: the characteristic function and the mode shapes (paper Fig. 2), veering diagrams.

Needs matplotlib (``pip install "mstmm[plot]"``); it is imported here only, never by
``import mstmm``. Without a display (and without ``MPLBACKEND``) the Agg backend is
selected. Figures are built with the object-oriented API (no pyplot state, nothing
left open) unless pyplot is already imported, in which case they are pyplot figures
so that ``plt.show()`` sees them. Every function returns the
:class:`matplotlib.figure.Figure`, draws into ``ax`` when one is given, and writes
the figure to ``path`` when one is given (format from the suffix, atomically).

>>> import mstmm, mstmm.plot
>>> scene = mstmm.load_scene(mstmm.example_path("wu_chou_1998"))
>>> fig = mstmm.plot.figure2(scene, "fig2.png")                      # doctest: +SKIP

Artists carry a ``gid`` so that a figure can be inspected: ``"delta"`` (the curve of
``log10|Delta|``), ``"roots"`` (one marker per root, repeated by multiplicity),
``"root-line"`` (one vertical line per distinct root), ``"mode"`` (a mode-shape or
veering curve), ``"mass"`` / ``"spring"`` (hanging masses of one mode and their
springs, on the beam's scale), ``"mass-clipped"`` (the masses beyond
:data:`MASS_CLIP`), ``"buckled"`` / ``"buckled-text"`` (the buckled range of a sweep
and its word), ``"clip-note"`` (an frf axis clipped below the peak),
``"attachment"`` (attachment points on the beam axis: one line per kind,
its marker the one its kind declares (``MARKER``), labelled ``"spring-mass (3)"``),
``"axis"`` (the beam axis), ``"uncoupled"`` (the own frequencies of a varied attachment,
``sqrt(k/m)`` for a spring-mass), ``"frf"`` /
``"phase"`` (an frf's magnitude and unwrapped phase), ``"dispersion"`` /
``"attenuation"`` / ``"gap"`` / ``"edge"`` (a cell's Re k L, Im k L, stop bands and band
edges). Every axis is labelled with its unit; legends sit beside the axes, where they
cover no curve. A buckled scene has nothing to plot: :class:`Buckled`.
"""

from __future__ import annotations

import math
import os
import re
import sys
import tempfile
from collections.abc import Sequence
from pathlib import Path

import matplotlib
import numpy as np

from mstmm import catalog

from .kernels import load_kernel
from .scene import Scene, SceneError
from .solve import Solution, solve
from .topology import parameter_vector, topology_of
from .units import field_unit, frf_unit


def _headless() -> bool:
    if os.environ.get("MPLBACKEND"):
        return False
    if sys.platform.startswith(("linux", "freebsd", "openbsd", "netbsd")):
        return not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))
    return False


if _headless() and "matplotlib.pyplot" not in sys.modules:
    matplotlib.use("Agg")

from matplotlib.axes import Axes  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

__all__ = [
    "Buckled",
    "characteristic",
    "figure2",
    "formats",
    "frf_figure",
    "mode_shapes",
    "save",
    "veering",
]

PathLike = str | os.PathLike[str]

#: Resolution of written raster images (dots per inch).
DPI = 150
#: The plotted band extends this far beyond the highest root when only ``modes`` is given.
MARGIN = 1.08

_TWO_PI = 2.0 * math.pi
#: A field of one attachment other than its position (its own frequencies may depend on it).
_ATTACHMENT_FIELD = re.compile(r"attachments\[(\d+)\]\.(?!x$)\w+(\[\d+\])?$")


def _to_hz(w):
    return np.asarray(w) / _TWO_PI


def _to_rad(f):
    return np.asarray(f) * _TWO_PI


def _figure(size: tuple[float, float]) -> Figure:
    """A new constrained-layout figure (a pyplot one when pyplot is imported)."""
    if "matplotlib.pyplot" in sys.modules:
        import matplotlib.pyplot as plt

        return plt.figure(figsize=size, layout="constrained")
    return Figure(figsize=size, layout="constrained")


def _new_figure(ncols: int = 1, size: tuple[float, float] = (7.0, 4.8)) -> tuple[Figure, list]:
    fig = _figure(size)
    return fig, list(np.atleast_1d(fig.subplots(1, ncols)))


def _pair(
    ax: tuple[Axes, Axes] | None, size: tuple[float, float], rows: int, **share
) -> tuple[Figure, Axes, Axes]:
    """The two axes given, or a new figure of two panels (``rows`` 2: one above the other;
    1: side by side) sharing an axis (``sharex=True`` or ``sharey=True``)."""
    if ax is not None:
        return ax[0].get_figure(), ax[0], ax[1]
    fig = _figure(size)
    first, second = fig.subplots(rows, 3 - rows, **share)
    return fig, first, second


def _axes(ax: Axes | None, size: tuple[float, float] = (7.0, 4.8)) -> tuple[Figure, Axes]:
    if ax is not None:
        return ax.get_figure(), ax
    fig, (new,) = _new_figure(1, size)
    return fig, new


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def formats() -> dict[str, str]:
    """Image formats :func:`save` can write: suffix (no dot) -> description."""
    return Figure().canvas.get_supported_filetypes()


def save(fig: Figure, path: PathLike, dpi: int = DPI) -> Path:
    """Write ``fig`` to ``path`` (format from the suffix; default PNG), atomically."""
    path = Path(path)
    fmt = path.suffix[1:].lower() or "png"
    supported = fig.canvas.get_supported_filetypes()
    if fmt not in supported:
        raise ValueError(
            f"{path}: unsupported image format {fmt!r} (choose from {', '.join(sorted(supported))})"
        )
    directory = path.parent if str(path.parent) else Path(".")
    fd, tmp = tempfile.mkstemp(dir=directory, prefix=".tmp-plot-", suffix=f".{fmt}")
    os.close(fd)
    try:
        fig.savefig(tmp, format=fmt, dpi=dpi)
        os.chmod(tmp, 0o666 & ~_umask())  # mkstemp made it 0600
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path


def _finish(fig: Figure, path: PathLike | None) -> Figure:
    if path is not None:
        save(fig, path)
    return fig


def _legend(ax: Axes) -> None:
    """The legend beside the axes (right of them), where it covers no curve."""
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, fontsize=8)


#: Markers for a kind that declares none (``MARKER`` in its file), one per such kind.
_SPARE_MARKERS = ("h", "p", "<", ">", "8", "H")


def _marker(kind: str, spare: list[str]) -> tuple[str, str]:
    """The marker and colour a kind declares, or a spare marker in grey."""
    declared = getattr(catalog.kind(kind), "MARKER", None)
    if declared is not None:
        return tuple(declared)
    if kind not in spare:
        spare.append(kind)
    return _SPARE_MARKERS[(spare.index(kind)) % len(_SPARE_MARKERS)], "0.3"


def _draw_attachments(ax: Axes, scene: Scene) -> None:
    """One marker line per kind present (``gid`` ``"attachment"``), labelled in the legend
    with the kind and how many sit on the beam."""
    kinds: dict[str, list[float]] = {}
    for a in scene.attachments:
        kinds.setdefault(a.kind, []).append(float(a.x))
    spare: list[str] = []
    for kind, xs in kinds.items():
        marker, color = _marker(kind, spare)
        ax.plot(
            xs,
            np.zeros(len(xs)),
            ls="none",
            marker=marker,
            ms=8,
            mfc="none" if marker not in ("^", "*") else color,
            mec=color,
            color=color,
            mew=1.4,
            clip_on=False,
            zorder=5,
            gid="attachment",
            label=f"{kind.replace('_', '-')} ({len(xs)})",
        )


def _distinct(sol: Solution) -> list[tuple[int, float, int]]:
    """``(mode number from 1, omega, multiplicity)`` of each distinct root of ``sol``."""
    out, i = [], 0
    while i < len(sol.omega):
        m = max(int(sol.multiplicity[i]), 1)
        out.append((i + 1, float(sol.omega[i]), m))
        i += m
    return out


def _rigid_body_modes(scene: Scene) -> int:
    """Number of zero natural frequencies of the scene."""
    return load_kernel(topology_of(scene)).rigid_body_modes(parameter_vector(scene))


def _modes_below(scene: Scene, omega: float) -> int:
    """How many natural frequencies lie below ``omega`` (numbers the modes of a band)."""
    if omega <= 0.0:
        return 0
    kernel = load_kernel(topology_of(scene))
    return int(kernel.count_below(np.array([omega]), parameter_vector(scene))[0])


class Buckled(ValueError):
    """The scene's axial forces reach its buckling load: it has no natural frequencies to
    plot. ``str()`` is the line ``mstmm solve`` prints; ``buckling`` the
    :class:`mstmm.buckling.Buckling` it reads."""

    def __init__(self, buckling) -> None:
        super().__init__(buckling.message())
        self.buckling = buckling


def _checked(sol: Solution) -> Solution:
    """``sol``, or :class:`Buckled` when its scene is buckled."""
    if sol.buckling is not None and sol.buckling.buckled:
        raise Buckled(sol.buckling)
    return sol


def _band_solution(
    scene: Scene, band: tuple[float, float] | None, modes: int | None, formulation: str
) -> tuple[Solution, float, float]:
    """Solve for the roots and return them with the band to plot (:class:`Buckled` when
    the scene is buckled)."""
    if band is not None:
        lo, hi = float(band[0]), float(band[1])
        if not (0.0 <= lo < hi and math.isfinite(hi)):
            raise ValueError(f"band must satisfy 0 <= lo < hi < inf (got {band!r})")
        return _checked(solve(scene, band=(lo, hi), formulation=formulation)), lo, hi
    count = modes or 10
    lowest = _checked(solve(scene, modes=count + 1, formulation=formulation, shapes=False))
    top = float(lowest.omega[count - 1]) if len(lowest.omega) >= count else 0.0
    if top <= 0.0:  # only rigid-body modes asked for: show up to the first elastic one
        first = solve(scene, modes=_rigid_body_modes(scene) + 1, shapes=False)
        top = float(first.omega[-1])
    hi = MARGIN * top
    nxt = float(lowest.omega[count]) if len(lowest.omega) > count else math.inf
    if top < nxt < hi:  # a root just above: stop half way, so the lowest ``modes`` are marked
        hi = 0.5 * (top + nxt)
    return solve(scene, band=(0.0, hi), formulation=formulation), 0.0, hi


def _draw_characteristic(
    ax: Axes, scene: Scene, sol: Solution, lo: float, hi: float, formulation: str, n: int
) -> None:
    kernel = load_kernel(topology_of(scene))
    p = parameter_vector(scene)
    start = lo if lo > 0.0 else hi * 1e-4  # Delta(0) vanishes with rigid-body modes
    # uniform in sqrt(omega), i.e. in beta = lam L: beam modes about evenly spaced
    omegas = np.linspace(math.sqrt(start), math.sqrt(hi), int(n)) ** 2
    mant, logs = kernel.evaluate(omegas, p, formulation)
    with np.errstate(divide="ignore", invalid="ignore"):
        y = (np.log(np.abs(mant)) + logs) / math.log(10.0)
    y[~np.isfinite(y)] = np.nan
    ax.plot(omegas, y, color="C0", lw=1.0, gid="delta", label=r"$\log_{10}|\Delta(\omega)|$")
    roots = _distinct(sol)
    for _number, w, m in roots:
        ax.axvline(w, color="C3", lw=0.7, ls="--", alpha=0.6, gid="root-line")
        if m > 1:
            ax.annotate(
                f"x{m}",
                (w, 1.0),
                xycoords=ax.get_xaxis_transform(),
                fontsize=7,
                ha="left",
                va="top",
                color="C3",
                xytext=(2, -2),
                textcoords="offset points",
            )
    ax.plot(
        sol.omega,
        np.zeros(len(sol.omega)),
        ls="none",
        marker="^",
        ms=6,
        color="C3",
        transform=ax.get_xaxis_transform(),
        clip_on=False,
        gid="roots",
        label=f"roots ({len(sol.omega)}, {len(roots)} distinct)",
    )
    ax.set_xlim(lo, hi)
    ax.set_xlabel(r"$\omega$ [rad/s]")
    ax.set_ylabel(r"$\log_{10}|\Delta(\omega)|$ [-] (scaled determinant)")
    ax.set_title(f"{scene.name}: characteristic function ({formulation})", fontsize=10)
    sec = ax.secondary_xaxis("top", functions=(_to_hz, _to_rad))
    sec.set_xlabel("f [Hz]")
    _legend(ax)


def characteristic(
    scene: Scene,
    band: tuple[float, float] | None = None,
    modes: int | None = None,
    formulation: str = "stable",
    n: int = 2000,
    ax: Axes | None = None,
    path: PathLike | None = None,
) -> Figure:
    """``log10|Delta(omega)|`` with the natural frequencies marked: the paper's Fig. 2(a).

    ``band=(lo, hi)`` (rad/s) plots that band and marks every root
    :func:`mstmm.solve` finds in it; otherwise the lowest ``modes`` (default 10)
    are found, the band runs from 0 to 8 % past the highest, and every root in it
    is marked (a cluster may add a few above the ``modes``-th). ``Delta`` is the
    ``formulation``'s characteristic function (``"stable"``: the second-compound
    chain; ``"paper"``: ``det U_bar`` of paper Eq. (4)) on ``n`` points uniform
    in ``sqrt(omega)``. Roots are drawn as dashed vertical lines (one per distinct
    root, ``xm`` written beside a root of multiplicity ``m``) and as triangles on
    the omega axis (one per root, repeated by multiplicity); the top axis is in Hz.
    """
    fig, ax = _axes(ax)
    sol, lo, hi = _band_solution(scene, band, modes, formulation)
    _draw_characteristic(ax, scene, sol, lo, hi, formulation, n)
    return _finish(fig, path)


def _copy_labels(sol: Solution, first_mode: int = 0) -> list[str]:
    """Per entry of ``sol.omega``: ``"7"``, or ``"7a"``, ``"7b"`` for the copies of a double
    root numbered 7-8 (the number of the root's first entry, a letter per copy)."""
    labels: list[str] = []
    for number, _w, m in _distinct(sol):
        n = first_mode + number
        labels += [f"{n}{chr(ord('a') + j)}" if m > 1 else f"{n}" for j in range(m)]
    return labels


#: Hanging masses are drawn at the beam's scale (its max |Y| = 1), clipped at this |Y|.
MASS_CLIP = 1.5
#: Beyond this many drawn modes, the mode shapes are coloured on a scale of mode numbers
#: (a colour bar) instead of one legend entry each.
LEGEND_MODES = 10


def _beam_scale(shape) -> float:
    """The factor that brings the beam's largest |Y| of ``shape`` to 1 (1 for a still beam)."""
    top = float(np.max(np.abs(shape.Y))) if len(shape.Y) else 0.0
    return 1.0 / top if top > 0.0 and math.isfinite(top) else 1.0


def _draw_masses(ax: Axes, shape, scale: float, color) -> float:
    """The hanging masses of one mode at the beam's scale, each joined to its attachment
    point by a thin line (its spring); a mass beyond :data:`MASS_CLIP` sits on the clip
    as a triangle pointing its way. Returns its largest |Y| on the beam's scale."""
    y = shape.mass_Y * scale
    shown = np.clip(y, -MASS_CLIP, MASS_CLIP)
    at_beam = np.interp(shape.mass_x, shape.x, shape.Y * scale)
    nan = np.full_like(at_beam, np.nan)
    sx = np.column_stack([shape.mass_x, shape.mass_x, nan]).ravel()
    sy = np.column_stack([at_beam, shown, nan]).ravel()
    ax.plot(sx, sy, color=color, lw=0.6, alpha=0.7, gid="spring")
    ax.plot(shape.mass_x, shown, ls="none", marker="o", ms=5, mfc="white", mec=color, gid="mass")
    out = np.abs(y) > MASS_CLIP
    for sign, marker in ((1.0, "^"), (-1.0, "v")):
        pick = out & (np.sign(y) == sign)
        if pick.any():
            ax.plot(shape.mass_x[pick], shown[pick], ls="none", marker=marker, ms=6, color=color,
                    gid="mass-clipped")  # fmt: skip
    return float(np.max(np.abs(y)))


def _drawn_modes(sol: Solution, modes: int, first_mode: int) -> list[tuple]:
    """``(shape, label, multiplicity)`` of the first ``modes`` roots, rigid-body zeros
    left out (counted, not drawn)."""
    labels = _copy_labels(sol, first_mode)
    count = max(int(modes), 0)
    return [
        (shape, label, int(m))
        for shape, label, m in zip(
            sol.shapes[:count], labels[:count], sol.multiplicity[:count], strict=True
        )
        if shape.omega > 0.0
    ]


def _mode_colors(ax: Axes, drawn: list[tuple]) -> list:
    """One colour per drawn mode: the colour cycle, or (beyond :data:`LEGEND_MODES`) a
    colour scale of mode numbers with its colour bar beside the axes."""
    if len(drawn) <= LEGEND_MODES:
        return [f"C{i % 10}" for i in range(len(drawn))]
    from matplotlib import colormaps
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize

    numbers = [int(re.match(r"\d+", label).group()) for _s, label, _m in drawn]
    norm = Normalize(min(numbers), max(numbers))
    bar = ax.get_figure().colorbar(
        ScalarMappable(norm, colormaps["viridis"]), ax=ax, location="bottom", shrink=0.8,
        aspect=40, pad=0.02,
    )  # fmt: skip
    w = [d[0].omega for d in drawn]
    bar.set_label(
        f"mode number ({len(drawn)} modes, {min(w):.4g} to {max(w):.4g} rad/s)", fontsize=8
    )
    return [colormaps["viridis"](norm(n)) for n in numbers]


def _draw_mode_shapes(ax: Axes, sol: Solution, modes: int, first_mode: int = 0) -> None:
    if sol.shapes is None:
        raise ValueError("the solution carries no mode shapes: solve it with shapes=True")
    scene = sol.scene
    drawn = _drawn_modes(sol, modes, first_mode)
    colors = _mode_colors(ax, drawn)
    legend = len(drawn) <= LEGEND_MODES
    clipped = False
    for (shape, label, m), color in zip(drawn, colors, strict=True):
        w = shape.omega
        scale = _beam_scale(shape)
        text = f"mode {label}: {w:.6g} rad/s = {w / _TWO_PI:.6g} Hz" + (f", x{m}" if m > 1 else "")
        lw = 1.4 if legend else 0.9
        line = ax.plot(shape.x, shape.Y * scale, color=color, lw=lw, gid="mode", label=text)[0]
        if legend and len(shape.mass_x):  # beyond LEGEND_MODES, the beam lines only
            top = _draw_masses(ax, shape, scale, color)
            if top > MASS_CLIP:
                clipped = True
                line.set_label(f"{text}; masses to {top:.3g}")
        if not legend:
            line.set_label(f"_{text}")  # a colour bar tells the modes apart
    ax.axhline(0.0, color="0.4", lw=0.8, gid="axis")
    _draw_attachments(ax, scene)
    L = scene.beam.length
    ax.set_xlim(-0.02 * L, 1.02 * L)
    if clipped:
        ax.set_ylim(-1.1 * MASS_CLIP, 1.1 * MASS_CLIP)
    ax.set_xlabel(f"x [m]   ({scene.beam.left} - {scene.beam.right})")
    masses = ""
    if any(len(d[0].mass_x) for d in drawn):
        masses = "; circles: hanging masses" if legend else "; hanging masses not drawn"
    if clipped:
        masses += f", clipped at {MASS_CLIP:g}"
    ax.set_ylabel(f"Y [-] (beam's max |Y| = 1{masses})", fontsize=9)
    ax.set_title(f"{scene.name}: mode shapes", fontsize=10)
    _legend(ax)


def mode_shapes(
    solution_or_scene: Solution | Scene,
    modes: int = 4,
    ax: Axes | None = None,
    path: PathLike | None = None,
) -> Figure:
    """The mode shapes of the lowest ``modes`` natural frequencies: the paper's Fig. 2(b).

    ``modes`` counts every natural frequency, rigid-body zeros included (as
    ``mstmm solve --modes``); the zeros are not drawn. Given a
    :class:`~mstmm.scene.Scene`, it is solved for ``modes`` frequencies; a
    :class:`~mstmm.solve.Solution` (with shapes) is drawn as is. Each mode is a
    curve ``Y(x)`` (paper Eq. (5), scaled to max ``|Y|`` = 1 over the beam, whatever
    its masses do); every shape of a multiple root is drawn, labelled ``7a``, ``7b``,
    ... The attachment points are triangles on the beam axis, each hanging mass a
    circle at its own displacement (on the beam's scale) above its attachment point,
    joined to the beam by a thin line (its spring); a mass beyond
    :data:`MASS_CLIP` sits on the clip as a triangle pointing its way, and the legend
    says how far it goes. The legend gives each frequency in rad/s and Hz, numbered as
    ``mstmm solve`` numbers them; beyond :data:`LEGEND_MODES` modes a colour bar of
    mode numbers below the axes takes its place.
    """
    fig, ax = _axes(ax)
    if isinstance(solution_or_scene, Solution):
        sol = solution_or_scene
    else:
        sol = _checked(solve(solution_or_scene, modes=int(modes)))
    _draw_mode_shapes(ax, sol, modes)
    return _finish(fig, path)


def figure2(
    scene: Scene,
    path: PathLike | None = None,
    modes: int = 4,
    band: tuple[float, float] | None = None,
    formulation: str = "stable",
    n: int = 2000,
) -> Figure:
    """The paper's Fig. 2 for ``scene``: (a) ``log10|Delta|`` with its roots, (b) mode shapes.

    ``modes`` counts every natural frequency, rigid-body zeros included (as
    ``mstmm solve --modes``). Without ``band`` panel (a) spans the lowest ``modes``
    and 8 % beyond, as :func:`characteristic`; with ``band`` it spans that band.
    Panel (b) shows the shapes of the first ``modes`` roots of panel (a), skipping
    rigid-body zeros, every shape of a multiple root.
    """
    if topology_of(scene).damped:
        raise SceneError(
            scene.source,
            "scene",
            "Fig. 2 plots a real characteristic function: a damped scene's roots are complex"
            " (plot its frequency response with --frf)",
            scene.name,
        )
    fig, (ax_a, ax_b) = _new_figure(2, (13.0, 4.8))
    first = 0
    if band is None:
        sol, lo, hi = _band_solution(scene, None, int(modes), formulation)
    else:
        sol, lo, hi = _band_solution(scene, band, None, formulation)
        first = _modes_below(scene, lo)
    _draw_characteristic(ax_a, scene, sol, lo, hi, formulation, n)
    _draw_mode_shapes(ax_b, sol, modes, first)
    ax_a.set_title(f"(a) {ax_a.get_title()}", fontsize=10)
    ax_b.set_title(f"(b) {ax_b.get_title()}", fontsize=10)
    return _finish(fig, path)


def _own_frequencies(scene: Scene, i: int, path_name: str, values: np.ndarray):
    """The own frequencies (rad/s) of ``attachments[i]`` at each value of ``path_name``,
    one column each (NaN where it has fewer), or None when it has none (or the scene is
    damped): the zeros of its unknowns' block with the beam held (a spring-mass's
    ``sqrt(k/m)``), as the kernel prints them from the kind's declaration
    (``event_internal``)."""
    from .study import column, parameter_matrix

    topology = topology_of(scene)
    internal = getattr(load_kernel(topology).module, "event_internal", None)
    if internal is None or topology.damped:
        return None
    P = parameter_matrix(scene, {path_name: values})
    row = column(scene, f"attachments[{i}].x") - 1
    found = []
    for p in P:
        out = np.empty(p.shape[0])
        n = internal(int(p[row]), p, int(p[row + 2]), p[0], p[1], p[2], out, 0)
        found.append(np.sort(out[:n]))
    width = max(len(f) for f in found)
    if width == 0:
        return None
    return np.array([np.pad(f, (0, width - len(f)), constant_values=np.nan) for f in found])


def _buckled(scene: Scene, path_name: str, values: np.ndarray) -> tuple[np.ndarray, float]:
    """Which points of a sweep are buckled (:mod:`mstmm.buckling`), and the value of an
    axial force at which the structure buckles (NaN for another field, or none buckled)."""
    from .buckling import buckling, compressed
    from .study import parameter_matrix

    P = parameter_matrix(scene, {path_name: values})
    kernel = load_kernel(topology_of(scene))
    mask = np.zeros(len(P), dtype=bool)
    critical = math.nan
    for i, p in enumerate(P):
        if compressed(p):
            state = buckling(kernel, p)
            mask[i] = state.buckled
            if path_name.endswith("axial_force") and math.isfinite(state.load_factor):
                critical = float(values[i]) * state.load_factor
    return mask, critical


def _shade_buckled(axes: Sequence[Axes], v: np.ndarray, buckled: np.ndarray, critical: float):
    """Shade and label the buckled runs of a sweep (``gid`` ``"buckled"``), from the
    buckling value ``critical`` when known, else half way to the next point."""
    edges = np.concatenate([[v[0]], 0.5 * (v[1:] + v[:-1]), [v[-1]]])
    runs = np.flatnonzero(np.diff(np.concatenate([[0], buckled.astype(int), [0]])))
    for start, stop in zip(runs[::2], runs[1::2], strict=True):
        lo, hi = edges[start], edges[stop]
        if math.isfinite(critical):
            lo, hi = (lo, critical) if stop < len(v) else (critical, hi)
        for k, ax in enumerate(axes):
            ax.axvspan(lo, hi, color="0.88", zorder=0, gid="buckled",
                       label="buckled" if k == 0 and start == runs[0] else None)  # fmt: skip
            where = ax.get_xaxis_transform()
            ax.text(0.5 * (lo + hi), 0.5, "buckled", transform=where, ha="center",
                    va="center", rotation=90, color="0.4", gid="buckled-text")  # fmt: skip


def _sweep_axes(ax, v: np.ndarray, y: np.ndarray, log_ok: bool) -> None:
    """Log x when the values span more than two decades; log y (``log_ok``) when the
    curves do, else linear from 0."""
    finite = y[np.isfinite(y) & (y > 0)]
    top = float(finite.max()) if finite.size else 1.0
    bottom = float(finite.min()) if finite.size else 0.0
    if v.size and v.min() > 0 and v.max() / v.min() > 100.0:
        ax.set_xscale("log")
    else:  # 1e5 as "1 x 1e5": the long tick labels ran into each other
        ax.ticklabel_format(axis="x", style="sci", scilimits=(-3, 4))
    if log_ok and bottom > 0 and top / bottom > 100.0:
        ax.set_yscale("log")
        ax.set_ylim(bottom / 1.3, top * 1.3)
    else:
        ax.set_ylim(0.0, top * 1.05)


def _mode_lines(ax: Axes, v: np.ndarray, y: np.ndarray, first: int) -> None:
    """One line per column of ``y`` (``gid`` ``"mode"``), numbered from ``first`` + 1."""
    for j in range(y.shape[1]):
        ax.plot(v, y[:, j], color=f"C{j % 10}", lw=1.4, gid="mode", label=f"mode {first + j + 1}")


def _sweep_legend(fig: Figure, ax: Axes, own: bool) -> None:
    """In our ``own`` figure, the legend right of everything (of the Hz axis, which it
    would otherwise cover); in given axes, beside them."""
    if own:
        fig.legend(*ax.get_legend_handles_labels(), loc="outside right upper", fontsize=8)
    else:
        _legend(ax)


def veering(
    scene: Scene,
    path_name: str,
    values: Sequence[float] | np.ndarray,
    modes: int = 5,
    ax: Axes | None = None,
    path: PathLike | None = None,
    uncoupled: bool = True,
) -> Figure:
    """Natural frequencies against one parameter: a veering diagram.

    ``path_name`` is a field path of :func:`mstmm.sweep` (``beam.EI``,
    ``attachments[2].k``, ...) and ``values`` the values it takes; the lowest
    ``modes`` natural frequencies at every value (counted as ``mstmm solve --modes``
    counts them, rigid-body zeros included) are drawn, one line per mode index
    (the zeros left out; a point the sweep cannot certify is a gap). The x axis is
    labelled with the field's unit (its kind's declaration), logarithmic when the
    values span more than two decades; the y axis is logarithmic when the frequencies
    do. The buckled range of a sweep under compression is shaded and labelled
    "buckled" (its edge the buckling load when an axial force is swept). When
    ``path_name`` is a value of an attachment (not its x) and ``uncoupled``, that
    attachment's own frequencies (a spring-mass's ``sqrt(k/m)``, a chain's, any
    kind's with unknowns) are drawn dashed: the curves veer where they cross them.

    A damped sweep (a damped scene, or a damping value swept) draws two panels, the
    TMD designer's figure: the damped frequencies ``w_d`` and the damping ratios
    ``zeta = sigma / |omega|`` of the same modes (``ax``: a pair of axes).
    """
    import warnings

    from .study import sweep

    values = np.asarray(values, dtype=float).ravel()
    nrigid = _rigid_body_modes(scene)
    with warnings.catch_warnings():  # the figure marks the buckled points
        warnings.filterwarnings("ignore", message=r".*points are buckled", category=RuntimeWarning)
        omega = sweep(scene, {path_name: values}, modes=int(modes))[:, nrigid:]
    order = np.argsort(values, kind="stable")
    v, omega = values[order], omega[order]
    if np.iscomplexobj(omega):
        return _finish(_damped_veering(scene, path_name, v, omega, nrigid, ax), path)
    own_figure = ax is None
    fig, ax = _axes(ax)
    _mode_lines(ax, v, omega, nrigid)
    match = _ATTACHMENT_FIELD.match(path_name)
    own = _own_frequencies(scene, int(match.group(1)), path_name, v) if match else None
    if uncoupled and own is not None:
        for j in range(own.shape[1]):
            ax.plot(
                v,
                own[:, j],
                color="k",
                lw=0.9,
                ls="--",
                gid="uncoupled",
                label=f"own frequencies of attachments[{match.group(1)}]" if j == 0 else None,
            )
    buckled, critical = _buckled(scene, path_name, v)
    if buckled.any():
        _shade_buckled([ax], v, buckled, critical)
    _sweep_axes(ax, v, omega, log_ok=True)
    ax.set_xlabel(f"{path_name} [{field_unit(scene, path_name)}]")
    ax.set_ylabel(r"$\omega$ [rad/s]")
    ax.set_title(f"{scene.name}: natural frequencies against {path_name}", fontsize=10)
    sec = ax.secondary_yaxis("right", functions=(_to_hz, _to_rad))
    sec.set_ylabel("f [Hz]")
    _sweep_legend(fig, ax, own_figure)
    return _finish(fig, path)


def _damped_veering(
    scene: Scene, path_name: str, v: np.ndarray, omega: np.ndarray, nrigid: int, ax
) -> Figure:
    """A damped sweep's two panels: ``w_d`` (above) and ``zeta`` (below) of each mode."""
    fig, ax_w, ax_z = _pair(ax, (8.0, 6.4), 2, sharex=True)
    w_d = omega.real
    with np.errstate(divide="ignore", invalid="ignore"):
        zeta = omega.imag / np.abs(omega)
    _mode_lines(ax_w, v, w_d, nrigid)
    _mode_lines(ax_z, v, zeta, nrigid)
    _sweep_axes(ax_w, v, w_d, log_ok=True)
    _sweep_axes(ax_z, v, zeta, log_ok=False)
    ax_w.set_ylabel(r"damped frequency $\omega_d$ [rad/s]")
    ax_z.set_ylabel(r"damping ratio $\zeta = \sigma/|\omega|$ [-]")
    ax_z.set_xlabel(f"{path_name} [{field_unit(scene, path_name)}]")
    ax_w.set_title(f"{scene.name}: damped modes against {path_name}", fontsize=10)
    sec = ax_w.secondary_yaxis("right", functions=(_to_hz, _to_rad))
    sec.set_ylabel("f [Hz]")
    _sweep_legend(fig, ax_w, ax is None)
    return fig


#: The magnitude axis of an frf spans at most this many decades below its peak (a zero
#: of the response, or a point near a support, reaches 1e-100 and hid everything else).
FRF_DECADES = 10


def _frf_phase(H: np.ndarray, omegas: np.ndarray, natural: np.ndarray, damped: bool):
    """The unwrapped phase (degrees) of one response, NaN where it is 0 or not finite.
    A damped response is unwrapped as is; an undamped one is a real function times a
    constant phase (1, i, -1: receptance, mobility, accelerance) that changes sign by
    exactly 180 deg, which no unwrapping can orient: it falls by 180 through a natural
    frequency (a resonance) and rises by 180 through an antiresonance."""
    phase = np.full(len(H), np.nan)
    with np.errstate(invalid="ignore"):
        ok = np.flatnonzero(np.isfinite(H) & (np.abs(H) > 0))
    if not ok.size:
        return phase
    if damped:
        phase[ok] = np.degrees(np.unwrap(np.angle(H[ok])))
        return phase
    base = float(np.angle(H[ok[0]]))
    sign = np.sign(np.real(H[ok] * np.exp(-1j * base)))
    w = np.asarray(omegas, dtype=float)[ok]
    steps = np.zeros(len(ok))
    for i in np.flatnonzero(sign[1:] != sign[:-1]):
        resonance = np.any((natural > w[i]) & (natural <= w[i + 1]))
        steps[i + 1] = -180.0 if resonance else 180.0
    phase[ok] = math.degrees(base) + np.cumsum(steps)
    return phase


def _frf_name(quantity: str, point) -> str:
    """A response's legend entry: what is plotted where, ``acceleration:x=5.0`` for the
    accelerance of ``displacement:x=5.0``."""
    angular = point.quantity.lower() in ("rotation", "theta")
    word = {"mobility": "velocity", "accelerance": "acceleration"}.get(quantity)
    if word is None:
        return str(point)
    rest = str(point).split(":", 1)[1]
    return f"{'angular ' if angular else ''}{word}:{rest}"


def _clip_magnitude(ax: Axes, mags: list[np.ndarray]) -> None:
    """Clip the magnitude axis at :data:`FRF_DECADES` below the peak, and say so on it."""
    values = np.concatenate(mags)
    values = values[np.isfinite(values) & (values > 0)]
    if not values.size:
        return
    peak = float(values.max())
    floor = peak * 10.0**-FRF_DECADES
    if values.min() < floor:
        ax.set_ylim(floor, peak * 3.0)
        ax.text(0.01, 0.02, f"axis clipped {FRF_DECADES} decades below the peak",
                transform=ax.transAxes, fontsize=7, color="0.35", gid="clip-note")  # fmt: skip


def frf_figure(
    scene: Scene,
    source,
    outputs,
    omegas: np.ndarray,
    path: PathLike | None = None,
    quantity: str = "receptance",
    ax: tuple[Axes, Axes] | None = None,
    label: str | None = None,
    hz: bool = False,
) -> Figure:
    """Frequency response of ``outputs`` to ``source`` (``mstmm.response`` points or their
    strings) over ``omegas`` (rad/s): magnitude (log scale, in the quantity's unit: m/N,
    rad/N, m/(N m), ... for a receptance; at most :data:`FRF_DECADES` decades below the
    peak, said on the axes when clipped) above, the unwrapped phase (degrees) below, the
    natural frequencies in the band marked (w_d of a damped scene). An undamped phase
    falls by 180 deg through each resonance and rises by 180 through each antiresonance.
    The legend names what is plotted (``velocity:x=5.0`` for a mobility). The frequency
    axis is in rad/s, or in Hz when ``hz``. ``ax``: draw into these two axes (a
    before/after comparison), labelled ``label``."""
    from .response import frf, parse_point
    from .solve import solve

    src = parse_point(source, "input")
    dst = [parse_point(o, "output") for o in (outputs if isinstance(outputs, list) else [outputs])]
    H = frf(scene, [src], dst, omegas, quantity=quantity)[:, 0, :]
    sol = solve(scene, band=(float(omegas[0]), float(omegas[-1])), shapes=False)
    marks = np.unique(np.real(sol.omega))
    damped = topology_of(scene).damped
    fig, ax_mag, ax_ph = _pair(ax, (8.0, 6.0), 2, sharex=True)
    f = _to_hz(omegas) if hz else np.asarray(omegas, dtype=float)
    units = {frf_unit(quantity, d.quantity.lower(), src.quantity.lower()) for d in dst}
    mags = []
    for j, d in enumerate(dst):
        name = f"{label}: {_frf_name(quantity, d)}" if label else _frf_name(quantity, d)
        if len(units) > 1:
            name += f" [{frf_unit(quantity, d.quantity.lower(), src.quantity.lower())}]"
        mags.append(np.abs(H[:, j]))
        ax_mag.semilogy(f, mags[-1], lw=1.2, label=name, gid="frf")
        phase = _frf_phase(H[:, j], omegas, marks, damped)
        ax_ph.plot(f, phase, lw=1.0, label=name, gid="phase")
    _clip_magnitude(ax_mag, mags)
    scale = 1.0 / _TWO_PI if hz else 1.0
    for w in marks[marks > 0]:
        ax_mag.axvline(w * scale, color="0.6", lw=0.6, ls=":", gid="root-line")
        ax_ph.axvline(w * scale, color="0.6", lw=0.6, ls=":", gid="root-line")
    symbol = {"receptance": "|H|", "mobility": r"|i$\omega$H|", "accelerance": r"|$\omega^2$H|"}
    unit = units.pop() if len(units) == 1 else "see legend"
    ax_mag.set_ylabel(f"{quantity} {symbol[quantity]} [{unit}]")
    ax_ph.set_ylabel("phase (unwrapped) [deg]")
    ax_ph.set_xlabel("f [Hz]" if hz else r"$\omega$ [rad/s]")
    ax_ph.set_xlim(f[0], f[-1])
    ax_mag.set_title(f"{scene.name}: {quantity} to {src} (natural frequencies dotted)", fontsize=10)
    _legend(ax_mag)
    return _finish(fig, path)


#: The two Bloch pairs of a cell (``Bands.k``'s columns): the more attenuated first.
_PAIRS = ("pair 1 (more attenuated)", "pair 2 (less attenuated)")


def dispersion(
    bands,
    path: PathLike | None = None,
    hz: bool = False,
    ax: tuple[Axes, Axes] | None = None,
) -> Figure:
    """Dispersion of a periodic cell (``mstmm.bands``): Re k L / pi of the propagating
    pairs (left) and the attenuation Im k L per cell of both pairs (right, log scale)
    against frequency (rad/s, or Hz with ``hz``), the stop bands shaded and the edges
    marked. The legend (right of both panels in a new figure) tells the pairs (the more
    attenuated dashed), their Re and Im parts, the stop bands and the edges apart."""
    own_figure = ax is None
    fig, ax_re, ax_im = _pair(ax, (10.5, 5.0), 1, sharey=True)
    from .bands import propagating_pairs

    scale = 1.0 / _TWO_PI if hz else 1.0
    f = bands.omega * scale
    kL = bands.k * bands.length
    moving = propagating_pairs(bands.mu)
    for j, style in ((1, "-"), (0, "--")):
        re = np.abs(kL[:, j].real) / np.pi
        if not bands.damped:
            re = np.where(moving[:, j], re, np.nan)
        ax_re.plot(re, f, style, color=f"C{j}", lw=1.2, gid="dispersion",
                   label=f"{_PAIRS[j]}: Re k L / pi")  # fmt: skip
        ax_im.semilogx(np.abs(kL[:, j].imag), f, style, color=f"C{j}", lw=1.2,
                       gid="attenuation", label=f"{_PAIRS[j]}: Im k L")  # fmt: skip
    for i, (lo, hi) in enumerate(bands.gaps):
        for a in (ax_re, ax_im):
            label = "stop band" if i == 0 and a is ax_re else None
            a.axhspan(lo * scale, hi * scale, color="0.85", zorder=0, gid="gap", label=label)
    for i, e in enumerate(bands.edges):
        ax_re.axhline(e.omega * scale, color="0.5", lw=0.5, ls=":", gid="edge",
                      label="band edge" if i == 0 else None)  # fmt: skip
    ax_re.set_xlim(0.0, 1.0)
    ax_re.set_xlabel("Re k L / pi [-]")
    ax_im.set_xlabel("Im k L (attenuation per cell) [Np]")
    ax_re.set_ylabel("f [Hz]" if hz else r"$\omega$ [rad/s]")
    ax_re.set_ylim(f[0], f[-1])
    title = f"{bands.cell.name}: dispersion"
    if bands.gaps:
        title += f", {len(bands.gaps)} stop band(s) shaded"
    ax_re.set_title(title, loc="left", fontsize=10)
    handles, labels = ax_re.get_legend_handles_labels()
    more = ax_im.get_legend_handles_labels()
    if own_figure:
        fig.legend(handles + more[0], labels + more[1], loc="outside right upper", fontsize=8)
    else:
        _legend(ax_im)
        ax_re.legend(fontsize=8)
    return _finish(fig, path)

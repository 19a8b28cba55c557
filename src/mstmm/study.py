"""Parameter studies: one compiled kernel, many parameter vectors, all cores.

``sweep(scene, {"attachments[2].k": values, ...}, modes=N)`` varies the named
fields together (equal-length arrays, point by point) and returns the lowest
``N`` frequencies of every point, an ``(n_points, N)`` array. The kernel's
certified root search (:mod:`mstmm.scan`) runs over the points with numba ``prange``;
a point whose roots the count cannot certify is NaN, with a warning, never a silent
guess.
"""

from __future__ import annotations

import math
import re
import time
import warnings
from collections.abc import Mapping

import numpy as np

from mstmm import catalog
from mstmm.physics import segment as segment_terms

from .events import read_events, sort_events
from .kernels import Kernel, load_kernel
from .limits import MAX_MODES, MAX_SWEEP_POINTS, check_count
from .progress import Bar
from .scene import CHECKS, Scene, SceneError, check_placement, check_representable
from .topology import field_index, parameter_vector, topology_of

_ATTACHMENT = re.compile(r"attachments\[(\d+)\]\.(\w+)(?:\[(\d+)\])?$")
SOURCE = "<sweep>"


#: Beam fields a stepped beam carries per segment: varying ``beam.<field>`` there would
#: change its first segment only, so a sweep names the segment.
PER_SEGMENT = catalog.SEGMENT_KEYS


def _paths(scene: Scene) -> dict[str, int]:
    """The field paths a sweep may vary and their index in the parameter vector."""
    fields = field_index(scene)
    if scene.beam.segments:
        del fields["beam.length"]
        for name in PER_SEGMENT:
            del fields[f"beam.{name}"]
    else:
        fields = {f: i for f, i in fields.items() if not f.startswith("beam.segments[")}
    return fields


#: Columns of the parameter vector that repeat another: the head holds the first
#: segment's EI and mass per length (the kernel's units) and a uniform beam's length is
#: also its segment's end.
_TWINS = {
    0: (0, catalog.HEAD),
    1: (1, catalog.HEAD + 1),
    2: (2, catalog.HEAD + 2),
    catalog.HEAD + 1: (1, catalog.HEAD + 1),
    catalog.HEAD + 2: (2, catalog.HEAD + 2),
}


def columns(scene: Scene, path: str) -> tuple[int, ...]:
    """Every index in the parameter vector a value of the field ``path`` is written to.

    Paths: ``beam.length|EI|mass_per_length|loss_factor|<physics>`` (a uniform beam
    only), ``beam.segments[s].EI|mass_per_length|loss_factor|<physics>`` (a stepped beam;
    the physics keys of ``catalog.SEGMENT_PHYSICS``: kappa_GA, rho_I, axial_force,
    foundation_k, foundation_kG),
    ``attachments[i].x``, ``attachments[i].<key>`` and
    ``attachments[i].<key>[j]`` (``i`` in x order, as ``scene.attachments``). Raises
    :class:`SceneError` for a path the scene does not have, saying what it has there.
    """
    fields = _paths(scene)
    if path in fields:
        return _TWINS.get(fields[path], (fields[path],))
    if path == "beam.length":
        problem = (
            "a stepped beam's total length is not a sweep parameter, nor is a segment's"
            " length; sweep beam.segments[s].EI|mass_per_length"
        )
    elif scene.beam.segments and path in {f"beam.{name}" for name in PER_SEGMENT}:
        name = path.split(".")[1]
        last = len(scene.beam.segments) - 1
        problem = (
            f"a stepped beam has a {name} per segment: vary beam.segments[i].{name}"
            f" (i = 0..{last}), each one you mean"
        )
    else:
        problem = _what_exists(scene, path, fields)
    raise SceneError(SOURCE, path, problem, path)


def column(scene: Scene, path: str) -> int:
    """Index in the parameter vector of a field path like ``beam.EI`` or
    ``attachments[2].k[1]`` (:func:`columns` gives every index a sweep writes)."""
    return columns(scene, path)[0]


def _what_exists(scene: Scene, path: str, fields: Mapping[str, int]) -> str:
    match = _ATTACHMENT.match(path)
    if match:
        i = int(match.group(1))
        n = len(scene.attachments)
        if i >= n:
            return f"not a parameter: the scene has {n} attachments"
        own = [f for f in fields if f.startswith(f"attachments[{i}].")]
        return f"not a field of this {scene.attachments[i].kind} (it has: {', '.join(own)})"
    if path.startswith("beam."):
        own = [f for f in fields if f.startswith("beam.")]
        return f"not a field of this beam (it has: {', '.join(own)})"
    return (
        "not a parameter (beam.length|EI|mass_per_length, beam.segments[s].EI|mass_per_length,"
        " attachments[i].x|<key>|<key>[j])"
    )


def _check_of(scene: Scene, path: str) -> str:
    """The check a field's values must pass (:data:`mstmm.scene.CHECKS`)."""
    match = _ATTACHMENT.match(path)
    if match:
        kind = catalog.kind(scene.attachments[int(match.group(1))].kind)
        return next(k.check for k in kind.KEYS if k.name == match.group(2))
    if path.endswith(".loss_factor"):
        return "nonnegative"
    physics = {key: check for key, check, _ in catalog.SEGMENT_PHYSICS}
    return physics.get(path.rsplit(".", 1)[-1], "positive")


def is_damping(scene: Scene, path: str) -> bool:
    """Whether a field path names a damping value: a loss factor, or a key its kind
    declares ``damping`` (a dashpot's or a spring-mass's ``c``, a chain's ``c[j]``)."""
    match = _ATTACHMENT.match(path)
    if match:
        kind = catalog.kind(scene.attachments[int(match.group(1))].kind)
        return any(k.damping for k in kind.KEYS if k.name == match.group(2))
    return path.endswith(".loss_factor")


def parameter_matrix(scene: Scene, vary: Mapping[str, np.ndarray]) -> np.ndarray:
    """One parameter vector per point: the scene's vector with the varied fields set.

    Each value is checked as its key declares (positive, nonnegative, a position within
    [0, L] or inside the beam, with L of that point); where an ``x`` varies the event rows
    are re-sorted by x per point (stable; each row's tag and offset travel with it).
    Placement (:func:`mstmm.scene.check_placement`) and what float64 can carry
    (:func:`mstmm.scene.check_representable`) are checked at every point.
    """
    values = {path: np.atleast_1d(np.asarray(v, dtype=float)) for path, v in vary.items()}
    sizes = {v.shape[0] for v in values.values()}
    if not values:
        raise SceneError(SOURCE, "-", "nothing is varied", dict(vary))
    if len(sizes) != 1:
        raise SceneError(SOURCE, ",".join(values), "varied arrays differ in length", sorted(sizes))
    n = sizes.pop()
    P = np.tile(parameter_vector(scene), (n, 1))
    for path, v in values.items():
        P[:, list(columns(scene, path))] = v[:, None]
    for path, v in values.items():
        passes, problem = CHECKS[_check_of(scene, path)]
        finite = np.isfinite(v)
        for ok, text in ((finite, "must be finite"), (finite & passes(v, P[:, 0]), problem)):
            if not ok.all():
                i = int(np.argmin(ok))
                problem_at = f"at point {i}, " + text.format(length=float(P[i, 0]))
                raise SceneError(SOURCE, path, problem_at, float(v[i]))
    if "beam.length" in values:
        _check_positions(scene, P)
    _check_shear_limit(scene, values, P)
    check_placement(P, SOURCE, scene, point="point")
    check_representable(P, SOURCE, scene, point="point")
    sort_events(P)
    return P


def _check_shear_limit(scene: Scene, values: Mapping[str, np.ndarray], P: np.ndarray) -> None:
    """Every Timoshenko segment short of its shear limit at every point
    (``physics.segment.shear_limit_broken``, as the scene file requires of its own
    values)."""
    n_seg = int(P[0, 3])
    rows = P[:, catalog.HEAD : catalog.HEAD + catalog.SEGMENT_WIDTH * n_seg]
    rows = rows.reshape(len(P), n_seg, catalog.SEGMENT_WIDTH)
    bad = segment_terms.shear_limit_broken(segment_terms.row_values(rows, catalog.SEGMENT_COLUMNS))
    if not bad.any():
        return
    i, seg = (int(v) for v in np.argwhere(bad)[0])
    prefix = f"beam.segments[{seg}]" if scene.beam.segments else "beam"
    compression = segment_terms.compression_key()
    keys = [compression] + [k for k in (t.name for t in segment_terms.terms()) if k != compression]
    names = [f"{prefix}.{key}" for key in keys]
    path = next((name for name in names if name in values), names[0])
    column = catalog.SEGMENT_COLUMNS[compression]
    raise SceneError(
        SOURCE,
        path,
        f"at point {i}, {segment_terms.shear_limit_message()}",
        float(values[path][i]) if path in values else float(rows[i, seg, column]),
    )


def _check_positions(scene: Scene, P: np.ndarray) -> None:
    """Every component's x within the beam at every point (the length varies)."""
    events = read_events(P, topology_of(scene).kinds)
    for block in events.blocks:
        key = catalog.kind(block.kind).KEYS[0]
        passes, problem = CHECKS[key.check]
        ok = passes(events.positions[:, block.label], P[:, 0])
        if not ok.all():
            i = int(np.argmin(ok))
            raise SceneError(
                SOURCE,
                f"attachments[{block.label}].x",
                f"at point {i}, " + problem.format(length=float(P[i, 0])),
                float(events.positions[i, block.label]),
            )


def sweep(
    scene: Scene,
    vary: Mapping[str, np.ndarray],
    modes: int = 5,
    *,
    kernel: Kernel | None = None,
    scheduler: str | None = None,
    chunk: int = 2000,
    progress: bool = False,
) -> np.ndarray:
    """Lowest ``modes`` natural frequencies (rad/s) at every point of a parameter study.

    An undamped study returns a real ``(n_points, modes)`` array. A damped one (the scene
    is damped, or a varied field is a damping value: a loss factor, a ``c``; see
    :func:`is_damping`) solves every point's damped roots (:func:`mstmm.damped.solve_damped`,
    in the damped kernel even where the point's damping is 0) and returns them complex:
    ``omega = w_d + i sigma`` (``.real`` the damped frequency, ``.imag`` the decay rate,
    ``sigma / abs(omega)`` the damping ratio), the lowest ``modes`` by ``w_d`` as
    ``solve`` lists them.

    ``scheduler`` (e.g. ``"tcp://host:8786"``, or a ``distributed.Client``) runs the
    points in chunks of ``chunk`` on an existing Dask cluster (extra ``mstmm[dask]``);
    each worker loads (or derives) the same kernel and sweeps its chunk on all its cores.
    ``progress`` draws a bar on standard error (the command line does so on a terminal).
    The points run in chunks of a fraction of a second each: Ctrl-C stops the study
    between two of them (KeyboardInterrupt).
    """
    check_count(modes, MAX_MODES, "modes", SOURCE, "modes")
    for path, values in vary.items():
        check_count(np.size(values), MAX_SWEEP_POINTS, "points", SOURCE, path)
    topology = topology_of(scene)
    P = parameter_matrix(scene, vary)
    if topology.damped or any(is_damping(scene, path) for path in vary):
        if scheduler is not None:
            raise SceneError(
                SOURCE, "scheduler", "a damped parameter study runs on the local cores only"
            )
        out, certified = _damped_sweep(scene, vary, modes, progress)
    elif scheduler is not None:
        out, certified = _dask_sweep(scheduler, topology.key, P, modes, chunk, progress)
    else:
        if kernel is None:
            kernel = load_kernel(topology)
        out, certified = _local_sweep(kernel, P, modes, progress)
    buckled = np.zeros(len(P), dtype=bool)
    if not topology.damped and not any(is_damping(scene, path) for path in vary):
        buckled = _buckled_points(scene, vary, P, kernel)
    out[~certified | buckled] = math.nan
    unsure = int(np.count_nonzero(~certified & ~buckled))
    if unsure:
        warnings.warn(
            f"{unsure} of {len(P)} points could not be certified by the root count: set to NaN",
            RuntimeWarning,
            stacklevel=2,
        )
    return out


def _buckled_points(scene: Scene, vary: Mapping[str, np.ndarray], P: np.ndarray, kernel):
    """The points of an undamped study whose axial forces reach the buckling load
    (:mod:`mstmm.buckling`), with a warning that says where the structure buckles."""
    from .buckling import buckling, compressed

    rows = [i for i in range(len(P)) if compressed(P[i])]
    buckled = np.zeros(len(P), dtype=bool)
    if not rows:
        return buckled
    kernel = kernel or load_kernel(topology_of(scene))
    factors = {}
    for i in rows:
        state = buckling(kernel, P[i])
        factors[i] = state.load_factor
        buckled[i] = state.buckled
    if buckled.any():
        first = int(np.argmax(buckled))
        where = ", ".join(f"{path} = {np.asarray(v)[first]:.6g}" for path, v in vary.items())
        warnings.warn(
            f"{int(buckled.sum())} of {len(P)} points are buckled (their axial forces reach the"
            f" buckling load; no natural frequencies): set to NaN; the first, at {where},"
            f" buckles at {factors[first]:.12g} times its axial forces",
            RuntimeWarning,
            stacklevel=3,
        )
    return buckled


#: Seconds one chunk of a local sweep should take: Ctrl-C waits at most about this long
#: (a compiled call cannot be interrupted; KeyboardInterrupt is raised between chunks).
CHUNK_SECONDS = 0.25


def _local_sweep(kernel: Kernel, P: np.ndarray, modes: int, show: bool):
    """``kernel.sweep`` over the rows of P in chunks sized to take about CHUNK_SECONDS
    each (the first chunk one row per thread, then grown or shrunk by the time taken)."""
    import numba

    threads = max(1, numba.get_num_threads())
    out = np.empty((len(P), int(modes)))
    certified = np.zeros(len(P), dtype=bool)
    bar = Bar(len(P), "sweep", show=show and len(P) >= 100)
    size, i = threads, 0
    while i < len(P):
        j = min(len(P), i + size)
        t0 = time.perf_counter()
        out[i:j], certified[i:j] = kernel.sweep(P[i:j], modes)
        took = time.perf_counter() - t0
        bar.update(j - i)
        per_row = took / (j - i)
        fits = int(CHUNK_SECONDS / per_row) if per_row > 0 else 8 * size
        size = max(threads, min(8 * size, fits))
        i = j
    bar.close()
    return out, certified


def scene_at(scene: Scene, vary: Mapping[str, np.ndarray], point: int) -> Scene:
    """The scene of one point of a study: the varied fields (paths as :func:`columns`
    takes them) set to their values at ``point``, validated again."""
    from .scene import scene_from_dict, scene_to_dict

    data = scene_to_dict(scene)
    beam = data["beam"]
    for path, values in vary.items():
        v = float(np.atleast_1d(np.asarray(values, dtype=float))[point])
        match = _ATTACHMENT.match(path)
        if match:
            i, key, j = int(match.group(1)), match.group(2), match.group(3)
            a = data["attachments"][i]
            if j is None:
                a[key] = v
            else:
                given = {k: tuple(x) if isinstance(x, list) else x for k, x in a.items()}
                kind = catalog.kind(a["type"])
                k = next(k for k in kind.KEYS if k.name == key)
                a[key] = [float(x) for x in catalog.value(a["type"], given, k)]
                a[key][int(j)] = v
            continue
        segment = re.match(r"beam\.segments\[(\d+)\]\.(\w+)$", path)
        if segment:
            beam["segments"][int(segment.group(1))][segment.group(2)] = v
        else:
            beam[path.split(".", 1)[1]] = v
    return scene_from_dict(data, source=SOURCE)


def _damped_sweep(scene: Scene, vary: Mapping[str, np.ndarray], modes: int, show: bool):
    """Every point's lowest ``modes`` damped roots, one damped solve each, all in the
    damped kernel of the scene's topology (a point whose damping is 0 included: its roots
    are then real). Certified: the count confirmed every root and each converged."""
    from .damped import solve_damped
    from .topology import Topology

    base = topology_of(scene)
    kernel = load_kernel(Topology(base.left, base.right, base.kinds, damped=True))
    n = len(next(iter(vary.values())))
    out = np.full((n, int(modes)), complex(math.nan, math.nan))
    certified = np.zeros(n, dtype=bool)
    bar = Bar(n, "damped sweep", show=show and n >= 10)
    for i in range(n):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            sol = solve_damped(scene_at(scene, vary, i), modes=modes, shapes=False, kernel=kernel)
        k = min(int(modes), sol.omega.size)
        out[i, :k] = sol.omega[:k]
        certified[i] = bool(sol.count_checked and sol.converged.all() and k == modes)
        bar.update(1)
    bar.close()
    return out, certified


def sweep_chunk(key: str, P: np.ndarray, modes: int) -> tuple[np.ndarray, np.ndarray]:
    """One chunk of a sweep on a worker: the kernel of topology ``key`` over the rows of P."""
    from .topology import Topology

    return load_kernel(Topology.from_key(key)).sweep(P, modes)


def _dask_sweep(scheduler, key: str, P: np.ndarray, modes: int, chunk: int, show: bool):
    pieces = [P[i : i + chunk] for i in range(0, len(P), chunk)]
    results = dask_map(scheduler, sweep_chunk, pieces, (key, modes), "sweep", show)
    return np.concatenate([r[0] for r in results]), np.concatenate([r[1] for r in results])


def dask_map(scheduler, fn, pieces: list, common: tuple, label: str, show: bool) -> list:
    """``fn(*common[:1], piece, *common[1:])`` for every piece on a Dask cluster (an address
    like ``tcp://host:8786`` or a ``distributed.Client``), in order; a progress bar counts
    the rows done. Each worker loads (or derives) its kernel itself."""
    try:
        from distributed import Client, as_completed
    except ImportError as exc:  # pragma: no cover - depends on the installation
        raise RuntimeError("a Dask scheduler needs the extra: pip install 'mstmm[dask]'") from exc
    client = scheduler if isinstance(scheduler, Client) else Client(scheduler)
    try:
        n = len(pieces)
        head, tail = common[:1], common[1:]
        args = [[c] * n for c in head] + [pieces] + [[c] * n for c in tail]
        futures = client.map(fn, *args)
        bar = Bar(sum(len(piece) for piece in pieces), f"{label} on the Dask cluster", show=show)
        for future in as_completed(futures):
            bar.update(len(pieces[futures.index(future)]))
        bar.close()
        return client.gather(futures)
    finally:
        if client is not scheduler:
            client.close()


def parse_range(text: str) -> np.ndarray:
    """``LOG:lo:hi:n``, ``LIN:lo:hi:n`` or a comma-separated list of values.

    Raises :class:`ValueError` saying what is wrong: not numbers, fewer than one
    point, a non-finite value, a LOG range not above 0.
    """
    kind, _, rest = text.partition(":")
    if kind.upper() in ("LOG", "LIN"):
        parts = rest.split(":")
        if len(parts) != 3:
            raise ValueError(f"expected {kind.upper()}:lo:hi:n")
        try:
            lo, hi, n = float(parts[0]), float(parts[1]), int(parts[2])
        except ValueError:
            raise ValueError("lo and hi must be numbers and n an integer") from None
        if n < 1:
            raise ValueError(f"n = {n}: a range needs at least 1 point")
        if n > MAX_SWEEP_POINTS:
            raise ValueError(f"n = {n}: at most {MAX_SWEEP_POINTS:,} points (a limit of mstmm)")
        if not (math.isfinite(lo) and math.isfinite(hi)):
            raise ValueError("lo and hi must be finite")
        if kind.upper() == "LOG":
            if lo <= 0.0 or hi <= 0.0:
                raise ValueError("a LOG range needs lo > 0 and hi > 0")
            return np.logspace(math.log10(lo), math.log10(hi), n)
        return np.linspace(lo, hi, n)
    try:
        values = np.array([float(v) for v in text.split(",")])
    except ValueError:
        raise ValueError("expected LOG:lo:hi:n, LIN:lo:hi:n or a list of numbers 1,2,3") from None
    if not np.isfinite(values).all():
        raise ValueError("values must be finite")
    return values

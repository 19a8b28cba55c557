"""Parameter studies: one compiled kernel, many parameter vectors, all cores.

``sweep(scene, {"attachments[2].k": values, ...}, modes=N)`` varies the named
fields together (equal-length arrays, point by point) and returns the lowest
``N`` frequencies of every point, an ``(n_points, N)`` array. The kernel's
certified scan runs over the points with numba ``prange``; a point it cannot
certify (double or very close roots) goes through the full search
(:func:`mstmm.scan.find_roots`); a point even that cannot certify is NaN, with
a warning, never a silent guess.
"""

from __future__ import annotations

import math
import re
import warnings
from collections.abc import Mapping

import numpy as np

from .kernels import Kernel, load_kernel
from .progress import Bar
from .scan import find_roots
from .scene import Scene, SceneError, check_representable
from .topology import ATTACHMENT_PARAMETERS, parameter_vector, topology_of

_BEAM_FIELDS = {"length": 0, "EI": 1, "mass_per_length": 2}
_ATTACHMENT = re.compile(r"attachments\[(\d+)\]\.(\w+)$")
SOURCE = "<sweep>"


def column(scene: Scene, path: str) -> int:
    """Index in the parameter vector of a field path like ``beam.EI`` or ``attachments[2].k``."""
    if path.startswith("beam.") and path[5:] in _BEAM_FIELDS:
        return _BEAM_FIELDS[path[5:]]
    match = _ATTACHMENT.match(path)
    if match:
        i, name = int(match.group(1)), match.group(2)
        if i >= len(scene.attachments):
            raise SceneError(SOURCE, path, f"the scene has {len(scene.attachments)} attachments", i)
        fields = ATTACHMENT_PARAMETERS[scene.attachments[i].kind]
        if name in fields:
            return 3 + 3 * i + fields.index(name)
    raise SceneError(
        SOURCE, path, "not a parameter (beam.length|EI|mass_per_length, attachments[i].x|k|m)", path
    )


def parameter_matrix(scene: Scene, vary: Mapping[str, np.ndarray]) -> np.ndarray:
    """One parameter vector per point, attachments re-sorted by ``x`` where ``x`` varies."""
    values = {path: np.atleast_1d(np.asarray(v, dtype=float)) for path, v in vary.items()}
    sizes = {v.shape[0] for v in values.values()}
    if len(sizes) != 1:
        raise SceneError(SOURCE, ",".join(values), "varied arrays differ in length", sorted(sizes))
    n = sizes.pop()
    P = np.tile(parameter_vector(scene), (n, 1))
    for path, v in values.items():
        bad = ~np.isfinite(v) | (v <= 0.0 if not path.endswith(".x") else v < 0.0)
        if bad.any():
            raise SceneError(SOURCE, path, "values must be finite and > 0", float(v[bad][0]))
        P[:, column(scene, path)] = v
    if len(scene.attachments):
        rec = P[:, 3:].reshape(n, -1, 3)
        outside = rec[:, :, 0] > P[:, :1]
        if outside.any():
            i, j = np.argwhere(outside)[0]
            raise SceneError(SOURCE, f"attachments[{j}].x", "must lie in [0, length]", rec[i, j, 0])
        order = np.argsort(rec[:, :, 0], axis=1, kind="stable")
        P[:, 3:] = np.take_along_axis(rec, order[:, :, None], axis=1).reshape(n, -1)
    check_representable(P, SOURCE, point="point")
    return P


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
    """Lowest ``modes`` frequencies (rad/s) at every point of a parameter study.

    ``scheduler`` (e.g. ``"tcp://host:8786"``, or a ``distributed.Client``) runs the
    points in chunks of ``chunk`` on an existing Dask cluster (extra ``mstmm[dask]``);
    each worker loads (or derives) the same kernel and sweeps its chunk on all its cores.
    ``progress`` draws a bar on standard error (the command line does so on a terminal).
    """
    P = parameter_matrix(scene, vary)
    topology = topology_of(scene)
    if scheduler is not None:
        out, certified = _dask_sweep(scheduler, topology.key, P, modes, chunk, progress)
        if kernel is None and not certified.all():
            kernel = load_kernel(topology)
    else:
        if kernel is None:
            kernel = load_kernel(topology)
        out, certified = _local_sweep(kernel, P, modes, progress)
    unsure = 0
    for i in np.flatnonzero(~certified):
        found = find_roots(kernel, P[i], modes=modes)
        omega = [r.omega for r in found.roots for _ in range(r.reported)]
        if found.count_checked and len(omega) == modes:
            out[i] = omega
        else:
            out[i] = math.nan
            unsure += 1
    if unsure:
        warnings.warn(
            f"{unsure} of {len(P)} points could not be certified by the root count: set to NaN",
            RuntimeWarning,
            stacklevel=2,
        )
    return out


def _local_sweep(kernel: Kernel, P: np.ndarray, modes: int, show: bool):
    if not show or len(P) < 100:
        return kernel.sweep(P, modes)
    parts = np.array_split(np.arange(len(P)), 40)
    bar = Bar(len(P), "sweep", show=True)
    outs, certs = [], []
    for idx in parts:
        o, c = kernel.sweep(P[idx], modes)
        outs.append(o)
        certs.append(c)
        bar.update(len(idx))
    bar.close()
    return np.concatenate(outs), np.concatenate(certs)


def sweep_chunk(key: str, P: np.ndarray, modes: int) -> tuple[np.ndarray, np.ndarray]:
    """One chunk of a sweep on a worker: the kernel of topology ``key`` over the rows of P."""
    from .topology import Topology

    return load_kernel(Topology.from_key(key)).sweep(P, modes)


def _dask_sweep(scheduler, key: str, P: np.ndarray, modes: int, chunk: int, show: bool):
    try:
        from distributed import Client, as_completed
    except ImportError as exc:  # pragma: no cover - depends on the installation
        raise RuntimeError("a Dask scheduler needs the extra: pip install 'mstmm[dask]'") from exc
    client = scheduler if isinstance(scheduler, Client) else Client(scheduler)
    try:
        pieces = [P[i : i + chunk] for i in range(0, len(P), chunk)]
        futures = client.map(sweep_chunk, [key] * len(pieces), pieces, [modes] * len(pieces))
        bar = Bar(len(P), "sweep on the Dask cluster", show=show)
        for future in as_completed(futures):
            bar.update(len(pieces[futures.index(future)]))
        bar.close()
        results = client.gather(futures)
    finally:
        if client is not scheduler:
            client.close()
    return np.concatenate([r[0] for r in results]), np.concatenate([r[1] for r in results])


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

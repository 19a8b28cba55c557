"""What ``mstmm show`` prints of paper Eq. (4) for any number of components: the chain, ``Z_all``,
``Z_bar`` and the zero pattern of ``U_bar``, with no symbolic product at all.

``symbolic(scene, evaluate=False)`` forms every product of the chain as an unevaluated
SymPy expression: its cost grows faster than the number of components squared (33 s for
100 spring-masses, past 300 s for 1,000). What ``mstmm show`` prints of the overall
equation needs only where its entries are structurally nonzero, which is the same
product carried out on booleans: an entry of ``A W`` is nonzero where some ``A[i, k]`` and
``W[k, j]`` both are (as ``assemble._matmul`` skips zero factors). Each component's
descriptor pattern is derived once per kind and shape (which of its values vanish, how
long its lists are): milliseconds for a thousand components. Imports SymPy (through
``mstmm.derive``): only ``mstmm show`` imports this module.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import numpy as np
import sympy as sp

from mstmm.derive.assemble import _zero, chain, component_descriptor, unknown_names
from mstmm.derive.reduce import zero_columns

__all__ = ["Structure", "component_label", "structure_of"]


@dataclass(frozen=True)
class Structure:
    """What ``mstmm show`` prints of a scene's overall transfer equation: the components
    along the chain (labels, ``x = 0`` to ``L``), the names of ``Z_all`` and ``Z_bar``, and
    ``pattern[i, j]``: whether entry (i, j) of ``U_bar`` is structurally nonzero."""

    chain: tuple[str, ...]
    Z_all: tuple[str, ...]
    Z_bar: tuple[str, ...]
    pattern: np.ndarray

    def sparsity(self) -> list[str]:
        """The rows of ``U_bar``: ``X`` for a structurally nonzero entry, ``.`` for zero
        (as :meth:`mstmm.derive.Derivation.sparsity`)."""
        return [" ".join("X" if v else "." for v in row) for row in self.pattern]


def _shape(values: dict) -> tuple:
    """A component's values reduced to what its descriptor's zero pattern depends on:
    each value zero (a damping value left out) or not, each list's length."""
    return tuple(
        (name, tuple(_zero(e) for e in v) if isinstance(v, list) else _zero(v))
        for name, v in values.items()
    )


@cache
def _descriptor_pattern(kind: str, shape: tuple) -> tuple[np.ndarray, ...]:
    """``(Cz, Cq, A, B) != 0`` of a component of ``kind`` with values of ``shape``."""
    values: dict = {}
    for name, zero in shape:
        if isinstance(zero, tuple):
            values[name] = [
                sp.S.Zero if z else sp.Symbol(f"{name}{j}", positive=True)
                for j, z in enumerate(zero)
            ]
        else:
            values[name] = sp.S.Zero if zero else sp.Symbol(name, positive=True)
    d = component_descriptor(kind, values)
    return tuple(
        np.array([[not _zero(e) for e in M.row(i)] for i in range(M.rows)], dtype=bool).reshape(
            M.rows, M.cols
        )
        for M in (d.Cz, d.Cq, d.A, d.B)
    )


def _times(A: np.ndarray, W: np.ndarray) -> np.ndarray:
    """The structural nonzeros of the product of two patterns."""
    return (A.astype(np.int64) @ W.astype(np.int64)) > 0


def structure_of(scene) -> Structure:
    """The chain, ``Z_all``, ``Z_bar`` and ``U_bar``'s zero pattern of ``scene``, as
    :func:`mstmm.derive.symbolic` gives them (a test compares the two), in time linear in
    the number of components per column of ``Z_all``."""
    components = chain(scene)
    points = [(kind, par) for kind, par in components if kind != "beam"]
    patterns = [_descriptor_pattern(kind, _shape(par["values"])) for kind, par in points]
    n_all = 8 + sum(p[1].shape[1] for p in patterns)
    W = np.zeros((4, n_all), dtype=bool)
    W[:, :4] = np.eye(4, dtype=bool)
    rows: list[np.ndarray] = []
    names: list[str] = []
    labels = ["Z_1 (left end)"]
    col = 4
    it = iter(patterns)
    for kind, par in components:
        if kind == "beam":  # every entry of a segment's transfer is nonzero
            W = np.broadcast_to(W.any(axis=0), W.shape).copy()
            labels.append(f"beam {par['l']}")
            continue
        Cz, Cq, A, B = next(it)
        n_q = Cq.shape[1]
        for r in range(Cz.shape[0]):
            row = _times(Cz[r : r + 1], W)[0]
            row[col : col + n_q] |= Cq[r]
            rows.append(row)
        W = _times(A, W)
        W[:, col : col + n_q] |= B
        names += unknown_names(kind, par["index"], n_q)
        labels.append(component_label(kind, par))
        col += n_q
    main = W.copy()
    main[:, n_all - 4 :] = np.eye(4, dtype=bool)
    U_all = np.vstack([main, *rows]) if rows else main
    Z_all = (
        *(f"{v}_1" for v in ("Y", "theta", "M", "Q")),
        *names,
        *(f"{v}_root" for v in ("Y", "theta", "M", "Q")),
    )
    drop = set(zero_columns(scene.beam.left, scene.beam.right, n_all))
    keep = [j for j in range(n_all) if j not in drop]
    return Structure(
        (*labels, "Z_root (right end)"),
        Z_all,
        tuple(Z_all[j] for j in keep),
        U_all[:, keep],
    )


def component_label(kind: str, par: dict) -> str:
    """A point component's label in the chain: ``spring_mass 2 (k_2, m_2, 0)`` (as
    :meth:`mstmm.derive.Derivation.chain` writes it)."""
    values = ", ".join(
        str(v) if not isinstance(v, list) else "[" + ", ".join(map(str, v)) + "]"
        for v in par["values"].values()
    )
    return f"{kind} {par['index']}" + (f" ({values})" if values else "")

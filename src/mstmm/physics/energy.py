"""A point kind's energy: the one declaration its physics is derived from.

SymPy is imported only when an :class:`Energy` is built (by ``mstmm.derive``, from a kind's
``energy(values)``); the runtime reads a kind's keys without it (docs/components.md).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

#: What carries an unknown q of a kind's energy: a rigid translation of the beam
#: (``"Y"``: a hanging mass's displacement) or a rigid rotation about the point
#: (``"theta"``: the rotation of a rotary inertia on a torsion spring).
MOVES = ("Y", "theta")


@dataclass(frozen=True)
class Energy:
    """A point kind's physics over ``u = [Y, theta, q...]`` (units L = EI = mbar = 1):
    stiffness ``K``, damping ``C`` and mass ``M`` (SymPy matrices, symmetric, (2 + n_q)
    square), so that its potential energy is ``u^T K u / 2``, its dissipation
    ``u'^T C u' / 2`` and its kinetic energy ``u'^T M u' / 2``; ``moves[j]`` says which
    rigid motion of the beam carries ``q[j]`` (:data:`MOVES`). A damping value is 0 in an
    undamped kernel. The mass may couple the beam's Y and theta to an unknown (an
    inerter): the modal masses carry it; a mass between two unknowns is refused."""

    K: Any
    C: Any
    M: Any
    moves: tuple = ()

    def __post_init__(self) -> None:
        import sympy as sp

        n = 2 + len(self.moves)
        for name in ("K", "C", "M"):
            X = getattr(self, name)
            if X.shape != (n, n):
                raise ValueError(f"energy: {name} is {n} x {n} over [Y, theta, q...]")
            if (X - X.T).applyfunc(sp.expand) != sp.zeros(n, n):
                raise ValueError(f"energy: {name} must be symmetric")
        if any(m not in MOVES for m in self.moves):
            raise ValueError(f"energy: each q moves with one of {MOVES}")
        for i in range(2, n):
            for j in range(2, n):
                if i != j and sp.expand(self.M[i, j]) != 0:
                    raise ValueError(
                        f"energy: M[{i}, {j}] = {self.M[i, j]} couples the unknowns q{i - 2}"
                        f" and q{j - 2} (the modal mass carries the mass of each unknown and"
                        " its coupling to the beam's Y and theta, not a mass between two"
                        " unknowns)"
                    )

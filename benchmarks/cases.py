"""The extreme cases of the numerical-stability suite, as data, and how a case is scored.

Shared by ``tests/test_extremes.py`` (which asserts) and ``benchmarks/stability.py``
(which writes ``docs/stability.md``), so that the report's numbers are the
computation the tests assert.

A :class:`Case` is a scene dict in the TOML layout (build it with
``mstmm.scene_from_dict``), the number of lowest modes compared, the condition
it exercises and the tolerance the default (``stable``) formulation must meet:
``1e-12`` where the problem is well conditioned (moderate dimensionless
parameters, simple and well-separated roots), ``1e-10`` otherwise (parameters
at the extremes of the issue's ranges, near-coincident attachments, multiple
roots, long chains).

Scoring (:func:`compare`): ``mstmm.solve(scene, modes=n, formulation=f)`` (mode
shapes on for the default formulation, the path a user calls) against the
independent reference model (``tests/reference_model.py``: global assembly and a
Wittrick-Williams count in
mpmath). The error of mode ``i`` is ``|omega_i - ref_i| / ref_i``; a reference
zero (rigid-body mode) must be returned as exactly ``0.0`` (error 0, else inf);
fewer roots than asked is an infinite error. The maximum over the modes is
:func:`evaluate_case`.

References are computed once per process and kept in a module-level dict (never
on disk). For the 1000-attachment case the reference polishes each root of the
stable solution in a narrow bracket with the reference's own count and global
determinant (``reference_model.band``), and ``count_below`` at the top of the
last bracket proves that the brackets hold every root below it (see
:func:`reference`).
"""

from __future__ import annotations

import math
import sys
import time
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from mpmath import mp, mpf

import mstmm

ROOT = Path(__file__).resolve().parent.parent
TESTS = ROOT / "tests"
if str(TESTS) not in sys.path:
    sys.path.insert(0, str(TESTS))

import reference_model as rm  # noqa: E402  (tests/reference_model.py)

WELL = 1e-12  # tolerance where well conditioned
ILL = 1e-10  # tolerance otherwise
ENDS = ("clamped", "pinned", "free", "sliding")
#: Relative half-width of the brackets in which the reference polishes our roots.
BRACKET = 1e-8


@dataclass(frozen=True)
class Case:
    """One extreme case: a scene (TOML layout), the modes compared, what it exercises."""

    name: str
    scene: dict
    modes: int
    condition: str
    tol: float
    reference: str = "frequencies"  # or "brackets" (polish the stable roots, count at the top)
    dps: int = 30

    def build(self) -> mstmm.Scene:
        return mstmm.scene_from_dict(self.scene)


def make_scene(
    name: str,
    left: str,
    right: str,
    attachments=(),
    *,
    L: float = 1.3,
    EI: float = 2.1e4,
    mbar: float = 7.9,
) -> dict:
    """Scene dict; ``attachments`` as dimensionless ``(x/L, k L^3/EI, m/(mbar L))`` triples."""
    atts = [
        {
            "type": "spring_mass",
            "x": xi * L,
            "k": K * EI / L**3,
            "m": M * mbar * L,
        }
        for xi, K, M in attachments
    ]
    beam = {"length": L, "EI": EI, "mass_per_length": mbar, "left": left, "right": right}
    return {"name": name, "beam": beam, "attachments": atts}


#: Three moderate spring-masses (dimensionless) used by the boundary-condition cases.
THREE = ((0.2, 40.0, 0.3), (0.55, 600.0, 0.15), (0.85, 5000.0, 0.05))


def _paper_example() -> dict:
    with open(mstmm.example_path("wu_chou_1998"), "rb") as fh:
        data = tomllib.load(fh)
    data["name"] = "wu_chou_1998"
    return data


def _many(n: int) -> tuple:
    """``n`` light spring-masses spread along the beam, oscillator frequencies 20..2000."""
    return tuple(
        ((i + 0.5) / n, (1.0 / n) * (20.0 + 1980.0 * i / (n - 1)) ** 2, 1.0 / n) for i in range(n)
    )


def _cases() -> list[Case]:
    out = []
    for left in ENDS:
        for right in ENDS:
            name = f"bc_{left}_{right}"
            out.append(
                Case(
                    name,
                    make_scene(name, left, right, THREE),
                    12,
                    f"end conditions {left}-{right} (3 spring-masses)",
                    WELL,
                )
            )
    out += [
        Case(
            "free_free_rigid",
            make_scene(
                "free_free_rigid",
                "free",
                "free",
                ((0.0, 80.0, 0.4), (0.5, 300.0, 0.2), (1.0, 80.0, 0.4)),
            ),
            8,
            "free-free: two zero frequencies (rigid-body), attachments at both free ends",
            WELL,
        ),
        Case(
            "paper_100_modes",
            _paper_example(),
            100,
            "paper example (Wu & Chou 1998), all of its first 100 modes (lambda L up to ~315)",
            WELL,
        ),
        Case(
            "soft_springs",
            make_scene(
                "soft_springs",
                "clamped",
                "free",
                ((0.3, 1e-6, 1.0), (0.6, 3e-6, 1.0), (0.9, 1e-5, 1.0)),
            ),
            10,
            "springs k = 1e-6 .. 1e-5 EI/L^3: oscillator modes 1e-3 below the beam's",
            ILL,
        ),
        Case(
            "stiff_springs",
            make_scene("stiff_springs", "pinned", "pinned", ((0.3, 1e12, 1.0), (0.7, 1e12, 0.5))),
            10,
            "springs k = 1e12 EI/L^3 with masses mbar*L: rigidly mounted point masses",
            ILL,
        ),
        Case(
            "stiff_heavy",
            make_scene("stiff_heavy", "clamped", "free", ((0.5, 1e12, 1e6), (0.8, 1e9, 1e6))),
            12,
            "k = 1e9, 1e12 EI/L^3, m = 1e6 mbar*L: near-rigid supports, oscillators in the band",
            ILL,
        ),
        Case(
            "springs_span",
            make_scene(
                "springs_span",
                "clamped",
                "pinned",
                tuple((0.1 + 0.12 * i, 10.0 ** (-6 + 3 * i), 1.0) for i in range(7)),
            ),
            15,
            "seven springs k = 1e-6 .. 1e12 EI/L^3 on one beam",
            ILL,
        ),
        Case(
            "light_masses",
            make_scene(
                "light_masses",
                "clamped",
                "free",
                ((0.4, 1e-4, 1e-6), (0.7, 1e-2, 1e-6), (1.0, 1.0, 1e-6)),
            ),
            10,
            "masses m = 1e-6 mbar*L, tuned into the beam band (10, 100, 1000)",
            ILL,
        ),
        Case(
            "heavy_masses",
            make_scene(
                "heavy_masses",
                "sliding",
                "free",
                ((0.25, 1e3, 1e6), (0.5, 1e8, 1e6), (0.9, 1e10, 1e6)),
            ),
            12,
            "masses m = 1e6 mbar*L (oscillators at 0.03, 10, 100)",
            ILL,
        ),
        Case(
            "masses_span",
            make_scene(
                "masses_span",
                "free",
                "pinned",
                tuple((0.05 + 0.15 * i, 100.0, 10.0 ** (-6 + 2 * i)) for i in range(7)),
            ),
            12,
            "seven masses m = 1e-6 .. 1e6 mbar*L on one beam",
            ILL,
        ),
        Case(
            "ends_clamped_free",
            make_scene(
                "ends_clamped_free", "clamped", "free", ((0.0, 200.0, 0.5), (1.0, 50.0, 0.3))
            ),
            10,
            "attachments at x = 0 (clamped: decoupled oscillator) and x = L (free end)",
            WELL,
        ),
        Case(
            "ends_pinned_sliding",
            make_scene(
                "ends_pinned_sliding",
                "pinned",
                "sliding",
                ((0.0, 500.0, 0.2), (0.0, 30.0, 0.6), (1.0, 70.0, 0.25)),
            ),
            10,
            "attachments at x = 0 (pinned, two) and x = L (sliding end)",
            WELL,
        ),
        Case(
            "ends_sliding_clamped",
            make_scene(
                "ends_sliding_clamped",
                "sliding",
                "clamped",
                ((0.0, 90.0, 0.4), (1.0, 400.0, 0.1)),
            ),
            10,
            "attachments at x = 0 (sliding end) and x = L (clamped: decoupled oscillator)",
            WELL,
        ),
        Case(
            "close_pair",
            make_scene(
                "close_pair",
                "clamped",
                "free",
                ((0.4, 300.0, 0.2), (0.4 + 1e-9, 800.0, 0.1)),
            ),
            10,
            "two different spring-masses 1e-9 L apart",
            ILL,
        ),
        Case(
            "close_pair_identical",
            make_scene(
                "close_pair_identical",
                "pinned",
                "pinned",
                ((0.4, 300.0, 0.2), (0.4 + 1e-9, 300.0, 0.2)),
            ),
            10,
            "two identical spring-masses 1e-9 L apart (a root within ~1e-18 of sqrt(k/m))",
            ILL,
        ),
        Case(
            "same_x_distinct",
            make_scene(
                "same_x_distinct",
                "clamped",
                "free",
                ((0.6, 50.0, 0.2), (0.6, 900.0, 0.1), (0.6, 4000.0, 0.05)),
            ),
            10,
            "three different spring-masses at one x",
            WELL,
        ),
        Case(
            "same_x_identical",
            make_scene(
                "same_x_identical",
                "clamped",
                "free",
                ((0.6, 300.0, 0.2), (0.6, 300.0, 0.2), (0.6, 300.0, 0.2)),
            ),
            10,
            "three identical spring-masses at one x: sqrt(k/m) is a double root",
            ILL,
        ),
        Case(
            "many_1000",
            make_scene("many_1000", "clamped", "free", _many(1000)),
            12,
            "1000 spring-masses (oscillators 20..2000 sqrt(EI/mbar)/L^2), long chain",
            ILL,
            reference="brackets",
            dps=20,
        ),
        Case(
            "scale_small_soft",
            make_scene("scale_small_soft", "clamped", "free", THREE, L=0.01, EI=1.0, mbar=0.02),
            10,
            "L = 0.01 m, EI = 1 N m^2 (omega ~ 1e4..1e7 rad/s)",
            WELL,
        ),
        Case(
            "scale_small_stiff",
            make_scene("scale_small_stiff", "pinned", "free", THREE, L=0.01, EI=1e9, mbar=7.8),
            10,
            "L = 0.01 m, EI = 1e9 N m^2 (omega ~ 1e8..1e11 rad/s)",
            WELL,
        ),
        Case(
            "scale_large_soft",
            make_scene("scale_large_soft", "free", "free", THREE, L=100.0, EI=1.0, mbar=0.5),
            10,
            "L = 100 m, EI = 1 N m^2 (omega ~ 1e-4..1e-1 rad/s)",
            WELL,
        ),
        Case(
            "scale_large_stiff",
            make_scene(
                "scale_large_stiff", "clamped", "clamped", THREE, L=100.0, EI=1e9, mbar=800.0
            ),
            10,
            "L = 100 m, EI = 1e9 N m^2",
            WELL,
        ),
    ]
    return out + _kind_cases()


def _beam(left, right, segments=None) -> dict:
    """A unit beam (L = EI = mbar = 1), or the given ``(length, EI, mbar)`` segments."""
    beam = {"left": left, "right": right}
    if segments:
        beam["segments"] = [{"length": a, "EI": b, "mass_per_length": c} for a, b, c in segments]
    else:
        beam.update(length=1.0, EI=1.0, mass_per_length=1.0)
    return beam


def _kind_cases() -> list[Case]:
    """Extremes of the component library (issue 13), on a unit beam (so the values are
    dimensionless: k in EI/L^3 or EI/L, J in mbar L^3)."""
    chain = {"type": "oscillator_chain", "x": 0.7, "k": [400.0, 150.0], "m": [0.05, 0.02]}
    data = [
        (
            "kind_spring_nearly_a_support",
            _beam("pinned", "free"),
            [{"type": "spring", "x": 0.5, "k": 1e12}, {"type": "spring", "x": 0.8, "k": 1e-6}],
            8,
            "springs to ground k = 1e12 (nearly a support) and 1e-6 EI/L^3",
        ),
        (
            "kind_soft_spring_free_free",
            _beam("free", "free"),
            [{"type": "spring", "x": 0.3, "k": 1e-6}, {"type": "spring", "x": 0.9, "k": 1e12}],
            8,
            "free-free on a 1e-6 and a 1e12 EI/L^3 spring: one frequency 1e-3 of the rest",
        ),
        (
            "kind_rotary_inertia_1e3",
            _beam("clamped", "free"),
            [{"type": "mass", "x": 1.0, "m": 1.0, "J": 1e3}, {"type": "mass", "x": 0.5, "m": 1e-3}],
            8,
            "tip mass with rotary inertia J = 1e3 mbar L^3",
        ),
        (
            "kind_ei_ratio_1e6",
            _beam("clamped", "free", [(0.3, 1.0, 1.0), (0.4, 1e6, 10.0), (0.3, 1.0, 1.0)]),
            [],
            8,
            "three segments, EI ratio 1e6 (a nearly rigid middle)",
        ),
        (
            "kind_hinge_1e-9_from_support",
            _beam("pinned", "pinned"),
            [{"type": "support", "x": 0.5}, {"type": "hinge", "x": 0.5 + 1e-9}],
            8,
            "a free hinge 1e-9 L from an inner support",
        ),
        (
            "kind_twenty_identical_chains",
            _beam("clamped", "free"),
            [dict(chain) for _ in range(20)],
            45,
            "20 identical two-stage chains at one point (roots of multiplicity 19)",
        ),
        (
            "kind_stiff_chain",
            _beam("clamped", "free"),
            [{"type": "oscillator_chain", "x": 0.6, "k": [1e10, 3e9, 1e9], "m": [0.3, 0.2, 0.1]}],
            8,
            "a three-stage chain on springs of 1e9 .. 1e10 EI/L^3 (its masses nearly fixed to"
            " the beam)",
        ),
        (
            "kind_every_kind_stepped",
            _beam("free", "free", [(0.35, 1.0, 1.0), (0.4, 30.0, 4.0), (0.25, 0.05, 0.3)]),
            [
                {"type": "spring_mass", "x": 0.35, "k": 1e9, "m": 1e-4},
                {"type": "mass", "x": 1.0, "m": 1e3, "J": 1e-6},
                {"type": "spring", "x": 0.0, "k": 1e10},
                {"type": "rotational_spring", "x": 0.0, "k": 1e-5},
                {"type": "support", "x": 0.6},
                {"type": "hinge", "x": 0.35, "k": 1e-6},
                {"type": "oscillator_chain", "x": 0.75, "k": [1e6, 1e-3], "m": [1e-2, 1e-6]},
            ],
            10,
            "every kind at extreme values on a free-free stepped beam, several at one point",
        ),
    ]
    return [
        Case(name, {"name": name, "beam": beam, "attachments": atts}, modes, condition, WELL)
        for name, beam, atts, modes, condition in data
    ]


CASES: list[Case] = _cases()
BY_NAME: dict[str, Case] = {c.name: c for c in CASES}


# ----------------------------------------------------------------------- scoring


@dataclass
class Reference:
    """Reference frequencies (mpf, rad/s, ascending, with multiplicity) and their provenance."""

    omega: list
    complete: bool = True
    note: str = ""
    seconds: float = 0.0


@dataclass
class Comparison:
    """One formulation on one case against the reference."""

    case: Case
    formulation: str
    omega: np.ndarray
    reference: Reference
    rel_err: np.ndarray  # per mode (as many as both sides have)
    max_rel_error: float
    zeros_exact: bool  # every reference zero is 0.0 here and vice versa
    n_rigid: int  # zeros in the reference
    converged: bool
    seconds: float
    problems: list[str] = field(default_factory=list)
    #: Largest error over the modes the solver did not flag as untrusted.
    max_trusted_error: float = math.nan

    @property
    def passed(self) -> bool:
        return self.max_rel_error <= self.case.tol and self.zeros_exact and not self.problems

    def first_mode_beyond(self, tol: float) -> int | None:
        """1-based index of the first mode whose error exceeds ``tol`` (None: none does)."""
        bad = np.nonzero(~(self.rel_err <= tol))[0]
        if bad.size:
            return int(bad[0]) + 1
        if len(self.omega) < self.case.modes:
            return len(self.omega) + 1
        return None

    def describe(self) -> str:
        """Multi-line diagnosis (for assertion messages)."""
        lines = [
            f"{self.case.name} [{self.formulation}]: max rel error {self.max_rel_error:.3e} "
            f"(tol {self.case.tol:.0e}), {len(self.omega)} roots, reference "
            f"{len(self.reference.omega)}{'' if self.reference.complete else ' (incomplete)'}",
            *self.problems,
        ]
        if self.reference.note:
            lines.append("reference: " + self.reference.note)
        n = len(self.rel_err)
        for i in range(n):
            if not self.rel_err[i] <= self.case.tol:
                lines.append(
                    f"  mode {i + 1}: got {float(self.omega[i])!r}, reference "
                    f"{mp.nstr(self.reference.omega[i], 20)}, rel error {self.rel_err[i]:.3e}"
                )
        return "\n".join(lines)


def _mode_ranges(modes: list[int]) -> str:
    """``[10, 11, 12, 15]`` -> ``"modes 10-12, 15"``."""
    parts: list[str] = []
    start = prev = modes[0]
    for m in [*modes[1:], None]:
        if m is not None and m == prev + 1:
            prev = m
            continue
        parts.append(f"{start}" if start == prev else f"{start}-{prev}")
        if m is not None:
            start = prev = m
    return ("mode " if len(modes) == 1 else "modes ") + ", ".join(parts)


_REFERENCES: dict[str, Reference] = {}
_SOLUTIONS: dict[tuple[str, str], tuple[mstmm.Solution, float]] = {}
_COMPARISONS: dict[tuple[str, str], Comparison] = {}


def solution(case: Case, formulation: str) -> tuple[mstmm.Solution, float]:
    """``mstmm.solve`` of the case (memoised per process) and its wall time in seconds."""
    key = (case.name, formulation)
    if key not in _SOLUTIONS:
        scene = case.build()
        t = time.perf_counter()
        # the default path (mode shapes on) for the default formulation
        shapes = formulation == "stable"
        sol = mstmm.solve(scene, modes=case.modes, formulation=formulation, shapes=shapes)
        _SOLUTIONS[key] = (sol, time.perf_counter() - t)
    return _SOLUTIONS[key]


def reference(case: Case) -> Reference:
    """The reference frequencies of the case (memoised per process, never written to disk).

    ``frequencies``: ``reference_model.frequencies(scene, modes, dps)``, independent of mstmm.

    ``brackets``: each positive root ``w`` of the stable solution gives a bracket
    ``[w (1 - BRACKET), w (1 + BRACKET)]`` (overlapping brackets merged), in which
    ``reference_model.band`` counts and polishes the true roots; the rigid-body
    zeros come from the end conditions; ``count_below`` at the top of the last
    bracket must equal the number of roots found, which proves that no root below
    it lies outside the brackets. A mismatch marks the reference incomplete (the
    case then fails).
    """
    if case.name in _REFERENCES:
        return _REFERENCES[case.name]
    t = time.perf_counter()
    if case.reference == "frequencies":
        ref = Reference(rm.frequencies(case.scene, case.modes, dps=case.dps))
    elif case.reference == "brackets":
        ref = _bracketed(case)
    else:
        raise ValueError(f"unknown reference method {case.reference!r}")
    ref.seconds = time.perf_counter() - t
    _REFERENCES[case.name] = ref
    return ref


def _bracketed(case: Case) -> Reference:
    sol, _ = solution(case, "stable")
    nrigid = rm.rigid_body_mode_count(case.scene)
    brackets: list[list[float]] = []
    for w in sorted(float(w) for w in sol.omega if w > 0):
        lo, hi = w * (1 - BRACKET), w * (1 + BRACKET)
        if brackets and lo <= brackets[-1][1]:
            brackets[-1][1] = hi
        else:
            brackets.append([lo, hi])
    found = [mpf(0)] * nrigid
    empty = []
    for lo, hi in brackets:
        roots = rm.band(case.scene, lo, hi, dps=case.dps)
        if not roots:
            empty.append(f"[{lo:.17g}, {hi:.17g}]")
        found += roots
    if not brackets:
        return Reference(found, False, "the stable solution has no positive root to polish")
    top = brackets[-1][1]
    below = rm.count_below(case.scene, top, dps=case.dps)
    notes = [
        f"{len(brackets)} brackets of relative half-width {BRACKET:g} around the stable roots; "
        f"count_below({top:.17g}) = {below}, roots found in the brackets "
        f"(+{nrigid} rigid) = {len(found)}"
    ]
    if empty:
        notes.append("no reference root in " + ", ".join(empty))
    complete = below == len(found) and not empty
    if below != len(found):
        notes.append(f"{below - len(found)} root(s) below {top:.17g} lie outside every bracket")
    return Reference(found, complete, "; ".join(notes))


def _rel_errors(got: np.ndarray, ref: list) -> np.ndarray:
    out = np.empty(min(len(got), len(ref)))
    with mp.workdps(40):
        for i in range(len(out)):
            g, r = float(got[i]), ref[i]
            if r == 0:
                out[i] = 0.0 if g == 0.0 else math.inf
            else:
                out[i] = float(abs(mpf(g) - r) / abs(r))
    return out


def compare(case: Case, formulation: str = "stable") -> Comparison:
    """Score one formulation on one case against the reference (memoised per process)."""
    key = (case.name, formulation)
    if key in _COMPARISONS:
        return _COMPARISONS[key]
    ref = reference(case)
    sol, seconds = solution(case, formulation)
    got = np.asarray(sol.omega, dtype=float)
    err = _rel_errors(got, ref.omega)
    problems = []
    missing = False
    if len(got) != case.modes:
        problems.append(f"returned {len(got)} roots, asked for {case.modes}")
        missing = True
    if len(ref.omega) < case.modes or not ref.complete:
        problems.append(f"reference incomplete: {len(ref.omega)} roots ({ref.note})")
        missing = True
    if not np.all(np.diff(got) >= 0):
        problems.append("frequencies not in ascending order")
    n_rigid = sum(1 for w in ref.omega if w == 0)
    zeros_exact = all(
        (ref.omega[i] == 0) == (got[i] == 0.0) for i in range(min(len(got), len(ref.omega)))
    ) and all(got[: min(n_rigid, len(got))] == 0.0)
    if not zeros_exact:
        problems.append(
            f"zero frequencies: reference has {n_rigid}, got "
            f"{got[: n_rigid + 1].tolist()} at the bottom"
        )
    if not np.all(sol.converged):
        bad = [i + 1 for i, ok in enumerate(sol.converged) if not ok]
        problems.append(f"flagged NOT TRUSTED by the solver: {_mode_ranges(bad)}")
    trusted = np.asarray(sol.converged[: err.size], dtype=bool)
    max_trusted = float(err[trusted].max()) if trusted.any() else math.nan
    max_err = math.inf if missing or not err.size else float(err.max())
    comp = Comparison(
        case,
        formulation,
        got,
        ref,
        err,
        max_err,
        zeros_exact,
        n_rigid,
        bool(np.all(sol.converged)),
        seconds,
        problems,
        max_trusted,
    )
    _COMPARISONS[key] = comp
    return comp


def evaluate_case(case: Case, formulation: str = "stable") -> float:
    """Largest relative error over the case's modes (inf when a root is missing)."""
    return compare(case, formulation).max_rel_error


def bracketed_root_errors(case: Case, formulation: str) -> np.ndarray:
    """Error of the characteristic function's own root near each reference root, per mode.

    A diagnostic of the formulation independent of the root search: for each
    positive simple reference root ``r_i``, the kernel's Brent refinement on the
    bracket between the geometric means with its neighbours (``r_i / 2`` and
    ``1.05 r_i`` at the ends), relative to ``r_i``. ``inf`` when the function
    has no sign change over that bracket, ``nan`` for a rigid-body or a multiple
    reference root (no sign change to look for).
    """
    ref = reference(case).omega
    scene = case.build()
    kernel = mstmm.kernel_for(scene)
    p = mstmm.parameter_vector(scene)
    out = np.full(min(case.modes, len(ref)), np.nan)
    values = [float(w) for w in ref]
    distinct = sorted({w for w in values if w > 0})
    for i, r in enumerate(values[: len(out)]):
        if r == 0 or values.count(r) > 1:
            continue
        j = distinct.index(r)
        a = math.sqrt(r * distinct[j - 1]) if j > 0 else r / 2
        b = math.sqrt(r * distinct[j + 1]) if j + 1 < len(distinct) else 1.05 * r
        mant, _ = kernel.evaluate(np.array([a, b]), p, formulation)
        if not mant[0] * mant[1] < 0:
            out[i] = math.inf
            continue
        root, _its, _ok = kernel.refine(a, b, p, formulation)
        with mp.workdps(40):
            out[i] = float(abs(mpf(root) - ref[i]) / ref[i])
    return out

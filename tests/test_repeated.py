"""N identical cells (``repeat = N``) solved by the count and the characteristic function in
O(log N) (``mstmm.repeated``, ``mstmm.numerics.doubling``), through ``mstmm.solve``'s
default path (mode shapes on): the natural frequencies against the mpmath reference model
(tests/reference_model.py: its own assembly of the expanded scene, its own count), the
count at frequencies between them, the clusters of identical resonators against the
reference's count in windows, and the scenes that keep the general search."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import reference_model as ref

import mstmm
from mstmm import compiling, repeated
from mstmm.scene import scene_to_dict

RTOL = 1e-12


@pytest.fixture(autouse=True)
def every_repeated_scene(monkeypatch):
    """These small structures take the path too (by default it starts at
    ``repeated.MIN_CELLS`` cells, where it pays; ``test_the_default_threshold``)."""
    monkeypatch.setattr(repeated, "MIN_CELLS", 2)


EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def repeated_scene(cell_beam: dict, attachments: list[dict], n: int, name: str):
    return mstmm.scene_from_dict(
        {"name": name, "repeat": n, "beam": cell_beam, "attachments": attachments}
    )


def spaced_resonators(n: int, left: str = "clamped", right: str = "free"):
    """The paper's beam as n cells, each with one spring-mass at its middle (half the beam's
    mass in all), their own frequency at beta = 7: a cluster of n roots below it."""
    beam = mstmm.load_scene(mstmm.example_path("wu_chou_1998")).beam
    L, EI, mbar = beam.length, beam.EI, beam.mass_per_length
    w0 = math.sqrt(EI / mbar) / L**2 * 49.0
    m = 0.5 * mbar * L / n
    cell = {"length": L / n, "EI": EI, "mass_per_length": mbar, "left": left, "right": right}
    sm = {"type": "spring_mass", "x": 0.5 * L / n, "k": m * w0**2, "m": m}
    return repeated_scene(cell, [sm], n, f"spaced_{n}"), w0


def metamaterial(n: int):
    scene = mstmm.load_scene(EXAMPLES / "metamaterial.toml")
    d = scene_to_dict(scene.cell) | {"repeat": n, "name": f"metamaterial_{n}"}
    return mstmm.scene_from_dict(d)


def _beam(left, right, **extra):
    return {"length": 0.25, "EI": 2.0, "mass_per_length": 1.5, "left": left, "right": right} | extra


CASES = {
    "metamaterial_free_free": (lambda: metamaterial(12), 18),
    "resonators_clamped_free": (lambda: spaced_resonators(40)[0], 12),
    "resonators_clamped_clamped": (lambda: spaced_resonators(30, "clamped", "clamped")[0], 12),
    "mass_with_J_at_the_joint_pinned_pinned": (
        lambda: repeated_scene(
            _beam("pinned", "pinned"),
            [
                {"type": "mass", "x": 0.0, "m": 0.05, "J": 2e-4},
                {"type": "spring_mass", "x": 0.15, "k": 40.0, "m": 0.04},
            ],
            9,
            "mass_j",
        ),
        14,
    ),
    "chain_sliding_free": (
        lambda: repeated_scene(
            _beam("sliding", "free"),
            [{"type": "oscillator_chain", "x": 0.1, "k": [30.0, 12.0], "m": [0.05, 0.03]}],
            7,
            "chain",
        ),
        14,
    ),
    "timoshenko_in_tension_clamped_pinned": (
        lambda: repeated_scene(
            _beam("clamped", "pinned", kappa_GA=400.0, rho_I=1e-3, axial_force=3.0),
            [{"type": "spring_mass", "x": 0.07, "k": 25.0, "m": 0.05}],
            6,
            "timoshenko",
        ),
        10,
    ),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_roots_against_the_reference(name):
    make, modes = CASES[name]
    scene = make()
    sol = mstmm.solve(scene, modes=modes)  # the default path: mode shapes on
    assert sol.kernel_mode == "repeated cells"
    assert sol.count_checked and sol.converged.all(), sol.warnings
    exact = np.array([float(w) for w in ref.frequencies(scene, modes, dps=30)])
    rigid = exact == 0.0
    assert np.all(sol.omega[rigid] == 0.0)
    err = np.abs(sol.omega[~rigid] - exact[~rigid]) / exact[~rigid]
    assert err.max() <= RTOL, (sol.omega, exact)
    assert len(sol.shapes) == modes


@pytest.mark.parametrize("name", sorted(CASES))
def test_count_between_the_roots_against_the_reference(name):
    scene = CASES[name][0]()
    exact = [float(w) for w in ref.frequencies(scene, 8, dps=30)]
    between = [0.5 * (a + b) for a, b in zip(exact, exact[1:]) if b > a > 0.0]
    chain = repeated.chain_of(scene)
    got = chain.count_below(np.array(between))
    want = [ref.count_below(scene, w, dps=30) for w in between]
    assert list(got) == want


def test_a_cluster_of_spaced_resonators_against_the_reference_count():
    """200 identical resonators at evenly spaced points: 200 roots crowd below their own
    frequency w0 (towards w0 (1 - 1e-12)); those in windows w0 (1 -+ d) against the
    reference's count there, the distinct values and the multiplicities summing to it."""
    scene, w0 = spaced_resonators(200)
    chain = repeated.chain_of(scene)
    modes = int(chain.count_below(np.array([w0 * (1.0 + 1e-6)]))[0]) + 2
    sol = mstmm.solve(scene, modes=modes, shapes=False)
    assert sol.kernel_mode == "repeated cells" and sol.count_checked
    for d in (1e-3, 1e-5, 1e-7):
        lo, hi = w0 * (1.0 - d), w0 * (1.0 + d)
        got = int(np.count_nonzero((sol.omega > lo) & (sol.omega < hi)))
        want = ref.count_below(scene, hi, dps=30) - ref.count_below(scene, lo, dps=30)
        assert got == want, (d, got, want)
    # each root within 1e-13 of a true one, the reference's count says, the last ones too
    # (1e-11 below w0, where the characteristic function's scale moves by e^40 between
    # neighbouring doubles: its values once flushed to zero stopped Brent 1e-12 off)
    below = sol.omega < w0
    top = int(np.count_nonzero(below))
    for i in (0, 1, 2, top - 3, top - 2, top - 1):
        w = sol.omega[i]
        assert ref.count_below(scene, w * (1.0 - 1e-13), dps=40) <= i, (i, w)
        assert ref.count_below(scene, w * (1.0 + 1e-13), dps=40) > i, (i, w)


def test_a_band_gives_the_roots_of_the_lowest_modes_inside_it():
    scene = metamaterial(30)
    low = mstmm.solve(scene, modes=40, shapes=False)
    a, b = low.omega[10], low.omega[30]
    band = mstmm.solve(scene, band=(a, b), shapes=False)
    assert band.kernel_mode == "repeated cells" and band.count_checked
    assert band.omega.size == 21  # the band's edges are roots, inclusive
    assert np.allclose(band.omega, low.omega[10:31], rtol=1e-14, atol=0.0)


def test_scenes_it_does_not_serve_keep_the_general_search():
    """A graded structure (no single cell), a cell with a support (no transfer matrix) and
    the paper's formulation go through the general search, with the same roots where both
    apply."""
    rainbow = mstmm.load_scene(EXAMPLES / "rainbow.toml")
    assert mstmm.solve(rainbow, modes=3, shapes=False).kernel_mode != "repeated cells"
    supported = repeated_scene(
        _beam("free", "free"), [{"type": "support", "x": 0.1}], 5, "supported"
    )
    sol = mstmm.solve(supported, modes=6, shapes=False)  # the cells' search cannot start
    assert sol.kernel_mode != "repeated cells"
    exact = [float(w) for w in ref.frequencies(supported, 6, dps=30)]
    assert np.allclose(sol.omega, exact, rtol=RTOL, atol=0.0)
    scene = metamaterial(10)
    paper = mstmm.solve(scene, modes=6, shapes=False, formulation="paper")
    assert paper.kernel_mode != "repeated cells"


def test_the_last_root_below_a_thousand_resonators_own_frequency():
    """1,000 spaced resonators: the highest root of the cluster lies 8.6e-12 below w0,
    where the characteristic function's scale moves by e^40 between neighbouring doubles
    (its values, once flushed to zero, stopped Brent 1e-12 off, with the count
    satisfied); the reference's count puts a root within 1e-14 of it."""
    scene, w0 = spaced_resonators(1000)
    chain = repeated.chain_of(scene)
    below = int(chain.count_below(np.array([w0 * (1.0 - 1e-15)]))[0])
    sol = mstmm.solve(scene, modes=below, shapes=False)
    w = sol.omega[-1]
    assert sol.kernel_mode == "repeated cells" and sol.count_checked and w < w0
    assert ref.count_below(scene, w * (1.0 - 1e-14), dps=40) == below - 1
    assert ref.count_below(scene, w * (1.0 + 1e-14), dps=40) == below


def test_the_default_threshold(monkeypatch):
    """By default, 200 cells (the metamaterial example) keep the general search, as fast
    there and with nothing more to compile; 1,000 cells take the cells' path."""
    monkeypatch.setattr(repeated, "MIN_CELLS", repeated.DEFAULT_MIN_CELLS)
    assert repeated.MIN_CELLS == 500
    assert mstmm.solve(metamaterial(200), modes=5, shapes=False).kernel_mode != "repeated cells"
    assert mstmm.solve(metamaterial(1000), modes=5, shapes=False).kernel_mode == "repeated cells"


def test_the_driver_compiles_for_the_signature_a_solve_calls_and_runs_as_python(monkeypatch):
    """A machine's first run compiles ``entry_repeated_search`` in a helper for
    ``entries.SIGNATURES`` (``mstmm.compiling``): a solve calls it with exactly that; while
    the helper compiles, its Python copy runs around the cell kernel's compiled functions
    and gives the reference's roots too."""
    from mstmm.numerics import entries

    scene = metamaterial(12)
    sol = mstmm.solve(scene, modes=10, shapes=False)
    assert sol.kernel_mode == "repeated cells"
    assert entries.entry_repeated_search.signatures == [entries.SIGNATURES["repeated_search"]]
    monkeypatch.setattr(compiling, "python_instead", lambda name, estimate, pending=False: True)
    scene = metamaterial(13)
    sol = mstmm.solve(scene, modes=10, shapes=False)
    exact = np.array([float(w) for w in ref.frequencies(scene, 10, dps=30)])
    assert sol.kernel_mode == "repeated cells" and sol.count_checked
    elastic = exact > 0.0
    assert np.all(sol.omega[~elastic] == 0.0)
    assert np.max(np.abs(sol.omega[elastic] - exact[elastic]) / exact[elastic]) <= RTOL


#: Cells found by a random comparison of this path with the general search (each solve of
#: 40 modes with both, on 60 random repeated scenes).
BAND_EDGE_CLUSTER = (  # spring-masses at the joints, clamped-clamped: 7 roots 5e-6 apart
    {"length": 0.4195996524381598, "EI": 4.371006677597008,
     "mass_per_length": 2.718651221412076, "left": "clamped", "right": "clamped"},
    [{"type": "spring_mass", "x": 0.0, "k": 907.0537217223642, "m": 0.22529846179032412}],
    33,
)  # fmt: skip
GROUNDED = (  # a grounded spring in every cell: waves grow by e^2.4 a cell below cut-on
    {"length": 0.5848312242364058, "EI": 3.719113849386831,
     "mass_per_length": 2.309062619466498, "left": "sliding", "right": "sliding"},
    [{"type": "spring_mass", "x": 0.00048183554710160025, "k": 12.618071870014498,
      "m": 0.08469990483312193},
     {"type": "rotational_spring", "x": 0.10822703924036331, "k": 54.6003987628558},
     {"type": "spring", "x": 0.169133048440601, "k": 78.81143062033762},
     {"type": "mass", "x": 0.28162005498195586, "m": 0.193649143472023,
      "J": 0.000623697980132001}],
    70,
)  # fmt: skip
LONG_CELLS = (  # 8 cells in tension: lam h = 8 across a cell at the 24th mode, 14 at the 40th
    {"length": 0.15894991317812304, "EI": 4.388353638999503,
     "mass_per_length": 2.4890512689121684, "axial_force": 7.487646522429452,
     "left": "clamped", "right": "clamped"},
    [{"type": "rotational_spring", "x": 0.08635006687916792, "k": 50.6949844928657},
     {"type": "mass", "x": 0.09133974882080835, "m": 0.27537088390121217,
      "J": 0.00048427545940356743}],
    8,
)  # fmt: skip


@pytest.mark.parametrize(
    "name, cells, modes, path",
    [
        ("band_edge_cluster", BAND_EDGE_CLUSTER, 40, "repeated cells"),
        ("grounded", GROUNDED, 8, "repeated cells"),
        ("long_cells", LONG_CELLS, 24, None),
    ],
)
def test_roots_where_the_count_or_the_function_loses_digits(name, cells, modes, path):
    """Against the mpmath reference to 1e-12, through the default path (mode shapes on):

    * a cluster at a band edge of the cells, where the characteristic function lost six
      digits (Brent put a root 9e-11 off; the count is exact there): a Brent root is kept
      only where the count steps beside it, else the count's bisection;
    * cells whose waves grow by e^2.4 each, where the count flips within 3e-10 of a root
      and the function does not (the count's bisection put it 4e-10 off): the function's
      root, clean on both sides, is kept;
    * cells across which a wave grows by e^14 at the 40th mode (its transfer keeps eps
      e^14 of its small terms: 1.7e-11 off): above e^6 (the 24th mode: e^8) the general
      search runs (``repeated.MAX_GROWTH``)."""
    beam, atts, n = cells
    scene = repeated_scene(beam, atts, n, name)
    sol = mstmm.solve(scene, modes=modes)
    assert sol.kernel_mode == path if path else sol.kernel_mode != "repeated cells"
    assert sol.count_checked and sol.converged.all() and not sol.warnings, sol.warnings
    exact = np.array([float(w) for w in ref.frequencies(scene, modes, dps=30)])
    assert np.max(np.abs(sol.omega - exact) / exact) < RTOL

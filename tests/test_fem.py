"""Checks of the finite-element model (tests/reference_fem.py) against the exact references,
closed forms for bare beams, and its own properties (solvers agree, inertia counts,
convergence rate, mesh, stiffness factor)."""

from __future__ import annotations

import itertools
import json
import sys
import tomllib
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

import reference_model as ref  # noqa: E402
from reference_fem import (  # noqa: E402
    _matrices,
    _model,
    _nodes,
    assemble,
    count_below,
    frequencies,
    mesh,
    richardson,
)

DATA = Path(__file__).resolve().parent / "data"
ENDS = ("clamped", "pinned", "free", "sliding")
SCENES = ("wu_chou_1998", "bare_cantilever")
RIGID = {  # rigid-body modes Y = a + b x allowed by the two end conditions
    ("free", "free"): 2,
    ("pinned", "free"): 1,
    ("free", "pinned"): 1,
    ("sliding", "free"): 1,
    ("free", "sliding"): 1,
    ("sliding", "sliding"): 1,
}


def load(name: str) -> dict:
    with open(DATA / f"{name}.toml", "rb") as fh:
        return tomllib.load(fh)


REFERENCE = {
    name: np.array([float(w) for w in entry["omega"]])
    for name, entry in json.loads((DATA / "reference.json").read_text()).items()
}


def bare(left: str, right: str, **beam) -> dict:
    values = {"length": 1.0, "EI": 1.0, "mass_per_length": 1.0, "left": left, "right": right}
    return {"beam": values | beam}


def rel(w, ref) -> np.ndarray:
    return np.abs(np.asarray(w) / np.asarray(ref) - 1.0)


# --- the exact references -------------------------------------------------------------


@pytest.mark.parametrize("name", SCENES)
@pytest.mark.parametrize("solver", ["dense", "sparse"])
def test_reference_64_elements(name, solver):
    ref = REFERENCE[name][:5]
    w = frequencies(load(name), 5, 64, solver)
    # h^4 discretization error: 1.65e-6 for mode 5 of the bare cantilever (its 5th
    # beam mode), 2.0e-8 for wu_chou (whose 5th mode is the 2nd beam mode)
    assert np.all(rel(w[:4], ref[:4]) < 1e-6)
    assert rel(w[4], ref[4]) < (2e-6 if name == "bare_cantilever" else 1e-7)
    assert np.all(w >= ref)  # FE frequencies are upper bounds
    assert np.all(rel(richardson(load(name), 5, 64, solver), ref) < 1e-9)


@pytest.mark.parametrize("name", SCENES)
def test_reference_all_ten_modes_fine_mesh(name):
    """Round-off does not limit the default solvers: Richardson(256) is near eps."""
    ref = REFERENCE[name]
    assert np.all(rel(richardson(load(name), 10, 256, "sparse"), ref) < 1e-11)
    # 2048 elements: the plain error is still the h^4 discretization error, not noise
    w = frequencies(load(name), 10, 2048, "sparse")
    assert np.all(rel(w, ref) < 5e-11)
    assert np.all(w >= ref * (1 - 1e-14))


def test_convergence_rate_h4():
    """Error ratio of 16 and 32 elements ~ 2^4 (frequencies), Richardson ~ 2^6."""
    scene, ref = load("bare_cantilever"), REFERENCE["bare_cantilever"][:5]
    ratio = rel(frequencies(scene, 5, 16), ref) / rel(frequencies(scene, 5, 32), ref)
    assert 15.0 < ratio[0] < 17.0
    assert np.all((ratio > 14.0) & (ratio < 17.0))
    ratio = rel(richardson(scene, 5, 16), ref) / rel(richardson(scene, 5, 32), ref)
    assert np.all((ratio > 55.0) & (ratio < 70.0))


def test_textbook_eigh_is_round_off_limited():
    """Documents why the default solvers are shift-inverted: eigh(K, M) loses digits."""
    scene, ref = load("wu_chou_1998"), REFERENCE["wu_chou_1998"][:5]
    textbook = rel(frequencies(scene, 5, 128, "eigh"), ref).max()
    assert textbook > 1e-6  # measured 7e-5 (the discretization error is 1.3e-9)
    assert rel(frequencies(scene, 5, 128, "dense"), ref).max() < 2e-9


# --- closed forms ------------------------------------------------------------------------


def test_pinned_pinned_closed_form():
    exact = (np.arange(1, 6) * np.pi) ** 2
    assert np.all(rel(frequencies(bare("pinned", "pinned"), 2, 128), exact[:2]) < 1e-8)
    assert np.all(rel(richardson(bare("pinned", "pinned"), 5, 128, "sparse"), exact) < 1e-10)


def test_clamped_free_closed_form():
    exact = 1.8751040687119611**2
    assert rel(frequencies(bare("clamped", "free"), 1, 128, "sparse")[0], exact) < 1e-8


def test_free_free_closed_form():
    w = frequencies(bare("free", "free"), 3, 128)
    assert w[0] == 0.0 and w[1] == 0.0
    assert rel(w[2], 4.730040744862704**2) < 1e-8
    w = frequencies(bare("free", "free"), 3, 128, "sparse")
    assert w[0] == 0.0 and w[1] == 0.0
    assert rel(w[2], 4.730040744862704**2) < 1e-8


def test_units_scale():
    """omega scales as sqrt(EI / (mbar L^4))."""
    w1 = frequencies(bare("clamped", "pinned"), 4, 32)
    w2 = frequencies(bare("clamped", "pinned", length=2.0, EI=3.0, mass_per_length=5.0), 4, 32)
    assert np.allclose(w2, w1 * np.sqrt(3.0 / (5.0 * 16.0)), rtol=1e-12)


@pytest.mark.parametrize("left,right", list(itertools.product(ENDS, ENDS)))
def test_rigid_body_zeros_all_ends(left, right):
    scene = bare(left, right, EI=63476.0, mass_per_length=15.4)
    scene["attachments"] = [{"type": "spring_mass", "x": 0.3, "k": 2e5, "m": 3.0}]
    nrigid = RIGID.get((left, right), 0)
    for solver in ("dense", "sparse"):
        w = frequencies(scene, 4, 32, solver)
        assert np.count_nonzero(w == 0.0) == nrigid
        assert np.all(w[nrigid:] > 1.0)


# --- solvers and counts agree ---------------------------------------------------------------


def test_dense_sparse_agree_wu_chou():
    scene = load("wu_chou_1998")
    dense = frequencies(scene, 10, 64, "dense")
    assert np.all(rel(frequencies(scene, 10, 64, "sparse"), dense) < 1e-10)
    assert np.all(rel(frequencies(scene, 10, 64, "svd"), dense) < 1e-9)


def random_scene(rng, left, right) -> dict:
    xs = [0.0, 1.3, *rng.uniform(0.0, 1.3, 2)]
    xs.append(xs[-1])  # two attachments at the same point
    attachments = [
        {"type": "spring_mass", "x": float(x), "k": float(rng.uniform(1, 50)), "m": 0.2} for x in xs
    ]
    return {"beam": bare(left, right, length=1.3, EI=2.0)["beam"], "attachments": attachments}


@pytest.mark.parametrize(
    "left,right", [("free", "free"), ("clamped", "pinned"), ("sliding", "free")]
)
def test_random_scenes_solvers_and_counts(left, right):
    scene = random_scene(np.random.default_rng(len(left) + 7 * len(right)), left, right)
    w = frequencies(scene, 12, 40, "dense")
    nz = w > 0
    assert np.all(rel(frequencies(scene, 12, 40, "sparse")[nz], w[nz]) < 1e-10)
    assert np.array_equal(frequencies(scene, 12, 40, "sparse") == 0, w == 0)
    assert count_below(scene, 0.5 * w[w > 0][0], 40) == np.count_nonzero(w == 0)
    for i in range(11):
        if w[i + 1] > w[i] * (1 + 1e-6):
            assert count_below(scene, 0.5 * (w[i] + w[i + 1]), 40) == i + 1


def test_count_below_reference_scene_is_lower_bound():
    """FE eigenvalues bound the exact ones from above: FE count <= exact count."""
    scene, ref = load("wu_chou_1998"), REFERENCE["wu_chou_1998"]
    w = frequencies(scene, 10, 8)
    for omega in np.concatenate([ref, w]) * (1 + 1e-9):
        fe = count_below(scene, omega, 8)
        assert fe == np.count_nonzero(w < omega)
        if omega < ref[-1]:
            assert fe <= np.count_nonzero(ref < omega)
    assert count_below(scene, 0.0, 8) == 0
    assert count_below(scene, 1e-3, 8) == 0


def test_repeated_oscillators():
    """Identical oscillators at one point: their differences move alone at sqrt(k/m)."""
    k, m = 4.0e4, 2.0
    scene = bare("clamped", "free", EI=63476.0, mass_per_length=15.4)
    scene["attachments"] = [{"type": "spring_mass", "x": 0.5, "k": k, "m": m}] * 3
    for solver in ("dense", "sparse"):
        w = frequencies(scene, 6, 32, solver)
        assert np.count_nonzero(rel(w, np.sqrt(k / m)) < 1e-12) == 2


def test_attachment_at_clamped_end_is_an_oscillator():
    k, m = 3.0e5, 2.0
    scene = load("bare_cantilever")
    scene["attachments"] = [{"type": "spring_mass", "x": 0.0, "k": k, "m": m}]
    w = frequencies(scene, 6, 32)
    base = frequencies(load("bare_cantilever"), 5, 32)
    assert np.allclose(np.sort(np.append(base, np.sqrt(k / m))), w, rtol=1e-13)


def test_scene_object_duck_typing():
    data = load("wu_chou_1998")
    obj = SimpleNamespace(
        beam=SimpleNamespace(**data["beam"]),
        attachments=[SimpleNamespace(x=a["x"], k=a["k"], m=a["m"]) for a in data["attachments"]],
    )
    assert np.array_equal(frequencies(obj, 5, 16), frequencies(data, 5, 16))
    mstmm = pytest.importorskip("mstmm")
    scene = mstmm.load_scene(DATA / "wu_chou_1998.toml")
    assert np.array_equal(frequencies(scene, 5, 16), frequencies(data, 5, 16))


def test_bad_input():
    with pytest.raises(ValueError):
        frequencies(bare("clamped", "glued"), 1, 8)
    with pytest.raises(ValueError):
        frequencies(bare("clamped", "free"), 1, 8, solver="magic")
    with pytest.raises(ValueError):
        frequencies(bare("clamped", "free"), 100, 8)
    scene = bare("clamped", "free")
    scene["attachments"] = [{"type": "spring_mass", "x": 2.0, "k": 1.0, "m": 1.0}]
    with pytest.raises(ValueError):
        frequencies(scene, 1, 8)


def test_too_fine_mesh_raises():
    with pytest.raises(FloatingPointError):
        frequencies(load("bare_cantilever"), 1, 16384, "sparse")


# --- mesh and matrices ---------------------------------------------------------------------


def test_mesh_nodes_at_attachments():
    scene = bare("clamped", "free")
    h = 1.0 / 10
    xs = [0.0, 0.25, 0.3 + 1e-5 * h, 0.7 - 2e-4 * h, 0.55, 0.55 + 1e-4 * h, 1.0]
    scene["attachments"] = [{"type": "spring_mass", "x": x, "k": 1.0, "m": 1.0} for x in xs]
    nodes = mesh(scene, 10)
    assert nodes[0] == 0.0 and nodes[-1] == 1.0 and np.all(np.diff(nodes) > 0)
    assert set(xs) <= set(nodes)
    # snapped: 0.3 + eps and 0.7 - eps replace uniform nodes; 0.25, 0.55 split elements
    assert len(nodes) == 11 + 3
    short = np.diff(nodes) < 1e-3 * h
    assert np.count_nonzero(short) == 1  # only between the two attachments near 0.55


@pytest.mark.parametrize("left,right", list(itertools.product(ENDS, ENDS)))
def test_matrices(left, right):
    scene = random_scene(np.random.default_rng(3), left, right)
    K, M = assemble(scene, 12)
    removed = {"clamped": 2, "pinned": 1, "sliding": 1, "free": 0}
    ndof = 2 * len(mesh(scene, 12)) + 5 - removed[left] - removed[right]
    assert K.shape == M.shape == (ndof, ndof)
    assert abs(K - K.T).max() == 0.0 and abs(M - M.T).max() == 0.0
    assert np.linalg.eigvalsh(M.toarray()).min() > 0
    model = _model(scene)
    Ks, Ms, G = _matrices(model, _nodes(model, 12))
    assert abs(Ks - K).max() == 0.0 and abs(Ms - M).max() == 0.0
    assert abs(G.T @ G - K).max() <= 1e-14 * abs(K).max()
    if left in ("free", "sliding") and right in ("free", "sliding"):
        v = translation(scene, 12)
        assert np.abs(K @ v).max() <= 1e-14 * abs(K).max()
        total = 1.3 * scene["beam"]["mass_per_length"] + sum(a["m"] for a in scene["attachments"])
        assert v @ M @ v == pytest.approx(total, rel=1e-14)


def translation(scene: dict, n_elements: int) -> np.ndarray:
    """The DOF vector of a unit rigid translation (Y = u = 1, theta = 0), free/sliding ends."""
    nodes = mesh(scene, n_elements)
    at = [int(np.searchsorted(nodes, a["x"])) for a in scene["attachments"]]
    v = []
    for i in range(nodes.size):
        theta = [] if (i == 0 and scene["beam"]["left"] == "sliding") else [0.0]
        if i == nodes.size - 1 and scene["beam"]["right"] == "sliding":
            theta = []
        v += [1.0, *theta] + [1.0] * at.count(i)
    return np.array(v)


# --- every attachment kind and stepped beams, against the reference model -----------------


def _at(kind: str, x: float, **values) -> dict:
    return {"type": kind, "x": x, **values}


def stepped(left: str, right: str, segments: list, attachments: list) -> dict:
    """Scene of a stepped beam, segments given as (length, EI, mass_per_length)."""
    keys = ("length", "EI", "mass_per_length")
    rows = [dict(zip(keys, s, strict=True)) for s in segments]
    beam = {"left": left, "right": right, "segments": rows}
    return {"beam": beam, "attachments": attachments}


KIND_SCENES = {
    "mass": bare("clamped", "free")
    | {"attachments": [_at("mass", 1.0, m=1.0, J=0.02), _at("mass", 0.4, m=0.3)]},
    "spring": bare("pinned", "free") | {"attachments": [_at("spring", 0.625, k=500.0)]},
    "restrained_ends": bare("free", "free")
    | {
        "attachments": [
            _at("spring", 0.0, k=2e3),
            _at("rotational_spring", 0.0, k=50.0),
            _at("rotational_spring", 0.7, k=5.0),
            _at("spring", 1.0, k=30.0),
        ]
    },
    "two_span": bare("pinned", "free") | {"attachments": [_at("support", 0.4)]},
    "free_free_support": bare("free", "free") | {"attachments": [_at("support", 0.3)]},
    "hinge_spring": bare("clamped", "clamped") | {"attachments": [_at("hinge", 0.3, k=5.0)]},
    "free_free_hinge": bare("free", "free") | {"attachments": [_at("hinge", 0.375)]},
    "pinned_hinge": bare("pinned", "pinned") | {"attachments": [_at("hinge", 0.5)]},
    "chain": bare("clamped", "free")
    | {
        "attachments": [
            _at("oscillator_chain", 0.8, k=[300.0, 200.0, 100.0], m=[0.1, 0.1, 0.05]),
            _at("oscillator_chain", 0.5, k=[150.0, 40.0], m=[0.05, 0.2]),
            _at("support", 0.5),
        ]
    },
    "stepped": stepped(
        "clamped",
        "free",
        [(0.25, 3.0, 2.0), (0.5, 1.0, 1.0), (0.25, 0.4, 0.6)],
        [_at("spring_mass", 0.25, k=400.0, m=0.2), _at("mass", 1.0, m=0.3, J=0.01)],
    ),
    "mixed_free": stepped(
        "free",
        "sliding",
        [(0.5, 2.0, 1.5), (0.75, 1.0, 1.0)],
        [
            _at("hinge", 0.5, k=3.0),
            _at("spring_mass", 0.5, k=250.0, m=0.1),
            _at("mass", 0.25, m=0.2, J=0.003),
            _at("oscillator_chain", 1.25, k=[100.0, 80.0], m=[0.1, 0.1]),
            _at("spring", 0.875, k=20.0),
        ],
    ),
}


@pytest.mark.parametrize("name", sorted(KIND_SCENES))
def test_every_kind_against_the_reference_model(name):
    """Against the exact reference, 6 modes: Richardson(64 -> 128 elements) within 2e-9,
    its error falling as h^6 from 32 elements (the plain one as h^4), the rigid-body zeros
    exactly where the reference has them, FE frequencies upper bounds."""
    scene = KIND_SCENES[name]
    exact = np.array([float(w) for w in ref.frequencies(scene, 6, dps=20)])
    nrigid = ref.rigid_body_mode_count(scene)
    assert np.count_nonzero(exact == 0) == nrigid
    fe = {n: frequencies(scene, 6, n) for n in (32, 64)}
    rich = {n: richardson(scene, 6, n) for n in (32, 64)}
    for w in (*fe.values(), *rich.values()):
        assert np.array_equal(w == 0, exact == 0)
    elastic = exact > 0
    err = {n: rel(w[elastic], exact[elastic]) for n, w in fe.items()}
    err_r = {n: rel(w[elastic], exact[elastic]) for n, w in rich.items()}
    assert np.all(fe[64][elastic] >= exact[elastic] * (1 - 1e-13))
    assert np.all(err[64] < 1e-5)
    assert np.all(err_r[64] < 2e-9), err_r[64]
    assert 14 < err[32][-1] / err[64][-1] < 17  # h^4
    assert 50 < err_r[32][-1] / err_r[64][-1] < 75  # h^6 after Richardson
    sparse = frequencies(scene, 6, 64, "sparse")
    assert np.all(rel(sparse[elastic], fe[64][elastic]) < 1e-10)


CARRIED = ("oscillator_chain", "mass")


def test_kinds_mesh_and_dofs():
    """A node at every attachment and segment boundary; a hinge adds a rotation, a chain
    its masses, a support removes Y; K = G^T G; a rigid translation of a free-free stepped
    beam with a chain and a point mass has zero stiffness and the total mass."""
    scene = KIND_SCENES["mixed_free"]
    nodes = mesh(scene, 8)
    assert {0.25, 0.5, 0.875, 1.25} <= set(nodes)
    K, M = assemble(scene, 8)
    nn = nodes.size
    assert K.shape == (2 * nn + 1 + 1 + 2 - 1,) * 2  # hinge, spring-mass, chain; sliding end
    model = _model(scene)
    Ks, Ms, G = _matrices(model, _nodes(model, 8))
    assert abs(G.T @ G - Ks).max() <= 1e-14 * abs(Ks).max()
    support = KIND_SCENES["chain"]
    assert assemble(support, 8)[0].shape[0] == 2 * mesh(support, 8).size + 5 - 2 - 1
    free = {
        "beam": dict(scene["beam"], right="free"),
        "attachments": [
            a for a in scene["attachments"] if a["type"] in ("oscillator_chain", "mass")
        ],
    }
    K, M = assemble(free, 8)
    nodes = mesh(free, 8)
    v = np.zeros(K.shape[0])
    i = 0
    for x in nodes:  # Y = 1, theta = 0, then the node's hanging masses = 1
        v[i] = 1.0
        i += 2
        hung = sum(len(a["m"]) for a in free["attachments"] if a["x"] == x and "k" in a)
        v[i : i + hung] = 1.0
        i += hung
    assert np.abs(K @ v).max() <= 1e-12 * abs(K).max()
    total = 0.5 * 1.5 + 0.75 * 1.0 + 0.2 + 0.2
    assert v @ M @ v == pytest.approx(total, rel=1e-14)


@pytest.mark.parametrize(
    "att",
    [
        {"type": "hinge", "x": 0.0},
        {"type": "glue", "x": 0.5},
        {"type": "spring", "x": 0.5, "k": 0.0},
        {"type": "oscillator_chain", "x": 0.5, "k": [1.0, 2.0], "m": [1.0]},
        {"type": "mass", "x": 0.5, "m": -1.0},
    ],
)
def test_bad_attachments(att):
    with pytest.raises(ValueError):
        frequencies(bare("clamped", "free") | {"attachments": [att]}, 1, 8)
    hinge = [{"type": "hinge", "x": 0.5}, {"type": "rotational_spring", "x": 0.5, "k": 1.0}]
    with pytest.raises(ValueError, match="ambiguous"):
        frequencies(bare("clamped", "free") | {"attachments": hinge}, 1, 8)

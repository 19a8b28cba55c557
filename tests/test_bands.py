"""mstmm.bands (issue 23): Bloch dispersion of a periodic cell and its certified band
edges, against closed forms: a bare beam's k^4 = mbar omega^2 / EI; Mead's periodically
supported beam (pass bands from the pinned-pinned to the clamped-clamped bay
frequencies); Sugino's asymptotic locally resonant gap [omega_t, omega_t sqrt(1 + mu)];
the attenuation of a finite beam of N cells against the cell's Im k; and the command."""

import json
import math
import subprocess
import sys

import mpmath
import numpy as np
import pytest

import mstmm
from mstmm.bands import bands

EI, MBAR, L = 2.0, 3.0, 0.7
C = math.sqrt(EI / MBAR)
W_BRAGG = (math.pi / L) ** 2 * C  # the bare beam's first Bragg frequency (k L = pi)


def cell(*attachments, left="free", right="free", **beam):
    b = {"length": L, "EI": EI, "mass_per_length": MBAR, "left": left, "right": right}
    return mstmm.scene_from_dict({"beam": b | beam, "attachments": list(attachments)})


def resonator(x, mu, omega_t):
    m = mu * MBAR * L
    return {"type": "spring_mass", "x": x, "k": m * omega_t**2, "m": m}


def test_bare_beam_dispersion_and_double_edges():
    """k^4 = mbar omega^2 / EI: mu = 2 cos kL and 2 cosh kL; the edges at k L = n pi are
    double (two branches meet, no gap opens) and alternate periodic / antiperiodic."""
    hi = (4.5 * math.pi / L) ** 2 * C
    b = bands(cell(), band=(0.0, hi), points=400)
    k = (MBAR * b.omega**2 / EI) ** 0.25
    prop = np.cos(k * L)
    assert np.max(np.abs(b.mu[:, 1].real / 2 - prop)) < 1e-12
    grow = b.mu[:, 0].real / (2 * np.cosh(k * L))
    assert np.all(np.abs(grow - 1.0) <= 1e-13)  # the evanescent pair, to round-off
    at_edge = np.isin(b.omega, [e.omega for e in b.edges])  # the curves reach each edge
    assert np.all(b.propagating[~at_edge] == 1)
    assert b.gaps == ()
    expected = [(n * math.pi / L) ** 2 * C for n in range(1, 5)]
    inside = [e for e in b.edges if e.omega > 0.0]
    assert [e.multiplicity for e in inside] == [2, 2, 2, 2]
    assert [e.kind for e in inside] == ["antiperiodic", "periodic"] * 2
    for e, w in zip(inside, expected):
        assert abs(e.omega - w) <= 1e-13 * w
    assert b.count_checked
    # the rigid translation of the free ring at omega = 0
    assert b.edges[0].omega == 0.0 and b.edges[0].kind == "periodic"


def test_strongly_evanescent_waves_keep_their_decay():
    """A long bare cell, lam L up to 40: the evanescent pair's Im k L = lam L to round-off
    (it came out 9 % off at lam L = 40, P's leading coefficient det X0 ~ exp(-lam L) taken
    from an LU of the O(1) basis); a supported cell has one pair, not a spurious second
    one with Im k L = 37 from det X0 = 1e-16 (it is exactly 0)."""
    lam_L = np.linspace(1.0, 40.0, 79)
    omegas = (lam_L / L) ** 2 * C
    b = bands(cell(), omegas=omegas, edges=False)
    assert np.max(np.abs(b.k[:, 0].imag * L / lam_L - 1.0)) < 1e-13
    assert np.max(np.abs(b.k[:, 0].real)) == 0.0
    assert np.max(np.abs(np.cos(b.k[:, 1].real * L) - np.cos(lam_L))) < 1e-13
    assert not b.notes
    s = bands(cell({"type": "support", "x": 0.3}), omegas=omegas, edges=False)
    assert np.all(np.isinf(s.mu[:, 0])) and np.all(np.isinf(s.k[:, 0].imag))
    assert np.all(np.isfinite(s.k[:, 1]))
    assert np.all((s.k[:, 1].real >= 0.0) & (s.k[:, 1].real * L <= math.pi))


@pytest.mark.parametrize("kw", [1e2, 1e5, 1e7])
def test_both_pairs_evanescent_are_said_when_inexact(kw):
    """Below a Winkler foundation's cut-on every k of the bare beam is complex, k^4 =
    (mbar omega^2 - k_w) / EI: mu = 2 cos k L against the closed form, to round-off times
    exp(Im k L), the error the note states where it passes 1e-8."""
    w = 0.3 * math.sqrt(kw / MBAR)
    b = bands(cell(foundation_k=kw), omegas=np.array([w]), edges=False)
    k4 = complex((MBAR * w**2 - kw) / EI)
    ks = [k4**0.25 * 1j**n for n in range(4)]
    exact = [2 * np.cos(k * L) for k in ks[:2]]  # -k gives the same mu
    got = b.mu[0]
    err = max(min(abs(g - e) / abs(e) for e in exact) for g in got)
    decay = max(k.imag for k in ks) * L
    bound = 4.0 * np.finfo(float).eps * math.exp(decay)
    assert err <= max(bound, 1e-14), (err, bound)
    if bound > 1e-8:
        (note,) = b.notes
        said = float(note.split("accurate to about ")[1].split(" ")[0])
        assert err <= said
    else:
        assert not b.notes


def _clamped_bay(n: int) -> float:
    """n-th root of cos x cosh x = 1 (mpmath, 30 digits)."""
    mpmath.mp.dps = 30
    x = mpmath.findroot(lambda t: mpmath.cos(t) * mpmath.cosh(t) - 1, (n + 0.5) * mpmath.pi)
    return float(x)


@pytest.mark.parametrize("x_support", [0.0, 0.2, 0.5])
def test_mead_periodically_supported_beam(x_support):
    """Mead (1970): the pass bands of a beam on equally spaced simple supports run from
    each pinned-pinned bay frequency (k L = n pi) to the next clamped-clamped one
    (cos kL cosh kL = 1); below the first, a stop band from 0. Wherever the support
    sits in the cell (the ring is cut elsewhere)."""
    hi = (3.2 * math.pi / L) ** 2 * C
    b = bands(cell({"type": "support", "x": x_support}), band=(0.0, hi), points=200)
    pinned = [(n * math.pi / L) ** 2 * C for n in (1, 2, 3)]
    clamped = [(_clamped_bay(n) / L) ** 2 * C for n in (1, 2)]
    expected = sorted(pinned + clamped)
    got = [e.omega for e in b.edges]
    assert [e.multiplicity for e in b.edges] == [1] * 5
    assert np.allclose(got, expected, rtol=2e-14, atol=0.0), (got, expected)
    gaps = [(0.0, pinned[0]), (clamped[0], pinned[1]), (clamped[1], pinned[2])]
    assert len(b.gaps) == 3
    for (a, c), (u, v) in zip(b.gaps, gaps):
        assert abs(a - u) <= 2e-14 * max(v, 1.0) and abs(c - v) <= 2e-14 * v
    assert b.count_checked
    assert np.all(b.propagating <= 1)


@pytest.mark.parametrize("mu, frac", [(0.01, 0.05), (0.1, 0.05), (0.05, 0.3), (0.2, 0.02)])
def test_sugino_asymptotic_gap(mu, frac):
    """Sugino et al. (2016): many light resonators per wavelength open a gap
    [omega_t, omega_t sqrt(1 + mu)], mu the resonator mass over the beam's per cell. The
    exact edges approach it as the cell shrinks against the wavelength: the gap's lower
    edge sits below omega_t by about mu (omega_t / omega_Bragg)^2 relative."""
    wt = frac * W_BRAGG
    b = bands(cell(resonator(0.3, mu, wt)), band=(0.5 * wt, 2.0 * wt), points=100)
    assert len(b.gaps) == 1 and b.count_checked
    lo, hi = b.gaps[0]
    assert [e.kind for e in b.edges if e.kind != "coalescence"] == ["antiperiodic", "periodic"]
    # the complex pair inside the gap turns real just below its top edge, both mu inside
    # (-2, 2): a narrow band of two propagating pairs (mpmath: test_bands_reference), so
    # the gap ends there, at a proved coalescence edge
    meet = [e for e in b.edges if e.kind == "coalescence"]
    assert all(e.certified for e in meet) and hi <= b.edges[-1].omega
    assert all(e.omega == hi for e in meet)
    assert abs(lo / wt - 1.0) <= 2.0 * mu * frac**2
    assert abs(hi / (wt * math.sqrt(1.0 + mu)) - 1.0) <= 2.0 * mu * frac**2
    # inside the gap both pairs decay; at its middle the slower is attenuated
    mid = bands(cell(resonator(0.3, mu, wt)), omegas=[0.5 * (lo + hi)], edges=False)
    assert mid.propagating[0] == 0 and mid.attenuation[0] > 0.0


def test_attenuation_of_a_finite_beam_matches_im_k():
    """A free-free beam of 60 cells driven at x = 0 at a frequency in the gap where both
    pairs are evanescent with real mu (near the gap's lower edge; deeper in, the two
    meet and turn complex, equally attenuated, and the response beats): the displacement
    at the cell boundaries decays by exp(-Im k L) per cell, the slower pair's (the
    faster one has died out after ten cells, exp(-10 (2.4 - 0.75)) ~ 1e-7, and the far
    end's reflection is exp(-2 * 35 * 0.75) small)."""
    mu, frac = 0.1, 0.3
    wt = frac * W_BRAGG
    one = cell(resonator(0.35, mu, wt))
    b = bands(one, band=(0.5 * wt, 2.0 * wt), points=50)
    lo, hi = b.gaps[0]
    w = lo + 0.09 * (hi - lo)
    at = bands(one, omegas=[w], edges=False)
    slow, fast = sorted(at.k[0].imag * L)
    assert abs(at.mu[0].imag).max() == 0.0 and fast - slow > 1.5
    n = 60
    atts = [resonator(0.35 + j * L, mu, wt) for j in range(n)]
    beam = {"length": n * L, "EI": EI, "mass_per_length": MBAR, "left": "free", "right": "free"}
    big = mstmm.scene_from_dict({"beam": beam, "attachments": atts})
    js = np.arange(10, 26)
    H = mstmm.frf(big, "force:x=0", [f"displacement:x={float(j * L)!r}" for j in js], [w])[0, 0]
    ratio = np.abs(H[1:]) / np.abs(H[:-1])
    assert np.allclose(-np.log(ratio), slow, rtol=1e-6), (np.log(ratio), slow)


def test_damped_cell_gives_complex_k():
    """A loss factor makes every wave decay: Im k > 0 everywhere, no sharp edge."""
    b = bands(cell(loss_factor=0.02), band=(1.0, 2 * W_BRAGG), points=50)
    assert b.damped and b.edges == () and np.all(b.k.imag > 0.0)
    k = (MBAR * b.omega**2 / (EI * (1 + 0.02j))) ** 0.25  # k^4 = mbar w^2 / (EI (1 + i eta))
    assert np.allclose(np.cos(b.k[:, 1] * L), np.cos(k * L), rtol=1e-10)


def test_stepped_cell_equals_uniform():
    """A uniform cell split into two equal segments has the same edges."""
    seg = {"length": L / 2, "EI": EI, "mass_per_length": MBAR}
    stepped = mstmm.scene_from_dict(
        {
            "beam": {"left": "free", "right": "free", "segments": [seg, seg]},
            "attachments": [resonator(0.2, 0.1, 0.3 * W_BRAGG)],
        }
    )
    band = (0.0, 1.5 * W_BRAGG)
    a = bands(stepped, band=band, points=20)
    b = bands(cell(resonator(0.2, 0.1, 0.3 * W_BRAGG)), band=band, points=20)
    assert len(a.edges) == len(b.edges)
    for e, f in zip(a.edges, b.edges):
        assert e.kind == f.kind and abs(e.omega - f.omega) <= 1e-13 * max(f.omega, 1.0)


def _run(*args):
    return subprocess.run(
        [sys.executable, "-m", "mstmm", *args], capture_output=True, text=True, timeout=600
    )


def test_command(tmp_path):
    path = tmp_path / "cell.toml"
    path.write_text(
        "[beam]\nlength = 0.7\nEI = 2.0\nmass_per_length = 3.0\nleft = 'free'\nright = 'free'\n"
        "[[attachments]]\ntype = 'support'\nx = 0.2\n"
    )
    r = _run("bands", str(path), "--band", "0", "120", "--format", "json", "--points", "20")
    assert r.returncode == 0, r.stderr
    data = json.loads(r.stdout)
    assert data["count_checked"] and len(data["gaps"]) == 3  # the last cut at 120
    assert abs(data["edges"][0]["omega"] - W_BRAGG) <= 1e-13 * W_BRAGG
    r = _run("bands", str(path), "--band", "0", "120")
    assert r.returncode == 0 and "stop band" in r.stdout
    r = _run("bands", str(path), "--points", "5", "--format", "csv")
    assert r.returncode == 0 and len(r.stdout.splitlines()) >= 6
    bad = tmp_path / "bad.toml"
    bad.write_text(path.read_text().replace("x = 0.2", "x = 0.7"))
    r = _run("bands", str(bad))
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and "attachments[0].x" in r.stderr and "0.7" in r.stderr


def test_plot(tmp_path):
    pytest.importorskip("matplotlib")
    out = tmp_path / "dispersion.png"
    b = bands(cell(resonator(0.3, 0.1, 0.3 * W_BRAGG)), band=(0.0, 1.2 * W_BRAGG), points=50)
    from mstmm import plot

    fig = plot.dispersion(b, path=out)
    assert out.stat().st_size > 1000
    assert any(p.get_gid() == "gap" for p in fig.axes[0].patches)


def test_metamaterial_example():
    """examples/metamaterial.toml: its cell's gap against Sugino's asymptotic one (mu =
    0.5, omega_t / omega_Bragg ~ 0.011: within 2 mu (omega_t / omega_Bragg)^2), and the
    transmission through the finite 200-cell beam (mstmm.frf from x = 0 to x = 2 m) in
    the gap against exp(-200 Im k L): the log agrees to the O(1) of the ends, out of
    ~30 to ~80 nepers."""
    from pathlib import Path

    path = Path(__file__).resolve().parent.parent / "examples" / "metamaterial.toml"
    scene = mstmm.load_scene(path)
    cell = scene.cell
    wt = math.sqrt(5329.586 / 0.00054)
    frac = wt / ((math.pi / cell.beam.length) ** 2 * math.sqrt(cell.beam.EI / 0.108))
    b = bands(scene, band=(0.0, 6000.0), points=100)
    assert b.count_checked and len(b.gaps) == 1
    lo, hi = b.gaps[0]
    assert abs(lo / wt - 1.0) <= 2 * 0.5 * frac**2
    assert abs(hi / (wt * math.sqrt(1.5)) - 1.0) <= 2 * 0.5 * frac**2
    ws = np.linspace(lo, hi, 7)[1:-1]
    att = bands(scene, omegas=ws, edges=False).attenuation
    H = mstmm.frf(scene, "force:x=0", ["displacement:x=0", "displacement:x=2.0"], ws)[:, 0, :]
    log_t = np.log(np.abs(H[:, 1]) / np.abs(H[:, 0]))
    assert np.all(np.abs(log_t + scene.repeat * att) < 2.0), (log_t, scene.repeat * att)


def timoshenko_cell() -> dict:
    """A Timoshenko cell with a resonator and a rotary mass: two pairs propagate above its
    cut-off."""
    return {
        "beam": {
            "length": L,
            "EI": EI,
            "mass_per_length": MBAR,
            "kappa_GA": 50.0,
            "rho_I": 0.01,
            "left": "free",
            "right": "free",
        },
        "attachments": [resonator(0.3, 0.1, 10.0), {"type": "mass", "x": 0.5, "m": 0.3, "J": 1e-3}],
    }


def test_coalescence_edges_above_a_timoshenko_cut_off():
    """Above a Timoshenko cell's cut-off two pairs propagate, and a pass band can end where
    they meet at an interior k (mu_1 = mu_2 inside (-2, 2)) and turn complex: between two
    edges with two pairs at both ends, ``bands._two_pairs`` proves whether they meet
    (once at most) and brackets the complex quartet. The two such gaps in this band are
    proved (count_checked): at each of their ends mpmath's two mu are real inside (-2, 2)
    on one side and a complex pair on the other, 1e-9 away; at their middle a complex
    pair."""
    import reference_bloch as ref

    data = timoshenko_cell()
    b = bands(mstmm.scene_from_dict(data), band=(100.0, 170.0), points=300)
    odd = [e for e in b.edges if e.kind == "coalescence"]
    assert len(odd) == 4 and b.count_checked and all(e.certified for e in odd), b.notes
    inner = [g for g in b.gaps if g[0] in {e.omega for e in odd}]
    assert [(lo, hi) for lo, hi in inner] == [
        (odd[0].omega, odd[1].omega),
        (odd[2].omega, odd[3].omega),
    ]
    for e in odd:
        sides = [[complex(v) for v in ref.bloch_mu(data, e.omega * (1.0 + d), dps=30)]
                 for d in (-1e-9, 1e-9)]  # fmt: skip
        pair = [abs(m[0].imag) > 0.0 for m in sides]
        assert pair[0] != pair[1], (e.omega, sides)
        assert all(abs(m.real) < 2.0 for m in sides[pair.index(False)]), (e.omega, sides)
    for lo, hi in inner:
        m1, m2 = (complex(v) for v in ref.bloch_mu(data, 0.5 * (lo + hi), dps=30))
        assert m1 == m2.conjugate() and abs(m1.imag) > 0.0, (m1, m2)


def test_two_propagating_pairs_between_edges_are_proved_or_said():
    """Between the certified edges 126.49 and 129.40 rad/s of the Timoshenko cell above two
    pairs propagate throughout: ``_two_pairs`` proves they do not meet (their phases at
    the two ends and the closed cell's count at a phase between them), count_checked.
    Where its phases cannot be told apart (PHASE_GAP made larger than the zone), the
    argument is not used: the stretch is said in a note and count_checked is False."""
    import importlib

    module = importlib.import_module("mstmm.bands")
    data = timoshenko_cell()
    b = bands(mstmm.scene_from_dict(data), band=(127.0, 129.0), points=50)
    assert not b.edges and np.all(b.propagating == 2)
    assert b.count_checked and not b.notes, b.notes
    saved = module.PHASE_GAP
    module.PHASE_GAP = 10.0
    try:
        b = bands(mstmm.scene_from_dict(data), band=(127.0, 129.0), points=50)
    finally:
        module.PHASE_GAP = saved
    assert not b.count_checked
    assert any("two wave pairs propagate" in n for n in b.notes), b.notes

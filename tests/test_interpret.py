"""The interpreted tier (mstmm.interpret): same answers as the references, used only when cheap.

The kernels' ``lowest`` run as plain Python is checked against the independent
mpmath model of ``tests/reference_model.py`` on every pair of end conditions;
the tier's decisions are checked on the process state that drives them.
The fresh-process command line (interpreted by default, compiled with
``MSTMM_INTERPRET_BUDGET=0``) is checked against the shared references in
``tests/test_reference.py``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import reference_model as ref
from test_roots import make, rel

import mstmm
from mstmm import interpret
from mstmm.scene import BOUNDARY_KINDS

PAIRS = [(a, b) for a in BOUNDARY_KINDS for b in BOUNDARY_KINDS]


@pytest.mark.parametrize("left,right", PAIRS)
def test_interpreted_solve_matches_reference(fresh_process, left, right):
    rng = np.random.default_rng([BOUNDARY_KINDS.index(left), BOUNDARY_KINDS.index(right)])
    draws = rng.uniform(0.05, 1.0, (3, 3)) * [1.0, 500.0, 1.0]
    atts = [(float(x), float(k), float(m)) for x, k, m in draws]
    atts.append((1.0, 50.0, 0.2))  # one at the right end
    scene = make(left, right, atts)
    modes = 6
    sol = mstmm.solve(scene, modes=modes, shapes=False)
    assert sol.kernel_mode == "interpreted"
    assert sol.count_checked and sol.converged.all(), sol.warnings
    exact = ref.frequencies(scene, modes, dps=30)
    for got, want in zip(sol.omega, exact, strict=True):
        if want == 0:
            assert got == 0.0
        else:
            assert rel(got, want) < 1e-12, (got, want)


def test_tier_runs_compiled_once_machine_code_is_loaded(fresh_process, data_dir):
    scene = mstmm.load_scene(data_dir / "wu_chou_1998.toml")
    interpret.mark_compiled()
    assert mstmm.solve(scene, modes=5, shapes=False).kernel_mode == "compiled"


def test_tier_runs_compiled_when_the_budget_is_spent(fresh_process, data_dir):
    scene = mstmm.load_scene(data_dir / "wu_chou_1998.toml")
    interpret._Process.spent = interpret.DEFAULT_BUDGET - 1e-3
    assert mstmm.solve(scene, modes=5, shapes=False).kernel_mode == "compiled"


def test_tier_runs_compiled_when_the_problem_is_large(fresh_process, data_dir):
    """An estimate over the budget (many modes, many attachments) goes straight to numba."""
    scene = mstmm.load_scene(data_dir / "wu_chou_1998.toml")
    modes = int(interpret.DEFAULT_BUDGET / interpret.COST_PER_MODE) + 1
    assert mstmm.solve(scene, modes=modes, shapes=False).kernel_mode == "compiled"


def test_budget_zero_turns_interpretation_off(fresh_process, data_dir):
    interpret.set_budget(0.0)
    scene = mstmm.load_scene(data_dir / "wu_chou_1998.toml")
    assert mstmm.solve(scene, modes=1, shapes=False).kernel_mode == "compiled"


def test_the_budget_is_charged(fresh_process, data_dir):
    scene = mstmm.load_scene(data_dir / "wu_chou_1998.toml")
    assert mstmm.solve(scene, modes=3, shapes=False).kernel_mode == "interpreted"
    assert interpret._Process.spent > 0.0


STAYS_IN_PYTHON = """
import sys
import mstmm
from numba.core.dispatcher import Dispatcher
sol = mstmm.solve(mstmm.load_scene(mstmm.example_path("wu_chou_1998")), modes=5, shapes=False)
loaded = sorted(
    f"{name}.{attr}"
    for name, mod in list(sys.modules.items())
    if name.startswith("mstmm") and mod is not None
    for attr, obj in vars(mod).items()
    if isinstance(obj, Dispatcher) and obj.overloads
)
print(sol.kernel_mode, sol.omega[0], loaded)
"""


def test_an_interpreted_solve_loads_no_machine_code():
    """Run as Python all the way down: no compiled function of mstmm is called (a call
    from Python would load machine code, the 0.35 s the tier exists to avoid, and give
    the compiled function's last bits). ``numerics.generic``'s real and complex twins
    are plain functions: the tier rebinds them too."""
    import subprocess
    import sys

    out = subprocess.run(
        [sys.executable, "-c", STAYS_IN_PYTHON], capture_output=True, text=True, check=True
    )
    mode, omega0, loaded = out.stdout.split(maxsplit=2)
    assert mode == "interpreted"
    assert rel(float(omega0), 102.79443360194969) < 1e-12  # README table, reference.json
    assert loaded.strip() == "[]"


def test_a_run_as_python_whose_estimate_proves_wrong_goes_on_compiled(
    fresh_process, monkeypatch
):
    """A string-like tensioned beam (P L^2 / EI ~ 2e8: each evaluation walks 10^4
    pieces) looks cheap to the cost model, which counts modes and components: its run as
    Python stops at its deadline (``interpret.deadline``) and the search runs compiled,
    to the closed-form roots of the tensioned pinned-pinned beam."""
    L, EI, mbar, P = 1.0, 6.0e4, 15.0, 1.0e13
    scene = mstmm.scene_from_dict(
        {
            "name": "string_like",
            "beam": {"length": L, "EI": EI, "mass_per_length": mbar, "left": "pinned",
                     "right": "pinned", "axial_force": P},
        }
    )
    # a small budget, so that the run outgrows it wherever the machine is fast
    monkeypatch.setattr(interpret._Process, "budget", 0.05)
    monkeypatch.setattr(interpret, "COLD_BUDGET", 0.05)
    kernel = mstmm.kernel_for(scene)
    assert kernel.interprets(mstmm.parameter_vector(scene), 2)  # the model says: Python
    sol = mstmm.solve(scene, modes=2, shapes=False)
    for n, w in enumerate(sol.omega, start=1):
        k = n * math.pi / L
        exact = k * k * math.sqrt(EI / mbar) * math.sqrt(1.0 + P / (EI * k * k))
        assert abs(w / exact - 1.0) < 1e-12, n
    assert sol.count_checked and sol.kernel_mode == "compiled"
    # the whole search as Python takes minutes here: the run stopped at its allowance
    # (twice the budget), one piece of a segment past it
    assert interpret._Process.spent < 2.0 * 0.05 + 0.5


def test_a_kernel_not_compiled_yet_gets_the_cold_budget(fresh_process, monkeypatch, data_dir):
    """Where numba's cache lacks the kernel's characteristic function, compiling is the
    other choice (seconds), not loading: work estimated past the budget but within
    ``COLD_BUDGET`` runs as Python; the same work on a compiled kernel does not."""
    monkeypatch.setattr(interpret, "COLD_BUDGET", 1.5)
    scene = mstmm.load_scene(data_dir / "wu_chou_1998.toml")
    kernel = mstmm.kernel_for(scene)
    p = mstmm.parameter_vector(scene)
    modes = int(1.0 / interpret.estimated_cost(1, kernel.attachments(p)))  # about 1 s
    monkeypatch.setattr(kernel, "_was_cold", True)
    assert kernel.interprets(p, modes)
    monkeypatch.setattr(kernel, "_was_cold", False)
    assert not kernel.interprets(p, modes)

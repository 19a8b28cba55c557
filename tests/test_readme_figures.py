"""The README's measured figures are exactly what the benchmarks recorded, never typed.

Every measured figure of README.md sits in a ``<!-- figures:NAME -->`` block
that ``python -m benchmarks.readme`` writes from ``docs/figures.json`` (and
``docs/certification.json``); here the committed README must equal what the
script writes from the committed figures, so a number typed into a block, or a
benchmark re-run without rewriting the README, fails.
"""

from __future__ import annotations

import copy
import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from benchmarks import figures, readme  # noqa: E402


@pytest.fixture(scope="module")
def recorded() -> tuple[dict, dict | None]:
    return figures.load(), readme.load_certification()


def test_readme_figures_are_those_the_benchmarks_recorded(recorded):
    text = readme.README.read_text()
    assert readme.render(text, *recorded) == text, (
        "README.md figures differ from docs/figures.json: run python -m benchmarks.readme"
    )


def test_every_block_is_in_the_readme_once():
    names = [m.group("name") for m in readme.BLOCK.finditer(readme.README.read_text())]
    assert sorted(names) == sorted(readme.BLOCKS)


def test_a_typed_number_is_caught(recorded):
    """Change one digit inside the Table 1 block: the rewrite differs from the edited text."""
    text = readme.README.read_text()
    block = re.search(r"<!-- figures:table1 -->.*?<!-- /figures:table1 -->", text, re.S)
    assert block is not None
    edited_block = re.sub(r"(\d+) us warm", lambda m: f"{int(m.group(1)) + 1} us warm", block[0])
    edited_block = re.sub(r"(\d+)\.(\d+) ms warm", r"\1.9\2 ms warm", edited_block)
    assert edited_block != block[0]
    edited = text.replace(block[0], edited_block)
    assert readme.render(edited, *recorded) == text


def test_unknown_or_missing_blocks_are_refused(recorded):
    with pytest.raises(ValueError, match="unknown figure block"):
        readme.render("<!-- figures:bogus -->1<!-- /figures:bogus -->", *recorded)
    with pytest.raises(ValueError, match="missing"):
        readme.render("no blocks at all", *recorded)


def test_figures_of_a_quick_run_are_refused(recorded):
    figs = copy.deepcopy(recorded[0])
    figs["table1"]["quick"] = True
    with pytest.raises(readme.MissingFigures, match="--quick"):
        readme.render(readme.README.read_text(), figs, recorded[1])
    del figs["table1"]
    with pytest.raises(readme.MissingFigures, match="python -m benchmarks.table1"):
        readme.render(readme.README.read_text(), figs, recorded[1])


def test_the_example_block_is_what_mstmm_solve_prints_now(recorded):
    """The example's frequencies in README.md are those of a fresh ``mstmm solve`` run of
    the current code, in the kernel mode the record names (the interpreted and the compiled
    kernel may differ in the last digit): a figure recorded before a change of the numerics
    (issue 20: mode 4 read ...736 in the README, ...741 when run) fails here."""
    import os
    import subprocess

    ex = recorded[0]["example"]
    budget = "1e9" if ex["kernel_mode"] == "interpreted" else "0"
    run = subprocess.run(
        [sys.executable, "-m", "mstmm", *ex["command"].split()[1:]],
        capture_output=True,
        text=True,
        timeout=600,
        env={**os.environ, "MSTMM_INTERPRET_BUDGET": budget},
    )
    assert run.returncode == 0, run.stderr

    def modes(text: str) -> list[str]:
        return [ln for ln in text.splitlines() if re.match(r"\s+\d+\s+\d", ln)]

    assert len(modes(run.stdout)) == 10
    assert modes(run.stdout) == modes(ex["output"])
    block = re.search(
        r"<!-- figures:example -->.*?<!-- /figures:example -->", readme.README.read_text(), re.S
    )
    assert modes(block[0]) == modes(run.stdout)

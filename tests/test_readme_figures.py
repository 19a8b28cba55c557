"""The measured figures of README.md and docs/*.md are exactly what the benchmarks recorded.

Every measured figure of the pages (README.md and every ``docs/*.md``) sits in a
``<!-- figures:NAME -->`` block that ``python -m benchmarks.readme`` writes from
``docs/figures.json`` (and ``docs/certification.json``), wherever the block stands; here
the committed pages must equal what the script writes from the committed figures, so a
number typed into a block, or a benchmark re-run without rewriting the pages, fails.
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


def _block(name: str) -> tuple[Path, str]:
    """The page holding block ``name`` and the block, markers included."""
    for page, text in readme.read_pages().items():
        m = re.search(rf"<!-- figures:{name} -->.*?<!-- /figures:{name} -->", text, re.S)
        if m:
            return page, m[0]
    raise AssertionError(f"no block {name}")


def test_figures_are_those_the_benchmarks_recorded(recorded):
    texts = readme.read_pages()
    new = readme.render_pages(texts, *recorded)
    stale = [p.name for p in texts if new[p] != texts[p]]
    assert not stale, f"{stale}: figures differ from docs/figures.json: run benchmarks.readme"


def test_every_block_is_in_the_pages_once():
    texts = readme.read_pages().values()
    names = [m.group("name") for t in texts for m in readme.BLOCK.finditer(t)]
    assert sorted(names) == sorted(readme.BLOCKS)


def test_the_pages_are_the_readme_and_the_docs():
    pages = readme.pages()
    assert pages[0] == ROOT / "README.md"
    assert {p.name for p in pages[1:]} == {p.name for p in (ROOT / "docs").glob("*.md")}


def test_a_typed_number_is_caught(recorded):
    """Change one digit inside the Table 1 block, wherever it stands: the rewrite differs
    from the edited text."""
    page, block = _block("table1")
    texts = readme.read_pages()
    edited_block = re.sub(r"(\d+) us warm", lambda m: f"{int(m.group(1)) + 1} us warm", block)
    edited_block = re.sub(r"(\d+)\.(\d+) ms warm", r"\1.9\2 ms warm", edited_block)
    assert edited_block != block
    edited = {**texts, page: texts[page].replace(block, edited_block)}
    assert readme.render_pages(edited, *recorded) == texts


def test_a_block_moves_to_another_page(recorded):
    """A block moved with its text to another page is rewritten there, its links made
    relative to that page."""
    texts = readme.read_pages()
    page, block = _block("many-modes")
    other = ROOT / "docs" / "moved.md"
    moved = {p: t.replace(block, "") for p, t in texts.items()}
    moved[other] = "# moved\n\n" + block.replace("](many_modes.md)", "](docs/many_modes.md)")
    out = readme.render_pages(moved, *recorded)
    assert "[docs/many_modes.md](many_modes.md)" in out[other]
    front = ROOT / "README.md"
    top = readme.render_pages({**moved, other: "", front: moved[front] + moved[other]}, *recorded)
    assert "[docs/many_modes.md](docs/many_modes.md)" in top[front]


def test_unknown_missing_or_repeated_blocks_are_refused(recorded):
    with pytest.raises(ValueError, match="unknown figure block"):
        readme.render_pages(
            {ROOT / "x.md": "<!-- figures:bogus -->1<!-- /figures:bogus -->"}, *recorded
        )
    with pytest.raises(ValueError, match="missing"):
        readme.render_pages({ROOT / "x.md": "no blocks at all"}, *recorded)
    texts = readme.read_pages()
    _, block = _block("table1")
    with pytest.raises(ValueError, match="more than once.*table1"):
        readme.render_pages({**texts, ROOT / "docs" / "twice.md": block}, *recorded)


def test_figures_of_a_quick_run_are_refused(recorded):
    figs = copy.deepcopy(recorded[0])
    figs["table1"]["quick"] = True
    with pytest.raises(readme.MissingFigures, match="--quick"):
        readme.render_pages(readme.read_pages(), figs, recorded[1])
    del figs["table1"]
    with pytest.raises(readme.MissingFigures, match="python -m benchmarks.table1"):
        readme.render_pages(readme.read_pages(), figs, recorded[1])


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
    page, block = _block("example")
    assert page == readme.README  # the front page's example
    assert modes(block) == modes(run.stdout)


def test_the_front_page_outputs_are_of_the_commands_it_shows(recorded):
    """Each front-page example block quotes the output recorded for the command that
    ``benchmarks.example`` runs now: a command changed there without re-recording
    (``python -m benchmarks.example --front-page``) fails here. (The commands themselves
    take minutes on a busy machine, so their outputs are not re-run here.)"""
    from benchmarks import example

    front = recorded[0]["front_page"]
    assert set(example.FRONT_PAGE) == {k for k in front if k != "measured"}
    for name, args in example.FRONT_PAGE.items():
        assert front[name]["command"] == "mstmm " + example._typed(args)
        page, block = _block(f"front-{name}")
        assert page == readme.README
        assert f"$ {front[name]['command']}\n" in block

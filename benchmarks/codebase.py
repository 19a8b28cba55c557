"""How much of the generated code SymPy prints, and how much numba is written by hand.

Run: ``python -m benchmarks.codebase [--record]`` (a few seconds; no timing).

Issue 21 asks for three numbers in the benchmark report:

* the lines of ``generated/`` printed by SymPy against all its lines. The derivation is
  run again with the printer's entry point in ``derive.emit`` (``code``: a whole function,
  printed from SymPy's codegen AST, or a module's constants) wrapped so that every line
  it returns is counted. What is not printed is each module's header (its docstring: what,
  topology, parameter order, regenerate command; the hashes and kinds it was printed
  with), its imports and the last line of a kernel (``bind_characteristic``, which
  compiles the printed functions with the characteristic functions). Counted over all
  lines, and over the lines of code (no docstring, comment or blank line); for the
  committed modules, and for a kernel of every kind (undamped and damped) as a user's
  richest topology;
* the lines of hand-written numba in ``src/mstmm/numerics/`` (ordinary, linted code:
  statements, not blank lines, comments or docstrings);
* the files a contributor touches to add a kind, from ``tests/test_new_kind.py``'s
  contract: the kind's file (the test fails if anything else must change).
"""

from __future__ import annotations

import argparse
import ast
import io
import tokenize
from contextlib import contextmanager
from pathlib import Path

from . import figures

ROOT = Path(__file__).resolve().parent.parent


def _nonblank(text: str) -> int:
    return sum(1 for line in text.splitlines() if line.strip())


@contextmanager
def _counting():
    """Count the non-blank lines ``derive.emit.code`` (SymPy's printer) returns."""
    from mstmm.derive import emit

    tally = [0]
    original = emit.code

    def counted(*args, **kwargs):
        out = original(*args, **kwargs)
        tally[0] += _nonblank(out)
        return out

    emit.code = counted
    try:
        yield tally
    finally:
        emit.code = original


def _printed(make) -> dict:
    """Of the source ``make()`` returns: its lines printed by SymPy, its non-blank lines,
    and its lines of code (``code``: not blank, comment or docstring)."""
    with _counting() as tally:
        source = make()
    return {"printed": tally[0], "lines": _nonblank(source), "code": _code_lines(source)}


def generated_share() -> dict:
    """The committed modules of ``generated/`` and a kernel of every kind."""
    from mstmm.derive import emit
    from mstmm.derive.bundled import BUNDLED_TOPOLOGIES

    from mstmm import catalog

    committed = [("euler_bernoulli.py", emit.numerics_source)]
    committed += [
        (f"{t.kernel_key}.py", lambda t=t: emit.kernel_source(t)) for t in BUNDLED_TOPOLOGIES
    ]
    rows = {name: _printed(make) for name, make in committed}
    kinds = tuple(sorted(catalog.builtin_kinds()))
    every = {
        "undamped": catalog.Topology("pinned", "free", tuple(k for k in kinds if k != "dashpot")),
        "damped": catalog.Topology("pinned", "free", kinds, True),
    }
    richest = {}
    for label, topology in every.items():
        richest[label] = {
            "kinds": len(topology.kinds),
            **_printed(lambda t=topology: emit.kernel_source(t)),
        }
    sums = {k: sum(r[k] for r in rows.values()) for k in ("printed", "lines", "code")}
    return {"modules": rows, **sums, "every_kind": richest}


def _statements(path: Path) -> int:
    """Lines holding code in a Python file: not blank, not a comment, not a docstring."""
    return _code_lines(path.read_text())


def _code_lines(text: str) -> int:
    """Lines holding code in Python source: not blank, not a comment, not a docstring."""
    docstrings: set[int] = set()
    for node in ast.walk(ast.parse(text)):
        body = getattr(node, "body", None)
        if isinstance(body, list) and body and isinstance(body[0], ast.Expr):
            value = body[0].value
            if isinstance(value, ast.Constant) and isinstance(value.value, str):
                docstrings.update(range(body[0].lineno, body[0].end_lineno + 1))
    lines: set[int] = set()
    for tok in tokenize.generate_tokens(io.StringIO(text).readline):
        if tok.type in (tokenize.COMMENT, tokenize.NL, tokenize.NEWLINE, tokenize.INDENT):
            continue
        if tok.type in (tokenize.DEDENT, tokenize.ENDMARKER):
            continue
        lines.update(range(tok.start[0], tok.end[0] + 1))
    return len(lines - docstrings)


def numerics_lines() -> dict:
    """Statements of hand-written numba per module of ``src/mstmm/numerics``."""
    folder = ROOT / "src" / "mstmm" / "numerics"
    per = {p.name: _statements(p) for p in sorted(folder.glob("*.py"))}
    return {"modules": per, "lines": sum(per.values())}


def measure() -> dict:
    return {
        "generated": generated_share(),
        "numerics": numerics_lines(),
        "files_to_add_a_kind": 1,
        "files_to_add_a_kind_checked_by": "tests/test_new_kind.py",
    }


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--record", action="store_true", help="write docs/figures.json")
    args = ap.parse_args(argv)
    fig = measure()
    g = fig["generated"]
    for name, r in g["modules"].items():
        print(
            f"generated/{name}: {r['printed']} of {r['lines']} lines printed by SymPy"
            f" ({r['printed']} of {r['code']} lines of code)"
        )
    print(
        f"generated/: {g['printed']} of {g['lines']} ({g['printed'] / g['lines']:.0%}) by SymPy;"
        f" of its lines of code {g['printed'] / g['code']:.0%}"
    )
    for label, r in g["every_kind"].items():
        print(
            f"a kernel of every kind ({label}, {r['kinds']} kinds): {r['lines']} lines,"
            f" {r['printed'] / r['lines']:.0%} by SymPy ({r['printed'] / r['code']:.0%} of"
            " its code)"
        )
    print(f"hand-written numba in src/mstmm/numerics: {fig['numerics']['lines']} lines of code")
    if args.record:
        path = figures.record("codebase", fig, command="python -m benchmarks.codebase --record")
        print(f"recorded in {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

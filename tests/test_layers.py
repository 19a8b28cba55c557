"""The runtime's modules import each other in one direction (issue 21, item 5): no cycle,
lazy imports inside functions included (``solve`` dispatches to ``damped``, which starts
from ``undamped``; it used to import ``solve`` back)."""

from __future__ import annotations

import ast
from pathlib import Path

import mstmm

ROOT = Path(mstmm.__file__).resolve().parent


def imports() -> dict[str, set[str]]:
    """Each runtime module -> the runtime modules it imports anywhere in its body."""
    modules = {p.stem for p in ROOT.glob("*.py")}
    graph = {}
    for name in modules:
        deps = set()
        for node in ast.walk(ast.parse((ROOT / f"{name}.py").read_text())):
            if not isinstance(node, ast.ImportFrom):
                continue
            if node.level == 1:
                deps |= {node.module.split(".")[0]} if node.module else {a.name for a in node.names}
            elif node.module and node.module.startswith("mstmm."):
                deps.add(node.module.split(".")[1])
        graph[name] = deps & modules - {name}
    return graph


def test_no_import_cycle_in_the_runtime():
    graph = imports()
    assert "damped" in graph["solve"] and "undamped" in graph["damped"]
    done: set[str] = set()

    def visit(v: str, path: list[str]) -> None:
        assert v not in path, " -> ".join([*path, v])
        if v in done:
            return
        for w in sorted(graph[v]):
            visit(w, [*path, v])
        done.add(v)

    for v in sorted(graph):
        visit(v, [])

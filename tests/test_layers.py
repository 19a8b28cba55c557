"""The runtime's modules import each other in one direction (issue 21, item 5): no cycle,
lazy imports inside functions included (``solve`` dispatches to ``damped``, which starts
from ``undamped``; it used to import ``solve`` back)."""

from __future__ import annotations

import ast
from pathlib import Path

import mstmm

ROOT = Path(mstmm.__file__).resolve().parent


def imported(node: ast.AST) -> set[str]:
    """The runtime modules (``mstmm.<name>``) an import statement names: ``from . import x``,
    ``from .x import y``, ``from mstmm import x``, ``from mstmm.x import y``, ``import
    mstmm.x``; names that are not modules are filtered out by the caller."""
    if isinstance(node, ast.Import):
        return {a.name.split(".")[1] for a in node.names if a.name.startswith("mstmm.")}
    if not isinstance(node, ast.ImportFrom):
        return set()
    if node.level == 1:
        return {node.module.split(".")[0]} if node.module else {a.name for a in node.names}
    if node.level == 0 and node.module == "mstmm":
        return {a.name for a in node.names}
    if node.level == 0 and node.module and node.module.startswith("mstmm."):
        return {node.module.split(".")[1]}
    return set()


def imports() -> dict[str, set[str]]:
    """Each runtime module -> the runtime modules it imports anywhere in its body."""
    modules = {p.stem for p in ROOT.glob("*.py")}
    graph = {}
    for name in modules:
        deps = set()
        for node in ast.walk(ast.parse((ROOT / f"{name}.py").read_text())):
            deps |= imported(node)
        graph[name] = deps & modules - {name}
    return graph


def test_every_form_of_import_is_seen():
    """``from mstmm import x`` is an import of ``x`` as ``from . import x`` is (it was
    missed: the circle compiling -> kernels -> compiling went unseen)."""
    forms = {
        "from . import kernels": {"kernels"},
        "from .kernels import Kernel": {"kernels"},
        "from mstmm import kernels": {"kernels"},
        "from mstmm.kernels import Kernel": {"kernels"},
        "import mstmm.kernels": {"kernels"},
        "from .numerics import entries": {"numerics"},
        "import numpy": set(),
    }
    for source, expected in forms.items():
        assert imported(ast.parse(source).body[0]) == expected, source


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

"""The runtime's modules import each other in one direction (issue 21, item 5): no cycle,
lazy imports inside functions included (``solve`` dispatches to ``damped``, which starts
from ``undamped``; it used to import ``solve`` back). The modules of a subpackage count one by
one (``scene.model``, ``scene.repeat``: issue 42 split ``scene.py`` into them)."""

from __future__ import annotations

import ast
from pathlib import Path

import mstmm

ROOT = Path(mstmm.__file__).resolve().parent


def _modules() -> dict[str, Path]:
    """Each runtime module by its dotted name below ``mstmm`` (``solve``, ``scene`` for
    ``scene/__init__.py``, ``scene.model``; the package's own ``__init__`` as ``__init__``)."""
    modules = {}
    for path in ROOT.rglob("*.py"):
        parts = path.relative_to(ROOT).with_suffix("").parts
        if len(parts) > 1 and parts[-1] == "__init__":
            parts = parts[:-1]
        modules[".".join(parts)] = path
    return modules


def imports() -> dict[str, set[str]]:
    """Each runtime module -> the runtime modules it imports anywhere in its body (a name
    imported from a package counts as its submodule when there is one)."""
    modules = _modules()
    graph = {}
    for name, path in modules.items():
        package = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
        if name == "__init__":
            package = []
        deps = set()
        for node in ast.walk(ast.parse(path.read_text())):
            if not isinstance(node, ast.ImportFrom):
                continue
            module = node.module.split(".") if node.module else []
            if node.level:
                target = ".".join(package[: len(package) - node.level + 1] + module)
            elif module[:1] == ["mstmm"] and len(module) > 1:  # not `from mstmm import x`
                target = ".".join(module[1:])
            else:
                continue
            for alias in node.names:
                submodule = f"{target}.{alias.name}".strip(".")
                deps.add(submodule if submodule in modules else target)
        graph[name] = deps & set(modules) - {name}
    return graph


def test_no_import_cycle_in_the_runtime():
    graph = imports()
    assert "damped" in graph["solve"] and "undamped" in graph["damped"]
    assert "scene.repeat" in graph["scene.reading"] and "scene.model" in graph["scene.repeat"]
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

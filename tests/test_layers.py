"""The runtime's modules import each other in one direction (issue 21, item 5): no cycle,
lazy imports inside functions included (``solve`` dispatches to ``damped``, which starts
from ``undamped``; it used to import ``solve`` back), every form of import seen (``from
mstmm import x`` was missed: the circle compiling -> kernels -> compiling went unseen),
and the modules of subpackages (``scene.model``, ``numerics.segment``) each a node."""

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


def imported(node: ast.AST, package: list[str], modules) -> set[str]:
    """The runtime modules an import statement in a module of ``package`` names: ``from .
    import x``, ``from .x import y``, ``from mstmm import x``, ``from mstmm.x import y``,
    ``import mstmm.x`` (a name imported from a package counts as its submodule when there
    is one)."""
    if isinstance(node, ast.Import):
        out = set()
        for a in node.names:
            parts = a.name.split(".")
            if parts[0] == "mstmm" and len(parts) > 1:
                out.add(".".join(parts[1:]))
        return out
    if not isinstance(node, ast.ImportFrom):
        return set()
    module = node.module.split(".") if node.module else []
    if node.level:
        target = ".".join(package[: len(package) - node.level + 1] + module)
    elif module[:1] == ["mstmm"]:
        target = ".".join(module[1:])
    else:
        return set()
    out = set()
    for alias in node.names:
        submodule = f"{target}.{alias.name}".strip(".")
        out.add(submodule if submodule in modules else target)
    return out


def imports() -> dict[str, set[str]]:
    """Each runtime module -> the runtime modules it imports anywhere in its body."""
    modules = _modules()
    graph = {}
    for name, path in modules.items():
        package = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
        if name == "__init__":
            package = []
        deps = set()
        for node in ast.walk(ast.parse(path.read_text())):
            deps |= imported(node, package, modules)
        graph[name] = deps & set(modules) - {name}
    return graph


def test_every_form_of_import_is_seen():
    modules = _modules()
    forms = {
        "from . import kernels": {"kernels"},
        "from .kernels import Kernel": {"kernels"},
        "from mstmm import kernels": {"kernels"},
        "from mstmm.kernels import Kernel": {"kernels"},
        "import mstmm.kernels": {"kernels"},
        "from .numerics import segment": {"numerics.segment"},
        "from mstmm.physics import segment": {"physics.segment"},
        "import numpy": set(),
    }
    for source, expected in forms.items():
        assert imported(ast.parse(source).body[0], [], modules) == expected, source


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

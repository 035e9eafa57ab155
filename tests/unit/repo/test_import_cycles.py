"""No import cycles anywhere in course_lib (imports read with ast, not run).

Every import counts, module level or inside a function: an import inside a function is how a
cycle hides, so it is a cycle here too.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3] / "course_lib"
PACKAGES = ("ros2", "launch", "lab", "sim", "lessons", "viz", "notebook", ".")


def _module_name(path: Path, root: Path) -> str:
    parts = list(path.relative_to(root.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _resolve(module: str, is_package: bool, node: ast.ImportFrom) -> str:
    if node.level == 0:
        return node.module or ""
    base = module.split(".")
    base = base if is_package else base[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join([*base, *([node.module] if node.module else [])])


def imports_of(path: Path, root: Path, known: set[str]) -> set[str]:
    """Return the modules of `known` that the file at `path` imports."""
    module = _module_name(path, root)
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            target = _resolve(module, path.name == "__init__.py", node)
            subs = [f"{target}.{alias.name}" for alias in node.names]
            targets = [s for s in subs if s in known] or [target]
        else:
            continue
        # A package's __init__ is always imported before its modules: not a cycle edge.
        found.update(t for t in targets if t in known and not module.startswith(t + "."))
    return found


def graph_of(root: Path, package: str) -> dict[str, set[str]]:
    """Return module -> imported modules for every module of course_lib.<package>."""
    files = sorted((root / package).rglob("*.py"))
    names = {_module_name(f, root): f for f in files}
    return {name: imports_of(path, root, set(names)) for name, path in names.items()}


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """Return one import cycle as a list of modules (first repeated last), or None."""
    state: dict[str, int] = {}
    stack: list[str] = []

    def visit(node: str) -> list[str] | None:
        state[node] = 1
        stack.append(node)
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == 1:
                return [*stack[stack.index(nxt) :], nxt]
            if nxt not in state and (cycle := visit(nxt)):
                return cycle
        stack.pop()
        state[node] = 2
        return None

    for node in sorted(graph):
        if node not in state and (cycle := visit(node)):
            return cycle
    return None


def folder_graph(root: Path) -> dict[str, set[str]]:
    """Return folder -> folders it imports from (every folder of course_lib, at every depth).

    A package's __init__ importing from its own subfolders is not an edge: it is the folder's
    front door, not a dependency between folders.
    """
    graph = graph_of(root, ".")
    packages = {m for m in graph if (root.parent / m.replace(".", "/")).is_dir()}

    def folder(module: str) -> str:
        return module if module in packages else module.rpartition(".")[0]

    folders: dict[str, set[str]] = {}
    for module, targets in graph.items():
        here = folder(module)
        for target in targets:
            there = folder(target)
            if there == here or (module in packages and there.startswith(module + ".")):
                continue
            folders.setdefault(here, set()).add(there)
    return folders


@pytest.mark.parametrize("package", PACKAGES)
def test_package_has_no_import_cycle(package: str) -> None:
    cycle = find_cycle(graph_of(ROOT, package))
    assert cycle is None, "import cycle: " + " -> ".join(cycle or [])


def test_a_cycle_is_found(tmp_path: Path) -> None:
    pkg = tmp_path / "course_lib" / "demo"
    pkg.mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "a.py").write_text("from . import b\n")
    (pkg / "b.py").write_text("def f():\n    from .c import x\n")
    (pkg / "c.py").write_text("from course_lib.demo.a import y\n")
    assert find_cycle(graph_of(tmp_path / "course_lib", "demo")) == [
        "course_lib.demo.a",
        "course_lib.demo.b",
        "course_lib.demo.c",
        "course_lib.demo.a",
    ]
    (pkg / "c.py").write_text("import json\n")
    assert find_cycle(graph_of(tmp_path / "course_lib", "demo")) is None


def test_no_cycle_between_folders() -> None:
    cycle = find_cycle(folder_graph(ROOT))
    assert cycle is None, "import cycle between folders: " + " -> ".join(cycle or [])


def test_a_cycle_between_folders_is_found(tmp_path: Path) -> None:
    root = tmp_path / "course_lib"
    for folder in ("low", "high"):
        (root / folder).mkdir(parents=True)
        (root / folder / "__init__.py").write_text("")
    (root / "__init__.py").write_text("")
    (root / "high" / "a.py").write_text("from ..low import b\n")
    (root / "low" / "b.py").write_text("def f():\n    from ..high.a import x\n")
    assert find_cycle(folder_graph(root)) in (
        ["course_lib.high", "course_lib.low", "course_lib.high"],
        ["course_lib.low", "course_lib.high", "course_lib.low"],
    )

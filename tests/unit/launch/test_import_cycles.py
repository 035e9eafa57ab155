"""course_lib.launch depends downward: no import cycles, not even through imports in functions."""

from __future__ import annotations

import ast
from pathlib import Path

import course_lib.launch

PACKAGE_DIR = Path(course_lib.launch.__file__).resolve().parent


def _module_name(package: str, path: Path, root: Path) -> str:
    parts = path.relative_to(root).with_suffix("").parts
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join((package, *parts))


def _imports(tree: ast.AST, module: str, is_package: bool, known: set[str]) -> set[str]:
    """Return the modules of `known` that `module` imports (anywhere in its body)."""
    base = module if is_package else module.rpartition(".")[0]
    found: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            origin = base
            for _ in range(node.level - 1):
                origin = origin.rpartition(".")[0]
            if node.level:
                origin = f"{origin}.{node.module}" if node.module else origin
            else:
                origin = node.module or ""
            # `from pkg import mod` imports pkg.mod; `from pkg import name` needs pkg itself.
            targets = [
                f"{origin}.{alias.name}" if f"{origin}.{alias.name}" in known else origin
                for alias in node.names
            ]
        else:
            continue
        found.update(t for t in targets if t in known and t != module)
    return found


def import_graph(root: Path, package: str) -> dict[str, set[str]]:
    """Map each module of the package in `root` to the package modules it imports."""
    files = {_module_name(package, p, root): p for p in sorted(root.rglob("*.py"))}
    return {
        name: _imports(ast.parse(path.read_text()), name, path.name == "__init__.py", set(files))
        for name, path in files.items()
    }


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """Return one import cycle (`[a, b, ..., a]`), or None."""
    state: dict[str, int] = {}  # 1: on the current path, 2: done
    path: list[str] = []

    def visit(name: str) -> list[str] | None:
        state[name] = 1
        path.append(name)
        for target in sorted(graph[name]):
            if state.get(target) == 1:
                return [*path[path.index(target) :], target]
            if target not in state and (cycle := visit(target)):
                return cycle
        path.pop()
        state[name] = 2
        return None

    for name in sorted(graph):
        if name not in state and (cycle := visit(name)):
            return cycle
    return None


def test_launch_modules_form_no_import_cycle() -> None:
    graph = import_graph(PACKAGE_DIR, "course_lib.launch")
    assert len(graph) > 10 and graph["course_lib.launch.cli"]
    assert find_cycle(graph) is None


def test_a_cycle_through_an_import_in_a_function_is_found(tmp_path: Path) -> None:
    (tmp_path / "__init__.py").write_text("")
    (tmp_path / "core.py").write_text("X = 1\n")
    (tmp_path / "a.py").write_text("from .core import X\nfrom . import b\n")
    (tmp_path / "b.py").write_text("def f():\n    from .a import X\n    return X\n")
    graph = import_graph(tmp_path, "pkg")
    assert find_cycle(graph) == ["pkg.a", "pkg.b", "pkg.a"]
    (tmp_path / "b.py").write_text("def f():\n    from .core import X\n    return X\n")
    assert find_cycle(import_graph(tmp_path, "pkg")) is None


def test_absolute_and_parent_imports_count(tmp_path: Path) -> None:
    (tmp_path / "__init__.py").write_text("")
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "__init__.py").write_text("from .. import top\n")
    (tmp_path / "top.py").write_text("import pkg.sub\n")
    assert find_cycle(import_graph(tmp_path, "pkg")) == ["pkg.sub", "pkg.top", "pkg.sub"]

"""Layering rules read from the source with `ast` (no import of the code under test).

- import cycles: strongly connected parts of the import graph of the given packages, counting
  every import (module level, inside functions, under `if TYPE_CHECKING`);
- private reads: `obj._name` where obj is not `self`/`cls`/`super()` (a module's own private
  names are plain names, not attribute reads, so they are fine);
- `__dict__` uses and `vars(...)` calls;
- modules importing vtk/pyvista (per package).

Run as a script for the figures: `python tests/layering.py [ROOT]` (default: the repo).
"""

from __future__ import annotations

import ast
import sys
from dataclasses import dataclass
from pathlib import Path

PACKAGES = ("core", "app")
OWN = frozenset({"self", "cls"})
#: Underscore names that are public API of the standard library (namedtuple methods).
PUBLIC_UNDERSCORE = frozenset({"_replace", "_asdict", "_fields", "_make"})
RENDERING = ("vtk", "vtkmodules", "pyvista", "pyvistaqt")


@dataclass(frozen=True)
class Finding:
    """One rule break: where and what."""

    path: str
    line: int
    text: str

    def __str__(self) -> str:
        return f"{self.path}:{self.line}: {self.text}"


def modules(root: Path, packages: tuple[str, ...] = PACKAGES) -> dict[str, Path]:
    """Dotted module name -> source file, for every .py file of the packages under root."""
    out = {}
    for package in packages:
        for path in sorted((root / package).rglob("*.py")):
            parts = path.relative_to(root).with_suffix("").parts
            name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
            out[name] = path
    return out


def _imported(name: str, path: Path, tree: ast.AST, known: set[str] | None = None) -> set[str]:
    """Absolute names of every module `tree` imports (relative imports resolved). In `from
    pkg import x`, x counts when it is a module of `known`, else pkg (x is a name in it)."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")
                anchor = anchor[: len(anchor) - node.level + 1]
                base = ".".join(anchor + ([base] if base else []))
            for alias in node.names:
                full = f"{base}.{alias.name}"
                found.add(full if known is None or full in known else base)
            if known is None:
                found.add(base)
    return found


def import_graph(root: Path, packages: tuple[str, ...] = PACKAGES) -> dict[str, set[str]]:
    """module -> the package modules it imports. Importing `a.b` also runs `a/__init__`,
    but that is the package's own doing, so only the named module counts as an edge."""
    mods = modules(root, packages)
    graph = {}
    for name, path in mods.items():
        tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
        graph[name] = {m for m in _imported(name, path, tree, set(mods))
                       if m in mods and m != name}
    return graph


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The import cycles: strongly connected parts with more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for nxt in sorted(graph.get(node, ())):
            if nxt not in index:
                visit(nxt)
                low[node] = min(low[node], low[nxt])
            elif nxt in on_stack:
                low[node] = min(low[node], index[nxt])
        if low[node] == index[node]:
            part = []
            while True:
                top = stack.pop()
                on_stack.discard(top)
                part.append(top)
                if top == node:
                    break
            if len(part) > 1:
                found.append(sorted(part))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return found


def _is_own(value: ast.expr) -> bool:
    """`self`, `cls` or `super()`: the object's own attributes may be private."""
    if isinstance(value, ast.Name):
        return value.id in OWN
    return (isinstance(value, ast.Call) and isinstance(value.func, ast.Name)
            and value.func.id == "super")


def _findings(root: Path, packages: tuple[str, ...], rule) -> list[Finding]:
    out = []
    for path in modules(root, packages).values():
        tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
        rel = str(path.relative_to(root))
        out.extend(Finding(rel, node.lineno, text) for node in ast.walk(tree)
                   if (text := rule(node)) is not None)
    return out


def _private_read(node: ast.AST) -> str | None:
    if (isinstance(node, ast.Attribute) and node.attr.startswith("_")
            and not (node.attr.startswith("__") and node.attr.endswith("__"))
            and node.attr not in PUBLIC_UNDERSCORE and not _is_own(node.value)):
        return f"private attribute read {ast.unparse(node)}"
    return None


def _dict_use(node: ast.AST) -> str | None:
    if isinstance(node, ast.Attribute) and node.attr == "__dict__":
        return f"__dict__ use {ast.unparse(node)}"
    if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
            and node.func.id == "vars" and node.args):
        return f"vars() use {ast.unparse(node)}"
    return None


def private_reads(root: Path, packages: tuple[str, ...] = PACKAGES) -> list[Finding]:
    """Every `obj._name` on an object other than self/cls/super()."""
    return _findings(root, packages, _private_read)


def dict_uses(root: Path, packages: tuple[str, ...] = PACKAGES) -> list[Finding]:
    """Every `x.__dict__` and `vars(x)`."""
    return _findings(root, packages, _dict_use)


def rendering_importers(root: Path, package: str) -> list[str]:
    """Modules of `package` that import vtk/pyvista (directly, anywhere in the module)."""
    out = []
    for name, path in modules(root, (package,)).items():
        tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
        if any(m.split(".")[0] in RENDERING for m in _imported(name, path, tree)):
            out.append(name)
    return sorted(out)


def report(root: Path) -> dict[str, object]:
    """The layering figures: cycles, private reads, __dict__ uses, VTK importers."""
    graph = import_graph(root)
    found = cycles(graph)
    return {"import cycles": len(found), "modules in cycles": sum(map(len, found)),
            "cycles": found, "private reads": len(private_reads(root)),
            "__dict__ uses": len(dict_uses(root)),
            **{f"{p} modules importing vtk/pyvista": len(rendering_importers(root, p))
               for p in PACKAGES}}


if __name__ == "__main__":
    here = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parents[1]
    for key, value in report(here).items():
        print(f"{key}: {value}")
    for finding in [*private_reads(here), *dict_uses(here)]:
        print(finding)

"""App layering, read from the source (tests/layering.py): only the scene package touches VTK,
pyvista, pyvistaqt or the plotter, and no two app modules define a top-level function or class
of the same name (one name, one meaning)."""

from __future__ import annotations

import ast
from collections import defaultdict
from pathlib import Path

from layering import modules, rendering_importers

ROOT = Path(__file__).resolve().parents[1]
SCENE = "app.scene"
#: Names several modules may define, each with the reason.
SHARED_NAMES = {"main": "the entry point of a command line (app.__main__ and app.cli)"}


def plotter_reads(root: Path) -> list[str]:
    """'module:line' of every `.plotter` attribute read in app modules outside the scene."""
    found = []
    for name, path in modules(root, ("app",)).items():
        if name == SCENE or name.startswith(SCENE + "."):
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        found.extend(f"{name}:{node.lineno}" for node in ast.walk(tree)
                     if isinstance(node, ast.Attribute) and node.attr == "plotter")
    return found


def top_level_names(root: Path) -> dict[str, list[str]]:
    """Function or class name -> the app modules defining it at top level."""
    seen: dict[str, list[str]] = defaultdict(list)
    for name, path in modules(root, ("app",)).items():
        for node in ast.parse(path.read_text(encoding="utf-8")).body:
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                seen[node.name].append(name)
    return seen


def test_only_the_scene_imports_vtk_pyvista_or_pyvistaqt() -> None:
    importers = rendering_importers(ROOT, "app")
    assert [name for name in importers if not name.startswith(SCENE + ".")] == []
    assert {"app.scene.view", "app.scene.interactive"} <= set(importers)  # the rule is seen


def test_only_the_scene_touches_the_plotter() -> None:
    assert plotter_reads(ROOT) == []


def test_no_two_app_modules_define_the_same_name() -> None:
    twice = {name: where for name, where in top_level_names(ROOT).items()
             if len(where) > 1 and name not in SHARED_NAMES}
    assert twice == {}


def test_the_rules_can_fail(tmp_path: Path) -> None:
    """A module outside the scene importing pyvista, reading a plotter, or repeating a name
    is caught."""
    (tmp_path / "app").mkdir()
    (tmp_path / "app" / "__init__.py").write_text("")
    (tmp_path / "app" / "menus.py").write_text(
        "import pyvista as pv\n\ndef export_shape(window):\n    window.plotter.render()\n")
    (tmp_path / "app" / "file_actions.py").write_text("def export_shape(ac, path):\n    pass\n")
    assert rendering_importers(tmp_path, "app") == ["app.menus"]
    assert plotter_reads(tmp_path) == ["app.menus:4"]
    assert top_level_names(tmp_path)["export_shape"] == ["app.file_actions", "app.menus"]

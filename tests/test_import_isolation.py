"""`import core` must not load any GUI or rendering module (core never imports Qt or VTK)."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

FORBIDDEN = ("PySide6", "pyvista", "pyvistaqt", "vtk", "vtkmodules", "qtpy", "matplotlib")
IMPORT_ALL_CORE = (
    "import core, importlib, pkgutil\n"
    "for info in pkgutil.walk_packages(core.__path__, 'core.'):\n"
    "    importlib.import_module(info.name)"
)


def loaded_top_modules(statement: str) -> set[str]:
    """Top-level package names in sys.modules after running statement in a fresh python."""
    code = f"import json, sys\n{statement}\nprint(json.dumps(sorted(sys.modules)))"
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=120
    )
    return {name.split(".")[0] for name in json.loads(result.stdout.splitlines()[-1])}


@pytest.mark.parametrize("statement", ["import core", IMPORT_ALL_CORE])
def test_core_imports_no_gui_modules(statement: str) -> None:
    """Importing core (alone, or every core module) pulls in none of the forbidden packages."""
    loaded = loaded_top_modules(statement)
    assert "core" in loaded
    assert loaded.isdisjoint(FORBIDDEN), sorted(loaded & set(FORBIDDEN))


def test_the_check_can_fail() -> None:
    """The detector sees a forbidden module when one is imported (guards against a blind test)."""
    assert "vtkmodules" in loaded_top_modules("import vtkmodules.vtkCommonCore")


def test_cli_entry_imports_no_qt() -> None:
    """The entry module keeps Qt out of its top level, so `alphascoop info` runs without Qt."""
    loaded = loaded_top_modules("import app.__main__")
    assert loaded.isdisjoint({"PySide6", "pyvista", "pyvistaqt", "vtkmodules", "qtpy"})

"""Layering rules for core and app, read from the source (tests/layering.py): no import cycles
(not even under TYPE_CHECKING or inside functions), no reads of another object's private
attributes, no `__dict__` tricks. Next to test_import_isolation (core never imports Qt/VTK)."""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest
from layering import cycles, dict_uses, import_graph, private_reads, rendering_importers, report

ROOT = Path(__file__).resolve().parents[1]


def test_no_import_cycles_in_core_or_app() -> None:
    found = cycles(import_graph(ROOT))
    assert not found, f"import cycles: {found}"


def test_no_object_reads_another_objects_private_attributes() -> None:
    found = private_reads(ROOT)
    assert not found, "\n".join(map(str, found))


def test_no_dict_tricks() -> None:
    found = dict_uses(ROOT)
    assert not found, "\n".join(map(str, found))


def test_core_modules_import_no_vtk() -> None:
    assert rendering_importers(ROOT, "core") == []


def _package(root: Path, files: dict[str, str]) -> Path:
    """A synthetic `core` package under root with the given module sources."""
    for name, source in {"core/__init__.py": "", **files}.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(source), encoding="utf-8")
    return root


@pytest.mark.parametrize("b_source", [
    "from . import a\n",
    "from core.a import thing\n",
    "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from .a import thing\n",
    "def late():\n    from core import a\n    return a\n",
    "import core.a\n",
])
def test_a_cycle_is_found_however_it_is_imported(tmp_path: Path, b_source: str) -> None:
    root = _package(tmp_path, {"core/a.py": "from .b import late\nthing = 1\n",
                               "core/b.py": b_source})
    assert cycles(import_graph(root, ("core",))) == [["core.a", "core.b"]]


def test_no_cycle_when_imports_go_one_way(tmp_path: Path) -> None:
    root = _package(tmp_path, {"core/a.py": "from .b import x\n", "core/b.py": "x = 1\n",
                               "core/sub/__init__.py": "from ..a import x\n"})
    graph = import_graph(root, ("core",))
    assert graph["core.sub"] == {"core.a"} and cycles(graph) == []


def test_private_reads_on_other_objects_are_found(tmp_path: Path) -> None:
    root = _package(tmp_path, {"core/m.py": """\
        import collections
        from .other import Thing

        def _helper():
            return 1

        class Mine:
            def __init__(self, other):
                self._own = _helper()
                self._other = other
                super().__init__()

            def peek(self):
                return self._other._secret, Thing()._table, self._own, self.__class__

            @classmethod
            def make(cls):
                return cls._factory()

        point = collections.namedtuple("P", "x")(1)._replace(x=2)
        """, "core/other.py": "class Thing:\n    _table = 1\n"})
    found = private_reads(root, ("core",))
    assert sorted(f.text for f in found) == ["private attribute read Thing()._table",
                                            "private attribute read self._other._secret"]
    assert {(f.path, f.line) for f in found} == {("core/m.py", 14)}


def test_dict_uses_are_found(tmp_path: Path) -> None:
    root = _package(tmp_path, {"core/m.py": """\
        class C:
            def fill(self, other):
                self.__dict__["x"] = 1
                return "y" in other.__dict__, vars(other)
        """})
    assert sorted(f.line for f in dict_uses(root, ("core",))) == [3, 4, 4]


def test_the_report_counts_what_the_rules_find(tmp_path: Path) -> None:
    root = _package(tmp_path, {"core/a.py": "from . import b\nimport vtk\n",
                               "core/b.py": "from . import a\nx = a._y\n",
                               "app/__init__.py": "", "app/v.py": "import pyvista\n"})
    figures = report(root)
    assert figures["import cycles"] == 1 and figures["private reads"] == 1
    assert figures["core modules importing vtk/pyvista"] == 1
    assert figures["app modules importing vtk/pyvista"] == 1

"""The window's exports: never over the open file, and what the export dialog offers."""

from __future__ import annotations

import os

import numpy as np
import pytest
from conftest import BUILD_TIMEOUT_MS, fake_export_dialog, open_and_wait

from core import AlphaComplex
from core.export import write_shape, write_table

pytestmark = pytest.mark.gui


@pytest.fixture
def scan(tmp_path):
    """b.ply and b.npz in tmp_path: a small closed surface and a table, both readable."""
    ac = AlphaComplex.from_points(np.random.default_rng(9).normal(size=(120, 3)))
    write_shape(ac, 10.0, tmp_path / "b.ply")
    write_table(ac, tmp_path / "b.npz")
    return tmp_path


def other_name(path, form: str):
    """The same file on disk through another path."""
    if form == "dotdot":
        (path.parent / "sub").mkdir(exist_ok=True)
        return path.parent / "sub" / ".." / path.name
    if form == "same":
        return path
    other = path.parent / f"link{path.suffix}"
    (os.symlink if form == "symlink" else os.link)(path, other)
    return other


@pytest.mark.parametrize("form", ["same", "dotdot", "symlink", "hardlink"])
@pytest.mark.parametrize(("action", "name"), [("export_shape", "b.ply"),
                                              ("export_table", "b.npz")])
def test_export_over_the_open_file_is_refused(window, qtbot, scan, monkeypatch, action, name,
                                              form):
    source = scan / name
    open_and_wait(qtbot, window, source)
    before = source.read_bytes()
    target = other_name(source, form)
    monkeypatch.setattr("app.file_actions.QFileDialog.getSaveFileName",
                        lambda *args, **kwargs: (str(target), ""))
    monkeypatch.setattr("app.export_dialog.run_dialog", fake_export_dialog(target))
    warnings: list[str] = []
    monkeypatch.setattr("app.menus.QMessageBox.warning", lambda *args: warnings.append(args[-1]))
    window.menus[action].trigger()
    qtbot.waitUntil(lambda: not window.jobs.is_busy(), timeout=BUILD_TIMEOUT_MS)
    assert len(warnings) == 1 and "input file" in warnings[0]
    assert not window.job_progress.isVisible(), "no export was started"
    assert source.read_bytes() == before


def shell_file(folder):
    """A thick spherical shell (.npy) whose shape at ALPHA pinches: non-manifold edges."""
    rng = np.random.default_rng(1)
    p = rng.normal(size=(600, 3))
    p *= rng.uniform(0.7, 1.0, (600, 1)) / np.linalg.norm(p, axis=1, keepdims=True)
    np.save(folder / "shell.npy", p)
    return folder / "shell.npy"


ALPHA = 0.25


def most_faces_on_an_edge(path) -> int:
    import trimesh

    mesh = trimesh.load(str(path), process=False, force="mesh")
    edges = np.sort(mesh.faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    return int(np.unique(edges, axis=0, return_counts=True)[1].max())


def export_via_dialog(qtbot, window, monkeypatch, target, manifold=None) -> tuple:
    """Export shape through the dialog; returns (default file name, box state) it showed."""
    seen: list = []
    monkeypatch.setattr("app.export_dialog.run_dialog",
                        fake_export_dialog(target, manifold=manifold, seen=seen))
    warnings: list[str] = []
    monkeypatch.setattr("app.menus.QMessageBox.warning", lambda *args: warnings.append(args[-1]))
    with qtbot.waitSignal(window.jobs.finished, timeout=BUILD_TIMEOUT_MS):
        window.menus["export_shape"].trigger()
    assert warnings == []
    return seen[0]


def test_export_dialog_offers_manifold_and_names_the_alpha(window, qtbot, tmp_path,
                                                           monkeypatch):
    open_and_wait(qtbot, window, shell_file(tmp_path))
    window.model.set_alpha(ALPHA)
    alpha = window.model.alpha
    name, box = export_via_dialog(qtbot, window, monkeypatch, tmp_path / "m.ply")
    assert os.path.basename(name) == f"shell_alpha{alpha:.4g}.ply" and box is True
    assert most_faces_on_an_edge(tmp_path / "m.ply") == 2
    assert "split" in window.status.text()
    _, box = export_via_dialog(qtbot, window, monkeypatch, tmp_path / "raw", manifold=False)
    assert box is True and most_faces_on_an_edge(tmp_path / "raw.ply") > 2
    _, box = export_via_dialog(qtbot, window, monkeypatch, tmp_path / "again.ply")
    assert box is False, "the choice is remembered"


def test_dialog_adds_the_selected_formats_extension(qtbot, tmp_path):
    from app.export_dialog import ExportShapeDialog

    dialog = ExportShapeDialog(None, tmp_path / "shell_alpha0.25.ply", True)
    qtbot.addWidget(dialog)
    dialog.selectNameFilter(next(f for f in dialog.nameFilters() if "(*.stl)" in f))
    assert dialog.chosen_path() == tmp_path / "shell_alpha0.25.stl", "the alpha stays whole"
    dialog.selectFile(str(tmp_path / "x.obj"))
    assert dialog.chosen_path() == tmp_path / "x.obj"
    dialog.selectFile(str(tmp_path / "typed_without_extension"))
    assert dialog.chosen_path() == tmp_path / "typed_without_extension.stl"

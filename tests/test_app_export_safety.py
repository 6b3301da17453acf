"""The window's exports: never over the open file, and what the export dialog offers."""

from __future__ import annotations

import os

import numpy as np
import pytest
from conftest import BUILD_TIMEOUT_MS, open_and_wait

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
    warnings: list[str] = []
    monkeypatch.setattr("app.menus.QMessageBox.warning", lambda *args: warnings.append(args[-1]))
    window.menus[action].trigger()
    qtbot.waitUntil(lambda: not window.jobs.is_busy(), timeout=BUILD_TIMEOUT_MS)
    assert len(warnings) == 1 and "input file" in warnings[0]
    assert not window.job_progress.isVisible(), "no export was started"
    assert source.read_bytes() == before

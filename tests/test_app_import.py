"""The window reads files like the command line: --columns/--subsample, and an import dialog
(columns detected, preview, geographic or not; subsampling) remembered per file type."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from conftest import BUILD_TIMEOUT_MS
from PIL import Image

from app.__main__ import window_parser
from app.dataset import ImportOptions

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture
def table_csv(tmp_path) -> Path:
    """lon,lat,alt,intensity rows around Zurich (3D in metres only via --columns)."""
    rng = np.random.default_rng(3)
    rows = np.column_stack([8.5 + rng.uniform(0, 0.01, 400), 47.37 + rng.uniform(0, 0.01, 400),
                            400 + rng.uniform(0, 30, 400), rng.integers(0, 255, 400)])
    path = tmp_path / "survey.csv"
    np.savetxt(path, rows, delimiter=",", header="lon,lat,alt,intensity", comments="",
               fmt=["%.6f", "%.6f", "%.2f", "%d"])
    return path


@pytest.fixture
def plain_xyz(tmp_path) -> Path:
    path = tmp_path / "cloud.xyz"
    np.savetxt(path, np.random.default_rng(4).normal(size=(600, 4)))
    return path


def answer(**choice):
    """A stand-in for app.modal.run_dialog that fills the import dialog as a user would;
    `seen` gets the options the dialog proposed before that."""
    seen = []

    def run(dialog) -> bool:
        seen.append(dialog.options())  # what the dialog proposed
        if "columns" in choice:
            dialog.columns.setText(choice["columns"])
        if "subsample" in choice:
            dialog.subsample.setChecked(choice["subsample"] is not None)
            if choice["subsample"]:
                dialog.count.setValue(choice["subsample"])
        if "method" in choice:
            dialog.method.setCurrentText(choice["method"])
        return choice.get("accept", True)
    return run, seen


def test_dialog_shows_columns_preview_and_geography(qtbot, table_csv):
    from app.import_dialog import ImportDialog

    dialog = ImportDialog(None, table_csv)
    qtbot.addWidget(dialog)
    header = [dialog.table.horizontalHeaderItem(c).text() for c in range(4)]
    assert header == ["0: lon", "1: lat", "2: alt", "3: intensity"]
    assert dialog.table.rowCount() == 8
    first = np.loadtxt(table_csv, delimiter=",", skiprows=1, max_rows=1)
    assert float(dialog.table.item(0, 0).text()) == pytest.approx(first[0])
    assert "lon,lat,alt" in dialog.detected.text() and dialog.is_geographic()
    dialog.columns.setText("alt,intensity")
    assert not dialog.is_geographic()
    dialog.columns.setText("1,0")
    assert dialog.is_geographic(), "columns by index resolve to lat,lon"
    assert dialog.options() == ImportOptions(columns="1,0")


def test_headerless_file_says_so(qtbot, plain_xyz):
    from app.import_dialog import ImportDialog

    dialog = ImportDialog(None, plain_xyz)
    qtbot.addWidget(dialog)
    assert "no header" in dialog.detected.text() and not dialog.is_geographic()
    assert dialog.table.columnCount() == 4 and dialog.table.rowCount() == 8
    assert dialog.options() == ImportOptions()


def test_big_files_offer_subsampling(qtbot, tmp_path, monkeypatch):
    import app.import_dialog as import_dialog

    path = tmp_path / "big.npy"
    np.save(path, np.random.default_rng(5).normal(size=(3000, 3)))
    assert not import_dialog.needs_dialog(path)
    monkeypatch.setattr(import_dialog, "BIG_FILE_BYTES", 1000)
    assert import_dialog.needs_dialog(path)
    dialog = import_dialog.ImportDialog(None, path)
    qtbot.addWidget(dialog)
    assert dialog.subsample.isChecked() and not dialog.columns.isEnabled()
    dialog.method.setCurrentText("random")
    assert dialog.options() == ImportOptions(subsample=1_000_000, subsample_method="random")


def test_window_passes_the_dialogs_choice_and_remembers_it(window, qtbot, plain_xyz,
                                                           monkeypatch):
    run, seen = answer(columns="0,1", subsample=150, method="random")
    monkeypatch.setattr("app.import_dialog.run_dialog", run)
    with qtbot.waitSignal(window.model.datasetChanged, timeout=BUILD_TIMEOUT_MS):
        window.open_asking(plain_xyz)
    ds = window.model.dataset
    assert ds.ac.dim == 2 and ds.report.n_points == 150
    run, seen = answer()
    monkeypatch.setattr("app.import_dialog.run_dialog", run)
    with qtbot.waitSignal(window.model.datasetChanged, timeout=BUILD_TIMEOUT_MS):
        window.open_asking(plain_xyz)
    again = seen[0]
    assert again == ImportOptions(columns="0,1", subsample=150, subsample_method="random")
    assert window.prefs.import_options(".csv") == ("", 0, "voxel"), "per file type"


def test_cancelling_the_dialog_opens_nothing(window, qtbot, plain_xyz, monkeypatch):
    run, _ = answer(accept=False)
    monkeypatch.setattr("app.import_dialog.run_dialog", run)
    before = window.loader.current
    assert window.open_asking(plain_xyz) is None
    assert window.loader.current == before and window.model.dataset is None


def test_files_without_choices_open_without_the_dialog(window, qtbot, tmp_path, monkeypatch):
    monkeypatch.setattr("app.import_dialog.run_dialog",
                        lambda dialog: pytest.fail("no dialog for a small binary file"))
    path = tmp_path / "p.npy"
    np.save(path, np.random.default_rng(6).normal(size=(200, 3)))
    with qtbot.waitSignal(window.model.datasetChanged, timeout=BUILD_TIMEOUT_MS):
        window.open_asking(path)


def test_window_command_line_reads_with_columns_and_subsample(qtbot, table_csv, monkeypatch):
    import shiboken6
    from PySide6.QtWidgets import QApplication

    import app.launch as launch
    from app.main_window import MainWindow

    opened = []
    monkeypatch.setattr(MainWindow, "open_path", lambda self, path, options=None:
                        opened.append((self, Path(path), options)))
    monkeypatch.setattr(QApplication, "exec", lambda self: 0)
    args = window_parser().parse_args([str(table_csv), "--columns", "alt,lon",
                                      "--subsample", "90"])
    try:
        assert launch.run_window(args) == 0
    finally:  # run_window closes and deletes its window itself when it returns
        for window, *_ in opened:
            if shiboken6.isValid(window):
                window.close()
    assert opened[0][1:] == (table_csv, ImportOptions(columns="alt,lon", subsample=90))


def test_load_dataset_honours_the_options(table_csv):
    from app.dataset import load_dataset
    from core.obtain import run_here

    ds = load_dataset(table_csv, lambda f, s: None, run_here,
                      options=ImportOptions(columns="lon,lat,alt", subsample=120))
    assert ds.ac.dim == 3 and ds.report.n_points <= 120


def test_screenshot_mode_takes_columns_and_subsample(tmp_path, table_csv):
    out = tmp_path / "shot.png"
    result = subprocess.run(
        [sys.executable, "-m", "app", str(table_csv), "--columns", "alt,intensity",
         "--subsample", "100", "--screenshot", str(out), "--size", "200x160"],
        capture_output=True, text=True, timeout=300, cwd=ROOT,
        env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin",
             "ALPHASCOOP_CACHE_DIR": str(tmp_path / "cache"), "QT_QPA_PLATFORM": "offscreen",
             "VTK_DEFAULT_OPENGL_WINDOW": "vtkEGLRenderWindow"})
    assert result.returncode == 0, result.stderr
    assert np.asarray(Image.open(out)).shape[:2] == (160, 200)
    bad = subprocess.run(
        [sys.executable, "-m", "app", str(table_csv), "--columns", "nope,lat",
         "--screenshot", str(out)], capture_output=True, text=True, timeout=300, cwd=ROOT,
        env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin",
             "ALPHASCOOP_CACHE_DIR": str(tmp_path / "cache"),
             "VTK_DEFAULT_OPENGL_WINDOW": "vtkEGLRenderWindow"})
    assert bad.returncode == 1 and "nope" in bad.stderr and len(bad.stderr.splitlines()) == 1

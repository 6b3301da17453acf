"""Explore a subsample, export at full resolution: the window's banner for a subsample, and
File → Export at full resolution… (the tiled export of every point, in the background)."""

from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np
import psutil
import pytest
from conftest import BUILD_TIMEOUT_MS, fake_export_dialog, wait_for_topology

from app.cli import main
from app.dataset import ImportOptions

pytest.importorskip("distributed")
pytestmark = pytest.mark.gui

SHARED = Path(__file__).resolve().parents[2] / "shared" / "data"
SHARED = SHARED if SHARED.is_dir() else Path("/work/shared/data")
SUBSAMPLE = 4000
ALPHA = 3.0  # feet: a few point spacings of the crop


@pytest.fixture
def crop(tmp_path) -> Path:
    """A 15,000-point crop of a real airborne LiDAR tile (autzen_trim.las), as a LAS file
    with its CRS records (read again by each open and by the export)."""
    import laspy

    src = SHARED / "autzen_trim.las"
    if not src.exists():
        pytest.skip(f"{src} is not here")
    las = laspy.read(src)
    x = np.asarray(las.x)
    keep = np.argsort(x, kind="stable")[:15_000]
    header = las.header
    out = laspy.LasData(header)
    out.points = las.points[np.sort(keep)]
    path = tmp_path / "crop.las"
    out.write(path)
    return path


def open_subsample(qtbot, window, path: Path) -> None:
    """Open `path` subsampled as the import dialog would, and wait for its topology."""
    with qtbot.waitSignal(window.model.datasetChanged, timeout=BUILD_TIMEOUT_MS):
        window.open_path(path, ImportOptions(subsample=SUBSAMPLE))
    wait_for_topology(qtbot, window)


def start_full_export(window, monkeypatch, target: Path, warnings: list) -> None:
    """File → Export at full resolution… to `target`, the dialog answered as a user would."""
    monkeypatch.setattr("app.export_dialog.run_dialog", fake_export_dialog(target))
    for where in ("app.menus", "app.main_window"):
        monkeypatch.setattr(f"{where}.QMessageBox.warning",
                            lambda *args: warnings.append(args[-1]))
    window.menus["export_full"].trigger()


def workers_left(before: set[int]) -> list[list[str]]:
    """Command lines of this process's live children not in `before` (multiprocessing's
    resource tracker, started once and kept for the process's life, is not a worker)."""
    alive = [c for c in psutil.Process().children(recursive=True)
             if c.pid not in before and c.is_running() and c.status() != psutil.STATUS_ZOMBIE]
    return [c.cmdline() for c in alive if "resource_tracker" not in " ".join(c.cmdline())]


def test_a_subsample_shows_the_banner(window, qtbot, crop):
    open_subsample(qtbot, window, crop)
    assert window.banner.isVisible()
    shown = window.model.dataset.report.n_points
    assert 0 < shown <= SUBSAMPLE
    assert f"Subsample: {shown:,} of 15,000 points" in window.banner.text()
    assert "Export at full resolution" in window.banner.text()
    with qtbot.waitSignal(window.model.datasetChanged, timeout=BUILD_TIMEOUT_MS):
        window.open_path(crop, ImportOptions())
    assert not window.banner.isVisible(), "every point read: no banner"


def test_full_export_equals_the_tiled_command(window, qtbot, crop, tmp_path, monkeypatch,
                                              capsys):
    open_subsample(qtbot, window, crop)
    window.model.set_alpha(ALPHA)
    alpha = window.model.alpha
    target, warnings = tmp_path / "full.ply", []
    with qtbot.waitSignal(window.jobs.finished, timeout=BUILD_TIMEOUT_MS):
        start_full_export(window, monkeypatch, target, warnings)
    assert warnings == []
    assert "tiled:" in window.status.text()
    command = tmp_path / "command.ply"
    assert main(["export", str(crop), "-o", str(command), "--alpha", repr(alpha),
                 "--tiled"]) == 0, capsys.readouterr().err
    assert target.read_bytes() == command.read_bytes()
    assert len(target.read_bytes()) > 10_000, "a real surface, not an empty file"


def test_cancel_leaves_nothing_half_written(window, qtbot, crop, tmp_path, monkeypatch):
    scratch = tmp_path / "scratch"
    scratch.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(scratch))
    open_subsample(qtbot, window, crop)
    out = tmp_path / "out"
    out.mkdir()
    target = out / "full.ply"
    target.write_bytes(b"the user's old file")
    before = {c.pid for c in psutil.Process().children(recursive=True)}
    cancelled: list = []
    window.jobs.cancelled.connect(lambda request: cancelled.append(request))

    def cancel_once_the_workers_start(_request, _fraction, stage):
        if stage == "starting the workers":
            window.job_progress.cancel.click()

    window.jobs.progress.connect(cancel_once_the_workers_start)
    warnings: list = []
    start_full_export(window, monkeypatch, target, warnings)
    qtbot.waitUntil(lambda: bool(cancelled), timeout=BUILD_TIMEOUT_MS)
    assert warnings == []
    assert "cancelled; nothing was written" in window.status.text()
    assert target.read_bytes() == b"the user's old file"
    assert sorted(p.name for p in out.iterdir()) == ["full.ply"], "no temporary left"
    assert list(scratch.iterdir()) == [], "the tile files are removed"
    assert workers_left(before) == [], "the cluster's workers are gone"


def test_a_failed_export_says_why_in_one_line(window, qtbot, crop, tmp_path, monkeypatch):
    open_subsample(qtbot, window, crop)
    crop.write_bytes(b"no longer a LAS file")
    target, warnings = tmp_path / "full.ply", []
    with qtbot.waitSignal(window.jobs.failed, timeout=BUILD_TIMEOUT_MS):
        start_full_export(window, monkeypatch, target, warnings)
    qtbot.waitUntil(lambda: bool(warnings), timeout=5_000)
    assert len(warnings) == 1 and "crop.las" in warnings[0] and "\n" not in warnings[0]
    assert not target.exists()


def test_a_scan_above_the_memory_budget_is_offered_as_a_subsample(qtbot, crop, monkeypatch):
    """A LAS/LAZ file small on disk (compressed) but with more points than the window can
    build gets the import dialog, subsample checked."""
    import app.import_dialog as import_dialog

    assert not import_dialog.needs_dialog(crop)
    monkeypatch.setattr("app.full_export.window_points", lambda: 14_999)
    assert import_dialog.needs_dialog(crop)
    dialog = import_dialog.ImportDialog(None, crop)
    qtbot.addWidget(dialog)
    assert dialog.subsample.isChecked()

"""Alpha modes outside the core: the CLI options, info/export metadata, the cache, the window's
mode dock (a background rebuild keeps the old shape until the new table is ready)."""

from __future__ import annotations

import json

import numpy as np
import pytest
from conftest import BUILD_TIMEOUT_MS, open_and_wait

from app.cli import main
from core.modes.alpha_modes import Mode, make_mode


@pytest.fixture(autouse=True)
def cache(tmp_path, monkeypatch):
    """Every test gets its own empty table cache."""
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))
    return tmp_path / "cache"


def _sheets_file(folder, with_normals: bool) -> str:
    """Two close noisy sheets as .npz (points, and normals when asked)."""
    rng = np.random.default_rng(0)
    axis = np.arange(10.0)
    grid = np.stack(np.meshgrid(axis, axis), axis=-1).reshape(-1, 2)
    grid = grid + rng.uniform(-0.25, 0.25, grid.shape)
    points = np.vstack([np.column_stack([grid, rng.normal(0, 0.02, len(grid))]),
                        np.column_stack([grid + 0.3, 0.5 + rng.normal(0, 0.02, len(grid))])])
    path = folder / ("sheets_n.npz" if with_normals else "sheets.npz")
    arrays = {"points": points}
    if with_normals:
        arrays["normals"] = np.tile([0.0, 0.0, 1.0], (len(points), 1))
    np.savez(path, **arrays)
    return str(path)


def run(capsys, *argv) -> tuple[int, str, str]:
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def test_info_reports_the_mode(tmp_path, capsys):
    path = _sheets_file(tmp_path, True)
    code, out, _ = run(capsys, "info", path, "--density", "6", "--combine", "max")
    assert code == 0
    assert "mode        density-scaled (k=6, max; alpha in local spacings)" in out
    code, out, _ = run(capsys, "info", path, "--anisotropic", "0.8", "--normals", "file",
                       "--json")
    info = json.loads(out)
    assert code == 0 and info["mode"] == {"name": "anisotropic", "density": None,
                                          "combine": "mean", "anisotropy": 0.8,
                                          "normals": "given"}
    assert info["complex"]["from_cache"] is False
    code, out, _ = run(capsys, "info", path, "--json")
    assert json.loads(out)["mode"]["name"] == "classic"


def test_modes_are_cached_apart(tmp_path, capsys):
    path = _sheets_file(tmp_path, False)
    firsts = []
    for options in ([], ["--density", "8"], ["--density", "8", "--combine", "max"],
                    ["--anisotropic", "0.5"]):
        for _ in range(2):
            code, out, _ = run(capsys, "info", path, "--json", *options)
            assert code == 0
            firsts.append(json.loads(out)["complex"]["from_cache"])
    assert firsts == [False, True] * 4


def test_export_metadata_names_the_mode(tmp_path, capsys):
    path = _sheets_file(tmp_path, False)
    out_file = tmp_path / "shape.ply"
    code, _, err = run(capsys, "export", path, "-o", out_file, "--anisotropic", "0.7",
                         "--sidecar")
    assert code == 0, err
    meta = json.loads((tmp_path / "shape.ply.json").read_text())
    assert meta["mode"]["name"] == "anisotropic" and meta["mode"]["anisotropy"] == 0.7
    table = tmp_path / "table.npz"
    code, _, err = run(capsys, "export", path, "-o", table, "--table", "--density", "4")
    assert code == 0, err
    with np.load(table) as data:
        assert json.loads(str(data["mode"]))["density"] == 4


@pytest.mark.parametrize("argv, status, words", [
    (["--combine", "max"], 2, "--combine needs --density"),
    (["--normals", "file"], 2, "--normals needs --anisotropic"),
    (["--anisotropic", "1"], 2, "TAU must be in [0, 1)"),
    (["--density", "0"], 2, "K must be a whole number"),
    (["--anisotropic", "0.5", "--normals", "file"], 1, "has no normals"),
])
def test_bad_mode_options_are_one_line(tmp_path, capsys, argv, status, words):
    code, _, err = run(capsys, "info", _sheets_file(tmp_path, False), *argv)
    assert code == status and words in err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_window_rebuilds_in_a_mode_keeping_the_old_shape(window, qtbot, tmp_path):
    path = _sheets_file(tmp_path, True)
    open_and_wait(qtbot, window, path)
    classic = window.model.dataset
    assert classic.ac.mode == Mode()
    panel = window.mode_panel
    panel.kind.setCurrentIndex(2)
    panel.tau.setValue(0.8)
    panel.normals.setCurrentText("file")
    assert not panel.neighbours.isEnabled() and panel.tau.isEnabled()
    with qtbot.waitSignal(window.model.datasetChanged, timeout=BUILD_TIMEOUT_MS):
        panel.rebuild.click()
        assert window.model.dataset is classic  # the old shape stays meanwhile
        assert window.progress.isVisible()
    assert window.model.dataset.ac.mode == make_mode(None, "mean", 0.8, True)
    assert "anisotropic (tau=0.8, given normals)" in window.info_panel.data.text()
    assert "anisotropic" in panel.built.text()
    assert window.model.dataset.path == classic.path
    open_and_wait(qtbot, window, path)  # later opens keep the chosen mode
    assert window.model.dataset.ac.mode.anisotropy == 0.8


def test_window_keeps_the_shown_mode_when_a_rebuild_fails(window, qtbot, tmp_path,
                                                          monkeypatch):
    from PySide6.QtWidgets import QMessageBox

    warnings = []
    monkeypatch.setattr(QMessageBox, "warning", lambda *args: warnings.append(args[2]))
    open_and_wait(qtbot, window, _sheets_file(tmp_path, False))
    shown = window.model.dataset
    with qtbot.waitSignal(window.loader.failed, timeout=BUILD_TIMEOUT_MS):
        window.set_mode(make_mode(None, "mean", 0.5, True))  # the file has no normals
    assert window.model.dataset is shown and "has no normals" in warnings[0]
    assert window.mode == Mode() and window.mode_panel.mode() == Mode()


def test_child_process_builds_in_the_mode(tmp_path, monkeypatch):
    import threading

    from app import build_process
    from core import AlphaComplex
    from core.obtain import obtain

    monkeypatch.setattr(build_process, "IN_THREAD_BELOW", 10)  # take the child-process path
    with np.load(_sheets_file(tmp_path, True)) as data:
        points, normals = data["points"], data["normals"] * -1.0
    mode = make_mode(4, "max", 0.6, True)
    for use_cache in (False, True, True):  # the last one loads the cached entry
        ac = obtain(points, mode=mode, normals=normals, signatures=True, use_cache=use_cache,
                    runner=build_process.ChildRunner(threading.Event())).complex
        assert ac.mode == mode
        direct = AlphaComplex.from_points(points, **mode.build_kwargs(normals))
        assert np.array_equal(ac.intervals(3), direct.intervals(3))

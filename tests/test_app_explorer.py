"""The explorer window end to end: open like a user, move alpha with keys, check every layer."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import BUILD_TIMEOUT_MS, fake_export_dialog, image_contrast, open_and_wait
from PySide6.QtCore import Qt
from reference import data_dir, needs_data

MIN_CONTRAST = 10.0
SINGULAR, REGULAR = 1, 2


def blobs_3d(n: int = 1200, seed: int = 1) -> np.ndarray:
    """(n, 3) noisy solid ring plus a separate ball: tunnels, components, singular bits."""
    rng = np.random.default_rng(seed)
    angle = rng.uniform(0, 2 * np.pi, n // 2)
    tube = rng.normal(scale=0.15, size=(n // 2, 3))
    ring = np.column_stack([np.cos(angle), np.sin(angle), np.zeros(n // 2)]) + tube
    ball = rng.normal(scale=0.3, size=(n - n // 2, 3)) + np.array([3.0, 0.0, 0.0])
    return np.concatenate([ring, ball])


def disc_2d(n: int = 600, seed: int = 2) -> np.ndarray:
    """(n, 2) points of an annulus: a 2D shape with a hole."""
    rng = np.random.default_rng(seed)
    angle, radius = rng.uniform(0, 2 * np.pi, n), np.sqrt(rng.uniform(0.25, 1.0, n))
    return np.column_stack([radius * np.cos(angle), radius * np.sin(angle)])


@pytest.fixture
def points_file(tmp_path):
    """Write an (n, d) array to tmp_path as .npy; returns the path."""
    def write(points: np.ndarray, name: str = "points.npy"):
        path = tmp_path / name
        np.save(path, points)
        return path
    return write


def wait_for(signal, timeout_ms: int = BUILD_TIMEOUT_MS) -> None:
    """Spin the event loop until signal fires (module fixtures cannot use qtbot); fail when
    it has not within timeout_ms."""
    from PySide6.QtCore import QEventLoop, QTimer

    loop, fired, timer = QEventLoop(), [], QTimer()

    def arrived(*_args) -> None:
        fired.append(True)
        loop.quit()

    signal.connect(arrived)
    timer.setSingleShot(True)
    timer.timeout.connect(loop.quit)
    timer.start(timeout_ms)
    try:
        loop.exec()
    finally:
        timer.stop()
        signal.disconnect(arrived)
    if not fired:
        pytest.fail(f"no {signal} within {timeout_ms / 1000:.0f} s")


@pytest.fixture(scope="module")
def shared_window(qapp, tmp_path_factory):
    """One window with the 3D test blobs open, shared by this module's read-mostly tests."""
    from PySide6.QtCore import QSettings
    from PySide6.QtTest import QTest

    from app.main_window import MainWindow

    folder = tmp_path_factory.mktemp("shared")
    win = MainWindow(QSettings(str(folder / "settings.ini"), QSettings.Format.IniFormat))
    win.resize(900, 650)
    win.show()
    QTest.qWaitForWindowExposed(win)
    path = folder / "blobs.npy"
    np.save(path, blobs_3d())
    win.open_path(path)
    wait_for(win.model.datasetChanged)
    assert win.model.dataset is not None, "the shared test dataset did not build"
    if not win.model.dataset.has_topology:
        wait_for(win.model.topologyChanged)
    assert win.model.dataset.signatures is not None, "the shared dataset has no topology"
    yield win
    win.close()


@pytest.fixture
def opened(shared_window, qtbot):
    """The shared window reset to its optimal alpha, every layer shown in default colours."""
    from app.palette import default_styles

    win = shared_window
    win.model.set_index(win.model.optimal_index())
    show_all_layers(win, default_styles(3))
    qtbot.wait(1)
    return win


def show_all_layers(win, styles) -> None:
    """Make every layer visible, in the given styles' colours and opacities."""
    for name, style in styles.items():
        win.layers_panel._edit(name, visible=True, colour=style.colour, opacity=style.opacity)


def layer_cells(layer) -> np.ndarray:
    """(k, s) connectivity a layer's VTK mesh holds (tets, triangles, lines or vertices)."""
    mesh = layer.mesh
    if layer.kind == "tets":
        assert set(mesh.celltypes.tolist()) <= {10}
        return mesh.cell_connectivity.reshape(-1, 4)
    cells, size = {"tris": (mesh.faces, 3), "lines": (mesh.lines, 2),
                   "verts": (mesh.verts, 1)}[layer.kind]
    return cells.reshape(-1, size + 1)[:, 1:]


def as_set(cells: np.ndarray) -> set[tuple[int, ...]]:
    """Simplices as a set of sorted vertex tuples (orientation and order ignored)."""
    return {tuple(row) for row in np.sort(np.asarray(cells), axis=1).tolist()}


def expected_layers(ac, alpha: float) -> dict[str, np.ndarray]:
    """Layer name -> simplices the core reports at alpha (shape and classify, independently)."""
    shape, dim = ac.shape(alpha), ac.dim
    facet_classes = ac.classify(alpha, dim - 1)
    expected = {
        "interior": shape.cells,
        "singular_edges": shape.singular(1),
        "singular_points": shape.singular(0).reshape(-1, 1),
    }
    if dim == 3:  # one surface: regular and singular triangles; the singular ones highlighted
        expected["surface"] = ac.simplices(2)[(facet_classes == REGULAR)
                                              | (facet_classes == SINGULAR)]
        expected["singular_highlight"] = ac.simplices(2)[facet_classes == SINGULAR]
    else:
        expected["boundary"] = ac.simplices(1)[facet_classes == REGULAR]
    return expected


def assert_layers_match(win) -> None:
    """Every shape layer's mesh holds exactly the simplices of its class at the model's alpha."""
    ac, alpha = win.model.dataset.ac, win.model.alpha
    for name, cells in expected_layers(ac, alpha).items():
        got = layer_cells(win.scene.layers[name])
        assert len(got) == len(cells), name
        assert as_set(got) == as_set(cells), name


def press(qtbot, win, key, times: int = 1) -> None:
    """Real key presses on the alpha slider, then wait for the model to settle."""
    before = win.model.index
    for _ in range(times):
        qtbot.keyClick(win.alpha_panel.slider, key)
    qtbot.waitUntil(lambda: win.model.index != before, timeout=5000)


def test_opens_at_default_alpha_with_matching_layers(window, qtbot, points_file) -> None:
    """A freshly opened file starts at the opening alpha (not empty, not the hull)."""
    open_and_wait(qtbot, window, points_file(blobs_3d(seed=3), "fresh.npy"))
    model = window.model
    assert model.alpha == model.dataset.ac.default_alpha()
    assert 0 < model.index < model.hull_index()
    assert window.alpha_panel.slider.value() == window.alpha_panel.travel.position(model.index)
    assert len(model.shape.cells) > 0
    show_all_layers(window, window.layers_panel.styles)
    assert_layers_match(window)


@pytest.mark.parametrize(("key", "direction"), [(Qt.Key.Key_Left, -1), (Qt.Key.Key_Right, 1)])
def test_arrow_keys_step_one_critical_value(opened, qtbot, key, direction) -> None:
    """An arrow key moves exactly one critical alpha; every layer follows."""
    start = opened.model.index
    press(qtbot, opened, key)
    assert opened.model.index == start + direction
    assert opened.model.alpha == opened.model.spectrum[start + direction]
    assert_layers_match(opened)


def test_page_keys_take_bigger_steps_and_layers_follow(opened, qtbot) -> None:
    """PageDown divides alpha by PAGE_FACTOR (snapped to the critical value at or below),
    PageUp multiplies it; the meshes change and still match."""
    from app.log_travel import PAGE_FACTOR

    model = opened.model
    start = model.index
    before = layer_cells(opened.scene.layers["interior"]).copy()
    press(qtbot, opened, Qt.Key.Key_PageDown)
    assert model.index < start - 1
    assert model.alpha <= model.spectrum[start] / PAGE_FACTOR < model.spectrum[model.index + 1]
    assert len(layer_cells(opened.scene.layers["interior"])) < len(before)
    assert_layers_match(opened)
    down = model.index
    press(qtbot, opened, Qt.Key.Key_PageUp)
    assert model.alpha <= model.spectrum[down] * PAGE_FACTOR < model.spectrum[model.index + 1]


def test_slider_steps_keep_the_same_actors(opened, qtbot) -> None:
    """Moving alpha swaps connectivity in place: no actor is added or replaced."""
    actors = dict(opened.scene.plotter.renderer.actors)
    press(qtbot, opened, Qt.Key.Key_Right, times=2)
    assert dict(opened.scene.plotter.renderer.actors) == actors


def test_typed_radius_snaps_to_the_shape_at_that_value(opened, qtbot) -> None:
    """Typing r selects the largest critical alpha <= r; the layers show that shape."""
    spectrum = opened.model.spectrum
    target = 0.5 * (spectrum[10] + spectrum[11])
    field = opened.alpha_panel.radius
    field.setFocus()
    field.selectAll()
    qtbot.keyClicks(field, f"{target:.12g}")
    qtbot.keyClick(field, Qt.Key.Key_Return)
    assert opened.model.index == 10
    assert_layers_match(opened)


def test_hull_and_optimal_buttons(opened, qtbot) -> None:
    """'Convex hull' shows every Delaunay cell; 'Optimal' returns to the optimal alpha."""
    qtbot.mouseClick(opened.alpha_panel.hull, Qt.MouseButton.LeftButton)
    ac = opened.model.dataset.ac
    assert len(layer_cells(opened.scene.layers["interior"])) == len(ac.simplices(ac.dim))
    qtbot.mouseClick(opened.alpha_panel.optimal, Qt.MouseButton.LeftButton)
    assert opened.model.index == opened.model.optimal_index()


def test_toggling_a_layer_hides_its_actor(opened, qtbot) -> None:
    """Unchecking a layer hides its actor; checking it shows it again, up to date."""
    row, actor = opened.layers_panel.rows["surface"], opened.scene.layers["surface"].actor
    row.visible.setChecked(False)
    assert not actor.GetVisibility()
    press(qtbot, opened, Qt.Key.Key_Right)
    row.visible.setChecked(True)
    assert actor.GetVisibility()
    assert_layers_match(opened)


def screenshot(win, qtbot) -> np.ndarray:
    """(h, w, 3) uint8 image of the view after one render."""
    win.scene.plotter.interactor.update()
    qtbot.wait(50)
    return win.scene.plotter.screenshot(return_img=True)


def test_screenshots_have_contrast_and_differ_between_alphas(opened, qtbot) -> None:
    """Two alphas give two different, non-blank pictures."""
    first = screenshot(opened, qtbot)
    qtbot.mouseClick(opened.alpha_panel.hull, Qt.MouseButton.LeftButton)
    second = screenshot(opened, qtbot)
    assert image_contrast(first) > MIN_CONTRAST and image_contrast(second) > MIN_CONTRAST
    assert np.abs(first.astype(int) - second.astype(int)).mean() > 1.0


def test_2d_data_gets_a_parallel_top_down_view(window, qtbot, points_file) -> None:
    """2D points: parallel projection looking down z, boundary drawn as edges."""
    open_and_wait(qtbot, window, points_file(disc_2d()))
    assert window.scene.plotter.camera.parallel_projection
    assert np.allclose(np.abs(window.scene.plotter.camera.direction), [0, 0, 1])
    assert window.scene.layers["boundary"].kind == "lines"
    assert set(window.layers_panel.rows) == set(window.scene.layers)
    assert "surface" not in window.layers_panel.rows
    assert "singular_highlight" not in window.layers_panel.rows
    assert_layers_match(window)


def test_bad_file_shows_error_and_keeps_previous_dataset(opened, qtbot, tmp_path, monkeypatch):
    """A broken file gives a readable dialog; the dataset on screen stays."""
    shown: list[str] = []
    monkeypatch.setattr("app.main_window.QMessageBox.warning",
                        lambda parent, title, text: shown.append(text))
    before = opened.model.dataset
    bad = tmp_path / "broken.ply"
    bad.write_bytes(b"ply\nformat binary_little_endian 1.0\nelement vertex 9\nend_header\n\x00")
    with qtbot.waitSignal(opened.loader.failed, timeout=BUILD_TIMEOUT_MS):
        opened.open_path(bad)
    assert len(shown) == 1 and "broken.ply" in shown[0] and "Traceback" not in shown[0]
    assert opened.model.dataset is before
    assert_layers_match(opened)


def test_cancel_leaves_the_window_usable(opened, qtbot, points_file) -> None:
    """Cancel during an open: nothing changes, and the slider still drives the old dataset."""
    before = opened.model.dataset
    with qtbot.waitSignal(opened.loader.cancelled, timeout=BUILD_TIMEOUT_MS):
        opened.open_path(points_file(blobs_3d(20_000, seed=5), "big.npy"))
        qtbot.mouseClick(opened.progress.cancel, Qt.MouseButton.LeftButton)
    assert opened.model.dataset is before
    assert not opened.progress.isVisible()
    press(qtbot, opened, Qt.Key.Key_Right)
    assert_layers_match(opened)


def test_newer_open_wins_over_older(window, qtbot, points_file) -> None:
    """Opening B while A is still loading shows B; A's late result is dropped."""
    first = points_file(blobs_3d(3000, seed=7), "a.npy")
    second = points_file(blobs_3d(800, seed=8), "b.npy")
    with qtbot.waitSignal(window.model.datasetChanged, timeout=BUILD_TIMEOUT_MS):
        window.open_path(first)
        window.open_path(second)
    window.loader.wait()
    qtbot.wait(50)
    assert window.model.dataset.path == second
    assert len(window.model.dataset.ac.points) == 800


def test_newer_open_kills_a_big_build_in_its_triangulation(window, qtbot, points_file,
                                                            monkeypatch) -> None:
    """Big builds run in a child process: a newer open stops the older one mid-Delaunay
    (it never finishes: no cache entry), and the newer dataset, built the same way, shows."""
    import multiprocessing

    from app import build_process
    from core.cache import entry_path

    monkeypatch.setattr(build_process, "IN_THREAD_BELOW", 0)
    big_points = blobs_3d(300_000, seed=10)
    big, small = points_file(big_points, "big.npy"), points_file(blobs_3d(900, seed=11), "s.npy")
    with qtbot.waitSignal(window.loader.progress, timeout=BUILD_TIMEOUT_MS,
                          check_params_cb=lambda r, f, stage: stage == "Delaunay triangulation"):
        first = window.open_path(big)
    with qtbot.waitSignals([window.loader.dropped, window.model.datasetChanged],
                           check_params_cbs=[lambda request, kind: kind == "cancelled", None],
                           timeout=BUILD_TIMEOUT_MS):
        window.open_path(small)
    window.loader.wait()
    assert window.model.dataset.path == small and first < window.loader.current
    assert not entry_path(big_points).exists()
    # the small one's build process may still write its entry, then ends (the big one is
    # gone: killed mid-Delaunay)
    qtbot.waitUntil(lambda: multiprocessing.active_children() == [], timeout=BUILD_TIMEOUT_MS)
    assert not entry_path(big_points).exists()
    show_all_layers(window, window.layers_panel.styles)
    press(qtbot, window, Qt.Key.Key_Right)
    assert_layers_match(window)


def test_reopening_loads_the_cached_table_and_says_so(window, qtbot, points_file,
                                                      monkeypatch) -> None:
    """The second open of the same points is a cache load, topology included."""
    import core.topology.betti

    path = points_file(blobs_3d(700, seed=12), "again.npy")
    open_and_wait(qtbot, window, path)
    first = window.model.dataset
    assert not first.from_cache and "built in" in window.status.text()

    def no_topology_pass(ac):
        raise AssertionError("re-opening recomputed the topology")

    monkeypatch.setattr(core.topology.betti, "build_topology", no_topology_pass)
    open_and_wait(qtbot, window, path)
    second = window.model.dataset
    assert second.from_cache and "loaded from cache in" in window.status.text()
    np.testing.assert_array_equal(second.signatures.betti, first.signatures.betti)
    assert second.optimal_alpha == first.optimal_alpha
    monkeypatch.undo()
    from core.cache import entry_path

    entry_path(np.load(path)).write_bytes(b"damaged")
    open_and_wait(qtbot, window, path)
    assert window.model.dataset.source == "rebuilt"
    said = "rebuilt (its cached table was damaged: not an .npz archive)"
    assert f"{said} in" in window.status.text()
    assert said in window.info_panel.data.text()


def test_signature_cursor_follows_alpha(opened, qtbot) -> None:
    """The signature plots' cursor sits at the current alpha after a key step."""
    panel = opened.signatures_panel
    assert opened.model.dataset.signatures is not None  # the fixture waited for them
    press(qtbot, opened, Qt.Key.Key_Right)
    assert panel.cursors
    for cursor in panel.cursors:
        assert cursor.get_xdata()[0] == pytest.approx(opened.model.alpha)


def run_file_action(qtbot, win, action: str) -> None:
    """Trigger a File menu action and wait until any background export it started is over."""
    win.menus[action].trigger()
    qtbot.waitUntil(lambda: not win.jobs.is_busy() and not win.job_progress.isVisible(),
                    timeout=BUILD_TIMEOUT_MS)


@pytest.mark.parametrize(("action", "name"), [("export_shape", "shape.ply"),
                                              ("export_table", "table.npz"),
                                              ("screenshot", "view.png")])
def test_file_menu_writes_and_reports(opened, qtbot, tmp_path, monkeypatch, action,
                                      name) -> None:
    """Export shape/table and screenshot write the chosen file and say what they wrote."""
    target = tmp_path / name
    monkeypatch.setattr("app.file_actions.QFileDialog.getSaveFileName",
                        lambda *args, **kwargs: (str(target), ""))
    monkeypatch.setattr("app.export_dialog.run_dialog", fake_export_dialog(target))
    warnings: list[str] = []
    monkeypatch.setattr("app.menus.QMessageBox.warning", lambda *args: warnings.append(args[-1]))
    run_file_action(qtbot, opened, action)
    assert warnings == []
    assert target.stat().st_size > 0
    assert str(target) in opened.status.text()
    leftovers = [p.name for p in tmp_path.iterdir() if p.name.startswith("tmp") or ".tmp" in p.name]
    assert leftovers == []


@pytest.mark.parametrize("action", ["export_shape", "export_table", "screenshot"])
def test_file_menu_shows_any_writer_error_in_a_dialog(opened, qtbot, tmp_path, monkeypatch,
                                                      action) -> None:
    """A writer failing with any exception gives one dialog naming it; nothing escapes."""
    monkeypatch.setattr("app.file_actions.QFileDialog.getSaveFileName",
                        lambda *args, **kwargs: (str(tmp_path / "out"), ""))
    monkeypatch.setattr("app.export_dialog.run_dialog", fake_export_dialog(tmp_path / "out"))

    def broken(*args, **kwargs):
        raise RuntimeError("renderer fell over")

    name = {"export_shape": "write_shape_file", "export_table": "write_table_file",
            "screenshot": "write_screenshot"}[action]
    monkeypatch.setattr(f"app.file_actions.{name}", broken)
    warnings: list[tuple[str, str]] = []
    monkeypatch.setattr("app.menus.QMessageBox.warning",
                        lambda parent, title, text: warnings.append((title, text)))
    run_file_action(qtbot, opened, action)
    assert len(warnings) == 1
    title, text = warnings[0]
    assert text.startswith(f"{title} failed") and "renderer fell over" in text
    assert "Traceback" not in text


def test_exports_run_in_the_background_and_cancel_leaves_the_old_file(opened, qtbot, tmp_path,
                                                                      monkeypatch) -> None:
    """While an export runs the window keeps stepping alpha; Cancel stops it before the
    rename, so the file already at the target is untouched and no temporary file is left."""
    import threading

    import core.export.table as table_writers

    target = tmp_path / "table.npz"
    target.write_bytes(b"the user's old file")
    monkeypatch.setattr("app.file_actions.QFileDialog.getSaveFileName",
                        lambda *args, **kwargs: (str(target), ""))
    started, release = threading.Event(), threading.Event()
    real = table_writers.TABLE_WRITERS[".npz"]

    def slow_npz(path, ac):
        started.set()
        release.wait(30)
        real(path, ac)

    monkeypatch.setitem(table_writers.TABLE_WRITERS, ".npz", slow_npz)
    opened.menus["export_table"].trigger()
    assert started.wait(10) and opened.jobs.is_busy() and opened.job_progress.isVisible()
    press(qtbot, opened, Qt.Key.Key_Right)  # the GUI thread is free meanwhile
    assert_layers_match(opened)
    with qtbot.waitSignal(opened.jobs.cancelled, timeout=BUILD_TIMEOUT_MS):
        qtbot.mouseClick(opened.job_progress.cancel, Qt.MouseButton.LeftButton)
        release.set()
    assert target.read_bytes() == b"the user's old file"
    assert [p.name for p in tmp_path.iterdir()] == ["table.npz"]
    assert "cancelled" in opened.status.text() and not opened.job_progress.isVisible()


def test_closing_does_not_wait_for_a_build_that_cannot_stop(qtbot, tmp_path, monkeypatch):
    """Close during an uninterruptible build: the window closes within the bounded wait."""
    import threading
    import time

    from PySide6.QtCore import QSettings

    from app import main_window
    from app.main_window import MainWindow

    release, started = threading.Event(), threading.Event()

    def stuck_build(path, progress, runner=None, **options):
        started.set()
        release.wait(30)  # like a Delaunay build: never looks at the cancel flag

    monkeypatch.setattr("app.worker.load_dataset", stuck_build)
    monkeypatch.setattr(main_window, "CLOSE_WAIT_MS", 200)
    win = MainWindow(QSettings(str(tmp_path / "s.ini"), QSettings.Format.IniFormat))
    late: list[int] = []
    for signal in (win.loader.finished, win.loader.failed, win.loader.cancelled):
        signal.connect(lambda request, *rest: late.append(request))
    win.show()
    win.open_path(tmp_path / "slow.npy")
    assert started.wait(10)
    began = time.perf_counter()
    try:
        assert win.close()
        assert time.perf_counter() - began < 5.0
        assert not win.isVisible()
    finally:
        release.set()
        assert win.loader.wait(10_000)
    qtbot.wait(20)
    assert late == []  # the late result never reached the closed window


def test_dropping_a_file_opens_it_and_remembers_it(window, qtbot, points_file) -> None:
    """A file dropped on the window opens; it then heads File → Open Recent."""
    from PySide6.QtCore import QMimeData, QPointF, QUrl
    from PySide6.QtGui import QDropEvent

    path = points_file(blobs_3d(600, seed=9), "dropped.npy")
    mime = QMimeData()
    mime.setUrls([QUrl.fromLocalFile(str(path))])
    event = QDropEvent(QPointF(10, 10), Qt.DropAction.CopyAction, mime,
                       Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier)
    with qtbot.waitSignal(window.model.datasetChanged, timeout=BUILD_TIMEOUT_MS):
        window.dropEvent(event)
    assert window.model.dataset.path == path
    assert window.prefs.recent_files()[0] == str(path.resolve())


def test_layer_styles_persist_between_windows(opened, qtbot, points_file) -> None:
    """A colour/visibility change is saved and a new window starts with it."""
    from app.main_window import MainWindow

    opened.layers_panel._edit("surface", colour="#123456", visible=False)
    assert opened.scene.layers["surface"].actor.prop.color.hex_rgb == "#123456"
    again = MainWindow(opened.prefs.store)
    qtbot.addWidget(again)
    try:
        open_and_wait(qtbot, again, points_file(blobs_3d(), "again.npy"))
        assert again.layers_panel.styles["surface"].colour == "#123456"
        assert not again.scene.layers["surface"].actor.GetVisibility()
    finally:
        again.close()


def drag_slider(qtbot, slider, dx: int) -> None:
    """Press the slider's handle with the mouse, drag it dx pixels, release."""
    from PySide6.QtCore import QEvent, QPointF
    from PySide6.QtGui import QMouseEvent
    from PySide6.QtWidgets import QApplication, QStyle, QStyleOptionSlider

    option = QStyleOptionSlider()
    slider.initStyleOption(option)
    handle = slider.style().subControlRect(QStyle.ComplexControl.CC_Slider, option,
                                           QStyle.SubControl.SC_SliderHandle, slider)
    start = QPointF(handle.center())
    left, none = Qt.MouseButton.LeftButton, Qt.MouseButton.NoButton
    steps = [(QEvent.Type.MouseButtonPress, start, left, left)]
    steps += [(QEvent.Type.MouseMove, start + QPointF(dx * i / 5, 0), none, left)
              for i in range(1, 6)]
    steps.append((QEvent.Type.MouseButtonRelease, start + QPointF(dx, 0), left, none))
    for kind, pos, button, buttons in steps:
        event = QMouseEvent(kind, pos, slider.mapToGlobal(pos), button, buttons,
                            Qt.KeyboardModifier.NoModifier)
        QApplication.sendEvent(slider, event)
    qtbot.wait(10)


def test_mouse_drag_moves_alpha_and_layers_follow(opened, qtbot) -> None:
    """Dragging the slider handle left lowers alpha; the drag's events coalesce to one shape."""
    model = opened.model
    start = model.index
    shown: list[int] = []
    model.alphaChanged.connect(lambda: shown.append(model.index))
    drag_slider(qtbot, opened.alpha_panel.slider, -60)
    qtbot.waitUntil(lambda: model.index < start, timeout=5000)
    panel = opened.alpha_panel
    assert model.index == panel.travel.index_at(panel.slider.value())
    assert len(shown) == 1
    assert_layers_match(opened)


def test_3d_surface_is_one_surface_with_an_optional_highlight(window, qtbot, points_file):
    """By default a 3D shape is drawn as one surface: regular and singular triangles in one
    colour, lit on both sides; the singular highlight is a layer that starts hidden."""
    from app.palette import default_styles

    styles = default_styles(3)
    assert styles["surface"].visible and not styles["singular_highlight"].visible
    open_and_wait(qtbot, window, points_file(blobs_3d(), "fresh.npy"))
    assert window.scene.plotter.renderer.GetTwoSidedLighting()
    assert not window.layers_panel.rows["singular_highlight"].visible.isChecked()
    assert not window.scene.layers["singular_highlight"].actor.GetVisibility()
    window.layers_panel.rows["singular_highlight"].visible.setChecked(True)
    assert window.scene.layers["singular_highlight"].actor.GetVisibility()
    expected = expected_layers(window.model.dataset.ac, window.model.alpha)
    assert len(expected["singular_highlight"]) > 0
    for name in ("surface", "singular_highlight"):
        assert as_set(layer_cells(window.scene.layers[name])) == as_set(expected[name])


def test_back_and_forward_return_to_the_alphas_visited(opened, qtbot) -> None:
    """Alt+Left goes back to the alpha before a jump, Alt+Right redoes it; so do the buttons."""
    model, panel = opened.model, opened.alpha_panel
    model.history.merge_seconds = 0.0
    start = model.index
    qtbot.mouseClick(panel.hull, Qt.MouseButton.LeftButton)
    assert model.index == model.hull_index()
    qtbot.keyClick(panel.slider, Qt.Key.Key_Left, Qt.KeyboardModifier.AltModifier)
    assert model.index == start
    qtbot.keyClick(panel.slider, Qt.Key.Key_Right, Qt.KeyboardModifier.AltModifier)
    assert model.index == model.hull_index()
    qtbot.mouseClick(panel.back, Qt.MouseButton.LeftButton)
    assert model.index == start and panel.forward.isEnabled()


def test_slider_marks_the_suggested_opening_and_optimal_alphas(opened) -> None:
    """Ticks sit at the slider positions of the suggested alphas, the opening and the optimal."""
    from app.log_travel import snap_index

    panel, ds = opened.alpha_panel, opened.model.dataset
    positions = {mark.position for mark in panel.slider.marks}
    suggested = ds.ac.suggest_alphas(5)
    assert suggested
    for r in suggested:
        assert panel.travel.position(snap_index(ds.spectrum, r.alpha)) in positions
    assert panel.travel.position(opened.model.optimal_index()) in positions
    assert panel.travel.position(opened.model.default_index()) in positions


@needs_data
def test_page_up_from_the_opening_stays_below_the_hull_on_a_real_scan(window, qtbot) -> None:
    """milk.pcd (an RGB-D scan): PageUp from where it opens moves up, far from the hull."""
    open_and_wait(qtbot, window, data_dir() / "milk.pcd")
    model = window.model
    assert model.index == model.default_index()
    press(qtbot, window, Qt.Key.Key_PageUp)
    assert model.default_index() < model.index < model.hull_index()
    assert model.alpha < 2 * model.dataset.default_alpha


def test_view_presets_and_reset_follow_the_data_frame(window, qtbot, points_file) -> None:
    """T/F/S/I show the top, front, side and iso views of the data's frame (z up for a .npy),
    centred on the data; R resets to the opening view."""
    from app.camera import Z_UP

    open_and_wait(qtbot, window, points_file(blobs_3d(), "frame.npy"))
    camera = window.scene.plotter.camera
    opening = np.array(camera.direction)
    bounds = np.array(window.scene.layers["points"].mesh.bounds).reshape(3, 2)
    for key, preset in (("T", "top"), ("F", "front"), ("S", "side"), ("I", "iso")):
        action = window.menus[f"view_{preset}"]
        assert action.shortcut().toString() == key
        action.trigger()
        look, up = Z_UP.direction(preset)
        assert np.allclose(camera.direction, look, atol=1e-6), preset
        assert np.allclose(camera.up, up, atol=1e-6), preset
        assert np.allclose(camera.focal_point, bounds.mean(axis=1)), preset
    window.menus["view_top"].trigger()
    assert window.menus["reset_view"].shortcut().toString() == "R"
    window.menus["reset_view"].trigger()
    assert np.allclose(camera.direction, opening, atol=1e-6)


def test_the_view_does_not_move_when_alpha_changes(opened, qtbot) -> None:
    """The docks keep their widths whatever their text says, so the 3D view's geometry stays
    put from the first critical value to the hull."""
    model = opened.model
    qtbot.wait(20)
    before = opened.scene.plotter.geometry()
    for index in (0, 1, model.default_index(), model.optimal_index(), model.hull_index() - 1,
                  model.hull_index(), 2):
        model.set_index(index)
        qtbot.wait(20)
        assert opened.scene.plotter.geometry() == before, index


def test_info_dock_prints_for_people(opened) -> None:
    """Singular words for one, extent-relative coordinates (no e-notation), and the axes."""
    from app.info_panel import box_lines, data_lines

    assert box_lines(((4918340.5, 636002.25, 406.26), (4918380.25, 637179.5, 520.51)), "m") == [
        "x 4918340.5 … 4918380.2 (39.75 m)",  # to 1/10,000 of the largest side
        "y 636002.2 … 637179.5 (1,177 m)",
        "z 406.3 … 520.5 (114.2 m)",
    ]
    text = "\n".join(data_lines(opened.model))
    assert "e+0" not in text and "x " in text and "spacing" in text
    assert "build: backend qhull" in text  # ac.build_info (core/pipeline.py)


def test_wait_for_fails_when_the_signal_never_comes(qapp) -> None:
    """A wait that times out fails the test (before, it fell through into a skip)."""
    from PySide6.QtCore import QTimer

    idle = QTimer()  # never started: its timeout never fires
    with pytest.raises(pytest.fail.Exception, match="within 0 s"):
        wait_for(idle.timeout, timeout_ms=50)

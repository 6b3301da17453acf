"""The main window's menus and their handlers (file dialogs, exports, view and shape actions)."""

from __future__ import annotations

from functools import partial
from pathlib import Path

from PySide6.QtGui import QAction, QKeySequence
from PySide6.QtWidgets import QDockWidget, QMainWindow, QMenu, QMessageBox

from app import file_actions
from app.clipping import add_clip_action
from app.colour_view import add_colour_menu
from app.export_dialog import ask_export_shape
from app.help import add_help_actions
from app.jobs import Job
from core.errors import InputError
from core.export import TABLE_FORMATS
from core.export.targets import refuse_source

ABOUT = (
    "<b>Alpha Scoop</b><br>Explore alpha shapes of 2D and 3D point sets: one Delaunay build, "
    "every alpha a cheap query.<br>Alpha is a radius; r² is the value CGAL and gudhi use."
)


def add_action(menu: QMenu, text: str, slot, shortcut=None) -> QAction:
    """Add a triggered action to menu."""
    action = menu.addAction(text)
    action.triggered.connect(lambda _=False: slot())
    if shortcut is not None:
        action.setShortcut(QKeySequence(shortcut))
    return action


def fill_recent(window, menu: QMenu) -> None:
    """Rebuild the Open Recent submenu from the preferences."""
    menu.clear()
    files = window.prefs.recent_files()
    for path in files:
        add_action(menu, Path(path).name, partial(window.open_asking, path)).setToolTip(path)
    menu.setEnabled(bool(files))


def run_writer(window, title: str, write) -> None:
    """Run a writer; report its result in the status bar, or its error in a dialog.

    Any failure of the writer (core errors, OS errors, a VTK or PIL error) becomes a message
    naming what failed; the slot never lets an exception escape into Qt.
    """
    try:
        message = write()
    except Exception as error:  # every writer failure is shown; none escapes the slot
        QMessageBox.warning(window, title, f"{title} failed: {error or type(error).__name__}")
    else:
        window.report(message)


def run_in_background(window, title: str, job) -> None:
    """Start a writer in the window's job runner (progress and Cancel in the status bar);
    its outcome arrives through the runner's signals. One at a time."""
    if window.jobs.start(Job(title, lambda progress, _cancel: job(progress))) is None:
        QMessageBox.information(window, title, "Another export is still running; wait for it "
                                               "or cancel it first.")
        return
    window.job_progress.start(title)


def is_the_source(window, title: str, path: Path) -> bool:
    """True, after a dialog saying so, when path is the open dataset's own file on disk."""
    try:
        refuse_source(path, window.model.dataset.path)
    except InputError as error:
        QMessageBox.warning(window, title, f"{title}: {error}")
        return True
    return False


def export_shape(window) -> None:
    """File → Export shape: formats from core.export, the oriented surface by default."""
    if window.model.dataset is None:
        QMessageBox.information(window, "Export shape", "Open a point set first.")
        return
    ds, alpha = window.model.dataset, window.model.alpha
    chosen = ask_export_shape(window, window.prefs, ds.path.stem, alpha)
    if chosen and not is_the_source(window, "Export shape", chosen[0]):
        path, manifold = chosen
        georef = None if ds.report is None else ds.report.georef  # longitude/latitude input
        run_in_background(window, "Export shape", lambda progress: file_actions.export_shape(
            ds.ac, alpha, path, progress, source=ds.path, georef=georef, manifold=manifold))


def export_table(window) -> None:
    """File → Export table: the interval table (.npz or .csv) for analysis elsewhere."""
    if window.model.dataset is None:
        return
    stem = window.model.dataset.path.stem
    path = file_actions.ask_save_path(window, window.prefs, "Export table",
                                      TABLE_FORMATS, f"{stem}_table")
    if path and not is_the_source(window, "Export table", path):
        ac, source = window.model.dataset.ac, window.model.dataset.path
        run_in_background(window, "Export table", lambda progress: file_actions.export_table(
            ac, path, progress, source=source))


def save_screenshot(window) -> None:
    """File → Save screenshot (PNG)."""
    path = file_actions.ask_save_path(window, window.prefs, "Save screenshot",
                                      {".png": "PNG image"}, "alphascoop")
    if path:
        run_writer(window, "Save screenshot",
                   lambda: file_actions.save_screenshot(window.plotter, path))


VIEW_KEYS = {"top": "T", "front": "F", "side": "S", "iso": "I"}


def show_view(window, preset: str) -> None:
    """View → a preset camera (app.camera.PRESETS), fitted to the data."""
    window.scene.view_preset(preset)
    window.scene.render()


def build_menus(window: QMainWindow) -> dict[str, QAction]:
    """Create File, View, Shape and Help menus on window; returns the main actions by name."""
    bar = window.menuBar()
    file_menu = bar.addMenu("&File")
    actions = {"open": add_action(file_menu, "&Open…", window.ask_and_open, QKeySequence.Open)}
    recent = file_menu.addMenu("Open &Recent")
    recent.aboutToShow.connect(lambda: fill_recent(window, recent))
    fill_recent(window, recent)
    file_menu.addSeparator()
    actions["export_shape"] = add_action(file_menu, "&Export shape…", lambda: export_shape(window))
    actions["export_table"] = add_action(file_menu, "Export &table…", lambda: export_table(window))
    actions["screenshot"] = add_action(file_menu, "Save &screenshot…",
                                       lambda: save_screenshot(window))
    file_menu.addSeparator()
    add_action(file_menu, "&Quit", window.close, QKeySequence.Quit)
    view = bar.addMenu("&View")
    for dock in window.findChildren(QDockWidget):
        view.addAction(dock.toggleViewAction())
    view.addSeparator()
    for preset, key in VIEW_KEYS.items():
        actions[f"view_{preset}"] = add_action(view, f"&{preset.capitalize()} view",
                                               partial(show_view, window, preset), key)
    actions["reset_view"] = add_action(view, "&Reset view",
                                       lambda: (window.scene.fit_view(), window.scene.render()),
                                       "R")
    view.addSeparator()
    actions["colour_by"] = add_colour_menu(view, window.colourer).menuAction()
    actions["clip"] = add_clip_action(view, window.clipper)
    shape = bar.addMenu("&Shape")
    model = window.model
    actions["optimal"] = add_action(shape, "&Optimal alpha",
                                    lambda: model.set_index(model.optimal_index()), "Ctrl+1")
    actions["hull"] = add_action(shape, "Convex &hull",
                                 lambda: model.set_index(model.hull_index()), "Ctrl+H")
    shape.addSeparator()
    actions["back"] = add_action(shape, "&Back to the previous alpha", model.go_back, "Alt+Left")
    actions["forward"] = add_action(shape, "&Forward", model.go_forward, "Alt+Right")
    help_menu = bar.addMenu("&Help")
    actions.update(add_help_actions(window, help_menu))
    add_action(help_menu, "&About Alpha Scoop", lambda: QMessageBox.about(window, "About", ABOUT))
    return actions

"""The main window's menus and their handlers (file dialogs, exports, view and shape actions).

Handlers get what they use passed in explicitly (`MenuTools`), never the window itself.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import partial
from pathlib import Path

from PySide6.QtGui import QAction, QKeySequence
from PySide6.QtWidgets import QDockWidget, QMainWindow, QMenu, QMessageBox, QWidget

from app import file_actions
from app.colour_view import Colourer, add_colour_menu
from app.export_dialog import ask_export_shape
from app.help import add_help_actions
from app.jobs import Job, Progress, Runner
from app.model import ExplorerModel
from app.progress_widget import ProgressWidget
from app.scene import Scene
from app.settings import Preferences
from core.errors import InputError
from core.export import TABLE_FORMATS
from core.export.targets import refuse_source

ABOUT = (
    "<b>Alpha Scoop</b><br>Explore alpha shapes of 2D and 3D point sets: one Delaunay build, "
    "every alpha a cheap query.<br>Alpha is a radius; r² is the value CGAL and gudhi use."
)
VIEW_KEYS = {"top": "T", "front": "F", "side": "S", "iso": "I"}


@dataclass(frozen=True)
class MenuTools:
    """What the menus' handlers work with: the dialogs' `parent`, the preferences, the model
    and scene, the export runner with its progress widget, `report(line)` for the status bar
    and `open_file(path)` (the import dialog first, as for a drop)."""

    parent: QWidget
    prefs: Preferences
    model: ExplorerModel
    scene: Scene
    exports: Runner
    export_progress: ProgressWidget
    report: Callable[[str], None]
    open_file: Callable[[str | Path], object]


def add_action(menu: QMenu, text: str, slot, shortcut=None) -> QAction:
    """Add a triggered action to menu."""
    action = menu.addAction(text)
    action.triggered.connect(lambda _=False: slot())
    if shortcut is not None:
        action.setShortcut(QKeySequence(shortcut))
    return action


def ask_and_open(tools: MenuTools) -> None:
    """File → Open: ask for a point file, then open it."""
    path = file_actions.ask_open_path(tools.parent, tools.prefs)
    if path:
        tools.open_file(path)


def fill_recent(tools: MenuTools, menu: QMenu) -> None:
    """Rebuild the Open Recent submenu from the preferences."""
    menu.clear()
    files = tools.prefs.recent_files()
    for path in files:
        add_action(menu, Path(path).name, partial(tools.open_file, path)).setToolTip(path)
    menu.setEnabled(bool(files))


def run_writer(tools: MenuTools, title: str, write: Callable[[], str]) -> None:
    """Run a writer; report its result in the status bar, or its error in a dialog.

    Any failure of the writer (core errors, OS errors, a VTK or PIL error) becomes a message
    naming what failed; the slot never lets an exception escape into Qt.
    """
    try:
        message = write()
    except Exception as error:  # every writer failure is shown; none escapes the slot
        QMessageBox.warning(tools.parent, title,
                            f"{title} failed: {error or type(error).__name__}")
    else:
        tools.report(message)


def run_in_background(tools: MenuTools, title: str, write: Callable[[Progress], str]) -> None:
    """Start write(progress) in the export runner (progress and Cancel in the status bar);
    its outcome arrives through the runner's signals. One at a time."""
    if tools.exports.start(Job(title, lambda progress, _cancel: write(progress))) is None:
        QMessageBox.information(tools.parent, title, "Another export is still running; wait "
                                                     "for it or cancel it first.")
        return
    tools.export_progress.start(title)


def is_the_source(tools: MenuTools, title: str, path: Path) -> bool:
    """True, after a dialog saying so, when path is the open dataset's own file on disk."""
    try:
        refuse_source(path, tools.model.dataset.path)
    except InputError as error:
        QMessageBox.warning(tools.parent, title, f"{title}: {error}")
        return True
    return False


def on_export_shape(tools: MenuTools) -> None:
    """File → Export shape: formats from core.export, the oriented surface by default."""
    ds = tools.model.dataset
    if ds is None:
        QMessageBox.information(tools.parent, "Export shape", "Open a point set first.")
        return
    alpha = tools.model.alpha
    chosen = ask_export_shape(tools.parent, tools.prefs, ds.path.stem, alpha)
    if chosen and not is_the_source(tools, "Export shape", chosen[0]):
        path, manifold = chosen
        georef = None if ds.report is None else ds.report.georef  # longitude/latitude input
        run_in_background(tools, "Export shape", lambda progress: file_actions.write_shape_file(
            ds.ac, alpha, path, progress, source=ds.path, georef=georef, manifold=manifold))


def on_export_full(tools: MenuTools) -> None:
    """File → Export at full resolution: the shape at the current alpha computed tile by
    tile from every point of the file (app.full_export), in the background."""
    from app import full_export

    ds = tools.model.dataset
    title = full_export.TITLE
    if ds is None:
        QMessageBox.information(tools.parent, title, "Open a point set first.")
        return
    if (why := full_export.refusal(ds)) is not None:
        QMessageBox.information(tools.parent, title, f"{title}: {why}.")
        return
    alpha = tools.model.alpha
    chosen = ask_export_shape(tools.parent, tools.prefs, f"{ds.path.stem}_full", alpha, title)
    if chosen and not is_the_source(tools, title, chosen[0]):
        (path, manifold), source, options = chosen, ds.path, ds.options  # not the dataset
        run_in_background(tools, title, lambda progress: full_export.write_full_resolution(
            source, options, alpha, path, manifold, progress))


def on_export_table(tools: MenuTools) -> None:
    """File → Export table: the interval table (.npz or .csv) for analysis elsewhere."""
    ds = tools.model.dataset
    if ds is None:
        return
    path = file_actions.ask_save_path(tools.parent, tools.prefs, "Export table",
                                      TABLE_FORMATS, f"{ds.path.stem}_table")
    if path and not is_the_source(tools, "Export table", path):
        run_in_background(tools, "Export table", lambda progress: file_actions.write_table_file(
            ds.ac, path, progress, source=ds.path))


def on_export_pockets(tools: MenuTools) -> None:
    """File → Export pockets: a molecule's pockets (VTU cells or CSV of lining residues)."""
    from app.pocket_export import POCKET_FORMATS, write_pockets_file

    ds = tools.model.dataset
    if ds is None or not ds.is_molecule or ds.atom_labels is None:
        QMessageBox.information(tools.parent, "Export pockets", "Open a molecule first.")
        return
    if ds.molecule is None:
        failure = tools.model.measures_failure
        QMessageBox.information(tools.parent, "Export pockets", (
            "The pockets are still being computed: try again in a moment." if failure is None
            else f"The pockets could not be computed: {failure}"))
        return
    path = file_actions.ask_save_path(tools.parent, tools.prefs, "Export pockets",
                                      POCKET_FORMATS, f"{ds.path.stem}_pockets")
    if path and not is_the_source(tools, "Export pockets", path):
        run_writer(tools, "Export pockets", lambda: write_pockets_file(ds, path))


def on_save_screenshot(tools: MenuTools) -> None:
    """File → Save screenshot (PNG)."""
    path = file_actions.ask_save_path(tools.parent, tools.prefs, "Save screenshot",
                                      {".png": "PNG image"}, "alphascoop")
    if path:
        run_writer(tools, "Save screenshot",
                   lambda: file_actions.write_screenshot(tools.scene, path))


def show_view(scene: Scene, preset: str) -> None:
    """View → a preset camera (app.camera.PRESETS), fitted to the data."""
    scene.view_preset(preset)
    scene.render()


def reset_view(scene: Scene) -> None:
    """View → Reset view: the opening camera, fitted to the data."""
    scene.fit_view()
    scene.render()


def add_clip_action(menu: QMenu, scene: Scene) -> QAction:
    """View → Clipping plane (Ctrl+K), checkable."""
    action = menu.addAction("Clipping &plane")
    action.setCheckable(True)
    action.setShortcut(QKeySequence("Ctrl+K"))
    action.setToolTip("cut the shape open with a plane you can drag and turn")
    action.toggled.connect(scene.set_clipping)
    return action


def add_file_menu(window: QMainWindow, tools: MenuTools) -> dict[str, QAction]:
    """File: Open, Open Recent, Export shape/at full resolution/table, Save screenshot,
    Quit."""
    menu = window.menuBar().addMenu("&File")
    actions = {"open": add_action(menu, "&Open…", partial(ask_and_open, tools), QKeySequence.Open)}
    recent = menu.addMenu("Open &Recent")
    recent.aboutToShow.connect(lambda: fill_recent(tools, recent))
    fill_recent(tools, recent)
    menu.addSeparator()
    actions["export_shape"] = add_action(menu, "&Export shape…", partial(on_export_shape, tools))
    actions["export_full"] = add_action(menu, "Export at &full resolution…",
                                        partial(on_export_full, tools))
    actions["export_table"] = add_action(menu, "Export &table…", partial(on_export_table, tools))
    actions["export_pockets"] = add_action(menu, "Export &pockets…",
                                           partial(on_export_pockets, tools))
    actions["screenshot"] = add_action(menu, "Save &screenshot…",
                                       partial(on_save_screenshot, tools))
    menu.addSeparator()
    add_action(menu, "&Quit", window.close, QKeySequence.Quit)
    return actions


def add_view_menu(window: QMainWindow, scene: Scene, colourer: Colourer) -> dict[str, QAction]:
    """View: the docks, camera presets, Colour by and the clipping plane."""
    view = window.menuBar().addMenu("&View")
    for dock in window.findChildren(QDockWidget):
        view.addAction(dock.toggleViewAction())
    view.addSeparator()
    actions = {f"view_{preset}": add_action(view, f"&{preset.capitalize()} view",
                                            partial(show_view, scene, preset), key)
               for preset, key in VIEW_KEYS.items()}
    actions["reset_view"] = add_action(view, "&Reset view", partial(reset_view, scene), "R")
    view.addSeparator()
    actions["colour_by"] = add_colour_menu(view, colourer).menuAction()
    actions["clip"] = add_clip_action(view, scene)
    return actions


def add_shape_menu(window: QMainWindow, model: ExplorerModel) -> dict[str, QAction]:
    """Shape: optimal alpha, convex hull, back and forward through the alphas visited."""
    shape = window.menuBar().addMenu("&Shape")
    actions = {"optimal": add_action(shape, "&Optimal alpha",
                                     lambda: model.set_index(model.optimal_index()), "Ctrl+1"),
               "hull": add_action(shape, "Convex &hull",
                                  lambda: model.set_index(model.hull_index()), "Ctrl+H")}
    shape.addSeparator()
    actions["back"] = add_action(shape, "&Back to the previous alpha", model.go_back, "Alt+Left")
    actions["forward"] = add_action(shape, "&Forward", model.go_forward, "Alt+Right")
    return actions


def build_menus(window: QMainWindow, tools: MenuTools, colourer: Colourer,
                explain_dock: QDockWidget) -> dict[str, QAction]:
    """Create File, View, Shape and Help menus on window (Help → What am I looking at?
    shows explain_dock); returns the main actions by name."""
    actions = add_file_menu(window, tools)
    actions.update(add_view_menu(window, tools.scene, colourer))
    actions.update(add_shape_menu(window, tools.model))
    help_menu = window.menuBar().addMenu("&Help")
    actions.update(add_help_actions(window, help_menu, explain_dock))
    add_action(help_menu, "&About Alpha Scoop", lambda: QMessageBox.about(window, "About", ABOUT))
    return actions

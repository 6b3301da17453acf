"""The explorer's main window: composes the view, docks, menus and the runners (no logic of
its own).

State lives in ExplorerModel, every VTK object in the Scene, background work in
app.jobs.Runner (loads, topology, a molecule's measures, exports); this class only wires
them.
"""

from __future__ import annotations

import os

os.environ["QT_API"] = "pyside6"

from pathlib import Path

from PySide6.QtCore import QCoreApplication, QEvent, QSettings, Qt, QTimer
from PySide6.QtGui import QIcon
from PySide6.QtWidgets import QDockWidget, QLabel, QMainWindow, QMessageBox, QWidget

from app import child_process, memory
from app.alpha_panel import AlphaPanel
from app.banner import banner_above, subsample_banner_label
from app.colour_view import Colourer
from app.dataset import POINTS_READ, ImportOptions
from app.full_export import subsample_banner
from app.help import ExplainPanel
from app.import_dialog import ask_import_options
from app.info_panel import InfoPanel
from app.inspect_panel import InspectPanel
from app.inspector import Inspector
from app.jobs import Runner
from app.layers_panel import LayersPanel
from app.layout_stop import contained
from app.menus import MenuTools, build_menus
from app.mode_panel import ModePanel
from app.model import ExplorerModel
from app.palette import ATOM_STYLE, CAVITY_STYLE, MOUTH_STYLE, POCKET_STYLE, cpk_rgb
from app.progress_widget import ProgressWidget
from app.reopen import ReopenFallback
from app.resources import ICON_PATH
from app.scene import exposed_of, pockets_of, scene_data
from app.scene.interactive import interactive_scene
from app.settings import Preferences
from app.signatures_dock import SignaturesPanel
from app.worker import load_job, measures_job, topology_job
from core.modes.alpha_modes import Mode

LAYOUT_DEPTH = 5  # rounds of layout requests a text change sends up (label, panel, dock, window)
CLOSE_WAIT_MS = 2000  # how long closing waits for a running build before leaving it behind


class MainWindow(QMainWindow):
    """Main window: 3D view in the centre, alpha/layers/info docks, status bar with progress."""

    def __init__(self, settings: QSettings | None = None) -> None:
        """Create the widgets; no dataset until open_path."""
        super().__init__()
        self.setWindowTitle("Alpha Scoop")
        self.setWindowIcon(QIcon(str(ICON_PATH)))
        self.setAcceptDrops(True)
        self.prefs = Preferences(settings)
        self.start_alpha: float | None = None  # `--alpha`: where the first open shows its file
        self.start_request: int | None = None  # the open start_alpha belongs to (the first)
        self.mode = Mode()  # the alpha mode of the next open or rebuild
        self.last_options: ImportOptions | None = None  # how the last file was read
        self.start_optimal = False  # open the next dataset at CGAL's optimal alpha
        self.fallback: ReopenFallback | None = None  # re-opened if the running load stops
        self.reopen_alpha: tuple[int, float | None] | None = None  # (request, the user's alpha)
        self.model = ExplorerModel()
        self.loader = Runner(self)  # loads and rebuilds: a newer one supersedes the older
        self.topology = Runner(self)  # the topology after a load (a newer one supersedes it)
        self.measures = Runner(self)  # a molecule's measures after a load (likewise)
        self.jobs = Runner(self, exclusive=True)  # exports: one at a time
        self.scene, view = interactive_scene(self)
        self.banner = subsample_banner_label()
        self.setCentralWidget(banner_above(self.banner, view))
        self.alpha_panel = AlphaPanel(self.model)
        self.layers_panel = LayersPanel()
        self.info_panel = InfoPanel(self.model)
        self.signatures_panel = SignaturesPanel(self.model)
        self.mode_panel = ModePanel()
        self.progress = ProgressWidget()
        self.job_progress = ProgressWidget()
        self.status = QLabel("Open a point set: File → Open, or drop a file here.")
        self.statusBar().addWidget(contained(self.status, scroll_vertically=False), 1)
        self.statusBar().addPermanentWidget(self.progress)
        self.statusBar().addPermanentWidget(self.job_progress)
        self._add_dock("Alpha", contained(self.alpha_panel), Qt.DockWidgetArea.RightDockWidgetArea)
        self._add_dock("Layers", self.layers_panel, Qt.DockWidgetArea.RightDockWidgetArea)
        info = self._add_dock("Info", self.info_panel, Qt.DockWidgetArea.LeftDockWidgetArea)
        mode = self._add_dock("Mode", self.mode_panel, Qt.DockWidgetArea.LeftDockWidgetArea)
        self.tabifyDockWidget(info, mode)  # a tab beside Info: the view keeps its room
        info.raise_()
        self._add_dock("Signatures", self.signatures_panel, Qt.DockWidgetArea.BottomDockWidgetArea)
        left = Qt.DockWidgetArea.LeftDockWidgetArea
        self.inspect_panel = InspectPanel(self.model)
        self.inspector = Inspector(self.model, self.scene, self.inspect_panel,
                                   self._add_dock("Inspect", self.inspect_panel, left))
        self.explain_dock = self._add_dock("Help", ExplainPanel(), left)
        self.explain_dock.setWindowTitle("What am I looking at?")
        self.explain_dock.hide()
        self.colourer = Colourer(self.scene, self.model)
        self.menus = build_menus(self, MenuTools(
            self, self.prefs, self.model, self.scene, self.jobs, self.job_progress, self.report,
            self.open_asking), self.colourer, self.explain_dock)
        self._connect()
        self._restore_layout()
        child_process.remove_orphans()  # scratch folders of a killed window's builds

    def _add_dock(self, title: str, widget: QWidget, area: Qt.DockWidgetArea) -> QDockWidget:
        """Put widget in a named dock (names let QSettings restore the layout)."""
        dock = QDockWidget(title, self)
        dock.setObjectName(f"dock_{title.lower()}")
        dock.setWidget(widget)
        self.addDockWidget(area, dock)
        return dock

    def _connect(self) -> None:
        """Wire loader -> window, model -> scene, layers -> scene."""
        self.loader.progress.connect(self._on_progress)
        self.loader.finished.connect(self._on_loaded)
        self.loader.failed.connect(self._on_failed)
        self.loader.cancelled.connect(self._on_cancelled)
        self.topology.finished.connect(self._on_topology)
        self.topology.failed.connect(self._on_topology_failed)
        self.measures.finished.connect(lambda _request, ds: self.model.set_measures(ds))
        self.measures.failed.connect(self._on_measures_failed)
        for outcome in (self.loader.finished, self.loader.failed, self.loader.cancelled,
                        self.loader.dropped):  # a superseded load's arrays are freed too
            outcome.connect(self._give_back_memory)  # after the slots above dropped the old
        self.progress.cancelRequested.connect(self.loader.cancel)
        self.jobs.progress.connect(lambda _request, fraction, stage:
                                   self.job_progress.update_progress(fraction, stage))
        self.jobs.finished.connect(self._on_job_done)
        self.jobs.failed.connect(self._on_job_failed)
        self.jobs.cancelled.connect(self._on_job_cancelled)
        self.job_progress.cancelRequested.connect(self.jobs.cancel)
        self.model.datasetChanged.connect(self._show_dataset)
        self.model.alphaChanged.connect(self._show_shape)
        self.model.measuresChanged.connect(self._show_measures)
        slider = self.alpha_panel.slider  # a drag draws a lighter frame; its release the full
        slider.sliderMoved.connect(lambda _position: self.scene.set_level_of_detail(True))
        slider.sliderReleased.connect(self._end_drag)
        self.model.datasetReleased.connect(self._show_released)
        self.layers_panel.styleChanged.connect(self._set_style)
        self.mode_panel.modeChosen.connect(self.set_mode)

    def open_path(self, path: str | Path, options: ImportOptions | None = None) -> int:
        """Load and build path in the worker (cancels any older open), read with `options`
        (columns, subsampling); returns the request id."""
        path = Path(path)
        self.prefs.set_last_dir(path)
        self.progress.start(f"opening {path.name}")
        self.last_options = options
        request = self.loader.start(load_job(path, self.mode, options))
        if self.start_request is None:
            self.start_request = request
        elif self.start_alpha is not None:  # a newer open: the start belonged to the first
            self.start_alpha = None
        return request

    def open_asking(self, path: str | Path) -> int | None:
        """Open path as a user does (File → Open, a drop): text and big files first show the
        import dialog (columns, subsampling); None when the user cancels it."""
        options = ask_import_options(self, Path(path), self.prefs)
        return None if options is None else self.open_path(path, options)

    def set_mode(self, mode: Mode, rebuild: bool = True) -> int | None:
        """Use the alpha `mode` from now on; with `rebuild`, build the open file again in it
        (in the background, read as it was; the current table is released once the file is
        read, and comes back from the cache if the rebuild is cancelled or fails). Returns
        the rebuild's request id, None when nothing was started."""
        self.mode = mode
        self.mode_panel.set_mode(mode)
        dataset = self.model.dataset
        if not rebuild or dataset is None:
            return None
        self.progress.start(f"rebuilding {dataset.path.name}: {mode.describe()}")
        return self.loader.start(load_job(dataset.path, mode, self.last_options))

    def _release(self) -> None:
        """Let the shown dataset go once a new load has read its file (before its table is
        built or loaded), so the window never holds two tables; remember how to re-open it
        (from the table cache) should the load be cancelled or fail. The view is empty
        meanwhile and the status line says why. A file that cannot be read leaves it be."""
        dataset = self.model.dataset
        if dataset is None:
            return
        self.fallback = ReopenFallback(dataset.path, dataset.ac.mode, self.last_options,
                                       self.model.alpha if self.model.touched else None)
        self.topology.cancel()  # its job holds the dataset: stop it now
        self.measures.cancel()  # likewise
        self.model.release()
        self.status.setText(f"{self.loader.title}: {dataset.path.name} was closed to make room "
                            "(Cancel re-opens it)")

    def _reopen_fallback(self, why: str) -> bool:
        """After a cancelled or failed load: re-open the file released for it (its table comes
        from the cache) at the alpha the user had; False when none was (a still shown one
        keeps its mode)."""
        fallback, self.fallback = self.fallback, None
        self.start_alpha = None  # a `--alpha` start belonged to the load that stopped
        if fallback is None:
            if self.model.dataset is not None:  # the shown table's mode stays the current one
                self.set_mode(self.model.dataset.ac.mode, rebuild=False)
            return False
        self.mode = fallback.mode
        self.mode_panel.set_mode(fallback.mode)
        self.progress.start(f"re-opening {fallback.path.name}")
        self.last_options = fallback.options
        request = self.loader.start(load_job(fallback.path, fallback.mode, fallback.options))
        self.reopen_alpha = (request, fallback.alpha)
        self.status.setText(f"{why}; re-opening {fallback.path.name}")
        return True

    def _on_job_done(self, _request: int, message: str) -> None:
        """An export finished: say what it wrote."""
        self.job_progress.stop()
        self.report(message)

    def _on_job_failed(self, _request: int, message: str) -> None:
        """An export failed: one dialog naming what failed."""
        self.job_progress.stop()
        QMessageBox.warning(self, self.jobs.title, message)

    def _on_job_cancelled(self, _request: int) -> None:
        """An export was cancelled: nothing was written (an old file stays as it was)."""
        self.job_progress.stop()
        self.report(f"{self.jobs.title} cancelled; nothing was written")

    def _on_progress(self, _request: int, fraction: float, stage: str) -> None:
        """Show the open's progress (the runner drops older requests' reports); once the
        file is read, the shown dataset is released."""
        if stage == POINTS_READ:
            self._release()
        self.progress.update_progress(fraction, stage)

    def _on_loaded(self, request: int, dataset) -> None:
        """Adopt the dataset of the current request (the runner drops stale ones); a re-open
        after a cancelled load goes to the alpha the user had (only that request's)."""
        self.progress.stop()
        self.fallback = None
        self.prefs.add_recent(dataset.path)
        self.mode_panel.show_built(dataset.ac.mode)
        self.model.set_dataset(dataset)
        self.topology.cancel()  # an older dataset's pass: stops at its next stage
        if not dataset.has_topology:
            self.topology.start(topology_job(dataset))
        self.measures.cancel()  # an older molecule's: its result is dropped
        if dataset.needs_measures:
            self.measures.start(measures_job(dataset))
        reopened, self.reopen_alpha = self.reopen_alpha, None
        start = self.start_alpha if request == self.start_request else None
        alpha = reopened[1] if reopened is not None and reopened[0] == request else start
        self.start_alpha = None
        if alpha is not None:
            self.model.set_alpha(alpha)
        elif self.start_optimal and dataset.has_topology:
            self.model.set_index(self.model.optimal_index())
        self.start_optimal = self.start_optimal and not dataset.has_topology
        # the docks take their new widths now, before the view's first frame: that frame is
        # drawn once, at its final size (a resize after it would draw it again)
        self.layout().activate()

    def _on_topology(self, _request: int, dataset) -> None:
        """The current dataset's topology arrived: fill in the docks (the model moves to the
        opening alpha if the slider was not touched); `--optimal` goes there now."""
        if not self.model.set_topology(dataset):  # another dataset's (the runner drops most)
            return
        if self.start_optimal:
            self.model.set_index(self.model.optimal_index())
            self.start_optimal = False
        self._show_status()

    def _on_topology_failed(self, _request: int, message: str) -> None:
        """The topology pass failed: the slider keeps working; say why (not over a file
        shown since that came with its topology, which superseded no pass)."""
        ds = self.model.dataset
        if ds is not None and not ds.has_topology:
            self.status.setText(f"{message}; the slider still works")

    def _on_measures_failed(self, _request: int, message: str) -> None:
        """A molecule's measures failed: the shape and slider stay; say why (not over
        another file shown since, which no measures superseded)."""
        if self.model.fail_measures(message):
            self._show_status()

    def _on_failed(self, _request: int, message: str) -> None:
        """Show why the current request failed; the file shown before comes back."""
        self.progress.stop()
        self._reopen_fallback("Opening failed")
        QMessageBox.warning(self, "Could not open the file", message)

    def _on_cancelled(self, _request: int) -> None:
        """Note a cancelled open in the status bar; the file shown before comes back."""
        self.progress.stop()
        if not self._reopen_fallback("Opening cancelled"):
            self.status.setText("Opening cancelled.")

    def _give_back_memory(self, *_outcome) -> None:
        """Once this event is handled (the old dataset or a cancelled load's arrays are
        dropped by then), return the freed memory to the OS (app.memory)."""
        QTimer.singleShot(0, memory.give_back)

    def _show_dataset(self) -> None:
        """New dataset: new layers and camera (the only time actors are added)."""
        ds = self.model.dataset
        styles = self.prefs.styles(ds.ac.dim, ds.ac.weights is not None)
        rgb = None
        if ds.atomic_numbers is not None:  # a molecule: atoms in CPK colours, its cavities
            styles["balls"], styles["cavities"] = ATOM_STYLE, CAVITY_STYLE
            styles["pockets"], styles["mouths"] = POCKET_STYLE, MOUTH_STYLE
            rgb = cpk_rgb(ds.atomic_numbers)
        self.layers_panel.set_layers(styles)  # first: the docks it widens redraw no shape
        self.scene.set_dataset(scene_data(ds, styles, rgb))
        self.colourer.set_dataset(ds.attributes)
        self._show_banner(subsample_banner(ds))
        self.setWindowTitle(f"Alpha Scoop - {ds.path.name}")
        self.alpha_panel.slider.setFocus()

    def _show_measures(self) -> None:
        """A molecule's measures arrived: its pockets and their mouths become layers (with
        the styles the Layers dock holds for them), drawn once."""
        ds = self.model.dataset
        pockets = pockets_of(ds)
        if pockets is None:  # they failed (model.measures_failure): nothing to draw
            return
        self.scene.add_pockets(pockets, self.layers_panel.styles)
        exposed = exposed_of(ds)
        if exposed is not None:
            self.scene.set_exposed(exposed)
        self.colourer.update()
        self.scene.render()

    def _show_banner(self, text: str | None) -> None:
        """Show the subsample banner with `text`, or hide it (None)."""
        self.banner.setText(text or "")
        self.banner.setVisible(text is not None)

    def _show_released(self) -> None:
        """The dataset was released: an empty view until the next one arrives."""
        self._show_banner(None)
        self.scene.clear()
        self.scene.render()
        self.setWindowTitle("Alpha Scoop")

    def _show_shape(self) -> None:
        """New alpha: swap layer connectivity, one render, status line."""
        self.scene.set_shape(self.model.shape)
        self.colourer.update()
        if self.model.dataset.atomic_numbers is not None:
            self.scene.set_cells("cavities", self.model.cavities())
        self.scene.render()
        self._show_status()

    def _end_drag(self) -> None:
        """The slider's release: its last alpha first (still queued when the release came
        with the last move), then the full frame, drawn once."""
        self.alpha_panel.flush()
        self.scene.set_level_of_detail(False)

    def _show_status(self) -> None:
        """Status line: points, cells, alpha, where the table came from, the topology, and a
        molecule's failed measures (kept on every later line)."""
        ds = self.model.dataset
        self.status.setText(
            f"{len(ds.ac.points):,} points · {len(self.model.shape.cells):,} cells · "
            + (f"alpha² {self.model.alpha2:.6g}" if self.model.weighted
               else f"alpha {self.model.alpha:.6g}")
            + (f" ({ds.ac.mode.name})" if ds.ac.mode.active else "")
            + f" · {ds.build_line()} · {ds.topology_line()}"
            + (f" · {self.model.measures_failure} (the shape and the slider still work)"
               if self.model.measures_failure else "")
        )

    def _set_style(self, name: str, style) -> None:
        """Apply and remember one layer's style; render once."""
        self.scene.set_style(name, style)
        self.colourer.update()
        if self.model.dataset is not None:
            self.prefs.set_style(self.model.dataset.ac.dim, name, style)
        self.scene.render()

    def event(self, event: QEvent) -> bool:
        """Before the window paints, lay out what a step's new texts asked for: Qt would lay
        them out after this paint and paint (compose the whole window) again."""
        if event.type() == QEvent.Type.UpdateRequest:
            for _ in range(LAYOUT_DEPTH):
                QCoreApplication.sendPostedEvents(None, QEvent.Type.LayoutRequest)
        return super().event(event)

    def dragEnterEvent(self, event) -> None:
        """Accept drags that carry local files."""
        if any(url.isLocalFile() for url in event.mimeData().urls()):
            event.acceptProposedAction()

    def dropEvent(self, event) -> None:
        """Open the first dropped local file."""
        files = [url.toLocalFile() for url in event.mimeData().urls() if url.isLocalFile()]
        if files:
            self.open_asking(files[0])
            event.acceptProposedAction()

    def _restore_layout(self) -> None:
        """Restore window geometry and dock layout from the preferences."""
        store = self.prefs.store
        if store.contains("window/geometry"):
            self.restoreGeometry(store.value("window/geometry"))
            self.restoreState(store.value("window/state"))

    def closeEvent(self, event) -> None:
        """Save the layout, stop the worker (hidden meanwhile), release VTK before Qt.

        Big builds run in a child process that cancel kills; what stays in the worker thread
        (reading, loading a cached table) cannot be interrupted, so the wait is bounded: after
        CLOSE_WAIT_MS the window closes anyway and a late result is dropped (stale request id).
        """
        self.prefs.store.setValue("window/geometry", self.saveGeometry())
        self.prefs.store.setValue("window/state", self.saveState())
        runners = (self.loader, self.topology, self.measures, self.jobs)
        for runner in runners:
            runner.cancel()
        if any(runner.is_busy() for runner in runners):
            self.hide()
        for runner in runners:  # a late result never reaches a closed window
            runner.shut_down(CLOSE_WAIT_MS)
        self.scene.close()
        super().closeEvent(event)

    def report(self, message: str) -> None:
        """Show a short result message (exports, screenshots) in the status bar."""
        self.status.setText(message)

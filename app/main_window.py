"""The explorer's main window: a QtInteractor in a QMainWindow (composition only)."""

from __future__ import annotations

import os

os.environ["QT_API"] = "pyside6"

from pathlib import Path

from PySide6.QtGui import QIcon
from PySide6.QtWidgets import QMainWindow
from pyvistaqt import QtInteractor

from app.loading import read_points
from app.resources import ICON_PATH
from app.scene import Scene


class MainWindow(QMainWindow):
    """Main window with the 3D view at its centre."""

    def __init__(self) -> None:
        """Create the view; no dataset until open_path."""
        super().__init__()
        self.setWindowTitle("Alpha Scoop")
        self.setWindowIcon(QIcon(str(ICON_PATH)))
        self.plotter = QtInteractor(self, auto_update=False)
        self.plotter.set_background("#1f2a36")
        self.setCentralWidget(self.plotter)
        self.scene = Scene(self.plotter)

    def open_path(self, path: str | Path) -> None:
        """Load the points of path and show them."""
        self.scene.set_points(read_points(path))
        self.setWindowTitle(f"Alpha Scoop - {Path(path).name}")
        self.scene.render()

    def closeEvent(self, event) -> None:
        """Close the plotter with the window, so VTK is released before Qt."""
        self.plotter.close()
        super().closeEvent(event)

"""File → Export shape's dialog: a save dialog with the manifold option and a file name that
carries the alpha (e.g. bunny_alpha0.01529.ply)."""

from __future__ import annotations

from pathlib import Path

from PySide6.QtWidgets import QCheckBox, QFileDialog, QWidget

from app.file_actions import filter_extension, name_filters
from app.modal import run_dialog
from app.settings import Preferences
from core.export import SHAPE_FORMATS

MANIFOLD_TEXT = "Manifold surface: split where the shape touches itself"
MANIFOLD_TIP = ("3D surfaces: copy the vertices where the shape pinches, so the file is a "
                "closed 2-manifold that slicers and CAD tools accept. Off: the raw boundary.")


def default_shape_name(stem: str, alpha: float, ext: str = ".ply") -> str:
    """'bunny_alpha0.01529.ply': the data's name and the alpha shown (4 significant digits).

    The extension is part of it: choosing another format in the dialog swaps the part after
    the last dot, which must not be the alpha's decimals.
    """
    return f"{stem}_alpha{alpha:.4g}{ext}"


class ExportShapeDialog(QFileDialog):
    """Qt's own (non-native) save dialog, with a manifold check box under the file name."""

    def __init__(self, parent: QWidget | None, start: Path, manifold: bool,
                 title: str = "Export shape") -> None:
        """Start at `start` (folder / default name); the box checked as `manifold`."""
        super().__init__(parent, title, str(start), name_filters(SHAPE_FORMATS))
        self.setAcceptMode(QFileDialog.AcceptMode.AcceptSave)
        self.setOption(QFileDialog.Option.DontUseNativeDialog, True)
        self.manifold = QCheckBox(MANIFOLD_TEXT)
        self.manifold.setToolTip(MANIFOLD_TIP)
        self.manifold.setChecked(manifold)
        grid = self.layout()
        grid.addWidget(self.manifold, grid.rowCount(), 0, 1, grid.columnCount())

    def chosen_path(self) -> Path | None:
        """The file chosen, with the selected format's extension added when none was typed."""
        files = self.selectedFiles()
        if not files or not files[0]:
            return None
        path = Path(files[0])
        if path.suffix.lower() not in SHAPE_FORMATS:
            path = path.with_name(path.name + filter_extension(self.selectedNameFilter(),
                                                               SHAPE_FORMATS))
        return path


def ask_export_shape(parent: QWidget, prefs: Preferences, stem: str, alpha: float,
                     title: str = "Export shape") -> tuple[Path, bool] | None:
    """(path, manifold) for File → Export shape (or another export of the shape: `title`),
    or None if cancelled; both remembered."""
    start = Path(prefs.last_dir() or ".") / default_shape_name(stem, alpha)
    dialog = ExportShapeDialog(parent, start, prefs.export_manifold(), title)
    try:
        if not run_dialog(dialog) or (path := dialog.chosen_path()) is None:
            return None
        manifold = dialog.manifold.isChecked()
    finally:
        dialog.deleteLater()
    prefs.set_last_dir(path)
    prefs.set_export_manifold(manifold)
    return path, manifold

"""The import dialog shown before a text or big file is opened: coordinate columns (detected,
with a preview of the first rows and whether they are geographic) and subsampling.

Choices are remembered per file type (core.io extension) in the preferences.
"""

from __future__ import annotations

from pathlib import Path

from PySide6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QDialog,
    QDialogButtonBox,
    QFormLayout,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QSpinBox,
    QTableWidget,
    QTableWidgetItem,
    QVBoxLayout,
    QWidget,
)

from app.dataset import ImportOptions
from app.full_export import above_budget
from app.modal import run_dialog
from app.settings import Preferences
from core.errors import FileFormatError
from core.io import SUBSAMPLE_METHODS
from core.io.columns import named_coordinates, parse_columns
from core.io.geographic import geographic_axes
from core.io.text_preview import preview

TEXT_FORMATS = (".xyz", ".pts", ".txt", ".csv")
BIG_FILE_BYTES = 64 * 1024**2  # from this size on, the dialog offers to subsample first
PREVIEW_ROWS = 8
DEFAULT_SUBSAMPLE = 1_000_000
GEOGRAPHIC = "geographic: longitude/latitude degrees, projected to metres (local conformal)"
CARTESIAN = "cartesian: coordinates used as they are"


def is_big(path: Path) -> bool:
    """A file of BIG_FILE_BYTES or more, or one whose header declares more points than the
    window can build in the memory available (app.full_export.above_budget)."""
    try:
        return path.stat().st_size >= BIG_FILE_BYTES or above_budget(path)
    except OSError:
        return False  # the reader will say what is wrong with it


def needs_dialog(path: Path) -> bool:
    """Text files (columns to choose) and big files (subsampling to offer) get the dialog."""
    return path.suffix.lower() in TEXT_FORMATS or is_big(path)


def chosen_names(columns: str, names: list[str] | None) -> list[str] | None:
    """Header names of the coordinate columns `columns` picks ('' = detected), if known."""
    if not names:
        return None
    if not columns.strip():
        picked = named_coordinates(names)
        return None if picked is None else [names[i] for i in picked]
    try:
        items = parse_columns(columns)
    except FileFormatError:
        return None
    out = [names[i] if isinstance(i, int) and -len(names) <= i < len(names) else i
           for i in items]
    return [n for n in out if isinstance(n, str)]


class ImportDialog(QDialog):
    """Columns (text files) and subsampling for one file; `options()` is the choice."""

    def __init__(self, parent: QWidget | None, path: Path, columns: str = "",
                 subsample: int = 0, method: str = "voxel") -> None:
        """Show `path`'s layout; start from the remembered columns/subsample/method."""
        super().__init__(parent)
        self.setWindowTitle(f"Import {path.name}")
        self.names: list[str] | None = None
        self.columns = QLineEdit(columns)
        self.columns.setPlaceholderText("detected")
        self.detected, self.kind = QLabel(), QLabel()
        self.table = QTableWidget()
        self.subsample = QCheckBox("Subsample to at most")
        self.count = QSpinBox()
        self.count.setRange(1, 2_000_000_000)
        self.count.setGroupSeparatorShown(True)
        self.count.setValue(subsample or DEFAULT_SUBSAMPLE)
        self.subsample.setChecked(bool(subsample) or is_big(path))
        self.method = QComboBox()
        self.method.addItems(SUBSAMPLE_METHODS)
        self.method.setCurrentText(method if method in SUBSAMPLE_METHODS else "voxel")
        self._layout(path)
        self.columns.textChanged.connect(self._show_kind)
        self._show_kind()

    def _layout(self, path: Path) -> None:
        """Arrange: file, columns and preview (text files), subsampling, buttons."""
        box = QVBoxLayout(self)
        box.addWidget(QLabel(f"{path.name} ({_size(path):,} bytes)"))
        if path.suffix.lower() in TEXT_FORMATS:
            form = QFormLayout()
            form.addRow("Coordinate columns", self.columns)
            form.addRow("", self.detected)
            form.addRow("Coordinates", self.kind)
            box.addLayout(form)
            box.addWidget(self.table)
            self._fill_preview(path)
        else:
            self.columns.setEnabled(False)
        row = QHBoxLayout()
        for widget in (self.subsample, self.count, QLabel("points by"), self.method):
            row.addWidget(widget)
        box.addLayout(row)
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Open
                                   | QDialogButtonBox.StandardButton.Cancel)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        box.addWidget(buttons)

    def _fill_preview(self, path: Path) -> None:
        """The reader's view of the file's head: header names and the first rows."""
        try:
            layout, rows = preview(path, PREVIEW_ROWS)
        except (FileFormatError, OSError) as error:
            self.detected.setText(str(error))
            return
        self.names = layout.names
        width = max([layout.n_cols, *(len(r) for r in rows)])
        self.table.setRowCount(len(rows))
        self.table.setColumnCount(width)
        labels = [str(i) for i in range(width)]
        if layout.names:
            labels[: len(layout.names)] = [f"{i}: {n}" for i, n in enumerate(layout.names)]
        self.table.setHorizontalHeaderLabels(labels)
        for r, cells in enumerate(rows):
            for c, cell in enumerate(cells):
                self.table.setItem(r, c, QTableWidgetItem(cell))
        picked = named_coordinates(layout.names) if layout.names else None
        detected = ("header: " + ", ".join(layout.names)) if layout.names else (
            f"no header: {layout.n_cols} columns, the first 2-3 numeric ones are used")
        if picked is not None:
            detected += " (coordinates: " + ",".join(layout.names[i] for i in picked) + ")"
        self.detected.setText(detected)

    def _show_kind(self) -> None:
        """Say whether the chosen (or detected) coordinate columns are geographic."""
        names = chosen_names(self.columns.text(), self.names)
        self.kind.setText(GEOGRAPHIC if names and geographic_axes(names) else CARTESIAN)

    def is_geographic(self) -> bool:
        """True when the coordinates chosen are longitude/latitude."""
        return self.kind.text() == GEOGRAPHIC

    def options(self) -> ImportOptions:
        """The choice as ImportOptions (columns None = detected; subsample None = all)."""
        columns = self.columns.text().strip() if self.columns.isEnabled() else ""
        return ImportOptions(columns=columns or None,
                             subsample=self.count.value() if self.subsample.isChecked() else None,
                             subsample_method=self.method.currentText())


def _size(path: Path) -> int:
    try:
        return path.stat().st_size
    except OSError:
        return 0


def ask_import_options(parent: QWidget | None, path: Path,
                       prefs: Preferences) -> ImportOptions | None:
    """The options to read `path` with: asked in the dialog for text and big files (None when
    cancelled), plain reading otherwise; choices remembered per file type."""
    if not needs_dialog(path):
        return ImportOptions()
    ext = path.suffix.lower()
    dialog = ImportDialog(parent, path, *prefs.import_options(ext))
    try:
        if not run_dialog(dialog):
            return None
        options = dialog.options()
    finally:
        dialog.deleteLater()
    prefs.set_import_options(ext, options.columns or "", options.subsample or 0,
                             options.subsample_method)
    return options

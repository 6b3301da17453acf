"""Mode dock: classic, density-scaled or anisotropic alpha (core.modes.alpha_modes) and their
parameters.

Rebuild asks the window to build the open file again in the chosen mode; the build runs in
the background like an open, and the current shape stays until the new table is ready.
"""

from __future__ import annotations

from PySide6.QtCore import QSignalBlocker, Signal
from PySide6.QtWidgets import (
    QComboBox,
    QDoubleSpinBox,
    QFormLayout,
    QLabel,
    QPushButton,
    QSpinBox,
    QWidget,
)

from core.modes.alpha_modes import Mode, make_mode

KINDS = ("Classic", "Density-scaled", "Anisotropic")
DEFAULT_NEIGHBOURS, DEFAULT_TAU = 8, 0.5


class ModePanel(QWidget):
    """A mode selector with its parameters; `modeChosen(Mode)` when Rebuild is pressed."""

    modeChosen = Signal(object)

    def __init__(self, parent: QWidget | None = None) -> None:
        """Build the widgets (classic selected)."""
        super().__init__(parent)
        self.kind = QComboBox()
        self.kind.addItems(KINDS)
        self.neighbours = QSpinBox()
        self.neighbours.setRange(1, 1000)
        self.neighbours.setValue(DEFAULT_NEIGHBOURS)
        self.neighbours.setToolTip("local spacing = distance to the K-th nearest neighbour")
        self.combine = QComboBox()
        self.combine.addItems(("mean", "max"))
        self.combine.setToolTip("how a simplex combines its vertices' spacings")
        self.tau = QDoubleSpinBox()
        self.tau.setRange(0.0, 0.99)
        self.tau.setSingleStep(0.05)
        self.tau.setValue(DEFAULT_TAU)
        self.tau.setToolTip("the alpha ball is compressed along the normal to 1 - tau")
        self.normals = QComboBox()
        self.normals.addItems(("estimate", "file"))
        self.normals.setToolTip("normals estimated by PCA, or the file's own")
        self.rebuild = QPushButton("Rebuild")
        self.built = QLabel()
        self.built.setWordWrap(True)
        form = QFormLayout(self)
        form.addRow("alpha", self.kind)
        form.addRow("neighbours K", self.neighbours)
        form.addRow("combine", self.combine)
        form.addRow("tau", self.tau)
        form.addRow("normals", self.normals)
        form.addRow(self.rebuild)
        form.addRow(self.built)
        self.kind.currentIndexChanged.connect(self._enable)
        self.rebuild.clicked.connect(lambda _=False: self.modeChosen.emit(self.mode()))
        self._enable()

    def _enable(self) -> None:
        """Only the chosen mode's parameters are editable."""
        kind = self.kind.currentIndex()
        for widget in (self.neighbours, self.combine):
            widget.setEnabled(kind == 1)
        for widget in (self.tau, self.normals):
            widget.setEnabled(kind == 2)

    def mode(self) -> Mode:
        """The mode the widgets describe."""
        kind = self.kind.currentIndex()
        if kind == 1:
            return make_mode(self.neighbours.value(), self.combine.currentText())
        if kind == 2 and self.tau.value() > 0.0:
            return make_mode(None, "mean", self.tau.value(), self.normals.currentText() == "file")
        return Mode()

    def set_mode(self, mode: Mode) -> None:
        """Show `mode` in the widgets (no modeChosen)."""
        blockers = [QSignalBlocker(w) for w in (self.kind, self.neighbours, self.combine,
                                               self.tau, self.normals)]
        self.kind.setCurrentIndex(1 if mode.density is not None
                                  else 2 if mode.anisotropy > 0.0 else 0)
        if mode.density is not None:
            self.neighbours.setValue(mode.density)
            self.combine.setCurrentText(mode.combine)
        if mode.anisotropy > 0.0:
            self.tau.setValue(mode.anisotropy)
            self.normals.setCurrentText("file" if mode.normals == "given" else "estimate")
        del blockers
        self._enable()

    def show_built(self, mode: Mode) -> None:
        """Say which mode the shown table was built in."""
        self.built.setText(f"shown: {mode.describe()}")

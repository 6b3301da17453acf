"""Alpha control: a slider over the spectrum index, an exact radius field, r², optimal/hull.

The slider, the field and the model show one value; widget changes go to the model, and the
model's alphaChanged updates the widgets under signal blockers (no feedback loop). Slider
events are coalesced with a zero-interval timer, so a fast drag queues no stale work.
"""

from __future__ import annotations

from PySide6.QtCore import QLocale, QSignalBlocker, Qt, QTimer
from PySide6.QtGui import QDoubleValidator
from PySide6.QtWidgets import (
    QFormLayout,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QPushButton,
    QSlider,
    QVBoxLayout,
    QWidget,
)

from app.model import ExplorerModel

PAGE_STEPS = 50


def format_alpha(value: float) -> str:
    """Alpha text for the field: 6 significant digits, 'inf' when infinite."""
    return f"{value:.6g}"


def radius_validator() -> QDoubleValidator:
    """Accepts radii >= 0 typed with '.' whatever the system locale, in plain or e-notation."""
    validator = QDoubleValidator(0.0, 1e300, 12)
    validator.setLocale(QLocale.c())
    validator.setNotation(QDoubleValidator.Notation.ScientificNotation)
    return validator


class AlphaPanel(QWidget):
    """Slider + radius field + r² + buttons, bound to an ExplorerModel."""

    def __init__(self, model: ExplorerModel, parent: QWidget | None = None) -> None:
        """Build the widgets and wire them to model."""
        super().__init__(parent)
        self.model = model
        self.slider = QSlider(Qt.Orientation.Horizontal)
        self.slider.setFocusPolicy(Qt.FocusPolicy.StrongFocus)
        self.slider.setTracking(True)
        self.radius = QLineEdit()
        self.radius.setValidator(radius_validator())
        self.radius.setToolTip("alpha as a radius; Enter snaps to the shape at that value")
        self.squared = QLabel()
        self.squared.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.squared.setToolTip("alpha squared: the value CGAL and gudhi use")
        self.step = QLabel()
        self.optimal = QPushButton("Optimal")
        self.hull = QPushButton("Convex hull")
        self._pending = 0
        self._timer = QTimer(self, singleShot=True, interval=0)
        self._layout()
        self._connect()
        self.sync()

    def _layout(self) -> None:
        """Arrange: r and r² fields, slider with position, buttons."""
        form = QFormLayout()
        form.addRow("r", self.radius)
        form.addRow("r²", self.squared)
        buttons = QHBoxLayout()
        buttons.addWidget(self.optimal)
        buttons.addWidget(self.hull)
        column = QVBoxLayout(self)
        column.addLayout(form)
        column.addWidget(self.slider)
        column.addWidget(self.step)
        column.addLayout(buttons)
        column.addStretch(1)

    def _connect(self) -> None:
        """Widget -> model (slider coalesced), model -> widgets."""
        self.slider.valueChanged.connect(self._queue_index)
        self._timer.timeout.connect(lambda: self.model.set_index(self._pending))
        self.radius.editingFinished.connect(self._apply_radius)
        self.optimal.clicked.connect(lambda: self.model.set_index(self.model.optimal_index()))
        self.hull.clicked.connect(lambda: self.model.set_index(self.model.hull_index()))
        self.model.datasetChanged.connect(self._timer.stop)
        self.model.datasetChanged.connect(self.sync)
        self.model.alphaChanged.connect(self.sync)

    def _queue_index(self, index: int) -> None:
        """Remember the newest slider index; the model gets it once events settle."""
        self._pending = index
        self._timer.start()

    def _apply_radius(self) -> None:
        """Send the typed radius to the model (it snaps to the critical value at or below)."""
        try:
            value = float(self.radius.text())
        except ValueError:
            self.sync()
            return
        self.model.set_alpha(value)
        self.sync()

    def sync(self) -> None:
        """Show the model's alpha in every widget without echoing back."""
        count = len(self.model.spectrum)
        self.setEnabled(count > 0)
        with QSignalBlocker(self.slider):
            self.slider.setRange(0, max(count - 1, 0))
            self.slider.setPageStep(max(1, count // PAGE_STEPS))
            self.slider.setValue(max(self.model.index, 0))
        if count == 0:
            self.radius.clear()
            self.squared.clear()
            self.step.clear()
            return
        alpha = self.model.alpha
        self.radius.setText(format_alpha(alpha) if alpha >= 0 else "")
        self.radius.setPlaceholderText("below zero radius: see r²" if alpha < 0 else "")
        self.squared.setText(f"{self.model.alpha2:.6g}")
        self.squared.setToolTip("alpha squared: the value CGAL and gudhi use"
                                + ("; weighted points enter at minus their squared radius"
                                   if self.model.weighted else ""))
        self.step.setText(f"critical value {self.model.index + 1:,} of {count:,}")

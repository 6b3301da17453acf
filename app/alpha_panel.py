"""Alpha control: a slider in log alpha, an exact radius field, r², back/forward, optimal/hull.

The slider's travel follows log alpha (app.log_travel) but it always lands on a critical
value: arrows step one, Page keys multiply alpha by a factor. The slider, the field and the
model show one value; widget changes go to the model, and the model's alphaChanged updates
the widgets under signal blockers (no feedback loop). Slider moves and key presses are
coalesced with a zero-interval timer, so a fast drag queues no stale work.
"""

from __future__ import annotations

from PySide6.QtCore import QLocale, QSignalBlocker, Qt, Signal
from PySide6.QtGui import QDoubleValidator
from PySide6.QtWidgets import (
    QFormLayout,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QPushButton,
    QSizePolicy,
    QVBoxLayout,
    QWidget,
)

from app.alpha_slider import AlphaSlider, Mark
from app.dataset import suggestions_of
from app.log_travel import LogTravel, snap_index
from app.model import ExplorerModel
from app.palette import MARK_COLOURS
from app.signed_travel import SignedTravel

OPTIMAL_TEXT, OPTIMAL_WAIT_TEXT = "Optimal", "Optimal: computing…"


def format_alpha(value: float) -> str:
    """Alpha text for the field: 6 significant digits, 'inf' when infinite."""
    return f"{value:.6g}"


def set_text(widget: QLabel | QLineEdit | QPushButton, text: str) -> None:
    """Set widget's text only when it differs: an unchanged row is not laid out again."""
    if widget.text() != text:
        widget.setText(text)


def radius_validator() -> QDoubleValidator:
    """Accepts radii >= 0 typed with '.' whatever the system locale, in plain or e-notation."""
    validator = QDoubleValidator(0.0, 1e300, 12)
    validator.setLocale(QLocale.c())
    validator.setNotation(QDoubleValidator.Notation.ScientificNotation)
    return validator


class AlphaPanel(QWidget):
    """Slider + radius field + r² + buttons, bound to an ExplorerModel."""

    _indexQueued = Signal()  # delivered queued: hands the newest slider index to the model

    def __init__(self, model: ExplorerModel, parent: QWidget | None = None) -> None:
        """Build the widgets and wire them to model."""
        super().__init__(parent)
        self.model = model
        self.slider = AlphaSlider()
        self.travel: LogTravel | SignedTravel | None = None
        self.radius = QLineEdit()
        self.radius.setValidator(radius_validator())
        self.radius.setToolTip("alpha as a radius; Enter snaps to the shape at that value")
        self.squared = QLabel()
        self.squared.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.squared.setToolTip("alpha squared: the value CGAL and gudhi use")
        self.step = QLabel()
        for label in (self.squared, self.step):  # changing text never resizes the dock
            label.setSizePolicy(QSizePolicy.Policy.Ignored, QSizePolicy.Policy.Preferred)
        self.optimal = QPushButton(OPTIMAL_TEXT)
        self.optimal.setToolTip("CGAL's optimal alpha: every point in one solid (Ctrl+1)")
        self.hull = QPushButton("Convex hull")
        self.back = QPushButton("◀ Back")
        self.back.setToolTip("the alpha visited before (Alt+Left)")
        self.forward = QPushButton("Forward ▶")
        self.forward.setToolTip("redo Back (Alt+Right)")
        self._pending = 0
        self._queued = False  # an index waits for the queued call
        self._layout()
        self._connect()
        if model.dataset is not None:
            self._new_travel()
        self.sync()

    def _layout(self) -> None:
        """Arrange: r and r² fields, slider with position, buttons."""
        form = QFormLayout()
        form.addRow("r", self.radius)
        form.addRow("r²", self.squared)
        buttons = QHBoxLayout()
        buttons.addWidget(self.optimal)
        buttons.addWidget(self.hull)
        history = QHBoxLayout()
        history.addWidget(self.back)
        history.addWidget(self.forward)
        column = QVBoxLayout(self)
        column.addLayout(form)
        column.addWidget(self.slider)
        column.addWidget(self.step)
        column.addLayout(history)
        column.addLayout(buttons)
        column.addStretch(1)

    def _connect(self) -> None:
        """Widget -> model (slider coalesced), model -> widgets."""
        self.slider.valueChanged.connect(
            lambda position: self._queue_index(self.travel.index_at(position)))
        self.slider.stepRequested.connect(lambda step: self._queue_index(self._base() + step))
        self.slider.pageRequested.connect(
            lambda up: self._queue_index(self.travel.page(self._base(), up)))
        self.slider.endRequested.connect(
            lambda end: self._queue_index(self.model.hull_index() if end else 0))
        self.slider.historyRequested.connect(
            lambda forward: self.model.go_forward() if forward else self.model.go_back())
        self.back.clicked.connect(self.model.go_back)
        self.forward.clicked.connect(self.model.go_forward)
        self._indexQueued.connect(self.flush, Qt.ConnectionType.QueuedConnection)
        self.radius.editingFinished.connect(self._apply_radius)
        self.optimal.clicked.connect(lambda: self.model.set_index(self.model.optimal_index()))
        self.hull.clicked.connect(lambda: self.model.set_index(self.model.hull_index()))
        self.model.datasetChanged.connect(self._drop_queued)
        self.model.datasetChanged.connect(self._new_travel)
        self.model.datasetChanged.connect(self.sync)
        self.model.topologyChanged.connect(self._new_travel)
        self.model.topologyChanged.connect(self.sync)
        self.model.alphaChanged.connect(self.sync)
        self.model.datasetReleased.connect(self._forget)

    def _base(self) -> int:
        """The index a key moves from: a still-queued one, else the model's."""
        return self._pending if self._queued else self.model.index

    def _queue_index(self, index: int) -> None:
        """Remember the newest slider index; the model gets it once events settle."""
        if self.model.dataset is None:
            return
        self._pending = max(0, min(index, self.model.hull_index()))
        if not self._queued:
            self._queued = True
            self._indexQueued.emit()

    def flush(self) -> None:
        """Hand the model the still-queued slider index, if any (the queued call, or now: a
        release draws no older alpha)."""
        if self._queued:
            self._queued = False
            self.model.set_index(self._pending)

    def _drop_queued(self) -> None:
        """Forget a queued index (it belonged to the dataset before)."""
        self._queued = False

    def _new_travel(self) -> None:
        """A new dataset or its topology: the log-alpha travel and tick marks (suggested,
        opening, optimal; the opening one only until the topology is known)."""
        ds = self.model.dataset
        travel = SignedTravel if self.model.weighted else LogTravel  # alpha² < 0: no log
        self.travel = travel(ds.spectrum, reach=ds.optimal_alpha)
        self.slider.set_marks(tuple(self.marks()))

    def _forget(self) -> None:
        """The dataset was released: no travel (it holds the spectrum), no marks, disabled."""
        self._drop_queued()
        self.travel = None
        self.slider.set_marks(())
        self.sync()

    def marks(self) -> list[Mark]:
        """Tick marks of the current dataset: suggested alphas, the opening and optimal one
        (the suggested and optimal ones once the topology is known)."""
        ds, model = self.model.dataset, self.model
        opening = Mark(self.travel.position(model.default_index()), MARK_COLOURS["opening"],
                       f"opening: r {ds.default_alpha:.4g}")
        if not ds.has_topology:
            return [opening]
        marks = [Mark(self.travel.position(snap_index(ds.spectrum, r.alpha)),
                      MARK_COLOURS["suggested"], f"suggested: r {r.alpha:.4g} (Betti {r.betti})")
                 for r in suggestions_of(ds)]
        marks.append(opening)
        marks.append(Mark(self.travel.position(model.optimal_index()), MARK_COLOURS["optimal"],
                          f"optimal: r {ds.optimal_alpha:.4g}"))
        return marks

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
            position = self.travel.position(self.model.index) if count else 0
            self.slider.setValue(position)
        self.back.setEnabled(self.model.history.can_back())
        self.forward.setEnabled(self.model.history.can_forward())
        ready = count > 0 and self.model.dataset.has_topology
        self.optimal.setEnabled(ready)
        set_text(self.optimal, OPTIMAL_TEXT if ready or count == 0 else OPTIMAL_WAIT_TEXT)
        if count == 0:
            self.radius.clear()
            self.squared.clear()
            self.step.clear()
            return
        alpha = self.model.alpha
        set_text(self.radius, format_alpha(alpha) if alpha >= 0 else "")
        placeholder = "below zero radius: see r²" if alpha < 0 else ""
        if self.radius.placeholderText() != placeholder:
            self.radius.setPlaceholderText(placeholder)
        set_text(self.squared, f"{self.model.alpha2:.6g}")
        tip = ("alpha squared: the value CGAL and gudhi use"
               + ("; weighted points enter at minus their squared radius"
                  if self.model.weighted else ""))
        if self.squared.toolTip() != tip:
            self.squared.setToolTip(tip)
        set_text(self.step, f"critical value {self.model.index + 1:,} of {count:,}")

"""The alpha slider: keys step through critical values, ticks mark the alphas worth a look.

Positions come from app.log_travel (log alpha); the slider itself only turns keys into
requests (one critical value, a page, an end, back/forward) and paints tick marks.
"""

from __future__ import annotations

from dataclasses import dataclass

from PySide6.QtCore import QPoint, Qt, Signal
from PySide6.QtGui import QColor, QKeyEvent, QPainter, QPen
from PySide6.QtWidgets import QSlider, QStyle, QStyleOptionSlider

from app.log_travel import TRAVEL

TICK_LENGTH = 6
STEP_KEYS = {Qt.Key.Key_Left: -1, Qt.Key.Key_Down: -1, Qt.Key.Key_Right: 1, Qt.Key.Key_Up: 1}


@dataclass(frozen=True)
class Mark:
    """A tick on the slider: position 0..TRAVEL, colour '#rrggbb', what it marks."""

    position: int
    colour: str
    label: str


class AlphaSlider(QSlider):
    """Horizontal slider over 0..TRAVEL that reports key presses as alpha requests."""

    stepRequested = Signal(int)  # -1 / +1 critical value
    pageRequested = Signal(bool)  # True: up (alpha x factor), False: down
    endRequested = Signal(bool)  # True: the hull, False: the first value
    historyRequested = Signal(bool)  # True: forward, False: back

    def __init__(self) -> None:
        """Empty slider with no marks."""
        super().__init__(Qt.Orientation.Horizontal)
        self.setRange(0, TRAVEL)
        self.setFocusPolicy(Qt.FocusPolicy.StrongFocus)
        self.setTracking(True)
        self.setMinimumHeight(self.sizeHint().height() + 2 * TICK_LENGTH)
        self.marks: tuple[Mark, ...] = ()

    def set_marks(self, marks: tuple[Mark, ...]) -> None:
        """Show these tick marks (and list them in the tooltip)."""
        self.marks = tuple(marks)
        self.setToolTip("<br>".join(mark.label for mark in self.marks))
        self.update()

    def keyPressEvent(self, event: QKeyEvent) -> None:
        """Arrows: one critical value; PageUp/Down: a factor of alpha; Home/End; Alt+arrows:
        back/forward."""
        key, alt = event.key(), bool(event.modifiers() & Qt.KeyboardModifier.AltModifier)
        if alt and key in (Qt.Key.Key_Left, Qt.Key.Key_Right):
            self.historyRequested.emit(key == Qt.Key.Key_Right)
        elif key in STEP_KEYS:
            self.stepRequested.emit(STEP_KEYS[key])
        elif key in (Qt.Key.Key_PageUp, Qt.Key.Key_PageDown):
            self.pageRequested.emit(key == Qt.Key.Key_PageUp)
        elif key in (Qt.Key.Key_Home, Qt.Key.Key_End):
            self.endRequested.emit(key == Qt.Key.Key_End)
        else:
            super().keyPressEvent(event)
            return
        event.accept()

    def mark_x(self, position: int) -> int:
        """Pixel x of a slider position (where the handle's centre would be)."""
        option = QStyleOptionSlider()
        self.initStyleOption(option)
        style = self.style()
        groove = style.subControlRect(QStyle.ComplexControl.CC_Slider, option,
                                      QStyle.SubControl.SC_SliderGroove, self)
        handle = style.subControlRect(QStyle.ComplexControl.CC_Slider, option,
                                      QStyle.SubControl.SC_SliderHandle, self)
        span = groove.width() - handle.width()
        return (groove.x() + handle.width() // 2
                + QStyle.sliderPositionFromValue(self.minimum(), self.maximum(), position, span))

    def paintEvent(self, event) -> None:
        """The slider, then its marks as short ticks below the groove."""
        super().paintEvent(event)
        if not self.marks:
            return
        painter = QPainter(self)
        bottom = self.height() - 1
        for mark in self.marks:
            painter.setPen(QPen(QColor(mark.colour), 2))
            x = self.mark_x(mark.position)
            painter.drawLine(QPoint(x, bottom - TICK_LENGTH), QPoint(x, bottom))
        painter.end()

"""Status-bar progress for a background task (a build, an export): stage, bar, elapsed time
and a Cancel button."""

from __future__ import annotations

import time

from PySide6.QtCore import QTimer, Signal
from PySide6.QtWidgets import QHBoxLayout, QLabel, QProgressBar, QPushButton, QWidget

TICK_MS = 200


class ProgressWidget(QWidget):
    """Hidden when idle; start() shows it, update() moves it, stop() hides it."""

    cancelRequested = Signal()

    def __init__(self, parent: QWidget | None = None) -> None:
        """Create the stage label, bar, clock and Cancel button."""
        super().__init__(parent)
        self.stage = QLabel()
        self.bar = QProgressBar(minimum=0, maximum=1000, textVisible=False)
        self.bar.setFixedWidth(160)
        self.clock = QLabel()
        self.cancel = QPushButton("Cancel")
        row = QHBoxLayout(self)
        row.setContentsMargins(0, 0, 0, 0)
        for widget in (self.stage, self.bar, self.clock, self.cancel):
            row.addWidget(widget)
        self.cancel.clicked.connect(self.cancelRequested)
        self._started = 0.0
        self._timer = QTimer(self, interval=TICK_MS)
        self._timer.timeout.connect(self._tick)
        self.hide()

    def start(self, what: str) -> None:
        """Show progress for a new job named what."""
        self._started = time.perf_counter()
        self.stage.setText(what)
        self.bar.setValue(0)
        self._tick()
        self._timer.start()
        self.show()

    def update_progress(self, fraction: float, stage: str) -> None:
        """Show fraction (0..1) done and the current stage."""
        self.bar.setValue(round(1000 * min(max(fraction, 0.0), 1.0)))
        self.stage.setText(stage)

    def stop(self) -> None:
        """Hide until the next start."""
        self._timer.stop()
        self.hide()

    def _tick(self) -> None:
        """Refresh the elapsed-time clock."""
        elapsed = int(time.perf_counter() - self._started)
        self.clock.setText(f"{elapsed // 60}:{elapsed % 60:02d}")

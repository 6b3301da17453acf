"""Run exports off the GUI thread, one at a time, with progress and cancel.

A job is `job(progress) -> str`: it reports through progress(fraction, stage), which raises
core.errors.Cancelled once Cancel was pressed (the core writers then leave the target as it
was), and returns the line that says what it wrote.
"""

from __future__ import annotations

import sys
import threading
import traceback
from collections.abc import Callable

from PySide6.QtCore import QObject, QThreadPool, Signal

from core.errors import AlphaScoopError, Cancelled
from core.progress import Progress

Job = Callable[[Progress], str]


def cancellable(cancel: threading.Event, report: Progress, why: str) -> Progress:
    """A progress callback for a worker thread: forwards reports, and raises Cancelled(why)
    at the first report after `cancel` is set."""

    def progress(fraction: float, stage: str) -> None:
        if cancel.is_set():
            raise Cancelled(why)
        report(fraction, stage)

    return progress


class JobRunner(QObject):
    """One background job at a time; its outcome comes back through queued signals."""

    progress = Signal(float, str)
    finished = Signal(str, str)  # title, what was written
    failed = Signal(str, str)  # title, why
    cancelled = Signal(str)  # title

    def __init__(self, parent: QObject | None = None) -> None:
        """A one-thread pool of its own (loading uses another)."""
        super().__init__(parent)
        self._pool = QThreadPool(self)
        self._pool.setMaxThreadCount(1)
        self._cancel = threading.Event()
        self._busy = False
        for outcome in (self.finished, self.failed, self.cancelled):
            outcome.connect(self._idle)  # queued: runs in the GUI thread, after the job ends

    def is_busy(self) -> bool:
        """True from start() until the job's outcome has reached the GUI thread."""
        return self._busy

    def start(self, title: str, job: Job) -> bool:
        """Run job in the background; False (nothing started) while another one runs."""
        if self._busy:
            return False
        self._busy = True
        self._cancel = cancel = threading.Event()
        self._pool.start(lambda: self._run(title, job, cancel))
        return True

    def _idle(self, *_outcome) -> None:
        self._busy = False

    def cancel(self) -> None:
        """Ask the running job to stop at its next progress report."""
        self._cancel.set()

    def wait(self, msecs: int = -1) -> bool:
        """Block until the worker is idle (used on close); False on timeout."""
        return self._pool.waitForDone(msecs)

    def _run(self, title: str, job: Job, cancel: threading.Event) -> None:
        """Worker-thread body: emit exactly one of finished/failed/cancelled."""
        progress = cancellable(cancel, self.progress.emit, f"{title} cancelled")
        try:
            message = job(progress)
        except Cancelled:
            self.cancelled.emit(title)
        except Exception as error:  # every failure becomes a dialog; none escapes the thread
            if not isinstance(error, AlphaScoopError):  # a bug: keep its traceback too
                traceback.print_exc(file=sys.stderr)
            self.failed.emit(title, f"{title} failed: {error or type(error).__name__}")
        else:
            self.finished.emit(title, message)

"""The window's one background runner: loads and exports run through it, off the GUI thread.

A job is a `Job`: `work(progress, cancel) -> result` plus a title and how its failures read.
Every start gets a new request id. The worker reports through progress(fraction, stage),
which raises core.errors.Cancelled once Cancel was pressed (core writers then leave their
target as it was); long steps that never report can watch `cancel` themselves (a child
process build). Outcomes come back to the GUI thread through one slot, `_deliver`, the only
place where a stale request's progress and outcome (a newer request was started, or the
runner was shut down) are dropped: listeners see exactly one outcome of the current request,
whatever the job raised (a BaseException too: SystemExit or KeyboardInterrupt then also end
the runner's thread, as Python means them to, and the next job gets a new one).
"""

from __future__ import annotations

import queue
import sys
import threading
import traceback
from collections.abc import Callable
from dataclasses import dataclass

from PySide6.QtCore import QObject, Signal

from core.errors import AlphaScoopError, Cancelled
from core.progress import Progress

Work = Callable[[Progress, threading.Event], object]
PROGRESS, FINISHED, FAILED, CANCELLED = "progress", "finished", "failed", "cancelled"


STOPS = (SystemExit, KeyboardInterrupt)  # what asks a thread to end, not only a job


def title_failed(title: str, error: Exception) -> str:
    """The default failure line: 'Export shape failed: disk full'."""
    return f"{title} failed: {error or type(error).__name__}"


def title_stopped(title: str, error: BaseException) -> str:
    """The line of a job stopped by a BaseException that is no Exception (SystemExit,
    KeyboardInterrupt, GeneratorExit): 'Open cloud.las stopped: SystemExit (3)'."""
    detail = f" ({error})" if str(error) else ""
    return f"{title} stopped: {type(error).__name__}{detail}"


@dataclass(frozen=True)
class Job:
    """What a runner runs: `work(progress, cancel)` returning its result, a `title` (shown
    with its progress and in its dialogs) and `explain(error) -> str`, the one line a
    failure shows (never a traceback)."""

    title: str
    work: Work
    explain: Callable[[Exception], str] | None = None

    def failure(self, error: BaseException) -> str:
        """The line shown for error; the default line when `explain` itself fails."""
        if not isinstance(error, Exception):
            return title_stopped(self.title, error)
        try:
            return self.explain(error) if self.explain else title_failed(self.title, error)
        except Exception:  # a bug in explain: keep its traceback, still show a line
            traceback.print_exc(file=sys.stderr)
            return title_failed(self.title, error)


def cancellable(cancel: threading.Event, report: Progress, why: str) -> Progress:
    """A progress callback for a worker thread: forwards reports, and raises Cancelled(why)
    at the first report after `cancel` is set."""

    def progress(fraction: float, stage: str) -> None:
        if cancel.is_set():
            raise Cancelled(why)
        report(fraction, stage)

    return progress


class Runner(QObject):
    """Runs one job at a time in a thread of its own; its outcome arrives as exactly one of
    finished(request, result), failed(request, message) or cancelled(request); a stale
    request's outcome is only announced as dropped(request, kind).

    `exclusive=False` (loads): a new start cancels the running request and supersedes it.
    `exclusive=True` (exports): start refuses (returns None) while a job runs.
    """

    progress = Signal(int, float, str)  # request, fraction 0..1, stage
    finished = Signal(int, object)  # request, the job's result
    failed = Signal(int, str)  # request, the one-line reason
    cancelled = Signal(int)  # request
    dropped = Signal(int, str)  # a stale request's outcome, not passed on: request, kind
    _report = Signal(int, str, object)  # worker thread -> _deliver (queued)

    def __init__(self, parent: QObject | None = None, *, exclusive: bool = False) -> None:
        """A one-thread pool: a new job waits for the previous one to stop. Its thread is a
        Python thread for the runner's life, not a Qt pool thread whose Python state is made
        and dropped around each job: pyproj 3.7 keeps a PROJ context per thread through that
        state and crashed on a second job's CRS. The thread is a daemon: a job that ignores
        Cancel is left behind at exit (closeEvent), it does not hold the process."""
        super().__init__(parent)
        self.exclusive = exclusive
        self._queue: queue.SimpleQueue = queue.SimpleQueue()
        self._thread: threading.Thread | None = None  # started with the first job
        self._active = 0  # jobs submitted and not yet returned
        self._idle = threading.Condition()  # also guards _thread and the queue's hand-over
        self._current = 0
        self._title = ""  # the newest request's job title; the job itself is not kept
        self._cancel = threading.Event()
        self._unfinished: set[int] = set()  # requests whose outcome has not been delivered
        self._report.connect(self._deliver)

    @property
    def current(self) -> int:
        """Id of the newest request (0 before the first)."""
        return self._current

    @property
    def title(self) -> str:
        """The newest request's job title (names it in messages). The runner keeps no
        reference to a job, so whatever its work holds (a dataset) is freed with it."""
        return self._title

    def is_busy(self) -> bool:
        """True from start() until every started job's outcome has reached the GUI thread."""
        return bool(self._unfinished) or self._active > 0

    def start(self, job: Job) -> int | None:
        """Run job in the background; returns its request id, or None when the runner is
        exclusive and another job is still running."""
        if self.exclusive and self._unfinished:
            return None
        self.cancel()
        self._current += 1
        request, cancel = self._current, threading.Event()
        self._title, self._cancel = job.title, cancel
        self._unfinished.add(request)
        with self._idle:
            self._active += 1
            self._queue.put((request, job, cancel))
            if self._thread is None:
                self._start_thread()
        return request

    def _start_thread(self) -> None:
        """Start the thread that serves the queue (the caller holds `_idle`)."""
        self._thread = threading.Thread(target=self._serve, name="alphascoop-job", daemon=True)
        self._thread.start()

    def cancel(self) -> None:
        """Ask the running job to stop (at its next progress report)."""
        self._cancel.set()

    def wait(self, msecs: int = -1) -> bool:
        """Block until the worker thread is idle; False on timeout."""
        with self._idle:
            return self._idle.wait_for(lambda: self._active == 0,
                                       None if msecs < 0 else msecs / 1000)

    def shut_down(self, msecs: int) -> bool:
        """Cancel, wait up to msecs, then drop whatever the job still reports (its result can
        no longer reach a closed window); False when the job had not stopped in time."""
        self.cancel()
        stopped = self.wait(msecs)
        self._current += 1  # every outstanding request is stale from now on
        return stopped

    def _serve(self) -> None:
        """The runner's thread: run the queued jobs one after another, until a job raises
        SystemExit or KeyboardInterrupt: that job's failure is reported, then the exception
        ends this thread (it is not swallowed) and the next job gets a new thread."""
        while True:
            stop = self._run(*self._queue.get())
            if stop is not None:
                raise stop

    def _run(self, request: int, job: Job, cancel: threading.Event) -> BaseException | None:
        """Worker-thread body: report exactly one outcome of request; returns the exception
        that should end the thread, if any."""
        try:
            return self._outcome(request, job, cancel)
        finally:
            with self._idle:
                self._active -= 1
                self._idle.notify_all()

    def _outcome(self, request: int, job: Job,
                 cancel: threading.Event) -> BaseException | None:
        """Run job and report its one outcome; returns a SystemExit or KeyboardInterrupt it
        raised, after handing the queue to a new thread."""
        progress = cancellable(cancel, lambda fraction, stage: self._report.emit(
            request, PROGRESS, (fraction, stage)), f"{job.title} cancelled")
        try:
            result = job.work(progress, cancel)
        except Cancelled:
            self._report.emit(request, CANCELLED, None)
        except BaseException as error:  # every failure becomes a message; none is lost
            # a stop is re-raised and ends the thread; threading.excepthook prints a
            # KeyboardInterrupt and ignores a SystemExit: the failure line names both
            stop = isinstance(error, STOPS)
            if not isinstance(error, (AlphaScoopError, MemoryError, *STOPS)):
                traceback.print_exc(file=sys.stderr)  # a bug: keep its traceback too
            if stop:
                self._retire()  # before the outcome, so a start answering it gets a thread
            self._report.emit(request, FAILED, job.failure(error))
            return error if stop else None
        else:
            self._report.emit(request, CANCELLED if cancel.is_set() else FINISHED, result)
        return None

    def _retire(self) -> None:
        """This thread is about to end: a later start begins a new one; a job queued
        meanwhile gets one now."""
        with self._idle:
            self._thread = None
            if not self._queue.empty():
                self._start_thread()

    def _deliver(self, request: int, kind: str, payload: object) -> None:
        """GUI thread: pass the current request's reports on; drop stale ones (the one place)."""
        if kind != PROGRESS:
            self._unfinished.discard(request)
        if request != self._current:
            if kind != PROGRESS:
                self.dropped.emit(request, kind)
            return
        if kind == PROGRESS:
            self.progress.emit(request, *payload)
        elif kind == FINISHED:
            self.finished.emit(request, payload)
        elif kind == FAILED:
            self.failed.emit(request, payload)
        else:
            self.cancelled.emit(request)

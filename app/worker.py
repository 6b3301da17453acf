"""Load and build datasets off the GUI thread, with progress, cancel and request ids.

Every open gets a new request id and cancels the one before; results of a request that is no
longer current are dropped, so a slow old build can never replace a newer dataset. Big
triangulations run in a child process (app.build_process) that Cancel kills at once. The
dataset is handed over as soon as the slider can use it; its topology (signatures, optimal
alpha) follows from a second thread (topologyReady), dropped too when a newer open came.
"""

from __future__ import annotations

import sys
import threading
import traceback
from pathlib import Path

from PySide6.QtCore import QObject, QThreadPool, Signal

from app import build_process
from app.dataset import Dataset, ImportOptions, load_dataset, with_topology
from app.jobs import cancellable
from core.errors import AlphaScoopError, Cancelled
from core.modes import Mode


class Loader(QObject):
    """Runs load_dataset in a one-thread pool and reports back through queued signals."""

    progress = Signal(int, float, str)
    finished = Signal(int, object)
    failed = Signal(int, str)
    cancelled = Signal(int)
    topologyReady = Signal(int, object)  # request, the dataset completed by with_topology
    topologyFailed = Signal(int, str)

    def __init__(self, parent: QObject | None = None) -> None:
        """One worker thread for loads (a new build waits for the previous one to stop) and
        one for the topology passes that follow them, so a new open never waits for one."""
        super().__init__(parent)
        self._pool = QThreadPool(self)
        self._pool.setMaxThreadCount(1)
        self._topology_pool = QThreadPool(self)
        self._topology_pool.setMaxThreadCount(1)
        self._current = 0
        self._cancel: threading.Event | None = None

    @property
    def current(self) -> int:
        """Id of the newest request (0 before the first)."""
        return self._current

    def is_busy(self) -> bool:
        """True while a request (or its topology pass) is queued or running."""
        return self._pool.activeThreadCount() + self._topology_pool.activeThreadCount() > 0

    def open(self, path: str | Path, mode: Mode | None = None,
             options: ImportOptions | None = None) -> int:
        """Start loading path (read with `options`) in the alpha `mode` (default classic);
        cancels the previous request; returns the new request id."""
        self.cancel()
        self._current += 1
        request, cancel = self._current, threading.Event()
        self._cancel = cancel
        self._pool.start(lambda: self._run(request, Path(path), cancel, mode or Mode(), options))
        return request

    def cancel(self) -> None:
        """Ask the running request to stop at its next progress step."""
        if self._cancel is not None:
            self._cancel.set()

    def wait(self, msecs: int = -1) -> bool:
        """Block until the worker is idle (used on close); False on timeout."""
        return self._pool.waitForDone(msecs) and self._topology_pool.waitForDone(msecs)

    def _run(self, request: int, path: Path, cancel: threading.Event, mode: Mode,
             options: ImportOptions | None = None) -> None:
        """Worker-thread body: emit exactly one of finished/failed/cancelled."""
        progress = cancellable(
            cancel, lambda fraction, stage: self.progress.emit(request, fraction, stage),
            "cancelled by the user")
        try:
            dataset = load_dataset(path, progress, build_process.ChildRunner(cancel),
                                   mode=mode, options=options, topology=False)
        except Cancelled:
            self.cancelled.emit(request)
        except AlphaScoopError as error:
            self.failed.emit(request, str(error))
        except MemoryError:
            self.failed.emit(request, f"{path.name}: not enough memory to build this point set")
        except Exception as error:
            traceback.print_exc(file=sys.stderr)
            self.failed.emit(request, f"{path.name}: unexpected error ({type(error).__name__}: "
                                      f"{error})")
        else:
            if cancel.is_set():
                self.cancelled.emit(request)
            else:
                self.finished.emit(request, dataset)
                if not dataset.has_topology:
                    self._topology_pool.start(lambda: self._complete(request, dataset, cancel))

    def _complete(self, request: int, dataset: Dataset, cancel: threading.Event) -> None:
        """Topology-thread body: the dataset's topology, emitted unless the request was
        cancelled (a newer open) meanwhile; checked between its stages."""
        def check() -> None:
            if cancel.is_set():
                raise Cancelled("a newer open")

        try:
            completed = with_topology(dataset, check)
        except Cancelled:
            return
        except MemoryError:
            self.topologyFailed.emit(request, "not enough memory for the topology pass")
        except Exception as error:
            traceback.print_exc(file=sys.stderr)
            self.topologyFailed.emit(request, f"topology failed ({type(error).__name__}: "
                                              f"{error})")
        else:
            if not cancel.is_set():
                self.topologyReady.emit(request, completed)

"""The window's side of a topology process (app.topology_process): start it, follow it in a
thread of its own, hand its result over, and stop it.

The window starts it once it has mapped (or loaded) the table the build process handed over
(in shared memory, app.shared_folder, which the process maps and lets go of at once; or as
its cache entry, written) and made the slider's cursor (app.worker.load_job); the topology
job then takes it over (`hand_to`) and waits for its result (`parts`). Until taken
over it stops with the load (the load's cancel: a cancelled or superseded open), after that
with the topology job (a newer open, the window closed); `stop` ends it in any case. The
result comes once the child has written its hand-over file: the child then goes on rewriting
the cache entry with the signatures, followed by the same thread and stopped the same way,
while the window already shows the topology. A newer open, a mode change or closing the
window within those seconds (about 7 s at 1M points) kills the rewrite too: the atomic write
leaves the entry whole but without the signatures, so the next open of that file computes the
topology again (a cost accepted so that nothing runs on behind the user's next action). The
scratch folder with the hand-over file is removed once the child has ended and its result
was read (or is no longer wanted).
"""

from __future__ import annotations

import queue
import sys
import threading
import time
from pathlib import Path

from app.child_process import POLL_SECONDS, CancelFlag, run_in_child, scratch
from app.messages import TableRead, TopologyJob, TopologyWritten
from app.shared_folder import SharedTable
from app.topology_file import TopologyParts, read_topology
from app.topology_process import NAME, topology_in_child
from core.complex import AlphaComplex
from core.errors import AlphaScoopError, Cancelled
from core.progress import Progress


def start_topology(ac: AlphaComplex, entry: Path | None, cancel: CancelFlag) -> TopologyChild:
    """A topology process of ac's table: from its cache `entry` when that file exists (then
    rewritten with the signatures), else from a temporary copy of ac."""
    if entry is not None and entry.is_file():
        return TopologyChild(entry, cancel)
    return TopologyChild(None, cancel, copy=ac)


class TopologyChild:
    """One topology process of a table and the thread that follows it (started at once).

    The table is the cache entry `entry` (rewritten with the signatures after the hand-over),
    or, given `copy` instead, a temporary copy of that complex (nothing is rewritten). It is
    stopped soon after `cancel` is set (until `hand_to` another) or `stop` is called.
    """

    def __init__(self, entry: Path | None, cancel: CancelFlag,
                 copy: AlphaComplex | None = None, shared: SharedTable | None = None) -> None:
        """Start the thread, which starts the process; exactly one of entry and copy. With
        `shared` (and entry) the process maps the table from that shared folder, holding it
        until it has, and rewrites entry once the build process has written it."""
        if (entry is None) == (copy is None):
            raise ValueError("a topology process reads either a cache entry or a copy")
        if shared is not None and entry is None:
            raise ValueError("a shared table is handed over with its cache entry")
        self._release = shared.folder.hold() if shared is not None else _nothing
        self.started = time.perf_counter()  # when the pass began (the topology's seconds)
        self._lock = threading.Lock()
        self._flags: list[CancelFlag] = [cancel]
        self._stopped = False
        self._handed = threading.Event()  # the hand-over file is written, or the child ended
        self._consumed = threading.Event()  # parts() is done with the hand-over file
        self._reading = threading.Lock()  # held while parts() reads the file
        self._gone = False  # the scratch folder is (being) removed
        self._stages: queue.SimpleQueue[tuple[float, str]] = queue.SimpleQueue()
        self._target: Path | None = None
        self._written: Path | None = None
        self._error: BaseException | None = None
        self._thread = threading.Thread(target=self._follow, args=(entry, copy, shared),
                                        name="alphascoop-topology-follower", daemon=True)
        self._thread.start()

    def is_set(self) -> bool:
        """True once the process is to stop (the CancelFlag run_in_child watches)."""
        with self._lock:
            return self._stopped or any(flag.is_set() for flag in self._flags)

    def hand_to(self, cancel: CancelFlag) -> bool:
        """From now on stop with `cancel` only; False (nothing changed) when the process was
        already told to stop."""
        with self._lock:
            if self._stopped or any(flag.is_set() for flag in self._flags):
                return False
            self._flags = [cancel]
            return True

    def stop(self) -> None:
        """Kill the process (if it still runs) and wait until its thread and folder are gone."""
        with self._lock:
            self._stopped = True
        self._thread.join()

    def wait(self, timeout: float | None = None) -> bool:
        """Wait until the process ended (its cache rewrite included) and its folder is gone;
        False on timeout. Its result must have been read, or the process stopped."""
        self._thread.join(timeout)
        return not self._thread.is_alive()

    def parts(self, ac: AlphaComplex, progress: Progress) -> TopologyParts:
        """The topology the process found for ac's table, as soon as its hand-over file is
        written (app.topology_file, checked against ac's table); its stages are relayed to
        progress meanwhile. Raises Cancelled when it was stopped, and its errors."""
        try:
            while not self._handed.wait(POLL_SECONDS):
                if self.is_set():
                    raise Cancelled("topology cancelled")
                self._relay(progress)
            self._relay(progress)
            with self._reading:
                if self._written is None or self._gone or self.is_set():
                    raise self._error or Cancelled("topology cancelled")
                return read_topology(self._written, ac)
        except BaseException:
            self.stop()  # no process and no folder left behind a failed or cancelled pass
            raise
        finally:
            self._consumed.set()

    def _relay(self, progress: Progress) -> None:
        """Pass the stages the child reported since the last call on to progress."""
        while True:
            try:
                progress(*self._stages.get_nowait())
            except queue.Empty:
                return

    def _note(self, fraction: float, stage: str) -> None:
        """The child's progress (follower thread): queue it for parts()."""
        self._stages.put((fraction, stage))

    def _take(self, message: object) -> None:
        """What the child handed over (follower thread): TableRead, then TopologyWritten
        (the result is ready)."""
        if isinstance(message, TableRead):
            self._release()  # mapped: the shared folder may go
        elif isinstance(message, TopologyWritten) and Path(message.target) == self._target:
            self._written = self._target
            self._handed.set()
        else:
            raise AlphaScoopError(f"the topology process sent {message!r}")

    def _follow(self, entry: Path | None, copy: AlphaComplex | None,
                shared: SharedTable | None) -> None:
        """Thread body: run the process to its end (or until stopped), then keep its folder
        until the result was read or is no longer wanted."""
        try:
            with scratch(f"{NAME}-") as folder:
                try:
                    table, saving = entry, None
                    if shared is not None:
                        table, saving = shared.folder.path, str(shared.saving)
                    if copy is not None:
                        table = Path(folder) / "table.npz"
                        copy.save(table)
                    self._target = Path(folder) / "topology.npz"
                    job = TopologyJob(str(table), None if entry is None else str(entry),
                                      str(self._target), saving)
                    run_in_child(topology_in_child, (job,), self._note, self, NAME, self._take)
                except BaseException as error:
                    self._keep(error)
                finally:
                    self._release()  # the process ended or was stopped
                    self._handed.set()
                    while not self._consumed.wait(POLL_SECONDS) and not self.is_set():
                        pass
                    with self._reading:
                        self._gone = True
        except BaseException as error:  # the scratch folder could not be made (disk full)
            self._release()
            self._keep(error)
            self._handed.set()

    def _keep(self, error: BaseException) -> None:
        """Keep error for parts(); once the result was handed over (then the cache rewrite or
        the folder's removal failed) nobody waits for it, so an unexpected one is printed."""
        if self._written is None:
            self._error = self._error or error
        elif not isinstance(error, Cancelled):
            print(f"alphascoop: the topology process failed after its hand-over ({error}); "
                  "the topology may not be in the cache", file=sys.stderr)


def _nothing() -> None:
    """The release of a process that holds no shared folder."""

"""Build big tables in a child process: Qhull cannot be interrupted, a process can be killed.

ChildRunner is the window's runner for core.obtain. The child builds the table (and its
signatures when asked) and hands it over at once through shared memory: a folder on /dev/shm
the runner made (app.shared_folder) into which the child writes the table, the slider
cursor's sort orders (core.query.cursor.cursor_orders) and the table's spectrum (both found in a
thread beside) as raw arrays (core.storage.mapped), which the caller and the topology process map,
read-only, instead of reading them. Then it sends the table's quick opening alpha
(core.topology.opening, found in a thread beside those writes; not with the signatures) and only
then writes the cache entry (atomic: core.cache), at a lower priority, holding a lock the
topology process waits for before it rewrites that entry with the signatures. The caller
does not wait for that write: it is left to the child (HandOver.saving), which a newer open
or closing the window still kills (the load's cancel; the entry is then absent, never
damaged, and that file is built again on its next open: nothing runs on behind the user's
next action). Without /dev/shm, or with too little room in it, the child writes the cache
entry (or a temporary file when the cache cannot be written or is not used) first and hands
that file over, with the orders in a scratch file.

The caller maps (or loads, without re-checking the file its own child wrote a moment ago) the
table it was handed and makes the cursor from those orders while the child still works; the
runner keeps both (`handed_over`). `on_saved(entry, n_points, shared)` is told once this
process has mapped (or loaded) a table without signatures that the child handed over in its
cache entry or in shared memory on its way there, and made its cursor (the window starts the
topology process then: app.worker; started earlier, it slowed the cursor and so the slider
going live, without finishing sooner). The shared folder is removed once this process and
the topology process have mapped it (or gave up): app.shared_folder. Cancel kills the child
at once, so a newer open or closing the window never waits for a Delaunay triangulation to
finish. Small sets build in the caller's thread: under IN_THREAD_BELOW points a build takes a
few seconds at most, and a process would add about one (its start and the table's trip
through a file).
"""

from __future__ import annotations

import contextlib
import fcntl
import os
import shutil
import sys
import threading
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

import numpy as np

from app.child_process import LOCK_NAME, LeaveRunning, make_scratch, run_in_child
from app.messages import BuildJob, OpeningFound, TableHandedOver
from app.shared_folder import SharedFolder, SharedTable
from core.complex import AlphaComplex
from core.errors import AlphaScoopError, Cancelled
from core.obtain import SAVE_START, BuildRequest, HandOver, run_here
from core.progress import Progress
from core.query.cursor import CursorOrders, cursor_orders
from core.storage.mapped import map_arrays, write_arrays
from core.storage.npz import read_npz
from core.storage.tables import save_mapped
from core.topology.opening import opening_alpha_of

IN_THREAD_BELOW = 50_000  # points: about 3 s of build here
ORDERS_NAME = "cursor.npz"  # the cursor's orders and the spectrum, beside the table
ORDERS_FOLDER = "cursor"  # the same in the shared folder, as core.storage.mapped arrays
SPECTRUM_NAME = "spectrum"  # the table's spectrum, beside the orders
SAVING_NAME = "saving.lock"  # locked by the child until its cache entry is written
SAVE_NICENESS = 10  # the entry's write after a shared hand-over yields the cores to others


class ChildRunner:
    """A core.obtain runner that builds in a child process, killed as soon as `cancel` is set.

    Sets under IN_THREAD_BELOW points are built in the calling thread instead.
    """

    def __init__(self, cancel: threading.Event,
                 on_saved: Callable[[Path, int, SharedTable | None], None] | None = None
                 ) -> None:
        """cancel: set it (from any thread) to stop the build; Cancelled is then raised.
        on_saved(entry, n_points, shared): called once the child handed over a table without
        signatures that is in its cache entry (shared None), or in shared memory and about
        to be written there (`shared`, to be held while it is mapped), after it was loaded
        here and its cursor made."""
        self.cancel = cancel
        self.on_saved = on_saved
        self._built: AlphaComplex | None = None  # the complex its child last handed over
        self._handed = HandOver()  # what the child found beside it
        # per child: (set by stop(): kill it, set once it ended and its folder is gone)
        self._children: list[tuple[threading.Event, threading.Event]] = []

    def __call__(self, request: BuildRequest, progress: Progress | None = None) -> AlphaComplex:
        """The complex of request, saved to request.save_to when that can be written.

        Raises core.errors.Cancelled soon after `cancel` is set, and the errors of the build
        (InputError for point sets that make no complex) as they are.
        """
        self._built, self._handed = None, HandOver()
        report = progress or (lambda _fraction, _stage: None)
        if len(request.points) < IN_THREAD_BELOW:
            return run_here(request, progress)
        folder, lock = make_scratch("alphascoop-build-")
        shared = SharedFolder.make()  # after the scratch folder: none left if that failed
        stopping, ended = threading.Event(), threading.Event()
        self._children.append((stopping, ended))

        def remove() -> None:  # once the child has ended (it may outlive this call)
            lock.close()
            shutil.rmtree(folder, ignore_errors=True)
            ended.set()

        try:
            opening_alpha, saving, taken = self._run(request, folder, shared, report, remove,
                                                     _Either(self.cancel, stopping))
        except BaseException:
            remove()  # (again: harmless) a child that failed or was killed has ended
            raise
        finally:
            if shared is not None:
                shared.release()  # the window has mapped it, or gave up
        if not taken:
            raise AlphaScoopError("the build process finished without handing its table over")
        ac, handed = taken[0]
        self._built = ac
        self._handed = replace(handed, opening_alpha=opening_alpha, saving=saving)
        return ac

    def stop(self) -> None:
        """Kill the child left writing its cache entry, if any, and wait until it has ended
        and its scratch folder is gone (a load that fails after the hand-over leaves no
        process behind; the entry is then absent, never damaged). Returns at once when no
        child of this runner runs."""
        for stopping, _ended in self._children:
            stopping.set()
        for _stopping, ended in self._children:
            ended.wait()

    def handed_over(self, ac: AlphaComplex) -> HandOver:
        """The quick opening alpha (None when the signatures hold it) and the cursor the
        child's orders made, for the complex this runner built last, and whether its child
        still writes its cache entry; else HandOver()."""
        return self._handed if ac is self._built else HandOver()

    def _run(self, request: BuildRequest, folder: Path, shared: SharedFolder | None,
             report: Progress, remove: Callable[[], None], cancel: _Either
             ) -> tuple[float | None, bool, list[tuple[AlphaComplex, HandOver]]]:
        """Run the child with its inputs in folder: the opening alpha it found, whether it
        was left writing the cache entry, and what it handed over. Without the signatures,
        a child that handed its table over in shared memory and then its opening alpha is
        left to write the cache entry on its own (then True), killed once `cancel` (the
        load's, or stop()) is set meanwhile; remove() once it ended."""
        source = folder / "points.npy"
        np.save(source, request.points)
        if request.weights is not None:
            np.save(folder / "weights.npy", request.weights)
        if request.mode.normals == "given" and request.normals is not None:
            np.save(folder / "normals.npy", np.asarray(request.normals, np.float64))
        job = BuildJob(request.mode, request.signatures,
                       None if request.save_to is None else str(request.save_to),
                       request.backend, None if shared is None else str(shared.path))
        taken: list[tuple[AlphaComplex, HandOver]] = []
        opening: list[float | None] = []

        def handed(message: object) -> None:
            if isinstance(message, TableHandedOver):
                taken.append(self._take(message, request, shared, report))
                return
            if not isinstance(message, OpeningFound):
                raise AlphaScoopError(f"the build process sent {message!r}")
            opening.append(message.opening_alpha)
            if taken and not request.signatures and request.save_to is not None:
                raise LeaveRunning  # only the entry's write is left: the window goes on

        try:
            result = run_in_child(build_in_child, (str(source), str(folder / "table.npz"), job),
                                  report, cancel, "alphascoop-build", handed, remove)
        except (AlphaScoopError, MemoryError) as error:
            if not taken or isinstance(error, Cancelled):
                raise
            print(f"alphascoop: the build process failed after handing its table over "
                  f"({error}); the window finds the opening alpha itself", file=sys.stderr)
            return opening[0] if opening else None, False, taken
        if result is None:
            return opening[0], True, taken
        if not isinstance(result, OpeningFound):
            raise AlphaScoopError(f"the build process answered {result!r}")
        return result.opening_alpha, False, taken

    def _take(self, handed: TableHandedOver, request: BuildRequest,
              shared: SharedFolder | None, report: Progress) -> tuple[AlphaComplex, HandOver]:
        """The table a child handed over and the cursor made from its orders; on_saved is
        told then when the table is, or is about to be written to, the cache entry without
        signatures."""
        self._check_cancel()  # no load for a table nobody will use
        mapped = handed.mapped and shared is not None
        taken = _load_handed(handed, mapped, report)
        self._check_cancel()  # nor a topology process
        if (self.on_saved is not None and not request.signatures
                and request.save_to is not None
                and (mapped or handed.table == str(request.save_to))):
            self.on_saved(request.save_to, len(request.points),
                          SharedTable(shared, Path(handed.saving)) if mapped else None)
        if shared is not None:
            shared.release()  # mapped here: only the topology process may still need it
        return taken

    def _check_cancel(self) -> None:
        """Cancelled when `cancel` is set."""
        if self.cancel.is_set():
            raise Cancelled("build cancelled")


class _Either:
    """A cancel flag set as soon as one of two events is (the load's cancel, or stop())."""

    def __init__(self, first: threading.Event, second: threading.Event) -> None:
        """The two events watched."""
        self._events = (first, second)

    def is_set(self) -> bool:
        """True once either event is set."""
        return any(event.is_set() for event in self._events)


def _load_handed(handed: TableHandedOver, mapped: bool, report: Progress
                 ) -> tuple[AlphaComplex, HandOver]:
    """The table and cursor orders a child handed over, as a complex and its cursor."""
    report(1.0, "loading the table")
    if handed.orders is None:
        return AlphaComplex.load(handed.table, verify=False), HandOver()
    arrays = (map_arrays(handed.orders) if mapped
              else read_npz(handed.orders, trusted=True))
    # our child wrote both just now: the table is not re-checked, its spectrum not re-sorted
    ac = AlphaComplex.load(handed.table, verify=False, spectrum=arrays.get(SPECTRUM_NAME))
    return ac, HandOver(cursor=ac.cursor(CursorOrders.from_arrays(arrays, ac.dim)))


def build_in_child(source: str, target: str, job: BuildJob, progress: Progress,
                   hand_over: Callable[[object], None]) -> OpeningFound:
    """Body of the build process: build (and the signatures if asked), hand the table over,
    save it to the cache entry; then return the quick opening alpha (None when the
    signatures hold it or it could not be found).

    The hand-over is a TableHandedOver: with a shared folder (job.shared) that has the
    room, the table and the cursor's orders are written there (core.storage.mapped) and
    handed over before the cache entry is written, while this process holds a lock on the
    file "saving" (beside `target`) until that write is done, and an OpeningFound follows
    at once; else (no shared memory, or too little) the table is handed over as the cache
    entry once written, or as `target` when it cannot be, with the orders in a file beside.
    Its orders are None when they could not be found.

    weights.npy and normals.npy beside the points hold those when given."""
    points = np.load(source, allow_pickle=False)
    weights = _optional(Path(source).with_name("weights.npy"))
    mode = job.mode
    normals = (_optional(Path(source).with_name("normals.npy"))
               if mode.normals == "given" else None)
    request = BuildRequest(points, weights, mode, normals, job.signatures,
                           None if job.save_to is None else Path(job.save_to), job.backend)
    saving = Path(target).with_name(SAVING_NAME)
    with open(saving, "wb") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # the kernel drops it if this process dies
        ac = request.build(progress)
        opening: list[float] = []
        orders: list[CursorOrders] = []
        # numpy's sorts and the file's writes leave the GIL: these run beside the writes
        finder = (_beside(lambda: opening.append(opening_alpha_of(ac.index, ac.points)),
                          "alphascoop-opening") if not request.signatures else lambda: None)
        sorter = _beside(lambda: orders.append(_orders_and_spectrum(ac)), "alphascoop-orders")
        shared = job.shared
        if shared is not None and _share(ac, Path(shared), progress):
            sorter()
            orders_folder = _share_orders(orders, Path(shared) / ORDERS_FOLDER)
            hand_over(TableHandedOver(shared, True, orders_folder, str(saving)))
            finder()
            hand_over(OpeningFound(float(opening[0]) if opening else None))
            if not request.signatures and request.save_to is not None:
                with contextlib.suppress(OSError):  # left to write alone: the cores go to
                    os.nice(SAVE_NICENESS)  # the window and the topology process
            request.save(ac)  # unreported: the window is past this stage already
        else:
            written = request.save(ac, progress)
            if written is None:
                ac.save(target)
                written = Path(target)
            sorter()
            orders_file = None
            if orders:
                orders_file = Path(target).with_name(ORDERS_NAME)
                np.savez(orders_file, **orders[0])  # scratch: no atomic write
            hand_over(TableHandedOver(str(written), False,
                                      None if orders_file is None else str(orders_file),
                                      str(saving)))
    finder()
    return OpeningFound(float(opening[0]) if opening else None)


def _orders_and_spectrum(ac: AlphaComplex) -> dict[str, np.ndarray]:
    """The cursor's orders (CursorOrders.to_arrays) and the table's spectrum ("spectrum"),
    which the window would otherwise sort itself while it makes the cursor."""
    return {**cursor_orders(ac.index).to_arrays(), SPECTRUM_NAME: ac.index.spectrum()}


def _share(ac: AlphaComplex, folder: Path, progress: Progress) -> bool:
    """Write ac's table into the shared folder; False (the folder emptied) when it lacks the
    room or ran out of it."""
    progress(SAVE_START, "handing the table over")
    try:
        if save_mapped(ac, folder):
            return True
    except OSError:
        pass
    _empty(folder)
    print("alphascoop: too little shared memory (/dev/shm) for the table; it is handed over "
          "as a file", file=sys.stderr)
    return False


def _share_orders(orders: list[dict[str, np.ndarray]], folder: Path) -> str | None:
    """The folder the cursor's orders were written to (None when there are none or they do
    not fit: the window then sorts them itself)."""
    if not orders:
        return None
    try:
        folder.mkdir()
        if write_arrays(folder, orders[0]):
            return str(folder)
    except OSError:
        pass
    shutil.rmtree(folder, ignore_errors=True)
    return None


def _empty(folder: Path) -> None:
    """Remove the arrays written into folder (the folder and its owner's lock stay)."""
    for path in folder.iterdir():
        if path.name != LOCK_NAME:
            if path.is_dir():
                shutil.rmtree(path, ignore_errors=True)
            else:
                path.unlink(missing_ok=True)


def _beside(job: Callable[[], None], name: str) -> Callable[[], None]:
    """Start job in a thread; returns the function that waits for it. A job that fails (out
    of memory beside the save, say) leaves its result to the window, which finds it itself."""
    def run() -> None:
        try:
            job()
        except (MemoryError, ValueError, AlphaScoopError):
            pass

    thread = threading.Thread(target=run, name=name)
    thread.start()
    return thread.join


def _optional(path: Path) -> np.ndarray | None:
    """The array saved at path, None when there is none."""
    return np.load(path, allow_pickle=False) if path.is_file() else None


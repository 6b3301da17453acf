"""Build big tables in a child process: Qhull cannot be interrupted, a process can be killed.

ChildRunner is the window's runner for core.obtain. The child builds the table (and its
signatures when asked), writes it to the cache entry (or to a temporary file when the cache
cannot be written or is not used) and hands it over as soon as it is written; beside the
save, in threads, it finds the slider cursor's sort orders (core.cursor.cursor_orders,
handed over in a scratch file) and, without the signatures, the table's quick opening alpha
(core.opening), sent when found. The caller loads the table it was handed (without
re-checking the file its own child wrote a moment ago) and makes the cursor from those
orders while the child still looks for the opening alpha; the runner keeps both
(`handed_over`). `on_saved(entry, n_points)` is told as soon as the child has handed over a
table without signatures written to its cache entry, before this process loads it (the
window starts the topology process then: app.worker). Cancel kills the child at once, so a
newer open or closing the window never waits for a Delaunay triangulation to finish. Small
sets build in the caller's thread: under IN_THREAD_BELOW points a build takes a few seconds at
most, and a process would add about one (its start and the table's trip through a file).
"""

from __future__ import annotations

import json
import sys
import threading
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

import numpy as np

from app.child_process import run_in_child, scratch
from core.complex import AlphaComplex
from core.cursor import CursorOrders, cursor_orders
from core.errors import AlphaScoopError, Cancelled
from core.modes import Mode, make_mode
from core.npz import read_npz
from core.obtain import BuildRequest, HandOver, run_here
from core.opening import opening_alpha_of
from core.progress import Progress

IN_THREAD_BELOW = 50_000  # points: about 3 s of build here
ORDERS_NAME = "cursor.npz"  # the cursor's sort orders, beside the table in the scratch folder


class ChildRunner:
    """A core.obtain runner that builds in a child process, killed as soon as `cancel` is set.

    Sets under IN_THREAD_BELOW points are built in the calling thread instead.
    """

    def __init__(self, cancel: threading.Event,
                 on_saved: Callable[[Path, int], None] | None = None) -> None:
        """cancel: set it (from any thread) to stop the build; Cancelled is then raised.
        on_saved(entry, n_points): called once the child wrote a table without signatures
        to its cache entry, before it is loaded here."""
        self.cancel = cancel
        self.on_saved = on_saved
        self._built: AlphaComplex | None = None  # the complex its child last handed over
        self._handed = HandOver()  # what the child found beside it

    def __call__(self, request: BuildRequest, progress: Progress | None = None) -> AlphaComplex:
        """The complex of request, saved to request.save_to when that can be written.

        Raises core.errors.Cancelled soon after `cancel` is set, and the errors of the build
        (InputError for point sets that make no complex) as they are.
        """
        self._built, self._handed = None, HandOver()
        report = progress or (lambda _fraction, _stage: None)
        if len(request.points) < IN_THREAD_BELOW:
            return run_here(request, progress)
        with scratch("alphascoop-build-") as folder:
            source, target = Path(folder) / "points.npy", Path(folder) / "table.npz"
            np.save(source, request.points)
            if request.weights is not None:
                np.save(Path(folder) / "weights.npy", request.weights)
            if request.mode.normals == "given" and request.normals is not None:
                np.save(Path(folder) / "normals.npy", np.asarray(request.normals, np.float64))
            job = {"mode": request.mode.to_dict(), "signatures": request.signatures,
                   "save_to": None if request.save_to is None else str(request.save_to),
                   "backend": request.backend}
            taken: list[tuple[AlphaComplex, HandOver]] = []
            try:
                answer = json.loads(run_in_child(
                    build_in_child, (str(source), str(target), job), report, self.cancel,
                    "alphascoop-build", lambda text: taken.append(self._take(text, request,
                                                                             report))))
            except (AlphaScoopError, MemoryError) as error:
                if not taken or isinstance(error, Cancelled):
                    raise
                print(f"alphascoop: the build process failed after handing its table over "
                      f"({error}); the window finds the opening alpha itself", file=sys.stderr)
                answer = {"opening_alpha": None}
        if not taken:
            raise AlphaScoopError("the build process finished without handing its table over")
        ac, handed = taken[0]
        self._built = ac
        self._handed = replace(handed, opening_alpha=answer["opening_alpha"])
        return ac

    def handed_over(self, ac: AlphaComplex) -> HandOver:
        """The quick opening alpha (None when the signatures hold it) and the cursor the
        child's orders made, for the complex this runner built last; else HandOver()."""
        return self._handed if ac is self._built else HandOver()

    def _take(self, text: str, request: BuildRequest, report: Progress
              ) -> tuple[AlphaComplex, HandOver]:
        """The table a child handed over (JSON {"table": its file, "orders": the cursor's
        orders file or None}) and the cursor made from those orders; on_saved is told first
        when that file is the cache entry of a table without signatures."""
        if self.cancel.is_set():  # no topology process for a table nobody will load
            raise Cancelled("build cancelled")
        answer = json.loads(text)
        if (self.on_saved is not None and not request.signatures
                and answer["table"] == str(request.save_to)):
            self.on_saved(Path(answer["table"]), len(request.points))
        return _load_handed(answer, report)


def _load_handed(answer: dict, report: Progress) -> tuple[AlphaComplex, HandOver]:
    """The table and cursor orders a child handed over, as a complex and its cursor."""
    report(1.0, "loading the table")
    ac = AlphaComplex.load(answer["table"], verify=False)  # our child wrote it just now
    if answer["orders"] is None:
        return ac, HandOver()
    orders = CursorOrders.from_arrays(read_npz(answer["orders"], trusted=True), ac.dim)
    return ac, HandOver(cursor=ac.cursor(orders))


def build_in_child(source: str, target: str, job: dict, progress: Progress,
                   hand_over: Callable[[str], None]) -> str:
    """Body of the build process: build (and the signatures if asked), save to the cache entry
    or else to `target`, and hand_over JSON {"table": the path written, "orders": the file of
    the cursor's sort orders (beside `target`), or None when they could not be found}; then
    return JSON {"opening_alpha": the quick opening alpha, or None when the signatures hold
    it or it could not be found}.

    `job` holds "mode" (Mode.to_dict()), "signatures" (bool), "save_to" (the cache entry
    or None) and "backend" (str or None); weights.npy and normals.npy beside the points
    hold those when given."""
    points = np.load(source, allow_pickle=False)
    weights = _optional(Path(source).with_name("weights.npy"))
    mode = _saved_mode(job["mode"])
    normals = (_optional(Path(source).with_name("normals.npy"))
               if mode.normals == "given" else None)
    request = BuildRequest(points, weights, mode, normals, bool(job["signatures"]),
                           None if job["save_to"] is None else Path(job["save_to"]),
                           job["backend"])
    ac = request.build(progress)
    opening: list[float] = []
    orders: list[CursorOrders] = []
    # numpy's sorts and the file's writes leave the GIL: these run beside the save
    finder = (_beside(lambda: opening.append(opening_alpha_of(ac.index, len(ac.points))),
                      "alphascoop-opening") if not request.signatures else lambda: None)
    sorter = _beside(lambda: orders.append(cursor_orders(ac.index)), "alphascoop-orders")
    written = request.save(ac, progress)
    if written is None:
        ac.save(target)
        written = Path(target)
    sorter()
    orders_file = None
    if orders:
        orders_file = Path(target).with_name(ORDERS_NAME)
        np.savez(orders_file, **orders[0].to_arrays())  # a scratch file: no atomic write
    hand_over(json.dumps({"table": str(written),
                          "orders": None if orders_file is None else str(orders_file)}))
    finder()
    return json.dumps({"opening_alpha": float(opening[0]) if opening else None})


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


def _saved_mode(saved: dict | None) -> Mode:
    """The Mode of Mode.to_dict() (classic when None)."""
    if saved is None:
        return Mode()
    return make_mode(saved["density"], saved["combine"], saved["anisotropy"],
                     saved["normals"] == "given")

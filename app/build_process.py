"""Build big tables in a child process: Qhull cannot be interrupted, a process can be killed.

ChildRunner is the window's runner for core.obtain. The child builds the table (and its
signatures when asked), writes it to the cache entry (or to a temporary file when the cache
cannot be written or is not used) and says where; the caller loads that file, which takes
a few percent of the build. Cancel kills the child at once, so a newer open or closing the
window never waits for a Delaunay triangulation to finish. Small sets build in the caller's
thread: under IN_THREAD_BELOW points a build takes a few seconds at most, and a process would
add about one (its start and the table's trip through a file).
"""

from __future__ import annotations

import multiprocessing
import tempfile
import threading
from multiprocessing.connection import Connection
from pathlib import Path

import numpy as np

from core import errors
from core.complex import AlphaComplex
from core.modes import Mode, make_mode
from core.obtain import BuildRequest, run_here
from core.progress import Progress

IN_THREAD_BELOW = 50_000  # points: about 3 s of build here
POLL_SECONDS = 0.1


class ChildRunner:
    """A core.obtain runner that builds in a child process, killed as soon as `cancel` is set.

    Sets under IN_THREAD_BELOW points are built in the calling thread instead.
    """

    def __init__(self, cancel: threading.Event) -> None:
        """cancel: set it (from any thread) to stop the build; Cancelled is then raised."""
        self.cancel = cancel

    def __call__(self, request: BuildRequest, progress: Progress | None = None) -> AlphaComplex:
        """The complex of request, saved to request.save_to when that can be written.

        Raises core.errors.Cancelled soon after `cancel` is set, and the errors of the build
        (InputError for point sets that make no complex) as they are.
        """
        report = progress or (lambda _fraction, _stage: None)
        if len(request.points) < IN_THREAD_BELOW:
            return run_here(request, progress)
        with tempfile.TemporaryDirectory(prefix="alphascoop-build-") as folder:
            source, target = Path(folder) / "points.npy", Path(folder) / "table.npz"
            np.save(source, request.points)
            if request.weights is not None:
                np.save(Path(folder) / "weights.npy", request.weights)
            if request.mode.normals == "given" and request.normals is not None:
                np.save(Path(folder) / "normals.npy", np.asarray(request.normals, np.float64))
            job = {"mode": request.mode.to_dict(), "signatures": request.signatures,
                   "save_to": None if request.save_to is None else str(request.save_to),
                   "backend": request.backend}
            written = _run_child(source, target, job, report, self.cancel)
            report(1.0, "loading the table")
            return AlphaComplex.load(written)


def _run_child(source: Path, target: Path, job: dict, progress: Progress,
               cancel: threading.Event) -> Path:
    """Start the build process and follow it; the path it wrote, or its error raised here."""
    context = multiprocessing.get_context("spawn")  # forking a process with Qt threads is unsafe
    receiver, sender = context.Pipe(duplex=False)
    child = context.Process(target=child_main, args=(str(source), str(target), job, sender),
                            name="alphascoop-build", daemon=True)
    child.start()
    sender.close()
    try:
        return _follow(child, receiver, progress, cancel)
    finally:
        if child.is_alive():
            child.kill()
        child.join()
        receiver.close()


def _follow(child, receiver: Connection, progress: Progress, cancel: threading.Event) -> Path:
    """Relay the child's messages until it is done; Cancelled as soon as cancel is set."""
    while True:
        if cancel.is_set():
            raise errors.Cancelled("cancelled by the user")
        try:
            message = receiver.recv() if receiver.poll(POLL_SECONDS) else None
        except EOFError:
            message = ("died",)
        if message is None:
            continue
        kind, *rest = message
        if kind == "progress":
            progress(*rest)
        elif kind == "done":
            return Path(rest[0])
        elif kind == "error":
            name, text = rest
            error_class = getattr(errors, name, None)
            if name == "MemoryError":
                raise MemoryError(text)
            if isinstance(error_class, type) and issubclass(error_class, errors.AlphaScoopError):
                raise error_class(text)
            raise errors.AlphaScoopError(text)
        else:
            child.join(1.0)
            raise errors.AlphaScoopError(
                f"the build process stopped without a result (exit code {child.exitcode}; "
                "out of memory?)")


def child_main(source: str, target: str, job: dict, sender: Connection) -> None:
    """Body of the build process: build (and the signatures if asked), save to the cache entry
    or else to `target`, report where (or why not).

    `job` holds "mode" (Mode.to_dict()), "signatures" (bool), "save_to" (the cache entry
    or None) and "backend" (str or None); weights.npy and normals.npy beside the points
    hold those when given."""
    try:
        points = np.load(source, allow_pickle=False)
        weights = _optional(Path(source).with_name("weights.npy"))
        mode = _saved_mode(job["mode"])
        normals = (_optional(Path(source).with_name("normals.npy"))
                   if mode.normals == "given" else None)
        request = BuildRequest(points, weights, mode, normals, bool(job["signatures"]),
                               None if job["save_to"] is None else Path(job["save_to"]),
                               job["backend"])
        ac, written = request.run(lambda f, s: sender.send(("progress", f, s)))
        if written is None:
            ac.save(target)
            written = Path(target)
        sender.send(("done", str(written)))
    except errors.AlphaScoopError as error:
        sender.send(("error", type(error).__name__, str(error)))
    except MemoryError:
        sender.send(("error", "MemoryError", "not enough memory to build this point set"))
    except Exception as error:  # reported to the user as one line, never a traceback
        sender.send(("error", "AlphaScoopError", f"unexpected error in the build "
                                                 f"({type(error).__name__}: {error})"))
    finally:
        sender.close()


def _optional(path: Path) -> np.ndarray | None:
    """The array saved at path, None when there is none."""
    return np.load(path, allow_pickle=False) if path.is_file() else None


def _saved_mode(saved: dict | None) -> Mode:
    """The Mode of Mode.to_dict() (classic when None)."""
    if saved is None:
        return Mode()
    return make_mode(saved["density"], saved["combine"], saved["anisotropy"],
                     saved["normals"] == "given")

"""Build big tables in a child process: Qhull cannot be interrupted, a process can be killed.

The child builds the table and its signatures, writes them to the cache (or to a temporary
file when the cache cannot be written) and says where; the caller loads that file, which takes
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
from core.cache import build_cached, load_cached, store
from core.complex import AlphaComplex
from core.modes import Mode, make_mode
from core.progress import Progress

IN_THREAD_BELOW = 50_000  # points: about 3 s of build here
POLL_SECONDS = 0.1
TABLE_SHARE, SAVE_START = 0.65, 0.95  # of the child's progress; the topology pass between


def build(points: np.ndarray, progress: Progress, cancel: threading.Event,
          use_cache: bool = True, weights: np.ndarray | None = None, *,
          mode: Mode | None = None, normals: np.ndarray | None = None) -> AlphaComplex:
    """The complex of (n, d) points (weighted: with (n,) squared radii `weights`; in the
    alpha `mode`, with `normals` if it takes given ones) with signatures computed, from the
    cache when possible.

    Raises core.errors.Cancelled soon after `cancel` is set, and the errors of the build
    (InputError for point sets that make no complex) as they are.
    """
    points = np.asarray(points, dtype=np.float64)
    mode = mode or Mode()
    if len(points) < IN_THREAD_BELOW:
        return build_cached(points, use_cache=use_cache, progress=progress, signatures=True,
                            weights=weights, mode=mode, normals=normals)
    if use_cache and (ac := load_cached(points, mode, normals, weights)) is not None:
        progress(1.0, "loaded from cache")
        if not ac.has_signatures:  # an entry the command line left without them
            ac.signatures()
            store(ac, points, normals, weights)
        return ac
    with tempfile.TemporaryDirectory(prefix="alphascoop-build-") as folder:
        source, target = Path(folder) / "points.npy", Path(folder) / "table.npz"
        np.save(source, points)
        if weights is not None:
            np.save(Path(folder) / "weights.npy", np.asarray(weights, dtype=np.float64))
        if mode.normals == "given" and normals is not None:
            np.save(Path(folder) / "normals.npy", np.asarray(normals, dtype=np.float64))
        written = _run_child(source, target, use_cache, progress, cancel, mode)
        progress(1.0, "loading the table")
        return AlphaComplex.load(written)


def _run_child(source: Path, target: Path, use_cache: bool, progress: Progress,
               cancel: threading.Event, mode: Mode) -> Path:
    """Start the build process and follow it; the path it wrote, or its error raised here."""
    context = multiprocessing.get_context("spawn")  # forking a process with Qt threads is unsafe
    receiver, sender = context.Pipe(duplex=False)
    child = context.Process(target=child_main, args=(str(source), str(target), use_cache, sender,
                                                     mode.to_dict()),
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


def child_main(source: str, target: str, use_cache: bool, sender: Connection,
               mode: dict | None = None) -> None:
    """Body of the build process: build, compute signatures, save, report where (or why not).

    `mode` is Mode.to_dict() (classic when None); given normals are in normals.npy beside
    the points."""
    try:
        points = np.load(source, allow_pickle=False)
        weights_file = Path(source).with_name("weights.npy")
        weights = np.load(weights_file, allow_pickle=False) if weights_file.exists() else None
        mode_ = Mode() if mode is None else make_mode(
            mode["density"], mode["combine"], mode["anisotropy"], mode["normals"] == "given")
        normals_path = Path(source).with_name("normals.npy")
        normals = (np.load(normals_path, allow_pickle=False)
                   if mode_.normals == "given" and normals_path.is_file() else None)
        ac = AlphaComplex.from_points(
            points, lambda f, s: sender.send(("progress", TABLE_SHARE * f, s)), weights=weights,
            **mode_.build_kwargs(normals))
        sender.send(("progress", TABLE_SHARE, "topology"))
        ac.signatures()
        sender.send(("progress", SAVE_START, "saving the table"))
        written = store(ac, points, normals, weights) if use_cache else None
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

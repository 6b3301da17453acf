"""Build big tables in a child process: Qhull cannot be interrupted, a process can be killed.

ChildRunner is the window's runner for core.obtain. The child builds the table (and its
signatures when asked), writes it to the cache entry (or to a temporary file when the cache
cannot be written or is not used) and says where; the caller loads that file, which takes
a few percent of the build. Without the signatures, the child finds the table's quick opening
alpha (core.opening) in a thread while it writes the file, so the window need not: the
runner keeps it (`opening_alpha`). `on_saved(entry, n_points)` is told as soon as the child
has written a table without signatures to its cache entry, before this process loads it (the
window starts the topology process then: app.worker). Cancel kills the child at once, so a
newer open or closing the window never waits for a Delaunay triangulation to finish. Small
sets build in the caller's thread: under IN_THREAD_BELOW points a build takes a few seconds at
most, and a process would add about one (its start and the table's trip through a file).
"""

from __future__ import annotations

import json
import threading
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

import numpy as np

from app.child_process import run_in_child, scratch
from core.cache import save_entry
from core.complex import AlphaComplex
from core.errors import AlphaScoopError
from core.modes import Mode, make_mode
from core.obtain import SAVE_START, BuildRequest, run_here
from core.opening import opening_alpha_of
from core.progress import Progress

IN_THREAD_BELOW = 50_000  # points: about 3 s of build here


class ChildRunner:
    """A core.obtain runner that builds in a child process, killed as soon as `cancel` is set.

    Sets under IN_THREAD_BELOW points are built in the calling thread instead.
    """

    def __init__(self, cancel: threading.Event,
                 on_saved: Callable[[Path, int], None] | None = None) -> None:
        """cancel: set it (from any thread) to stop the build; Cancelled is then raised.
        on_saved(entry, n_points): called once the child wrote a table without signatures
        to its cache entry, before it is loaded here (`opening_alpha` is set by then)."""
        self.cancel = cancel
        self.on_saved = on_saved
        #: The quick opening alpha (core.opening.opening_alpha_of) of the table this runner
        #: last built in its child; None when it was built here or with its signatures.
        self.opening_alpha: float | None = None

    def __call__(self, request: BuildRequest, progress: Progress | None = None) -> AlphaComplex:
        """The complex of request, saved to request.save_to when that can be written.

        Raises core.errors.Cancelled soon after `cancel` is set, and the errors of the build
        (InputError for point sets that make no complex) as they are.
        """
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
            answer = json.loads(run_in_child(build_in_child, (str(source), str(target), job),
                                             report, self.cancel, "alphascoop-build"))
            self.opening_alpha = answer["opening_alpha"]
            if (self.on_saved is not None and not request.signatures
                    and answer["table"] == str(request.save_to)):
                self.on_saved(Path(answer["table"]), len(request.points))
            report(1.0, "loading the table")
            ac = AlphaComplex.load(answer["table"])
            return ac


def build_in_child(source: str, target: str, job: dict, progress: Progress) -> str:
    """Body of the build process: build (and the signatures if asked), save to the cache entry
    or else to `target`; JSON {"table": the path written, "opening_alpha": the quick opening
    alpha, or None when the signatures hold it}.

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
    ac, _ = replace(request, save_to=None).run(progress)
    opening: list[float] = []
    finder = threading.Thread(  # numpy's sorts and the file's writes leave the GIL
        target=_find_opening_alpha, args=(ac, opening), name="alphascoop-opening")
    if not request.signatures:
        finder.start()
    progress(SAVE_START, "saving the table")
    written = None if request.save_to is None else save_entry(ac, request.save_to)
    if written is None:
        ac.save(target)
        written = Path(target)
    if finder.is_alive():
        finder.join()
    return json.dumps({"table": str(written),
                       "opening_alpha": float(opening[0]) if opening else None})


def _find_opening_alpha(ac: AlphaComplex, out: list[float]) -> None:
    """Append ac's quick opening alpha to `out`; nothing when it cannot be found here (out
    of memory beside the save, say): the window then finds it itself."""
    try:
        out.append(opening_alpha_of(ac.index, len(ac.points)))
    except (MemoryError, ValueError, AlphaScoopError):
        pass


def _optional(path: Path) -> np.ndarray | None:
    """The array saved at path, None when there is none."""
    return np.load(path, allow_pickle=False) if path.is_file() else None


def _saved_mode(saved: dict | None) -> Mode:
    """The Mode of Mode.to_dict() (classic when None)."""
    if saved is None:
        return Mode()
    return make_mode(saved["density"], saved["combine"], saved["anisotropy"],
                     saved["normals"] == "given")

"""The load job: read and build a dataset in the window's background runner (app.jobs).

Big triangulations run in a child process (app.build_process) that Cancel kills at once;
request ids, cancel and dropping stale results are the runner's.
"""

from __future__ import annotations

import threading
from pathlib import Path

from app import build_process
from app.dataset import Dataset, ImportOptions, load_dataset
from app.jobs import Job, Progress
from core.errors import AlphaScoopError
from core.modes import Mode


def load_job(path: str | Path, mode: Mode | None = None,
             options: ImportOptions | None = None) -> Job:
    """A job that loads path (read with `options`) and builds it in the alpha `mode`
    (default classic); its result is the app.dataset.Dataset."""
    path, mode = Path(path), mode or Mode()

    def work(progress: Progress, cancel: threading.Event) -> Dataset:
        def build(points, report, **kwargs):
            return build_process.build(points, report, cancel, **kwargs)

        return load_dataset(path, progress, build, mode=mode, options=options)

    return Job(f"opening {path.name}", work, lambda error: load_failure(path, error))


def load_failure(path: Path, error: Exception) -> str:
    """The one line a failed open shows: the core's own message, or what went wrong."""
    if isinstance(error, AlphaScoopError):
        return str(error)
    if isinstance(error, MemoryError):
        return f"{path.name}: not enough memory to build this point set"
    return f"{path.name}: unexpected error ({type(error).__name__}: {error})"

"""The load, topology and measures jobs: read and build a dataset, then complete its topology
and a molecule's measures, in the window's background runners (app.jobs).

Big triangulations run in a child process (app.build_process) that Cancel kills at once. The
load job hands the dataset over as soon as the slider can use it (the table and its cursor);
the topology job (signatures, optimal alpha, persistence) follows in a runner of its own (in
a child process of its own for big sets: app.topology_process), so a newer open cancels it
and drops its result like any stale request. For a table the build process wrote to the
cache, the load job starts that topology process once the window has mapped (or loaded)
the table handed over (in shared memory, before the entry is written; or as the entry once
written) and made its cursor (started earlier, it competed with that set-up and the slider
went live later); the dataset carries it
(`Dataset.topology_child`) to the topology job. A load that is cancelled, superseded or fails
stops it, and the build process if that was left writing the cache entry, and waits until
both have ended before it reports its outcome. A molecule's measures (exact area, cavities,
pockets: several times the build's cost) follow in a runner of their own (measures_job).
"""

from __future__ import annotations

import threading
import time
from dataclasses import replace
from pathlib import Path

from app import build_process, topology_process
from app.dataset import (
    Dataset,
    ImportOptions,
    load_dataset,
    with_measures,
    with_parts,
    with_topology,
)
from app.jobs import Job, Progress
from app.shared_folder import SharedTable
from app.topology_child import TopologyChild, start_topology
from core.errors import AlphaScoopError, Cancelled
from core.modes.alpha_modes import Mode


def load_job(path: str | Path, mode: Mode | None = None,
             options: ImportOptions | None = None) -> Job:
    """A job that loads path (read with `options`) and builds it in the alpha `mode`
    (default classic); its result is the app.dataset.Dataset, without its topology unless
    the cached table held it (then topology_job is not needed)."""
    path, mode = Path(path), mode or Mode()

    def work(progress: Progress, cancel: threading.Event) -> Dataset:
        started: list[TopologyChild] = []

        def on_saved(entry: Path, n_points: int, shared: SharedTable | None) -> None:
            if n_points >= topology_process.IN_THREAD_BELOW:
                started.append(TopologyChild(entry, cancel, shared=shared))

        runner = build_process.ChildRunner(cancel, on_saved=on_saved)
        try:
            dataset = load_dataset(path, progress, runner, mode=mode, options=options,
                                   topology=False, measures=False)
        except BaseException:  # cancelled, superseded or failed: nothing is left running
            for child in started:
                child.stop()
            runner.stop()  # a build process left writing the cache entry: killed, joined
            raise
        if not started:
            return dataset
        if dataset.has_topology or dataset.entry is None:  # not expected: stop it then
            started[0].stop()
            return dataset
        return replace(dataset, topology_child=started[0])

    return Job(f"opening {path.name}", work, lambda error: load_failure(path, error))


def topology_job(dataset: Dataset) -> Job:
    """A job that completes dataset's topology; its result is the completed Dataset. Big
    datasets are completed in a topology process (app.topology_child: the one the load
    started, else a new one) that Cancel kills; small ones here (app.dataset.with_topology),
    stopped by Cancel between its stages."""
    def work(progress: Progress, cancel: threading.Event) -> Dataset:
        def check() -> None:
            if cancel.is_set():
                raise Cancelled("topology cancelled")

        child = dataset.topology_child
        if child is not None and not child.hand_to(cancel):
            # stopped before this job took it: a newer open began meanwhile. That open may
            # still fail before it releases this dataset, so the pass starts again (a stale
            # one is cancelled with the release).
            child.stop()
            child = None
        progress(0.0, "topology")
        small = child is None and len(dataset.ac.points) < topology_process.IN_THREAD_BELOW
        if dataset.has_topology or small:
            if child is not None:
                child.stop()
            return with_topology(dataset, check)
        if child is None:
            child = start_topology(dataset.ac, dataset.entry, cancel)
        parts = child.parts(dataset.ac, progress)
        check()
        return with_parts(dataset, parts, time.perf_counter() - child.started)

    return Job(f"topology of {dataset.path.name}", work,
               lambda error: f"topology of {dataset.path.name} failed: "
                             f"{load_failure(dataset.path, error)}")


def measures_job(dataset: Dataset) -> Job:
    """A job that measures a molecule's dataset (app.dataset.with_measures); its result is
    the Dataset with them. Cancel stops it between the measures' stages."""
    def work(progress: Progress, cancel: threading.Event) -> Dataset:
        def check() -> None:
            if cancel.is_set():
                raise Cancelled("measures cancelled")

        progress(0.0, "measures")
        return with_measures(dataset, check)

    return Job(f"measures of {dataset.path.name}", work,
               lambda error: f"measures of {dataset.path.name} failed: "
                             f"{load_failure(dataset.path, error)}")


def load_failure(path: Path, error: Exception) -> str:
    """The one line a failed open shows: the core's own message, or what went wrong."""
    if isinstance(error, AlphaScoopError):
        return str(error)
    if isinstance(error, MemoryError):
        return f"{path.name}: not enough memory to build this point set"
    return f"{path.name}: unexpected error ({type(error).__name__}: {error})"

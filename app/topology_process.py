"""The topology pass of a big dataset (signatures, optimal and opening alpha, persistence) in a
child process, so the window's GUI thread never waits for the GIL while it runs.

In a thread of the window, the pass's scipy and numpy steps that hold the GIL (the persistence's
cavity pairs, scipy's minimum spanning trees) stalled the slider for up to 1.4 s at 100k
points. The child reads the table from its cache entry (or maps it from the shared folder the
build process handed it over in, app.shared_folder, or reads a copy the window saves when the
dataset has no entry), computes the topology and writes it to the hand-over file
(app.topology_file), which the window attaches to its own complex. Only then, after it said
HANDED_OVER, does it rewrite the cache entry with the signatures (so the next open skips the
pass): the window does not wait for that rewrite (about 7 s at 1M points). The rewrite is
atomic (core.storage.atomic), so a child killed in the middle of it (a newer open, the window
closed) leaves the old entry as it was. (Chosen over a file of the topology beside the entry, which
the cache's reads, pruning and checks of which table it belongs to would have to treat as one
with the entry.) A table handed over in shared memory is still being written to its entry by
the build process: the rewrite waits for that write (a lock the build process holds; the
kernel drops it if that process dies) and is skipped when no entry came of it, so the entry
ends up with the signatures, never overwritten by the table without them. (Chosen over this
process writing the entry alone: the build process's entry stays when the topology is
cancelled.) The window's side (starting it early, following it, Cancel):
app.topology_child.
"""

from __future__ import annotations

import fcntl
from collections.abc import Callable
from pathlib import Path

from app.messages import TableRead, TopologyJob, TopologyWritten
from app.topology_file import write_topology
from core.cache import save_entry
from core.complex import AlphaComplex
from core.progress import Progress

IN_THREAD_BELOW = 20_000  # points: below this the pass takes well under a second in a thread
NAME = "alphascoop-topology"  # the process's name (ps, top)
READ = "topology: signatures"  # the table is read (then TableRead: a shared folder may go)
HANDED_OVER = "topology: handed over"  # its file is written (then TopologyWritten)
SAVING = "topology: saving the signatures to the cache"  # after HANDED_OVER, when it rewrites


def topology_in_child(job: TopologyJob, progress: Progress,
                      hand_over: Callable[[object], None]) -> TopologyWritten:
    """Body of the topology process: read job.table (a file, or a shared folder it maps:
    core.storage.mapped; it reports READ and hands TableRead over then), compute its
    topology, write it to job.target, report HANDED_OVER and hand TopologyWritten over; then,
    given the cache job.entry, wait until the build process no longer holds its lock on the
    file job.saving (it writes that entry meanwhile: app.build_process) and rewrite the entry
    with the signatures if it exists. Returns TopologyWritten."""
    table, entry = job.table, job.entry
    progress(0.0, "topology: loading the table")
    ac = AlphaComplex.load(table, verify=not Path(table).is_dir())  # a folder: just written
    progress(0.2, READ)
    hand_over(TableRead())
    ac.signatures()
    progress(0.8, "topology: persistence")
    write_topology(job.target, ac, entry is not None)
    progress(0.9, HANDED_OVER)
    written = TopologyWritten(job.target)
    hand_over(written)
    if entry is not None:
        _wait_for_build(job.saving)
        if Path(entry).is_file():  # else the build process could not write it: no cache
            progress(0.95, SAVING)
            save_entry(ac, Path(entry))
    return written


def _wait_for_build(saving: str | None) -> None:
    """Wait until no process holds its lock on the file `saving` (gone: nobody does)."""
    if saving is None:
        return
    try:
        lock = open(saving, "rb")  # closed below, after the wait
    except FileNotFoundError:  # the build process ended and its scratch folder went
        return
    with lock:
        fcntl.flock(lock, fcntl.LOCK_SH)

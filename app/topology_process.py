"""The topology pass of a big dataset (signatures, optimal and opening alpha, persistence) in a
child process, so the window's GUI thread never waits for the GIL while it runs.

In a thread of the window, the pass's scipy and numpy steps that hold the GIL (the persistence's
cavity pairs, scipy's minimum spanning trees) stalled the slider for up to 1.4 s at 100k
points. The child reads the table from its cache entry (or from a copy the window saves when
the dataset has no entry), computes the topology and writes it to the hand-over file
(app.topology_file), which the window attaches to its own complex. Only then, after it said
HANDED_OVER, does it rewrite the cache entry with the signatures (so the next open skips the
pass): the window does not wait for that rewrite (about 7 s at 1M points). The rewrite is
atomic (core.atomic), so a child killed in the middle of it (a newer open, the window closed)
leaves the old entry as it was. (Chosen over a file of the topology beside the entry,
which the cache's reads, pruning and checks of which table it belongs to would have to treat
as one with the entry.) The window's side (starting it early, following it, Cancel):
app.topology_child.
"""

from __future__ import annotations

from pathlib import Path

from app.topology_file import write_topology
from core.cache import save_entry
from core.complex import AlphaComplex
from core.progress import Progress

IN_THREAD_BELOW = 20_000  # points: below this the pass takes well under a second in a thread
NAME = "alphascoop-topology"  # the process's name (ps, top)
HANDED_OVER = "topology: handed over"  # the stage the child reports once its file is written
SAVING = "topology: saving the signatures to the cache"  # after HANDED_OVER, when it rewrites


def topology_in_child(table: str, rewrite: bool, target: str, progress: Progress) -> str:
    """Body of the topology process: load the table, compute its topology, write it to
    target and report HANDED_OVER; then, when `rewrite`, rewrite the cache entry `table` with
    the signatures. Returns target."""
    progress(0.0, "topology: loading the table")
    ac = AlphaComplex.load(table)
    progress(0.2, "topology: signatures")
    ac.signatures()
    progress(0.8, "topology: persistence")
    write_topology(target, ac, rewrite)
    progress(0.9, HANDED_OVER)
    if rewrite:
        progress(0.95, SAVING)
        save_entry(ac, Path(table))
    return target

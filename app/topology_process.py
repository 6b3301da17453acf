"""The topology pass of a big dataset (signatures, optimal and opening alpha, persistence) in a
child process, so the window's GUI thread never waits for the GIL while it runs.

In a thread of the window, the pass's scipy and numpy steps that hold the GIL (the persistence's
cavity pairs, scipy's minimum spanning trees) stalled the slider for up to 1.4 s at 100k
points. The child reads the table from its cache entry (or from a copy the window saves when
the dataset has no entry), computes the topology with core.obtain.add_topology (which rewrites
the entry, so the next open skips the pass) and writes the results (app.topology_file), which
the window attaches to its own complex. Cancel kills the child at once.
"""

from __future__ import annotations

import threading
from pathlib import Path

from app.child_process import run_in_child, scratch
from app.topology_file import TopologyParts, read_topology, write_topology
from core.complex import AlphaComplex
from core.obtain import Obtained, add_topology
from core.progress import Progress

IN_THREAD_BELOW = 20_000  # points: below this the pass takes well under a second in a thread


def topology_parts(ac: AlphaComplex, entry: Path | None, progress: Progress,
                   cancel: threading.Event) -> TopologyParts:
    """ac's topology, computed in a child process from the cache `entry` (rewritten there
    with the signatures) or, without one, from a temporary copy of ac. Raises
    core.errors.Cancelled soon after `cancel` is set."""
    with scratch("alphascoop-topology-") as folder:
        table = entry
        if table is None or not table.is_file():
            table = Path(folder) / "table.npz"
            ac.save(table)
        target = Path(folder) / "topology.npz"
        written = run_in_child(topology_in_child, (str(table), table == entry, str(target)),
                               progress, cancel, "alphascoop-topology")
        return read_topology(written, ac)


def topology_in_child(table: str, rewrite: bool, target: str, progress: Progress) -> str:
    """Body of the topology process: load the table, compute its topology (rewriting the
    cache entry `table` with the signatures when `rewrite`), write it to target."""
    progress(0.0, "topology: loading the table")
    ac = AlphaComplex.load(table)
    progress(0.2, "topology: signatures")
    obtained = add_topology(Obtained(ac, "cache", Path(table) if rewrite else None))
    progress(0.8, "topology: persistence")
    write_topology(target, ac, obtained.entry is not None)
    return target

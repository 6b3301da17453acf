"""Tiled shapes out of core: points streamed into per-tile files, tiles run as Dask tasks (a
local cluster sized to the machine, or an existing one), results merged.

Every file goes under one scratch folder (workers of an existing cluster must share it),
removed at the end whatever happens: Ctrl-C (KeyboardInterrupt) or core.errors.Cancelled
from `progress` cancels the tasks first. A tile that fails is retried once; failing again,
it is named in a TileError. Results are written atomically, so nothing half-written is read.
"""

from __future__ import annotations

import ctypes
import os
import resource
import shutil
import tempfile
import time
from collections.abc import Iterator
from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path

import numpy as np

from core.errors import AlphaScoopError
from core.parallel import unsplit
from core.progress import Progress
from core.storage.atomic import atomic_path
from core.tiled.copc import CopcSource
from core.tiled.memory import Query
from core.tiled.merge import TiledShape, merge_tiles
from core.tiled.partition import read_tile, tile_folder, write_parts, write_tile
from core.tiled.plan import (
    TilePlan,
    histogram,
    histogram_shape,
    margin_for,
    plan_tiles,
)
from core.tiled.result import TileResult
from core.tiled.sources import Survey, check_unchanged, file_stamp, survey
from core.tiled.summary import TiledSummary, summarize_tiles
from core.tiled.tile import compute_tile

#: A worker's share of the machine's memory when no budget is given, and its cap.
MEMORY_SHARE, MEMORY_CAP = 0.6, 4 << 30
#: Part of a worker's memory a tile's build may plan for (the rest: Dask, the result).
BUILD_SHARE = 0.7
#: Seconds between progress calls while tiles run (how soon a cancel is seen).
HEARTBEAT = 0.25


class TileError(AlphaScoopError):
    """A tile failed twice (its number, box and the reason are in the message)."""


@dataclass(frozen=True)
class RunOptions:
    """How to run: `workers` of a local cluster (default: the machine's cores),
    `memory_per_worker` bytes (default: a share of the machine's memory), `scheduler`
    address of an existing cluster, `scratch` folder (shared by its workers),
    `tile_points` per tile core, `progress(fraction, stage)`, `retries` per tile."""

    workers: int | None = None
    memory_per_worker: int | None = None
    scheduler: str | None = None
    scratch: str | os.PathLike | None = None
    tile_points: int | None = None
    progress: Progress | None = None
    retries: int = 1


@dataclass
class RunReport:
    """What a run did: tiles, the plan, seconds per stage, each tile's points, seconds (wall
    and its worker's CPU: the worker's other threads included) and its worker's peak memory
    (bytes); for a source read by box (COPC), the points each tile's box query decoded
    (`read`, by tile)."""

    plan: TilePlan | None = None
    seconds: dict[str, float] = field(default_factory=dict)
    tiles: list[dict] = field(default_factory=list)
    read: dict[int, int] = field(default_factory=dict)

    @property
    def peak_worker_bytes(self) -> int:
        """Largest peak resident memory any worker reported."""
        return max((t["peak_bytes"] for t in self.tiles), default=0)


def default_workers() -> int:
    """One worker per core."""
    return max(1, os.cpu_count() or 1)


def default_memory(workers: int) -> int:
    """A worker's memory when none is given: MEMORY_SHARE of the machine over the workers,
    at most MEMORY_CAP."""
    import psutil

    return int(min(MEMORY_CAP, MEMORY_SHARE * psutil.virtual_memory().total / workers))


def tile_task(folder: str, out: str, dim: int, weighted: bool, at: dict) -> dict:
    """One tile on a worker: read its parts, compute its owned shape, save it atomically to
    `out` (.npz); what it cost. The build runs unsplit (core.parallel): a worker is one
    core's share of the cluster, the other cores run other tiles."""
    start, cpu = time.perf_counter(), time.process_time()
    rows, coords, in_core, weights = read_tile(Path(folder), dim, weighted)
    result = unsplit(partial(compute_tile, rows, coords, in_core, weights, at, dim))
    with atomic_path(out) as tmp, open(tmp, "wb") as fh:
        np.savez(fh, **result.to_arrays())
    points, core = len(rows), int(in_core.sum())
    del rows, coords, in_core, weights, result
    _trim_heap()
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    return {"points": points, "core": core,
            "seconds": time.perf_counter() - start,
            "cpu_seconds": time.process_time() - cpu, "peak_bytes": int(peak)}


def _trim_heap() -> None:
    """Hand the heap a tile freed back to the system (glibc's malloc_trim; elsewhere
    nothing): the worker's resident memory, which Dask's memory limit watches, then falls
    back between tiles without the fixed threshold distributed would set (client_for)."""
    try:
        ctypes.CDLL("libc.so.6").malloc_trim(0)
    except (OSError, AttributeError):
        pass


def _step(options: RunOptions, fraction: float, stage: str) -> None:
    if options.progress is not None:
        options.progress(fraction, stage)


def plan_source(source, seen: Survey, q: Query, options: RunOptions, workers: int,
                memory: int) -> TilePlan:
    """The second pass: the density histogram, then the tile plan."""
    width, bins = histogram_shape(seen.lo, seen.hi)
    counts = np.zeros(bins, dtype=np.int64)
    for coords, _ in source.chunks():
        counts += histogram(coords, seen.lo, width, bins)
    margin = margin_for(q.alpha2, seen.max_weight,
                        float(max(np.abs(seen.lo).max(), np.abs(seen.hi).max())))
    return plan_tiles(seen.lo, seen.hi, counts, margin, tile_points=options.tile_points,
                      budget_bytes=int(BUILD_SHARE * memory), workers=workers)


def partition_source(source, plan: TilePlan, scratch: Path, options: RunOptions,
                     count: int, report: RunReport | None = None) -> list[int]:
    """The third pass: every chunk into the part files of its tiles (a COPC file whose
    points all lie in their octree nodes: each tile's box through the octree,
    `partition_boxes`); the tiles that have core points, ascending."""
    if isinstance(source, CopcSource) and source.index_holds:
        return partition_boxes(source, plan, scratch, options,
                               report if report is not None else RunReport())
    tiles: set[int] = set()
    first = 0
    for chunk, (coords, weights) in enumerate(source.chunks()):
        tiles |= write_parts(plan, scratch, chunk, first, coords, weights)
        first += len(coords)
        _step(options, 0.05 + 0.25 * first / count, "splitting the points into tiles")
    return sorted(tiles)


def partition_boxes(source: CopcSource, plan: TilePlan, scratch: Path, options: RunOptions,
                    report: RunReport) -> list[int]:
    """Each tile's points read by its box (core and margin) through the source's index, only
    the octree nodes meeting it decoded: the same rows and the same part of each point as
    the streamed pass gives (`plan.members` is `plan.touching` for one tile); what each
    box read goes to `report.read`."""
    tiles = []
    for tile in range(plan.n_tiles):
        rows, coords = source.box(*plan.reach(tile))
        report.read[tile] = len(rows)
        in_tile, in_core = plan.members(coords, tile)
        if in_core.any():
            write_tile(scratch, tile, rows[in_tile], in_core[in_tile], coords[in_tile], None)
            tiles.append(tile)
        _step(options, 0.05 + 0.25 * (tile + 1) / plan.n_tiles,
              "reading the tiles through the COPC index")
    return tiles


def client_for(options: RunOptions, workers: int, memory: int, scratch: Path):
    """A distributed Client: of the cluster at `options.scheduler`, or of a new local
    cluster of `workers` single-threaded processes with `memory` bytes each (on
    127.0.0.1, no dashboard, their own files under `scratch`). The scheduler's HTTP
    server, which it starts even without a dashboard, takes a free port: on its default
    8787, taken by another cluster, distributed warns on stderr."""
    from distributed import Client, LocalCluster

    if options.scheduler:
        return Client(options.scheduler, timeout="30s")
    import dask

    # MALLOC_TRIM_THRESHOLD_, which distributed sets for its workers, fixes glibc's mmap
    # threshold: every large temporary array is then mapped and unmapped anew (five times
    # the page faults, some 13% more CPU for a tile's build); peaks are unchanged
    settings = {"temporary-directory": str(scratch / "workers"),
                "distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}
    with dask.config.set(settings):
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                               memory_limit=memory, host="127.0.0.1",
                               dashboard_address=None, local_directory=str(scratch / "workers"),
                               scheduler_kwargs={"dashboard_address": "127.0.0.1:0"})
    return Client(cluster)


def run_tiles(client, tiles: list[int], plan: TilePlan, scratch: Path, dim: int,
              weighted: bool, q: Query, options: RunOptions, report: RunReport
              ) -> list[Path]:
    """Submit one task per tile, wait for all with progress; the result files in tile
    order. While tiles run, `progress` is called at least every HEARTBEAT seconds (so a
    Cancelled raised from it stops the run promptly). A tile failing after its retries
    raises TileError naming it; an interrupt cancels every task before it propagates."""
    from distributed import as_completed

    (scratch / "results").mkdir(exist_ok=True)
    outs = {t: scratch / "results" / f"t{t:07d}.npz" for t in tiles}
    futures = {client.submit(tile_task, str(tile_folder(scratch, t)), str(outs[t]), dim,
                             weighted, q.at, key=f"alphascoop-tile-{t}-{scratch.name}",
                             retries=options.retries, pure=False): t for t in tiles}
    try:
        done, stage = 0, f"tiles 0 of {len(tiles):,}"
        _step(options, 0.3, stage)
        pending = as_completed(futures)
        while not pending.is_empty():
            batch = pending.next_batch(block=False)
            if not batch:
                time.sleep(HEARTBEAT)
                _step(options, 0.3 + 0.6 * done / len(tiles), stage)
                continue
            for future in batch:
                tile = futures[future]
                if future.status != "finished":
                    raise _tile_error(plan, tile, future)
                report.tiles.append({"tile": tile, **future.result()})
                done += 1
            stage = f"tiles {done:,} of {len(tiles):,}"
            _step(options, 0.3 + 0.6 * done / len(tiles), stage)
    except BaseException:
        client.cancel(list(futures), force=True)
        raise
    return [outs[t] for t in tiles]


def _tile_error(plan: TilePlan, tile: int, future) -> TileError:
    """The error naming a failed tile, its core box and why it failed."""
    lo, hi = plan.box(tile)
    exc = future.exception()
    box = ", ".join(f"{a:.6g}..{b:.6g}" for a, b in zip(lo, hi, strict=True))
    return TileError(f"tile {tile} (core {box}) failed after retrying: "
                     f"{type(exc).__name__}: {exc}")


def _results(paths: list[Path]) -> Iterator[TileResult]:
    """The tiles' results, read one at a time."""
    for path in paths:
        with np.load(path, allow_pickle=False) as arrays:
            yield TileResult.from_arrays({k: arrays[k] for k in arrays.files})


def _saved(paths: list[Path]) -> Iterator:
    """The tiles' saved arrays, one open .npz at a time (an array is read when asked for)."""
    for path in paths:
        with np.load(path, allow_pickle=False) as arrays:
            yield arrays


def tiled_run(source, q: Query, options: RunOptions | None = None,
              report: RunReport | None = None, *, summary: bool = False
              ) -> TiledShape | TiledSummary:
    """The shape at `q` of a chunked `source` (core.tiled.sources), tile by tile on Dask;
    with `summary`, only its numbers (core.tiled.summary: no step holds the whole shape)."""
    options = options or RunOptions()
    report = report if report is not None else RunReport()
    workers = options.workers or default_workers()
    memory = options.memory_per_worker or default_memory(workers)
    if options.scratch is not None:
        os.makedirs(options.scratch, exist_ok=True)
    scratch = Path(tempfile.mkdtemp(prefix="alphascoop-tiles-", dir=options.scratch))
    environ = dict(os.environ)  # distributed's nannies write their workers' settings into it
    # the workers start while the points are split (a local cluster takes seconds)
    pool = ThreadPoolExecutor(1, thread_name_prefix="alphascoop-cluster")
    starting = pool.submit(client_for, options, workers, memory, scratch)
    pool.shutdown(wait=False)
    client = None
    try:
        clock = time.perf_counter()
        _step(options, 0.0, "reading the points")
        stamp = file_stamp(source)
        seen = survey(source)
        plan = report.plan = plan_source(source, seen, q, options, workers, memory)
        tiles = partition_source(source, plan, scratch, options, seen.count, report)
        check_unchanged(source, stamp)
        report.seconds["partition"] = time.perf_counter() - clock
        clock = time.perf_counter()
        _step(options, 0.3, "starting the workers")
        client = starting.result()
        report.seconds["start"] = time.perf_counter() - clock  # what was left to wait
        clock = time.perf_counter()
        paths = run_tiles(client, tiles, plan, scratch, source.dim,
                          source.weights is not None, q, options, report)
        report.seconds["tiles"] = time.perf_counter() - clock
        clock = time.perf_counter()
        _step(options, 0.9, "merging the tiles")
        if summary:
            merged = summarize_tiles(_saved(paths), dim=source.dim,
                                     ambient_dim=source.ambient_dim, n_rows=seen.count,
                                     alpha=q.alpha, alpha2=q.alpha2,
                                     weighted=source.weights is not None)
        else:
            merged = merge_tiles(_results(paths), dim=source.dim,
                                 ambient_dim=source.ambient_dim, frame=source.frame,
                                 alpha=q.alpha, alpha2=q.alpha2,
                                 weighted=source.weights is not None)
        report.seconds["merge"] = time.perf_counter() - clock
        return merged
    finally:
        client = client if client is not None else _started(starting)
        if client is not None:
            close_client(client, options)
        shutil.rmtree(scratch, ignore_errors=True)
        restore_environment(environ)


def restore_environment(environ: dict[str, str]) -> None:
    """Put back the process's environment as it was before the run: a local cluster's
    nannies set OMP_NUM_THREADS=1, MALLOC_TRIM_THRESHOLD_ and the like in this process for
    their workers, which every process started later (a window's build) would inherit."""
    for name in set(os.environ) - set(environ):
        del os.environ[name]
    for name, value in environ.items():
        if os.environ.get(name) != value:
            os.environ[name] = value


def _started(starting: Future):
    """The client a start in the background made (waiting for it), None if it failed."""
    try:
        return starting.result()
    except Exception:  # the run's own error is the one to report
        return None


def close_client(client, options: RunOptions) -> None:
    """Close the client (and the local cluster this run started)."""
    cluster = None if options.scheduler else client.cluster
    client.close()
    if cluster is not None:
        cluster.close()

"""Tiled exact shapes (core.tiled): tiled vs in memory on one machine, 1 -> 2 workers, each
worker's peak memory, and a 100M-point time estimated from the measured per-tile cost.

    .venv/bin/python benchmarks/bench_tiled.py [--n 1000000] [--alpha 0.01] [--tile-points N]

Every run is in its own fresh interpreter (the tiled ones start their own local Dask
cluster of single-threaded worker processes); the tiled result is checked against the
in-memory one (simplex counts per class), so the times compare equal answers.
"""

from __future__ import annotations

import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

from benchmarks.datasets import noisy_torus
from benchmarks.isolate import Probe, run_isolated, size_options
from benchmarks.results import Figure, save

GIB = float(1 << 30)
BIG = 100_000_000


def in_memory(path: str, alpha: float) -> dict:
    """AlphaComplex.from_points, then the shape's classes at alpha (what `info` needs)."""
    from core import AlphaComplex

    points = np.load(path, allow_pickle=False)
    probe = Probe()
    ac = AlphaComplex.from_points(points)
    counts = [np.bincount(ac.classify(alpha, k), minlength=4)[1:].tolist()
              for k in range(ac.dim + 1)]
    return probe.result(counts=counts)


def tiled(path: str, alpha: float, workers: int, tile_points: int) -> dict:
    """core.tiled.runner.tiled_run on a local cluster of `workers` processes."""
    from core.tiled.memory import query
    from core.tiled.runner import RunOptions, RunReport, tiled_run
    from core.tiled.sources import ArraySource

    points = np.load(path, allow_pickle=False)
    probe = Probe()
    report = RunReport()
    merged = tiled_run(ArraySource.from_points(points), query(alpha=alpha),
                       RunOptions(workers=workers, memory_per_worker=int(2 * GIB),
                                  tile_points=tile_points), report)
    counts = [[int(np.count_nonzero(c == v)) for v in (1, 2, 3)] for c in merged.classes]
    return probe.result(counts=counts, tiles=merged.n_tiles, stages=report.seconds,
                        tile_points=[t["points"] for t in report.tiles],
                        tile_seconds=[t["seconds"] for t in report.tiles],
                        worker_peak_gib=report.peak_worker_bytes / GIB)


def in_process(path: str, alpha: float, tile_points: int) -> dict:
    """core.tiled.tiled_shape: the same tiles one after another in this process (no Dask,
    no tile files): what the tiles' own work costs against the in-memory build."""
    from core.tiled import tiled_shape

    points = np.load(path, allow_pickle=False)
    probe = Probe()
    merged = tiled_shape(points, alpha, tile_points=tile_points)
    counts = [[int(np.count_nonzero(c == v)) for v in (1, 2, 3)] for c in merged.classes]
    return probe.result(counts=counts, tiles=merged.n_tiles)


def estimate(run: dict, n: int, workers: int) -> float:
    """Seconds for BIG points at the same density of tile work: the measured seconds per
    tile point (margins included) and partition seconds per input point, scaled."""
    per_point = sum(run["tile_seconds"]) / sum(run["tile_points"])
    margin_factor = sum(run["tile_points"]) / n
    partition = run["stages"]["partition"] / n
    return BIG * (partition + per_point * margin_factor / workers)


def main() -> None:
    parser = size_options(__doc__, 1_000_000)
    parser.add_argument("--alpha", type=float, default=0.01, help="alpha radius (torus of "
                        "radius 1, tube 0.35: 0.01 is a few spacings at 1M points)")
    parser.add_argument("--tile-points", type=int, default=None,
                        help="points per tile core (default n / 4: four tiles)")
    args = parser.parse_args()
    tile_points = args.tile_points or args.n // 4
    load_before = os.getloadavg()
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "torus.npy")
        np.save(path, noisy_torus(args.n, args.seed))
        memory = run_isolated(in_memory, path, args.alpha)
        two = run_isolated(tiled, path, args.alpha, 2, tile_points)
        one = run_isolated(tiled, path, args.alpha, 1, tile_points)
        local = run_isolated(in_process, path, args.alpha, tile_points)
    for name, run in (("in memory", memory), ("2 workers", two), ("1 worker", one),
                      ("in process", local)):
        if "error" in run:
            raise SystemExit(f"{name}: {run['error']}\n{run.get('trace', '')}")
        print(f"{name:>10}: {run['seconds']:.1f} s, peak {run['peak_mib']:.0f} MiB"
              + (f", {run['tiles']} tiles, worker peak {run['worker_peak_gib']:.2f} GiB, "
                 f"stages {run['stages']}" if "stages" in run else ""))
    same = memory["counts"] == two["counts"] == one["counts"] == local["counts"]
    label = f"{args.n / 1e6:g}M-point noisy torus, alpha {args.alpha:g}"
    figures = [
        Figure("tiled_vs_memory", f"{label}: tiled on a local cluster of 2 workers vs "
               "the in-memory build, wall time", two["seconds"], "s", "in memory",
               memory["seconds"], "<= 1.3"),
        Figure("one_to_two_workers", f"{label}: tiled with 1 worker vs 2 workers (the "
               "speed-up), wall time", one["seconds"], "s", "2 workers", two["seconds"],
               ">= 1.7"),
        Figure("tiles_in_process_vs_memory", f"{label}: the same tiles one after another "
               "in one process (no Dask, no tile files) vs the in-memory build, wall time",
               local["seconds"], "s", "in memory", memory["seconds"]),
        Figure("worker_peak", f"{label}: largest peak memory of a worker",
               max(one["worker_peak_gib"], two["worker_peak_gib"]), "GiB", goal="<= 2"),
        Figure("estimate_100m", "100M points on 2 workers, estimated from this run's "
               "per-tile-point cost (margins included) and partition rate",
               estimate(two, args.n, 2), "s"),
    ]
    notes = [f"Tiled answers equal the in-memory ones (simplex counts per class): {same}.",
             f"{two['tiles']} tiles of at most {tile_points:,} core points; stages of the "
             f"2-worker run (s): {', '.join(f'{k} {v:.1f}' for k, v in two['stages'].items())}.",
             "The machine's cores are shared with other work: the 1 -> 2 worker ratio is "
             "bounded by the cores free during the run.",
             "Load average (1, 5, 15 min) at the start: "
             f"{', '.join(f'{x:.2f}' for x in load_before)}; at the end: "
             f"{', '.join(f'{x:.2f}' for x in os.getloadavg())} "
             f"({os.cpu_count()} cores)."]
    print(save("bench_tiled", figures, notes=notes))
    if not same:
        raise SystemExit("tiled and in-memory answers differ")


if __name__ == "__main__":
    main()

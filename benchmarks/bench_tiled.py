"""Tiled exact shapes (core.tiled): tiled vs in memory on one machine, 1 -> 2 workers, each
worker's peak memory, and a 100M-point time estimated from the measured per-tile cost.

    .venv/bin/python benchmarks/bench_tiled.py [--n 1000000] [--alpha 0.01] [--tile-points N]
    .venv/bin/python benchmarks/bench_tiled.py --big 20000000    # results/bench_tiled_20m

Every run is in its own fresh interpreter (the tiled ones start their own local Dask
cluster of single-threaded worker processes); the tiled result is checked against the
in-memory one (simplex counts per class), so the times compare equal answers. `--big N`
only runs the tiled run end to end on 2 workers (2 GiB each, tiles planned from that
budget): a noisy torus of N points written to a LAS file chunk by chunk, streamed through
the partition and summarized tile by tile, so no process holds all points or the shape;
alpha is `--alpha` times sqrt(1M / N) (the same multiple of the point spacing).
"""

from __future__ import annotations

import os
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

from benchmarks.datasets import noisy_torus, write_torus_las
from benchmarks.isolate import Probe, run_isolated, size_options
from benchmarks.results import Figure, save

GIB = float(1 << 30)
BIG = 100_000_000
WORKER_GIB = 2


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
                        tile_cpu_seconds=[t["cpu_seconds"] for t in report.tiles],
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


def streamed(path: str, alpha: float, workers: int) -> dict:
    """tiled_run(summary=True) of a LAS file streamed in chunks on a local cluster of
    `workers` processes of 2 GiB each, tiles planned from that budget."""
    from pathlib import Path

    from core.tiled.memory import query
    from core.tiled.runner import RunOptions, RunReport, tiled_run
    from core.tiled.sources import LasSource

    probe = Probe()
    report = RunReport()
    summary = tiled_run(LasSource(Path(path)), query(alpha=alpha),
                        RunOptions(workers=workers, memory_per_worker=int(WORKER_GIB * GIB)),
                        report, summary=True)
    return probe.result(counts=[list(c) for c in summary.classes],
                        components=summary.components, tiles=summary.n_tiles,
                        stages=report.seconds, points=summary.n_points,
                        tile_points=[t["points"] for t in report.tiles],
                        tile_seconds=[t["seconds"] for t in report.tiles],
                        tile_cpu_seconds=[t["cpu_seconds"] for t in report.tiles],
                        worker_peak_gib=report.peak_worker_bytes / GIB)


def estimate(run: dict, n: int, workers: int) -> float:
    """Seconds for BIG points at the same density of tile work: the measured seconds per
    tile point (margins included) and partition seconds per input point, scaled."""
    per_point = sum(run["tile_seconds"]) / sum(run["tile_points"])
    margin_factor = sum(run["tile_points"]) / n
    partition = run["stages"]["partition"] / n
    return BIG * (partition + per_point * margin_factor / workers)


def big_run(n: int, alpha_1m: float, seed: int) -> None:
    """The end-to-end run of n streamed points on 2 workers, saved as bench_tiled_<n>."""
    alpha = alpha_1m * (1e6 / n) ** 0.5
    load_before = os.getloadavg()
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "torus.las")
        clock = time.perf_counter()
        write_torus_las(n, seed, path)
        written = time.perf_counter() - clock
        run = run_isolated(streamed, path, alpha, 2)
    if "error" in run:
        raise SystemExit(f"{n:,} points: {run['error']}\n{run.get('trace', '')}")
    tile_points, tile_cpu = sum(run["tile_points"]), sum(run["tile_cpu_seconds"])
    print(f"{n:,} points: {run['seconds']:.0f} s, {run['tiles']} tiles, worker peak "
          f"{run['worker_peak_gib']:.2f} GiB, main process peak {run['peak_mib']:.0f} MiB, "
          f"stages {run['stages']}")
    label = f"{n / 1e6:g}M-point noisy torus streamed from a LAS file, alpha {alpha:.3g}"
    figures = [
        Figure("end_to_end", f"{label}: tiled on a local cluster of 2 workers, end to end "
               "(the file read three times, tiles, summary), wall time", run["seconds"], "s"),
        Figure("worker_peak", f"{label}: largest peak memory of a worker ({WORKER_GIB} GiB "
               "budget each)", run["worker_peak_gib"], "GiB", goal="<= 2"),
        Figure("main_peak", f"{label}: peak memory of the process that streams, splits and "
               "summarizes (the scheduler in it)", run["peak_mib"] / 1024, "GiB"),
        Figure("tile_cpu_per_million", f"{label}: a tile's CPU per million tile points "
               "(margins included; the worker's own threads too)",
               tile_cpu / tile_points * 1e6, "s"),
        Figure("estimate_100m", "100M points on 2 workers, estimated from this run's "
               "per-tile-point wall cost (margins included) and partition rate",
               estimate(run, n, 2), "s"),
        Figure("estimate_100m_cpu", "100M points on 2 free cores, estimated from this run's "
               "per-tile-point CPU cost and partition rate",
               BIG * (run["stages"]["partition"] / n + tile_cpu / n / 2), "s"),
    ]
    notes = [f"{run['tiles']} tiles planned from the {WORKER_GIB} GiB budget (at most "
             f"{max(run['tile_points']):,} points with margins, {tile_points / n:.3f} tile "
             f"points per input point); {run['points']:,} points, components "
             f"{run['components']:,}, simplices per class (singular, regular, interior): "
             f"{run['counts']}.",
             "Stages (s): " + ", ".join(f"{k} {v:.1f}" for k, v in run["stages"].items())
             + f"; the LAS file was written in {written:.0f} s before the run (not counted).",
             "The machine's cores are shared with other work: wall times stretch with the "
             "load, the CPU figures much less.",
             "Load average (1, 5, 15 min) at the start: "
             f"{', '.join(f'{x:.2f}' for x in load_before)}; at the end: "
             f"{', '.join(f'{x:.2f}' for x in os.getloadavg())} ({os.cpu_count()} cores)."]
    name = f"bench_tiled_{n // 1_000_000}m" if n % 1_000_000 == 0 else f"bench_tiled_{n}"
    print(save(name, figures, notes=notes))


def main() -> None:
    parser = size_options(__doc__, 1_000_000)
    parser.add_argument("--alpha", type=float, default=0.01, help="alpha radius (torus of "
                        "radius 1, tube 0.35: 0.01 is a few spacings at 1M points)")
    parser.add_argument("--tile-points", type=int, default=None,
                        help="points per tile core (default n / 4: four tiles)")
    parser.add_argument("--big", type=int, default=None, metavar="N",
                        help="only the streamed end-to-end run of N points on 2 workers")
    args = parser.parse_args()
    if args.big:
        big_run(args.big, args.alpha, args.seed)
        return
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
             "CPU seconds (every process of the run): in memory "
             f"{memory['cpu_seconds']:.1f}, 2 workers {two['cpu_seconds']:.1f}, 1 worker "
             f"{one['cpu_seconds']:.1f}, in process {local['cpu_seconds']:.1f}; the tiles' "
             f"own on 2 workers {sum(two['tile_cpu_seconds']):.1f}.",
             "Load average (1, 5, 15 min) at the start: "
             f"{', '.join(f'{x:.2f}' for x in load_before)}; at the end: "
             f"{', '.join(f'{x:.2f}' for x in os.getloadavg())} "
             f"({os.cpu_count()} cores)."]
    print(save("bench_tiled", figures, notes=notes))
    if not same:
        raise SystemExit("tiled and in-memory answers differ")


if __name__ == "__main__":
    main()

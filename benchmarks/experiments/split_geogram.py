"""Does the weighted build still gain from triangulating in two halves with geogram?

    python benchmarks/experiments/split_geogram.py [--n 100000 200000] [--reps 3]

A measurement behind a decision, not part of the build: on the random ball packings of
benchmarks/bench_weighted.py, the best of `reps` runs of
- geogram in one call (core.backends.geogram.regular_cells, what weighted builds do),
- core.backends.split with geogram's halves (split.subset_cells patched; geogram runs one call at a
  time, so the halves follow each other) and, from the same run, what it would take with the
  halves at once: the split minus its faster half,
- Qhull's split (what weighted builds did before, on two threads).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from benchmarks.bench_weighted import packing
from core.backends import geogram, split
from core.build.delaunay import compacted
from core.pipeline import power_of_two_scale


def scaled(n: int) -> tuple[np.ndarray, np.ndarray]:
    """The packing centred and scaled by a power of two, as the pipeline hands it over."""
    points, weights = packing(n)
    points = points - 0.5 * (points.min(0) + points.max(0))
    scale = power_of_two_scale(points)
    return points / scale, weights / scale**2


def best(reps: int, run) -> float:
    times = []
    for _ in range(reps):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--n", type=int, nargs="+", default=[100_000, 200_000])
    parser.add_argument("--reps", type=int, default=3)
    args = parser.parse_args()
    if not geogram.available():
        print("geogram's library is not built")
        return 1
    qhull_cells = split.subset_cells
    halves: list[float] = []

    def geogram_cells(points, weights, ids):
        start = time.perf_counter()
        cells, nbrs = geogram.regular_cells(points[ids], weights[ids])
        halves.append(time.perf_counter() - start)
        return ids[cells].astype(np.int32), nbrs

    for n in args.n:
        points, weights = scaled(n)
        whole = best(args.reps, lambda p=points, w=weights: compacted(
            *geogram.regular_cells(p, w), len(p)))
        split.subset_cells = geogram_cells
        runs = []
        try:
            for _ in range(args.reps):
                halves.clear()
                start = time.perf_counter()
                result = split.split_triangulation(points, weights)
                total = time.perf_counter() - start
                assert not isinstance(result, str), result
                faster = sorted(halves)[-2]  # of the two halves (the band's call is smaller)
                runs.append((total, total - faster))
        finally:
            split.subset_cells = qhull_cells
        total, at_once = min(runs)
        qhull = best(args.reps, lambda p=points, w=weights: split.split_triangulation(p, w))
        print(f"{n:,} balls: geogram one call {whole:.3f} s; split with geogram halves "
              f"{total:.3f} s (halves at once: {at_once:.3f} s at best); Qhull's split "
              f"{qhull:.3f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())

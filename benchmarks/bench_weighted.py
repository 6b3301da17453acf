"""Weighted build: ours vs gudhi's weighted precision="fast", and vs our classic
build of the same points, and our weighted build with geogram (the default where its library
was built) vs the same build with Qhull (backend="qhull": two halves on two threads,
core.backends.split), in one run, each step in its own fresh interpreter.

    .venv/bin/python benchmarks/bench_weighted.py --n 200000 [--seed 0] [--json out.json]
"""

from __future__ import annotations

import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

from benchmarks.core_report import write_json
from benchmarks.isolate import Probe, StageClock, run_isolated, size_options
from benchmarks.results import clock_pair, save, slug

GOALS = (("gudhi weighted fast", 0.8), ("our classic build", 2.0),
         ("weighted, Qhull", None))


def packing(n: int, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """(n, 3) uniform points in the unit cube and (n,) weights: squared radii drawn uniformly
    from 1 to 2 times the median nearest-neighbour spacing (a random packing of balls)."""
    from scipy.spatial import cKDTree

    rng = np.random.default_rng(seed)
    points = rng.random((n, 3))
    dist, _ = cKDTree(points).query(points[: min(n, 20000)], k=2)
    spacing = float(np.median(dist[:, 1]))
    return points, (rng.uniform(1.0, 2.0, n) * spacing) ** 2


def _tiny() -> tuple[np.ndarray, np.ndarray]:
    """50 weighted points for first-call set-up before the baseline."""
    return packing(50, 1)


def gudhi_weighted(path: str) -> dict:
    """gudhi.AlphaComplex(points, weights, precision='fast').create_simplex_tree()."""
    import gudhi

    pts, w = _tiny()
    gudhi.AlphaComplex(points=pts, weights=w.tolist(), precision="fast").create_simplex_tree()
    with np.load(path) as data:
        points, weights = data["points"], data["weights"]
    weight_list = weights.tolist()  # gudhi takes a Python sequence; not timed
    probe = Probe()
    tree = gudhi.AlphaComplex(points=points, weights=weight_list,
                              precision="fast").create_simplex_tree()
    return probe.result(simplices=int(tree.num_simplices()))


def ours(path: str, weighted: bool, backend: str | None = None) -> dict:
    """AlphaComplex.from_points(points[, weights=w], backend=backend) with the time of each
    build stage (backend="qhull": the weighted build by Qhull, for the A/B figure)."""
    from core import AlphaComplex

    pts, w = _tiny()
    AlphaComplex.from_points(pts, weights=w if weighted else None, backend=backend)
    with np.load(path) as data:
        points, weights = data["points"], data["weights"]
    clock = StageClock()
    probe = Probe()
    ac = AlphaComplex.from_points(points, weights=weights if weighted else None,
                                  progress=clock, backend=backend)
    result = probe.result(counts=[len(ac.simplices(k)) for k in range(ac.dim + 1)],
                          hidden=int((ac.input_index < 0).sum()),
                          backend=ac.build_info.backend, note=ac.build_info.backend_note)
    result["stages"] = clock.stages()
    return result


def main(argv: list[str] | None = None) -> int:
    parser = size_options(__doc__, 200_000, "weighted points")
    args = parser.parse_args(argv)
    points, weights = packing(args.n, args.seed)
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "packing.npz")
        np.savez(path, points=points, weights=weights)
        results = {"our weighted build": run_isolated(ours, path, True),
                   "gudhi weighted fast": run_isolated(gudhi_weighted, path),
                   "our classic build": run_isolated(ours, path, False),
                   "weighted, Qhull": run_isolated(ours, path, True, "qhull")}
    mine = results["our weighted build"]
    print(f"{args.n:,} weighted points (radii 1-2 spacings), seed {args.seed}")
    for name, figures in results.items():
        if "error" in figures:
            print(f"  {name:<22} ERROR {figures['error']}")
            continue
        print(f"  {name:<22} {figures['seconds']:7.2f} s wall {figures['cpu_seconds']:7.2f} s cpu"
              f"  peak +{figures['extra_mib']:.0f} MiB")
        if figures.get("note"):
            print(f"      note: {figures['note']}")
        for stage in figures.get("stages", []):
            print(f"      {stage['stage']:<28} {stage['seconds']:6.2f} s")
    if "hidden" in mine:
        print(f"  hidden points: {mine['hidden']:,}; simplices {mine['counts']}")
    for name, goal in GOALS:
        other = results[name]
        if "error" in other or "error" in mine:
            continue
        ratio = mine["seconds"] / other["seconds"]
        cpu = mine["cpu_seconds"] / other["cpu_seconds"]
        verdict = "" if goal is None else (f" (goal <= {goal}x): "
                                           f"{'PASS' if ratio <= goal else 'FAIL'}")
        print(f"  weighted / {name}: {ratio:.2f}x wall, {cpu:.2f}x cpu{verdict}")
    if args.json:
        write_json(args.json, {"n": args.n, "seed": args.seed, "results": results})
    figures = [fig for name, goal in GOALS for fig in clock_pair(
        f"weighted_vs_{slug(name)}", f"weighted build / {name}, {args.n:,} balls", mine,
        name, results[name], None if goal is None else f"<= {goal}")]
    save("bench_weighted", figures, notes=[
        f"{args.n:,} uniform points in a cube with radii 1-2 times the spacing (seed "
        f"{args.seed}); each build in its own fresh interpreter; the figure is our weighted "
        f"build (AlphaComplex.from_points with weights), made by "
        f"{mine.get('backend', '?')}."])
    return 0


if __name__ == "__main__":
    sys.exit(main())

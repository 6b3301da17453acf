"""Triangulation backends: our core build with gmsh and with Qhull against gudhi's
bare `AlphaComplex(precision="fast")` build, and gmsh's triangulation (completed near the hull
and certified) against scipy's Delaunay, in one run, each step in its own fresh interpreter.

    flock /work/wt/bench.lock .venv/bin/python benchmarks/bench_backends.py --n 1000000 \
        [--sets torus,bunny] [--seed 0] [--json out.json]
"""

from __future__ import annotations

import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

from benchmarks.core_report import write_json
from benchmarks.datasets import bunny_scan, noisy_torus
from benchmarks.isolate import Probe, StageClock, run_isolated, size_options
from benchmarks.results import clock_pair, save, slug

#: (mine, theirs, goal): ratio of wall times mine / theirs must be <= goal.
GOALS = (("build gmsh", "gudhi fast", 0.5), ("build qhull", "gudhi fast", 0.8),
         ("gmsh triangulation", "scipy Delaunay", None),
         ("qhull triangulation", "scipy Delaunay", None))
SETS = {"torus": noisy_torus, "bunny": bunny_scan}


def _prepared(path: str) -> np.ndarray:
    """The points as the build hands them to a backend (core.pipeline stage 2 + centring)."""
    from core.build.points import merge_duplicates, spatial_order
    from core.pipeline import power_of_two_scale

    points = np.load(path)
    unique, _ = merge_duplicates(points)
    coords = unique[spatial_order(unique)]
    coords = coords - 0.5 * (coords.min(axis=0) + coords.max(axis=0))
    return coords / power_of_two_scale(coords)


def scipy_delaunay(path: str) -> dict:
    """scipy.spatial.Delaunay on the prepared points (what the Qhull backend runs)."""
    from scipy.spatial import Delaunay

    Delaunay(np.random.default_rng(0).random((50, 3)))
    points = _prepared(path)
    probe = Probe()
    tri = Delaunay(points)
    return probe.result(cells=len(tri.simplices))


def gmsh_triangulation(path: str) -> dict:
    """core.backends.delaunay(points, "gmsh"): gmsh + restoration near the hull + checks."""
    from core.backends import delaunay

    delaunay(_prepared_tiny(), "gmsh")
    points = _prepared(path)
    probe = Probe()
    tri, _ = delaunay(points, "gmsh")
    return probe.result(cells=len(tri.cells))


def qhull_triangulation(path: str) -> dict:
    """core.backends.delaunay(points, "qhull"): Qhull in two halves on two threads, the band
    restored and checked (core.backends.split), or one call where that cannot be promised."""
    from core.backends import delaunay

    delaunay(_prepared_tiny(), "qhull")
    points = _prepared(path)
    probe = Probe()
    tri, choice = delaunay(points, "qhull")
    return probe.result(cells=len(tri.cells), note=choice.note)


def _prepared_tiny() -> np.ndarray:
    return np.random.default_rng(1).random((200, 3)) - 0.5


def gudhi_fast(path: str) -> dict:
    """gudhi.AlphaComplex(points, precision='fast').create_simplex_tree()."""
    import gudhi

    gudhi.AlphaComplex(points=_prepared_tiny(), precision="fast").create_simplex_tree()
    points = np.load(path)
    probe = Probe()
    tree = gudhi.AlphaComplex(points=points, precision="fast").create_simplex_tree()
    return probe.result(simplices=int(tree.num_simplices()))


def ours(path: str, backend: str) -> dict:
    """AlphaComplex.from_points(points, backend=...) with the time of each build stage."""
    from core import AlphaComplex

    AlphaComplex.from_points(_prepared_tiny(), backend="qhull")
    points = np.load(path)
    clock = StageClock()
    probe = Probe()
    ac = AlphaComplex.from_points(points, backend=backend, progress=clock)
    result = probe.result(counts=[len(ac.simplices(k)) for k in range(ac.dim + 1)],
                          backend=ac.build_info.backend, note=ac.build_info.backend_note)
    result["stages"] = clock.stages()
    return result


STEPS = {"scipy Delaunay": (scipy_delaunay,), "qhull triangulation": (qhull_triangulation,),
         "gmsh triangulation": (gmsh_triangulation,),
         "gudhi fast": (gudhi_fast,), "build qhull": (ours, "qhull"),
         "build gmsh": (ours, "gmsh")}


def report(name: str, n: int, results: dict) -> list[str]:
    """The figures and goal ratios of one data set as text lines."""
    lines = [f"{name}: {n:,} points"]
    for step, figures in results.items():
        if "error" in figures:
            lines.append(f"  {step:<20} ERROR {figures['error']}")
            continue
        lines.append(f"  {step:<20} {figures['seconds']:7.2f} s wall {figures['cpu_seconds']:7.2f}"
                     f" s cpu  peak +{figures['extra_mib']:.0f} MiB")
        if figures.get("note"):
            lines.append(f"      note: {figures['note']}")
        for stage in figures.get("stages", []):
            lines.append(f"      {stage['stage']:<28} {stage['seconds']:6.2f} s")
    for mine, theirs, goal in GOALS:
        a, b = results.get(mine, {}), results.get(theirs, {})
        if "seconds" not in a or "seconds" not in b:
            continue
        ratio, cpu = a["seconds"] / b["seconds"], a["cpu_seconds"] / b["cpu_seconds"]
        verdict = ("" if goal is None else
                   f" (goal <= {goal}x): {'PASS' if ratio <= goal else 'FAIL'}")
        lines.append(f"  {mine} / {theirs}: {ratio:.2f}x wall, {cpu:.2f}x cpu{verdict}")
    return lines


def main(argv: list[str] | None = None) -> int:
    parser = size_options(__doc__, 200_000, "points of each set")
    parser.add_argument("--sets", default="torus,bunny")
    parser.add_argument("--steps", default=",".join(STEPS))
    args = parser.parse_args(argv)
    everything, figures = {}, []
    for name in args.sets.split(","):
        points = SETS[name](args.n, args.seed)
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "points.npy")
            np.save(path, points)
            results = {}
            for step in args.steps.split(","):
                fn, *extra = STEPS[step]
                results[step] = run_isolated(fn, path, *extra)
                results[step].pop("trace", None)
        everything[name] = results
        figures += [fig for mine, theirs, goal in GOALS for fig in clock_pair(
            f"{slug(mine)}_vs_{slug(theirs)}_{name}", f"{mine} / {theirs}, {args.n:,} {name} "
            "points", results.get(mine, {}), theirs, results.get(theirs, {}),
            None if goal is None else f"<= {goal}")]
        print("\n".join(report(name, args.n, results)), flush=True)
        if args.json:
            write_json(args.json, {"n": args.n, "seed": args.seed, "results": everything})
    save("bench_backends", figures, notes=[
        "Each step in its own fresh interpreter; \"build\" is AlphaComplex.from_points with "
        "that backend, \"triangulation\" the backend's certified triangulation alone."])
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Certified build: the build with exact certification and sign decisions against
the floating-point build of the same points, in one run, each in its own fresh interpreter.

    flock /work/wt/bench.lock .venv/bin/python benchmarks/bench_exact.py --n 1000000 \
        [--seed 0] [--json out.json]
    .venv/bin/python benchmarks/bench_exact.py --scan ../shared/data/milk.pcd

With --scan the points are a real scan's (core.io.read_points: duplicates merged) instead of
the torus: quantized scans are where the exact path, the flips and the local repairs work.
"""

from __future__ import annotations

import dataclasses
import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

from benchmarks.core_report import write_json
from benchmarks.datasets import noisy_torus
from benchmarks.isolate import Probe, StageClock, run_isolated, size_options
from benchmarks.results import clock_pair, save

GOAL = 1.10  # the certified build at most 10 % slower


def build(path: str, certify: bool) -> dict:
    """core.pipeline.build_complex(points, certify=...) with the time of each build stage."""
    from core.pipeline import build_complex

    build_complex(noisy_torus(50, 1), certify=certify)  # first-call set-up, not timed
    points = np.load(path)
    clock = StageClock()
    probe = Probe()
    built = build_complex(points, certify=certify, progress=clock)
    result = probe.result(info=dataclasses.asdict(built.info),
                          cells=len(built.table.levels[-1].simplices))
    result["stages"] = clock.stages()
    return result


def _points(args) -> tuple[np.ndarray, str]:
    """The points to build and a line saying what they are: the torus, or --scan's file."""
    if not args.scan:
        return noisy_torus(args.n, args.seed), f"{args.n:,} noisy torus points, seed {args.seed}"
    from core.io import read_points

    points = np.asarray(read_points(args.scan).points, dtype=np.float64)
    return points, f"{os.path.basename(args.scan)}: {len(points):,} distinct points"


def certification(exact: dict) -> str:
    """What the certified build did, as a sentence for the result's notes."""
    info = exact.get("info")
    if not isinstance(info, dict):
        return f"The certified build failed: {exact.get('error')}."
    return (f"The certified build: backend {info.get('backend')}, "
            f"{info.get('exact_predicates')} predicates decided exactly, {info.get('flips')} "
            f"flips, {info.get('uncertified')} facets uncertified.")


def main(argv: list[str] | None = None) -> int:
    parser = size_options(__doc__, 200_000, "torus points")
    parser.add_argument("--scan", metavar="PATH", help="build this point file instead")
    args = parser.parse_args(argv)
    points, label = _points(args)
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "points.npy")
        np.save(path, points)
        results = {"floating point": run_isolated(build, path, False),
                   "certified": run_isolated(build, path, True)}
    print(label)
    for name, figures in results.items():
        if "error" in figures:
            print(f"  {name:<15} ERROR {figures['error']}")
            continue
        print(f"  {name:<15} {figures['seconds']:7.2f} s wall {figures['cpu_seconds']:7.2f} s "
              f"cpu  peak +{figures['extra_mib']:.0f} MiB  {figures['cells']:,} cells")
        for stage in figures["stages"]:
            print(f"      {stage['stage']:<30} {stage['seconds']:6.2f} s")
    fast, exact = results["floating point"], results["certified"]
    if "error" not in fast and "error" not in exact:
        print(f"  certification: {exact['info']}")
        ratio = exact["seconds"] / fast["seconds"]
        cpu = exact["cpu_seconds"] / fast["cpu_seconds"]
        verdict = "" if args.scan else (
            f" (goal <= {GOAL}x in CPU time, which a busy machine disturbs less than wall "
            f"time): {'PASS' if cpu <= GOAL else 'FAIL'}")
        print(f"  certified / floating point: {ratio:.3f}x wall, {cpu:.3f}x cpu{verdict}")
    if args.json:
        write_json(args.json, {"input": label, "n": len(points), "seed": args.seed,
                               "results": results})
    name = "bench_exact" if not args.scan else f"bench_exact_{os.path.basename(args.scan)}"
    save(name.replace(".", "_"), clock_pair(
        "certified_vs_floating_point", f"certified build / floating-point build, {label}",
        exact, "floating-point build", fast,
        cpu_goal=None if args.scan else f"<= {GOAL}"),
        notes=[certification(exact)])
    return 0


if __name__ == "__main__":
    sys.exit(main())

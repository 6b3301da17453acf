"""Benchmark of the core table against scipy, gudhi and Open3D: build, memory, load, queries.

    python benchmarks/bench_core.py --n 200000 [--n 1000000] [--skip-gudhi] [--skip-open3d]
        [--reps 5] [--seed 0] [--json results.json]

Every measurement runs in its own spawned interpreter so its peak memory is its own. The goal
figures of every size go to benchmarks/results/bench_core.json (benchmarks/results.py).
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import platform
import sys
import tempfile
import time

import core_report
import measure
from datasets import write_torus
from isolate import run_isolated
from results import save as save_result


def parse_args(argv: list[str] | None = None) -> argparse.Namespace:
    """Command-line options; --n may be given several times."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--n", type=int, action="append", help="points (repeatable)")
    parser.add_argument("--seed", type=int, default=0, help="torus sample seed")
    parser.add_argument("--reps", type=int, default=5, help="repeats of cheap timings (best)")
    parser.add_argument("--skip-gudhi", action="store_true", help="do not time gudhi")
    parser.add_argument("--skip-open3d", action="store_true", help="do not time Open3D")
    parser.add_argument("--json", metavar="PATH", help="also write the results as JSON")
    args = parser.parse_args(argv)
    args.n = args.n or [200_000]
    if min(args.n) < 4 or args.reps < 1:
        parser.error("--n must be at least 4 and --reps at least 1")
    if args.json and not os.path.isdir(os.path.dirname(os.path.abspath(args.json))):
        parser.error(f"--json: the folder of {args.json} does not exist")
    return args


def _step(name: str, fn: object, *fn_args: object) -> dict:
    """Run one isolated measurement, logging its name and wall time to stderr."""
    print(f"  {name} ...", end="", file=sys.stderr, flush=True)
    start = time.perf_counter()
    result = run_isolated(fn, *fn_args)
    status = result.get("error", "ok")
    print(f" {time.perf_counter() - start:.1f} s ({status})", file=sys.stderr, flush=True)
    return result


def _open3d_alphas(query: dict) -> list[float]:
    """The alphas Open3D reconstructs at: the 0.1/0.5/0.9 quantiles and the optimal alpha."""
    return [s["alpha"] for s in query.get("shapes", [])
            if s["quantile"] is None or 0.0 < s["quantile"] < 1.0]


def run_size(n: int, args: argparse.Namespace, folder: str) -> dict:
    """All measurements for one point count; returns {'results', 'ratios', 'table'}."""
    print(f"n = {n}", file=sys.stderr)
    points = os.path.join(folder, f"torus_{n}.npy")
    table = os.path.join(folder, f"table_{n}.npz")
    results = {"data": _step("torus sample", write_torus, n, args.seed, points)}
    results["scipy"] = _step("scipy Delaunay", measure.scipy_delaunay, points)
    if not args.skip_gudhi:
        results["gudhi"] = _step("gudhi AlphaComplex fast", measure.gudhi_alpha, points)
    results["build"] = _step("AlphaComplex.from_points + save", measure.core_build, points,
                             table)
    if "error" not in results["build"]:
        results["query"] = _step("load, shape, signatures", measure.core_query, table,
                                 args.reps)
    alphas = _open3d_alphas(results.get("query", {}))
    if not args.skip_open3d and alphas:
        if importlib.util.find_spec("open3d") is None:
            results["open3d"] = {"error": "skipped: open3d is not importable"}
        else:
            results["open3d"] = _step("Open3D alpha shapes", measure.open3d_alpha, points,
                                      alphas)
    for path in (points, table):
        if os.path.exists(path):
            os.unlink(path)
    rows = core_report.ratios(core_report.figures(results))
    table = core_report.format_tables(n, results, rows)
    return {"results": results, "ratios": rows, "table": table}


def main(argv: list[str] | None = None) -> int:
    """Run the benchmark for every --n, print the tables, write JSON after each size."""
    args = parse_args(argv)
    machine = {"python": platform.python_version(), "cpus": os.cpu_count(),
               "platform": platform.platform()}
    payload = {"machine": machine, "seed": args.seed, "reps": args.reps, "runs": {}}
    figures = []
    with tempfile.TemporaryDirectory(prefix="alphascoop-bench-") as folder:
        for n in args.n:
            payload["runs"][str(n)] = run = run_size(n, args, folder)
            print(run["table"] + "\n", flush=True)
            figures += core_report.result_figures(n, run["ratios"])
            if args.json:
                core_report.write_json(args.json, payload)
    load = ", ".join(f"{value:.1f}" for value in os.getloadavg())
    save_result("bench_core", figures, notes=[
        "Noisy torus points; every measurement in its own spawned interpreter; times are the "
        f"best of {args.reps} for the cheap queries, one run for the builds. Load average "
        f"(1, 5, 15 min) {load} at the end."])
    return 0


if __name__ == "__main__":
    sys.exit(main())

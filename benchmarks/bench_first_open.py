"""Benchmark of a first open in the window (issue 15), against gudhi's bare build, in one run.

    xvfb-run -a python benchmarks/bench_first_open.py [--n 1000000] [--seed 0] [--soak]
        [--skip-gudhi] [--json out.json]

Each step runs in its own fresh process (isolate.run_isolated), so its peak memory is its
own: scipy's Delaunay alone, gudhi's `AlphaComplex(precision="fast").create_simplex_tree()`,
our core build with each backend (`from_points(backend=...)`: Qhull, and gmsh when it is
installed), and a first open in a real MainWindow with an empty table cache: file -> slider
live (the window has the dataset) -> topology done (signatures, optimal alpha). The window's
peak is its own process's and, apart, its build and topology processes' own. With --soak the
same window then opens and cancels a third file 10 times and re-opens a cube and the torus
alternately 10 times (RSS after each). Ratios are against gudhi fast (time) and scipy
Delaunay (peak memory).
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import os
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import numpy as np
from datasets import noisy_torus, write_points
from isolate import Probe, run_isolated
from measure import gudhi_alpha, scipy_delaunay
from window_open import first_open

GOALS = (  # (figure, reference, goal, at most?)
    ("window: slider live", "gudhi fast", 0.6),
    ("window: topology done", "gudhi fast", 0.9),
    ("core build, gmsh", "gudhi fast", 0.5),
    ("core build, qhull", "gudhi fast", 0.8),
)
PEAK_GOAL = 2.5  # first open's peak (either process) / scipy Delaunay's peak
SOAK_GOAL = 1.2  # RSS after each re-open / RSS after the first open


def parse_args(argv: list[str] | None = None) -> argparse.Namespace:
    """Command-line options."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--n", type=int, default=1_000_000, help="torus points")
    parser.add_argument("--seed", type=int, default=0, help="torus sample seed")
    parser.add_argument("--soak", action="store_true", help="cancelled opens and re-opens")
    parser.add_argument("--skip-gudhi", action="store_true", help="do not time gudhi")
    parser.add_argument("--json", metavar="PATH", help="also write the results as JSON")
    args = parser.parse_args(argv)
    if args.n < 1000:
        parser.error("--n must be at least 1000")
    return args


def core_build(points_path: str, backend: str) -> dict:
    """AlphaComplex.from_points(points, backend=backend) alone: time and peak."""
    from core import AlphaComplex

    AlphaComplex.from_points(np.random.default_rng(0).random((50, 3)), backend=backend)
    points = np.load(points_path, allow_pickle=False)
    probe = Probe()
    ac = AlphaComplex.from_points(points, backend=backend)
    return probe.result(backend=ac.build_info.backend, cells=len(ac.simplices(3)))


def _step(name: str, fn: object, *fn_args: object) -> dict:
    """Run one isolated measurement, logging its name and wall time to stderr."""
    print(f"  {name} ...", end="", file=sys.stderr, flush=True)
    start = time.perf_counter()
    result = run_isolated(fn, *fn_args)
    print(f" {time.perf_counter() - start:.1f} s ({result.get('error', 'ok')})",
          file=sys.stderr, flush=True)
    return result


def measure(args: argparse.Namespace, folder: str) -> dict:
    """Every step, each in its own process; {name: result}."""
    torus, cube, other = (os.path.join(folder, f"{name}.npy") for name in ("torus", "cube",
                                                                            "cancelled"))
    write_points(noisy_torus(args.n, args.seed), torus)
    write_points(np.random.default_rng(args.seed + 1).random((args.n, 3)), cube)
    write_points(noisy_torus(args.n, args.seed + 2), other)
    results = {"scipy Delaunay": _step("scipy Delaunay", scipy_delaunay, torus)}
    if not args.skip_gudhi:
        results["gudhi fast"] = _step("gudhi fast", gudhi_alpha, torus)
    backends = ["qhull"] + (["gmsh"] if importlib.util.find_spec("gmsh") else [])
    for backend in backends:
        results[f"core build, {backend}"] = _step(f"core build ({backend})", core_build,
                                                  torus, backend)
    window = _step("window first open", first_open, torus, cube, other, args.soak)
    results["window"] = window
    if "error" not in window:
        for key, name in (("live", "slider live"), ("topology", "topology done")):
            results[f"window: {name}"] = {"seconds": window[f"{key}_seconds"],
                                          "cpu_seconds": window[f"{key}_cpu_seconds"]}
    return results


def ratio_rows(results: dict) -> list[tuple[str, float, float, float, float, bool]]:
    """(figure / reference, value, reference value, ratio, goal, goal met) for every goal
    that both sides of were measured; time goals on the wall and on the CPU clock."""
    rows = []
    for figure, reference, goal in GOALS:
        for clock in ("seconds", "cpu_seconds"):
            value, ref = (results.get(k, {}).get(clock) for k in (figure, reference))
            if value is not None and ref:
                label = "time" if clock == "seconds" else "CPU"
                rows.append((f"{figure} / {reference} ({label})", value, ref, value / ref,
                             goal))
    window, scipy = results.get("window", {}), results.get("scipy Delaunay", {})
    if "peak_mib" in window and scipy.get("peak_mib"):
        peak = max(window["peak_mib"], window["child_peak_mib"])
        rows.append(("window first open peak / scipy peak (MiB)", peak, scipy["peak_mib"],
                     peak / scipy["peak_mib"], PEAK_GOAL))
    soak = window.get("soak")
    if soak:
        after = soak["after_open_mib"]
        rows.append(("soak: worst RSS after a re-open / after the first open (MiB)",
                     max(after), window["rss_after_mib"], max(after) / window["rss_after_mib"],
                     SOAK_GOAL))
        for name, firsts, again in (("cube", after[0], after[2::2]),
                                    ("torus", window["rss_after_mib"], after[1::2])):
            if again:
                rows.append((f"soak: worst RSS after a re-open of the {name} / after its first "
                             "(MiB)", max(again), firsts, max(again) / firsts, SOAK_GOAL))
    return [(name, v, r, q, goal, q <= goal) for name, v, r, q, goal in rows]


def format_report(n: int, results: dict) -> str:
    """Markdown tables: the steps, then the goal ratios."""
    lines = [f"### n = {n:,}", "", "| step | wall s | cpu s | peak MiB | note |",
             "|---|---|---|---|---|"]
    for name, res in results.items():
        if name == "window" or name.startswith("window:") or "error" in res:
            if "error" in res:
                lines.append(f"| {name} | | | | {res['error']} |")
            continue
        note = f"backend {res['backend']}" if "backend" in res else ""
        lines.append(f"| {name} | {res['seconds']:.2f} | {res['cpu_seconds']:.2f} | "
                     f"{res['peak_mib']:.0f} | {note} |")
    window = results.get("window", {})
    children = ", ".join(f"{name} {mib:.0f}"
                         for name, mib in window.get("child_peaks_mib", {}).items())
    if "live_seconds" in window:
        lines.append(f"| window: slider live | {window['live_seconds']:.2f} | "
                     f"{window['live_cpu_seconds']:.2f} | {window['peak_mib']:.0f} | backend "
                     f"{window['backend']}; children's own peaks (MiB): {children}; CPU "
                     "includes the children |")
        lines.append(f"| window: topology done | {window['topology_seconds']:.2f} | "
                     f"{window['topology_cpu_seconds']:.2f} | | |")
    lines += ["", "| figure | value | reference | ratio | goal | met |",
              "|---|---|---|---|---|---|"]
    for name, value, ref, ratio, goal, met in ratio_rows(results):
        lines.append(f"| {name} | {value:.4g} | {ref:.4g} | {ratio:.3g} | <= {goal} | "
                     f"{'yes' if met else 'NO'} |")
    soak = window.get("soak")
    if soak:
        lines += ["", "soak RSS MiB after each cancelled open: "
                  + ", ".join(f"{v:.0f}" for v in soak["after_cancel_mib"]),
                  "soak RSS MiB after each re-open (cube first): "
                  + ", ".join(f"{v:.0f}" for v in soak["after_open_mib"]),
                  "re-open seconds: " + ", ".join(f"{v:.1f}" for v in soak["open_seconds"]),
                  f"build processes left: {soak['build_processes_left']}; old datasets alive: "
                  f"{soak['old_datasets_alive']}; window peak over the soak "
                  f"{soak['peak_mib']:.0f} MiB"]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    """Run every step once, print the tables, write the JSON."""
    args = parse_args(argv)
    if not os.environ.get("DISPLAY"):
        print("bench_first_open needs a display: run it under xvfb-run -a", file=sys.stderr)
        return 2
    with tempfile.TemporaryDirectory(prefix="alphascoop-bench-") as folder:
        results = measure(args, folder)
    print(format_report(args.n, results), flush=True)
    if args.json:
        Path(args.json).write_text(json.dumps({"n": args.n, "seed": args.seed,
                                               "results": results}, indent=1, default=str))
    return 0


if __name__ == "__main__":
    sys.exit(main())

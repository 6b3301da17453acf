"""Benchmark of the alpha modes: each mode's build against the classic build of the same points,
in one run.

    python benchmarks/bench_modes.py [--n 200000] [--seed 0] [--json out.json]

Builds run in this order: classic, density (k=8), anisotropic (tau=0.5, estimated normals),
classic again; the classic figure is the faster of its two runs, so warming up favours no
side. Wall and CPU seconds are both reported, and every stage of a build (the progress calls
of AlphaComplex.from_points) is timed, so the mode's own stages show apart (the neighbours
and normals are estimated beside the classic table: the "neighbours" stage is the wait for
what is left of them when the table is done).
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from itertools import pairwise
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from core_report import write_json
from datasets import noisy_torus
from isolate import size_options
from results import Figure, save

from core import AlphaComplex

GOAL = 1.3  # a mode's build at most this many times the classic build
MODES = {"classic": {}, "density k=8": {"density": 8}, "anisotropic tau=0.5": {"anisotropy": 0.5}}


def parse_args(argv: list[str] | None = None) -> argparse.Namespace:
    """Command-line options."""
    parser = size_options(__doc__, 200_000, "torus points")
    return parser.parse_args(argv)


def timed_build(points, kwargs: dict) -> dict:
    """Wall and CPU seconds of one from_points call, and wall seconds per progress stage."""
    stages: list[tuple[str, float]] = []
    start, cpu = time.perf_counter(), time.process_time()
    AlphaComplex.from_points(points, lambda f, s: stages.append((s, time.perf_counter())),
                             **kwargs)
    end = time.perf_counter()
    marks = [*stages, ("end", end)]
    per_stage: dict[str, float] = {}
    for (name, t0), (_, t1) in pairwise(marks):
        per_stage[name] = per_stage.get(name, 0.0) + t1 - t0
    return {"wall": end - start, "cpu": time.process_time() - cpu, "stages": per_stage}


def run(n: int, seed: int) -> dict:
    """Every build of the run, the classic baseline and each mode's ratios."""
    points = noisy_torus(n, seed)
    AlphaComplex.from_points(points[:50])  # imports and first-call set-up, not timed
    load_before = os.getloadavg()[0]
    runs = {name: timed_build(points, kwargs) for name, kwargs in MODES.items()}
    again = timed_build(points, {})
    base = min((runs["classic"], again), key=lambda r: r["wall"])
    runs["classic"] = base
    ratios = {name: {"wall": r["wall"] / base["wall"], "cpu": r["cpu"] / base["cpu"]}
              for name, r in runs.items() if name != "classic"}
    load = [load_before, os.getloadavg()[0]]  # 1-minute load average before and after
    return {"n": n, "seed": seed, "builds": runs, "ratios": ratios, "goal": GOAL,
            "load": load}


def report(result: dict) -> str:
    """The figures as text: builds, mode stages, ratios against the goal."""
    before, after = result["load"]
    lines = [f"{result['n']:,} torus points (seed {result['seed']}), load average "
             f"{before:.1f} before, {after:.1f} after (other processes share the cores: "
             "wall times are worth comparing only on a quiet machine)",
             f"{'build':<22}{'wall s':>9}{'cpu s':>9}"]
    for name, r in result["builds"].items():
        lines.append(f"{name:<22}{r['wall']:>9.2f}{r['cpu']:>9.2f}")
    mode_stages = ("neighbours", "scaled radii", "filtration repair")
    for name, r in result["builds"].items():
        own = {s: t for s, t in r["stages"].items() if s in mode_stages}
        if own:
            lines.append(f"  {name}: " + ", ".join(f"{s} {t:.2f} s" for s, t in own.items()))
    for name, ratio in result["ratios"].items():
        verdict = "PASS" if max(ratio["wall"], ratio["cpu"]) <= GOAL else "FAIL"
        lines.append(f"{name:<22} ratio {ratio['wall']:.3f} wall, {ratio['cpu']:.3f} cpu "
                     f"(goal <= {GOAL} on both): {verdict}")
    return "\n".join(lines)


def result_figures(result: dict) -> list[Figure]:
    """Each mode's build against the classic build of the run, on the wall and CPU clocks."""
    base, n = result["builds"]["classic"], result["n"]
    return [Figure(name=f"{name.split()[0]}_{clock}", label=f"{name} build, {clock_name}, "
                   f"{n:,} torus points", value=result["builds"][name][clock], unit="s",
                   anchor="classic build", anchor_value=base[clock], goal=f"<= {GOAL}")
            for name in result["ratios"] for clock, clock_name in (("wall", "wall"),
                                                                  ("cpu", "CPU"))]


def main(argv: list[str] | None = None) -> int:
    """Run and print; write the result (and the detailed JSON when asked)."""
    args = parse_args(argv)
    result = run(args.n, args.seed)
    print(report(result))
    if args.json:
        write_json(args.json, result)
    before, after = result["load"]
    save("bench_modes", result_figures(result), notes=[
        "Builds in one process in the order classic, density, anisotropic, classic; the classic "
        f"anchor is the faster of its two runs. Load average {before:.1f} before, "
        f"{after:.1f} after."])
    return 0


if __name__ == "__main__":
    sys.exit(main())

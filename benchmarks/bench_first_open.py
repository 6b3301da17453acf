"""Benchmark of a first open in the window, against gudhi's bare build, in one run.

    xvfb-run -a python benchmarks/bench_first_open.py [--n 1000000] [--seed 0]
        [--set torus|bunny] [--steps scipy,gudhi,qhull,gmsh,window,window-qhull]
        [--soak | --soak-cycles N] [--json out.json]

Each step runs in its own fresh process (isolate.run_isolated), so its peak memory is its
own: scipy's Delaunay alone, gudhi's `AlphaComplex(precision="fast").create_simplex_tree()`,
our core build with each backend (`from_points(backend=...)`: Qhull, and gmsh when it is
installed), and a first open in a real MainWindow with an empty table cache: file -> slider
live (the window has the dataset) -> first frame drawn -> topology done (signatures, optimal
alpha); `window-qhull` is the same first open with the window's backend forced to Qhull
($ALPHASCOOP_BACKEND=qhull; reported, no goal). The window's peak is its own process's and,
apart, its build and topology processes' own (a build's and its gmsh half process's summed:
they run at once). --set picks the points: the noisy torus
(default) or `bunny`, a scan-like sample of the Stanford bunny (datasets.bunny_scan, needs
shared/data/bunny.ply). With --soak the same window then opens and cancels a third file
(another sample of the set) 10 times and re-opens a cube and the set alternately 10 times
(RSS after each); --soak-cycles N does N of each (a bounded soak at 1M). --steps picks the
steps and their order (the window's ratios need gudhi and scipy; put the step that matters
first when a timeout bounds the run). Each step's line is printed as soon as it ends (and
the JSON rewritten), so a run stopped by `timeout` still reports what it measured. Ratios
are against gudhi fast (time) and scipy Delaunay (peak memory).
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import numpy as np
from core_report import write_json
from datasets import bunny_scan, noisy_torus, write_points
from isolate import Probe, run_isolated
from measure import gudhi_alpha, scipy_delaunay
from results import Figure, slug
from results import save as save_result
from window_open import CANCELS, REOPENS, first_open

GOALS = (  # (figure, reference, goal: at most; None: reported only)
    ("window: slider live", "gudhi fast", 0.6),
    ("window: first frame", "gudhi fast", 0.6),
    ("window: topology done", "gudhi fast", 0.9),
    ("window, qhull: slider live", "gudhi fast", None),
    ("window, qhull: first frame", "gudhi fast", None),
    ("window, qhull: topology done", "gudhi fast", None),
    ("core build, gmsh", "gudhi fast", 0.5),
    ("core build, qhull", "gudhi fast", 0.8),
)
STEPS = ("scipy", "gudhi", "qhull", "gmsh", "window", "window-qhull")
DEFAULT_STEPS = ("scipy", "gudhi", "qhull", "gmsh", "window")
SETS = {"torus": noisy_torus, "bunny": bunny_scan}
PEAK_GOAL = 2.5  # first open's peak (either process) / scipy Delaunay's peak
SOAK_GOAL = 1.2  # RSS after each re-open / RSS after the first open


def parse_args(argv: list[str] | None = None) -> argparse.Namespace:
    """Command-line options."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--n", type=int, default=1_000_000, help="points")
    parser.add_argument("--seed", type=int, default=0, help="sample seed")
    parser.add_argument("--set", default="torus", choices=sorted(SETS),
                        help="the point set: noisy torus (default) or scan-like bunny")
    parser.add_argument("--steps", default=",".join(DEFAULT_STEPS),
                        help=f"comma-separated steps to run in that order, of {','.join(STEPS)} "
                             f"(default {','.join(DEFAULT_STEPS)})")
    parser.add_argument("--soak", action="store_true",
                        help=f"after the window's first open: {CANCELS} cancelled opens and "
                             f"{REOPENS} re-opens")
    parser.add_argument("--soak-cycles", type=int, metavar="N",
                        help="a soak of N cancelled opens and N re-opens (implies --soak)")
    parser.add_argument("--skip-gudhi", action="store_true", help="do not time gudhi")
    parser.add_argument("--json", metavar="PATH", help="also write the results as JSON")
    args = parser.parse_args(argv)
    if args.n < 1000:
        parser.error("--n must be at least 1000")
    steps = [step.strip() for step in args.steps.split(",") if step.strip()]
    unknown = sorted(set(steps) - set(STEPS))
    if unknown or not steps:
        parser.error(f"--steps: unknown {', '.join(unknown) or 'empty list'}; "
                     f"choose from {','.join(STEPS)}")
    if args.soak_cycles is not None and args.soak_cycles < 1:
        parser.error("--soak-cycles must be at least 1")
    args.steps = [step for step in dict.fromkeys(steps)  # in the order given, once each
                  if not (step == "gudhi" and args.skip_gudhi)]
    args.cycles = args.soak_cycles or (max(CANCELS, REOPENS) if args.soak else 0)
    return args


def core_build(points_path: str, backend: str) -> dict:
    """AlphaComplex.from_points(points, backend=backend) alone: time and peak."""
    from core import AlphaComplex

    AlphaComplex.from_points(np.random.default_rng(0).random((50, 3)), backend=backend)
    points = np.load(points_path, allow_pickle=False)
    probe = Probe()
    ac = AlphaComplex.from_points(points, backend=backend)
    return probe.result(backend=ac.build_info.backend, cells=len(ac.simplices(3)))


def window_with_backend(backend: str, *args: object) -> dict:
    """window_open.first_open with the window's triangulation backend forced
    ($ALPHASCOOP_BACKEND, which the window's load reads)."""
    from app.dataset import BACKEND_VARIABLE

    os.environ[BACKEND_VARIABLE] = backend
    return first_open(*args)


def _step(name: str, fn: object, *fn_args: object) -> dict:
    """Run one isolated measurement, logging its name and wall time to stderr and its
    figures to stdout as soon as it ends."""
    print(f"  {name} ...", end="", file=sys.stderr, flush=True)
    start = time.perf_counter()
    result = run_isolated(fn, *fn_args)
    print(f" {time.perf_counter() - start:.1f} s ({result.get('error', 'ok')})",
          file=sys.stderr, flush=True)
    print(f"step done: {name}: " + ", ".join(
        f"{key} {value:.2f}" if isinstance(value, float) else f"{key} {value}"
        for key, value in result.items() if not isinstance(value, dict)), flush=True)
    return result


def measure(args: argparse.Namespace, folder: str, save=lambda _results: None) -> dict:
    """The chosen steps, each in its own process; {name: result}. save(results) is called
    after each step (the JSON of a run stopped early)."""
    sample = SETS[args.set]
    main, cube, other = (os.path.join(folder, f"{name}.npy") for name in (args.set, "cube",
                                                                           "cancelled"))
    write_points(sample(args.n, args.seed), main)
    if args.cycles:
        write_points(np.random.default_rng(args.seed + 1).random((args.n, 3)), cube)
        write_points(sample(args.n, args.seed + 2), other)
    have_gmsh = importlib.util.find_spec("gmsh") is not None
    steps = {"scipy": ("scipy Delaunay", scipy_delaunay, main),
             "gudhi": ("gudhi fast", gudhi_alpha, main),
             "qhull": ("core build, qhull", core_build, main, "qhull"),
             "gmsh": ("core build, gmsh", core_build, main, "gmsh"),
             "window": ("window", first_open, main, cube, other, args.cycles),
             "window-qhull": ("window, qhull", window_with_backend, "qhull", main, cube, other,
                              0)}
    results: dict = {}
    for step in args.steps:
        if step == "gmsh" and not have_gmsh:
            continue
        name, fn, *fn_args = steps[step]
        results[name] = _step(name, fn, *fn_args)
        save(results)
    for window_step in ("window", "window, qhull"):
        window = results.get(window_step, {})
        if window and "error" not in window:
            for key, name in (("live", "slider live"), ("frame", "first frame"),
                              ("topology", "topology done")):
                results[f"{window_step}: {name}"] = {
                    "seconds": window[f"{key}_seconds"],
                    "cpu_seconds": window[f"{key}_cpu_seconds"]}
    return results


def ratio_rows(results: dict, point_set: str = "torus"
               ) -> list[tuple[str, float, float, float, float | None, bool | None]]:
    """(figure / reference, value, reference value, ratio, goal, goal met) for every goal
    that both sides of were measured; time goals on the wall and on the CPU clock (goal and
    met None: a figure reported without a goal); the soak's re-opens of the set opened first
    are labelled `point_set`."""
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
        peak = max(window["peak_mib"], together_peak(window["child_peaks_mib"]))
        rows.append(("window first open peak / scipy peak (MiB)", peak, scipy["peak_mib"],
                     peak / scipy["peak_mib"], PEAK_GOAL))
    soak = window.get("soak")
    if soak:
        after = soak["after_open_mib"]
        rows.append(("soak: worst RSS after a re-open / after the first open (MiB)",
                     max(after), window["rss_after_mib"], max(after) / window["rss_after_mib"],
                     SOAK_GOAL))
        for name, firsts, again in (("cube", after[0], after[2::2]),
                                    (point_set, window["rss_after_mib"], after[1::2])):
            if again:
                rows.append((f"soak: worst RSS after a re-open of the {name} / after its first "
                             "(MiB)", max(again), firsts, max(again) / firsts, SOAK_GOAL))
    return [(name, v, r, q, goal, None if goal is None else q <= goal)
            for name, v, r, q, goal in rows]


def together_peak(children: dict[str, float]) -> float:
    """The largest of the window's processes' peaks, a build's and its gmsh half's summed
    (they run at once)."""
    build = children.get("alphascoop-build", 0.0) + children.get("alphascoop-half", 0.0)
    return max(build, children.get("alphascoop-topology", 0.0))


def format_report(n: int, results: dict, point_set: str = "torus") -> str:
    """Markdown tables: the steps, then the goal ratios."""
    lines = [f"### n = {n:,}, {point_set}", "", "| step | wall s | cpu s | peak MiB | note |",
             "|---|---|---|---|---|"]
    for name, res in results.items():
        if name.startswith("window") or "error" in res:
            if "error" in res:
                lines.append(f"| {name} | | | | {res['error']} |")
            continue
        note = f"backend {res['backend']}" if "backend" in res else ""
        if res.get("children_peak_mib"):
            note += f"; its gmsh half process's own peak {res['children_peak_mib']:.0f} MiB"
        lines.append(f"| {name} | {res['seconds']:.2f} | {res['cpu_seconds']:.2f} | "
                     f"{res['peak_mib']:.0f} | {note} |")
    for step in ("window", "window, qhull"):
        window = results.get(step, {})
        children = ", ".join(f"{name} {mib:.0f}"
                             for name, mib in window.get("child_peaks_mib", {}).items())
        if "live_seconds" in window:
            lines.append(f"| {step}: slider live | {window['live_seconds']:.2f} | "
                         f"{window['live_cpu_seconds']:.2f} | {window['peak_mib']:.0f} | "
                         f"backend {window['backend']}; children's own peaks (MiB): "
                         f"{children}; CPU includes the children |")
            lines.append(f"| {step}: first frame drawn | {window['frame_seconds']:.2f} | "
                         f"{window['frame_cpu_seconds']:.2f} | | the event loop free again |")
            lines.append(f"| {step}: topology done | {window['topology_seconds']:.2f} | "
                         f"{window['topology_cpu_seconds']:.2f} | | |")
    lines += ["", "| figure | value | reference | ratio | goal | met |",
              "|---|---|---|---|---|---|"]
    for name, value, ref, ratio, goal, met in ratio_rows(results, point_set):
        target, verdict = ("", "reported") if goal is None else (
            f"<= {goal}", "yes" if met else "NO")
        lines.append(f"| {name} | {value:.4g} | {ref:.4g} | {ratio:.3g} | {target} | "
                     f"{verdict} |")
    window = results.get("window", {})
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


def load_text() -> str:
    """The machine's load average now (1, 5, 15 minutes): read the figures with it."""
    return "load average " + " ".join(f"{value:.1f}" for value in os.getloadavg())


def main(argv: list[str] | None = None) -> int:
    """Run every step once, print the tables, write the JSON."""
    args = parse_args(argv)
    if not os.environ.get("DISPLAY"):
        print("bench_first_open needs a display: run it under xvfb-run -a", file=sys.stderr)
        return 2
    def save(results: dict) -> None:
        if args.json:
            write_json(args.json, {"n": args.n, "seed": args.seed, "set": args.set,
                                   "steps": args.steps, "soak_cycles": args.cycles,
                                   "load_average": os.getloadavg(), "results": results})

    print(f"n = {args.n:,} ({args.set}), steps {','.join(args.steps)}, soak cycles {args.cycles}, "
          f"{load_text()} at the start", flush=True)
    with tempfile.TemporaryDirectory(prefix="alphascoop-bench-") as folder:
        results = measure(args, folder, save)
    save(results)
    print(f"{load_text()} at the end", flush=True)
    print(format_report(args.n, results, args.set), flush=True)
    name = "bench_first_open" if args.set == "torus" else f"bench_first_open_{args.set}"
    save_result(name, result_figures(args.n, results, args.set), notes=[
        f"{args.n:,} {args.set} points, a first open with an empty table cache; the window's "
        "CPU time includes its build and topology processes. Steps: " + ", ".join(args.steps)
        + f". {load_text().capitalize()} at the end (2 cores: above 2, others were running)."])
    return 0


def result_figures(n: int, results: dict, point_set: str) -> list[Figure]:
    """Every goal row as a figure beside its anchor of the same run."""
    figures = []
    for label, value, ref, _ratio, goal, _met in ratio_rows(results, point_set):
        figure, _, reference = label.partition(" / ")
        reference, clock = reference.rsplit(" (", 1) if "(" in reference else (reference, "")
        clock = {"time)": "wall", "CPU)": "cpu"}.get(clock, "")
        unit = "MiB" if "MiB" in label else "s"
        name = slug(figure.replace("window:", "")) + (
            f"_vs_{slug(reference.split()[0])}" if unit == "s" else "") + (
            f"_{clock}" if clock else "")
        figures.append(Figure(name=name, label=f"{label}, {n:,} {point_set} points",
                              value=value, unit=unit, anchor=reference, anchor_value=ref,
                              goal=None if goal is None else f"<= {goal}"))
    return figures


if __name__ == "__main__":
    sys.exit(main())

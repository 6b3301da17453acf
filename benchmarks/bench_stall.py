"""How long the window's GUI thread freezes while a first open's topology completes.

    xvfb-run -a python benchmarks/bench_stall.py [--n 100000] [--seed 0] [--json out.json]

Two first opens of the same noisy torus, each in a new window in its own fresh process with an
empty table cache (window_open.first_open): the topology pass in a thread of the window (what
small sets use) and in the topology process (app.topology_process). A 10 ms
QTimer probe on the GUI thread measures the longest stall between "slider live" (after its
first frame) and "topology done": the time a slider drag would freeze while the topology
computes, and apart the longest including the docks filling in when it arrives. The two opens
are repeated with the probe dragging: every tick moves a cursor one critical value (a slider
step's query, without its render), and the longest step is reported too.
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from core_report import write_json
from datasets import noisy_torus, write_points
from isolate import run_isolated, size_options
from results import Figure, save
from window_open import first_open

WAYS = (("thread", True), ("process", False))


def measure(n: int, seed: int) -> dict:
    """{way: first_open result} for the topology in a thread and in its process."""
    with tempfile.TemporaryDirectory(prefix="alphascoop-bench-") as folder:
        torus = os.path.join(folder, "torus.npy")
        write_points(noisy_torus(n, seed), torus)
        return {f"{way}{', dragging' if drag else ''}": run_isolated(
                    first_open, torus, torus, torus, False, in_thread, drag)
                for drag in (False, True) for way, in_thread in WAYS}


def format_report(n: int, results: dict) -> str:
    """A markdown table: per way, the stall and the times."""
    lines = [f"### n = {n:,}", "", "| topology in | longest GUI stall s while it computes | "
             "longest drag step s | with its arrival s | slider live s | topology done s | "
             "window peak MiB | children's peaks MiB |", "|---|---|---|---|---|---|---|---|"]
    for way, res in results.items():
        if "error" in res:
            lines.append(f"| {way} | {res['error']} | | | | | | |")
            continue
        children = ", ".join(f"{name} {mib:.0f}" for name, mib in res["child_peaks_mib"].items())
        lines.append(f"| {way} | {res['longest_stall_seconds']:.3f} | "
                     f"{res['longest_step_seconds']:.3f} | "
                     f"{res['longest_stall_with_arrival_seconds']:.3f} | {res['live_seconds']:.2f} "
                     f"| {res['topology_seconds']:.2f} | {res['peak_mib']:.0f} | {children} |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    """Measure both ways once, print the table, write the JSON."""
    parser = size_options(__doc__, 100_000, "torus points")
    args = parser.parse_args(argv)
    if not os.environ.get("DISPLAY"):
        print("bench_stall needs a display: run it under xvfb-run -a", file=sys.stderr)
        return 2
    results = measure(args.n, args.seed)
    print(format_report(args.n, results), flush=True)
    if args.json:
        write_json(args.json, {"n": args.n, "results": results})
    save("bench_stall", result_figures(args.n, results), notes=[
        "The longest stall of the GUI thread (a 10 ms timer probe) between the slider going "
        "live and the topology arriving, with the topology pass in its process against the "
        "same pass in a thread of the window."])
    return 0


def result_figures(n: int, results: dict) -> list[Figure]:
    """The longest stall and drag step with the topology in its process, against a thread."""
    process, thread = results.get("process", {}), results.get("thread", {})
    if "error" in process or "error" in thread or not process or not thread:
        return []
    return [Figure(name=key.removesuffix("_seconds"), label=f"{words}, topology in its "
                   f"process, {n:,} torus points", value=process[key], unit="s",
                   anchor="topology in a thread", anchor_value=thread[key])
            for key, words in (("longest_stall_seconds", "longest GUI stall while it computes"),
                               ("longest_step_seconds", "longest drag step while it computes"))]


if __name__ == "__main__":
    sys.exit(main())

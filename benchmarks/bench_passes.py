"""Per-stage timings of the build's table passes and of the topology pass, this checkout
against another one in the same run (the figures: each pass's sum of stages, this checkout
against the other, in benchmarks/results/bench_passes.json).

    python benchmarks/bench_passes.py --before /path/to/old/checkout [--n 200000] [--n 1000000]
        [--rounds 2] [--gudhi] [--json out.json]

Each measurement runs `python bench_passes.py --worker ROOT N SEED` in a fresh interpreter
whose PYTHONPATH is ROOT, so both checkouts build the same points in the same conditions;
the rounds alternate before/after and the best of them is kept (the machine is shared).
"""

from __future__ import annotations

import argparse
import itertools
import json
import os
import resource
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TABLE_STAGES = ("circumspheres of cells", "facets", "edges", "vertices")
TOPOLOGY_STAGES = ("topology", "signatures")


def worker(n: int, seed: int) -> dict:
    """Build the noisy torus with the checkout on sys.path; wall/cpu seconds per stage."""
    sys.path.insert(0, HERE)
    from datasets import noisy_torus

    from core.complex import AlphaComplex
    from core.topology.betti import build_topology
    from core.topology.signatures import compute_signatures

    points = noisy_torus(n, seed)
    AlphaComplex.from_points(points[:50]).signatures()  # imports and first calls: not timed
    marks = []

    def progress(_fraction: float, stage: str) -> None:
        marks.append((stage, time.perf_counter(), time.process_time()))

    start = (time.perf_counter(), time.process_time())
    ac = AlphaComplex.from_points(points, progress)
    marks.append(("end", time.perf_counter(), time.process_time()))
    figures = {"build": [marks[-1][1] - start[0], marks[-1][2] - start[1]]}
    for (stage, wall, cpu), (_, wall2, cpu2) in itertools.pairwise(marks):
        figures[stage] = [wall2 - wall, cpu2 - cpu]
    wall, cpu = time.perf_counter(), time.process_time()
    topology = build_topology(ac)
    figures["topology"] = [time.perf_counter() - wall, time.process_time() - cpu]
    index = getattr(ac, "index", None)  # None in checkouts older than the table index object
    wall, cpu = time.perf_counter(), time.process_time()
    compute_signatures(*((ac,) if index is None else (index, ac.points)), topology)
    figures["signatures"] = [time.perf_counter() - wall, time.process_time() - cpu]
    figures["peak MiB"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    return figures


def gudhi_worker(n: int, seed: int) -> dict:
    """gudhi's AlphaComplex(precision='fast') simplex tree of the same points (reference)."""
    sys.path.insert(0, HERE)
    import gudhi
    from datasets import noisy_torus

    points = noisy_torus(n, seed)
    gudhi.AlphaComplex(points=points[:50], precision="fast").create_simplex_tree()
    wall, cpu = time.perf_counter(), time.process_time()
    gudhi.AlphaComplex(points=points, precision="fast").create_simplex_tree()
    return {"build": [time.perf_counter() - wall, time.process_time() - cpu],
            "peak MiB": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0}


def run(root: str, n: int, seed: int, kind: str = "--worker") -> dict:
    """One worker in a fresh interpreter with `root` first on PYTHONPATH."""
    env = dict(os.environ, PYTHONPATH=root)
    done = subprocess.run([sys.executable, os.path.abspath(__file__), kind, root, str(n),
                           str(seed)], env=env, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        raise SystemExit(f"worker for {root} failed: {done.stderr.strip().splitlines()[-1:]}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def best(runs: list[dict]) -> dict:
    """Per stage, the run with the smallest wall time (its cpu beside it); peak: the largest."""
    out = {key: min((r[key] for r in runs), key=lambda f: f[0]) for key in runs[0]
           if key != "peak MiB"}
    out["peak MiB"] = max(r["peak MiB"] for r in runs)
    return out


def table(n: int, before: dict, after: dict, gudhi: dict | None) -> str:
    """Markdown rows: stage, before and after wall/cpu, and the before/after ratios."""
    rows = [f"### n = {n}", "",
            "| stage | before wall s | after wall s | speed-up wall | before cpu s | "
            "after cpu s | speed-up cpu |", "|---|---|---|---|---|---|---|"]
    stages = ["build", "Delaunay triangulation", *TABLE_STAGES, *TOPOLOGY_STAGES]
    for stage in stages:
        if stage in before and stage in after:
            (bw, bc), (aw, ac) = before[stage], after[stage]
            rows.append(f"| {stage} | {bw:.2f} | {aw:.2f} | {bw / aw:.2f}x | {bc:.2f} | "
                        f"{ac:.2f} | {bc / ac:.2f}x |")
    for name, figures in (("table passes", TABLE_STAGES), ("topology pass", TOPOLOGY_STAGES)):
        b = [sum(before[s][i] for s in figures) for i in (0, 1)]
        a = [sum(after[s][i] for s in figures) for i in (0, 1)]
        rows.append(f"| {name} (sum) | {b[0]:.2f} | {a[0]:.2f} | {b[0] / a[0]:.2f}x | "
                    f"{b[1]:.2f} | {a[1]:.2f} | {b[1] / a[1]:.2f}x |")
    rows.append(f"| peak MiB (build + topology) | {before['peak MiB']:.0f} | "
                f"{after['peak MiB']:.0f} | | | | |")
    if gudhi is not None:
        rows.append(f"| gudhi AlphaComplex fast | {gudhi['build'][0]:.2f} | | "
                    f"after build / gudhi = {after['build'][0] / gudhi['build'][0]:.2f} | "
                    f"{gudhi['build'][1]:.2f} | | "
                    f"{after['build'][1] / gudhi['build'][1]:.2f} |")
    return "\n".join(rows)


def main(argv: list[str] | None = None) -> int:
    """Parse options; as a worker print one JSON line, else compare and print tables."""
    argv = sys.argv[1:] if argv is None else argv
    if argv and argv[0] in ("--worker", "--gudhi-worker"):
        fn = worker if argv[0] == "--worker" else gudhi_worker
        print(json.dumps(fn(int(argv[2]), int(argv[3]))))
        return 0
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--before", required=True, help="checkout of the code to compare with")
    parser.add_argument("--n", type=int, action="append", help="points (repeatable)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--rounds", type=int, default=2, help="alternating runs of each side")
    parser.add_argument("--gudhi", action="store_true", help="also time gudhi fast once")
    parser.add_argument("--json", metavar="PATH")
    args = parser.parse_args(argv)
    if not os.path.isdir(os.path.join(args.before, "core")):
        parser.error(f"--before: {args.before} has no core/ folder")
    after_root = os.path.dirname(HERE)
    payload, figures = {}, []
    for n in args.n or [200_000]:
        sides = {"before": [], "after": []}
        for _ in range(max(1, args.rounds)):
            for side, root in (("before", args.before), ("after", after_root)):
                sides[side].append(run(root, n, args.seed))
                print(f"n={n} {side}: build {sides[side][-1]['build'][0]:.1f} s",
                      file=sys.stderr, flush=True)
        payload[n] = {"before": sides["before"], "after": sides["after"], "gudhi": None}
        _write(args.json, payload)
        print(table(n, best(sides["before"]), best(sides["after"]), None) + "\n", flush=True)
        figures += result_figures(n, best(sides["before"]), best(sides["after"]))
        if args.gudhi:  # after the table, so a long gudhi run loses nothing measured before
            payload[n]["gudhi"] = gudhi = run(after_root, n, args.seed, "--gudhi-worker")
            _write(args.json, payload)
            print(table(n, best(sides["before"]), best(sides["after"]), gudhi).splitlines()[-1]
                  + "\n", flush=True)
    sys.path.insert(0, HERE)
    from results import save

    save("bench_passes", figures, notes=[
        f"This checkout against {os.path.abspath(args.before)}, the best of {args.rounds} "
        "alternating rounds per side, each in a fresh interpreter."])
    return 0


def result_figures(n: int, before: dict, after: dict) -> list:
    """Each pass's summed stages, this checkout against the other, on both clocks."""
    sys.path.insert(0, HERE)
    from results import Figure

    figures = []
    for name, stages in (("table passes", TABLE_STAGES), ("topology pass", TOPOLOGY_STAGES)):
        for i, clock in enumerate(("wall", "CPU")):
            figures.append(Figure(
                name=f"{name.replace(' ', '_')}_{clock.lower()}_{n}",
                label=f"{name} (sum of stages), {clock}, {n:,} torus points",
                value=sum(after[s][i] for s in stages), unit="s",
                anchor="the other checkout", anchor_value=sum(before[s][i] for s in stages)))
    return figures


def _write(path: str | None, payload: dict) -> None:
    """Write the JSON atomically (temporary file + os.replace), if a path was given."""
    if path:
        with open(path + ".tmp", "w") as handle:
            json.dump(payload, handle, indent=1)
        os.replace(path + ".tmp", path)


if __name__ == "__main__":
    sys.exit(main())

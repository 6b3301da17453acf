"""Benchmark of the table cache: bytes per point of an entry and the cached reopen, against
the reference layout (format version 2, every array stored) and the reference code reading it,
in one run.

    flock /work/bench.lock .venv/bin/python benchmarks/bench_cache.py --n 200000 1000000 \
        [--seed 0] [--reps 3] [--reference f6a487b | --reference-tree PATH] [--json out.json]

For each size the noisy torus is built once with its signatures and stored in a fresh cache
folder (the compact entry, core.storage.compact); the same table is written beside it in the
reference layout (its full arrays, as the reference code wrote them: the cache key is the same,
so that code finds it). Then each reopen (`core.obtain.obtain(points, signatures=True)`, a
cache hit) runs in its own fresh interpreter, alternately with this tree's code and with the
reference commit's core (`git archive`d into a temporary folder); the best of --reps each. The
entry's bytes per point are held to at most 1000, the reopen to no slower than the reference.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import numpy as np

from benchmarks.core_report import write_json
from benchmarks.datasets import noisy_torus
from benchmarks.isolate import run_isolated
from benchmarks.results import Figure, save

ROOT = Path(__file__).resolve().parent.parent
REFERENCE = "f6a487b"  # the last commit whose entries held every array (format version 2)
BYTES_GOAL = 1000  # bytes per point of an entry, at most
REOPEN_GOAL = 1.0  # the reopen / the reference's reopen, at most
REOPEN = """
import json, sys, time
import numpy as np
from core.obtain import obtain
points = np.load(sys.argv[1])
obtain(np.random.default_rng(0).random((50, 3)), use_cache=False)  # imports and first calls
start, cpu = time.perf_counter(), time.process_time()
got = obtain(points, signatures=True, cache_dir=sys.argv[2])
seconds, cpu = time.perf_counter() - start, time.process_time() - cpu
print(json.dumps({"seconds": seconds, "cpu_seconds": cpu, "source": got.source,
                  "spectrum": len(got.complex.spectrum())}))
"""


def build_entries(points_path: str, compact: str, full: str) -> dict:
    """Child task: build the points' complex with its signatures into the cache folder
    `compact` (this tree's entry) and write the same table's full arrays, version 2, as the
    entry of the folder `full`; the entries' sizes in bytes."""
    from core.cache import entry_path
    from core.obtain import obtain
    from core.storage.atomic import atomic_write
    from core.storage.checksums import write_npz
    from core.storage.compact import unpack
    from core.storage.npz import read_npz

    points = np.load(points_path)
    built = obtain(points, signatures=True, cache_dir=compact)
    members = dict(read_npz(built.entry))
    members.pop("checksums")
    arrays = {**unpack(members), "version": np.array(2)}
    reference = entry_path(points, folder=full)
    reference.parent.mkdir(parents=True, exist_ok=True)
    atomic_write(reference, lambda handle: write_npz(handle, arrays))
    return {"compact_bytes": built.entry.stat().st_size, "full_bytes": reference.stat().st_size,
            "members": {name: int(a.nbytes) for name, a in members.items()}}


def reopen(tree: Path, points_path: str, cache: str) -> dict:
    """One cached reopen in a fresh interpreter running the core of `tree`."""
    env = {**os.environ, "PYTHONPATH": str(tree)}
    done = subprocess.run([sys.executable, "-c", REOPEN, points_path, cache], cwd=tree, env=env,
                          capture_output=True, text=True, check=False)
    if done.returncode != 0:
        return {"error": done.stderr.strip().splitlines()[-1] if done.stderr else "failed"}
    return json.loads(done.stdout.strip().splitlines()[-1])


def reference_tree(folder: Path, commit: str) -> Path:
    """The reference commit's core, extracted into folder (git archive)."""
    archive = subprocess.run(["git", "archive", commit, "core"], cwd=ROOT, capture_output=True,
                             check=True).stdout
    subprocess.run(["tar", "-x", "-C", str(folder)], input=archive, check=True)
    return folder


def best(runs: list[dict]) -> dict:
    """The fastest of the runs that were cache hits ({'error'} when none was)."""
    good = [r for r in runs if r.get("source") == "cache"]
    if not good:
        return {"error": next((r["error"] for r in runs if "error" in r), "not a cache hit")}
    return {"seconds": min(r["seconds"] for r in good),
            "cpu_seconds": min(r["cpu_seconds"] for r in good)}


def run_size(n: int, args: argparse.Namespace, work: Path, reference: Path) -> dict:
    """Build, write both entries and time the reopens of n torus points."""
    points_path = str(work / f"points_{n}.npy")
    np.save(points_path, noisy_torus(n, args.seed))
    compact, full = str(work / f"compact_{n}"), str(work / f"full_{n}")
    sizes = run_isolated(build_entries, points_path, compact, full)
    if "error" in sizes:
        return sizes
    runs: dict[str, list[dict]] = {"compact": [], "reference": []}
    for _ in range(args.reps):  # alternately, so that a change of load hits both
        runs["reference"].append(reopen(reference, points_path, full))
        runs["compact"].append(reopen(ROOT, points_path, compact))
    return {**sizes, "n": n, "runs": runs,
            "compact": best(runs["compact"]), "reference": best(runs["reference"])}


def figures(result: dict) -> list[Figure]:
    """The figures of one size: bytes per point (goal), size and reopen against the
    reference."""
    n = result["n"]
    out = [Figure(name=f"entry_bytes_per_point_{n}", label=f"cache entry, {n:,} points",
                  value=result["compact_bytes"] / n, unit="B/point", goal=f"<= {BYTES_GOAL}"),
           Figure(name=f"entry_size_{n}", label=f"cache entry size, {n:,} points",
                  value=result["compact_bytes"] / 1e6, unit="MB",
                  anchor="the reference layout's entry", anchor_value=result["full_bytes"] / 1e6)]
    mine, theirs = result["compact"], result["reference"]
    if "seconds" in mine and "seconds" in theirs:
        for clock, word, key, goal in (("wall", "wall", "seconds", f"<= {REOPEN_GOAL}"),
                                       ("cpu", "CPU", "cpu_seconds", None)):
            out.append(Figure(name=f"reopen_{n}_{clock}",
                              label=f"cached reopen, {n:,} points, {word}", value=mine[key],
                              unit="s", anchor="the reference code reading its own entry",
                              anchor_value=theirs[key], goal=goal))
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, nargs="+", default=[200_000], help="torus sizes")
    parser.add_argument("--seed", type=int, default=0, help="sample seed")
    parser.add_argument("--reps", type=int, default=3, help="reopens of each entry per size")
    parser.add_argument("--reference", default=REFERENCE, help="the reference commit")
    parser.add_argument("--reference-tree", metavar="PATH",
                        help="a checkout whose core/ is the reference (instead of --reference)")
    parser.add_argument("--json", metavar="PATH", help="also write the results as JSON")
    args = parser.parse_args(argv)
    out, results = [], {}
    with tempfile.TemporaryDirectory() as folder:
        work = Path(folder)
        if args.reference_tree:
            reference = Path(args.reference_tree).resolve()
            if not (reference / "core").is_dir():
                parser.error(f"{reference} holds no core/")
        else:
            (work / "reference").mkdir()
            reference = reference_tree(work / "reference", args.reference)
        for n in args.n:
            start = time.perf_counter()
            results[n] = result = run_size(n, args, work, reference)
            if "error" in result:
                print(f"{n:>9,} points: ERROR {result['error']}")
                continue
            for figure in figures(result):
                out.append(figure)
                ratio = "" if figure.ratio is None else f"  {figure.ratio:.3f}x {figure.anchor}"
                print(f"{figure.label:<42} {figure.value:10.3f} {figure.unit}{ratio}")
            print(f"    ({time.perf_counter() - start:.0f} s for this size)")
    if args.json:
        write_json(args.json, {"seed": args.seed, "reference": args.reference,
                               "results": {str(n): r for n, r in results.items()}})
    load = ", ".join(f"{value:.1f}" for value in os.getloadavg())
    reference_name = (f"the checkout {args.reference_tree}" if args.reference_tree
                      else f"commit {args.reference}")
    save("bench_cache", out, notes=[
        f"Noisy torus (seed {args.seed}) with its signatures and topology. The reference is "
        f"{reference_name}'s core reading the same table in its layout (format version "
        f"2, every array stored); each reopen (obtain, a cache hit) in a fresh interpreter, "
        f"alternately, best of {args.reps}. Load average (1, 5, 15 min) {load} at the end."])
    return 0


if __name__ == "__main__":
    sys.exit(main())

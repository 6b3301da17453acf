"""Where the automatic backend should switch: our core build with Qhull (halves as automatic),
gmsh in one call and gmsh in halves, at several sizes of the torus and the bunny scan, each
build in its own fresh interpreter, the order of the three rotated from size to size.

    flock /work/bench.lock .venv/bin/python benchmarks/experiments/backend_thresholds.py \
        [--sizes 50000,100000,200000,350000,500000] [--repeats 2] \
        [--variants "qhull,gmsh one call,gmsh halves"] [--json out.json]
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

from benchmarks.bench_backends import SETS, ours
from benchmarks.isolate import run_isolated

VARIANTS = ("qhull", "gmsh one call", "gmsh halves")


def build(path: str, variant: str) -> dict:
    """ours(path, backend) with gmsh's split threshold set for the variant."""
    from core.backends import split

    if variant == "gmsh one call":
        split.GMSH_SPLIT_FROM_POINTS = 1 << 40
    elif variant == "gmsh halves":
        split.GMSH_SPLIT_FROM_POINTS = 0
    return ours(path, "qhull" if variant == "qhull" else "gmsh")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="50000,100000,200000,350000,500000")
    parser.add_argument("--sets", default="torus,bunny")
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--variants", default=",".join(VARIANTS))
    parser.add_argument("--json", metavar="PATH")
    args = parser.parse_args()
    rows = []
    sizes = [int(s) for s in args.sizes.split(",")]
    turn = 0
    for rep in range(args.repeats):
        for n in sizes:
            for name in args.sets.split(","):
                points = SETS[name](n, 0)
                with tempfile.TemporaryDirectory() as folder:
                    path = os.path.join(folder, "points.npy")
                    np.save(path, points)
                    chosen = tuple(v for v in VARIANTS if v in args.variants.split(","))
                    order = chosen[turn % len(chosen):] + chosen[:turn % len(chosen)]
                    turn += 1
                    for variant in order:
                        r = run_isolated(build, path, variant)
                        row = {"rep": rep, "n": n, "set": name, "variant": variant,
                               "seconds": r.get("seconds"), "cpu_seconds": r.get("cpu_seconds"),
                               "backend": r.get("backend"), "note": r.get("note"),
                               "error": r.get("error"), "load": os.getloadavg()[0]}
                        rows.append(row)
                        print(json.dumps(row), flush=True)
                        if args.json:
                            with open(args.json, "w") as handle:
                                json.dump(rows, handle, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Benchmark of a molecule end to end against freesasa, and of the weighted build against gudhi.

    python benchmarks/bench_molecule.py [--sizes 2 18 180] [--probe 1.4] [--no-save]

Inputs: copies of the shared 1A8O (556 atoms without its waters), each turned by a seeded
random rotation, on a 3 x 3 x k grid 24 Å apart (neighbouring copies interpenetrate like packed
domains), written as one PDB file: 2, 18 and 180 copies give 1,112, 10,008 and 100,080 atoms.

Per size, in one run, each timing the best of REPS (at 100,000 atoms the best of
LARGE_REPS, and one run of measure_molecule):
- ours end to end: read the PDB (core.io.molecule), build the weighted complex, exact area and
  volume of the union (`union_measures`); and the whole `measure_molecule` (also per-atom
  areas, exact cavities and pockets);
- freesasa end to end, its default: read the same PDB (freesasa.Structure, all records as ATOM)
  and its default Lee–Richards (20 slices, probe 1.4 Å, ProtOr radii): area only;
- our weighted build against gudhi's weighted AlphaComplex with precision 'fast' (its
  simplex tree), on the same centres and weights.
End to end and the build are also compared on the CPU clock (all threads of the process).
Figures go to benchmarks/results/molecule.json (benchmarks/results.py).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from benchmarks.results import Figure, save  # noqa: E402
from core.complex import AlphaComplex  # noqa: E402
from core.io.molecule import read_molecule  # noqa: E402
from core.molecule.analysis import measure_molecule  # noqa: E402
from core.molecule.measures import dual_simplices, union_measures  # noqa: E402

SPACING = 24.0  # Å between copies: about the protein's width, so copies overlap a little


def _source() -> Path:
    """The shared 1A8O.pdb: beside the checkout (or a worktree's parent), or $ALPHASCOOP_DATA."""
    import os

    places = [ROOT.parent / "shared" / "data", ROOT.parents[1] / "shared" / "data"]
    if os.environ.get("ALPHASCOOP_DATA"):
        places.append(Path(os.environ["ALPHASCOOP_DATA"]))
    return next((p / "1A8O.pdb" for p in places if (p / "1A8O.pdb").is_file()),
                places[0] / "1A8O.pdb")


SOURCE = _source()
CHAINS = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789"
RESIDUE_STEP = 1000  # copies past the 62nd reuse a chain letter, residues numbered on from here
REPS = 3  # every timing is the best of this many runs (the machine is shared)
SINGLE_RUN_ATOMS = 50_000  # above this, LARGE_REPS runs per timing, one of measure_molecule
LARGE_REPS = 2  # one run alone catches whatever else the shared machine ran then


def _atom_lines() -> list[str]:
    """1A8O's atom records without waters, every one as ATOM (freesasa skips HETATM)."""
    lines = [line for line in SOURCE.read_text().splitlines()
             if line.startswith(("ATOM", "HETATM")) and line[17:20] != "HOH"]
    return ["ATOM  " + line[6:] for line in lines]


def write_copies(copies: int, path: Path, seed: int = 0) -> int:
    """Write `copies` rotated copies of 1A8O on the grid as one PDB file; the atom count.
    Every copy is its own (chain, residue numbers): no atom repeats another's name."""
    lines = _atom_lines()
    xyz = np.array([[float(line[30 + 8 * i:38 + 8 * i]) for i in range(3)] for line in lines])
    base = xyz - xyz.mean(0)
    rotations = Rotation.random(copies, random_state=seed)
    grid = np.stack(np.meshgrid(range(3), range(3), range(-(-copies // 9)), indexing="ij"),
                    -1).reshape(-1, 3)[:copies]
    out, serial = [], 0
    for c, (rot, g) in enumerate(zip(rotations, grid, strict=True)):
        for line, p in zip(lines, rot.apply(base) + SPACING * g, strict=True):
            serial += 1
            residue = int(line[22:26]) + RESIDUE_STEP * (c // len(CHAINS))
            out.append(f"{line[:6]}{serial % 100000:5d}{line[11:21]}{CHAINS[c % len(CHAINS)]}"
                       f"{residue:4d}{line[26:30]}{p[0]:8.3f}{p[1]:8.3f}{p[2]:8.3f}{line[54:]}")
    path.write_text("\n".join(out) + "\nEND\n")
    return serial


def timed(reps: int, fn, *args, **kwargs):
    """(result, seconds): the best wall time of `reps` calls (timed_both without the CPU)."""
    out, wall, _ = timed_both(reps, fn, *args, **kwargs)
    return out, wall


def timed_both(reps: int, fn, *args, **kwargs):
    """(result, wall seconds, CPU seconds): the best of `reps` calls on each clock (the CPU
    clock counts every thread of this process: on a shared machine it shows the work done
    where the wall clock shows the waits too)."""
    wall, cpu, out = float("inf"), float("inf"), None
    for _ in range(reps):
        start, start_cpu = time.perf_counter(), time.process_time()
        out = fn(*args, **kwargs)
        wall = min(wall, time.perf_counter() - start)
        cpu = min(cpu, time.process_time() - start_cpu)
    return out, wall, cpu


def ours_area_volume(path: Path, probe: float):
    """Read, build, exact area and volume of the union: our end to end."""
    mol = read_molecule(path)
    ac = AlphaComplex.from_points(mol.centres, weights=mol.weights(probe))
    k = dual_simplices(ac)
    return union_measures(ac.points, np.sqrt(ac.weights), *k[1:], vertices=k[0][:, 0])


def ours_everything(path: Path, probe: float):
    """Read, build, measure_molecule (area, volume, per-atom areas, cavities, pockets)."""
    mol = read_molecule(path)
    return measure_molecule(AlphaComplex.from_points(mol.centres, weights=mol.weights(probe)),
                            probe)


def freesasa_default(path: Path):
    """freesasa end to end with its defaults: read the PDB, Lee–Richards."""
    import freesasa

    return freesasa.calc(freesasa.Structure(str(path)))


def gudhi_fast(centres: np.ndarray, weights: np.ndarray):
    """gudhi's weighted alpha complex, precision 'fast', to its simplex tree."""
    import gudhi

    return gudhi.AlphaComplex(points=centres, weights=weights,
                              precision="fast").create_simplex_tree()


def run_size(copies: int, probe: float, folder: Path) -> tuple[list[Figure], dict]:
    """Figures and a table row for one input size."""
    import freesasa

    freesasa.setVerbosity(freesasa.silent)
    path = folder / f"copies{copies}.pdb"
    atoms = write_copies(copies, path)
    reps = LARGE_REPS if atoms > SINGLE_RUN_ATOMS else REPS
    union, ours, ours_cpu = timed_both(reps, ours_area_volume, path, probe)
    full, everything = timed(1 if atoms > SINGLE_RUN_ATOMS else REPS, ours_everything, path,
                             probe)
    result, theirs, theirs_cpu = timed_both(reps, freesasa_default, path)
    mol = read_molecule(path)
    weights = mol.weights(probe)
    _, build, build_cpu = timed_both(reps, AlphaComplex.from_points, mol.centres,
                                     weights=weights)
    _, gudhi, gudhi_cpu = timed_both(reps, gudhi_fast, mol.centres, weights)
    size = f"{atoms:,} atoms"
    figures = [
        Figure(f"end_to_end_{atoms}", f"read + build + exact area and volume, {size}", ours,
               "s", "freesasa default Lee-Richards, read + area", theirs, "<= 1"),
        Figure(f"everything_{atoms}", f"read + build + measure_molecule (per-atom, cavities, "
               f"pockets), {size}", everything, "s",
               "freesasa default Lee-Richards, read + area", theirs),
        Figure(f"weighted_build_{atoms}", f"weighted build, {size}", build, "s",
               "gudhi weighted AlphaComplex, precision fast", gudhi, "<= 0.8"),
        Figure(f"end_to_end_{atoms}_cpu", f"read + build + exact area and volume, {size}, CPU",
               ours_cpu, "s", "freesasa default Lee-Richards, read + area, CPU", theirs_cpu),
        Figure(f"weighted_build_{atoms}_cpu", f"weighted build, {size}, CPU", build_cpu, "s",
               "gudhi weighted AlphaComplex, precision fast, CPU", gudhi_cpu),
    ]
    row = [atoms, round(ours, 3), round(everything, 3), round(theirs, 3), round(build, 3),
           round(gudhi, 3), round(union.area, 2), round(result.totalArea(), 2),
           len(full.pockets), len(full.cavities)]
    return figures, row


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[2, 18, 180],
                        help="copies of 1A8O per input (556 atoms each)")
    parser.add_argument("--probe", type=float, default=1.4, help="probe radius, Å")
    parser.add_argument("--no-save", action="store_true", help="print only")
    parser.add_argument("--results", type=Path, default=None, help="folder of the result JSON "
                        "(default benchmarks/results)")
    args = parser.parse_args(argv)
    figures, rows = [], []
    with tempfile.TemporaryDirectory() as folder:
        for copies in args.sizes:
            more, row = run_size(copies, args.probe, Path(folder))
            figures += more
            rows.append(row)
            for f in more:
                print(f"{f.label:<70} {f.value:8.3f} s  vs {f.anchor_value:8.3f} s  "
                      f"ratio {f.ratio:.2f}" + (f" (goal {f.goal}: {f.met})" if f.goal else ""))
    columns = ["atoms", "ours_end_to_end_s", "ours_everything_s", "freesasa_default_s",
               "our_build_s", "gudhi_fast_build_s", "our_area", "freesasa_area", "pockets",
               "cavities"]
    if not args.no_save:
        extra = {} if args.results is None else {"folder": args.results}
        print(save("molecule", figures, **extra, tables=[{
            "title": "Molecules end to end (synthetic copies of 1A8O)", "columns": columns,
            "rows": rows}], notes=[
            "Ours: read the PDB, weighted build, exact area and volume; freesasa: read the "
            "same PDB and its default Lee-Richards (20 slices; ProtOr radii, area only). "
            "'everything' adds per-atom areas, exact cavities and pockets.",
            "Inputs: rotated copies of 1A8O packed 24 Å apart (bench_molecule.py)."]))
    return 0


if __name__ == "__main__":
    sys.exit(main())

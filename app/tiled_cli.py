"""`alphascoop info|export --tiled`: exact shapes at one alpha, tile by tile on Dask, for
point sets bigger than memory (core.tiled). No Qt."""

from __future__ import annotations

import argparse
import re
from pathlib import Path

SIZE_UNITS = {"": 1, "b": 1, "k": 10**3, "kb": 10**3, "kib": 2**10, "m": 10**6, "mb": 10**6,
              "mib": 2**20, "g": 10**9, "gb": 10**9, "gib": 2**30, "t": 10**12, "tb": 10**12,
              "tib": 2**40}
STREAMED = (".las", ".laz")


def memory_size(text: str) -> int:
    """A memory size in bytes from '2GiB', '1500MB', '4g' or a plain number of bytes."""
    match = re.fullmatch(r"\s*([0-9]*\.?[0-9]+)\s*([a-zA-Z]*)\s*", text)
    unit = match and match.group(2).lower()
    if not match or unit not in SIZE_UNITS or float(match.group(1)) <= 0:
        raise argparse.ArgumentTypeError(f"expected a memory size such as 2GiB or 1500MB, "
                                         f"not {text!r}")
    return int(float(match.group(1)) * SIZE_UNITS[unit])


def scheduler_address(text: str) -> str:
    """A Dask scheduler address tcp://HOST:PORT."""
    if not re.fullmatch(r"tcp://[^\s:/]+:[0-9]{1,5}", text):
        raise argparse.ArgumentTypeError(f"expected tcp://HOST:PORT, not {text!r}")
    return text


def add_tiled_options(sub: argparse.ArgumentParser, count) -> None:
    """--tiled and how tiles run (the point count type `count` is the CLI's)."""
    group = sub.add_argument_group("tiled (exact shapes of point sets bigger than memory)")
    group.add_argument("--tiled", action="store_true",
                       help="compute the shape at --alpha/--alpha2 tile by tile (exact; "
                            "LAS/LAZ streamed in chunks, COPC read by its index), on a "
                            "local Dask cluster")
    group.add_argument("--tile-points", type=count, metavar="N",
                       help="at most N points in a tile's core (default: from the memory)")
    group.add_argument("--memory-per-worker", type=memory_size, metavar="SIZE",
                       help="memory of each worker, e.g. 2GiB (default: a share of the "
                            "machine's)")
    group.add_argument("--scheduler", type=scheduler_address, metavar="tcp://HOST:PORT",
                       help="run the tiles on this existing Dask cluster")
    group.add_argument("--scratch", metavar="DIR",
                       help="folder for the tile files (with --scheduler: one the workers "
                            "share; default: a temporary folder)")


def check_tiled(args, usage_error) -> None:
    """Options that a tiled run cannot honour, as usage errors (`usage_error(message)`)."""
    tiled_only = ("tile_points", "memory_per_worker", "scheduler", "scratch")
    if not args.tiled:
        given = [o for o in tiled_only if getattr(args, o) is not None]
        if given:
            raise usage_error(f"--{given[0].replace('_', '-')} needs --tiled")
        return
    if args.alpha is None and args.alpha2 is None:
        raise usage_error("--tiled needs --alpha R or --alpha2 A2 (a tiled shape is computed "
                          "at one alpha)")
    if args.scheduler and not args.scratch:
        raise usage_error("--scheduler needs --scratch DIR, a folder every worker can read")
    for option in ("density", "anisotropic", "scan"):
        if getattr(args, option, None) is not None:
            raise usage_error(f"--{option} does not apply with --tiled")
    if getattr(args, "table", False):
        raise usage_error("--table does not apply with --tiled (a tiled run has no table)")


def point_source(path: str | Path, columns: str | None = None, subsample: int | None = None,
                 weights: str | None = None, radius: str | None = None,
                 radius_add: float | None = None):
    """(chunked point source, georef, load report or None) of a file read with these
    options: a plain LAS/LAZ is streamed (core.tiled.sources.LasSource), a COPC file (the
    COPC VLR, whatever its name) read by its octree (core.tiled.copc.CopcSource), a big
    plain text or PLY file streamed (core.io.streams); anything else is read whole by
    core.io."""
    from core.io import read_points
    from core.io.streams import streamed_source
    from core.tiled.sources import ArraySource

    path = Path(path)
    plain = not (columns or subsample or weights or radius)
    if path.suffix.lower() in STREAMED and plain:
        return las_source(path), None, None
    source = streamed_source(path) if plain else None
    if source is not None:
        return source, None, None
    ps = read_points(path, columns=columns, subsample=subsample, weights=weights,
                     radius=radius, radius_add=radius_add)
    return ArraySource.from_points(ps.points, ps.weights), ps.report.georef, ps.report


def las_source(path: Path):
    """The chunked source of a LAS/LAZ file: by its index if the file is COPC (after the
    header checks core.io makes, so laspy never reads a corrupt VLR count)."""
    from core.errors import FileFormatError
    from core.io.las_checks import check_las_file
    from core.tiled.copc import CopcSource
    from core.tiled.octree import is_copc
    from core.tiled.sources import LasSource, unreadable_las

    if not path.is_file():
        raise FileFormatError(f"{path}: no such file")
    check_las_file(path)
    try:
        copc = is_copc(path)
    except Exception as exc:  # laspy on a header it cannot parse
        raise unreadable_las(path, exc) from exc
    return CopcSource.open(path) if copc else LasSource(path)


def run_tiled(args, progress=None, summary: bool = False):
    """(merged shape, run report, georef, load report) of the tiled run the options ask;
    with `summary` (for `info`), only the shape's numbers (core.tiled.summary: no step holds
    the whole shape) where no georeference asks for the polygons' own measures."""
    from core.tiled.memory import query
    from core.tiled.runner import RunOptions, RunReport, tiled_run

    source, georef, load_report = point_source(args.file, args.columns, args.subsample,
                                               args.weights, args.radius, args.radius_add)
    options = RunOptions(memory_per_worker=args.memory_per_worker, scheduler=args.scheduler,
                         scratch=args.scratch, tile_points=args.tile_points,
                         progress=progress)
    report = RunReport()
    merged = tiled_run(source, query(args.alpha, args.alpha2), options, report,
                       summary=summary and georef is None)
    return merged, report, georef, load_report


def tiled_summary(merged, report, georef, load_report) -> dict:
    """What `info --tiled` reports, JSON-ready (`merged`: a TiledShape, or a TiledSummary
    where there is no `georef`)."""
    from core.tiled.view import MergedComplex

    measures = (("volume", "area") if merged.dim == 3 else ("area", "perimeter"))
    out = {
        "tiled": True,
        "load": None if load_report is None else load_report.to_dict(),
        "points": merged.n_points,
        "dim": merged.dim,
        "ambient_dim": merged.ambient_dim,
        "weighted": merged.weighted,
        "hidden_points": merged.hidden,
        "alpha": merged.alpha,
        "alpha2": merged.alpha2,
        "tiles": merged.n_tiles,
        "tile_side": report.plan.side,
        "margin": report.plan.margin,
        "classes": {name: {"exterior": None, **counts}
                    for name, counts in merged.counts().items()},
        "components": merged.components,
        "euler_characteristic": merged.euler(),
        "betti": merged.betti(),
        measures[0]: merged.measure,
        measures[1]: merged.boundary_measure,
        "seconds": {k: round(v, 3) for k, v in report.seconds.items()},
        "peak_worker_bytes": report.peak_worker_bytes,
    }
    if georef is not None:
        from core.export.polygons import geographic_metadata

        ac = MergedComplex(merged)
        meta = geographic_metadata(ac, ac.shape(), georef)
        out.update({k: meta[k] for k in ("units", "area_m2", "perimeter_m") if k in meta})
    return out


def tiled_text(info: dict) -> str:
    """The human-readable form of `tiled_summary`."""
    names = [k for k in ("volume", "area", "perimeter") if k in info]
    lines = [f"points      {info['points']:,} ({info['dim']}D, {info['tiles']:,} tiles of side "
             f"{info['tile_side']:.6g}, margin {info['margin']:.6g})",
             f"at alpha    {info['alpha']:.6g}" + (f" (alpha² {info['alpha2']:.6g})"
                                                    if info["weighted"] else ""),
             f"components  {info['components']:,}"
             + (f", holes {info['betti'][1]:,}" if info["betti"] else ""),
             *(f"{n:<12}{info[n]:.6g}" for n in names),
             f"{'classes':<12}{'singular':>12}{'regular':>12}{'interior':>12}"]
    for name, counts in info["classes"].items():
        lines.append(f"  {name:<10}" + "".join(f"{counts[c]:>12,}"
                                             for c in ("singular", "regular", "interior")))
    return "\n".join(lines)


def write_merged(merged, output: str | Path, *, alpha: float | None = None,
                 alpha2: float | None = None, manifold: bool = True, sidecar: bool = False,
                 source: str | Path | None = None, georef=None, progress=None) -> str:
    """Write a merged tiled shape with core.export (atomic; never over `source`); its
    one-line report."""
    from core.export import write_shape
    from core.tiled.view import MergedComplex

    report = write_shape(MergedComplex(merged), alpha, output, alpha2=alpha2,
                         manifold=manifold, sidecar=sidecar, source=source, georef=georef,
                         progress=progress)
    return report.line() + f" [tiled: {merged.n_tiles:,} tiles]"


def write_tiled(args, merged, georef) -> str:
    """Write the merged shape the export options ask for; its one-line report."""
    alpha = None if args.alpha2 is not None else args.alpha
    return write_merged(merged, args.output, alpha=alpha, alpha2=args.alpha2,
                        manifold=args.manifold, sidecar=args.sidecar, source=args.file,
                        georef=georef)

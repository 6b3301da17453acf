"""Explore a subsample, export at full resolution (no Qt): the banner a subsampled dataset
shows, and File → Export at full resolution…, the tiled export (core.tiled on Dask) of every
point of the file at the window's alpha, as `alphascoop export --tiled` writes it."""

from __future__ import annotations

import importlib.util
from pathlib import Path

from app.dataset import Dataset, ImportOptions
from app.tiled_cli import STREAMED, point_source, write_merged
from core.complex import at_value
from core.progress import Progress, Stepper

TITLE = "Export at full resolution"
#: Share of the progress bar the tiled run takes (the write takes the rest).
RUN_SHARE = 0.9
#: Share of the memory available now that the window's build may plan for.
WINDOW_MEMORY_SHARE = 0.5


def window_points() -> int:
    """Points the window can build in the memory available now (core.storage.memory, which
    also heeds rlimits and cgroups; core.tiled.plan's BYTES_PER_POINT of a 3D build)."""
    from core.storage.memory import available_memory
    from core.tiled.plan import BYTES_PER_POINT

    return int(WINDOW_MEMORY_SHARE * available_memory() // BYTES_PER_POINT[3])


def declared_points(path: Path) -> int | None:
    """The point count a LAS/LAZ header declares (None: another format, or unreadable: the
    reader will say why)."""
    if path.suffix.lower() not in STREAMED:
        return None
    try:
        import laspy

        with laspy.open(path) as reader:
            return int(reader.header.point_count)
    except Exception:  # any header laspy refuses: the open itself reports it
        return None


def above_budget(path: Path) -> bool:
    """True when the file declares more points than the window can build (window_points)."""
    count = declared_points(path)
    return count is not None and count > window_points()


def subsample_banner(dataset: Dataset) -> str | None:
    """The banner of a dataset read as a subsample ('Subsample: 20,000 of 108,000 points…'),
    None when every point was read."""
    report = dataset.report
    if report is None or report.subsampled_from is None:
        return None
    return (f"Subsample: {report.n_points:,} of {report.subsampled_from:,} points "
            f"({report.subsample_method}). The shape shown is the subsample's; "
            f"File → {TITLE}… computes it from every point at the current alpha.")


def refusal(dataset: Dataset) -> str | None:
    """Why this dataset cannot be exported at full resolution (None: it can)."""
    if importlib.util.find_spec("distributed") is None:
        return "it runs on Dask, which is not installed (pip install 'alphascoop[tiled]')"
    if dataset.is_molecule:
        return "a molecule is never subsampled: use Export shape"
    if dataset.ac.mode.active:
        return (f"alpha modes ({dataset.ac.mode.name}) are not tiled: switch to classic "
                "alpha first")
    return None


def write_full_resolution(path: Path, options: ImportOptions | None, alpha: float,
                          output: Path, manifold: bool = True,
                          progress: Progress | None = None) -> str:
    """Read every point of `path` (its columns as `options` say, never subsampled), compute
    the shape at `alpha` (the table's value: a signed radius for weighted points) tile by
    tile on a local Dask cluster, and write it to `output` atomically; the line saying what
    was written. Cancelled from `progress` stops the tasks and leaves `output` as it was."""
    from core.tiled.memory import query
    from core.tiled.runner import RunOptions, tiled_run

    columns = None if options is None else options.columns
    at = at_value(alpha)
    step = Stepper(progress)
    source, georef, _ = point_source(path, columns=columns)
    merged = tiled_run(source, query(at.get("alpha"), at.get("alpha2")),
                       RunOptions(progress=step.part(0.0, RUN_SHARE)))
    return write_merged(merged, output, alpha=at.get("alpha"), alpha2=at.get("alpha2"),
                        manifold=manifold, source=path, georef=georef,
                        progress=step.part(RUN_SHARE, 1.0 - RUN_SHARE))

"""Loading and building a dataset (no Qt): read points, build the complex, pick a start alpha."""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from app.camera import Z_UP, ViewFrame, frame_for
from core import AlphaComplex
from core.cache import build_cached, is_cached
from core.complex import at_value
from core.cursor import ShapeCursor
from core.io import LoadReport, read_points
from core.modes import Mode, file_normals
from core.molecule.analysis import MoleculeMeasures, measure_molecule
from core.progress import Progress
from core.signatures import Signatures

Build = Callable[..., AlphaComplex]  # build(points, progress[, weights=, mode=, normals=])
READ_SHARE, BUILD_SHARE, INDEX_START = 0.1, 0.85, 0.95


def build_here(points: np.ndarray, progress: Progress, weights: np.ndarray | None = None,
               mode: Mode | None = None, normals: np.ndarray | None = None) -> AlphaComplex:
    """The complex and its signatures, built in this thread (cached); weighted when
    `weights` (squared radii) are given, in the alpha `mode` (with `normals` if it takes
    given ones)."""
    return build_cached(points, progress=progress, signatures=True, weights=weights,
                        mode=mode, normals=normals)


@dataclass(frozen=True)
class Dataset:
    """A built dataset: its source, complex, spectrum (s,) float64 and timings in seconds."""

    path: Path
    ac: AlphaComplex
    spectrum: np.ndarray
    optimal_alpha: float
    default_alpha: float  # where the view opens (ac.default_alpha())
    signatures: Signatures
    n_input: int
    report: LoadReport | None
    load_seconds: float
    build_seconds: float
    cursor: ShapeCursor | None = None  # the slider's incremental shape (None: made on use)
    from_cache: bool = False  # the table was loaded from the cache, not built
    attributes: dict = field(default_factory=dict)  # name -> per-point values, rows of ac.points
    frame: ViewFrame = Z_UP  # which way is up, and the view it opens with (app.camera)
    #: Molecules: the measures of the atoms' union at alpha² = 0, and (m,) int16 atomic
    #: numbers aligned with ac.points (None for other point sets).
    molecule: MoleculeMeasures | None = None
    atomic_numbers: np.ndarray | None = None

    @property
    def unit(self) -> str | None:
        """The length unit the file declares ('m' for geographic data projected to metres),
        None when unknown."""
        return "m" if self.report is not None and self.report.georef is not None else None

    def build_line(self) -> str:
        """How the table came and which backend triangulated it: 'built in 12.3 s (gmsh)'
        or 'loaded from cache in 0.4 s (qhull)'."""
        how = "loaded from cache" if self.from_cache else "built"
        return f"{how} in {self.build_seconds:.2f} s ({self.ac.build_info.backend})"


@dataclass(frozen=True)
class ImportOptions:
    """How to read a file: coordinate columns ('x,y,z', names or 0-based indices; None =
    detected) and thinning to at most `subsample` points by 'voxel' or 'random'."""

    columns: str | None = None
    subsample: int | None = None
    subsample_method: str = "voxel"

    def read_kwargs(self) -> dict:
        """Keywords for core.io.read_points."""
        return {"columns": self.columns or None, "subsample": self.subsample,
                "subsample_method": self.subsample_method}


def load_dataset(path: str | Path, progress: Progress, build: Build = build_here,
                 mode: Mode | None = None, options: ImportOptions | None = None) -> Dataset:
    """Read (with `options`: columns, subsampling) and build path in the alpha `mode`
    (default classic), reporting progress(fraction, stage); Cancelled stops it.

    `build(points, progress)` makes the complex with its signatures (the window passes
    app.build_process.build, which can be cancelled mid-triangulation); weighted files
    (core.io: weight or radius columns) call it with the keyword `weights` too, a mode with
    `mode` and its given `normals`.
    """
    mode = mode or Mode()
    path = Path(path)
    started = time.perf_counter()
    progress(0.0, "reading")
    pointset = read_points(path, **(options or ImportOptions()).read_kwargs())
    read_done = time.perf_counter()

    def build_progress(fraction: float, stage: str) -> None:
        progress(READ_SHARE + BUILD_SHARE * fraction, stage)

    normals = file_normals(mode, pointset.attributes, path.name)
    weights = pointset.weights
    cached = is_cached(pointset, mode, normals)
    options = {} if weights is None else {"weights": weights}
    if mode.active:
        options.update(mode=mode, normals=normals)
    ac = build(pointset.points, build_progress, **options)
    built = time.perf_counter()
    progress(READ_SHARE + BUILD_SHARE, "choosing alpha")
    molecule, numbers = _molecule(ac, pointset)
    # a molecule opens at alpha² = 0: the dual of the union of its balls, what it measures
    optimal = float(ac.optimal_alpha())
    alpha = 0.0 if molecule is not None else float(ac.default_alpha())
    progress(INDEX_START, "indexing for the slider")
    cursor = ac.cursor()
    cursor.move(**at_value(alpha))  # the table value itself, negative ones included
    ac.signatures().counts_at(alpha)  # sorts its class thresholds here, not in the info dock
    ac.persistence()  # for the signatures dock's diagram, computed here, not in the GUI thread
    progress(1.0, "done")
    return Dataset(
        path=path, ac=ac, spectrum=ac.spectrum(), optimal_alpha=optimal,
        default_alpha=alpha,
        signatures=ac.signatures(), n_input=len(pointset.points), report=pointset.report,
        load_seconds=read_done - started, build_seconds=built - read_done, cursor=cursor,
        from_cache=cached, frame=frame_for(path, pointset.report), molecule=molecule,
        atomic_numbers=numbers,
        attributes=aligned_attributes(pointset.attributes, ac.input_index, len(ac.points)),
    )


def aligned_attributes(attributes: dict[str, np.ndarray], input_index: np.ndarray,
                       n_points: int) -> dict[str, np.ndarray]:
    """Per-input-row attributes re-indexed to the complex's points (input_index maps input rows
    to point rows, -1 = not a vertex); merged duplicates keep one row's value. Read-only."""
    index = np.asarray(input_index, dtype=np.int64)
    used = index >= 0
    out = {}
    for name, values in attributes.items():
        values = np.asarray(values)
        if len(values) != len(index):
            continue
        aligned = np.zeros((n_points, *values.shape[1:]), dtype=values.dtype)
        aligned[index[used]] = values[used]
        aligned.flags.writeable = False
        out[name] = aligned
    return out


def _molecule(ac: AlphaComplex, pointset) -> tuple[MoleculeMeasures | None, np.ndarray | None]:
    """For a molecule (atoms with atomic numbers, weighted): its measures at alpha² = 0 and
    the atomic numbers of ac's points; (None, None) otherwise."""
    numbers = pointset.attributes.get("atomic_number")
    if numbers is None or ac.weights is None or ac.dim != 3:
        return None, None
    rows = np.zeros(len(ac.points), dtype=np.int16)
    shown = ac.input_index >= 0
    rows[ac.input_index[shown]] = np.asarray(numbers)[shown]
    probe = float(np.sqrt(pointset.attributes["weights"][0])
                  - pointset.attributes["vdw_radius"][0])
    return measure_molecule(ac, round(probe, 6)), rows

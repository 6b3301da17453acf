"""Loading a dataset (no Qt): read points, obtain the complex (core.obtain: cache or build),
pick a start alpha; `with_topology` completes its topology afterwards, `with_measures` a
molecule's measures."""

from __future__ import annotations

import os
import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from app.camera import Z_UP, ViewFrame, frame_for
from app.topology_child import TopologyChild
from app.topology_file import TopologyParts, attach
from core import AlphaComplex
from core.complex import at_value
from core.errors import InputError
from core.io import LoadReport, read_points
from core.modes.alpha_modes import Mode, file_normals
from core.molecule.analysis import MoleculeMeasures, measure_molecule
from core.obtain import Obtained, Runner, Source, add_topology, obtain, run_here
from core.pipeline import BACKENDS, check_backend
from core.progress import Progress
from core.query.cursor import ShapeCursor
from core.topology.opening import opening_alpha_of
from core.topology.persistence import Persistence
from core.topology.pieces import Pieces, pieces_at
from core.topology.signatures import Signatures
from core.topology.suggest import AlphaRange

READ_SHARE, BUILD_SHARE, INDEX_START = 0.1, 0.85, 0.95
POINTS_READ = "points read"  # the stage reported once the file was read, before the table
N_SUGGESTIONS = 5  # suggested alphas shown (slider ticks, the signature plots' ▼ markers)
BACKEND_VARIABLE = "ALPHASCOOP_BACKEND"  # the window's backend: qhull, gmsh, unset = automatic
SOURCE_WORDS = {"built": "built", "cache": "loaded from cache",
                "rebuilt": "rebuilt (its cached table was damaged)"}


@dataclass(frozen=True)
class Dataset:
    """A built dataset: its source, complex, spectrum (s,) float64 and timings in seconds.

    The topology (signatures, optimal alpha, persistence) may come after the table: until
    `has_topology`, `signatures`, `optimal_alpha` and `persistence` are None and
    `default_alpha` is the quick choice (quick_alpha); with_topology(dataset) completes it
    here, with_parts(dataset, parts) with what a topology process found.
    """

    path: Path
    ac: AlphaComplex
    spectrum: np.ndarray
    optimal_alpha: float | None
    default_alpha: float  # where the view opens (ac.default_alpha(); quick_alpha before)
    signatures: Signatures | None
    n_input: int
    report: LoadReport | None
    load_seconds: float
    build_seconds: float
    cursor: ShapeCursor | None = None  # the slider's incremental shape (None: made on use)
    source: Source = "built"  # where the table came from (core.obtain): built, cache, rebuilt
    entry: Path | None = None  # its cache file (None: not cached)
    damage: str | None = None  # "rebuilt": what was wrong with the cached table (core.obtain)
    topology_seconds: float | None = None  # the topology pass (0 when it came with the table)
    attributes: dict = field(default_factory=dict)  # name -> per-point values, rows of ac.points
    frame: ViewFrame = Z_UP  # which way is up, and the view it opens with (app.camera)
    #: Molecules: the measures of the atoms' union at alpha² = 0 (None for other point sets,
    #: and for a molecule until with_measures: they may come after the table), and (m,)
    #: int16 atomic numbers aligned with ac.points (None for other point sets).
    molecule: MoleculeMeasures | None = None
    atomic_numbers: np.ndarray | None = None
    probe: float | None = None  # a molecule's probe radius in Å (None: not a molecule)
    #: Molecules: (m,) str 'chain:residue:number:atom' of each of ac.points (else None).
    atom_labels: np.ndarray | None = None
    persistence: Persistence | None = None  # known with the topology (None before)
    #: The N_SUGGESTIONS suggested alphas, found with the topology off the GUI thread (None
    #: before, or for a dataset made elsewhere: suggestions_of computes them then).
    suggestions: tuple[AlphaRange, ...] | None = None
    #: The topology process the window started for this table while it loaded it
    #: (app.worker), until the topology job takes it over; None once the topology is known.
    topology_child: TopologyChild | None = None
    #: The pieces the triangles make at the opening alpha (found with the topology, off the
    #: GUI thread; None before).
    opening_pieces: Pieces | None = None
    #: How the file was read (columns, subsampling): a full-resolution export reads it
    #: again with the same columns (app.full_export).
    options: ImportOptions | None = None

    @property
    def has_topology(self) -> bool:
        """True once signatures, optimal alpha and persistence are known."""
        return self.signatures is not None

    @property
    def is_molecule(self) -> bool:
        """True for a molecule's atoms (weighted balls with atomic numbers), measured or not."""
        return self.probe is not None

    @property
    def needs_measures(self) -> bool:
        """True for a molecule whose measures are not known yet (with_measures gives them)."""
        return self.is_molecule and self.molecule is None

    @property
    def unit(self) -> str | None:
        """The length unit the file declares ('m' for geographic data projected to metres, 'Å'
        for a molecule), None when unknown."""
        if self.is_molecule:
            return "Å"
        return "m" if self.report is not None and self.report.georef is not None else None

    @property
    def from_cache(self) -> bool:
        """True when the table was read from the cache, not built."""
        return self.source == "cache"

    def build_line(self) -> str:
        """How the table came and which backend triangulated it: 'built in 12.3 s (gmsh)',
        'loaded from cache in 0.4 s (qhull)' or 'rebuilt (its cached table was damaged) in
        12.3 s (qhull)'."""
        words = SOURCE_WORDS[self.source]
        if self.source == "rebuilt" and self.damage:
            words = f"rebuilt (its cached table was damaged: {self.damage})"
        return f"{words} in {self.build_seconds:.2f} s ({self.ac.build_info.backend})"

    def topology_line(self) -> str:
        """'topology: computing…', or how long it took ('topology in 3.1 s'; 'topology
        from cache' when it came with the table)."""
        if not self.has_topology:
            return "topology: computing…"
        if not self.topology_seconds:
            return "topology from cache"
        return f"topology in {self.topology_seconds:.2f} s"


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


def load_dataset(path: str | Path, progress: Progress, runner: Runner = run_here,
                 mode: Mode | None = None, options: ImportOptions | None = None,
                 topology: bool = True, measures: bool = True) -> Dataset:
    """Read (with `options`: columns, subsampling) and build path in the alpha `mode`
    (default classic), reporting progress(fraction, stage); Cancelled stops it.

    The complex comes from core.obtain (the cache, or a build by `runner`: the window passes
    app.build_process.ChildRunner, which Cancel kills mid-triangulation). Without `topology`
    the dataset is returned as soon as the slider can use it (the table and its cursor); the
    window then completes it with with_topology in the background. A cached table that holds
    its topology is always returned complete. Without `measures` a molecule comes without its
    measures (pockets, cavities, exact area: the costly part), completed by with_measures.
    The stage POINTS_READ is reported once the file was read and checked for the mode, before
    the table is built or loaded. The triangulation backend is chosen automatically unless
    $ALPHASCOOP_BACKEND forces one.
    """
    mode = mode or Mode()
    path = Path(path)
    backend = window_backend()
    started = time.perf_counter()
    progress(0.0, "reading")
    pointset = read_points(path, **(options or ImportOptions()).read_kwargs())
    read_done = time.perf_counter()

    def build_progress(fraction: float, stage: str) -> None:
        progress(READ_SHARE + BUILD_SHARE * fraction, stage)

    normals = file_normals(mode, pointset.attributes, path.name)
    progress(READ_SHARE, POINTS_READ)  # the window lets its shown dataset go now
    try:
        obtained = obtain(pointset.points, weights=pointset.weights, mode=mode,
                          normals=normals, signatures=topology, backend=backend,
                          runner=runner, progress=build_progress)
    except InputError as error:
        if backend is None:
            raise
        raise InputError(f"{error} (the backend was forced by {BACKEND_VARIABLE}={backend})"
                         ) from None
    ac = obtained.complex
    built = time.perf_counter()
    progress(READ_SHARE + BUILD_SHARE, "choosing alpha")
    probe, numbers = _molecule(ac, pointset)
    molecule = measure_molecule(ac, probe) if probe is not None and measures else None
    labels = None if probe is None else _atom_labels(ac, pointset)
    complete = ac.has_signatures
    # a molecule opens at alpha² = 0: the dual of the union of its balls, what it measures
    handed = runner.handed_over(ac)  # what a build process found beside the table
    known = handed.opening_alpha
    alpha = 0.0 if probe is not None else (
        float(ac.default_alpha()) if complete else quick_alpha(ac) if known is None else known)
    progress(INDEX_START, "indexing for the slider")
    cursor = handed.cursor or ac.cursor()
    cursor.move(**at_value(alpha))  # the table value itself, negative ones included
    dataset = Dataset(
        path=path, ac=ac, spectrum=spectrum_of(ac, probe is not None),
        optimal_alpha=None, default_alpha=alpha,
        signatures=None, n_input=len(pointset.points), report=pointset.report,
        load_seconds=read_done - started, build_seconds=built - read_done, cursor=cursor,
        source=obtained.source, entry=obtained.entry, damage=obtained.damage,
        frame=frame_for(path, pointset.report, pointset.points),
        molecule=molecule, atomic_numbers=numbers, atom_labels=labels, probe=probe,
        attributes=aligned_attributes(pointset.attributes, ac.input_index, len(ac.points)),
        options=options,
    )
    if complete:
        dataset = with_topology(dataset)
    progress(1.0, "done")
    return dataset


def spectrum_of(ac: AlphaComplex, molecule: bool) -> np.ndarray:
    """(s,) float64 the values the slider stands on: the complex's critical values, and for
    a molecule alpha² = 0 too (where it opens and its measures are; the shape there is the
    one at the critical value below). Read-only."""
    spectrum = ac.spectrum()
    if not molecule or np.any(spectrum == 0.0):
        return spectrum
    spectrum = np.insert(spectrum, np.searchsorted(spectrum, 0.0), 0.0)
    spectrum.flags.writeable = False
    return spectrum


def window_backend() -> str | None:
    """The triangulation backend $ALPHASCOOP_BACKEND forces on the window's builds ("qhull"
    or "gmsh", as the command line's --backend), None when it is unset, empty or "auto";
    InputError naming the variable when it asks for something else or for a gmsh that is
    not installed."""
    given = os.environ.get(BACKEND_VARIABLE, "")
    value = given.strip().lower()
    if value in ("", "auto"):
        return None
    if value not in BACKENDS:
        raise InputError(f"{BACKEND_VARIABLE}={given!r}: must be {', '.join(BACKENDS)}, auto "
                         "or empty (automatic)")
    try:
        return check_backend(value)
    except InputError as error:
        raise InputError(f"{BACKEND_VARIABLE}={given!r}: {error}") from None


def quick_alpha(ac: AlphaComplex) -> float:
    """Where a view opens before the topology is known: the opening rule alone (the smallest
    alpha whose triangles put 99 % of the points in pieces, at most 5 point spacings:
    core.topology.opening), which needs only the table. ac.default_alpha() is the same value
    unless CGAL's optimal alpha, known with the topology, is smaller."""
    return float(opening_alpha_of(ac.index, ac.points))


def with_topology(dataset: Dataset, check: Callable[[], None] | None = None) -> Dataset:
    """The dataset with its topology: signatures (saved to its cache entry if they were not
    there), optimal and opening alpha, persistence. `check()` is called between the stages
    and may raise core.errors.Cancelled to stop."""
    if dataset.has_topology:
        return dataset
    started = time.perf_counter()
    ac = dataset.ac
    came = ac.has_signatures
    check = check or (lambda: None)
    check()
    obtained = add_topology(Obtained(ac, dataset.source, dataset.entry, dataset.damage))
    for stage in (ac.default_alpha, ac.persistence):  # default_alpha: the optimal one too
        check()
        stage()
    return _completed(dataset, ac, ac.optimal_alpha(), ac.default_alpha(), ac.persistence(),
                      entry=obtained.entry,
                      seconds=0.0 if came else time.perf_counter() - started)


def with_measures(dataset: Dataset, check: Callable[[], None] | None = None) -> Dataset:
    """A molecule's dataset with its measures (core.molecule.analysis.measure_molecule at
    alpha² = 0: exact area and volume, per-atom areas, cavities, pockets); `check()` is called
    between their stages and may raise core.errors.Cancelled to stop."""
    if not dataset.needs_measures:
        return dataset
    return replace(dataset, molecule=measure_molecule(dataset.ac, dataset.probe, check=check))


def with_parts(dataset: Dataset, parts: TopologyParts, seconds: float) -> Dataset:
    """The dataset completed with the topology a topology process computed for its table
    (app.topology_process): its complex is the same table with that topology attached."""
    ac = attach(dataset.ac, parts)
    return _completed(dataset, ac, parts.optimal_alpha, parts.default_alpha, parts.persistence,
                      entry=dataset.entry if parts.entry_saved else None, seconds=seconds)


def _completed(dataset: Dataset, ac: AlphaComplex, optimal: float, default: float,
               persistence: Persistence, *, entry: Path | None, seconds: float) -> Dataset:
    """The dataset with ac (its table with the topology), the optimal and opening alphas (a
    molecule keeps its own, alpha² = 0), persistence and suggestions: the tail with_topology
    and with_parts share."""
    default = dataset.default_alpha if dataset.is_molecule else default
    ac.signatures().counts_at(default)  # sorts its class thresholds here, not in the info dock
    return replace(dataset, ac=ac, signatures=ac.signatures(), optimal_alpha=float(optimal),
                   default_alpha=float(default), persistence=persistence,
                   opening_pieces=pieces_at(ac.index, ac.points, default),
                   suggestions=ac.suggest_alphas(N_SUGGESTIONS), entry=entry,
                   topology_seconds=seconds, topology_child=None)


def suggestions_of(dataset: Dataset) -> tuple[AlphaRange, ...]:
    """The dataset's suggested alphas (those found with its topology, else computed now)."""
    if dataset.suggestions is not None:
        return dataset.suggestions
    return dataset.ac.suggest_alphas(N_SUGGESTIONS)


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


def _atom_labels(ac: AlphaComplex, pointset) -> np.ndarray | None:
    """(m,) str 'chain:residue:number:atom' of ac's atoms, read again from the molecule file
    (the point set keeps numbers only); None when the file is not a molecule file."""
    from core.io.molecule import atom_labels, molecule_extension, read_molecule

    path = Path(pointset.report.path)
    if molecule_extension(path) is None:
        return None
    return np.array([f"{a['chain']}:{a['residue']}:{a['number']}:{a['atom']}"
                     for a in atom_labels(read_molecule(path), ac.points)])


def _molecule(ac: AlphaComplex, pointset) -> tuple[float | None, np.ndarray | None]:
    """For a molecule (atoms with atomic numbers, weighted): its probe radius in Å and the
    atomic numbers of ac's points; (None, None) otherwise."""
    numbers = pointset.attributes.get("atomic_number")
    if numbers is None or ac.weights is None or ac.dim != 3:
        return None, None
    rows = np.zeros(len(ac.points), dtype=np.int16)
    shown = ac.input_index >= 0
    rows[ac.input_index[shown]] = np.asarray(numbers)[shown]
    probe = float(np.sqrt(pointset.attributes["weights"][0])
                  - pointset.attributes["vdw_radius"][0])
    return round(probe, 6), rows

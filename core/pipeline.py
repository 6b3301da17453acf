"""The build pipeline: points in, an immutable `BuiltComplex` out (AlphaComplex wraps it).

Stages, in order: check the input (points, weights, mode) -> prepare the coordinates (merge
duplicates, project planar 3D, order spatially) -> triangulate (the backend stage) -> build
the interval table -> scale the table for a mode -> scale everything back to the input units.
What the stages did is recorded in a frozen `BuildInfo`, saved with the table.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from core.backends import BACKENDS, Choice, check_backend, delaunay, regular
from core.build.certify import Certified, certified_triangulation, point_ties
from core.build.delaunay import Triangulation, sort_rows
from core.build.levels import Table
from core.build.points import (
    Frame,
    as_points,
    canonical_order,
    check_spread,
    merge_duplicates,
    spatial_order,
)
from core.build.table import build_table
from core.build.weights import as_weights, hide_light_duplicates
from core.errors import InputError
from core.modes.alpha_modes import (
    Mode,
    check_normals,
    directionless,
    local_geometry_beside,
    make_mode,
    scaled_table,
    unit_rows,
)
from core.progress import Progress, Stepper

_SAID_WHEN_SET = ("estimated_normals", "density_neighbours")  # BuildInfo fields, 0 = unsaid
MAX_WEIGHT_RATIO = 1e100  #: |weight| / extent² beyond which power computations overflow

__all__ = ["BACKENDS", "BuildInfo", "BuiltComplex", "build_complex", "check_backend"]


@dataclass(frozen=True)
class BuildInfo:
    """How a table was built; saved with it as `build_<field>` scalars (str, int or float
    fields only, so a stage adding a field needs nothing else to have it saved and loaded).

    `backend`: the triangulation backend that made the cells ("qhull" for scipy/Qhull,
    "gmsh", "geogram" for weighted points); `backend_note`: why the automatic choice did not
    use gmsh ("" when it did, or was not asked to: too few points, gmsh not installed,
    weights) or geogram (it failed), and why a large build was not split in two halves
    (core.backends.split; "" when it was, or was small).
    `exact_predicates`: sign decisions (certification and table) that the floating-point
    filter could not settle and exact arithmetic decided; `flips`: cells the certification
    changed (flips and hull repairs, core/build/certify.py); `uncertified`: facets it could not
    certify (left as the backend made them; 0 = a certified Delaunay triangulation, -1 = not
    certified: weighted builds, tables saved before certification); `estimated_normals`:
    points of an anisotropic build with given normals whose normal was zero (no direction),
    so was estimated from the neighbours as the "estimate" mode does; `density_neighbours`:
    the k a density build used when the points were too few for the k asked (every other
    point). These last two are 0 when nothing happened, and then not said by `describe`.
    """

    backend: str = "qhull"
    backend_note: str = ""
    exact_predicates: int = 0
    flips: int = 0
    uncertified: int = -1
    estimated_normals: int = 0
    density_neighbours: int = 0

    def to_dict(self) -> dict[str, str | int | float]:
        """The fields by name (JSON-ready: for `alphascoop info --json`)."""
        return dataclasses.asdict(self)

    def describe(self) -> str:
        """One line for people: "backend qhull" (every field that is not empty, name then
        value); the sentinel uncertified -1 is said in words, "not certified (weighted points
        or an older table)", never printed as a number; a weighted geogram build says its
        predicates are exact (they are) rather than "not certified" with the zero counts of a
        certification that did not run."""
        fields = {name: value for name, value in self.to_dict().items()
                  if value != "" and (value != 0 or name not in _SAID_WHEN_SET)}
        if self.backend == "geogram" and self.uncertified < 0:
            for name in ("exact_predicates", "flips", "uncertified"):
                del fields[name]
            fields["triangulated"] = "with its exact predicates (no certification pass)"
        elif fields.get("uncertified", 0) < 0:
            del fields["uncertified"]
            fields["not_certified"] = "(weighted points or an older table)"
        return ", ".join(f"{name.replace('_', ' ')} {value}" for name, value in fields.items())

    def to_arrays(self) -> dict[str, np.ndarray]:
        """The fields as 0-d arrays named `build_<field>` (for core/storage/tables.py)."""
        return {f"build_{f.name}": np.array(getattr(self, f.name))
                for f in dataclasses.fields(self)}

    @classmethod
    def from_arrays(cls, arrays: dict[str, np.ndarray]) -> BuildInfo:
        """The info saved in `arrays`; fields a file lacks (older tables) take their
        defaults. ValueError/TypeError for a value of the wrong kind."""
        convert = {"str": str, "int": int, "float": float}
        values = {}
        for f in dataclasses.fields(cls):
            value = arrays.get(f"build_{f.name}")
            if value is None:
                continue
            if np.shape(value) != ():
                raise ValueError(f"build_{f.name} is not a scalar")
            values[f.name] = convert[str(f.type)](value.item() if f.type != "str" else value)
        return cls(**values)


@dataclass(frozen=True, eq=False)
class BuiltComplex:
    """What the pipeline returns: everything an AlphaComplex holds, in the input's units.

    `points` (m, dim) float64 the complex's vertices (spatially ordered, planar 3D in plane
    coordinates); `input_index` (n,) int64 the vertex row of every input point (-1 = hidden
    weighted point); `table` the interval table; `frame` the plane of planar 3D input (None
    otherwise); `ambient_dim` the input's dimension; `mode` the alpha mode; `weights` (m,)
    squared radii or None; `info` how it was built.
    """

    points: np.ndarray
    input_index: np.ndarray
    table: Table
    frame: Frame | None
    ambient_dim: int
    mode: Mode
    weights: np.ndarray | None
    info: BuildInfo


@dataclass(frozen=True, eq=False)
class _Input:
    """The checked input: (n, d) points, (n,) weights or None, the mode, (n, d) normals."""

    points: np.ndarray
    weights: np.ndarray | None
    mode: Mode
    normals: np.ndarray | None


@dataclass(frozen=True, eq=False)
class _Prepared:
    """Distinct points in complex coordinates, spatially ordered, with their bookkeeping."""

    coords: np.ndarray  # (m, dim) float64
    weights: np.ndarray | None  # (m,) or None
    input_index: np.ndarray  # (n,) int64, -1 = hidden duplicate
    frame: Frame | None


def power_of_two_scale(centred: np.ndarray) -> float:
    """A power of two near the data's extent: dividing by it is exact and avoids overflow."""
    extent = float(np.abs(centred).max())
    return 2.0 ** math.floor(math.log2(extent)) if extent > 0 else 1.0


def _checked_input(points: object, weights: object, density: int | None, combine: str,
                   anisotropy: float, normals: object) -> _Input:
    """Stage 1: points, weights and mode checked together (InputError otherwise)."""
    raw = as_points(points)
    w = as_weights(weights, len(raw))
    if w is not None:
        check_weight_range(w, raw)
    mode = make_mode(density, combine, anisotropy, normals is not None)
    if w is not None and mode.active:
        raise InputError("weights cannot be combined with the density or anisotropy "
                         "modes: build a weighted or a mode complex")
    if mode.anisotropy > 0.0 and normals is not None:
        normals = check_normals(normals, len(raw), raw.shape[1])
    return _Input(raw, w, mode, normals)  # type: ignore[arg-type]


def check_weight_range(weights: np.ndarray, points: np.ndarray) -> None:
    """InputError for weights out of proportion to the points: beyond MAX_WEIGHT_RATIO
    times the squared extent, the powers of the orthogonal spheres (squares of weights over
    squared distances) overflow float64, and the table would hold infinities, not values."""
    extent = float(np.ptp(points, axis=0).max()) if len(points) else 0.0
    largest = float(np.abs(weights).max())
    with np.errstate(over="ignore"):
        bound = MAX_WEIGHT_RATIO * extent * extent
    if extent > 0 and largest > bound:
        raise InputError(f"weights up to {largest:.3g} (squared radii) are out of proportion to "
                         f"points spread over {extent:.3g}: beyond {MAX_WEIGHT_RATIO:.0e} times "
                         "the squared extent their powers overflow float64; rescale the "
                         "weights or the points")


def _prepared(given: _Input) -> _Prepared:
    """Stage 2: duplicates merged (hidden weighted ones marked -1), planar 3D projected to
    its plane, rows in spatial order."""
    unique, input_index = merge_duplicates(given.points)
    w = given.weights
    if w is not None:
        w, input_index = hide_light_duplicates(w, input_index, len(unique))
    frame = check_spread(unique)
    coords = unique if frame is None else (unique - frame.origin) @ frame.basis.T
    order = spatial_order(coords)
    coords = coords[order]
    w = None if w is None else w[order]
    rank = np.append(np.empty(len(order), dtype=np.int64), -1)
    rank[order] = np.arange(len(order))
    input_index = rank[input_index]  # -1 (hidden duplicates) stays -1 via rank[-1]
    return _Prepared(coords, w, input_index, frame)


def _triangulated(prep: _Prepared, backend: str | None) -> tuple[Triangulation, Choice]:
    """Stage 3 (backend): the Delaunay (regular, when weighted) cells of the points, centred
    and scaled exactly by a power of two for the triangulator, and which backend made them
    (core.backends; regular triangulations are geogram's, or Qhull's)."""
    coords, w = prep.coords, prep.weights
    offset = 0.5 * (coords.min(axis=0) + coords.max(axis=0))
    lift_scale = power_of_two_scale(coords - offset)
    if w is None or bool(np.all(w == w[0])):  # equal weights: the Delaunay cells
        return delaunay((coords - offset) / lift_scale, backend)
    if backend == "gmsh":
        raise InputError("the gmsh backend makes Delaunay triangulations only: weighted "
                         "points need backend='qhull' or None")
    return regular((coords - offset) / lift_scale, w / lift_scale**2, backend)


def _certified(prep: _Prepared, tri: Triangulation) -> Certified:
    """Stage 3b: the backend's Delaunay cells certified with exact predicates on the points
    themselves (scaled by a power of two, exactly), repaired by flips (core/build/certify.py)."""
    scale = power_of_two_scale(prep.coords)
    ties = point_ties(prep.coords)  # of the points themselves: any subset breaks ties alike
    return dataclasses.replace(certified_triangulation(prep.coords / scale, tri, ties),
                               scale=scale)


def _compacted(prep: _Prepared, tri: Triangulation) -> _Prepared:
    """The points the triangulation kept as vertices (others merged or hidden)."""
    if len(tri.kept) == len(prep.coords):
        return prep
    input_index = np.where(prep.input_index >= 0,
                           tri.vertex_of_point[np.maximum(prep.input_index, 0)], -1)
    return _Prepared(prep.coords[tri.kept], None if prep.weights is None
                     else prep.weights[tri.kept], input_index, prep.frame)


def _point_normals(normals: np.ndarray, input_index: np.ndarray, m: int,
                   frame: Frame | None) -> np.ndarray:
    """(m, dim) unit normals of the complex's points from the (n, ambient) input normals
    (planar 3D: projected onto the plane; a duplicate point takes one of its rows)."""
    out = np.zeros((m, normals.shape[1]))
    out[input_index] = normals
    return unit_rows(out if frame is None else out @ frame.basis.T)


def _renumbered(prep: _Prepared, tri: Triangulation) -> tuple[_Prepared, Triangulation, bool]:
    """Stage 3c: the points renumbered in canonical_order (a function of each point alone),
    cells and neighbours alongside, and whether anything moved. A simplex's vertices then
    come in the same order in any subset of the points (a tile of core.tiled) as in the
    whole set, so the table's radii, computed from the vertices in that order, round alike.
    The certified cell spheres (computed in the old order) are not reused when it moved."""
    order = canonical_order(prep.coords)
    m = len(order)
    if np.array_equal(order, np.arange(m)):
        return prep, tri, False
    rank = np.empty(m + 1, dtype=np.int64)
    rank[order] = np.arange(m)
    rank[m] = -1
    cells = np.ascontiguousarray(rank[tri.cells], dtype=np.int32)
    neighbors = np.array(tri.neighbors, dtype=np.int32, copy=True)
    sort_rows(cells, neighbors)
    identity = np.arange(m, dtype=np.int64)
    moved = _Prepared(prep.coords[order], None if prep.weights is None else prep.weights[order],
                      rank[prep.input_index], prep.frame)
    return moved, Triangulation(cells, neighbors, identity, identity.copy()), True


def _table(prep: _Prepared, tri: Triangulation, given: _Input, step: Stepper,
           exact: bool = True, certified: Certified | None = None) -> Table:
    """Stages 4-6: the interval table on the points scaled exactly by a power of two (its
    arithmetic is relative to a vertex, so no rounding shift), the mode's scaling, and the
    values and measures scaled back to the input units. The certification's cell spheres
    are reused when they were computed on the same points (same scale)."""
    coords, w, mode = prep.coords, prep.weights, given.mode
    scale = power_of_two_scale(coords)
    local = None
    if mode.active:  # the points' neighbourhoods, estimated beside the classic table
        normals = (_point_normals(given.normals, prep.input_index, len(coords), prep.frame)
                   if mode.normals == "given" else None)
        local = local_geometry_beside(coords, mode, normals)
    spheres = None
    if certified is not None and certified.scale == scale:
        spheres = certified.spheres
    step(0.6, "interval table")
    share = 0.3 if mode.active else 0.4
    table = build_table(coords / scale, tri.cells, tri.neighbors, step.part(0.6, share),
                        exact=exact, spheres=spheres,
                        weights=None if w is None else w / scale**2,
                        sort=not mode.active, radii=not mode.active or mode.classic_radii,
                        mirror=tri.mirror)
    for level in table.levels:
        for arr in (level.enter, level.regular, level.interior):
            arr *= scale
    if local is not None:
        step(0.9, "neighbours")  # the wait for what is left of them when the table is done
        table = scaled_table(table, coords, mode, local(), step.part(0.9, 0.1))
    with np.errstate(over="ignore"):
        measure_scale = np.float64(scale) ** coords.shape[1]
    if not np.isfinite(measure_scale):
        raise InputError(f"coordinates up to {scale:.3g} are too large: their "
                         f"{'areas' if coords.shape[1] == 2 else 'volumes'} overflow "
                         "float64; rescale the points (e.g. to metres or kilometres)")
    table.cell_measure *= measure_scale
    return table


def build_complex(points: object, progress: Progress | None = None, *,
                  weights: object = None, density: int | None = None, combine: str = "mean",
                  anisotropy: float = 0.0, normals: object = None,
                  backend: str | None = None, certify: bool = True) -> BuiltComplex:
    """Run the pipeline on (n, 2) or (n, 3) points (arguments as AlphaComplex.from_points).

    `progress(fraction, stage)` is called between stages; raising core.errors.Cancelled
    from it stops the build. InputError for input that makes no complex. `certify=False`
    skips the exact certification and sign decisions (the floating-point build, for the
    benchmark that measures what they cost).
    """
    step = Stepper(progress)
    step(0.0, "checking points")
    chosen = check_backend(backend)
    given = _checked_input(points, weights, density, combine, anisotropy, normals)
    prep = _prepared(given)
    step(0.02, "Delaunay triangulation" if prep.weights is None else "regular triangulation")
    tri, choice = _triangulated(prep, chosen)
    exact = certify and (prep.weights is None or bool(np.all(prep.weights == prep.weights[0])))
    certified = None
    if exact:
        step(0.55, "certifying the triangulation")
        certified = _certified(prep, tri)
        tri = certified.triangulation
    prep, tri, moved = _renumbered(_compacted(prep, tri), tri)
    table = _table(prep, tri, given, step, exact, None if moved else certified)
    info = BuildInfo(choice.backend, choice.note) if certified is None else BuildInfo(
        choice.backend, choice.note, certified.exact_predicates + table.exact_predicates,
        certified.flips, certified.uncertified)
    if given.mode.density is not None and given.mode.density > len(prep.coords) - 1:
        info = dataclasses.replace(info, density_neighbours=len(prep.coords) - 1)
    if given.mode.anisotropy > 0.0 and given.normals is not None:
        info = dataclasses.replace(info, estimated_normals=int(directionless(_point_normals(
            given.normals, prep.input_index, len(prep.coords), prep.frame)).sum()))
    return BuiltComplex(np.ascontiguousarray(prep.coords), prep.input_index, table, prep.frame,
                        given.points.shape[1], given.mode, prep.weights, info)

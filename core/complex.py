"""AlphaComplex: the Delaunay triangulation and interval table, built once, queried often."""

from __future__ import annotations

import math
import os
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

from . import storage
from .delaunay import triangulate
from .errors import InputError
from .modes import Mode, check_normals, make_mode, scaled_table, unit_rows
from .points import Frame, as_points, check_spread, merge_duplicates, spatial_order
from .shape import AlphaShape, readonly
from .table import Level, Progress, Table, build_table

if TYPE_CHECKING:
    from .cursor import ShapeCursor

EXTERIOR, SINGULAR, REGULAR, INTERIOR = 0, 1, 2, 3


def _power_of_two_scale(centred: np.ndarray) -> float:
    """A power of two near the data's extent: dividing by it is exact and avoids overflow."""
    extent = float(np.abs(centred).max())
    return 2.0 ** math.floor(math.log2(extent)) if extent > 0 else 1.0


def _radius(alpha: object) -> float:
    """`alpha` as a float radius >= 0 (inf allowed); an InputError (a ValueError) otherwise."""
    try:
        value = float(alpha)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise InputError(f"alpha must be a number (a radius), not {alpha!r}") from None
    if not value >= 0:
        raise InputError(f"alpha is a radius and must be >= 0, not {alpha!r}")
    return value


def _point_normals(normals: np.ndarray, input_index: np.ndarray, m: int,
                   frame: Frame | None) -> np.ndarray:
    """(m, dim) unit normals of the complex's points from the (n, ambient) input normals
    (planar 3D: projected onto the plane; a duplicate point takes one of its rows)."""
    out = np.zeros((m, normals.shape[1]))
    out[input_index] = normals
    return unit_rows(out if frame is None else out @ frame.basis.T)


class AlphaComplex:
    """Alpha complex of a 2D or 3D point set over all alphas (radii) at once.

    Build with `from_points` (or `load`); then every alpha is a query on the interval table.
    Arrays handed out are read-only.
    """

    def __init__(self, points: np.ndarray, input_index: np.ndarray, table: Table,
                 frame: Frame | None = None, ambient_dim: int | None = None,
                 mode: Mode | None = None) -> None:
        self._table = table
        self.mode = mode or Mode()
        self.points = readonly(points)
        self.input_index = readonly(input_index)
        self.frame = frame
        self.dim = points.shape[1]
        self.ambient_dim = ambient_dim or (3 if frame is not None else self.dim)
        for level in table.levels:
            for name in ("simplices", "enter", "regular", "interior", "face_ids"):
                if getattr(level, name) is not None:
                    readonly(getattr(level, name))
        for arr in (table.facet_cells, table.facet_flip, table.cell_measure,
                    table.facet_interior_order):
            readonly(arr)

    @classmethod
    def from_points(cls, points: object, progress: Progress | None = None, *,
                    density: int | None = None, combine: str = "mean",
                    anisotropy: float = 0.0, normals: object = None) -> AlphaComplex:
        """Build from (n, 2) or (n, 3) points; duplicates merged, planar 3D built in 2D.

        `progress(fraction, stage)` is called between stages; raising core.errors.Cancelled
        from it stops the build. Raises InputError for points that make no complex.
        Modes (core/modes.py; alpha is then in the mode's units): `density=k` divides radii
        by the local spacing (distance to the k-th neighbour, `combine`d over a simplex's
        vertices by "mean" or "max"); `anisotropy=tau` in [0, 1) compresses the alpha ball
        along the surface normal, taken from `normals` ((n, d) like the points) or estimated.
        """
        def step(fraction: float, stage: str) -> None:
            if progress is not None:
                progress(fraction, stage)

        step(0.0, "checking points")
        raw = as_points(points)
        mode = make_mode(density, combine, anisotropy, normals is not None)
        if mode.anisotropy > 0.0 and normals is not None:
            normals = check_normals(normals, len(raw), raw.shape[1])
        unique, input_index = merge_duplicates(raw)
        frame = check_spread(unique)
        coords = unique if frame is None else (unique - frame.origin) @ frame.basis.T
        order = spatial_order(coords)
        coords = coords[order]
        rank = np.empty(len(order), dtype=np.int64)
        rank[order] = np.arange(len(order))
        input_index = rank[input_index]
        offset = 0.5 * (coords.min(axis=0) + coords.max(axis=0))
        step(0.02, "Delaunay triangulation")
        tri = triangulate((coords - offset) / _power_of_two_scale(coords - offset))
        if len(tri.kept) < len(coords):
            coords = coords[tri.kept]
            input_index = tri.vertex_of_point[input_index]
        # The table works on the points themselves, scaled exactly by a power of two: its
        # arithmetic is relative to a vertex, so it needs no (rounding) shift to the origin.
        scale = _power_of_two_scale(coords)
        local = coords / scale
        step(0.6, "interval table")
        share = 0.3 if mode.active else 0.4
        table = build_table(local, tri.cells, tri.neighbors,
                            None if progress is None else lambda f, s: step(0.6 + share * f, s))
        for level in table.levels:
            for arr in (level.enter, level.regular, level.interior):
                arr *= scale
        if mode.active:
            table = scaled_table(table, coords, mode,
                                 _point_normals(normals, input_index, len(coords), frame)
                                 if mode.normals == "given" else None,
                                 None if progress is None else lambda f, s: step(0.9 + 0.1 * f, s))
        with np.errstate(over="ignore"):
            measure_scale = np.float64(scale) ** coords.shape[1]
        if not np.isfinite(measure_scale):
            raise InputError(f"coordinates up to {scale:.3g} are too large: their "
                             f"{'areas' if coords.shape[1] == 2 else 'volumes'} overflow "
                             "float64; rescale the points (e.g. to metres or kilometres)")
        table.cell_measure *= measure_scale
        return cls(np.ascontiguousarray(coords), input_index, table, frame, raw.shape[1], mode)

    # --- the table -------------------------------------------------------------------------
    def _level(self, k: int) -> Level:
        if not 0 <= k <= self.dim:
            raise ValueError(f"k must be between 0 and {self.dim}, not {k}")
        return self._table.levels[k]

    def simplices(self, k: int) -> np.ndarray:
        """(n_k, k+1) int32 k-simplices as rows of `points`, rows ascending, sorted by enter."""
        return self._level(k).simplices

    def intervals(self, k: int) -> np.ndarray:
        """(n_k, 3) float64 columns enter <= regular <= interior (radii; inf = never)."""
        cache = self.__dict__.setdefault("_intervals", {})
        if k not in cache:
            level = self._level(k)
            cache[k] = readonly(np.stack((level.enter, level.regular, level.interior), axis=1))
        return cache[k]

    def face_ids(self, k: int) -> np.ndarray:
        """(n_k, k+1) int32: row in simplices(k-1) of the face opposite each vertex (k >= 1)."""
        if k < 1:
            raise ValueError("vertices have no faces: k must be >= 1")
        return self._level(k).face_ids

    def facet_cells(self) -> np.ndarray:
        """(n_{dim-1}, 2) int32: the cells on both sides of each facet, -1 = outside."""
        return self._table.facet_cells

    def cell_measures(self) -> np.ndarray:
        """(n_dim,) float64 volume (3D) or area (2D) of every cell."""
        return self._table.cell_measure

    @cached_property
    def _facet_cell0(self) -> np.ndarray:
        """Contiguous first column of facet_cells (the shape's orientation lookup)."""
        return np.ascontiguousarray(self._table.facet_cells[:, 0])

    @cached_property
    def _oriented_facets(self) -> np.ndarray:
        """(2 n_facets, dim) int32: row 2i is facet i facing out of its cell 0, row 2i+1 out
        of its cell 1, so the shape orients its boundary with a single gather."""
        facets = self._table.levels[self.dim - 1].simplices
        flip = self._table.facet_flip
        out = np.empty((2 * len(facets), self.dim), dtype=np.int32)
        for side, reverse in ((0, flip), (1, ~flip)):
            rows = out[side::2]
            rows[:] = facets
            rows[reverse, -2:] = facets[reverse][:, [-1, -2]]
        return readonly(out)

    @cached_property
    def _facets_by_interior(self) -> tuple[np.ndarray, np.ndarray]:
        """Facet interior and enter values in ascending interior order (contiguous, for the
        shape's scans of the facets not yet interior)."""
        facets = self._table.levels[self.dim - 1]
        order = self._table.facet_interior_order
        return np.take(facets.interior, order), np.take(facets.enter, order)

    @cached_property
    def _cumulative_measure(self) -> np.ndarray:
        return np.cumsum(self._table.cell_measure)

    @cached_property
    def _spectrum(self) -> np.ndarray:
        values = np.concatenate([[0.0]] + [lv.enter for lv in self._table.levels[1:]])
        values.sort()
        keep = np.empty(len(values), dtype=bool)
        keep[0] = True
        np.not_equal(values[1:], values[:-1], out=keep[1:])
        return readonly(values[keep])

    def spectrum(self) -> np.ndarray:
        """(s,) float64 sorted distinct alphas at which the complex changes; 0 comes first."""
        return self._spectrum

    # --- queries ---------------------------------------------------------------------------
    def classify(self, alpha: float, k: int) -> np.ndarray:
        """(n_k,) int8 class of every k-simplex: 0 exterior, 1 singular, 2 regular, 3 interior."""
        alpha = _radius(alpha)
        level = self._level(k)
        out = (level.enter <= alpha).view(np.int8).copy()
        out += level.regular <= alpha
        out += level.interior <= alpha
        return readonly(out)

    def shape(self, alpha: float) -> AlphaShape:
        """The alpha shape at `alpha` (a radius); arrays are computed when first used."""
        return AlphaShape(self, _radius(alpha))

    def cursor(self) -> ShapeCursor:
        """A ShapeCursor: shapes at one alpha after another, each step costing what changed
        (the explorer's slider); building it sorts the table once more."""
        from .cursor import ShapeCursor

        return ShapeCursor(self)

    def to_ambient(self, coords: np.ndarray) -> np.ndarray:
        """Map (k, dim) complex coordinates to the input space ((k, ambient_dim))."""
        coords = np.asarray(coords, dtype=np.float64)
        if self.frame is None:
            return coords
        return self.frame.origin + coords @ self.frame.basis

    def counts(self) -> tuple[int, ...]:
        """Number of simplices per dimension, vertices first."""
        return tuple(len(level.enter) for level in self._table.levels)

    # --- files -----------------------------------------------------------------------------
    def save(self, path: str | os.PathLike) -> None:
        """Write the table to an .npz file atomically (see core/storage.py for the layout)."""
        storage.save(self, path)

    @classmethod
    def load(cls, path: str | os.PathLike) -> AlphaComplex:
        """Read a table written by `save`; FileFormatError if it is not one."""
        return storage.load(cls, path)

    def __repr__(self) -> str:
        return f"AlphaComplex(dim={self.dim}, points={len(self.points)}, simplices={self.counts()})"

    # --- topology (core.topology / core.signatures) ---
    @cached_property
    def _topology(self):
        from .topology import build_topology

        return build_topology(self)

    @cached_property
    def _signatures(self):
        from .signatures import compute_signatures

        return compute_signatures(self, self._topology)

    @cached_property
    def _locator(self):
        from .locate import Locator

        return Locator(self.points, self.simplices(self.dim), self.face_ids(self.dim),
                       self.facet_cells())

    def _adopt(self, topology, signatures) -> None:
        """Take topology and signatures saved with the table instead of computing them."""
        self.__dict__.update(_topology=topology, _signatures=signatures,
                             _spectrum=signatures.alphas)

    def betti(self, alpha: float) -> tuple[int, ...]:
        """Betti numbers at alpha: (components, holes) in 2D, (components, tunnels, voids) in 3D."""
        return self._topology.betti(alpha)

    def signatures(self):
        """Betti numbers, solid components, measures and class counts over the whole spectrum."""
        return self._signatures

    @cached_property
    def _persistence(self):
        from .persistence import compute_persistence

        return compute_persistence(self, self._topology)

    def persistence(self):
        """Persistence pairs (birth, death alphas) of components and of holes (2D) / voids (3D)."""
        return self._persistence

    @cached_property
    def _cover_alpha(self) -> float:
        from .suggest import cover_alpha

        return cover_alpha(self.simplices(self.dim), self.intervals(self.dim)[:, 0],
                           len(self.points))

    def optimal_alpha(self, n_components: int = 1) -> float:
        """Smallest alpha with every point in a cell and <= n_components solid parts (CGAL)."""
        from .suggest import optimal_alpha

        return optimal_alpha(self._signatures, self._cover_alpha, n_components)

    def suggest_alphas(self, k: int = 5) -> tuple:
        """The k alpha ranges where the Betti numbers hold longest on a log scale, best first."""
        from .suggest import suggest_alphas

        return suggest_alphas(self._signatures, k)

    def contains(self, query_points: object, alpha: float) -> np.ndarray:
        """(k,) bool: each query point lies in a cell of the complex at alpha.

        Queries are (k, ambient_dim) input-space points (planar 3D input: projected onto the
        plane) or (k, dim) complex coordinates.
        """
        from .locate import contains
        from .locate import query_points as checked

        queries = checked(query_points, self.dim, self.ambient_dim, self.to_ambient)
        return contains(self._locator, queries, alpha, self.intervals(self.dim)[:, 0])

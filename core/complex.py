"""AlphaComplex: the Delaunay triangulation and interval table, built once, queried often."""

from __future__ import annotations

import os
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

from . import storage
from .build import BuildInfo, build_complex
from .errors import InputError
from .modes import Mode
from .points import Frame
from .power import signed_sqrt, signed_square
from .progress import Progress
from .shape import AlphaShape, readonly, threshold
from .table import Level, Table

if TYPE_CHECKING:
    from .cursor import ShapeCursor

EXTERIOR, SINGULAR, REGULAR, INTERIOR = 0, 1, 2, 3


def _radius(alpha: object) -> float:
    """`alpha` as a float radius >= 0 (inf allowed); an InputError (a ValueError) otherwise."""
    try:
        value = float(alpha)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise InputError(f"alpha must be a number (a radius), not {alpha!r}") from None
    if not value >= 0:
        raise InputError(f"alpha is a radius and must be >= 0, not {alpha!r}; pass a "
                         "squared value (which may be negative) as alpha2=")
    return value


def table_value(alpha: object = None, alpha2: object = None) -> float:
    """The table's value for a query given as exactly one of `alpha` (a radius >= 0) or
    `alpha2` (its square; any real, negative below zero radius): sign(a2) * sqrt(|a2|)."""
    if (alpha is None) == (alpha2 is None):
        raise InputError("give exactly one of alpha (a radius) and alpha2 (a squared radius), "
                         f"not {'both' if alpha is not None else 'neither'}")
    if alpha is not None:
        return _radius(alpha)
    try:
        value = float(alpha2)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise InputError(f"alpha2 must be a number (a squared radius), not {alpha2!r}") from None
    if value != value:
        raise InputError("alpha2 must be a number (a squared radius), not NaN")
    return float(signed_sqrt(np.float64(value)))


def at_value(value: float) -> dict[str, float]:
    """Keyword arguments that make any query select the table value `value` (a spectrum
    entry, say): alpha=value where it is >= 0 (exact for every table), else alpha2=its
    signed square (weighted tables below zero radius)."""
    value = float(value)
    return {"alpha": value} if value >= 0 else {"alpha2": value * abs(value)}


class AlphaComplex:
    """Alpha complex of a 2D or 3D point set over all alphas (radii) at once.

    Build with `from_points` (or `load`); then every alpha is a query on the interval table.
    Arrays handed out are read-only.

    Weighted complexes (`weights` given: squared radii, power distance |x - p|² - w) have
    values that may be negative. Their table holds signed radii sign(a2) * sqrt(|a2|) of the
    squared values a2 (equal to the radius where a2 >= 0): `intervals`, `spectrum`,
    signatures, persistence and `optimal_alpha` speak that unit; `intervals_sq`,
    `spectrum_sq` and `optimal_alpha2` give squares. Every query takes either `alpha` (a
    radius >= 0) or the keyword `alpha2` (a squared value, may be negative), never both.
    """

    def __init__(self, points: np.ndarray, input_index: np.ndarray, table: Table,
                 frame: Frame | None = None, ambient_dim: int | None = None,
                 mode: Mode | None = None, weights: np.ndarray | None = None, *,
                 build_info: BuildInfo | None = None) -> None:
        self._table = table
        #: How the table was built (core/build.py): the triangulation backend, ...
        self.build_info = build_info or BuildInfo()
        self.mode = mode or Mode()
        self.points = readonly(points)
        self.input_index = readonly(input_index)
        #: (m,) float64 squared radii aligned with `points`, or None for a classic complex.
        self.weights = None if weights is None else readonly(weights)
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
                    weights: object = None, density: int | None = None,
                    combine: str = "mean", anisotropy: float = 0.0,
                    normals: object = None, backend: str | None = None) -> AlphaComplex:
        """Build from (n, 2) or (n, 3) points; duplicates merged, planar 3D built in 2D.

        The pipeline is core/build.py. `progress(fraction, stage)` is called between stages;
        raising core.errors.Cancelled from it stops the build. Raises InputError for points
        that make no complex.
        `weights`: (n,) squared radii for a weighted complex (regular triangulation, power
        distance); None or all zeros build the classic complex. Points whose ball is hidden
        by the others get input_index -1.
        Modes (core/modes.py; alpha is then in the mode's units): `density=k` divides radii
        by the local spacing (distance to the k-th neighbour, `combine`d over a simplex's
        vertices by "mean" or "max"); `anisotropy=tau` in [0, 1) compresses the alpha ball
        along the surface normal, taken from `normals` ((n, d) like the points) or estimated.
        `backend`: the triangulation backend, "qhull", "gmsh" or None (automatic); what was
        used is `build_info.backend`.
        """
        built = build_complex(points, progress, weights=weights, density=density,
                              combine=combine, anisotropy=anisotropy, normals=normals,
                              backend=backend)
        return cls(built.points, built.input_index, built.table, built.frame,
                   built.ambient_dim, built.mode, built.weights, build_info=built.info)

    # --- the table -------------------------------------------------------------------------
    def _level(self, k: int) -> Level:
        if not 0 <= k <= self.dim:
            raise ValueError(f"k must be between 0 and {self.dim}, not {k}")
        return self._table.levels[k]

    def simplices(self, k: int) -> np.ndarray:
        """(n_k, k+1) int32 k-simplices as rows of `points`, rows ascending, sorted by enter."""
        return self._level(k).simplices

    def intervals(self, k: int) -> np.ndarray:
        """(n_k, 3) float64 columns enter <= regular <= interior (radii; inf = never; signed
        radii sign(a2) * sqrt(|a2|) for weighted complexes)."""
        cache = self.__dict__.setdefault("_intervals", {})
        if k not in cache:
            level = self._level(k)
            cache[k] = readonly(np.stack((level.enter, level.regular, level.interior), axis=1))
        return cache[k]

    def intervals_sq(self, k: int) -> np.ndarray:
        """(n_k, 3) float64 enter <= regular <= interior as squared radii (the filtration
        values of CGAL and gudhi; negative for weighted values below zero radius)."""
        return readonly(signed_square(self.intervals(k)))

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
        levels = self._table.levels
        first = [[0.0]] if self.weights is None else [levels[0].enter]
        values = np.concatenate(first + [lv.enter for lv in levels[1:]])
        values.sort()
        keep = np.empty(len(values), dtype=bool)
        keep[0] = True
        np.not_equal(values[1:], values[:-1], out=keep[1:])
        return readonly(values[keep])

    def spectrum(self) -> np.ndarray:
        """(s,) float64 sorted distinct alphas at which the complex changes; 0 comes first
        (weighted: the vertices' values come first, signed radii)."""
        return self._spectrum

    def spectrum_sq(self) -> np.ndarray:
        """(s,) float64 the spectrum as squared values (may be negative when weighted)."""
        return readonly(signed_square(self._spectrum))

    # --- queries ---------------------------------------------------------------------------
    def classify(self, alpha: float | None = None, k: int | None = None, *,
                 alpha2: float | None = None) -> np.ndarray:
        """(n_k,) int8 class of every k-simplex: 0 exterior, 1 singular, 2 regular, 3 interior
        (alpha = inf is the convex hull: hull simplices stay REGULAR, never INTERIOR)."""
        alpha = threshold(table_value(alpha, alpha2))
        if k is None:
            raise InputError("classify needs k, the dimension of the simplices")
        level = self._level(k)
        out = (level.enter <= alpha).view(np.int8).copy()
        out += level.regular <= alpha
        out += level.interior <= alpha
        return readonly(out)

    def shape(self, alpha: float | None = None, *, alpha2: float | None = None) -> AlphaShape:
        """The alpha shape at `alpha` (a radius) or `alpha2` (squared); arrays are computed
        when first used. Its `alpha` attribute is the table value (signed radius)."""
        return AlphaShape(self, table_value(alpha, alpha2),
                          None if alpha2 is None else float(alpha2))

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

    def betti(self, alpha: float | None = None, *, alpha2: float | None = None
              ) -> tuple[int, ...]:
        """Betti numbers at alpha: (components, holes) in 2D, (components, tunnels, voids) in 3D."""
        at = np.array([threshold(table_value(alpha, alpha2))], dtype=np.float64)
        return tuple(int(b) for b in self._topology.betti_many(at)[0])

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
        """Smallest alpha with every point in a cell and <= n_components solid parts (CGAL);
        a signed radius for weighted complexes (see optimal_alpha2)."""
        from .suggest import optimal_alpha

        return optimal_alpha(self._signatures, self._cover_alpha, n_components)

    def default_alpha(self) -> float:
        """The alpha a view opens at: where the shape looks like the object (core.opening).

        The smallest alpha at which the triangles (surface and solid) join at least 99 % of the
        points into one piece, and never more than `optimal_alpha()` (CGAL's rule for solids).
        Computed with the signatures and saved with them.
        """
        return min(self._signatures.opening_alpha, self.optimal_alpha())

    def optimal_alpha2(self, n_components: int = 1) -> float:
        """optimal_alpha as a squared value (may be negative for weighted complexes)."""
        return float(signed_square(np.float64(self.optimal_alpha(n_components))))

    def suggest_alphas(self, k: int = 5) -> tuple:
        """The k alpha ranges where the Betti numbers hold longest on a log scale, best first."""
        from .suggest import suggest_alphas

        return suggest_alphas(self._signatures, k)

    def contains(self, query_points: object, alpha: float | None = None, *,
                 alpha2: float | None = None) -> np.ndarray:
        """(k,) bool: each query point lies in a cell of the complex at alpha.

        Queries are (k, ambient_dim) input-space points (planar 3D input: projected onto the
        plane) or (k, dim) complex coordinates.
        """
        from .locate import contains
        from .locate import query_points as checked

        value = threshold(table_value(alpha, alpha2))
        queries = checked(query_points, self.dim, self.ambient_dim, self.to_ambient)
        return contains(self._locator, queries, value, self.intervals(self.dim)[:, 0])

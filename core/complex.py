"""AlphaComplex: the queried result of a build (core/pipeline.py) or a load
(core/storage/tables.py).

It holds the points and a frozen TableIndex (core/query/index.py) and answers every query from
them; topology and signatures are computed on first use, or handed in when they were saved.
"""

from __future__ import annotations

import os

import numpy as np

from core.arrays import readonly
from core.build.points import Frame
from core.errors import InputError
from core.geometry.power import signed_square
from core.modes.alpha_modes import Mode
from core.pipeline import BuildInfo, build_complex
from core.progress import Progress
from core.query.alpha import at_value, table_value, threshold
from core.query.classes import EXTERIOR, INTERIOR, REGULAR, SINGULAR
from core.query.cursor import CursorOrders, ShapeCursor
from core.query.index import TableIndex
from core.query.locate import Locator, contains
from core.query.locate import query_points as checked_queries
from core.query.shape import AlphaShape
from core.storage import tables as storage
from core.topology import betti as forests
from core.topology.betti import Topology
from core.topology.persistence import Persistence, compute_persistence
from core.topology.signatures import Signatures, compute_signatures
from core.topology.suggest import AlphaRange, cover_alpha, optimal_alpha, suggest_alphas

__all__ = ["EXTERIOR", "INTERIOR", "REGULAR", "SINGULAR", "AlphaComplex", "at_value",
           "table_value"]


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

    def __init__(self, points: np.ndarray, input_index: np.ndarray, index: TableIndex,
                 frame: Frame | None = None, ambient_dim: int | None = None,
                 mode: Mode | None = None, weights: np.ndarray | None = None, *,
                 build_info: BuildInfo | None = None,
                 topology: Topology | None = None,
                 signatures: Signatures | None = None) -> None:
        """The complex of (m, dim) `points` and its table `index`; `input_index` (n,) maps
        input rows to points (-1 = hidden). `topology` and `signatures`, when given (saved
        with a table), are used instead of being computed."""
        #: The table and its lookups (core/query/index.py), shared with shapes and cursors.
        self.index = index
        #: How the table was built (core/pipeline.py): the triangulation backend, ...
        self.build_info = build_info or BuildInfo()
        self.mode = mode or Mode()
        self.points = readonly(points)
        self.input_index = readonly(input_index)
        #: (m,) float64 squared radii aligned with `points`, or None for a classic complex.
        self.weights = None if weights is None else readonly(weights)
        self.frame = frame
        self.dim = points.shape[1]
        self.ambient_dim = ambient_dim or (3 if frame is not None else self.dim)
        self._topology = topology
        self._signatures = signatures
        self._persistence: Persistence | None = None
        self._cover_alpha: float | None = None
        self._locator: Locator | None = None

    @classmethod
    def from_points(cls, points: object, progress: Progress | None = None, *,
                    weights: object = None, density: int | None = None,
                    combine: str = "mean", anisotropy: float = 0.0,
                    normals: object = None, backend: str | None = None) -> AlphaComplex:
        """Build from (n, 2) or (n, 3) points; duplicates merged, planar 3D built in 2D.

        The pipeline is core/pipeline.py. `progress(fraction, stage)` is called between stages;
        raising core.errors.Cancelled from it stops the build. Raises InputError for points
        that make no complex.
        `weights`: (n,) squared radii for a weighted complex (regular triangulation, power
        distance); None or all zeros build the classic complex. Points whose ball is hidden
        by the others get input_index -1.
        Modes (core/modes/alpha_modes.py; alpha is then in the mode's units): `density=k` divides
        radii by the local spacing (distance to the k-th neighbour, `combine`d over a simplex's
        vertices by "mean" or "max"); `anisotropy=tau` in [0, 1) compresses the alpha ball
        along the surface normal, taken from `normals` ((n, d) like the points) or estimated.
        `backend`: the triangulation backend, "qhull", "gmsh" (the optional `fast` extra,
        used only where its cells are certainly Qhull's; InputError otherwise) or None
        (automatic: gmsh where installed and certain, else Qhull; weighted points: geogram
        where its library was built, else Qhull); what was used is `build_info.backend`
        (core/backends).
        """
        built = build_complex(points, progress, weights=weights, density=density,
                              combine=combine, anisotropy=anisotropy, normals=normals,
                              backend=backend)
        return cls(built.points, built.input_index,
                   TableIndex(built.table, built.weights is not None), built.frame,
                   built.ambient_dim, built.mode, built.weights, build_info=built.info)

    # --- the table -------------------------------------------------------------------------
    def simplices(self, k: int) -> np.ndarray:
        """(n_k, k+1) int32 k-simplices as rows of `points`, rows ascending, sorted by enter."""
        return self.index.simplices(k)

    def intervals(self, k: int) -> np.ndarray:
        """(n_k, 3) float64 columns enter <= regular <= interior (radii; inf = never; signed
        radii sign(a2) * sqrt(|a2|) for weighted complexes)."""
        return self.index.intervals(k)

    def intervals_sq(self, k: int) -> np.ndarray:
        """(n_k, 3) float64 enter <= regular <= interior as squared radii (the filtration
        values of CGAL and gudhi; negative for weighted values below zero radius)."""
        return readonly(signed_square(self.intervals(k)))

    def face_ids(self, k: int) -> np.ndarray:
        """(n_k, k+1) int32: row in simplices(k-1) of the face opposite each vertex (k >= 1)."""
        return self.index.face_ids(k)

    def facet_cells(self) -> np.ndarray:
        """(n_{dim-1}, 2) int32: the cells on both sides of each facet, -1 = outside."""
        return self.index.facet_cells()

    def cell_measures(self) -> np.ndarray:
        """(n_dim,) float64 volume (3D) or area (2D) of every cell."""
        return self.index.cell_measures()

    def spectrum(self) -> np.ndarray:
        """(s,) float64 sorted distinct alphas at which the complex changes; 0 comes first
        (weighted: the vertices' values come first, signed radii)."""
        return self.index.spectrum()

    def spectrum_sq(self) -> np.ndarray:
        """(s,) float64 the spectrum as squared values (may be negative when weighted)."""
        return readonly(signed_square(self.index.spectrum()))

    # --- queries ---------------------------------------------------------------------------
    def classify(self, alpha: float | None = None, k: int | None = None, *,
                 alpha2: float | None = None) -> np.ndarray:
        """(n_k,) int8 class of every k-simplex: 0 exterior, 1 singular, 2 regular, 3 interior
        (alpha = inf is the convex hull: hull simplices stay REGULAR, never INTERIOR)."""
        alpha = threshold(table_value(alpha, alpha2, self.index.weighted))
        if k is None:
            raise InputError("classify needs k, the dimension of the simplices")
        level = self.index.level(k)
        out = (level.enter <= alpha).view(np.int8).copy()
        out += level.regular <= alpha
        out += level.interior <= alpha
        return readonly(out)

    def shape(self, alpha: float | None = None, *, alpha2: float | None = None) -> AlphaShape:
        """The alpha shape at `alpha` (a radius) or `alpha2` (squared); arrays are computed
        when first used. Its `alpha` attribute is the table value (signed radius)."""
        return AlphaShape(self.index, self.points, table_value(alpha, alpha2, self.index.weighted),
                          None if alpha2 is None else float(alpha2))

    def cursor(self, orders: CursorOrders | None = None) -> ShapeCursor:
        """A ShapeCursor: shapes at one alpha after another, each step costing what changed
        (the explorer's slider); building it sorts the table once more, unless the
        `orders` (core.query.cursor.cursor_orders of this table) were found already."""
        return ShapeCursor(self.index, self.points, orders)

    def to_ambient(self, coords: np.ndarray) -> np.ndarray:
        """Map (k, dim) complex coordinates to the input space ((k, ambient_dim))."""
        coords = np.asarray(coords, dtype=np.float64)
        if self.frame is None:
            return coords
        return self.frame.origin + coords @ self.frame.basis

    def counts(self) -> tuple[int, ...]:
        """Number of simplices per dimension, vertices first."""
        return self.index.counts()

    # --- files -----------------------------------------------------------------------------
    def save(self, path: str | os.PathLike) -> None:
        """Write the table to an .npz file atomically (see core/storage/tables.py for the
        layout)."""
        storage.save(self, path)

    @classmethod
    def load(cls, path: str | os.PathLike, *, verify: bool = True,
             trust_checksums: bool = False,
             spectrum: np.ndarray | None = None) -> AlphaComplex:
        """Read a table written by `save` (or the folder of `storage.save_mapped`: mapped, not
        read); FileFormatError if it is not one. verify=False skips most checks: only for a
        file this program has just written (core.storage.tables). `spectrum`: the table's spectrum
        as this program found it beside the table (a build process's hand-over), so it is
        not sorted again (storage.load). trust_checksums: an archive whose checksums match is
        not checked array by array again (the table cache's own entries)."""
        saved = storage.load(path, verify=verify, trust_checksums=trust_checksums,
                             spectrum=spectrum)
        return cls(saved.points, saved.input_index, saved.index, saved.frame, saved.ambient_dim,
                   saved.mode, saved.weights, build_info=saved.build_info,
                   topology=saved.topology, signatures=saved.signatures)

    def __repr__(self) -> str:
        return f"AlphaComplex(dim={self.dim}, points={len(self.points)}, simplices={self.counts()})"

    # --- topology (core.topology.betti / core.topology.signatures), computed on first use
    # ---------------
    def topology(self) -> Topology:
        """The forests behind Betti numbers and solid components (core.topology.betti), built on
        first use in O(n log n) or handed in with a saved table."""
        if self._topology is None:
            self._topology = forests.build_topology(self)
        return self._topology

    @property
    def has_signatures(self) -> bool:
        """True once the signatures are at hand (computed, or loaded with the table): then
        `signatures()` costs nothing and `save` writes them too."""
        return self._signatures is not None

    def signatures(self) -> Signatures:
        """Betti numbers, solid components, measures and class counts over the whole spectrum
        (computed on first call, O(n log n))."""
        if self._signatures is None:
            self._signatures = compute_signatures(self.index, self.points, self.topology())
        return self._signatures

    def betti(self, alpha: float | None = None, *, alpha2: float | None = None
              ) -> tuple[int, ...]:
        """Betti numbers at alpha: (components, holes) in 2D, (components, tunnels, voids) in 3D."""
        value = threshold(table_value(alpha, alpha2, self.index.weighted))
        at = np.array([value], dtype=np.float64)
        return tuple(int(b) for b in self.topology().betti_many(at)[0])

    def persistence(self) -> Persistence:
        """Persistence pairs (birth, death alphas) of components and of holes (2D) / voids (3D)."""
        if self._persistence is None:
            self._persistence = compute_persistence(self, self.topology())
        return self._persistence

    def optimal_alpha(self, n_components: int = 1) -> float:
        """Smallest alpha with every point in a cell and <= n_components solid parts (CGAL);
        a signed radius for weighted complexes (see optimal_alpha2)."""
        if self._cover_alpha is None:
            self._cover_alpha = cover_alpha(self.simplices(self.dim),
                                            self.index.level(self.dim).enter, len(self.points))
        return optimal_alpha(self.signatures(), self._cover_alpha, n_components)

    def default_alpha(self) -> float:
        """The alpha a view opens at: where the shape looks like the object (core.topology.opening).

        The smallest alpha at which the triangles (surface and solid) put at least 99 % of the
        points in pieces of 0.1 % of them or more (a scene's objects stay apart), at most 5
        median point spacings, and never more than `optimal_alpha()` (CGAL's rule for solids).
        Computed with the signatures and saved with them.
        """
        return min(self.signatures().opening_alpha, self.optimal_alpha())

    def optimal_alpha2(self, n_components: int = 1) -> float:
        """optimal_alpha as a squared value (may be negative for weighted complexes)."""
        return float(signed_square(np.float64(self.optimal_alpha(n_components))))

    def suggest_alphas(self, k: int = 5) -> tuple[AlphaRange, ...]:
        """The k alpha ranges where the Betti numbers hold longest on a log scale, best first."""
        return suggest_alphas(self.signatures(), k)

    def contains(self, query_points: object, alpha: float | None = None, *,
                 alpha2: float | None = None) -> np.ndarray:
        """(k,) bool: each query point lies in a cell of the complex at alpha.

        Queries are (k, ambient_dim) input-space points (planar 3D input: projected onto the
        plane) or (k, dim) complex coordinates.
        """
        value = threshold(table_value(alpha, alpha2, self.index.weighted))
        queries = checked_queries(query_points, self.dim, self.ambient_dim, self.to_ambient)
        if self._locator is None:
            self._locator = Locator(self.points, self.simplices(self.dim),
                                    self.face_ids(self.dim), self.facet_cells())
        return contains(self._locator, queries, value, self.intervals(self.dim)[:, 0])

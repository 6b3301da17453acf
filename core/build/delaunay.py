"""The triangulations the table is built on, by Qhull (scipy): Delaunay for classic points,
regular (weighted Delaunay, the lower hull of the lifted points) for weighted ones, with cells
in the canonical form the table uses (`Triangulation`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import ConvexHull, Delaunay, QhullError, cKDTree

from core.errors import InputError
from core.parallel import nonzero, rows_cols, slot_of, take
from core.tolerances import LOWER_FACET_COS

_NETWORKS = {3: ((0, 1), (1, 2), (0, 1)), 4: ((0, 1), (2, 3), (0, 2), (1, 3), (1, 2))}


@dataclass(frozen=True)
class Triangulation:
    """Cells with ascending vertex rows, their neighbours, and the vertex compaction."""

    cells: np.ndarray  # (t, d+1) int32, each row ascending
    neighbors: np.ndarray  # (t, d+1) int32, neighbour opposite each vertex; -1 = hull
    vertex_of_point: np.ndarray  # (m,) int64: vertex row for every input row (-1 = hidden)
    kept: np.ndarray  # (v,) int64: input rows that are vertices, ascending
    # (t, d+1) int8: the column of each neighbour's row that holds the cell (-1 = hull), where
    # the backend found it while matching facets (core.backends.facets.paired); else None
    mirror: np.ndarray | None = None

    def __post_init__(self) -> None:
        """A mirror must fit the neighbours (a `replace` of cells or neighbours that kept an
        old one would make the facet passes wrong silently): checked on a sample of rows."""
        if self.mirror is not None and not mirror_fits(self.neighbors, self.mirror):
            raise ValueError("Triangulation.mirror does not fit its neighbours")


def mirror_fits(neighbors: np.ndarray, mirror: np.ndarray, samples: int = 512) -> bool:
    """On `samples` evenly spread rows: each neighbour's row holds the cell back in the
    mirror's column, and the mirror is -1 exactly on the hull."""
    if mirror.shape != neighbors.shape:
        return False
    rows = np.unique(np.linspace(0, len(neighbors) - 1, min(samples, len(neighbors)),
                                 dtype=np.int64))
    nbr, back = neighbors[rows].astype(np.int64), mirror[rows].astype(np.int64)
    inner = nbr >= 0
    if not np.array_equal(inner, back >= 0):
        return False
    cell = np.broadcast_to(rows[:, None], nbr.shape)
    return bool(np.all(neighbors[nbr[inner], back[inner]] == cell[inner]))


def interior_facets(neighbors: np.ndarray, mirror: np.ndarray | None = None
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Every interior facet once, (t, i, u, j) (n,) int64: cell t's facet opposite its
    vertex i is cell u's opposite its vertex j (t < u, t ascending), from a (t, d+1)
    neighbour table (-1 = hull). j is read from `mirror` (the neighbours' columns that
    point back, Triangulation.mirror) where given, else found in u's row (one compare per
    column, core.parallel.slot_of). Shared by the backend check and the certification."""
    def inner(lo: int, hi: int) -> np.ndarray:
        return neighbors[lo:hi] > np.arange(lo, hi, dtype=neighbors.dtype)[:, None]

    slots = nonzero(inner, len(neighbors))
    t, i = rows_cols(slots, neighbors.shape[1])
    u = take(neighbors.ravel(), slots, np.int64)
    if mirror is not None:
        return t, i, u, take(mirror.ravel(), slots, np.int64)
    return t, i, u, slot_of(neighbors, u, t)


def sort_rows(cells: np.ndarray, neighbors: np.ndarray) -> None:
    """Sort every row of `cells` ascending in place, permuting `neighbors` alongside."""
    for i, j in _NETWORKS[cells.shape[1]]:
        swap = cells[:, i] > cells[:, j]
        for arr in (cells, neighbors):
            first, second = arr[:, i].copy(), arr[:, j].copy()
            np.copyto(arr[:, i], second, where=swap)
            np.copyto(arr[:, j], first, where=swap)


def _first_line(exc: BaseException) -> str:
    text = str(exc).strip()
    return text.splitlines()[0] if text else type(exc).__name__


def delaunay_cells(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Qhull's Delaunay cells of (m, d) points, rows ascending, and their neighbour table
    ((t, d+1) int32 each, -1 = hull); points Qhull leaves out are in no cell."""
    try:
        tri = Delaunay(points)
    except (QhullError, ValueError) as exc:
        raise InputError(f"the Delaunay triangulation failed (degenerate input?): "
                         f"{_first_line(exc)}") from None
    cells = np.ascontiguousarray(tri.simplices, dtype=np.int32)
    neighbors = np.ascontiguousarray(tri.neighbors, dtype=np.int32)
    if len(cells) == 0:
        raise InputError("the points span no cell: they are (nearly) collinear or coplanar")
    sort_rows(cells, neighbors)
    return cells, neighbors


def regular_cells(points: np.ndarray, weights: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Qhull's regular cells of (m, d) points with (m,) weights (the lower hull of the
    lifted points (p, |p|² - w)), rows ascending, and their neighbour table; hidden points
    are in no cell."""
    lifted = np.column_stack((points, np.einsum("nd,nd->n", points, points) - weights))
    try:  # Q5: no final pass widening the outer planes (the facets are the same without it)
        hull = ConvexHull(lifted, qhull_options="Qt Qbb Qc Q12 Q5")
    except (QhullError, ValueError) as exc:
        raise InputError(f"the regular triangulation failed (degenerate input?): "
                         f"{_first_line(exc)}") from None
    lower = hull.equations[:, -2] < -LOWER_FACET_COS
    if not lower.any():
        raise InputError("the points span no cell: they are (nearly) collinear or coplanar")
    new_id = np.full(len(lower), -1, dtype=np.int64)
    new_id[lower] = np.arange(int(lower.sum()))
    cells = np.ascontiguousarray(hull.simplices[lower], dtype=np.int32)
    around = hull.neighbors[lower]
    neighbors = np.ascontiguousarray(np.where(around >= 0, new_id[around], -1), dtype=np.int32)
    sort_rows(cells, neighbors)
    return cells, neighbors


def triangulate(points: np.ndarray) -> Triangulation:
    """Delaunay cells of (m, d) distinct points; points Qhull leaves out are merged.

    Qhull drops points it cannot separate from a vertex (coplanar in the lifted space); each
    such point is mapped to its nearest vertex so no input point is lost.
    """
    cells, neighbors = delaunay_cells(points)
    m = len(points)
    used = np.zeros(m, dtype=bool)
    used[cells.ravel()] = True
    vertex_of_point = np.cumsum(used, dtype=np.int64) - 1
    kept = np.flatnonzero(used)
    if not used.all():
        lost = np.flatnonzero(~used)
        _, nearest = cKDTree(points[kept]).query(points[lost])
        vertex_of_point[lost] = nearest
        cells = vertex_of_point[cells].astype(np.int32)
    return Triangulation(cells, neighbors, vertex_of_point, kept)


def compacted(cells: np.ndarray, neighbors: np.ndarray, m: int) -> Triangulation:
    """The Triangulation of (t, d+1) cells on m points whose unused points are hidden
    (vertex_of_point -1), cells renumbered to vertex rows."""
    used = np.zeros(m, dtype=bool)
    used[cells.ravel()] = True
    kept = np.flatnonzero(used)
    vertex_of_point = np.where(used, np.cumsum(used, dtype=np.int64) - 1, -1)
    if not used.all():
        cells = vertex_of_point[cells].astype(np.int32)
    return Triangulation(cells, neighbors, vertex_of_point, kept)


def regular_triangulate(points: np.ndarray, weights: np.ndarray) -> Triangulation:
    """Regular (weighted Delaunay) cells of (m, d) distinct points with (m,) weights.

    The lower convex hull of the lifted points (p, |p|² - w) (Qhull in d + 1 dimensions).
    Points that are no vertex of it are hidden: their balls add nothing to the union of the
    others' power cells; `vertex_of_point` maps them to -1. Input that is well scaled
    (centred, extent about 1) keeps the lifting accurate.
    """
    return compacted(*regular_cells(points, weights), len(points))

"""The Delaunay triangulation (scipy/Qhull), with cells in the canonical form the table uses."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import Delaunay, QhullError, cKDTree

from .errors import InputError

_NETWORKS = {3: ((0, 1), (1, 2), (0, 1)), 4: ((0, 1), (2, 3), (0, 2), (1, 3), (1, 2))}


@dataclass(frozen=True)
class Triangulation:
    """Cells with ascending vertex rows, their neighbours, and the vertex compaction."""

    cells: np.ndarray  # (t, d+1) int32, each row ascending
    neighbors: np.ndarray  # (t, d+1) int32, neighbour opposite each vertex; -1 = hull
    vertex_of_point: np.ndarray  # (m,) int64: vertex row for every input row
    kept: np.ndarray  # (v,) int64: input rows that are vertices, ascending


def sort_rows(cells: np.ndarray, neighbors: np.ndarray) -> None:
    """Sort every row of `cells` ascending in place, permuting `neighbors` alongside."""
    for i, j in _NETWORKS[cells.shape[1]]:
        swap = cells[:, i] > cells[:, j]
        for arr in (cells, neighbors):
            first, second = arr[:, i].copy(), arr[:, j].copy()
            np.copyto(arr[:, i], second, where=swap)
            np.copyto(arr[:, j], first, where=swap)


def triangulate(points: np.ndarray) -> Triangulation:
    """Delaunay cells of (m, d) distinct points; points Qhull leaves out are merged.

    Qhull drops points it cannot separate from a vertex (coplanar in the lifted space); each
    such point is mapped to its nearest vertex so no input point is lost.
    """
    try:
        tri = Delaunay(points)
    except (QhullError, ValueError) as exc:
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise InputError(
            f"the Delaunay triangulation failed (degenerate input?): {first}"
        ) from None
    cells = np.ascontiguousarray(tri.simplices, dtype=np.int32)
    neighbors = np.ascontiguousarray(tri.neighbors, dtype=np.int32)
    if len(cells) == 0:
        raise InputError("the points span no cell: they are (nearly) collinear or coplanar")
    sort_rows(cells, neighbors)
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

"""Point location in the complex's own triangulation: a visibility walk run for all queries at once.

Each query starts in a cell of its nearest vertex (k-d tree) and steps across the facet it lies
most beyond until no facet separates it from the cell. In a Delaunay triangulation such walks
cannot cycle, so they stop after a few steps; a random choice among separating facets takes
over after `GREEDY_STEPS` in case rounding on degenerate cells makes the greedy walk loop.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

from core.errors import InputError

#: A query whose barycentric coordinates are all >= -LOCATE_RTOL is inside the cell, so a
#: point on a shared facet is accepted by either side instead of bouncing between them.
LOCATE_RTOL = 1e-12
GREEDY_STEPS = 200
MAX_STEPS = 5000


class Locator:
    """Finds the cell (row of simplices(dim)) holding each query point; -1 outside the hull."""

    def __init__(self, points: np.ndarray, cells: np.ndarray, face_ids: np.ndarray,
                 facet_cells: np.ndarray) -> None:
        self.points = np.asarray(points, dtype=np.float64)
        self.cells = np.asarray(cells, dtype=np.int64)
        self.tree = cKDTree(self.points)
        self.neighbors = neighbor_cells(face_ids, facet_cells)
        self.vertex_cell = np.zeros(len(self.points), dtype=np.int64)
        self.vertex_cell[self.cells.ravel()] = np.repeat(
            np.arange(len(self.cells)), self.cells.shape[1]
        )

    def locate(self, queries: np.ndarray) -> np.ndarray:
        """(k,) int64 cell row of each of the (k, dim) query points, -1 outside the hull."""
        q = np.asarray(queries, dtype=np.float64)
        _, nearest = self.tree.query(q)
        current = self.vertex_cell[nearest]
        found = np.full(len(q), -1, dtype=np.int64)
        active = np.arange(len(q))
        rng = np.random.default_rng(0)
        for step in range(MAX_STEPS):
            if len(active) == 0:
                break
            cell = current[active]
            lam = barycentric(self.points, self.cells[cell], q[active])
            beyond = lam < -LOCATE_RTOL
            inside = ~beyond.any(axis=1)
            found[active[inside]] = cell[inside]
            pick = lam if step < GREEDY_STEPS else -rng.random(lam.shape) * beyond
            nxt = self.neighbors[cell, np.argmin(pick, axis=1)]
            move = ~inside & (nxt >= 0)
            current[active[move]] = nxt[move]
            active = active[move]
        return found


def contains(locator: Locator, queries: np.ndarray, alpha: float,
             cell_enter: np.ndarray) -> np.ndarray:
    """(k,) bool: each (k, dim) query lies in a cell whose enter <= alpha (a table value:
    a radius, or for weighted complexes a signed radius, checked by the caller)."""
    alpha = float(alpha)
    cells = locator.locate(queries)
    inside = cells >= 0
    inside[inside] = cell_enter[cells[inside]] <= alpha
    return inside


def neighbor_cells(face_ids: np.ndarray, facet_cells: np.ndarray) -> np.ndarray:
    """(c, dim + 1) int64 cell across the facet opposite each vertex of each cell, -1 = outside."""
    faces = np.asarray(face_ids, dtype=np.int64)
    sides = np.asarray(facet_cells, dtype=np.int64)[faces]
    own = np.arange(len(faces))[:, None]
    return np.where(sides[..., 0] == own, sides[..., 1], sides[..., 0])


def barycentric(points: np.ndarray, cells: np.ndarray, q: np.ndarray) -> np.ndarray:
    """(a, dim + 1) barycentric coordinates of the (a, dim) queries in their (a, dim + 1) cells.

    Signed volumes with one vertex swapped for the query, relative to the query for accuracy;
    a flat cell gets coordinates scaled by the largest swapped volume instead of its own.
    """
    swapped = swapped_volumes(points[cells] - q[:, None, :])
    total = swapped.sum(axis=1)
    largest = np.abs(swapped).max(axis=1, initial=0.0)
    scale = np.where(np.abs(total) <= LOCATE_RTOL * largest, -largest, total)
    scale[scale == 0.0] = 1.0
    return swapped / scale[:, None]


def swapped_volumes(rel: np.ndarray) -> np.ndarray:
    """(a, dim + 1) dim!-volumes of each cell with vertex j moved to the origin (the query).

    rel: (a, dim + 1, dim) vertices relative to the query. Expanding the volume determinant,
    only the terms without the moved vertex survive: one triple product (3D) or cross (2D).
    """
    if rel.shape[2] == 2:
        w0, w1, w2 = rel[:, 0], rel[:, 1], rel[:, 2]
        cross = [_cross2(w1, w2), -_cross2(w0, w2), _cross2(w0, w1)]
        return np.stack(cross, axis=1)
    w0, w1, w2, w3 = rel[:, 0], rel[:, 1], rel[:, 2], rel[:, 3]
    c23, c01 = np.cross(w2, w3), np.cross(w0, w1)
    dots = [_dot(w1, c23), -_dot(w0, c23), _dot(c01, w3), -_dot(c01, w2)]
    return np.stack(dots, axis=1)


def _cross2(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(a,) z of the cross product of (a, 2) vectors."""
    return a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(a,) row-wise dot products of (a, 3) vectors."""
    return np.einsum("ij,ij->i", a, b)


def query_points(queries: object, dim: int, ambient_dim: int, to_ambient) -> np.ndarray:
    """(k, dim) float64 finite query points in the complex's coordinates, or InputError.

    For planar 3D input (dim 2, ambient_dim 3), (k, 3) queries are projected onto the plane
    through `to_ambient`, the complex's affine map back to the input space.
    """
    try:
        q = np.asarray(queries, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise InputError(f"query points must be numbers: {exc}") from None
    if q.ndim == 1 and q.shape[0] in (dim, ambient_dim):
        q = q[None, :]
    if q.ndim != 2 or q.shape[1] not in (dim, ambient_dim):
        raise InputError(
            f"query points must be an array of shape (k, {ambient_dim}), got shape {q.shape}"
        )
    if not np.isfinite(q).all():
        raise InputError("query points contain NaN or infinite values")
    if q.shape[1] == dim:
        return q
    origin = to_ambient(np.zeros((1, dim)))
    basis = to_ambient(np.eye(dim)) - origin
    return (q - origin) @ np.linalg.pinv(basis)

"""Cavities: the voids of the dual complex (bounded components of its complement, b2) and
the volume of empty space each one encloses."""

from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

GRID_POINTS = 200_000  # grid points per cavity's bounding box for its volume


def void_cells(cell_empty: np.ndarray, facet_cells: np.ndarray,
               facet_empty: np.ndarray) -> np.ndarray:
    """(n_cells,) int64 void label of every cell, -1 for cells in the complex or outside.

    cell_empty (n_cells,) bool: the cell is not in the complex; facet_cells (n_facets, 2) the
    cells on each side of a facet (-1 = beyond the hull); facet_empty: the facet is not in the
    complex. Empty cells joined through empty facets form one region of the complement; the
    regions that reach beyond the hull are the outside, the others are the voids (b2 of them).
    """
    n = len(cell_empty)
    outside = n  # one node for everything beyond the hull
    a, b = np.asarray(facet_cells[:, 0], np.int64), np.asarray(facet_cells[:, 1], np.int64)
    a, b = np.where(a < 0, outside, a), np.where(b < 0, outside, b)
    keep = np.asarray(facet_empty, bool)
    graph = coo_matrix((np.ones(int(keep.sum())), (a[keep], b[keep])), shape=(n + 1, n + 1))
    _, comp = connected_components(graph, directed=False)
    empty = np.append(np.asarray(cell_empty, bool), True)
    is_void = empty & (comp != comp[outside])
    _, labels = np.unique(comp[:n][is_void[:n]], return_inverse=True)
    out = np.full(n, -1, dtype=np.int64)
    out[is_void[:n]] = labels
    return out


def _grid_points_in_cells(corners: np.ndarray, origin: np.ndarray, step: float) -> np.ndarray:
    """(p, 3) points of the grid origin + step * (i + 1/2) inside the tetrahedra (t, 4, 3).

    Each tetrahedron enumerates the grid points of its own bounding box, all at once.
    """
    lo = np.floor((corners.min(1) - origin) / step - 0.5).astype(np.int64) + 1
    hi = np.floor((corners.max(1) - origin) / step - 0.5).astype(np.int64)
    size = np.maximum(hi - lo + 1, 0)
    count = size.prod(1)
    tet = np.repeat(np.arange(len(corners)), count)
    k = np.arange(int(count.sum())) - np.repeat(np.cumsum(count) - count, count)
    sy, sz = size[tet, 1], size[tet, 2]
    ijk = lo[tet] + np.stack([k // (sy * sz), (k // sz) % sy, k % sz], 1)
    x = origin + step * (ijk + 0.5)
    edges = np.transpose(corners[:, 1:] - corners[:, :1], (0, 2, 1))
    lam = np.einsum("pij,pj->pi", np.linalg.inv(edges)[tet], x - corners[tet, 0])
    return x[(lam >= 0).all(1) & (lam.sum(1) <= 1)]


def void_volumes(labels: np.ndarray, cells: np.ndarray, centres: np.ndarray,
                 radii: np.ndarray, grid_points: int = GRID_POINTS) -> np.ndarray:
    """(n_voids,) float64 volume of the empty space in each void (its cells minus the balls).

    An estimate on a regular grid of about `grid_points` points per void's bounding box
    (cell centred): the error is of the order of the void's surface times the step², far
    below the void's volume.
    """
    n_voids = int(labels.max()) + 1 if len(labels) else 0
    tree, reach = cKDTree(centres), float(radii.max())
    out = np.zeros(n_voids)
    for v in range(n_voids):
        corners = centres[cells[labels == v]]  # (t, 4, 3)
        lo, hi = corners.min((0, 1)), corners.max((0, 1))
        step = float(np.prod(hi - lo) / grid_points) ** (1 / 3)
        x = _grid_points_in_cells(corners, lo, step)
        pairs = cKDTree(x).sparse_distance_matrix(tree, reach, output_type="ndarray")
        covered = np.zeros(len(x), bool)
        covered[pairs["i"][pairs["v"] <= radii[pairs["j"]]]] = True
        out[v] = (~covered).sum() * step ** 3
    return out

"""Cavities: the voids of the dual complex (bounded components of its complement, b2); their
exact volume and lining area come from `regions`."""

from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components


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


def cavity_cells(ac, alpha2: float = 0.0) -> np.ndarray:
    """(k,) int64 rows of ac.simplices(3) in the voids of a 3D complex at alpha² (the cells
    the window highlights as cavities)."""
    labels = void_cells(ac.intervals_sq(3)[:, 0] > alpha2, ac.facet_cells(),
                        ac.intervals_sq(2)[:, 0] > alpha2)
    return np.flatnonzero(labels >= 0)

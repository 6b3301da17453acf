"""Which solid component each cell of the complex belongs to at one alpha (CGAL's definition:
cells in the complex joined through shared facets), for colouring the shape by component.

One pass over the facets and scipy's connected components: O(n) per alpha, for a display
mode, not for the slider's hot path.
"""

from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from core.query.alpha import radius


def solid_labels(ac, alpha: float) -> np.ndarray:
    """(c,) int64 component of each cell in the complex at alpha (cells are the first c rows
    of simplices(dim), sorted by enter). Label 0 is the largest component (by cell count),
    1 the next, and so on; ties go to the component whose first cell entered first."""
    alpha = radius(alpha, ac.weights is not None)
    count = int(np.searchsorted(ac.intervals(ac.dim)[:, 0], alpha, side="right"))
    if count == 0:
        return np.zeros(0, dtype=np.int64)
    sides = np.asarray(ac.facet_cells(), dtype=np.int64)
    inner = sides[((sides >= 0) & (sides < count)).all(axis=1)]
    graph = coo_matrix((np.ones(len(inner), dtype=np.int8), (inner[:, 0], inner[:, 1])),
                       shape=(count, count))
    _, labels = connected_components(graph, directed=False)
    sizes = np.bincount(labels)
    first = np.full(len(sizes), count, dtype=np.int64)
    np.minimum.at(first, labels, np.arange(count))
    rank = np.empty(len(sizes), dtype=np.int64)
    rank[np.lexsort((first, -sizes))] = np.arange(len(sizes))
    return rank[labels]


def facet_labels(ac, facet_ids: np.ndarray, labels: np.ndarray) -> np.ndarray:
    """(f,) int64 component of the cell in the complex beside each facet id (-1 if none): a
    REGULAR facet has exactly one. `labels` is solid_labels(ac, alpha) at the facets' alpha."""
    sides = np.asarray(ac.facet_cells(), dtype=np.int64)[np.asarray(facet_ids, dtype=np.int64)]
    inside = (sides >= 0) & (sides < len(labels))
    cell = np.where(inside[:, 0], sides[:, 0], np.where(inside[:, 1], sides[:, 1], -1))
    return np.where(cell >= 0, labels[np.maximum(cell, 0)] if len(labels) else -1, -1)

"""Cell neighbours from the cells alone (gmsh returns none): facets matched by packed keys."""

from __future__ import annotations

import numpy as np


def _packed(cells: np.ndarray, columns: list[list[int]], base: int,
            dtype: type) -> np.ndarray:
    """Facet keys in `dtype`: the facet opposite vertex i of every cell at i * t + cell,
    its vertices packed in base `base`."""
    t = len(cells)
    keys = np.empty(len(columns) * t, dtype=dtype)
    for i, cols in enumerate(columns):
        part = keys[i * t:(i + 1) * t]
        part[:] = cells[:, cols[0]]
        for c in cols[1:]:
            part *= dtype(base)
            part += cells[:, c].astype(dtype)
    return keys


def _sorted_facets(cells: np.ndarray, n_points: int) -> tuple[np.ndarray, np.ndarray]:
    """The order that sorts all facet keys (flat index i * t + cell for the facet opposite
    vertex i) and (len - 1,) bool: sorted facet k equals facet k + 1. One uint64 key where
    m**d fits, else a lexsort of (first vertices, last vertex)."""
    width = cells.shape[1]
    columns = [[j for j in range(width) if j != i] for i in range(width)]
    if float(n_points) ** (width - 1) < 2.0**64:
        keys = _packed(cells, columns, n_points, np.uint64)
        order = np.argsort(keys)
        keys = keys[order]
        return order, keys[1:] == keys[:-1]
    head = _packed(cells, [cols[:-1] for cols in columns], n_points, np.int64)
    tail = np.concatenate([cells[:, cols[-1]] for cols in columns])
    order = np.lexsort((tail, head))
    head, tail = head[order], tail[order]
    return order, (head[1:] == head[:-1]) & (tail[1:] == tail[:-1])


def neighbours(cells: np.ndarray, n_points: int) -> tuple[np.ndarray, bool]:
    """(t, d+1) int32 neighbour opposite each vertex (-1 = none) of (t, d+1) ascending
    cells on `n_points` points, and whether every facet is in at most two cells (a facet in
    three or more makes no triangulation; its entries are then meaningless)."""
    t, width = cells.shape
    order, same = _sorted_facets(cells, n_points)
    manifold = not bool(np.any(same[1:] & same[:-1]))
    first, second = order[:-1][same], order[1:][same]
    flat = np.full(width * t, -1, dtype=np.int32)
    flat[first] = second % t
    flat[second] = first % t
    return np.ascontiguousarray(flat.reshape(width, t).T), manifold

"""Cell neighbours from the cells alone (gmsh returns none): facets matched by packed keys.

Every facet is keyed at its slot cell * (d+1) + i (the facet opposite vertex i of a cell),
so the matched slots give both the neighbour table and, free, each neighbour's column that
points back (the `mirror`, which the certification and the table would otherwise find by a
random gather of the neighbours' rows).
"""

from __future__ import annotations

import numpy as np


def _packed(cells: np.ndarray, columns: list[list[int]], base: int,
            dtype: type) -> np.ndarray:
    """(t * len(columns),) facet keys in `dtype`, the facet of columns[i] of every cell at
    slot cell * len(columns) + i, its vertices packed in base `base`."""
    keys = np.empty((len(cells), len(columns)), dtype=dtype)
    for i, cols in enumerate(columns):
        part = cells[:, cols[0]].astype(dtype)
        for c in cols[1:]:
            part *= dtype(base)
            part += cells[:, c].astype(dtype)
        keys[:, i] = part
    return keys.ravel()


def _sorted_facets(cells: np.ndarray, n_points: int) -> tuple[np.ndarray, np.ndarray]:
    """The order that sorts all facet keys (slot cell * (d+1) + i for the facet opposite
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
    tail = np.stack([cells[:, cols[-1]] for cols in columns], axis=1).ravel()
    order = np.lexsort((tail, head))
    head, tail = head[order], tail[order]
    return order, (head[1:] == head[:-1]) & (tail[1:] == tail[:-1])


def paired(cells: np.ndarray, n_points: int) -> tuple[np.ndarray, np.ndarray, bool]:
    """(t, d+1) int32 neighbour opposite each vertex (-1 = none) of (t, d+1) ascending
    cells on `n_points` points, (t, d+1) int8 the neighbour's column that holds the cell
    (its `mirror`, -1 = none), and whether every facet is in at most two cells (a facet in
    three or more makes no triangulation; the tables are then meaningless)."""
    t, width = cells.shape
    order, same = _sorted_facets(cells, n_points)
    manifold = not bool(np.any(same[1:] & same[:-1]))
    first, second = order[:-1][same], order[1:][same]
    del order, same
    index = np.int32 if width * t < 2**31 else np.int64
    other = np.full(width * t, -1, dtype=index)  # the slot across each slot
    other[first] = second
    other[second] = first
    del first, second
    mirror = np.remainder(other, width).astype(np.int8)
    mirror[other < 0] = -1
    other //= width  # the cell across (-1 stays -1)
    return other.astype(np.int32, copy=False).reshape(t, width), mirror.reshape(t, width), manifold


def neighbours(cells: np.ndarray, n_points: int) -> tuple[np.ndarray, bool]:
    """paired() without the mirror: the neighbour table and whether it is manifold."""
    nbrs, _, manifold = paired(cells, n_points)
    return nbrs, manifold

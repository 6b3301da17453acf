"""The opening alpha: the smallest alpha at which the shape's triangles make the object.

CGAL's optimal alpha (every point in one solid) suits solids; on a surface scan it is a faceted
blob tens of spacings wide. A scan looks like its object as soon as its triangles (regular,
singular or interior: the surface and any solid behind it) join nearly every point into one
piece. That alpha comes from one spanning forest: an edge joins its ends once its first
triangle is in, and the largest component only grows, so a binary search over the forest's
merges finds it with a few `connected_components` calls.
"""

from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from core.arrays import ascends
from core.build.sorting import argsort_radii
from core.query.index import TableIndex
from core.topology.union_find import ordered_forest

#: Share of the points the largest piece must hold: scans carry a few stray points (outliers,
#: specks) that join only at alphas far beyond the object's own.
OPENING_SHARE = 0.99


def lowest_enter_cofaces(face_ids: np.ndarray, coface_enter: np.ndarray,
                         n_faces: int) -> np.ndarray:
    """(n_faces,) float64 smallest enter among each face's cofaces (inf: none).

    face_ids: (c, k + 1) int rows of the faces of c cofaces; coface_enter: (c,) float64.
    """
    first = np.full(n_faces, np.inf)
    np.minimum.at(first, np.asarray(face_ids, dtype=np.int64).ravel(),
                  np.repeat(np.asarray(coface_enter, dtype=np.float64), face_ids.shape[1]))
    return first


def joined_share(n_points: int, a: np.ndarray, b: np.ndarray,
                 sizes: np.ndarray | None = None) -> float:
    """Share of n_points in the largest component of the graph with edges (a, b); with
    `sizes`, node i stands for sizes[i] points (a contracted graph) and n_points is their sum."""
    nodes = n_points if sizes is None else len(sizes)
    graph = coo_matrix((np.ones(len(a), dtype=np.int8), (a, b)), shape=(nodes, nodes))
    _, labels = connected_components(graph, directed=False)
    held = np.bincount(labels) if sizes is None else np.bincount(labels, weights=sizes)
    return float(held.max()) / n_points


def opening_alpha(n_points: int, edges: np.ndarray, edge_first_triangle: np.ndarray,
                  share: float = OPENING_SHARE) -> float:
    """Smallest alpha at which triangles join >= share of the n_points into one component.

    edges: (e, 2) int vertex rows; edge_first_triangle: (e,) float64 enter of each edge's first
    triangle (inf: none). Returns inf when no alpha reaches the share.
    """
    values = np.asarray(edge_first_triangle, dtype=np.float64)
    finite = np.flatnonzero(np.isfinite(values))
    order = finite[argsort_radii(values[finite])]
    edges = np.asarray(edges, dtype=np.int64)[order]
    joined = ordered_forest(n_points, edges[:, 0], edges[:, 1])  # in order of arrival
    return reaching_alpha(n_points, edges[joined, 0], edges[joined, 1],
                          values[order[joined]], share)


def reaching_alpha(n_points: int, a: np.ndarray, b: np.ndarray, weights: np.ndarray,
                   share: float = OPENING_SHARE) -> float:
    """The weight of the first merge (a[j], b[j]) of a spanning forest, merges in ascending
    (f,) `weights`, after which one component holds >= share of the n_points; inf if none."""
    if n_points == 0 or joined_share(n_points, a, b) < share:
        return float("inf")
    high = _first_reaching(n_points, a, b, share)
    return float(weights[high - 1]) if high > 0 else 0.0


def _first_reaching(n_points: int, a: np.ndarray, b: np.ndarray, share: float) -> int:
    """The fewest first merges (a, b) of a spanning forest, in order, whose largest
    component holds >= share of the n_points (all of them do; 0 is never tested).

    After m merges the largest of the n - m components holds at most m + 1 points, so fewer
    than ceil(share * n) - 1 merges never reach the share: the search starts there, on the
    graph contracted by those merges (one node per component, weighted by its size), which
    has n - m nodes, a few percent of the points, instead of all of them at every step."""
    low, high = max(int(np.ceil(share * n_points)) - 2, 0), len(a)
    if high - low <= 1:
        return high
    _, labels = connected_components(
        coo_matrix((np.ones(low, dtype=np.int8), (a[:low], b[:low])),
                   shape=(n_points, n_points)), directed=False)
    sizes = np.bincount(labels).astype(np.float64)
    a, b = labels[a[low:]], labels[b[low:]]  # merge low + i is (a[i], b[i]) from here on
    offset, high = low, high - low
    low = 0
    while high - low > 1:
        middle = (low + high) // 2
        if joined_share(n_points, a[:middle], b[:middle], sizes) >= share:
            high = middle
        else:
            low = middle
    return offset + high


def triangle_forest(index: TableIndex, n_points: int
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(a, b, weights): the merges of the points' spanning forest when every edge arrives
    with its first triangle, triangles in row order (the table's, by enter); (f,) int64
    vertex rows and (f,) float64 ascending enter of the triangle that brings each merge.

    A triangle's last new edge always closes a cycle (its ends are joined by the triangle's
    other two edges, already there), so only the others are candidates: a few edges instead
    of all of them, in order with no sort.
    """
    triangles = index.face_ids(2)
    first = index.first_cofaces(2)
    row = np.arange(len(triangles), dtype=np.int32)
    new = [np.take(first, triangles[:, c]) == row for c in range(3)]
    # a new edge that is not the triangle's last new one: edge 0 when 1 or 2 is new too,
    # edge 1 when 2 is, never edge 2 (column by column: a cumsum over rows is slow)
    candidate = np.column_stack((new[0] & (new[1] | new[2]), new[1] & new[2]))
    flat = np.flatnonzero(candidate)
    flat = flat // 2 * 3 + flat % 2  # back to slots of the (t, 3) rows
    ends = index.simplices(1)[triangles.ravel()[flat]]
    joined = ordered_forest(n_points, ends[:, 0], ends[:, 1])
    return (ends[joined, 0].astype(np.int64), ends[joined, 1].astype(np.int64),
            index.level(2).enter[flat[joined] // triangles.shape[1]])


def opening_alpha_of(index: TableIndex, n_points: int) -> float:
    """`opening_alpha` of the table `index` of a complex with `n_points` points; the largest
    critical alpha (the whole triangulation) when no alpha reaches the share.

    Ties between edges of equal first-triangle enter may merge in another order than
    `opening_alpha`'s, which changes no merge's weight of the first that reaches the share."""
    last = index.last_value()
    triangle_enter = index.level(2).enter
    if len(triangle_enter) == 0:
        return last
    if not ascends(triangle_enter):
        edge_first = lowest_enter_cofaces(index.face_ids(2), triangle_enter,
                                          len(index.simplices(1)))
        return min(opening_alpha(n_points, index.simplices(1), edge_first), last)
    return min(reaching_alpha(n_points, *triangle_forest(index, n_points)), last)

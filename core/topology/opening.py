"""The opening alpha: the smallest alpha at which the shape's triangles make the object(s).

CGAL's optimal alpha (every point in one solid) suits solids; on a surface scan it is a faceted
blob tens of spacings wide. A scan looks like its objects as soon as its triangles (regular,
singular or interior: the surface and any solid behind it) join nearly every point into a
piece of some size: a scene's objects (a table, a mug, the wall behind) stay apart, and only
stray specks are left out. Pieces only grow as alpha grows, so the share of the points in them
only grows too: a binary search over one spanning forest's merges (an edge joins its ends once
its first triangle is in) finds that alpha with a few `connected_components` calls. The alpha
is never wider than MAX_SPACINGS median nearest-neighbour spacings: a ball that wide spans
the gaps between objects rather than between neighbours on one surface.
"""

from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from core.arrays import ascends
from core.build.sorting import argsort_radii
from core.query.index import TableIndex
from core.topology.union_find import ordered_forest

#: Share of the points the pieces must hold: scans carry a few stray points (outliers,
#: specks) that join only at alphas far beyond the objects' own.
OPENING_SHARE = 0.99
#: A piece holds at least this share of the points, and at least MIN_PIECE points (one
#: triangle): smaller ones are specks, not objects.
PIECE_SHARE = 0.001
MIN_PIECE = 3
#: The opening alpha is at most this many median nearest-neighbour spacings.
MAX_SPACINGS = 5.0


def lowest_enter_cofaces(face_ids: np.ndarray, coface_enter: np.ndarray,
                         n_faces: int) -> np.ndarray:
    """(n_faces,) float64 smallest enter among each face's cofaces (inf: none).

    face_ids: (c, k + 1) int rows of the faces of c cofaces; coface_enter: (c,) float64.
    """
    first = np.full(n_faces, np.inf)
    np.minimum.at(first, np.asarray(face_ids, dtype=np.int64).ravel(),
                  np.repeat(np.asarray(coface_enter, dtype=np.float64), face_ids.shape[1]))
    return first


def piece_size(n_points: int) -> int:
    """The fewest points a piece holds: PIECE_SHARE of n_points, at least MIN_PIECE (at most
    n_points, so that a tiny set can still make one piece)."""
    return max(min(MIN_PIECE, n_points), int(np.ceil(PIECE_SHARE * n_points)))


def component_sizes(n_points: int, a: np.ndarray, b: np.ndarray,
                    sizes: np.ndarray | None = None) -> np.ndarray:
    """(c,) float64 points in each component of the graph with edges (a, b); with `sizes`,
    node i stands for sizes[i] points (a contracted graph)."""
    nodes = n_points if sizes is None else len(sizes)
    graph = coo_matrix((np.ones(len(a), dtype=np.int8), (a, b)), shape=(nodes, nodes))
    _, labels = connected_components(graph, directed=False)
    return np.bincount(labels, weights=sizes).astype(np.float64)


def pieces_share(n_points: int, a: np.ndarray, b: np.ndarray, min_size: int,
                 sizes: np.ndarray | None = None) -> float:
    """Share of n_points in components of >= min_size points of the graph with edges (a, b)
    (`sizes`: as in component_sizes, n_points is then their sum)."""
    held = component_sizes(n_points, a, b, sizes)
    return float(held[held >= min_size].sum()) / n_points


def edge_forest(n_points: int, edges: np.ndarray, edge_first_triangle: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(a, b, weights) of the spanning forest whose edges arrive with their first triangle:
    edges (e, 2) int vertex rows, edge_first_triangle (e,) float64 (inf: never). (f,) int64
    ends and (f,) float64 ascending weights of each merge."""
    values = np.asarray(edge_first_triangle, dtype=np.float64)
    finite = np.flatnonzero(np.isfinite(values))
    order = finite[argsort_radii(values[finite])]
    edges = np.asarray(edges, dtype=np.int64)[order]
    joined = ordered_forest(n_points, edges[:, 0], edges[:, 1])  # in order of arrival
    return edges[joined, 0], edges[joined, 1], values[order[joined]]


def opening_alpha(n_points: int, edges: np.ndarray, edge_first_triangle: np.ndarray,
                  share: float = OPENING_SHARE) -> float:
    """Smallest alpha at which triangles put >= share of the n_points in pieces of at least
    piece_size(n_points) points (edges and edge_first_triangle as in edge_forest); inf when
    no alpha does."""
    return reaching_alpha(n_points, *edge_forest(n_points, edges, edge_first_triangle), share)


def reaching_alpha(n_points: int, a: np.ndarray, b: np.ndarray, weights: np.ndarray,
                   share: float = OPENING_SHARE) -> float:
    """The weight of the first merge (a[j], b[j]) of a spanning forest, merges in ascending
    (f,) `weights`, after which >= share of the n_points lie in pieces of at least
    piece_size(n_points) points; inf if none."""
    size = piece_size(n_points)
    if n_points == 0 or pieces_share(n_points, a, b, size) < share:
        return float("inf")
    high = _first_reaching(n_points, a, b, share, size)
    return float(weights[high - 1]) if high > 0 else 0.0


def _first_reaching(n_points: int, a: np.ndarray, b: np.ndarray, share: float,
                    size: int) -> int:
    """The fewest first merges (a, b) of a spanning forest, in order, after which >= share
    of the n_points lie in components of >= size points (all of them do; 0 is never tested).

    A component of k points took k - 1 merges, so pieces holding share * n points took at
    least share * n * (1 - 1 / size) of them: the search starts there, on the graph
    contracted by those merges (one node per component, weighted by its size), a few percent
    of the points for large sets, instead of all of them at every step."""
    need = int(np.ceil(share * n_points * (1.0 - 1.0 / size)))
    low, high = max(need - 1, 0), len(a)
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
        if pieces_share(n_points, a[:middle], b[:middle], size, sizes) >= share:
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


def opening_forest(index: TableIndex, n_points: int
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(a, b, weights) of the triangles' spanning forest of the table `index`: triangle_forest
    when its triangles ascend by enter (the table's order), else edge_forest."""
    triangle_enter = index.level(2).enter
    if ascends(triangle_enter):
        return triangle_forest(index, n_points)
    edge_first = lowest_enter_cofaces(index.face_ids(2), triangle_enter,
                                      len(index.simplices(1)))
    return edge_forest(n_points, index.simplices(1), edge_first)


def point_spacing(index: TableIndex, points: np.ndarray) -> float:
    """Median nearest-neighbour distance of the (m, d) `points` of the table `index` (0.0
    with no edge): a point's nearest neighbour is one of its Delaunay edges, the one that
    enters first (its enter is half its length; no other edge enters earlier), and edge rows
    ascend by enter, so it is the point's lowest edge row (weighted points: the edge that
    enters first). Points in no edge are left out."""
    edges = index.simplices(1)
    if len(edges) == 0:
        return 0.0
    first = index.first_cofaces(1)
    ends = edges[first[first < len(edges)]]
    points = np.asarray(points, dtype=np.float64)
    return float(np.median(np.linalg.norm(points[ends[:, 0]] - points[ends[:, 1]], axis=1)))


def opening_alpha_of(index: TableIndex, points: np.ndarray) -> float:
    """`opening_alpha` of the table `index` of a complex with (m, d) `points`, at most
    MAX_SPACINGS point spacings; the largest critical alpha (the whole triangulation) when
    nothing smaller qualifies.

    Ties between edges of equal first-triangle enter may merge in another order than
    `opening_alpha`'s, which changes no merge's weight of the first that reaches the share."""
    last = index.last_value()
    if len(index.level(2).enter) == 0:
        return last
    reached = reaching_alpha(len(points), *opening_forest(index, len(points)))
    return min(reached, widest_opening(index, points), last)


def widest_opening(index: TableIndex, points: np.ndarray) -> float:
    """The largest critical alpha of the table `index` within MAX_SPACINGS point spacings
    (the shape there is the one at MAX_SPACINGS spacings); inf when none is."""
    cap = MAX_SPACINGS * point_spacing(index, points)
    levels = [index.level(k).enter for k in range(0 if index.weighted else 1, index.dim + 1)]
    best = max((float(np.max(v[v <= cap], initial=-np.inf)) for v in levels),
               default=-np.inf)
    best = max(best, -np.inf if index.weighted else 0.0)
    return best if np.isfinite(best) else float("inf")

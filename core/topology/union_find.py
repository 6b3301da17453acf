"""Union-find over a filtration, done by scipy's compiled graph routines instead of Python loops.

`ordered_forest` gives the edges that merge components when edges arrive in a given order
(Kruskal's filter), `spanning_forest` the same by weight, `rank_forest` for edges that arrive
with the later of their nodes (solid components). `younger_roots` applies the
elder rule to those merges (which component dies at each one) by divide and conquer over the
arrival order, one `connected_components` call per halving level: O(m log m) in C plus numpy.
"""

from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix, csr_matrix
from scipy.sparse.csgraph import connected_components, minimum_spanning_tree


def spanning_forest(n_nodes: int, u: np.ndarray, v: np.ndarray, weight: np.ndarray) -> tuple:
    """A minimum spanning forest of edges (u, v), edges by weight (ties in the given order).

    For every w, its edges of weight <= w span the subgraph of all edges of weight <= w, so
    they count the merges of a filtration in which edges arrive by weight.
    Returns (weights, a, b): (f,) float64 ascending and (f,) int64 end nodes of each edge.
    """
    weight = np.asarray(weight, dtype=np.float64)
    order = np.argsort(weight, kind="stable")
    joined = order[ordered_forest(n_nodes, np.asarray(u)[order], np.asarray(v)[order])]
    return (weight[joined], np.asarray(u, dtype=np.int64)[joined],
            np.asarray(v, dtype=np.int64)[joined])


def ordered_forest(n_nodes: int, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """(f,) int64 ascending positions of the edges (u, v), taken in the given order, that
    join two components (Kruskal's filter; the same edges as a spanning forest with weights
    1, 2, 3, ...). Any pairs allowed, self-loops and repeats included.

    scipy's Kruskal argsorts its weights, the slow part on millions of edges in random
    order. Here edge i becomes a node n + i whose row holds its two ends: the lower one with
    weight 2i + 1 (always joining: the node is new) and the higher with weight 2i + 2 (joining
    exactly when the ends are still apart). Row by row the weights already ascend, so the
    graph needs no conversion and that sort is one linear pass.
    """
    u, v = np.asarray(u), np.asarray(v)
    live = np.flatnonzero(u != v)  # a self-loop never joins
    k = len(live)
    if k == 0:
        return np.zeros(0, dtype=np.int64)
    size = n_nodes + k
    index = np.int32 if 2 * k + 1 < 2**31 and size < 2**31 else np.int64
    ends = np.empty((k, 2), dtype=index)
    np.minimum(u[live], v[live], out=ends[:, 0], casting="unsafe")
    np.maximum(u[live], v[live], out=ends[:, 1], casting="unsafe")
    indptr = np.zeros(size + 1, dtype=index)
    indptr[n_nodes + 1:] = np.arange(2, 2 * k + 1, 2, dtype=index)
    graph = csr_matrix((np.arange(1.0, 2.0 * k + 1.0), ends.ravel(), indptr), shape=(size, size))
    del ends, indptr
    weights = minimum_spanning_tree(graph, overwrite=True).data  # in row order: edge order
    closing = weights[weights % 2.0 == 0.0]
    return live[(closing * 0.5).astype(np.int64) - 1]


def rank_forest(rank: np.ndarray, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """(f,) int64 ascending ranks at which an edge (u, v) first joins two components when
    each edge arrives with the later of its two nodes: node x arrives at rank[x] (1..n,
    distinct). Pairs must be distinct."""
    ru, rv = rank[u].astype(np.int64) - 1, rank[v].astype(np.int64) - 1
    return later_forest(len(rank), np.maximum(ru, rv), np.minimum(ru, rv)) + 1


def later_forest(n_nodes: int, later: np.ndarray, earlier: np.ndarray) -> np.ndarray:
    """(f,) int64 ascending `later` values of the edges (later, earlier), later > earlier,
    that first join two components when each edge arrives with its later node (nodes in
    index order). Laid out with the later node as row, scipy's Kruskal gets its weights
    already in order (no random-order sort)."""
    graph = coo_matrix(((later + 1).astype(np.float64), (later, earlier)),
                       shape=(n_nodes, n_nodes))
    tree = minimum_spanning_tree(graph.tocsr(), overwrite=True)
    return tree.data.astype(np.int64) - 1  # in row order: ascending


def younger_roots(key: np.ndarray, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Elder rule: for forest edges merged in the given order, the key of the component that dies.

    key: (n,) int64, distinct, larger = older (born earlier). u, v: (m,) node ids of forest edges
    in merge order (no edge may close a cycle). Returns (m,) int64: min over the two merging
    components of their largest key. Each halving level keeps, for every block of edges, the node
    labels of the components formed by all earlier edges, so the recursion is flat numpy work.
    """
    labels_u = np.asarray(u, dtype=np.int64).copy()
    labels_v = np.asarray(v, dtype=np.int64).copy()
    best = np.asarray(key, dtype=np.int64).copy()
    position = np.arange(len(labels_u), dtype=np.int64)
    span = 1 << max(0, int(len(labels_u) - 1).bit_length())
    while span > 1:
        half = span >> 1
        right = (position & half) != 0
        labels_u, labels_v, best = _merge_left_halves(labels_u, labels_v, best, right)
        span = half
    if len(labels_u) == 0:
        return np.zeros(0, dtype=np.int64)
    return np.minimum(best[labels_u], best[labels_v])


def _merge_left_halves(lu: np.ndarray, lv: np.ndarray, best: np.ndarray, right: np.ndarray):
    """Relabel right-half edges by the components their block's left-half edges form; compact."""
    size = len(best)
    left = ~right
    graph = coo_matrix(
        (np.ones(int(left.sum()), dtype=np.int8), (lu[left], lv[left])), shape=(size, size)
    )
    n_comp, comp = connected_components(graph, directed=False)
    merged = np.full(n_comp, -1, dtype=np.int64)
    np.maximum.at(merged, comp, best)
    lu = np.where(right, comp[lu] + size, lu)
    lv = np.where(right, comp[lv] + size, lv)
    best = np.concatenate([best, merged])
    used = np.zeros(len(best), dtype=bool)
    used[lu] = True
    used[lv] = True
    remap = np.cumsum(used) - 1
    return remap[lu], remap[lv], best[used]

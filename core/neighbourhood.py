"""Per-point local geometry from the k nearest neighbours: spacing and oriented PCA normals.

The two alpha modes of Teichmann & Capps (IEEE Vis 1998) need them: density scaling divides
radii by the local spacing, anisotropy compresses the alpha ball along the surface normal.
"""

from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import breadth_first_order, connected_components, minimum_spanning_tree
from scipy.spatial import cKDTree

from .parallel import halves

#: Weight added to every edge of the orientation graph: csgraph drops explicit zeros, and two
#: parallel normals (weight 0) must still be joined.
_EDGE_FLOOR = 1e-9


def neighbours(points: np.ndarray, k: int) -> tuple[np.ndarray, np.ndarray]:
    """Distances and ids (m, k') of each point's k' = min(k, m-1) nearest other points, nearest
    first; the points are unique, so a point's own row is column 0 of the query and dropped."""
    k = min(k, len(points) - 1)
    dist, ids = cKDTree(points).query(points, k=k + 1, workers=2)
    return dist[:, 1:], ids[:, 1:]


def spacing(dist: np.ndarray) -> np.ndarray:
    """(m,) float64 local spacing: the distance to the k-th nearest neighbour (last column)."""
    return np.ascontiguousarray(dist[:, -1])


def pca_normals(points: np.ndarray, ids: np.ndarray) -> np.ndarray:
    """(m, d) unit normals: the least-variance direction of each point with its neighbours
    (batched eigh of the covariances, in halves: the gathers are memory-bound)."""
    out = np.empty_like(points)

    def part(start: int, stop: int) -> None:
        group = np.concatenate((points[start:stop, None, :], points[ids[start:stop]]), axis=1)
        group -= group.mean(axis=1, keepdims=True)
        cov = np.einsum("mki,mkj->mij", group, group)
        _, vectors = np.linalg.eigh(cov)  # eigenvalues ascending: column 0 is the normal
        out[start:stop] = vectors[:, :, 0]

    width = max(ids.shape[1], 1)  # split by gathered neighbours, cut between whole rows
    halves(lambda start, stop: part(start // width, stop // width), len(ids) * width)
    return out


def orient(points: np.ndarray, normals: np.ndarray, ids: np.ndarray) -> np.ndarray:
    """Flip normals so neighbours agree (Hoppe et al. 1992): signs propagate along a minimum
    spanning tree of the k-nearest-neighbour graph weighted by 1 - |n_i . n_j|; each tree's
    root faces away from the centroid of its points."""
    m, k = ids.shape
    rows = np.repeat(np.arange(m), k)
    cols = ids.ravel()
    dots = np.einsum("md,md->m", normals[rows], normals[cols])
    graph = coo_matrix((1.0 - np.abs(dots) + _EDGE_FLOOR, (rows, cols)), shape=(m, m))
    tree = minimum_spanning_tree(graph.tocsr())
    tree = (tree + tree.T).tocsr()
    _, part = connected_components(tree, directed=False)
    roots = np.unique(part, return_index=True)[1]
    # One search from an extra node joined to every tree's root reaches all trees at once.
    link = coo_matrix((np.ones(len(roots)), (np.full(len(roots), m), roots)), shape=(m + 1,) * 2)
    joined = (_grown(tree, m + 1) + link + link.T).tocsr()
    _, pred = breadth_first_order(joined, m, directed=False)
    parent = pred[:m].copy()
    parent[roots] = roots
    flip = np.einsum("md,md->m", normals, normals[parent]) < 0  # relative to the parent
    centres = np.stack([np.bincount(part, weights=col) for col in points.T], axis=1)
    centres /= np.bincount(part)[:, None]
    away = points[roots] - centres[part[roots]]
    flip[roots] = np.einsum("md,md->m", normals[roots], away) < 0
    return np.where(_path_parity(parent, flip)[:, None], -normals, normals)


def _grown(matrix, size: int):
    """`matrix` as a (size, size) sparse matrix (extra empty rows and columns)."""
    coo = matrix.tocoo()
    return coo_matrix((coo.data, (coo.row, coo.col)), shape=(size, size))


def _path_parity(parent: np.ndarray, flip: np.ndarray) -> np.ndarray:
    """(m,) bool XOR of `flip` over each node's path up to its root (inclusive), where roots
    are their own parent: pointer jumping, log2(depth) vectorized passes."""
    acc, jump = flip.copy(), parent.copy()  # acc[i]: XOR over the path [i, jump[i])
    is_root = parent == np.arange(len(parent))
    while True:
        active = ~is_root[jump]
        if not active.any():
            break
        acc = acc ^ (active & acc[jump])
        jump = np.where(active, jump[jump], jump)
    return np.where(is_root, acc, acc ^ acc[jump])

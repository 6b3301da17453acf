"""Per-point local geometry from the k nearest neighbours: spacing and oriented PCA normals.

The two alpha modes of Teichmann & Capps (IEEE Vis 1998) need them: density scaling divides
radii by the local spacing, anisotropy compresses the alpha ball along the surface normal.
"""

from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix, csr_matrix
from scipy.sparse.csgraph import breadth_first_order, connected_components, minimum_spanning_tree
from scipy.spatial import cKDTree

from core.parallel import halves

#: Weight added to every edge of the orientation graph: csgraph drops explicit zeros, and two
#: parallel normals (weight 0) must still be joined.
_EDGE_FLOOR = 1e-9
#: The closed-form normal serves covariances whose two lowest eigenvalues are apart by more
#: than this fraction of their spread (the normal's error is rounding / gap); eigh the rest.
_EIGEN_GAP = 1e-3
_PCA_ROWS = 1 << 14  #: points per chunk of the PCA (their neighbourhoods stay in the cache)


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
    (least_axes of the covariances, in halves and chunks: the gathers are memory-bound)."""
    out = np.empty_like(points)

    def part(start: int, stop: int) -> None:
        for lo in range(start, stop, _PCA_ROWS):
            hi = min(lo + _PCA_ROWS, stop)
            rows = np.empty((hi - lo, ids.shape[1] + 1), dtype=np.intp)
            rows[:, 0] = np.arange(lo, hi)
            rows[:, 1:] = ids[lo:hi]
            group = np.take(points, rows, axis=0)  # (n, k+1, d): each point and its neighbours
            group -= group.mean(axis=1, keepdims=True)
            out[lo:hi] = least_axes(np.matmul(group.transpose(0, 2, 1), group))

    width = max(ids.shape[1], 1)  # split by gathered neighbours, cut between whole rows
    halves(lambda start, stop: part(start // width, stop // width), len(ids) * width)
    return out


def least_axes(cov: np.ndarray) -> np.ndarray:
    """(m, d) unit eigenvectors of the smallest eigenvalues of (m, d, d) symmetric matrices.
    3D: the closed form (trigonometric eigenvalues, the longest cross product of two rows of
    cov - lowest I), an order of magnitude faster than LAPACK's batched eigh, which settles
    the matrices whose lowest eigenvalue is not well apart from the middle one."""
    if cov.shape[1] != 3:
        return np.linalg.eigh(cov)[1][:, :, 0]  # eigenvalues ascending: column 0
    a = {(i, j): np.ascontiguousarray(cov[:, i, j]) for i in range(3) for j in range(i, 3)}
    shift = (a[0, 0] + a[1, 1] + a[2, 2]) / 3.0
    b00, b11, b22 = a[0, 0] - shift, a[1, 1] - shift, a[2, 2] - shift
    a01, a02, a12 = a[0, 1], a[0, 2], a[1, 2]
    spread = np.sqrt((b00 * b00 + b11 * b11 + b22 * b22
                      + 2.0 * (a01 * a01 + a02 * a02 + a12 * a12)) / 6.0)
    det = (b00 * (b11 * b22 - a12 * a12) - a01 * (a01 * b22 - a12 * a02)
           + a02 * (a01 * a12 - b11 * a02))
    safe = np.where(spread > 0, spread, 1.0)
    angle = np.arccos(np.clip(det / (2.0 * safe**3), -1.0, 1.0)) / 3.0
    low = shift + 2.0 * spread * np.cos(angle + 2.0 * np.pi / 3.0)
    high = shift + 2.0 * spread * np.cos(angle)
    rows = [[a[0, 0] - low, a01, a02], [a01, a[1, 1] - low, a12], [a02, a12, a[2, 2] - low]]
    best, best_sq = None, None
    for u, w in ((0, 1), (0, 2), (1, 2)):
        r, t = rows[u], rows[w]
        vec = [r[1] * t[2] - r[2] * t[1], r[2] * t[0] - r[0] * t[2], r[0] * t[1] - r[1] * t[0]]
        sq = vec[0] * vec[0] + vec[1] * vec[1] + vec[2] * vec[2]
        if best is None:
            best, best_sq = vec, sq
            continue
        longer = sq > best_sq
        best = [np.where(longer, v, b) for v, b in zip(vec, best, strict=True)]
        best_sq = np.maximum(best_sq, sq)
    out = np.stack(best, axis=1) / np.sqrt(np.where(best_sq > 0, best_sq, 1.0))[:, None]
    poor = ~(3.0 * shift - low - high - low > _EIGEN_GAP * (high - low))  # NaN: poor too
    if poor.any():
        out[poor] = np.linalg.eigh(cov[poor])[1][:, :, 0]
    return out


def orient(points: np.ndarray, normals: np.ndarray, ids: np.ndarray) -> np.ndarray:
    """Flip normals so neighbours agree (Hoppe et al. 1992): signs propagate along a minimum
    spanning tree of the k-nearest-neighbour graph weighted by 1 - |n_i . n_j|; each tree's
    root faces away from the centroid of its points."""
    m = len(ids)
    tree = minimum_spanning_tree(orientation_graph(normals, ids))
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


def orientation_graph(normals: np.ndarray, ids: np.ndarray) -> csr_matrix:
    """The (m, m) graph joining each point to its neighbours `ids` (m, k), weighted by
    1 - |n_i . n_j| + _EDGE_FLOOR, in canonical CSR form (columns ascending in each row, as
    a COO matrix's tocsr gives it, so the spanning tree breaks ties the same way), built
    column by column: no (m k, d) copies of the normals."""
    m, k = ids.shape
    weights = np.empty((m, k))
    for c in range(k):
        dots = np.einsum("md,md->m", normals, np.take(normals, ids[:, c], axis=0))
        np.subtract(1.0, np.abs(dots), out=weights[:, c])
        weights[:, c] += _EDGE_FLOOR
    order = np.argsort(ids, axis=1)
    columns = np.take_along_axis(ids, order, axis=1).astype(np.int32)
    data = np.take_along_axis(weights, order, axis=1)
    indptr = np.arange(0, m * k + 1, k, dtype=np.int32)
    return csr_matrix((data.ravel(), columns.ravel(), indptr), shape=(m, m))


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

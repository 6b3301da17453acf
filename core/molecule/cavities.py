"""Cavities: the voids of the dual complex (bounded components of its complement, b2) and
the volume of empty space each one encloses."""

from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

SAMPLES = 8_000  # Monte Carlo points per void at most, for its volume
CELL_SAMPLES = 1_000  # Monte Carlo points per cell of a void (up to SAMPLES)
MIN_HITS = 20  # empty samples wanted in a void; below, it is sampled again ...
RETRY_FACTOR = 16  # ... with this many times the samples
RETRY_BUDGET = 200_000  # in all voids together at most
NEIGHBOURS = 24  # nearest centres tested per sample (all balls in reach, or more asked)


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


def _sample_cells(corners: np.ndarray, volumes: np.ndarray, group: np.ndarray,
                  per_group: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """((Σ per_group, 3) points, their cells): per_group[g] points uniform in the union of
    the tetrahedra (t, 4, 3) of group g (cells sorted by group), in group order."""
    totals = np.bincount(group, weights=volumes)
    cum = np.cumsum(volumes)
    before = np.concatenate(([0.0], np.cumsum(totals)))[:-1]
    owner = np.repeat(np.arange(len(per_group)), per_group)
    u = before[owner] + rng.random(len(owner)) * totals[owner]
    cell = np.minimum(np.searchsorted(cum, u, side="right"), len(volumes) - 1)
    lam = rng.dirichlet(np.ones(4), size=len(owner))  # uniform barycentric coordinates
    return np.einsum("pi,pij->pj", lam, corners[cell]), cell


def _covered(x: np.ndarray, tree: cKDTree, radii: np.ndarray) -> np.ndarray:
    """(p,) bool: the points x (p, 3) lie in some ball (centres in `tree`)."""
    if len(x) == 0:
        return np.zeros(0, bool)
    reach = float(radii.max())
    dist, idx = tree.query(x, k=NEIGHBOURS, distance_upper_bound=reach)
    found = np.isfinite(dist)
    covered = (found & (dist <= radii[np.where(found, idx, 0)])).any(1)
    for i in np.flatnonzero(found[:, -1] & ~covered):  # more balls in reach than asked for
        near = np.asarray(tree.query_ball_point(x[i], reach), np.int64)
        covered[i] = bool((np.linalg.norm(tree.data[near] - x[i], axis=1) <= radii[near]).any())
    return covered


def void_volumes(labels: np.ndarray, cells: np.ndarray, centres: np.ndarray,
                 radii: np.ndarray, cell_volumes: np.ndarray, samples: int = SAMPLES,
                 seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """((n_voids,), (n_voids,)) float64 empty volume of each void (its cells minus the balls)
    and the standard error of that estimate.

    Monte Carlo with CELL_SAMPLES points per cell, at most `samples` per void, uniform in the
    void's cells (volumes `cell_volumes` (n_cells,)), seeded: the same input gives the same
    figures. Voids where fewer than MIN_HITS points were empty (tiny voids in big cells) are
    sampled again with RETRY_FACTOR times as many points (at most RETRY_BUDGET in all).
    """
    n_voids = int(labels.max()) + 1 if len(labels) else 0
    if n_voids == 0:
        return np.zeros(0), np.zeros(0)
    mine = np.flatnonzero(labels >= 0)
    mine = mine[np.argsort(labels[mine], kind="stable")]
    group, vols = labels[mine], cell_volumes[mine]
    vertices = cells[mine]
    corners, tree = centres[vertices], cKDTree(centres)
    rng = np.random.default_rng(seed)
    per_group = np.minimum(CELL_SAMPLES * np.bincount(group, minlength=n_voids), samples)
    hits = _empty_hits(vertices, corners, vols, group, per_group, tree, radii, rng)
    retry = np.flatnonzero(hits < MIN_HITS)
    if len(retry):
        more = np.zeros(n_voids, np.int64)
        more[retry] = min(samples * RETRY_FACTOR, RETRY_BUDGET // len(retry))
        hits = hits + _empty_hits(vertices, corners, vols, group, more, tree, radii, rng)
        per_group = per_group + more
    p = hits / per_group
    total = np.bincount(group, weights=vols, minlength=n_voids)
    return p * total, total * np.sqrt(np.maximum(p * (1 - p), 1 / per_group) / per_group)


def _empty_hits(vertices, corners, vols, group, per_group, tree, radii, rng) -> np.ndarray:
    """(n_voids,) how many of per_group[g] uniform samples in void g's cells (vertex rows
    (t, 4), corners (t, 4, 3)) are empty.

    A sample inside one of its cell's four vertex balls (most are) needs no tree query."""
    x, cell = _sample_cells(corners, vols, group, per_group, rng)
    vertex_r2 = radii[vertices] ** 2  # (t, 4)
    d2 = ((x[:, None, :] - corners[cell]) ** 2).sum(-1)
    empty = ~(d2 <= vertex_r2[cell]).any(1)
    empty[empty] = ~_covered(x[empty], tree, radii)
    return np.bincount(np.repeat(np.arange(len(per_group)), per_group), weights=empty,
                       minlength=len(per_group))


def cavity_cells(ac, alpha2: float = 0.0) -> np.ndarray:
    """(k,) int64 rows of ac.simplices(3) in the voids of a 3D complex at alpha² (the cells
    the window highlights as cavities)."""
    labels = void_cells(ac.intervals_sq(3)[:, 0] > alpha2, ac.facet_cells(),
                        ac.intervals_sq(2)[:, 0] > alpha2)
    return np.flatnonzero(labels >= 0)

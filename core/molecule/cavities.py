"""Cavities: the voids of the dual complex (bounded components of its complement, b2) and
the volume of empty space each one encloses."""

from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

SAMPLES = 40_000  # Monte Carlo points per void for its volume


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


def _sample_cells(corners: np.ndarray, volumes: np.ndarray, n: int,
                  rng: np.random.Generator) -> np.ndarray:
    """(n, 3) points uniform in the union of the tetrahedra (t, 4, 3) of the given volumes."""
    cell = rng.choice(len(corners), size=n, p=volumes / volumes.sum())
    lam = rng.dirichlet(np.ones(4), size=n)  # uniform barycentric coordinates
    return np.einsum("pi,pij->pj", lam, corners[cell])


def _covered(x: np.ndarray, centres: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """(p,) bool: the points x (p, 3) lie in some ball."""
    lo, hi = x.min(0), x.max(0)
    near = np.linalg.norm(np.clip(centres, lo, hi) - centres, axis=1) < radii
    covered = np.zeros(len(x), bool)
    hits = cKDTree(x).query_ball_point(centres[near], radii[near], return_sorted=False)
    if len(hits):
        covered[np.concatenate([np.asarray(h, np.int64) for h in hits])] = True
    return covered


def void_volumes(labels: np.ndarray, cells: np.ndarray, centres: np.ndarray,
                 radii: np.ndarray, cell_volumes: np.ndarray, samples: int = SAMPLES,
                 seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """((n_voids,), (n_voids,)) float64 empty volume of each void (its cells minus the balls)
    and the standard error of that estimate.

    Monte Carlo with `samples` points uniform in the void's cells (volumes `cell_volumes`
    (n_cells,)), seeded: the same input gives the same figures.
    """
    rng = np.random.default_rng(seed)
    n_voids = int(labels.max()) + 1 if len(labels) else 0
    volume, error = np.zeros(n_voids), np.zeros(n_voids)
    for v in range(n_voids):
        mine = labels == v
        total = float(cell_volumes[mine].sum())
        x = _sample_cells(centres[cells[mine]], cell_volumes[mine], samples, rng)
        p = 1.0 - _covered(x, centres, radii).mean()
        volume[v], error[v] = p * total, total * np.sqrt(max(p * (1 - p), 1 / samples) / samples)
    return volume, error

"""Flat and folded cells of a Qhull triangulation: cells whose volume is rounding noise (a
cospherical or exactly flat group) enter with their neighbours, and a fold's thinner cell
counts as flat."""

from __future__ import annotations

import numpy as np

from core.geometry.circumspheres import edge_vectors
from core.parallel import slot_of, take
from core.tolerances import FOLD_CANDIDATE_RTOL, ILL_CONDITIONED_RTOL


def delay_flat_cells(enter: np.ndarray, flat: np.ndarray, neighbors: np.ndarray) -> None:
    """Let flat cells (zero volume, from cospherical points) enter with their last neighbour.

    Qhull fills a cospherical group with some flat cells; exact triangulations have none. A
    flat cell entering before its neighbours would show a zero-thickness solid with arbitrary
    orientation; entering with them it only closes the group, as the exact complex does.
    """
    ids = np.flatnonzero(flat)
    while len(ids):
        around = neighbors[ids]
        later = np.where(around >= 0, enter[np.maximum(around, 0)], -np.inf).max(axis=1)
        grow = later > enter[ids]
        if not grow.any():
            return
        enter[ids[grow]] = later[grow]
        ids = ids[grow]


def thin_pairs(neighbors: np.ndarray, thin: np.ndarray, flat: np.ndarray
               ) -> tuple[np.ndarray, ...]:
    """Each pair of neighbouring non-flat cells with a thin one once, as (t, i, u, j): cell
    t's neighbour opposite its vertex i is u, whose vertex j is opposite t (t < u), in no
    particular order. Read from the thin cells' rows only."""
    width = neighbors.shape[1]
    rows = np.flatnonzero(thin)
    a = np.repeat(rows, width)
    b = take(neighbors, rows).ravel().astype(np.int64)
    slot = np.tile(np.arange(width), len(rows))
    keep = b >= 0
    keep[keep] = ~flat[b[keep]]
    keep &= ~thin[np.maximum(b, 0)] | (a < b)  # two thin cells: their pair once
    a, b, slot = a[keep], b[keep], slot[keep]
    other = slot_of(neighbors, b, a)
    low = a < b
    t, u = np.where(low, a, b), np.where(low, b, a)
    return t, np.where(low, slot, other), u, np.where(low, other, slot)


def folded_cells(points: np.ndarray, cells: np.ndarray, neighbors: np.ndarray, det: np.ndarray,
                 flat: np.ndarray) -> np.ndarray:
    """(n,) bool: non-flat cells on a fold, i.e. on the same side of a facet as a non-flat
    neighbour.

    Qhull fills exactly flat groups (decimal lattices) with cells whose float64 volume is
    rounding noise; two such cells may then overlap across their shared facet. Their signs
    are noise, so they are flat: the thinner of each pair (both if both ill-conditioned).
    Only pairs with a nearly flat cell are examined (a fold needs one).
    """
    n = len(cells)
    extent = float(np.ptp(points, axis=0).max())
    thin = (np.abs(det) <= FOLD_CANDIDATE_RTOL * extent ** points.shape[1]) & ~flat
    if not thin.any():
        return np.zeros(n, dtype=bool)
    t, i, u, j = thin_pairs(neighbors, thin, flat)
    # facets listed in ascending vertex order: opposite sides <=> parities of i+j and of
    # the two signs differ
    fold = ((i + j) % 2 == 1) == ((det[t] < 0) ^ (det[u] < 0))
    t, u = t[fold], u[fold]
    ids = np.unique(np.concatenate((t, u)))
    vec = edge_vectors(points, cells[ids])
    scale = np.sqrt(np.prod(np.einsum("nid,nid->ni", vec, vec), axis=1))
    shape = np.zeros(n)
    shape[ids] = np.abs(det[ids]) / np.where(scale > 0, scale, 1.0)
    thin_t = shape[t] <= shape[u]
    both = (shape[t] <= ILL_CONDITIONED_RTOL) & (shape[u] <= ILL_CONDITIONED_RTOL)
    out = np.zeros(n, dtype=bool)
    out[t[thin_t | both]] = True
    out[u[~thin_t | both]] = True
    return out

"""Closed boundary rings of a 2D shape from its oriented REGULAR edges (shape on the left).

At a vertex where the shape touches itself, each incoming edge continues along the outgoing
edge met first when turning clockwise, so a ring follows one wedge of the shape and rings
never cross. Ring order comes from pointer jumping, not a Python walk.
"""

from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components


def successors(points: np.ndarray, edges: np.ndarray) -> np.ndarray:
    """(r,) int64: the edge that follows each oriented edge (a, b) around its ring."""
    tail, head = edges[:, 0].astype(np.int64), edges[:, 1].astype(np.int64)
    out_angle = _angle(points[head] - points[tail])
    in_angle = _angle(points[tail] - points[head])  # the incoming edge seen from its head
    order = np.lexsort((out_angle, tail))
    key_tail, key_angle = tail[order], out_angle[order]
    first = np.searchsorted(key_tail, head, side="left")
    last = np.searchsorted(key_tail, head, side="right") - 1
    composite = key_tail.astype(np.float64) * 8.0 + key_angle  # angles are below 2 pi < 8
    below = np.searchsorted(composite, head * 8.0 + in_angle, side="left") - 1
    pos = np.where(below >= first, below, last)  # nearest clockwise, else wrap around
    return order[pos]


def _angle(vec: np.ndarray) -> np.ndarray:
    """Direction angle in [0, 2 pi)."""
    return np.mod(np.arctan2(vec[:, 1], vec[:, 0]), 2 * np.pi)


def ring_order(nxt: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Edge ids grouped by ring and in walking order, and each ring's start offset."""
    n = len(nxt)
    ring = connected_components(coo_matrix((np.ones(n), (np.arange(n), nxt)), shape=(n, n)),
                                directed=True, connection="weak")[1]
    start = np.full(ring.max() + 1, n, dtype=np.int64)
    np.minimum.at(start, ring, np.arange(n))
    is_start = np.zeros(n, dtype=bool)
    is_start[start] = True
    dist = _distance_from_start(nxt, is_start)
    order = np.lexsort((dist, ring))
    offsets = np.flatnonzero(np.concatenate([[True], ring[order][1:] != ring[order][:-1]]))
    return order, offsets


def _distance_from_start(nxt: np.ndarray, is_start: np.ndarray) -> np.ndarray:
    """(n,) steps from the ring's start edge to each edge, by pointer doubling."""
    n = len(nxt)
    prev = np.empty(n, dtype=np.int64)
    prev[nxt] = np.arange(n)
    step = np.where(is_start, -1, prev)  # pointer to the predecessor, cut at the start
    dist = (step >= 0).astype(np.int64)
    while np.any(step >= 0):
        live = step >= 0
        target = step[live]
        dist[live] += dist[target]
        step[live] = step[target]
    return dist

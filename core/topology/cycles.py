"""Edges that can never join two components, found from the triangulation's own short cycles,
so that the forests' union-find (core/topology/union_find.py) sees only the edges that might.

A forest taken in a fixed order keeps an edge only when its ends are still apart, and dropping
an edge whose ends are already joined when it comes changes no other edge's fate: the forest
stays the same, bit for bit. Two kinds of cycle give such edges for free:
- a triangle: the last of its three edges closes the path of the other two (vertex graph);
- the ring of cells around an inner ridge (an edge in 3D, a vertex in 2D), joined through the
  facets that hold the ridge: the last of those facets closes the ring (the complement's dual
  graph, facets in decreasing alpha).
On a scan about four edges in five and half the facets drop out.
"""

from __future__ import annotations

import numpy as np


def open_edges(face_ids: np.ndarray, n_edges: int) -> np.ndarray:
    """(e,) int64 ascending edge rows that are not the highest edge row of any triangle.

    face_ids: (t, 3) int edge rows of every triangle. With edges taken in row order, the
    highest edge of a triangle always finds its ends joined by the other two."""
    closing = np.zeros(n_edges, dtype=bool)
    closing[face_ids.max(axis=1)] = True
    return np.flatnonzero(~closing)


def inner_ridges(ridge_ids: np.ndarray, facet_cells: np.ndarray, n_ridges: int) -> np.ndarray:
    """(n_ridges,) bool: ridges on no hull facet, so the cells around them close a ring.

    ridge_ids: (f, dim) int ridge rows of every facet; facet_cells: (f, 2), -1 = outside."""
    hull = (facet_cells < 0).any(axis=1)
    inner = np.ones(n_ridges, dtype=bool)
    inner[ridge_ids[hull].ravel()] = False
    return inner


def ring_closers(first_facet: np.ndarray, inner: np.ndarray, n_facets: int) -> np.ndarray:
    """(n_facets,) bool: facets that come last around some inner ridge when facets arrive in
    decreasing row order (the complement's dual graph): the lowest facet row of the ring."""
    closing = np.zeros(n_facets + 1, dtype=bool)
    closing[first_facet[inner]] = True
    return closing[:n_facets]

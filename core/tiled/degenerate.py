"""A tile whose points make no complex of their own (one point, or all on one line): its
owned shape at alpha, for classic (unweighted) points.

Every point of the whole set within the margin of the core is in the tile, so if the tile is
a line, the complex near the core is that line's: the vertices, and the edges between
neighbours along the line whose half length is at most alpha (their smallest sphere is then
empty and small enough; any other pair has a point of the line inside). Nothing is interior
and no edge is a face of a member triangle.
"""

from __future__ import annotations

import numpy as np

from core.build.points import merge_duplicates
from core.tiled.result import TileResult, global_ids


def _radius(at: dict) -> float:
    """The alpha radius of `at` ({"alpha": R} or {"alpha2": A2}; below zero: no edge)."""
    if "alpha2" in at:
        a2 = float(at["alpha2"])
        return float(np.sqrt(a2)) if a2 >= 0 else -1.0
    return float(at["alpha"])


def line_tile(rows: np.ndarray, coords: np.ndarray, in_core: np.ndarray, at: dict, dim: int):
    """core.tiled.tile.TileResult of a tile of classic points on one line (or one point)."""
    unique, index = merge_duplicates(np.asarray(coords, dtype=np.float64))
    ids = global_ids(index, rows, len(unique))
    core_point = np.zeros(len(unique), dtype=bool)
    core_point[index[in_core]] = True
    edges, half = _line_edges(unique)
    member = half <= _radius(at)
    edges, half = edges[member], half[member]
    lowest = np.where(ids[edges[:, 0]] < ids[edges[:, 1]], edges[:, 0], edges[:, 1])
    keep = core_point[lowest]
    edges, half = edges[keep], half[keep]
    degree = np.zeros(len(unique), dtype=np.int64)
    np.add.at(degree, edges.ravel(), 1)
    verts = np.flatnonzero(core_point)
    vertex_reg = np.full(len(unique), np.nan)
    np.fmin.at(vertex_reg, edges.ravel(), np.repeat(half, 2))
    simplices = [np.sort(ids[verts])[:, None], np.sort(ids[edges], axis=1)]
    order = np.argsort(ids[verts])
    classes = [np.where(degree[verts] > 0, 2, 1).astype(np.int8)[order],
               np.ones(len(edges), dtype=np.int8)]
    intervals = [np.column_stack([np.zeros(len(verts)), vertex_reg[verts],
                                  np.full(len(verts), np.nan)])[order],
                 np.column_stack([half, np.full((len(half), 2), np.nan)])]
    for k in range(2, dim + 1):
        simplices.append(np.empty((0, k + 1), dtype=np.int64))
        classes.append(np.empty(0, dtype=np.int8))
        intervals.append(np.empty((0, 3)))
    used = np.unique(np.concatenate([s.ravel() for s in simplices]))
    order = np.argsort(rows)
    coords_of = np.asarray(coords)[order[np.searchsorted(rows, used, sorter=order)]]
    return TileResult(tuple(simplices), tuple(classes), tuple(intervals),
                      np.empty((0, dim), dtype=np.int64), used, coords_of, 0.0, 0.0,
                      int(np.count_nonzero(in_core)), 0)


def _line_edges(unique: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(e, 2) local ids of neighbours along the line of the points, and their half lengths."""
    if len(unique) < 2:
        return np.empty((0, 2), dtype=np.int64), np.empty(0)
    centred = unique - unique.mean(axis=0)
    direction = np.linalg.svd(centred, full_matrices=False)[2][0]
    order = np.argsort(centred @ direction, kind="stable")
    edges = np.column_stack([order[:-1], order[1:]]).astype(np.int64)
    half = 0.5 * np.linalg.norm(unique[edges[:, 1]] - unique[edges[:, 0]], axis=1)
    return edges, half

"""One tile: the alpha complex of its core points and margin, classified at alpha, and the
simplices the tile owns (their lowest global vertex id lies in its core), in global ids.

The project's own build (AlphaComplex.from_points: exact predicates, the interval table)
decides everything; this module only maps local vertices to global ids and keeps what the
tile owns. Why the kept simplices are the global ones: core.tiled.
"""

from __future__ import annotations

import numpy as np

from core.complex import AlphaComplex
from core.errors import InputError
from core.tiled.degenerate import line_tile
from core.tiled.result import TileResult, global_ids
from core.topology.signatures import facet_measures


def compute_tile(rows: np.ndarray, coords: np.ndarray, in_core: np.ndarray,
                 weights: np.ndarray | None, at: dict, dim: int) -> TileResult:
    """The owned part of the shape at `at` ({"alpha": R} or {"alpha2": A2}) of one tile:
    input `rows` (n,) int64, `coords` (n, dim) float64, `in_core` (n,) bool, `weights` (n,)
    or None; `dim` the whole set's dimension (a tile may be flatter: core.tiled)."""
    try:
        ac = AlphaComplex.from_points(coords, weights=weights)
    except InputError:
        if weights is not None and np.any(weights != 0):
            raise
        return line_tile(rows, coords, in_core, at, dim)
    ids = global_ids(np.asarray(ac.input_index), rows, len(ac.points))
    core_point = np.zeros(len(ac.points), dtype=bool)
    index = np.asarray(ac.input_index)
    core_point[index[in_core & (index >= 0)]] = True
    shape = ac.shape(**at)
    simplices, classes, intervals, measure = [], [], [], 0.0
    touched = np.zeros(len(ac.points), dtype=bool)  # local points the kept simplices use
    for k in range(dim + 1):
        s, c, iv, keep = _owned_level(ac, ids, core_point, at, shape.alpha, k, dim)
        simplices.append(s)
        classes.append(c)
        intervals.append(iv)
        if len(keep):
            touched[np.asarray(ac.simplices(k))[keep]] = True
        if k == dim == ac.dim and len(keep):
            measure = float(np.sum(np.asarray(ac.cell_measures())[keep]))
    regular, boundary = np.empty((0, dim), dtype=np.int64), 0.0
    if ac.dim == dim:  # the complex's points are the input's coordinates (not flattened)
        local = np.asarray(shape.regular_facets, dtype=np.int64)
        owned = local[_owner_in_core(ids, local, core_point)]
        regular = ids[owned]
        boundary = float(facet_measures(ac.points, owned).sum())
    used = np.sort(ids[touched])  # a mask, not np.unique of every simplex's vertices
    coords_of = input_coordinates(rows, coords, used)
    hidden = int(np.count_nonzero(in_core & (index < 0)))
    return TileResult(tuple(simplices), tuple(classes), tuple(intervals), regular, used,
                      coords_of, measure, boundary, int(np.count_nonzero(in_core)), hidden)


def _owner_in_core(ids: np.ndarray, local: np.ndarray, core_point: np.ndarray) -> np.ndarray:
    """(s,) bool: the local simplices (s, k+1) whose lowest global vertex id is a core
    point of this tile (the owner rule: each simplex is kept by exactly one tile)."""
    if len(local) == 0:
        return np.zeros(0, dtype=bool)
    lowest = np.argmin(ids[local], axis=1)
    return core_point[local[np.arange(len(local)), lowest]]


def _owned_level(ac, ids, core_point, at: dict, alpha: float, k: int, dim: int):
    """(simplices, classes, intervals, kept local rows) of the owned k-simplices in the
    complex at `at` (`alpha`: its table value); a flat tile's classes as in `dim`."""
    if k > ac.dim:
        return (np.empty((0, k + 1), np.int64), np.empty(0, np.int8),
                np.empty((0, 3)), np.empty(0, np.int64))
    cls = np.asarray(ac.classify(k=k, **at))
    members = np.flatnonzero(cls > 0)
    local = np.asarray(ac.simplices(k))[members].astype(np.int64)
    keep = _owner_in_core(ids, local, core_point)
    rows = members[keep]
    out = np.sort(ids[local[keep]], axis=1)
    iv = np.array(ac.intervals(k)[rows], dtype=np.float64)
    iv[iv > alpha] = np.nan
    c = cls[rows]
    if ac.dim < dim:  # a flat tile in 3D: nothing is interior, faces of members regular
        c = np.where(k < ac.dim, np.minimum(c, 2), 1).astype(np.int8)
        iv[:, 2] = np.nan
        if k == ac.dim:
            iv[:, 1] = np.nan
    return out, c, iv, rows


def input_coordinates(rows: np.ndarray, coords: np.ndarray, used: np.ndarray) -> np.ndarray:
    """(v, dim) the tile's own input coordinates of the global ids `used` (input rows of
    the tile), exactly as given (never rebuilt from a flat tile's plane)."""
    order = np.argsort(rows)
    return np.ascontiguousarray(coords[order[np.searchsorted(rows, used, sorter=order)]])

"""Thin big scans to a target count: a voxel grid (even coverage) or a seeded random draw."""

from __future__ import annotations

import numpy as np

from core.build.points import merge_duplicates
from core.errors import InputError

SUBSAMPLE_METHODS = ("voxel", "random")
_BISECTION_STEPS = 40


def first_unique(rows: np.ndarray) -> np.ndarray:
    """(n,) bool mask keeping the first occurrence of every exact duplicate of (n, d<=3) rows."""
    _, ids = merge_duplicates(np.asarray(rows, dtype=np.float64))
    # ids number distinct rows in order of first appearance: a row is first when its id is new
    return np.diff(np.maximum.accumulate(ids), prepend=-1) > 0


def _voxel_firsts(points: np.ndarray, size: float) -> np.ndarray:
    """Sorted indices of the first point in every occupied voxel of edge `size`."""
    cells = np.floor((points - points.min(axis=0)) / size)
    dims = cells.max(axis=0) + 1
    if float(np.prod(dims)) >= 2.0**53:  # too many voxels for one exact float key each
        return np.flatnonzero(first_unique(cells))
    key = cells @ np.cumprod(np.r_[1.0, dims[:-1]])
    return np.sort(np.unique(key, return_index=True)[1])  # first index of every voxel


def voxel_indices(points: np.ndarray, target: int) -> np.ndarray:
    """(k,) int64 indices, k <= target: one point per voxel, voxel size found by bisection."""
    extent = float(np.max(np.ptp(points, axis=0)))
    if extent == 0.0:
        return np.arange(min(1, len(points)), dtype=np.int64)
    lo, hi = 0.0, 2.0 * extent  # hi puts every point in one voxel
    best = _voxel_firsts(points, hi)
    for _ in range(_BISECTION_STEPS):
        mid = 0.5 * (lo + hi)
        if mid <= 0.0 or mid == hi:
            break
        idx = _voxel_firsts(points, mid)
        if len(idx) <= target:
            hi, best = mid, idx
            if len(idx) >= 0.99 * target:
                break
        else:
            lo = mid
    return best.astype(np.int64)


def random_indices(n: int, target: int, seed: int = 0) -> np.ndarray:
    """(target,) sorted int64 indices drawn without replacement, reproducible by seed."""
    rng = np.random.default_rng(seed)
    return np.sort(rng.choice(n, size=target, replace=False)).astype(np.int64)


def subsample_indices(
    points: np.ndarray, target: int, *, method: str = "voxel", seed: int = 0
) -> np.ndarray:
    """Indices of at most `target` rows of (n, d) `points`, by `method` ('voxel' or 'random')."""
    if target < 1:
        raise InputError(f"subsample target must be a positive count, not {target}")
    if target >= len(points):
        return np.arange(len(points), dtype=np.int64)
    if method == "voxel":
        return voxel_indices(points, target)
    if method == "random":
        return random_indices(len(points), target, seed)
    raise InputError(f"unknown subsample method {method!r}; use one of {SUBSAMPLE_METHODS}")

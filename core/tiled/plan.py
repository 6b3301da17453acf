"""Tile sizes from the point density and a memory budget, and which tiles a point belongs to.

Tiles are cubes (squares in 2D) of one side on a grid from the points' lower corner. A point
lies in the *core* of exactly one tile (floor of its grid coordinate, clipped to the grid)
and in the *margin* of every other tile whose core, grown by `margin` on each side, holds it.
Both use the same floor of shifted coordinates, so a point within `margin` of a core point
is always in that core's tile (the argument in core.tiled).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

#: Relative and absolute slack added to the margin: it covers the rounding of the shifted
#: coordinates (a few ulps), far below any point spacing that matters.
MARGIN_RTOL = 1e-6
#: Bytes of peak memory one tile point costs in a build (3D Delaunay, table and shape;
#: 2D about a third): a worker's tile of 413k points of a 20M-point noisy torus (5.4 cells a
#: point) peaked 3.9 KB a point above the worker's own 0.2 GiB (1M torus: 3.5 KB).
BYTES_PER_POINT = {2: 1200, 3: 4000}
#: Bins per axis of the density histogram a plan is made from.
HISTOGRAM_BINS = {2: 512, 3: 64}


def margin_for(alpha2: float, max_weight: float = 0.0, scale: float = 0.0) -> float:
    """The margin around a tile's core: twice the largest radius an empty (orthogonal) ball
    of a member simplex can have seen from its vertex, 2 * sqrt(alpha2 + max_weight)
    (classic points: max_weight 0, 2 * alpha), plus MARGIN_RTOL slack and 64 ulps of
    the coordinates' magnitude `scale`."""
    reach = 2.0 * math.sqrt(max(alpha2 + max_weight, 0.0))
    return reach * (1.0 + MARGIN_RTOL) + 64.0 * np.spacing(max(abs(scale), 1.0))


@dataclass(frozen=True)
class TilePlan:
    """A grid of tiles: `origin` (d,) lower corner, `side` of each tile, `shape` tiles per
    axis, and the `margin` every tile is grown by."""

    origin: tuple[float, ...]
    side: float
    shape: tuple[int, ...]
    margin: float

    @property
    def n_tiles(self) -> int:
        """Number of tiles in the grid (some may hold no point)."""
        return math.prod(self.shape)

    def _grid(self, points: np.ndarray, shift: float) -> np.ndarray:
        """(n, d) int64 grid cell of each point moved by `shift` on every axis, clipped."""
        cell = np.floor((points - np.asarray(self.origin) + shift) / self.side)
        return np.clip(cell, 0, np.asarray(self.shape) - 1).astype(np.int64)

    def core_tile(self, points: np.ndarray) -> np.ndarray:
        """(n,) int64 flat index of the tile whose core holds each point."""
        return np.ravel_multi_index(self._grid(points, 0.0).T, self.shape)

    def touching(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(rows, tiles) int64 pairs: every tile whose core grown by the margin holds the
        point `points[row]` (its own core tile included)."""
        lo = self._grid(points, -self.margin)
        hi = self._grid(points, self.margin)
        span = hi - lo + 1
        rows, tiles = [], []
        for offset in itertools.product(*(range(int(s)) for s in span.max(axis=0))):
            step = np.asarray(offset, dtype=np.int64)
            inside = np.flatnonzero((step < span).all(axis=1))
            rows.append(inside)
            tiles.append(np.ravel_multi_index((lo[inside] + step).T, self.shape))
        return np.concatenate(rows), np.concatenate(tiles)

    def members(self, points: np.ndarray, tile: int) -> tuple[np.ndarray, np.ndarray]:
        """((n,) bool, (n,) bool): which `points` `touching` pairs with `tile` (its core
        grown by the margin), and which lie in its core (the same arithmetic)."""
        index = np.asarray(np.unravel_index(tile, self.shape), dtype=np.int64)
        lo = self._grid(points, -self.margin)
        hi = self._grid(points, self.margin)
        in_tile = np.all((lo <= index) & (index <= hi), axis=1)
        return in_tile, np.all(self._grid(points, 0.0) == index, axis=1)

    def reach(self, tile: int) -> tuple[np.ndarray, np.ndarray]:
        """(lo, hi) (d,) a box holding every point `members` pairs with `tile`: its core
        grown by the margin and a rounding slack, unbounded beyond the grid's ends (points
        there are clipped into the outer tiles)."""
        lo, hi = self.box(tile)
        index = np.asarray(np.unravel_index(tile, self.shape))
        slack = self.margin + MARGIN_RTOL * self.side + 64.0 * np.spacing(
            np.abs(np.r_[lo, hi]).max())
        lo = np.where(index == 0, -np.inf, lo - slack)
        hi = np.where(index == np.asarray(self.shape) - 1, np.inf, hi + slack)
        return lo, hi

    def box(self, tile: int) -> tuple[np.ndarray, np.ndarray]:
        """(lo, hi) (d,) corners of a tile's nominal core (points beyond the grid's ends are
        clipped into its outer tiles)."""
        index = np.asarray(np.unravel_index(tile, self.shape), dtype=np.float64)
        lo = np.asarray(self.origin) + index * self.side
        return lo, lo + self.side


def histogram(points: np.ndarray, lo: np.ndarray, width: float, bins: tuple[int, ...]
              ) -> np.ndarray:
    """Counts of `points` on a grid of cubic bins of `width` from `lo` (clipped)."""
    cell = np.clip(np.floor((points - lo) / width), 0, np.asarray(bins) - 1).astype(np.int64)
    flat = np.ravel_multi_index(cell.T, bins)
    return np.bincount(flat, minlength=math.prod(bins)).reshape(bins)


def _block_max(counts: np.ndarray, total: np.ndarray, block: int, grow: int
               ) -> tuple[int, int, int]:
    """(largest core count, largest core+margin count, nonempty tiles) over tiles of
    `block` bins per axis, the margin counted as `grow` whole bins on each side (`total`:
    the counts' summed-area table)."""
    padded = np.pad(counts, [(0, (-s) % block) for s in counts.shape])
    shape = tuple(s // block for s in padded.shape)
    cores = padded.reshape([x for s in shape for x in (s, block)]).sum(
        axis=tuple(range(1, 2 * len(shape), 2)))
    index = np.argwhere(cores > 0)
    lo = np.maximum(index * block - grow, 0)
    hi = np.minimum((index + 1) * block + grow, counts.shape)
    grown = _box_sums(total, lo, hi)
    return int(cores.max()), int(grown.max(initial=0)), len(index)


def _summed_area(counts: np.ndarray) -> np.ndarray:
    """Summed-area table of `counts`, one zero row in front on every axis."""
    total = counts.astype(np.int64)
    for axis in range(counts.ndim):
        total = np.cumsum(total, axis=axis)
    return np.pad(total, [(1, 0)] * counts.ndim)


def _box_sums(total: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """(b,) sums of the counts in the boxes [lo, hi) ((b, d) bins) from their summed-area
    table `total` (inclusion-exclusion over the 2^d corners)."""
    out = np.zeros(len(lo), dtype=np.int64)
    d = lo.shape[1]
    for corner in itertools.product((0, 1), repeat=d):
        pick = np.where(np.asarray(corner, dtype=bool), hi, lo)
        out += (-1) ** (d - sum(corner)) * total[tuple(pick.T)]
    return out


def plan_tiles(lo: np.ndarray, hi: np.ndarray, counts: np.ndarray, margin: float, *,
               tile_points: int | None = None, budget_bytes: int | None = None,
               workers: int = 1) -> TilePlan:
    """The coarsest grid whose every tile core holds at most `tile_points` points and every
    tile with its margin fits `budget_bytes` (BYTES_PER_POINT), preferring at least
    `workers` nonempty tiles. `counts`: the density histogram of the points over cubic bins
    from `lo` (`histogram`, HISTOGRAM_BINS); its bin width is max(hi - lo) / HISTOGRAM_BINS."""
    dim = len(lo)
    width = _bin_width(lo, hi)
    unlimited = np.iinfo(np.int64).max
    core_limit = tile_points or unlimited
    all_limit = (budget_bytes // BYTES_PER_POINT[dim]) if budget_bytes else unlimited
    grow = math.ceil(margin / width)
    chosen = None
    total = _summed_area(counts)
    for block in range(max(counts.shape), 0, -1):
        core, widest, filled = _block_max(counts, total, block, grow)
        if core <= core_limit and widest <= all_limit:
            chosen = chosen or block
            if filled >= workers:
                chosen = block
                break
    side = width * (chosen or 1)
    if chosen is None:  # finer than one bin: assume points spread evenly inside the bins
        side *= min(1.0, (min(core_limit, all_limit) / max(int(counts.max()), 1)) ** (1 / dim))
    shape = tuple(max(1, math.ceil(float(h - lo_) / side)) for lo_, h in zip(lo, hi, strict=True))
    return TilePlan(tuple(float(x) for x in lo), float(side), shape, float(margin))


def _bin_width(lo: np.ndarray, hi: np.ndarray) -> float:
    """Side of the histogram's cubic bins: the largest extent over HISTOGRAM_BINS (a tiny
    positive width for a single point)."""
    extent = float(np.max(np.asarray(hi) - np.asarray(lo)))
    return (extent or 1.0) / HISTOGRAM_BINS[len(lo)] * (1 + 1e-12)


def histogram_shape(lo: np.ndarray, hi: np.ndarray) -> tuple[float, tuple[int, ...]]:
    """(bin width, bins per axis) of the density histogram over the box [lo, hi]."""
    width = _bin_width(lo, hi)
    bins = tuple(max(1, math.ceil(float(h - lo_) / width)) for lo_, h in zip(lo, hi, strict=True))
    return width, bins

"""Tiled shapes of points held in memory: the same tiles, tile computation and merge as the
out-of-core runner, one tile after another in this process (tests, and the reference the
runner is compared with)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.build.points import Frame, as_points, check_spread, merge_duplicates
from core.build.weights import as_weights
from core.query.alpha import table_value
from core.tiled.merge import TiledShape, merge_tiles
from core.tiled.partition import tile_groups
from core.tiled.plan import TilePlan, histogram, histogram_shape, margin_for, plan_tiles
from core.tiled.tile import compute_tile


@dataclass(frozen=True)
class Query:
    """The alpha asked for: `at` the keyword of the core's queries ({"alpha": R} or
    {"alpha2": A2}), `alpha` its table value (signed radius), `alpha2` its signed square."""

    at: dict
    alpha: float
    alpha2: float


def query(alpha: float | None = None, alpha2: float | None = None) -> Query:
    """The Query of exactly one of `alpha` (a radius) or `alpha2` (a squared radius)."""
    value = table_value(alpha, alpha2)
    if not np.isfinite(value):
        raise ValueError("a tiled shape needs a finite alpha (the margin is 2 alpha)")
    at = {"alpha": float(alpha)} if alpha2 is None else {"alpha2": float(alpha2)}
    return Query(at, value, value * abs(value) if alpha2 is None else float(alpha2))


def prepared(points: object) -> tuple[np.ndarray, Frame | None, int]:
    """(n, dim) coordinates the complex is built on (planar 3D input projected on its plane
    exactly as core.build does: the same frame of the same distinct points), the frame,
    and the input's dimension."""
    raw = as_points(points)
    unique, index = merge_duplicates(raw)
    frame = check_spread(unique)
    if frame is None:
        return raw, None, raw.shape[1]
    return ((unique - frame.origin) @ frame.basis.T)[index], frame, raw.shape[1]


def plan_for(coords: np.ndarray, margin: float, tile_points: int | None,
             budget_bytes: int | None, workers: int = 1) -> TilePlan:
    """The tile plan of points in memory (their density histogram, core.tiled.plan)."""
    lo, hi = coords.min(axis=0), coords.max(axis=0)
    width, bins = histogram_shape(lo, hi)
    return plan_tiles(lo, hi, histogram(coords, lo, width, bins), margin,
                      tile_points=tile_points, budget_bytes=budget_bytes, workers=workers)


def tiled_shape(points: object, alpha: float | None = None, *, alpha2: float | None = None,
                weights: object = None, tile_points: int | None = None,
                budget_bytes: int | None = None, plan: TilePlan | None = None
                ) -> TiledShape:
    """The shape at `alpha` (or `alpha2`) of (n, 2|3) `points` (and (n,) squared-radius
    `weights`), computed tile by tile: the same simplices per class as
    AlphaComplex.from_points(points, weights=weights).shape(alpha), in global ids.
    `tile_points` bounds the points of a tile's core, `budget_bytes` a tile's build; `plan`
    (with its margin) overrides both."""
    q = query(alpha, alpha2)
    coords, frame, ambient = prepared(points)
    w = as_weights(weights, len(coords))
    if plan is None:
        reach = margin_for(q.alpha2, 0.0 if w is None else float(w.max()),
                           float(np.abs(coords).max()))
        plan = plan_for(coords, reach, tile_points, budget_bytes)
    dim = coords.shape[1]
    results = (compute_tile(rows, coords[rows], in_core, None if w is None else w[rows],
                            q.at, dim)
               for _, rows, in_core in tile_groups(plan, coords))
    return merge_tiles(results, dim=dim, ambient_dim=ambient, frame=frame, alpha=q.alpha,
                       alpha2=q.alpha2, weighted=w is not None)

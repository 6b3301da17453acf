"""The summary of a tiled shape (core.tiled.summary): the merged shape's numbers, folded in
a tile at a time."""

from __future__ import annotations

import numpy as np
import pytest

from core import AlphaComplex
from core.tiled.memory import plan_for, prepared
from core.tiled.merge import merge_tiles
from core.tiled.partition import tile_groups
from core.tiled.plan import margin_for
from core.tiled.summary import Components, summarize_tiles
from core.tiled.tile import compute_tile


def tile_results(points: np.ndarray, alpha: float, tile_points: int,
                 weights: np.ndarray | None = None) -> list:
    coords = prepared(points)[0]
    heaviest = 0.0 if weights is None else float(weights.max())
    plan = plan_for(coords, margin_for(alpha * alpha, heaviest), tile_points, None)
    dim = coords.shape[1]
    return [compute_tile(rows, coords[rows], in_core, None if weights is None else
                         weights[rows], {"alpha": alpha}, dim)
            for _, rows, in_core in tile_groups(plan, coords)]


@pytest.mark.parametrize("dim, alpha", [(2, 0.012), (3, 0.05)])
def test_summary_is_the_merged_shapes_numbers(dim, alpha):
    """Many components crossing many tiles: the same counts, measures and components as the
    merged shape and the in-memory complex."""
    points = np.random.default_rng(8).random((3000, dim))
    results = tile_results(points, alpha, 150)
    assert len(results) >= 16
    merged = merge_tiles(iter(results), dim=dim, ambient_dim=dim, frame=None, alpha=alpha,
                         alpha2=alpha * alpha, weighted=False)
    summary = summarize_tiles((r.to_arrays() for r in results), dim=dim, ambient_dim=dim,
                              n_rows=len(points), alpha=alpha, alpha2=alpha * alpha,
                              weighted=False)
    assert summary.counts() == merged.counts()
    assert (summary.euler(), summary.betti()) == (merged.euler(), merged.betti())
    assert summary.components == merged.components == AlphaComplex.from_points(
        points).betti(alpha)[0]
    assert 1 < summary.components < len(points)
    assert summary.measure == pytest.approx(merged.measure, rel=1e-12)
    assert summary.boundary_measure == pytest.approx(merged.boundary_measure, rel=1e-12)
    assert (summary.n_points, summary.n_tiles) == (len(points), merged.n_tiles)


@pytest.mark.parametrize("dim, alpha", [(2, 0.012), (3, 0.05)])
def test_summary_of_weighted_points_and_repeated_rows(dim, alpha):
    """Weighted points, some hidden, and rows repeated (a repeat is no vertex of its own):
    the merged shape's numbers, and the in-memory complex's components and 2D holes."""
    rng = np.random.default_rng(9)
    unique = rng.random((2500, dim))
    points = np.concatenate([unique, unique[:300]])
    weights = np.concatenate([w := rng.random(2500) * (0.3 * alpha * alpha), w[:300]])
    results = tile_results(points, alpha, 150, weights)
    merged = merge_tiles(iter(results), dim=dim, ambient_dim=dim, frame=None, alpha=alpha,
                         alpha2=alpha * alpha, weighted=True)
    summary = summarize_tiles((r.to_arrays() for r in results), dim=dim, ambient_dim=dim,
                              n_rows=len(points), alpha=alpha, alpha2=alpha * alpha,
                              weighted=True)
    assert summary.hidden == merged.hidden > 0
    assert summary.counts() == merged.counts()
    betti = AlphaComplex.from_points(points, weights=weights).betti(alpha)
    assert summary.components == merged.components == betti[0] > 1
    assert summary.betti() == (list(betti) if dim == 2 else None)
    assert summary.measure == pytest.approx(merged.measure, rel=1e-12)


def test_components_join_chains_fed_in_any_order():
    """A path 0-1-...-9 fed one edge at a time from both ends, a separate pair, a lone
    vertex, and a row that is no vertex (a merged duplicate): three components."""
    joined = Components(14)
    path = [(i, i + 1) for i in range(9)]
    for edge in path[::2] + path[1::2][::-1]:
        joined.add(np.array(edge), np.array([edge]))
    joined.add(np.array([10, 11, 12]), np.array([[11, 12]]))
    assert joined.count() == 3
    assert set(joined.find(np.arange(10)).tolist()) == {0}
    assert joined.find(np.array([12]))[0] == 11


def test_counting_components_takes_no_copy_of_the_rows():
    """Counting the roots of every input row (10^8 of them in a big run) allocates a bounded
    block at a time, not several (n,) int64 arrays beside the union-find's own."""
    import tracemalloc

    n = 1 << 22
    joined = Components(n)
    joined.add(np.arange(n), np.array([[0, 1], [2, n - 1]]))
    tracemalloc.start()
    try:
        assert joined.count() == n - 2
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 2 * n  # a quarter of one (n,) int64 array

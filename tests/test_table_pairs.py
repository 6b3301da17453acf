"""The table's neighbour-pair helpers against the plain (n, w) formulations they replace."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import Delaunay

from core.build.folds import thin_pairs


def _reference(neighbors: np.ndarray, thin: np.ndarray, flat: np.ndarray) -> set:
    """(t, i, u, j) of every pair t < u of non-flat neighbours with a thin one, by masks
    over the whole (n, w) table."""
    n = len(neighbors)
    real = neighbors >= 0
    pair = real & (neighbors > np.arange(n)[:, None])
    pair &= thin[:, None] | thin[np.maximum(neighbors, 0)]
    pair &= ~flat[:, None] & ~flat[np.maximum(neighbors, 0)]
    t, i = np.nonzero(pair)
    u = neighbors[t, i]
    j = np.argmax(neighbors[u] == t[:, None], axis=1)
    return set(zip(t.tolist(), i.tolist(), u.tolist(), j.tolist(), strict=True))


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("share", [0.0, 0.05, 0.5, 1.0])
def test_thin_pairs_equal_the_whole_table_masks(dim: int, share: float) -> None:
    rng = np.random.default_rng(int(share * 100) + dim)
    neighbors = Delaunay(rng.random((400, dim))).neighbors.astype(np.int32)
    thin = rng.random(len(neighbors)) < share
    flat = ~thin & (rng.random(len(neighbors)) < 0.1)
    got = thin_pairs(neighbors, thin, flat)
    assert len(got[0]) == len(set(zip(*(a.tolist() for a in got), strict=True)))  # once each
    assert set(zip(*(a.tolist() for a in got), strict=True)) == _reference(neighbors, thin, flat)

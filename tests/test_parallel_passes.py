"""The build's and topology's split passes (core.parallel: in_chunks, take, sort, searchsorted,
reduce_segments) give exactly what the plain numpy calls give, and the table and signatures
built with every pass split (tiny thresholds and chunks) equal the ones built without."""

from __future__ import annotations

import contextlib
from unittest import mock

import numpy as np
import pytest

import core.geometry
import core.parallel
import core.table
from core.complex import AlphaComplex
from core.parallel import (
    in_chunks,
    reduce_segments,
    searchsorted,
    sort,
    take,
    together,
)


@contextlib.contextmanager
def everything_split():
    """Split every pass of more than 2 items; chunks of 7 rows."""
    with contextlib.ExitStack() as stack:
        stack.enter_context(mock.patch.object(core.parallel, "PARALLEL_ABOVE", 2))
        stack.enter_context(mock.patch.object(core.geometry, "CHUNK", 7))
        stack.enter_context(mock.patch.object(core.geometry, "CACHE_CHUNK", 7))
        stack.enter_context(mock.patch.object(core.table, "CACHE_CHUNK", 7))
        yield


def test_split_passes_equal_numpy() -> None:
    rng = np.random.default_rng(3)
    values = rng.integers(0, 50, 1001).astype(np.float64)
    ids = rng.integers(-1001, 1001, 777)
    rows = rng.random((1001, 3))
    with everything_split():
        np.testing.assert_array_equal(take(values, ids), values[ids])
        np.testing.assert_array_equal(take(rows, ids), rows[ids])
        ascending = np.sort(values)
        for side in ("left", "right"):
            np.testing.assert_array_equal(searchsorted(ascending, values, side),
                                          np.searchsorted(ascending, values, side))
        keys = rng.integers(0, 2**60, 999, dtype=np.uint64)
        mine = keys.copy()
        sort(mine)
        np.testing.assert_array_equal(mine, np.sort(keys))
        starts = np.flatnonzero(np.r_[True, rng.random(1000) < 0.2])
        for ufunc in (np.minimum, np.maximum, np.add):
            got = reduce_segments(ufunc, lambda lo, hi: values[lo:hi], starts, len(values),
                                  np.float64)
            np.testing.assert_array_equal(got, ufunc.reduceat(values, starts))
        seen = np.zeros(1001, dtype=np.int8)

        def mark(lo: int, hi: int) -> None:
            assert hi - lo <= 10 and lo % 10 == 0  # a plain loop's chunk boundaries
            seen[lo:hi] += 1

        in_chunks(mark, 1001, 10)
        together(lambda: in_chunks(mark, 1001, 10))()  # from a background job
        in_chunks(lambda lo, hi: in_chunks(mark, 1001, 10) if lo == 0 else None, 20, 10)
        assert (seen == 3).all()  # nested in the helper thread: no deadlock, nothing lost


def _everything(ac: AlphaComplex) -> dict:
    """Every table array and signature curve of a complex."""
    out = {"facet_cells": ac.facet_cells()}
    for k in range(ac.dim + 1):
        out[f"simplices{k}"] = ac.simplices(k)
        out[f"intervals{k}"] = ac.intervals(k)
        if k:
            out[f"face_ids{k}"] = ac.face_ids(k)
    sig = ac.signatures()
    for name in ("alphas", "betti", "solid_components", "measure", "boundary_measure"):
        out[name] = getattr(sig, name)
    out["opening"] = np.array([sig.opening_alpha, ac.optimal_alpha()])
    return out


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("kind", ["random", "grid", "weighted"])
def test_table_and_signatures_are_the_same_split_or_not(dim: int, kind: str) -> None:
    rng = np.random.default_rng(dim)
    points = (rng.integers(0, 6, (300, dim)).astype(float) if kind == "grid"
              else rng.random((300, dim)))
    weights = rng.random(300) * 1e-3 if kind == "weighted" else None
    plain = _everything(AlphaComplex.from_points(points, weights=weights))
    with everything_split():
        split = _everything(AlphaComplex.from_points(points, weights=weights))
    assert plain.keys() == split.keys()
    for name, array in plain.items():
        assert array.dtype == split[name].dtype, name
        np.testing.assert_array_equal(array, split[name], err_msg=name)


def test_searchsorted_ascending_searches_values_that_do_not_ascend_whole():
    from core.parallel import searchsorted_ascending

    ascending = np.arange(5.0)
    values = np.array([3.0, 1.0, 2.0, 4.5, 0.0])
    for side in ("left", "right"):
        np.testing.assert_array_equal(searchsorted_ascending(ascending, values, side, chunk=2),
                                      np.searchsorted(ascending, values, side))

"""The build's and topology's split passes (core.parallel: in_chunks, take, searchsorted,
reduce_segments) give exactly what the plain numpy calls give, and the table and signatures
built with every pass split (tiny thresholds and chunks) equal the ones built without."""

from __future__ import annotations

import contextlib
from concurrent.futures import ThreadPoolExecutor
from unittest import mock

import numpy as np
import pytest

import core.backends.gmsh
import core.build.sorting
import core.build.table_edges
import core.build.table_facets
import core.geometry.circumspheres
import core.parallel
from core.complex import AlphaComplex
from core.parallel import (
    cast,
    in_chunks,
    nonzero,
    reduce_segments,
    rows_cols,
    searchsorted,
    take,
    together,
    unsplit,
)
from core.pipeline import build_complex


@contextlib.contextmanager
def everything_split():
    """Split every pass of more than 2 items; chunks of 7 rows."""
    with contextlib.ExitStack() as stack:
        stack.enter_context(mock.patch.object(core.parallel, "PARALLEL_ABOVE", 2))
        stack.enter_context(mock.patch.object(core.build.sorting, "PARALLEL_ABOVE", 2))
        stack.enter_context(mock.patch.object(core.geometry.circumspheres, "CHUNK", 7))
        stack.enter_context(mock.patch.object(core.geometry.circumspheres, "CACHE_CHUNK", 7))
        stack.enter_context(mock.patch.object(core.build.table_facets, "CACHE_CHUNK", 7))
        stack.enter_context(mock.patch.object(core.build.table_edges, "CACHE_CHUNK", 7))
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
        with ThreadPoolExecutor(1) as outside:  # a regression fails here instead of hanging
            nested = outside.submit(lambda: together(lambda: together(lambda: 7)() + 1)())
            assert nested.result(timeout=30) == 8  # a job starting a job


def test_an_unsplit_job_runs_every_pass_in_its_own_thread() -> None:
    """Inside unsplit no pass is handed to a helper (so a job beside another never queues
    behind the other's halves), the results are the same, and the flag ends with the job."""
    import threading

    rng = np.random.default_rng(4)
    values, ids = rng.random(5000), rng.integers(0, 5000, 3000)
    with everything_split():
        threads: set[str] = set()

        def mark(lo: int, hi: int) -> None:
            threads.add(threading.current_thread().name)

        core.parallel.halves(mark, 5000, core.parallel.PASSES)
        assert len(threads) == 2  # split outside
        threads.clear()
        got = together(lambda: unsplit(lambda: (
            unsplit(lambda: None),  # a nested job leaves the outer one unsplit
            core.parallel.halves(mark, 5000, core.parallel.PASSES),
            in_chunks(mark, 5000, 100), take(values, ids))[3]))()
        assert len(threads) == 1 and next(iter(threads)).startswith("alphascoop-helper-jobs")
        np.testing.assert_array_equal(got, values[ids])
        threads.clear()
        together(lambda: core.parallel.halves(mark, 5000, core.parallel.PASSES))()
        assert len(threads) == 2  # the job's flag ended with it: the next job splits


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


@pytest.mark.parametrize("n", [0, 1, 2, 3, 7, 1001])
def test_split_nonzero_and_slots_equal_numpy(n: int) -> None:
    """Each half's hits listed and joined: the same as one np.flatnonzero, also where a
    half has no hit or every hit (a dropped or misplaced half fails)."""
    rng = np.random.default_rng(n)
    masks = {"random": rng.random((n, 4)) < 0.3, "flat": rng.random(n) < 0.5,
             "first half empty": np.arange(n)[:, None] >= n // 2 + np.zeros((1, 3), int),
             "second half empty": np.arange(n)[:, None] < n // 2 + np.zeros((1, 3), int),
             "none": np.zeros((n, 3), bool), "all": np.ones((n, 3), bool)}
    with everything_split():
        for name, mask in masks.items():
            got = nonzero(lambda lo, hi, mask=mask: mask[lo:hi], n)
            want = np.flatnonzero(mask)
            assert got.dtype == np.int64, name
            np.testing.assert_array_equal(got, want, err_msg=name)
            width = mask[0].size if n else 1
            rows, cols = rows_cols(got, width)
            np.testing.assert_array_equal(rows, want // width, err_msg=name)
            np.testing.assert_array_equal(cols, want % width, err_msg=name)
        ints = rng.integers(-5, 5, (n, 4)).astype(np.int32)
        np.testing.assert_array_equal(cast(ints, np.int64), ints.astype(np.int64))
        assert cast(ints, np.int64).dtype == np.int64


def _argsort_radii_whole(values: np.ndarray) -> np.ndarray:
    """argsort_radii in one thread and one part (the code before it was split)."""
    key = values.astype(np.float32)
    bits = key.view(np.uint32)
    if len(values) and values.min() < 0:
        bits = np.where(key < 0, ~bits, bits | np.uint32(0x80000000))
    packed = np.sort((bits.astype(np.uint64) << np.uint64(32))
                     | np.arange(len(values), dtype=np.uint64))
    order = (packed & np.uint64(0xFFFFFFFF)).astype(np.int64)
    return order[np.argsort(values[order], kind="stable")]


@pytest.mark.parametrize("n", [0, 1, 2, 5, 1000])
def test_split_argsort_radii_equals_a_stable_argsort(n: int) -> None:
    """The order is packed, unpacked and fixed in two parts cut where the float32 key
    changes: it must be np.argsort(kind="stable") exactly, with ties, negatives, inf,
    values beyond float32 and values equal in float32 only; and where the whole pass
    was no stable argsort (-0.0 beside 0.0 in a table without negatives), the same as
    that pass."""
    rng = np.random.default_rng(n)
    cases = [rng.integers(0, 9, n) * 0.25, rng.normal(size=n),
             np.where(rng.random(n) < 0.1, np.inf, rng.random(n)),
             1e39 * (1 + rng.random(n)), 1 + rng.integers(0, 3, n) * 2.0**-40]
    zeros = np.where(rng.random(n) < 0.5, -0.0, 0.0)
    with everything_split(), np.errstate(over="ignore"):
        for values in cases:
            np.testing.assert_array_equal(core.build.sorting.argsort_radii(values),
                                          np.argsort(values, kind="stable"))
        for values in [*cases, zeros]:
            np.testing.assert_array_equal(core.build.sorting.argsort_radii(values),
                                          _argsort_radii_whole(values))


def test_stable_fix_joins_its_parts_only_where_the_cut_is_sound() -> None:
    values = np.array([3.0, 1.0, 2.0, 1.0, 5.0, 4.0])
    order = np.arange(6)
    want = np.argsort(values, kind="stable")
    for cut in range(7):  # most cuts are not sound here: the parts are not ordered
        np.testing.assert_array_equal(core.build.sorting.stable_fix(values, order, cut), want)
    values = np.array([2.0, 1.0, 1.0, 5.0, 4.0, 4.0])
    np.testing.assert_array_equal(core.build.sorting.stable_fix(values, order, 3),
                                  np.argsort(values, kind="stable"))


def _table_arrays(built) -> dict:
    """Every array of a built table (levels, adjacency, measures, orders) and its info."""
    table = built.table
    out = {"facet_cells": table.facet_cells, "facet_flip": table.facet_flip,
           "cell_measure": table.cell_measure, "by_interior": table.facet_interior_order,
           "exact": np.array(table.exact_predicates), "points": built.points}
    for k, level in enumerate(table.levels):
        for name in ("simplices", "enter", "regular", "interior", "face_ids"):
            if getattr(level, name) is not None:
                out[f"{name}{k}"] = getattr(level, name)
    return out


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("backend", [
    "qhull", pytest.param("gmsh", marks=pytest.mark.skipif(
        not core.backends.gmsh.installed(), reason="the optional gmsh package is not installed"))])
def test_every_table_array_is_the_same_split_or_not(dim: int, backend: str) -> None:
    """Built with every pass split in tiny parts (the gmsh backend: its neighbour table,
    mirror columns and checks too), each table array equals the unsplit build's."""
    rng = np.random.default_rng(10 + dim)
    points = rng.random((701, dim))
    plain = build_complex(points, backend=backend)
    with everything_split():
        split = build_complex(points, backend=backend)
    assert plain.info == split.info
    a, b = _table_arrays(plain), _table_arrays(split)
    assert a.keys() == b.keys()
    for name, array in a.items():
        assert array.dtype == b[name].dtype, name
        np.testing.assert_array_equal(array, b[name], err_msg=name)


def test_edge_pass_reads_triangles_packed_or_not_the_same() -> None:
    """The edge pass's packed triangle words (vertices below WORDS_UP_TO) and its
    column reads (larger point sets) give the same table."""
    points = np.random.default_rng(5).random((500, 3))
    packed = _table_arrays(build_complex(points))
    with mock.patch.object(core.build.table_edges, "WORDS_UP_TO", 0):
        columns = _table_arrays(build_complex(points))
    for name, array in packed.items():
        np.testing.assert_array_equal(array, columns[name], err_msg=name)


@pytest.mark.parametrize("weighted", [False, True])
def test_edge_incidences_radix_sorted_as_packed(weighted: bool) -> None:
    """The edge pass's incidences sorted by the radix passes (keys of up to RADIX_KEY_BITS
    bits) are the packed sort's: the same keys, each key's triangles ascending; and the
    table, whose edge ids and attach bits then come from the radix order rather than from
    the triangles' rows, is the same."""
    rng = np.random.default_rng(6)
    points = rng.random((900, 3))
    weights = rng.uniform(0.0, 0.002, 900) if weighted else None
    built = build_complex(points, weights=weights)
    triangles = built.table.levels[2].simplices
    radix = core.build.table_edges._edge_incidences(triangles, len(built.points))
    with mock.patch.object(core.build.table_edges, "RADIX_KEY_BITS", 0):
        packed = core.build.table_edges._edge_incidences(triangles, len(built.points))
        packed_table = _table_arrays(build_complex(points, weights=weights))
    assert packed[3] is None  # the radix order, for the incidences' opposite vertices
    for ours, theirs in zip(radix[:3], packed[:3], strict=True):
        assert np.asarray(ours).dtype == np.asarray(theirs).dtype
        np.testing.assert_array_equal(ours, theirs)
    for name, array in _table_arrays(built).items():
        np.testing.assert_array_equal(array, packed_table[name], err_msg=name)


@pytest.mark.parametrize("n", [1, 2, 7, 1001])
def test_gmsh_relinked_rows_in_halves(n: int) -> None:
    """The rows of gmsh's neighbour table that the restoration changed, found in halves:
    the same as a whole-table compare, changes in either half seen."""
    from core import backends

    rng = np.random.default_rng(n)
    own = rng.integers(-1, 50, (n, 4)).astype(np.int32)
    whole = np.concatenate((own, rng.integers(-1, 50, (3, 4)).astype(np.int32)))
    whole[:n][rng.random(n) < 0.2, rng.integers(0, 4)] += 1
    whole[n - 1, 3] += 1  # a change in the last row of the second half
    out = np.ones(n + 3, dtype=bool)
    with everything_split():
        backends._relinked(whole, own, out)
    np.testing.assert_array_equal(out[:n], (whole[:n] != own).any(axis=1))
    assert out[n:].all()


def test_backend_check_counts_points_in_no_cell_in_halves() -> None:
    """The backend check marks the vertices of the cells in halves: one point left out of
    every cell is counted exactly once, whichever half its cells were in."""
    from core.backends.certify import why_not_delaunay
    from core.build.delaunay import triangulate

    points = np.random.default_rng(8).random((300, 3))
    tri = triangulate(points)
    for v in (int(tri.cells[0, 0]), int(tri.cells[-1, -1])):
        cells = np.where(tri.cells == v, (v + 1) % 300, tri.cells)
        with everything_split():
            assert why_not_delaunay(points, cells, tri.neighbors) == "1 points are in no cell"

"""core.arrays' helpers against plain Python."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from core.arrays import compact_ids, row_index, unique_sorted


@st.composite
def tables_and_rows(draw) -> tuple[np.ndarray, np.ndarray]:
    """A (t, c) table and (q, c) rows of small ids (rows repeat, in the table too), of
    either int width."""
    c = draw(st.integers(1, 4))
    size = draw(st.integers(1, 6))
    ids = st.integers(0, size - 1)
    table = draw(arrays(draw(st.sampled_from([np.int32, np.int64])),
                        (draw(st.integers(0, 40)), c), elements=ids))
    rows = draw(arrays(draw(st.sampled_from([np.int32, np.int64])),
                       (draw(st.integers(0, 40)), c), elements=ids))
    return table, rows


@settings(max_examples=300, deadline=None)
@given(tables_and_rows())
def test_row_index_is_a_dictionary_of_the_first_equal_rows(case) -> None:
    table, rows = case
    first: dict[tuple, int] = {}
    for i, row in enumerate(table.tolist()):
        first.setdefault(tuple(row), i)
    found = row_index(table, rows)
    assert found.dtype == np.int64 and found.shape == (len(rows),)
    assert found.tolist() == [first.get(tuple(row), -1) for row in rows.tolist()]


def test_row_index_picks_the_first_of_equal_rows_in_a_large_table() -> None:
    """Duplicates spread over a table larger than one sort block."""
    rng = np.random.default_rng(5)
    table = rng.integers(0, 30, (200_000, 3))
    rows = rng.integers(0, 31, (50_000, 3))
    first: dict[tuple, int] = {}
    for i, row in enumerate(map(tuple, table.tolist())):
        first.setdefault(row, i)
    assert row_index(table, rows).tolist() == [first.get(row, -1)
                                              for row in map(tuple, rows.tolist())]


INT_TYPES = [np.int8, np.uint8, np.int16, np.int32, np.uint32, np.int64, np.uint64]


@settings(max_examples=200, deadline=None)
@given(st.sampled_from(INT_TYPES).flatmap(lambda dtype: arrays(
    dtype, st.tuples(st.integers(0, 30), st.integers(1, 3)),
    elements=st.integers(int(np.iinfo(dtype).min), int(np.iinfo(dtype).max)))))
def test_unique_sorted_is_np_unique(values) -> None:
    """Every int width, extremes included, 2-D input flattened; few and many repeats."""
    for case in (values, values % 4):
        got, want = unique_sorted(case), np.unique(case)
        assert got.dtype == want.dtype and np.array_equal(got, want)


def test_unique_sorted_on_a_million_mostly_distinct_ids() -> None:
    ids = np.random.default_rng(2).integers(0, 400_000, (1_000_000, 3))
    assert np.array_equal(unique_sorted(ids), np.unique(ids))


@settings(max_examples=200, deadline=None)
@given(st.integers(1, 50).flatmap(lambda n: st.tuples(st.just(n), arrays(
    st.sampled_from([np.int32, np.int64]), st.tuples(st.integers(0, 40), st.integers(1, 3)),
    elements=st.integers(0, n - 1)))))
def test_compact_ids_is_np_unique_with_its_inverse(case) -> None:
    n, ids = case
    used, rows = compact_ids(ids, n)
    want, inverse = np.unique(ids, return_inverse=True)
    assert used.dtype == rows.dtype == np.int64 and rows.shape == ids.shape
    assert np.array_equal(used, want) and np.array_equal(rows, inverse.reshape(ids.shape))


@settings(max_examples=200, deadline=None)
@given(st.lists(st.lists(st.one_of(st.integers(-40, 40).map(lambda i: i / 8),
                                   st.just(np.inf), st.just(-np.inf)), max_size=30),
                max_size=4))
def test_unique_sorted_of_ascending_runs_is_np_unique(runs) -> None:
    """A table's levels, each ascending with ties and infinities, merged by a stable sort."""
    values = np.concatenate([np.sort(np.array(run, dtype=np.float64)) for run in runs]
                            or [np.empty(0)])
    got, want = unique_sorted(values, kind="stable"), np.unique(values)
    assert got.dtype == want.dtype and np.array_equal(got, want)

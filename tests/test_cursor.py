"""ShapeCursor (the slider's incremental shape) against classify() and fresh shapes."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from core import REGULAR, SINGULAR, AlphaComplex
from core.complex import at_value
from core.errors import InputError
from core.query.cursor import CursorOrders, cursor_orders


def lattice_3d(size: int) -> np.ndarray:
    """A cubic grid: massive ties in every class (cospherical cells)."""
    axis = np.arange(size, dtype=np.float64)
    return np.stack(np.meshgrid(axis, axis, axis), axis=-1).reshape(-1, 3)


def assert_same_as_fresh(ac: AlphaComplex, shape, alpha: float) -> None:
    """The cursor's shape holds exactly classify()'s REGULAR facets and SINGULAR simplices,
    each row equal to the fresh shape's row for the same id (orientation included)."""
    dim = ac.dim
    fresh = ac.shape(alpha)
    ids = shape.regular_facet_ids
    order = np.argsort(ids)
    np.testing.assert_array_equal(ids[order],
                                  np.flatnonzero(ac.classify(alpha, dim - 1) == REGULAR))
    np.testing.assert_array_equal(shape.regular_facets[order], fresh.regular_facets)
    for k in range(dim):
        ids = shape.singular_ids(k)
        order = np.argsort(ids)
        np.testing.assert_array_equal(ids[order], np.flatnonzero(ac.classify(alpha, k) == SINGULAR))
        np.testing.assert_array_equal(shape.singular(k)[order], ac.simplices(k)[ids[order]])
    np.testing.assert_array_equal(shape.cells, fresh.cells)
    assert shape.measure == fresh.measure


@pytest.fixture(params=["cost model", "always delta", "always reset", "delta in halves",
                        "reset in halves"])
def strategy(request, monkeypatch):
    """Run a test with the cursor's own choice, or forcing delta steps or resets (with
    every pass split between two threads, as long ones are)."""
    import core.parallel
    import core.query.cursor

    if request.param != "cost model":
        force = "reset" in request.param
        monkeypatch.setattr(core.query.cursor.IntervalSet, "_cheaper_to_reset",
                            lambda self, c, n: force)
    if "halves" in request.param:
        monkeypatch.setattr(core.parallel, "PARALLEL_ABOVE", 2)
        monkeypatch.setattr(core.query.cursor, "FEW", 0)
    return request.param


def walk(ac: AlphaComplex, indexes) -> None:
    """Move one cursor along spectrum indexes, checking every stop."""
    spectrum = ac.spectrum()
    cursor = ac.cursor()
    for index in indexes:
        alpha = float(spectrum[int(index) % len(spectrum)])
        assert_same_as_fresh(ac, cursor.move(alpha), alpha)


@pytest.mark.parametrize("dim", [2, 3])
def test_arrow_page_and_far_steps_both_ways(dim, strategy):
    rng = np.random.default_rng(dim)
    ac = AlphaComplex.from_points(rng.random((1500, dim)))
    n = len(ac.spectrum())
    start = n // 3
    arrows = start + np.arange(60)
    pages = start + 60 + (n // 50) * np.arange(8)
    back = pages[-1] - np.arange(1, 40)
    far = rng.integers(0, n, 12)
    walk(ac, np.concatenate([arrows, pages, back, far, [0, n - 1, 0, n // 2]]))


def test_ties_on_a_lattice(strategy):
    ac = AlphaComplex.from_points(lattice_3d(5))
    walk(ac, list(range(len(ac.spectrum()))) + list(range(len(ac.spectrum()) - 1, -1, -1)))


def test_alpha_between_critical_values_and_beyond(strategy):
    ac = AlphaComplex.from_points(np.random.default_rng(7).random((300, 3)))
    spectrum = ac.spectrum()
    cursor = ac.cursor()
    for alpha in [0.5 * (spectrum[10] + spectrum[11]), 0.0, float(spectrum[-1]) * 3, np.inf,
                  float(spectrum[len(spectrum) // 2])]:
        assert_same_as_fresh(ac, cursor.move(alpha), float(alpha))


def test_shapes_handed_out_are_read_only_and_unchanged_by_later_moves():
    ac = AlphaComplex.from_points(np.random.default_rng(3).random((800, 3)))
    spectrum = ac.spectrum()
    cursor = ac.cursor()
    alpha = float(spectrum[len(spectrum) // 3])
    first = cursor.move(alpha)
    facets, singular = first.regular_facets.copy(), first.singular(1).copy()
    with pytest.raises(ValueError):
        first.regular_facets[0, 0] = 0
    for index in range(len(spectrum) // 3, len(spectrum) // 3 + 200):
        cursor.move(float(spectrum[index]))
    np.testing.assert_array_equal(first.regular_facets, facets)
    np.testing.assert_array_equal(first.singular(1), singular)
    assert_same_as_fresh(ac, first, alpha)


def test_a_cursor_shape_hands_out_the_cursors_own_rows():
    """A slider step's SINGULAR and REGULAR rows are the cursor's own (no gather from the
    table), read-only, and row for row the simplices of singular_ids."""
    ac = AlphaComplex.from_points(np.random.default_rng(4).random((600, 3)))
    cursor = ac.cursor()
    shape = cursor.move(float(ac.spectrum()[len(ac.spectrum()) // 2]))
    shared = 0
    for k in range(3):
        rows = shape.singular(k)
        shared += len(rows) > 0 and np.shares_memory(rows, cursor.singular[k].rows)
        assert not rows.flags.writeable
        np.testing.assert_array_equal(rows, ac.simplices(k)[shape.singular_ids(k)])
    assert shared == sum(len(shape.singular(k)) > 0 for k in range(3)) >= 2
    assert np.shares_memory(shape.regular_facets, cursor.regular.rows)
    assert not shape.regular_facets.flags.writeable


def test_bad_alpha_is_an_input_error_and_keeps_the_cursor():
    ac = AlphaComplex.from_points(np.random.default_rng(4).random((200, 2)))
    cursor = ac.cursor()
    alpha = float(ac.spectrum()[50])
    cursor.move(alpha)
    for bad in (-1.0, float("nan"), "wide"):
        with pytest.raises(InputError):
            cursor.move(bad)
    assert cursor.alpha == alpha
    assert_same_as_fresh(ac, cursor.move(float(ac.spectrum()[60])), float(ac.spectrum()[60]))


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 2**32 - 1), dim=st.sampled_from([2, 3]), grid=st.booleans(),
       force=st.sampled_from([None, True, False]), halves=st.booleans(),
       steps=st.lists(st.integers(-400, 400), min_size=1, max_size=25))
def test_any_walk_matches_fresh_shapes(seed, dim, grid, force, halves, steps):
    import contextlib
    from unittest import mock

    import core.parallel
    import core.query.cursor
    from core.query.cursor import IntervalSet

    rng = np.random.default_rng(seed)
    points = rng.integers(0, 5, (60, dim)).astype(float) if grid else rng.random((60, dim))
    try:
        ac = AlphaComplex.from_points(points)
    except InputError:
        return
    choice = (mock.patch.object(IntervalSet, "_cheaper_to_reset", lambda self, c, n: force)
              if force is not None else contextlib.nullcontext())
    split = contextlib.ExitStack()
    if halves:
        split.enter_context(mock.patch.object(core.query.cursor, "FEW", 0))
        split.enter_context(mock.patch.object(core.parallel, "PARALLEL_ABOVE", 2))
    with choice, split:
        walk(ac, np.cumsum([len(ac.spectrum()) // 2, *steps]))


def test_split_passes_fill_every_element_and_never_wait_on_their_own_thread():
    from core.parallel import PARALLEL_ABOVE, halves, select, together

    n = 2 * PARALLEL_ABOVE + 3
    seen = np.zeros(n, dtype=np.int8)

    def mark(start: int, stop: int) -> None:
        seen[start:stop] += 1

    halves(mark, n)
    assert (seen == 1).all()
    together(lambda: halves(mark, n))()  # from a background job
    assert (seen == 2).all()
    halves(lambda start, stop: halves(mark, n) if start else None, n)  # nested in the helper
    assert (seen == 3).all()
    keep = np.random.default_rng(0).random(n) < 0.3
    values = np.arange(n, dtype=np.int64) * 7
    out, ranks = np.empty(int(keep.sum()), np.int64), np.empty(int(keep.sum()), np.int32)
    select(keep, [(values, out)], ranks=ranks)
    np.testing.assert_array_equal(out, values[keep])
    np.testing.assert_array_equal(ranks, np.flatnonzero(keep))


def reference_orders(ac: AlphaComplex) -> CursorOrders:
    """The cursor's sort orders by numpy's stable argsort (ties by id), from the definition."""
    def by(values: np.ndarray, ids: np.ndarray) -> np.ndarray:
        return ids[np.argsort(values[ids], kind="stable")].astype(np.int32)

    facets = ac.index.level(ac.dim - 1)
    singular = []
    for k in range(ac.dim):
        level = ac.index.level(k)
        by_enter = by(level.enter, np.flatnonzero(level.enter < level.regular))
        singular.append((by_enter, by(level.regular, by_enter)))
    return CursorOrders(by(facets.regular, np.flatnonzero(facets.regular < facets.interior)),
                        tuple(singular))


@pytest.mark.parametrize("weighted", [False, True])
@pytest.mark.parametrize("dim", [2, 3])
def test_orders_found_apart_make_the_same_cursor(dim, weighted):
    """cursor_orders (what a build process hands over) equals the definition, and a cursor
    made from them hands out the same shapes, row for row, as one that sorts itself."""
    rng = np.random.default_rng(10 + dim)
    points = rng.random((1200, dim))
    extra = {"weights": rng.random(1200) * 1e-3} if weighted else {}
    ac = AlphaComplex.from_points(points, **extra)
    orders = cursor_orders(ac.index)
    want = reference_orders(ac)
    np.testing.assert_array_equal(orders.regular, want.regular)
    for (enter, ended), (want_enter, want_ended) in zip(orders.singular, want.singular,
                                                        strict=True):
        np.testing.assert_array_equal(enter, want_enter)
        np.testing.assert_array_equal(ended, want_ended)
    again = CursorOrders.from_arrays(orders.to_arrays(), ac.dim)
    own, handed = ac.cursor(), ac.cursor(again)
    spectrum = ac.spectrum()
    for alpha in spectrum[rng.integers(0, len(spectrum), 25)]:
        mine, theirs = own.move(**at_value(alpha)), handed.move(**at_value(alpha))
        np.testing.assert_array_equal(mine.regular_facets, theirs.regular_facets)
        np.testing.assert_array_equal(mine.regular_facet_ids, theirs.regular_facet_ids)
        for k in range(dim):
            np.testing.assert_array_equal(mine.singular(k), theirs.singular(k))
            np.testing.assert_array_equal(mine.singular_ids(k), theirs.singular_ids(k))


def test_orders_of_another_table_are_an_input_error():
    ac = AlphaComplex.from_points(np.random.default_rng(3).random((400, 3)))
    other = AlphaComplex.from_points(np.random.default_rng(4).random((500, 3)))
    with pytest.raises(InputError, match="do not fit"):
        ac.cursor(cursor_orders(other.index))
    int64 = cursor_orders(ac.index)
    with pytest.raises(InputError, match="do not fit"):
        ac.cursor(CursorOrders(int64.regular.astype(np.int64), int64.singular))
    for bad in (-1, len(ac.index.level(ac.dim - 1).enter)):  # ids outside the facets
        regular = int64.regular.copy()
        regular[0] = bad
        with pytest.raises(InputError, match="do not fit"):
            ac.cursor(CursorOrders(regular, int64.singular))


def assert_same_as_shape(ac: AlphaComplex, shape, value: float) -> None:
    """The cursor's shape at table value `value` (negative ones too: weighted) holds, row for
    row and oriented alike, what ac.shape and ac.classify give there."""
    at = at_value(value)
    fresh = ac.shape(**at)
    ids = shape.regular_facet_ids
    order = np.argsort(ids)
    np.testing.assert_array_equal(ids[order],
                                  np.flatnonzero(ac.classify(k=ac.dim - 1, **at) == REGULAR))
    np.testing.assert_array_equal(shape.regular_facets[order], fresh.regular_facets)
    for k in range(ac.dim):
        ids = shape.singular_ids(k)
        order = np.argsort(ids)
        np.testing.assert_array_equal(ids[order],
                                      np.flatnonzero(ac.classify(k=k, **at) == SINGULAR))
        np.testing.assert_array_equal(shape.singular(k)[order], fresh.singular(k))


@pytest.mark.parametrize("weighted", [False, True])
@pytest.mark.parametrize("dim", [2, 3])
def test_set_up_in_chunks_and_halves_gives_the_shapes_row_for_row(dim, weighted, monkeypatch):
    """The cursor's set-up (facets oriented chunk by chunk, ranks scattered in halves), with
    tiny chunks and every pass split, from handed orders or its own sorts: its shapes equal
    ac.shape's at many alphas (classic and weighted, 2D and 3D), and its oriented rows equal
    core.query.index.facing_out's definition for every facet."""
    import core.parallel
    import core.query.cursor
    from core.query.index import facing_out

    monkeypatch.setattr(core.query.cursor, "ROW_CHUNK", 7)
    monkeypatch.setattr(core.parallel, "PARALLEL_ABOVE", 2)
    rng = np.random.default_rng(20 + dim)
    points = rng.random((700, dim))
    extra = {"weights": rng.random(700) * 2e-3} if weighted else {}
    ac = AlphaComplex.from_points(points, **extra)
    index = ac.index
    facets = np.arange(len(index.level(dim - 1).enter))
    cells = index.facet_cells()
    inside_second = (cells[:, 1] >= 0) & (cells[:, 1] < cells[:, 0])
    np.testing.assert_array_equal(
        core.query.cursor._oriented_rows(index, facets[::-1].copy()),
        facing_out(index.simplices(dim - 1), index.table.facet_flip, inside_second)[::-1])
    spectrum = ac.spectrum()
    stops = np.concatenate([rng.integers(0, len(spectrum), 30), [0, len(spectrum) - 1]])
    for cursor in (ac.cursor(), ac.cursor(cursor_orders(index))):
        for stop in stops:
            value = float(spectrum[stop])
            assert_same_as_shape(ac, cursor.move(**at_value(value)), value)

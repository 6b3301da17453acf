"""A moving alpha (the explorer's slider): each step updates the shape by what changed.

`ShapeCursor.move(alpha)` returns the same AlphaShape as `ac.shape(alpha)`, but its REGULAR
facets and SINGULAR simplices come from sets kept since the last move. Each set ranks its
candidates by the alpha at which they join; the members are kept as a sorted rank array, so a
step costs the simplices that changed plus sequential passes over the answer (no random
gathers of answer rows), and a far jump is one sequential filter of a prefix.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np

from core.arrays import readonly
from core.build.sorting import argsort_radii
from core.errors import InputError
from core.parallel import (
    PASSES,
    halves,
    in_chunks,
    place,
    select,
    take,
    together,
    unsplit,
)
from core.query.alpha import table_value, threshold
from core.query.index import TableIndex, facing_out
from core.query.shape import AlphaShape, Known

FEW = 256  # changes up to this many are spliced by runs of memcpy, more by a masked pass
EVENT_COST = 8  # an ended simplex (random look-ups, a sort) costs about this many elements
#                of a sequential pass
NOT_A_CANDIDATE = np.iinfo(np.int32).max
ROW_CHUNK = 1 << 16  # facets oriented per chunk (its temporaries stay in cache)


def _between(sorted_values: np.ndarray, low: float, high: float) -> slice:
    """Positions of the values in (low, high] of an ascending array."""
    return slice(int(np.searchsorted(sorted_values, low, "right")),
                 int(np.searchsorted(sorted_values, high, "right")))


class IntervalSet:
    """The simplices i with lo[i] <= alpha < hi[i] at a moving alpha.

    Candidates (lo < hi) get a rank in ascending lo; at alpha the members are the ranks
    below K(alpha) = #(lo <= alpha) whose hi exceeds alpha. Moving up keeps the members that
    the hi order does not end and appends a contiguous rank range; moving down truncates and
    inserts what the hi order says is open again. Member ranks and rows are new read-only
    arrays at every step (never written afterwards), so shapes can hold them without a copy.
    """

    def __init__(self, lo: np.ndarray, hi: np.ndarray, by_lo: np.ndarray, by_hi: np.ndarray,
                 hi_sorted: np.ndarray, rows_by_lo: np.ndarray) -> None:
        """`lo`, `hi`: (n,) bounds of all n simplices; `by_lo`: the candidates by ascending
        lo; `by_hi`, `hi_sorted`: simplex ids by ascending hi and their hi values (others
        than candidates are ignored); `rows_by_lo`: (m, width) int32 rows of the candidates
        in `by_lo` order."""
        self._by_lo = by_lo.astype(np.int32, copy=False)
        self._lo_sorted = take(lo, by_lo)  # random gathers: in halves (core.parallel)
        self._hi_by_lo = take(hi, by_lo)
        self._rank = _rank_array(self._by_lo, len(lo))
        self._by_hi, self._hi_sorted = by_hi, hi_sorted
        self._width = rows_by_lo.shape[1]
        self._row = np.dtype((np.void, 4 * self._width))  # one row as one item: faster moves
        self._rows_by_lo = np.ascontiguousarray(rows_by_lo, np.int32).view(self._row).ravel()
        self._count = 0  # K at the current alpha
        self.members = readonly(np.zeros(0, dtype=np.int32))  # sorted ranks
        self.rows = readonly(np.zeros(0, dtype=self._row))

    @property
    def size(self) -> int:
        """Number of members at the current alpha."""
        return len(self.members)

    def _entered(self, alpha: float) -> int:
        return int(np.searchsorted(self._lo_sorted, alpha, "right"))

    def _set(self, members: np.ndarray, rows: np.ndarray, count: int) -> None:
        self.members, self.rows, self._count = readonly(members), readonly(rows), count

    def reset(self, alpha: float) -> None:
        """Members at alpha from scratch: one sequential filter of the entered prefix."""
        count = self._entered(alpha)
        keep = np.empty(count, dtype=bool)
        halves(lambda a, b: np.greater(self._hi_by_lo[a:b], alpha, out=keep[a:b]), count)
        size = int(np.count_nonzero(keep))
        members, rows = np.empty(size, dtype=np.int32), np.empty(size, dtype=self._row)
        select(keep, [(self._rows_by_lo[:count], rows)], ranks=members)
        self._set(members, rows, count)

    def go(self, old: float, new: float) -> None:
        """Move from alpha `old` (the current one) to `new`: by the changes or from scratch,
        whichever costs less."""
        if new == old:
            return
        count = self._entered(new)
        ended = self._by_hi[_between(self._hi_sorted, min(old, new), max(old, new))]
        if self._cheaper_to_reset(count, len(ended)):
            self.reset(new)
        elif new > old:
            self._up(new, count, ended)
        else:
            self._down(count, ended)

    def _ranks(self, ids: np.ndarray) -> np.ndarray:
        """Ranks of simplex ids (NOT_A_CANDIDATE for others): random reads, in halves."""
        ranks = np.empty(len(ids), dtype=np.int32)
        halves(lambda a, b: np.take(self._rank, ids[a:b], out=ranks[a:b]), len(ids))
        return ranks

    def _cheaper_to_reset(self, count: int, n_ended: int) -> bool:
        """A reset scans `count` ranks; a delta step looks up the ended ones and passes over
        the members and the newly entered ranks."""
        return count <= self.size + EVENT_COST * n_ended + abs(count - self._count)

    def _up(self, new: float, count: int, ended: np.ndarray) -> None:
        ranks = self._ranks(ended)
        leaving = ranks[ranks < self._count]  # were members: lo <= old < hi <= new
        start = self._count
        joining = np.flatnonzero(self._hi_by_lo[start:count] > new)
        size = self.size - len(leaving) + len(joining)
        members, rows = np.empty(size, dtype=np.int32), np.empty(size, dtype=self._row)
        kept = self.size - len(leaving)
        if len(leaving) <= FEW:  # copy the runs between them
            gaps = np.searchsorted(self.members, np.sort(leaving))
            _copy_runs(self.members, self.rows, members, rows, gaps, skip=True)
        else:  # a byte map by rank stays in cache; binary searches would not
            gone = np.zeros(self._count, dtype=bool)
            gone[leaving] = True
            keep = np.empty(self.size, dtype=bool)

            def stays(a: int, b: int) -> None:
                np.take(gone, self.members[a:b], out=keep[a:b])
                np.logical_not(keep[a:b], out=keep[a:b])

            halves(stays, self.size)
            select(keep, [(self.members, members[:kept]), (self.rows, rows[:kept])])
        np.add(joining, start, out=members[kept:], casting="unsafe")
        entered, fresh = self._rows_by_lo[start:count], rows[kept:]
        halves(lambda a, b: np.take(entered, joining[a:b], out=fresh[a:b]), len(joining))
        self._set(members, rows, count)

    def _down(self, count: int, ended: np.ndarray) -> None:
        ranks = self._ranks(ended)
        returning = np.sort(ranks[ranks < count])  # members again: lo <= new < hi <= old
        cut = int(np.searchsorted(self.members, count))
        if len(returning) <= FEW:  # copy the runs between the insertion points
            size = cut + len(returning)
            members, rows = np.empty(size, dtype=np.int32), np.empty(size, dtype=self._row)
            at = np.searchsorted(self.members[:cut], returning)
            _copy_runs(self.members[:cut], self.rows[:cut], members, rows, at, skip=False)
            slots = at + np.arange(len(at))
            members[slots] = returning
            rows[slots] = np.take(self._rows_by_lo, returning)
        else:  # merge through maps by rank: present (staying or returning), returning
            present, back = np.zeros(count, dtype=bool), np.zeros(count, dtype=bool)
            present[self.members[:cut]] = True
            present[returning] = back[returning] = True
            size = cut + len(returning)
            members, rows = np.empty(size, dtype=np.int32), np.empty(size, dtype=self._row)
            select(present, [], ranks=members)
            staying = np.empty(size, dtype=bool)

            def stays(a: int, b: int) -> None:
                np.take(back, members[a:b], out=staying[a:b])
                np.logical_not(staying[a:b], out=staying[a:b])

            halves(stays, size)
            place(staying, self.rows[:cut], np.take(self._rows_by_lo, returning), rows)
        self._set(members, rows, count)

    def snapshot(self) -> tuple[Callable[[], np.ndarray], np.ndarray]:
        """(ids, rows) of the members: a function giving the (k,) int64 ids (computed only if
        asked) and the read-only (k, width) int32 rows, both in rank order."""
        members, by_lo = self.members, self._by_lo
        return (lambda: np.take(by_lo, members).astype(np.int64),
                self.rows.view(np.int32).reshape(-1, self._width))


def _copy_runs(members: np.ndarray, rows: np.ndarray, out_members: np.ndarray,
               out_rows: np.ndarray, at: np.ndarray, skip: bool) -> None:
    """Copy members/rows into the front of the outputs run by run around the sorted
    positions `at`: dropping the items there (skip) or leaving a hole before each (insert).
    A few memcpy calls: cheaper than a masked pass when the positions are few."""
    source, target = 0, 0
    for position in at.tolist():
        run = position - source
        out_members[target:target + run] = members[source:position]
        out_rows[target:target + run] = rows[source:position]
        source, target = (position + 1, target + run) if skip else (position, target + run + 1)
    run = len(members) - source
    out_members[target:target + run] = members[source:]
    out_rows[target:target + run] = rows[source:]


class ShapeCursor:
    """The alpha shape at a moving alpha; `move(alpha)` equals `ac.shape(alpha)` as sets.

    Build once per complex with `ac.cursor()` (a few sorts of the table); one cursor serves
    one caller at a time (not thread-safe). Ids and rows it hands out are in the order the
    simplices joined their class, not by id.
    """

    def __init__(self, index: TableIndex, points: np.ndarray,
                 orders: CursorOrders | None = None) -> None:
        """Over the table `index` of a complex with (m, dim) `points`: rank the REGULAR
        facets by (regular, interior) and every SINGULAR level by (enter, regular); the two
        jobs run in two threads. `orders`: those ranks already found for this table
        (cursor_orders, by a build process beside its save), so only gathers remain. The
        table's spectrum (the slider's stops, asked for next) is found in the singular
        levels' thread, the shorter job, when it is not known yet."""
        self._index = index
        self._points = points
        if orders is None:
            def singular_sets() -> dict[int, IntervalSet]:
                return {k: _singular_set(index, k, *_singular_orders(index, k))
                        for k in range(index.dim)}
        else:
            orders.check(index)

            def singular_sets() -> dict[int, IntervalSet]:
                return {k: _singular_set(index, k, *orders.singular[k])
                        for k in range(index.dim)}
        singular = together(lambda: unsplit(lambda: (singular_sets(), index.spectrum())))
        self.regular = _regular_set(index, _regular_order(index) if orders is None
                                    else orders.regular)
        self.singular: dict[int, IntervalSet] = singular()[0]
        self.alpha: float | None = None

    def _sets(self) -> list[IntervalSet]:
        return [self.regular, *self.singular.values()]

    def move(self, alpha: float | None = None, *, alpha2: float | None = None) -> AlphaShape:
        """The shape at alpha (a radius) or alpha2 (squared), from the previous one by the
        simplices that changed."""
        value = table_value(alpha, alpha2, self._index.weighted)
        at = threshold(value)  # inf (the hull) keeps hull facets REGULAR
        for tracked in self._sets():
            if self.alpha is None:
                tracked.reset(at)
            else:
                tracked.go(threshold(self.alpha), at)
        self.alpha = value
        known = Known(*self.regular.snapshot(),
                      {k: tracked.snapshot() for k, tracked in self.singular.items()})
        return AlphaShape(self._index, self._points, value,
                          None if alpha2 is None else float(alpha2), known)


@dataclass(frozen=True, eq=False)
class CursorOrders:
    """The sorts a ShapeCursor is built on (most of its set-up), apart from the cursor so a
    build process can find them beside its save and hand them over with the table.

    `regular`: (r,) int32 the REGULAR candidates (facets with regular < interior) by
    ascending regular, ties by id; `singular[k]`: ((s_k,) int32 the SINGULAR candidates
    (enter < regular) of level k by ascending enter, the same ids by ascending regular).
    """

    regular: np.ndarray
    singular: tuple[tuple[np.ndarray, np.ndarray], ...]

    def to_arrays(self) -> dict[str, np.ndarray]:
        """The orders by name, for np.savez ('regular', 'enter_k', 'ended_k')."""
        out = {"regular": self.regular}
        for k, (by_enter, by_ended) in enumerate(self.singular):
            out[f"enter_{k}"], out[f"ended_{k}"] = by_enter, by_ended
        return out

    @classmethod
    def from_arrays(cls, arrays: Mapping[str, np.ndarray], dim: int) -> CursorOrders:
        """The orders to_arrays gave, for a table of dimension dim (KeyError if one lacks)."""
        return cls(arrays["regular"], tuple((arrays[f"enter_{k}"], arrays[f"ended_{k}"])
                                            for k in range(dim)))

    def check(self, index: TableIndex) -> None:
        """InputError unless these are int32 id arrays of the right levels, lengths and id
        range (cheap: that they sort the table is trusted, as orders this program found)."""
        facets = index.level(index.dim - 1)
        wanted = [(self.regular, int(np.count_nonzero(facets.regular < facets.interior)),
                   len(facets.enter))]
        for k, pair in enumerate(self.singular):
            level = index.level(k)
            wanted += [(order, int(np.count_nonzero(level.enter < level.regular)),
                        len(level.enter)) for order in pair]
        if len(self.singular) != index.dim or not all(
                isinstance(order, np.ndarray) and order.dtype == np.int32
                and order.shape == (length,)
                and (length == 0 or (int(order.min()) >= 0 and int(order.max()) < ids))
                for order, length, ids in wanted):
            raise InputError("cursor orders that do not fit this table")


def cursor_orders(index: TableIndex) -> CursorOrders:
    """The CursorOrders of the table `index`: what ShapeCursor would sort itself."""
    return CursorOrders(_regular_order(index),
                        tuple(_singular_orders(index, k) for k in range(index.dim)))


def _regular_order(index: TableIndex) -> np.ndarray:
    """(r,) int32 the REGULAR candidates (regular < interior) by ascending regular."""
    facets = index.level(index.dim - 1)
    by_regular = argsort_radii(facets.regular)
    return by_regular[take(facets.interior, by_regular)
                      > take(facets.regular, by_regular)].astype(np.int32)


def _singular_orders(index: TableIndex, k: int) -> tuple[np.ndarray, np.ndarray]:
    """(s,) int32 the SINGULAR k-candidates (enter < regular) by ascending enter, and by
    ascending regular."""
    level = index.level(k)
    by_enter = np.flatnonzero(level.enter < level.regular)
    if k == 0:  # levels k >= 1 are sorted by enter; weighted vertices keep the points' order
        by_enter = by_enter[argsort_radii(np.take(level.enter, by_enter))]
    by_ended = by_enter[argsort_radii(np.take(level.regular, by_enter))]
    return by_enter.astype(np.int32), by_ended.astype(np.int32)


def _regular_set(index: TableIndex, by_regular: np.ndarray) -> IntervalSet:
    """The REGULAR facets: candidates ranked by regular, ended by interior."""
    facets = index.level(index.dim - 1)
    return IntervalSet(facets.regular, facets.interior, by_regular,
                       index.table.facet_interior_order, index.interiors_sorted,
                       _oriented_rows(index, by_regular))


def _singular_set(index: TableIndex, k: int, by_enter: np.ndarray,
                  by_ended: np.ndarray) -> IntervalSet:
    """The SINGULAR k-simplices: candidates ranked by enter, ended by regular."""
    level = index.level(k)
    return IntervalSet(level.enter, level.regular, by_enter, by_ended,
                       take(level.regular, by_ended), take(level.simplices, by_enter))


def _rank_array(by_lo: np.ndarray, n: int) -> np.ndarray:
    """(n,) int32 the rank of every simplex in `by_lo` (NOT_A_CANDIDATE for the others):
    a fill and a random scatter, each in halves (the halves write disjoint items)."""
    rank = np.empty(n, dtype=np.int32)
    halves(lambda a, b: rank[a:b].fill(NOT_A_CANDIDATE), n, PASSES)

    def part(start: int, stop: int) -> None:
        rank[by_lo[start:stop]] = np.arange(start, stop, dtype=np.int32)

    halves(part, len(by_lo), PASSES)
    return rank


def _oriented_rows(index: TableIndex, ids: np.ndarray) -> np.ndarray:
    """(len(ids), dim) int32 facets as the shape orients them while REGULAR (as
    core.query.index.facing_out turns them, chunk by chunk).

    In its REGULAR interval a facet bounds exactly one cell: the one entered first (cells
    are sorted by enter), which is cell 1 when that is real and lower. Chunk by chunk, in
    two threads: each chunk's gathers and swaps stay in cache, with no whole-length
    temporaries (fresh memory costs more than the passes at a million points).
    """
    facets, cells = index.simplices(index.dim - 1), index.facet_cells()
    flip = index.table.facet_flip
    rows = np.empty((len(ids), index.dim), dtype=np.int32)

    def part(start: int, stop: int) -> None:
        chunk, block = ids[start:stop], rows[start:stop]
        np.take(facets, chunk, axis=0, out=block)
        pair = np.take(cells, chunk, axis=0)
        inside_second = (pair[:, 1] >= 0) & (pair[:, 1] < pair[:, 0])
        facing_out(block, np.take(flip, chunk), inside_second, out=block)

    in_chunks(part, len(ids), ROW_CHUNK)
    return rows

"""A moving alpha (the explorer's slider): each step updates the shape by what changed.

`ShapeCursor.move(alpha)` returns the same AlphaShape as `ac.shape(alpha)`, but its REGULAR
facets and SINGULAR simplices come from sets kept since the last move: a step costs the
simplices whose class changed between the two alphas plus one contiguous copy of the answer,
not a scan of the table and a gather of every answer row. Far jumps fall back to a fresh query.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from .shape import AlphaShape, readonly
from .table import argsort_radii

if TYPE_CHECKING:
    from .complex import AlphaComplex

Rows = Callable[[np.ndarray], np.ndarray]
Query = Callable[[AlphaShape], np.ndarray]


def _between(sorted_values: np.ndarray, low: float, high: float) -> slice:
    """Positions of the values in (low, high] of an ascending array."""
    return slice(int(np.searchsorted(sorted_values, low, "right")),
                 int(np.searchsorted(sorted_values, high, "right")))


class IntervalSet:
    """The simplices i with lo[i] <= alpha < hi[i], kept as an unordered dense list.

    Candidates are indexed twice, by lo and by hi, so the simplices that join or leave
    between two alphas are two contiguous ranges of those orders. Members sit in the first
    `size` slots of `members`/`rows`; removals fill their holes from the tail.
    """

    def __init__(self, n: int, lo: np.ndarray, hi: np.ndarray, by_lo: np.ndarray,
                 by_hi: np.ndarray, rows: Rows, width: int, query: Query) -> None:
        """`lo`, `hi`: (n,) bounds of all n simplices; `by_lo`/`by_hi`: the candidates
        (lo < hi) sorted by each; `rows(ids)` gives their (k, width) connectivity and
        `query(shape)` their ids from a fresh AlphaShape (for far jumps)."""
        self._lo, self._hi = lo, hi
        self._by_lo, self._lo_sorted = by_lo, np.take(lo, by_lo)
        self._by_hi, self._hi_sorted = by_hi, np.take(hi, by_hi)
        self._rows, self._query = rows, query
        self._slot = np.full(n, -1, dtype=np.int32)
        self._row = np.dtype((np.void, 4 * width))  # a row as one item: 1D moves are faster
        self._width = width
        self.members = np.empty(0, dtype=np.int64)
        self.rows = np.empty(0, dtype=self._row)
        self.size = 0

    def changes(self, old: float, new: float) -> tuple[np.ndarray, np.ndarray]:
        """Ids that join and that leave the set when alpha moves from old to new."""
        low, high = min(old, new), max(old, new)
        by_lo = self._by_lo[_between(self._lo_sorted, low, high)]
        by_hi = self._by_hi[_between(self._hi_sorted, low, high)]
        # Starting inside (low, high] by lo: members at high only if they also end after it;
        # ending inside it by hi: members at low only if they started by then.
        at_high = by_lo[np.take(self._hi, by_lo) > high]
        at_low = by_hi[np.take(self._lo, by_hi) <= low]
        return (at_high, at_low) if new > old else (at_low, at_high)

    def event_count(self, old: float, new: float) -> int:
        """How many candidate bounds lie between the two alphas (the cost of a delta step)."""
        low, high = min(old, new), max(old, new)
        for_lo, for_hi = _between(self._lo_sorted, low, high), _between(self._hi_sorted, low, high)
        return (for_lo.stop - for_lo.start) + (for_hi.stop - for_hi.start)

    def move(self, old: float, new: float) -> None:
        """Update the members from alpha `old` to alpha `new` by the simplices that changed."""
        joining, leaving = self.changes(old, new)
        self._remove(leaving)
        self._append(joining)

    def reset(self, shape: AlphaShape) -> None:
        """Replace the members by those of a fresh shape (far jumps, first use)."""
        self._slot[self.members[: self.size]] = -1
        self.size = 0
        self._append(self._query(shape))

    def _append(self, ids: np.ndarray) -> None:
        end = self.size + len(ids)
        if end > len(self.members):  # grow with headroom: a slider step never reallocates
            capacity = max(end + end // 2, 2 * len(self.members), 1024)
            members = np.empty(capacity, dtype=np.int64)
            members[: self.size] = self.members[: self.size]
            rows = np.empty(capacity, dtype=self._row)
            rows[: self.size] = self.rows[: self.size]
            self.members, self.rows = members, rows
        self.members[self.size:end] = ids
        self.rows[self.size:end] = np.ascontiguousarray(self._rows(ids), np.int32).view(
            self._row).ravel()
        self._slot[ids] = np.arange(self.size, end, dtype=np.int32)
        self.size = end

    def _remove(self, ids: np.ndarray) -> None:
        if len(ids) == 0:
            return
        slots = self._slot[ids]
        size = self.size - len(ids)
        holes = slots[slots < size]
        tail = np.ones(self.size - size, dtype=bool)
        tail[slots[slots >= size] - size] = False
        movers = size + np.flatnonzero(tail)
        self.members[holes] = self.members[movers]
        self.rows[holes] = self.rows[movers]
        self._slot[self.members[holes]] = holes
        self._slot[ids] = -1
        self.size = size

    def snapshot(self) -> tuple[np.ndarray, np.ndarray]:
        """Read-only copies of the member ids (k,) and rows (k, width), in slot order."""
        rows = self.rows[: self.size].copy().view(np.int32).reshape(-1, self._width)
        return readonly(self.members[: self.size].copy()), readonly(rows)


class ShapeCursor:
    """The alpha shape at a moving alpha; `move(alpha)` equals `ac.shape(alpha)` as sets.

    Build once per complex with `ac.cursor()` (a few sorts of the table); one cursor serves
    one caller at a time (not thread-safe). Ids and rows it hands out are in no set order.
    """

    def __init__(self, complex_: AlphaComplex) -> None:
        """Index the REGULAR facets by (regular, interior) and every SINGULAR level by
        (enter, regular)."""
        self._ac = ac = complex_
        dim = ac.dim
        facets = ac._level(dim - 1)
        cells = ac.facet_cells()
        by_regular = argsort_radii(facets.regular)
        by_regular = by_regular[np.take(facets.interior, by_regular)
                                > np.take(facets.regular, by_regular)]

        def oriented(ids: np.ndarray) -> np.ndarray:
            # In its REGULAR interval a facet bounds exactly one cell: the one entered first
            # (cells are sorted by enter), which is cell 1 when that is real and lower.
            pairs = cells[ids]  # fancy indexing: np.take would copy the strided columns first
            inside_second = (pairs[:, 1] >= 0) & (pairs[:, 1] < pairs[:, 0])
            return np.take(ac._oriented_facets, 2 * ids + inside_second, 0)

        ac._oriented_facets, ac._facets_by_interior  # noqa: B018 (built here, not on a step)
        interior_order = ac._table.facet_interior_order
        by_interior = interior_order[np.take(facets.regular, interior_order)
                                     < np.take(facets.interior, interior_order)]
        self.regular = IntervalSet(len(facets.enter), facets.regular, facets.interior,
                                   by_regular, by_interior, oriented, dim,
                                   lambda shape: shape.regular_facet_ids)
        self.singular: dict[int, IntervalSet] = {}
        for k in range(dim):
            level = ac._level(k)
            by_enter = np.flatnonzero(level.enter < level.regular)  # sorted by enter already
            by_regular = by_enter[argsort_radii(np.take(level.regular, by_enter))]
            self.singular[k] = IntervalSet(
                len(level.enter), level.enter, level.regular, by_enter, by_regular,
                lambda ids, s=level.simplices: np.take(s, ids, 0), k + 1,
                lambda shape, k=k: shape.singular_ids(k))
        self.alpha: float | None = None

    def _sets(self) -> list[tuple[IntervalSet, int | None]]:
        return [(self.regular, None)] + [(s, k) for k, s in self.singular.items()]

    def move(self, alpha: float) -> AlphaShape:
        """The shape at alpha (a radius), from the previous one by the simplices that changed."""
        shape = self._ac.shape(alpha)
        alpha = shape.alpha
        for tracked, _ in self._sets():
            if self.alpha is None or tracked.event_count(self.alpha, alpha) > max(
                    tracked.size, 4096):
                tracked.reset(shape)
            else:
                tracked.move(self.alpha, alpha)
        self.alpha = alpha
        singular = {k: tracked.snapshot() for k, tracked in self.singular.items()}
        return shape._seed(self.regular.snapshot(), singular)

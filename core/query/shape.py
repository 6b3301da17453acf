"""The alpha shape at one alpha: an immutable view of the table's answer, computed lazily."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from core.arrays import readonly
from core.query.alpha import threshold
from core.query.index import TableIndex

#: A facet taken from the suffix by interior (a gather, then a sort back into table order)
#: costs about 24 times one of the contiguous pass over the prefix that entered (measured on
#: a 200k-point scan's table).
GATHER_COST = 24


@dataclass(frozen=True, eq=False)
class Known:
    """Answers a ShapeCursor already holds for a shape: per class, a function giving the ids
    (called only if they are asked for) and the rows (the same sets the shape would compute,
    in the cursor's order). `singular` maps k to (ids function, (s, k+1) rows)."""

    regular_ids: Callable[[], np.ndarray]
    regular_rows: np.ndarray
    singular: dict[int, tuple[Callable[[], np.ndarray], np.ndarray]]


class AlphaShape:
    """Simplices of the alpha complex at `alpha`, by class; arrays are read-only.

    Each array is computed on first access and costs about the size of its answer, never a
    pass over the whole triangulation beyond the prefix of simplices that entered.
    """

    def __init__(self, index: TableIndex, points: np.ndarray, alpha: float,
                 alpha2: float | None = None, known: Known | None = None) -> None:
        """The shape at table value `alpha` of the table `index` over the complex's (m, dim)
        `points`; `alpha2` the squared value asked for, if it was; `known`: answers a cursor
        already has."""
        self._index = index
        self._known = known
        self.alpha = float(alpha)
        self._alpha2 = self.alpha * abs(self.alpha) if alpha2 is None else float(alpha2)
        self._at = threshold(self.alpha)  # compared with the table (inf: the hull)
        self.dim = index.dim
        self.points = points
        self._singular_ids: dict[int, np.ndarray] = {}
        self._singular: dict[int, np.ndarray] = (
            {} if known is None else {k: rows for k, (_, rows) in known.singular.items()})

    @property
    def alpha2(self) -> float:
        """The shape's alpha as a squared value (signed: negative below zero radius); the
        value asked for when the shape was made with alpha2=."""
        return self._alpha2

    def _entered(self, k: int) -> int:
        """Number of k-simplices in the complex (they are a prefix: sorted by enter)."""
        return self._index.entered(k, self._at)

    @cached_property
    def cell_ids(self) -> np.ndarray:
        """(c,) int64 rows of `simplices(dim)` in the complex."""
        return readonly(np.arange(self._entered(self.dim)))

    @cached_property
    def cells(self) -> np.ndarray:
        """(c, dim+1) int32 cells of the complex."""
        return readonly(self._index.level(self.dim).simplices[: self._entered(self.dim)])

    @cached_property
    def _facet_ids(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Rows of `simplices(dim-1)` on the boundary, and those that are REGULAR / SINGULAR.

        Takes whichever costs less: a pass over the facets that entered (a prefix by enter)
        or a gather of those not yet interior (a suffix by interior, sorted back into table
        order), so high alphas cost little too.
        """
        level = self._index.level(self.dim - 1)
        count = self._entered(self.dim - 1)
        order = self._index.table.facet_interior_order
        by_interior, enter_by_interior = self._index.facets_by_interior
        first = int(np.searchsorted(by_interior, self._at, "right"))
        if GATHER_COST * (len(order) - first) < count:
            ids = np.sort(order[first:][enter_by_interior[first:] <= self._at])
        else:
            ids = np.flatnonzero(level.interior[:count] > self._at)
        regular = np.take(level.regular, ids) <= self._at
        return ids, np.compress(regular, ids), np.compress(~regular, ids)  # 3x a mask index

    @cached_property
    def _boundary_ids(self) -> np.ndarray:
        """Rows of `simplices(dim-1)` that are SINGULAR or REGULAR at alpha."""
        return self._facet_ids[0]

    @cached_property
    def boundary_facets(self) -> np.ndarray:
        """(b, dim) int32 facets on the boundary of the shape (REGULAR or SINGULAR)."""
        return readonly(np.take(self._index.level(self.dim - 1).simplices, self._boundary_ids, 0))

    @cached_property
    def regular_facet_ids(self) -> np.ndarray:
        """(r,) int64 rows of `simplices(dim-1)` that are REGULAR at alpha."""
        if self._known is not None:
            return readonly(self._known.regular_ids())
        return readonly(self._facet_ids[1])

    @cached_property
    def regular_facets(self) -> np.ndarray:
        """(r, dim) int32 REGULAR facets oriented away from their cell (3D: normal
        (b-a)x(c-a) points out; 2D: the shape lies left of a->b, so outer rings run CCW)."""
        if self._known is not None:
            return self._known.regular_rows
        ids = self.regular_facet_ids
        inside_is_second = np.take(self._index.facet_cell0, ids) >= self._entered(self.dim)
        rows = 2 * ids + inside_is_second
        return readonly(np.take(self._index.oriented_facets, rows, 0))

    def singular_ids(self, k: int) -> np.ndarray:
        """(s,) int64 rows of `simplices(k)` that are SINGULAR at alpha (k < dim)."""
        if not 0 <= k < self.dim:
            raise ValueError(f"singular simplices exist for 0 <= k < {self.dim}, not k={k}")
        cache = self._singular_ids
        if k not in cache and self._known is not None and k in self._known.singular:
            cache[k] = readonly(self._known.singular[k][0]())
        elif k not in cache and k == self.dim - 1:
            cache[k] = readonly(self._facet_ids[2])
        elif k not in cache and k == 0:  # weighted vertices are not sorted by enter
            level = self._index.level(0)
            cache[k] = readonly(np.flatnonzero((level.enter <= self._at)
                                               & (level.regular > self._at)))
        elif k not in cache:
            level = self._index.level(k)
            count = self._entered(k)
            cache[k] = readonly(np.flatnonzero(level.regular[:count] > self._at))
        return cache[k]

    def singular(self, k: int) -> np.ndarray:
        """(s, k+1) int32 SINGULAR k-simplices (k < dim): in the complex, face of nothing."""
        cache = self._singular
        if k not in cache:
            ids = self.singular_ids(k)
            cache[k] = readonly(np.take(self._index.level(k).simplices, ids, 0))
        return cache[k]

    @cached_property
    def measure(self) -> float:
        """Volume (3D) or area (2D) of the complex: the sum of its cells' measures."""
        count = self._entered(self.dim)
        return float(self._index.cumulative_measure[count - 1]) if count else 0.0

    def __repr__(self) -> str:
        return (f"AlphaShape(alpha={self.alpha:.6g}, dim={self.dim}, "
                f"cells={self._entered(self.dim)}, measure={self.measure:.6g})")

"""The alpha shape at one alpha: an immutable view of the table's answer, computed lazily."""

from __future__ import annotations

from collections.abc import Callable
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from .complex import AlphaComplex


#: The largest float64: what an infinite alpha is compared with (see `threshold`).
LARGEST = float(np.finfo(np.float64).max)


def threshold(alpha: float) -> float:
    """The value a query at `alpha` compares the table with: +inf (the convex hull) is taken
    as the largest float. It is above every finite table value but below inf, which in the
    table means never (the `interior` of a simplex on the hull), so `value <= threshold`
    keeps hull simplices from turning interior, exactly as at any alpha past the spectrum."""
    return min(float(alpha), LARGEST)


def readonly(arr: np.ndarray) -> np.ndarray:
    """`arr` with its writeable flag cleared (a widget must not corrupt the table)."""
    arr.flags.writeable = False
    return arr


class AlphaShape:
    """Simplices of the alpha complex at `alpha`, by class; arrays are read-only.

    Each array is computed on first access and costs about the size of its answer, never a
    pass over the whole triangulation beyond the prefix of simplices that entered.
    """

    def __init__(self, complex_: AlphaComplex, alpha: float, alpha2: float | None = None) -> None:
        self._ac = complex_
        self.alpha = float(alpha)
        self._alpha2 = self.alpha * abs(self.alpha) if alpha2 is None else float(alpha2)
        self._at = threshold(self.alpha)  # compared with the table (inf: the hull)
        self.dim = complex_.dim
        self.points = complex_.points

    @property
    def alpha2(self) -> float:
        """The shape's alpha as a squared value (signed: negative below zero radius); the
        value asked for when the shape was made with alpha2=."""
        return self._alpha2

    def _entered(self, k: int) -> int:
        """Number of k-simplices in the complex (they are a prefix: sorted by enter)."""
        return int(np.searchsorted(self._ac._level(k).enter, self._at, side="right"))

    @cached_property
    def cell_ids(self) -> np.ndarray:
        """(c,) int64 rows of `simplices(dim)` in the complex."""
        return readonly(np.arange(self._entered(self.dim)))

    @cached_property
    def cells(self) -> np.ndarray:
        """(c, dim+1) int32 cells of the complex."""
        return readonly(self._ac._level(self.dim).simplices[: self._entered(self.dim)])

    @cached_property
    def _facet_ids(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Rows of `simplices(dim-1)` on the boundary, and those that are REGULAR / SINGULAR.

        Scans whichever is shorter: the facets that entered (a prefix by enter) or those not
        yet interior (a suffix by interior), so high alphas cost little too.
        """
        level = self._ac._level(self.dim - 1)
        count = self._entered(self.dim - 1)
        order = self._ac._table.facet_interior_order
        by_interior, enter_by_interior = self._ac._facets_by_interior
        first = int(np.searchsorted(by_interior, self._at, "right"))
        if 4 * (len(order) - first) < count:  # gathers cost about 4x a contiguous pass
            ids = np.sort(order[first:][enter_by_interior[first:] <= self._at])
        else:
            ids = np.flatnonzero(level.interior[:count] > self._at)
        regular = np.take(level.regular, ids) <= self._at
        return ids, ids[regular], ids[~regular]

    @cached_property
    def _boundary_ids(self) -> np.ndarray:
        """Rows of `simplices(dim-1)` that are SINGULAR or REGULAR at alpha."""
        return self._facet_ids[0]

    @cached_property
    def boundary_facets(self) -> np.ndarray:
        """(b, dim) int32 facets on the boundary of the shape (REGULAR or SINGULAR)."""
        return readonly(np.take(self._ac._level(self.dim - 1).simplices, self._boundary_ids, 0))

    @cached_property
    def regular_facet_ids(self) -> np.ndarray:
        """(r,) int64 rows of `simplices(dim-1)` that are REGULAR at alpha."""
        seeded = self.__dict__.get("_seeded_ids", {}).get("regular")
        return readonly(seeded() if seeded else self._facet_ids[1])

    @cached_property
    def regular_facets(self) -> np.ndarray:
        """(r, dim) int32 REGULAR facets oriented away from their cell (3D: normal
        (b-a)x(c-a) points out; 2D: the shape lies left of a->b, so outer rings run CCW)."""
        ids = self.regular_facet_ids
        ac = self._ac
        inside_is_second = np.take(ac._facet_cell0, ids) >= self._entered(self.dim)
        rows = 2 * ids + inside_is_second
        return readonly(np.take(ac._oriented_facets, rows, 0))

    def singular_ids(self, k: int) -> np.ndarray:
        """(s,) int64 rows of `simplices(k)` that are SINGULAR at alpha (k < dim)."""
        if not 0 <= k < self.dim:
            raise ValueError(f"singular simplices exist for 0 <= k < {self.dim}, not k={k}")
        cache = self.__dict__.setdefault("_singular_ids", {})
        seeded = self.__dict__.get("_seeded_ids", {})
        if k not in cache and k in seeded:
            cache[k] = readonly(seeded[k]())
        elif k not in cache and k == self.dim - 1:
            cache[k] = readonly(self._facet_ids[2])
        elif k not in cache and k == 0:  # weighted vertices are not sorted by enter
            level = self._ac._level(0)
            cache[k] = readonly(np.flatnonzero((level.enter <= self._at)
                                               & (level.regular > self._at)))
        elif k not in cache:
            level = self._ac._level(k)
            count = self._entered(k)
            cache[k] = readonly(np.flatnonzero(level.regular[:count] > self._at))
        return cache[k]

    def singular(self, k: int) -> np.ndarray:
        """(s, k+1) int32 SINGULAR k-simplices (k < dim): in the complex, face of nothing."""
        cache = self.__dict__.setdefault("_singular", {})
        if k not in cache:
            ids = self.singular_ids(k)
            cache[k] = readonly(np.take(self._ac._level(k).simplices, ids, 0))
        return cache[k]

    def _seed(self, regular: tuple[Callable[[], np.ndarray], np.ndarray],
              singular: dict[int, tuple[Callable[[], np.ndarray], np.ndarray]]) -> AlphaShape:
        """Fill the REGULAR facets and SINGULAR simplices with what a ShapeCursor kept: per
        class, a function giving the ids (called only if they are asked for) and the rows
        (the same sets as computed here, in the cursor's order)."""
        ids, self.__dict__["regular_facets"] = regular
        self.__dict__["_seeded_ids"] = {"regular": ids, **{k: f for k, (f, _) in singular.items()}}
        self.__dict__["_singular"] = {k: rows for k, (_, rows) in singular.items()}
        return self

    @cached_property
    def measure(self) -> float:
        """Volume (3D) or area (2D) of the complex: the sum of its cells' measures."""
        count = self._entered(self.dim)
        return float(self._ac._cumulative_measure[count - 1]) if count else 0.0

    def __repr__(self) -> str:
        return (f"AlphaShape(alpha={self.alpha:.6g}, dim={self.dim}, "
                f"cells={self._entered(self.dim)}, measure={self.measure:.6g})")

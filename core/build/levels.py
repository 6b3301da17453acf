"""The interval table's containers: one Level per dimension, the Table of all levels and the
cell/facet adjacency, and the reordering of a level by a sort order."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.arrays import readonly
from core.build.sorting import argsort_radii
from core.parallel import inverse_permutation, take


@dataclass
class Level:
    """The simplices of one dimension k, sorted by enter, and their three alphas."""

    simplices: np.ndarray  # (n, k+1) int32, rows ascending
    enter: np.ndarray  # (n,) float64, ascending; (0,) for faces built without values
    regular: np.ndarray  # (n,) float64
    interior: np.ndarray  # (n,) float64, inf = on the convex hull
    face_ids: np.ndarray | None = None  # (n, k+1) int32: row in level k-1 opposite each vertex


@dataclass
class Table:
    """All levels plus the cell/facet adjacency the queries need."""

    levels: list[Level]
    facet_cells: np.ndarray  # (f, 2) int32 cells on both sides of each facet, -1 = outside
    facet_flip: np.ndarray  # (f,) bool: reverse the last two vertices to face out of cell 0
    cell_measure: np.ndarray  # (c,) float64 unsigned volume/area of every cell
    # (f,) int32 facet rows sorted by interior ((0,) in an unsorted table until its mode
    # sorts it); None: not sorted yet, sorted on first use (facet_interior_order)
    facet_order: np.ndarray | None
    # sign decisions that needed exact arithmetic (core.build.table_signs)
    exact_predicates: int = 0

    @property
    def facet_interior_order(self) -> np.ndarray:
        """(f,) int32 facet rows sorted by interior. A build leaves it to the first use (a
        shape's interior facets, a cursor, a save), so a build nobody asks it of (a
        molecule's measures) never sorts its facets a second time."""
        if self.facet_order is None:
            self.facet_order = readonly(
                argsort_radii(self.levels[-2].interior).astype(np.int32))
        return self.facet_order

    @facet_interior_order.setter
    def facet_interior_order(self, order: np.ndarray) -> None:
        self.facet_order = order


def permute_level(level: Level, order: np.ndarray | None) -> np.ndarray | None:
    """Reorder `level` by `order` in place; return the inverse permutation (None: no
    order, the level stays as built)."""
    if order is None:
        return None
    level.simplices = take(level.simplices, order)
    shared = level.regular is level.enter and level.interior is level.enter  # cells
    level.enter = take(level.enter, order)
    level.regular = level.enter.copy() if shared else take(level.regular, order)
    level.interior = level.enter.copy() if shared else take(level.interior, order)
    if level.face_ids is not None:
        level.face_ids = take(level.face_ids, order)
    return inverse_permutation(order)

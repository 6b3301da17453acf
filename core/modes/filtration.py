"""A mode's filtration from its own values (core/modes/alpha_modes.py): the repair that makes it one
(faces never after their cofaces) and the one sort of every level by the new enter values,
with the ids into each level renumbered."""

from __future__ import annotations

import numpy as np

from core.build.levels import Table
from core.build.sorting import argsort_radii
from core.parallel import inverse_permutation, renumber, take, together


def _orders(enters: list[np.ndarray]) -> list[np.ndarray]:
    """Per level, the order that sorts it by enter (vertices keep their rows: they all
    enter at 0). The facets, the longest level, are sorted in a helper thread meanwhile
    (numpy's sort releases the GIL)."""
    d = len(enters) - 1
    facets = together(lambda: argsort_radii(enters[d - 1]))
    orders = {k: argsort_radii(enters[k]) for k in range(1, d + 1) if k != d - 1}
    orders[d - 1] = facets()
    return [np.arange(len(enters[0])), *(orders[k] for k in range(1, d + 1))]


def repaired(table: Table, own: list[np.ndarray]) -> list[tuple[np.ndarray, ...]]:
    """(enter, regular, interior) per level from the own values (inf: attached faces),
    cells down, as core/modes/alpha_modes.py's docstring says. `own` is consumed: the faces' enter
    values are written over their own ones."""
    d = len(own) - 1
    cells = own[d]
    fc = table.facet_cells
    outside = fc[:, 1] < 0
    second = np.where(outside, np.inf, cells[np.maximum(fc[:, 1], 0)])
    first = cells[fc[:, 0]]
    regular, interior = np.minimum(first, second), np.maximum(first, second)
    out = [(cells, cells, cells),
           (np.minimum(own[d - 1], regular, out=own[d - 1]), regular, interior)]
    for k in range(d - 2, -1, -1):
        enter_up, interior_up = out[-1][0], out[-1][2]
        faces = table.levels[k + 1].face_ids if k > 0 else table.levels[1].simplices
        regular = np.full(len(own[k]), np.inf)
        interior = np.full(len(own[k]), -np.inf)
        for c in range(k + 2):  # a column at a time: no (n, k+2) copies of the values
            column = np.ascontiguousarray(faces[:, c])
            np.minimum.at(regular, column, enter_up)
            np.maximum.at(interior, column, interior_up)
        enter = np.zeros(len(own[k])) if k == 0 else np.minimum(own[k], regular, out=own[k])
        out.append((enter, regular, interior))
    return out[::-1]


def resorted(table: Table, values: list[tuple[np.ndarray, ...]]) -> Table:
    """`table` with the new values, each level sorted by enter and the ids into it
    renumbered, in place (the count of exact sign decisions kept: the mode's classic radii
    may have needed some). `values` is consumed: every array of the table and of `values`
    is let go as soon as its sorted copy replaces it, so the build's peak memory stays near
    the classic build's (first-touched memory costs more CPU than these gathers)."""
    d = len(values) - 1
    orders = _orders([enter for enter, _, _ in values])
    levels = table.levels
    levels[0].enter, levels[0].regular, levels[0].interior = values.pop(0)  # rows kept
    below = None  # the inverse numbering of the level below (vertices: none)
    for k in range(1, d + 1):
        order, level, row = orders[k], levels[k], list(values.pop(0))
        level.enter = take(row.pop(0), order)
        if k == d:  # cells: three equal arrays
            level.regular, level.interior = level.enter.copy(), level.enter.copy()
        else:
            level.regular = take(row.pop(0), order)
            level.interior = take(row.pop(0), order)
        del row
        level.simplices = take(level.simplices, order)
        if below is not None:  # renumbered before the rows move: the same ids
            level.face_ids = renumber(level.face_ids, below)
        level.face_ids = take(level.face_ids, order)
        below = inverse_permutation(order)
    by_interior = together(lambda: argsort_radii(levels[d - 1].interior).astype(np.int32))
    facets = orders[d - 1]
    table.facet_cells = renumber(take(table.facet_cells, facets), below)
    table.facet_flip = take(table.facet_flip, facets)
    table.cell_measure = take(table.cell_measure, orders[d])
    table.facet_interior_order = by_interior()
    return table

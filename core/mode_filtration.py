"""A mode's filtration from its own values (core/modes.py): the repair that makes it one
(faces never after their cofaces) and the one sort of every level by the new enter values,
with the ids into each level renumbered."""

from __future__ import annotations

import numpy as np

from .parallel import take, together
from .table import Level, Table, argsort_radii


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
    cells down, as core/modes.py's docstring says."""
    d = len(own) - 1
    cells = own[d]
    fc = table.facet_cells
    outside = fc[:, 1] < 0
    second = np.where(outside, np.inf, cells[np.maximum(fc[:, 1], 0)])
    first = cells[fc[:, 0]]
    regular, interior = np.minimum(first, second), np.maximum(first, second)
    out = [(cells, cells, cells), (np.minimum(own[d - 1], regular), regular, interior)]
    for k in range(d - 2, -1, -1):
        enter_up, interior_up = out[-1][0], out[-1][2]
        faces = table.levels[k + 1].face_ids if k > 0 else table.levels[1].simplices
        flat_faces = faces.ravel()
        regular = np.full(len(own[k]), np.inf)
        interior = np.full(len(own[k]), -np.inf)
        np.minimum.at(regular, flat_faces, np.repeat(enter_up, k + 2))
        np.maximum.at(interior, flat_faces, np.repeat(interior_up, k + 2))
        enter = np.zeros(len(own[k])) if k == 0 else np.minimum(own[k], regular)
        out.append((enter, regular, interior))
    return out[::-1]


def _renumber(ids: np.ndarray, inverse: np.ndarray) -> np.ndarray:
    """Apply a new numbering (int32 `inverse`) to int32 ids, -1 = none kept: one gather (in
    halves) from the inverse with -1 appended, which index -1 reads."""
    return take(np.append(inverse, np.int32(-1)), ids.ravel()).reshape(ids.shape)


def resorted(table: Table, values: list[tuple[np.ndarray, ...]]) -> Table:
    """The table with the new values, each level sorted by enter, ids renumbered."""
    d = len(values) - 1
    orders = _orders([enter for enter, _, _ in values])
    inverses = []
    for order in orders:
        inverse = np.empty(len(order), dtype=np.int32)
        inverse[order] = np.arange(len(order), dtype=np.int32)
        inverses.append(inverse)
    levels = [Level(table.levels[0].simplices.copy(), *(a.copy() for a in values[0]))]
    for k in range(1, d + 1):
        old, order, row = table.levels[k], orders[k], values[k]
        enter = take(row[0], order)
        regular, interior = ((enter.copy(), enter.copy()) if k == d
                             else (take(row[1], order), take(row[2], order)))
        levels.append(Level(take(old.simplices, order), enter, regular, interior,
                            _renumber(take(old.face_ids, order), inverses[k - 1])))
    by_interior = together(lambda: argsort_radii(levels[d - 1].interior).astype(np.int32))
    facets = orders[d - 1]
    return Table(levels, _renumber(take(table.facet_cells, facets), inverses[d]),
                 take(table.facet_flip, facets), take(table.cell_measure, orders[d]),
                 by_interior())

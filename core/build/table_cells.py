"""The cell pass of the interval table: every top-dimensional cell's value (its circumradius,
or signed radius of power), sign, attach bits and measure, the level sorted by value."""

from __future__ import annotations

import math

import numpy as np

from core.build.cell_pass import CellSpheres
from core.build.folds import delay_flat_cells, folded_cells
from core.build.levels import Level, permute_level
from core.build.sorting import sort_order
from core.build.table_signs import settle_cells
from core.geometry.circumspheres import cell_spheres
from core.geometry.power import cell_orthospheres, signed_sqrt
from core.parallel import renumber, take


def cell_level(points: np.ndarray, cells: np.ndarray, neighbors: np.ndarray,
               weights: np.ndarray | None = None, exact: list[int] | None = None,
               spheres: CellSpheres | None = None, sort: bool = True,
               mirror: np.ndarray | None = None):
    """Level d sorted by enter, its neighbours (renumbered), signed d!-measures (0 for flat
    cells), attach bits (bit i: vertex i attaches the facet opposite it), volumes/areas and
    the neighbours' mirror columns (None where not given). Counts of exactly decided
    predicates are appended to `exact`. `spheres`: the cells'
    core.geometry.circumspheres.cell_spheres when already computed (core.build.cell_pass), used in
    place."""
    if weights is None:
        r2, det, flat, bits = (cell_spheres(points, cells) if spheres is None else
                               (spheres.r2, spheres.det, spheres.flat, spheres.bits))
        enter = np.sqrt(r2)
        if exact is not None:
            exact.append(settle_cells(points, cells, enter, det, flat))
    else:
        power, det, flat, bits = cell_orthospheres(points, weights, cells)
        enter = signed_sqrt(power)
    measure = np.abs(det) / math.factorial(points.shape[1])
    flat |= folded_cells(points, cells, neighbors, det, flat)
    bits[flat] = 0  # flat cells' facets get the global attachment test
    if flat.any():
        det[flat] = 0.0  # orientation unknown: the facets use the other side or the hull
        delay_flat_cells(enter, flat, neighbors)
    level = Level(cells, enter, enter, enter)
    order = sort_order(enter, sort)
    if order is None:  # as built; three arrays, as permute_level leaves them
        level.regular, level.interior = enter.copy(), enter.copy()
        return level, neighbors, det, bits, measure, mirror
    inverse = permute_level(level, order)
    return (level, renumber(take(neighbors, order), inverse), take(det, order), take(bits, order),
            take(measure, order), None if mirror is None else take(mirror, order))

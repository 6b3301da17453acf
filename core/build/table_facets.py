"""The facet pass of the interval table: each facet shared by two cells (or one, on the hull)
taken once from the cells' neighbour table, its value (its own smallest sphere unless
attached, then its first cell's), regular and interior from its cells, its orientation and
the cells' face ids; on two threads."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from core.build.levels import Level, permute_level
from core.build.sorting import sort_order_beside
from core.build.table_signs import settle_facets, settle_obtuse
from core.geometry.circumspheres import (
    CACHE_CHUNK,
    any_point_inside,
    circumspheres,
    facet_radii2,
)
from core.geometry.power import (
    any_point_below,
    edge_powers,
    orthospheres,
    signed_sqrt,
    triangle_powers,
)
from core.parallel import PASSES, halves, in_chunks, nonzero, rows_cols, slot_of, take


def _faces_centre(points: np.ndarray, facets: np.ndarray) -> np.ndarray:
    """(h,) bool: hull facets whose natural orientation faces the centroid (so must flip).

    The hull is convex, so the centroid is inside: robust even when the cell behind is flat.
    """
    first = points[facets[:, 0]]
    to_centre = points.mean(axis=0) - first
    if points.shape[1] == 2:
        edge = points[facets[:, 1]] - first
        return edge[:, 0] * to_centre[:, 1] - edge[:, 1] * to_centre[:, 0] < 0
    normal = np.cross(points[facets[:, 1]] - first, points[facets[:, 2]] - first)
    return np.einsum("nd,nd->n", normal, to_centre) > 0


def _facet_spheres(points: np.ndarray, simplices: np.ndarray, weights: np.ndarray | None,
                   exact: list[int] | None = None):
    """Facet values (radii, or signed radii of powers), (3D) attach bits of their edges, and
    the global attachment test for the listed facets."""
    if weights is None:
        if exact is not None and simplices.shape[1] == 3:
            r2, obtuse, doubt = facet_radii2(points, simplices, exact=True)
            obtuse, n_exact = settle_obtuse(points, simplices, obtuse, doubt)
            exact.append(n_exact)
        else:
            r2, obtuse = facet_radii2(points, simplices)

        def global_test(ids: np.ndarray) -> np.ndarray:
            offsets, _, _, _ = circumspheres(points, simplices[ids])
            centres = points[simplices[ids, 0]] + offsets
            return any_point_inside(points, centres, r2[ids])
        return np.sqrt(r2), obtuse, global_test
    if simplices.shape[1] == 2:
        power, obtuse = edge_powers(points, weights, simplices)[0], None
    else:
        power, obtuse = triangle_powers(points, weights, simplices)

    def power_test(ids: np.ndarray) -> np.ndarray:
        offsets, _, _, _ = orthospheres(points, weights, simplices[ids])
        centres = points[simplices[ids, 0]] + offsets
        return any_point_below(points, weights, centres, power[ids])
    return signed_sqrt(power), obtuse, power_test


def _attach_bits(bits: np.ndarray, cell: np.ndarray, vertex: np.ndarray) -> np.ndarray:
    """(n,) bool bit `vertex` of the attach bits of `cell` (its vertex opposite the facet
    lies inside the facet's smallest sphere), in halves."""
    out = np.empty(len(cell), dtype=bool)

    def part(lo: int, hi: int) -> None:
        out[lo:hi] = (np.take(bits, cell[lo:hi]) >> vertex[lo:hi]) & 1

    halves(part, len(cell), PASSES)
    return out


def _facet_enter(points: np.ndarray, cells: Level, det: np.ndarray, simplices: np.ndarray,
                 weights: np.ndarray | None, exact: list[int] | None, first_side: tuple,
                 second_side: tuple, near_flat: np.ndarray, regular: np.ndarray,
                 bits: np.ndarray) -> tuple[np.ndarray, np.ndarray | None]:
    """The facets' enter values (their own radius unless attached, then `regular`) and the
    (3D) attach bits of their edges. first_side = (first_cell, first_col, first_enter):
    every facet's first cell, the column of its vertex opposite the facet, its enter;
    second_side = (two_sided, second_cell, second_col, second_enter): the same for the
    facets with a second cell (two_sided: their ascending ids)."""
    first_cell, first_col, first_enter = first_side
    two_sided, second_cell, second_col, second_enter = second_side
    radius, obtuse, global_test = _facet_spheres(points, simplices, weights, exact)
    first_attached = _attach_bits(bits, first_cell, first_col)
    second_attached = _attach_bits(bits, second_cell, second_col)
    if weights is None and exact is not None:  # doubtful float decisions made exact
        sides = [(slice(None), first_cell, first_col, first_attached, first_enter),
                 (two_sided, second_cell, second_col, second_attached, second_enter)]
        attached, n_exact = settle_facets(points, cells.simplices, cells.enter, det, simplices,
                                          radius, sides)
        exact.append(n_exact)
    else:
        attached = first_attached.copy()
        attached[two_sided] |= second_attached
    del first_attached, second_attached
    if near_flat.any():
        ids = np.flatnonzero(near_flat)
        attached[ids] |= global_test(ids)
    return np.where(attached, regular, np.minimum(radius, regular)), obtuse


def facet_level(points: np.ndarray, cells: Level, neighbors: np.ndarray, det: np.ndarray,
                bits: np.ndarray, weights: np.ndarray | None = None,
                exact: list[int] | None = None, sort: bool = True, radii: bool = True,
                mirror: np.ndarray | None = None):
    """Level d-1 from the cells' neighbour table: each shared facet taken once, from the
    lower-numbered of its cells (its first cell; its second, if any, is the neighbour
    across). Returns the level, its (f, 2) cells (-1 outside), flips, which facets touch a
    flat cell, and the (3D) attach bits of their edges; sets the cells' face ids. Every
    per-cell value is gathered once per side (the second side's gathers are random) on two
    threads (core.parallel.take). radii=False: no values for the facets ((0,) arrays), only
    their structure. `mirror`: the neighbours' columns that point back, if known (else
    found from their rows)."""
    n_cells, width = cells.simplices.shape

    def keep(lo: int, hi: int) -> np.ndarray:
        rows = neighbors[lo:hi]
        return (rows > np.arange(lo, hi, dtype=np.int32)[:, None]) | (rows < 0)

    # the facets' slots (cell * width + column) in the neighbour table: cell-major
    first_slot = nonzero(keep, n_cells)
    first_cell, first_col = rows_cols(first_slot, width)
    other_cell = take(neighbors.ravel(), first_slot)  # every facet's second cell, -1 = none
    simplices = _drop_vertex(cells.simplices, first_cell, first_col)
    # the facets with a second cell; second_* arrays are aligned with them
    two_sided = np.flatnonzero(other_cell >= 0)
    second_cell = take(other_cell, two_sided)
    if mirror is None:
        second_col = slot_of(neighbors, second_cell, take(first_cell, two_sided))
    else:
        second_col = take(take(mirror.ravel(), first_slot), two_sided).astype(np.int64)

    first_det, second_det = take(det, first_cell), take(det, second_cell)
    near_flat = _near_flat(first_det, second_det, two_sided)
    obtuse = None
    if radii:
        first_enter, second_enter = take(cells.enter, first_cell), take(cells.enter, second_cell)
        regular, interior = _bounds(first_enter, second_enter, two_sided)
        enter, obtuse = _facet_enter(points, cells, det, simplices, weights, exact,
                                     (first_cell, first_col, first_enter),
                                     (two_sided, second_cell, second_col, second_enter),
                                     near_flat, regular, bits)
        del first_enter, second_enter
    else:  # a mode supplies all its faces' values (core/modes/alpha_modes.py)
        enter = regular = interior = np.empty(0)  # (0,): no values
    order = sort_order_beside(enter, sort)  # while the facets' orientation and ids are found

    flip = _flips(first_col, first_det, second_col, second_det, two_sided)
    del first_det, second_det
    hull = np.flatnonzero(other_cell < 0)
    flip[hull] = _faces_centre(points, simplices[hull])

    cell_faces = _cell_faces(n_cells, width, first_slot, second_cell, second_col, two_sided)
    del first_slot, second_cell, second_col
    level = Level(simplices.astype(np.int32, copy=False), enter, regular, interior)
    facet_cells = np.empty((len(first_cell), 2), dtype=np.int32)
    facet_cells[:, 0], facet_cells[:, 1] = first_cell, other_cell
    del first_cell, other_cell, first_col, two_sided
    order = order()
    if order is None:
        cells.face_ids = cell_faces
        return level, facet_cells, flip, near_flat, obtuse
    inverse = permute_level(level, order)
    cells.face_ids = take(inverse, cell_faces.ravel()).reshape(cell_faces.shape)
    return (level, take(facet_cells, order), take(flip, order), take(near_flat, order),
            None if obtuse is None else take(obtuse, order))


def _by_facets(part: Callable[[int, int, int, int], None], two_sided: np.ndarray,
               n: int) -> None:
    """part(lo, hi, two_lo, two_hi) over the facets [lo, hi) in halves, with
    two_sided[two_lo:two_hi] (the ascending facets that have a second cell) exactly those
    in [lo, hi)."""
    def run(lo: int, hi: int) -> None:
        two_lo, two_hi = np.searchsorted(two_sided, (lo, hi))
        part(lo, hi, int(two_lo), int(two_hi))

    halves(run, n, PASSES)


def _near_flat(first_det: np.ndarray, second_det: np.ndarray, two_sided: np.ndarray
               ) -> np.ndarray:
    """(f,) bool: a facet's first cell (first_det) or its second (second_det, for the facets
    two_sided) is flat."""
    out = np.empty(len(first_det), dtype=bool)

    def part(lo: int, hi: int, two_lo: int, two_hi: int) -> None:
        np.equal(first_det[lo:hi], 0, out=out[lo:hi])
        out[two_sided[two_lo:two_hi]] |= second_det[two_lo:two_hi] == 0

    _by_facets(part, two_sided, len(first_det))
    return out


def _bounds(first_enter: np.ndarray, second_enter: np.ndarray, two_sided: np.ndarray
            ) -> tuple[np.ndarray, np.ndarray]:
    """(f,) regular and interior of the facets: the least and greatest enter of their
    cells (first_enter the first's; second_enter the second's, for the facets two_sided;
    none is inf)."""
    regular, interior = np.empty(len(first_enter)), np.empty(len(first_enter))

    def part(lo: int, hi: int, two_lo: int, two_hi: int) -> None:
        other_enter = np.full(hi - lo, np.inf)
        other_enter[two_sided[two_lo:two_hi] - lo] = second_enter[two_lo:two_hi]
        np.minimum(first_enter[lo:hi], other_enter, out=regular[lo:hi])
        np.maximum(first_enter[lo:hi], other_enter, out=interior[lo:hi])

    _by_facets(part, two_sided, len(first_enter))
    return regular, interior


def _flips(first_col: np.ndarray, first_det: np.ndarray, second_col: np.ndarray,
           second_det: np.ndarray, two_sided: np.ndarray) -> np.ndarray:
    """(f,) bool: reverse the facet's last two vertices to face out of its first cell,
    read from the better conditioned of its cells (the vertex in column first_col or
    second_col left out, signs first_det or second_det)."""
    flip = np.empty(len(first_col), dtype=bool)

    def part(lo: int, hi: int, two_lo: int, two_hi: int) -> None:
        np.not_equal((first_col[lo:hi] & 1).astype(bool), first_det[lo:hi] < 0,
                     out=flip[lo:hi])
        second = two_sided[two_lo:two_hi]
        col, sign = second_col[two_lo:two_hi], second_det[two_lo:two_hi]
        better = np.abs(sign) > np.abs(first_det[second])
        flip_other = ~((col & 1).astype(bool) ^ (sign < 0))
        flip[second[better]] = flip_other[better]

    _by_facets(part, two_sided, len(first_col))
    return flip


def _cell_faces(n_cells: int, width: int, first_slot: np.ndarray, second_cell: np.ndarray,
                second_col: np.ndarray, two_sided: np.ndarray) -> np.ndarray:
    """(c, w) int32 facet id opposite each vertex of every cell: facet f at first_slot[f]
    of its first cell and, for the facets two_sided, at column second_col of their second
    cell second_cell."""
    cell_faces = np.full((n_cells, width), -1, dtype=np.int32)
    flat = cell_faces.ravel()

    def part(lo: int, hi: int, two_lo: int, two_hi: int) -> None:
        flat[first_slot[lo:hi]] = np.arange(lo, hi, dtype=np.int32)
        slots = second_cell[two_lo:two_hi].astype(np.int64) * width + second_col[two_lo:two_hi]
        flat[slots] = two_sided[two_lo:two_hi]

    _by_facets(part, two_sided, len(first_slot))
    return cell_faces


def _drop_vertex(simplices: np.ndarray, rows: np.ndarray, drop: np.ndarray) -> np.ndarray:
    """(n, w-1) the ascending rows `rows` of (c, w) `simplices` without column `drop`; in
    cache-sized chunks, alternate ones in a helper thread."""
    out = np.empty((len(rows), simplices.shape[1] - 1), dtype=simplices.dtype)

    def part(lo: int, hi: int) -> None:
        full = np.take(simplices, rows[lo:hi], axis=0)
        gone = drop[lo:hi]
        for c in range(out.shape[1]):
            np.copyto(out[lo:hi, c], np.where(gone > c, full[:, c], full[:, c + 1]))

    in_chunks(part, len(rows), 4 * CACHE_CHUNK)
    return out

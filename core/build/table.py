"""Builds the interval table: for every Delaunay simplex, the alphas where it enters the
complex (enter), becomes a face of a higher simplex (regular) and turns interior (interior).

Rules (CGAL's GENERAL mode; ARCHITECTURE.md): a cell enters at its circumradius; a face enters
at its smallest circumradius unless attached (a cofacet's vertex strictly inside that sphere),
then with its first cofacet; regular = smallest enter among cofacets; interior = largest enter
among the cells around it, inf on the convex hull. Each level is returned sorted by enter.

Weighted points (weights = squared radii) use the same rules with orthogonal spheres and power
distance (core.geometry.power); their values are signed radii sign(p) * sqrt(|p|) of the powers p,
so every comparison is the same as on powers, and vertices enter at -sqrt(w) (or, attached, with
their first edge).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from core.build.cell_pass import CellSpheres
from core.build.table_signs import settle_cells, settle_facets, settle_obtuse
from core.geometry.circumspheres import (
    CACHE_CHUNK,
    any_point_inside,
    cell_spheres,
    circumspheres,
    edge_vectors,
    facet_radii2,
)
from core.geometry.power import (
    any_point_below,
    cell_orthospheres,
    edge_powers,
    orthospheres,
    signed_sqrt,
    triangle_powers,
)
from core.parallel import (
    PARALLEL_ABOVE,
    PASSES,
    both,
    halves,
    in_chunks,
    nonzero,
    reduce_segments,
    rows_cols,
    slot_of,
    take,
    together,
)
from core.progress import Progress
from core.tolerances import FOLD_CANDIDATE_RTOL, ILL_CONDITIONED_RTOL

#: The edge pass packs each triangle's first vertex, second vertex and 3 attach bits into
#: one int64 (first << FIRST_SHIFT | second << 3 | bits), read by one gather per incidence,
#: for tables of up to WORDS_UP_TO points (the second vertex's VERTEX_BITS bits).
VERTEX_BITS = 29
FIRST_SHIFT = VERTEX_BITS + 3
WORDS_UP_TO = 1 << VERTEX_BITS


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
    facet_interior_order: np.ndarray  # (f,) int32 facet rows sorted by interior
    # sign decisions that needed exact arithmetic (core.build.table_signs)
    exact_predicates: int = 0


def _permute(level: Level, order: np.ndarray | None) -> np.ndarray | None:
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
    return _inverse(order)


def _inverse(order: np.ndarray) -> np.ndarray:
    """(n,) int32 inverse of a permutation, its two halves scattered at once."""
    inverse = np.empty(len(order), dtype=np.int32)

    def part(lo: int, hi: int) -> None:
        inverse[order[lo:hi]] = np.arange(lo, hi, dtype=np.int32)

    halves(part, len(order), PASSES)
    return inverse


def _remap(ids: np.ndarray, inverse: np.ndarray) -> np.ndarray:
    """Apply an inverse permutation to an int32 id array that uses -1 for none: one gather
    from the inverse with -1 appended (index -1 reads it)."""
    return take(np.append(inverse, np.int32(-1)), ids.ravel()).reshape(ids.shape)


def argsort_radii(values: np.ndarray) -> np.ndarray:
    """Stable argsort of (n,) float64 values (inf allowed; negative ones for weighted
    tables), n < 2**32.

    np.sort of (float32 key, index) packed in a uint64 is several times faster than
    np.argsort here; float32 rounding is monotone, so a stable pass over the nearly sorted
    result restores the exact float64 order. The packing, unpacking and that pass run on
    two threads (the pass in two parts cut where the float32 key changes).
    """
    n = len(values)
    if n >= 2**32:
        return np.argsort(values, kind="stable")
    negative = bool(n) and bool(values.min() < 0)
    packed = np.empty(n, dtype=np.uint64)

    def pack(lo: int, hi: int) -> None:
        with np.errstate(over="ignore"):  # beyond float32's range: inf keys, fixed below
            key = values[lo:hi].astype(np.float32)
        bits = key.view(np.uint32)
        if negative:  # IEEE order as unsigned: flip negatives, set positives' sign
            bits = np.where(key < 0, ~bits, bits | np.uint32(0x80000000))
        out = packed[lo:hi]
        out[:] = bits
        out <<= np.uint64(32)
        out |= np.arange(lo, hi, dtype=np.uint64)

    halves(pack, n, PASSES)
    packed.sort()
    order = np.empty(n, dtype=np.int64)

    def unpack(lo: int, hi: int) -> None:
        np.bitwise_and(packed[lo:hi], np.uint64(0xFFFFFFFF), out=order[lo:hi].view(np.uint64))

    halves(unpack, n, PASSES)
    return stable_fix(values, order, _key_cut(packed))


def _key_cut(packed: np.ndarray) -> int:
    """A position near the middle of the sorted (key << 32 | index) array where the key
    changes: n where the middle key runs to the end, 0 for the largest key or short arrays
    (either means one part)."""
    n = len(packed)
    if n < PARALLEL_ABOVE:
        return 0
    key = int(packed[n // 2 - 1]) >> 32
    if key == 0xFFFFFFFF:
        return 0
    return int(np.searchsorted(packed, np.uint64((key + 1) << 32)))


def stable_fix(values: np.ndarray, order: np.ndarray, cut: int) -> np.ndarray:
    """order[np.argsort(values[order], kind="stable")]: in two parts on two threads when
    every value before `cut` is at most every value from it (0: in one part)."""
    def fix(lo: int, hi: int) -> np.ndarray:
        part = order[lo:hi]
        return part[np.argsort(np.take(values, part), kind="stable")]

    if 0 < cut < len(order):
        first, second = both(lambda: fix(0, cut), lambda: fix(cut, len(order)))
        if values[first[-1]] <= values[second[0]]:
            out = np.empty_like(order)
            both(lambda: np.copyto(out[:cut], first), lambda: np.copyto(out[cut:], second))
            return out
    return fix(0, len(order))


def _order(enter: np.ndarray, sort: bool) -> np.ndarray | None:
    """The order that sorts a level by enter, None when the level keeps its built order."""
    return argsort_radii(enter) if sort else None


def _order_beside(enter: np.ndarray, sort: bool) -> Callable[[], np.ndarray | None]:
    """_order started in a helper thread (core.parallel.together), for the caller to do
    the level's other work meanwhile; returns the function that waits for it."""
    if not sort:
        return lambda: None
    return together(lambda: argsort_radii(enter))


def _delay_flat(enter: np.ndarray, flat: np.ndarray, neighbors: np.ndarray) -> None:
    """Let flat cells (zero volume, from cospherical points) enter with their last neighbour.

    Qhull fills a cospherical group with some flat cells; exact triangulations have none. A
    flat cell entering before its neighbours would show a zero-thickness solid with arbitrary
    orientation; entering with them it only closes the group, as the exact complex does.
    """
    ids = np.flatnonzero(flat)
    while len(ids):
        around = neighbors[ids]
        later = np.where(around >= 0, enter[np.maximum(around, 0)], -np.inf).max(axis=1)
        grow = later > enter[ids]
        if not grow.any():
            return
        enter[ids[grow]] = later[grow]
        ids = ids[grow]


def _thin_pairs(neighbors: np.ndarray, thin: np.ndarray, flat: np.ndarray
                ) -> tuple[np.ndarray, ...]:
    """Each pair of neighbouring non-flat cells with a thin one once, as (t, i, u, j): cell
    t's neighbour opposite its vertex i is u, whose vertex j is opposite t (t < u), in no
    particular order. Read from the thin cells' rows only."""
    width = neighbors.shape[1]
    rows = np.flatnonzero(thin)
    a = np.repeat(rows, width)
    b = take(neighbors, rows).ravel().astype(np.int64)
    slot = np.tile(np.arange(width), len(rows))
    keep = b >= 0
    keep[keep] = ~flat[b[keep]]
    keep &= ~thin[np.maximum(b, 0)] | (a < b)  # two thin cells: their pair once
    a, b, slot = a[keep], b[keep], slot[keep]
    other = slot_of(neighbors, b, a)
    low = a < b
    t, u = np.where(low, a, b), np.where(low, b, a)
    return t, np.where(low, slot, other), u, np.where(low, other, slot)


def _folded(points: np.ndarray, cells: np.ndarray, neighbors: np.ndarray, det: np.ndarray,
            flat: np.ndarray) -> np.ndarray:
    """(n,) bool: non-flat cells on a fold, i.e. on the same side of a facet as a non-flat
    neighbour.

    Qhull fills exactly flat groups (decimal lattices) with cells whose float64 volume is
    rounding noise; two such cells may then overlap across their shared facet. Their signs
    are noise, so they are flat: the thinner of each pair (both if both ill-conditioned).
    Only pairs with a nearly flat cell are examined (a fold needs one).
    """
    n = len(cells)
    extent = float(np.ptp(points, axis=0).max())
    thin = (np.abs(det) <= FOLD_CANDIDATE_RTOL * extent ** points.shape[1]) & ~flat
    if not thin.any():
        return np.zeros(n, dtype=bool)
    t, i, u, j = _thin_pairs(neighbors, thin, flat)
    # facets listed in ascending vertex order: opposite sides <=> parities of i+j and of
    # the two signs differ
    fold = ((i + j) % 2 == 1) == ((det[t] < 0) ^ (det[u] < 0))
    t, u = t[fold], u[fold]
    ids = np.unique(np.concatenate((t, u)))
    vec = edge_vectors(points, cells[ids])
    scale = np.sqrt(np.prod(np.einsum("nid,nid->ni", vec, vec), axis=1))
    shape = np.zeros(n)
    shape[ids] = np.abs(det[ids]) / np.where(scale > 0, scale, 1.0)
    thin_t = shape[t] <= shape[u]
    both = (shape[t] <= ILL_CONDITIONED_RTOL) & (shape[u] <= ILL_CONDITIONED_RTOL)
    out = np.zeros(n, dtype=bool)
    out[t[thin_t | both]] = True
    out[u[~thin_t | both]] = True
    return out


def _cells(points: np.ndarray, cells: np.ndarray, neighbors: np.ndarray,
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
    flat |= _folded(points, cells, neighbors, det, flat)
    bits[flat] = 0  # flat cells' facets get the global attachment test
    if flat.any():
        det[flat] = 0.0  # orientation unknown: the facets use the other side or the hull
        _delay_flat(enter, flat, neighbors)
    level = Level(cells, enter, enter, enter)
    order = _order(enter, sort)
    if order is None:  # as built; three arrays, as _permute leaves them
        level.regular, level.interior = enter.copy(), enter.copy()
        return level, neighbors, det, bits, measure, mirror
    inverse = _permute(level, order)
    return (level, _remap(take(neighbors, order), inverse), take(det, order), take(bits, order),
            take(measure, order), None if mirror is None else take(mirror, order))


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
                 weights: np.ndarray | None, exact: list[int] | None, side0: tuple,
                 side1: tuple, near_flat: np.ndarray, regular: np.ndarray, bits: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray | None]:
    """The facets' enter values (their own radius unless attached, then `regular`) and the
    (3D) attach bits of their edges. side0 = (t0, i0, e0): every facet's first cell, the
    vertex opposite, its enter; side1 = (has1, t1, j1, e1): the same for the facets with a
    second cell."""
    t0, i0, e0 = side0
    has1, t1h, j1, e1h = side1
    radius, obtuse, global_test = _facet_spheres(points, simplices, weights, exact)
    inside0, inside1 = _attach_bits(bits, t0, i0), _attach_bits(bits, t1h, j1)
    if weights is None and exact is not None:  # doubtful float decisions made exact
        sides = [(slice(None), t0, i0, inside0, e0), (has1, t1h, j1, inside1, e1h)]
        attached, n_exact = settle_facets(points, cells.simplices, cells.enter, det, simplices,
                                          radius, sides)
        exact.append(n_exact)
    else:
        attached = inside0.copy()
        attached[has1] |= inside1
    del inside0, inside1
    if near_flat.any():
        ids = np.flatnonzero(near_flat)
        attached[ids] |= global_test(ids)
    return np.where(attached, regular, np.minimum(radius, regular)), obtuse


def _facets(points: np.ndarray, cells: Level, neighbors: np.ndarray, det: np.ndarray,
            bits: np.ndarray, weights: np.ndarray | None = None,
            exact: list[int] | None = None, sort: bool = True, radii: bool = True,
            mirror: np.ndarray | None = None):
    """Level d-1 from the cells' neighbour table: each shared facet taken once. Every
    per-cell value is gathered once per side (the second side's gathers are random) on
    two threads (core.parallel.take). radii=False: no values for the facets ((0,) arrays),
    only their structure. `mirror`: the neighbours' columns that point back, if
    known (else found from their rows)."""
    n_cells, width = cells.simplices.shape
    def keep(lo: int, hi: int) -> np.ndarray:
        rows = neighbors[lo:hi]
        return (rows > np.arange(lo, hi, dtype=np.int32)[:, None]) | (rows < 0)

    slot0 = nonzero(keep, n_cells)  # cell-major, as np.nonzero lists them
    t0, i0 = rows_cols(slot0, width)
    t1 = take(neighbors.ravel(), slot0)
    simplices = _drop_vertex(cells.simplices, t0, i0)
    has1 = np.flatnonzero(t1 >= 0)
    t1h = take(t1, has1)
    if mirror is None:
        j1 = slot_of(neighbors, t1h, take(t0, has1))
    else:
        j1 = take(take(mirror.ravel(), slot0), has1).astype(np.int64)

    det0, det1 = take(det, t0), take(det, t1h)
    near_flat = _near_flat(det0, det1, has1)
    obtuse = None
    if radii:
        e0, e1h = take(cells.enter, t0), take(cells.enter, t1h)
        regular, interior = _bounds(e0, e1h, has1)
        enter, obtuse = _facet_enter(points, cells, det, simplices, weights, exact,
                                     (t0, i0, e0), (has1, t1h, j1, e1h), near_flat, regular,
                                     bits)
        del e0, e1h
    else:  # a mode supplies all its faces' values (core/modes/alpha_modes.py)
        enter = regular = interior = np.empty(0)  # (0,): no values
    order = _order_beside(enter, sort)  # while the facets' orientation and ids are found

    flip = _flips(i0, det0, j1, det1, has1)
    del det0, det1
    hull = np.flatnonzero(t1 < 0)
    flip[hull] = _faces_centre(points, simplices[hull])

    cell_faces = _cell_faces(n_cells, width, slot0, t1h, j1, has1)
    del slot0, t1h, j1
    level = Level(simplices.astype(np.int32, copy=False), enter, regular, interior)
    facet_cells = np.empty((len(t0), 2), dtype=np.int32)
    facet_cells[:, 0], facet_cells[:, 1] = t0, t1
    del t0, t1, i0, has1
    order = order()
    if order is None:
        cells.face_ids = cell_faces
        return level, facet_cells, flip, near_flat, obtuse
    inverse = _permute(level, order)
    cells.face_ids = take(inverse, cell_faces.ravel()).reshape(cell_faces.shape)
    return (level, take(facet_cells, order), take(flip, order), take(near_flat, order),
            None if obtuse is None else take(obtuse, order))


def _by_facets(part: Callable[[int, int, int, int], None], has1: np.ndarray, n: int) -> None:
    """part(lo, hi, k0, k1) over the facets [lo, hi) in halves, with has1[k0:k1] (the
    ascending facets that have a second cell) exactly those in [lo, hi)."""
    def run(lo: int, hi: int) -> None:
        k0, k1 = np.searchsorted(has1, (lo, hi))
        part(lo, hi, int(k0), int(k1))

    halves(run, n, PASSES)


def _near_flat(det0: np.ndarray, det1: np.ndarray, has1: np.ndarray) -> np.ndarray:
    """(f,) bool: a facet's first cell (det0) or its second (det1, for the facets has1)
    is flat."""
    out = np.empty(len(det0), dtype=bool)

    def part(lo: int, hi: int, k0: int, k1: int) -> None:
        np.equal(det0[lo:hi], 0, out=out[lo:hi])
        out[has1[k0:k1]] |= det1[k0:k1] == 0

    _by_facets(part, has1, len(det0))
    return out


def _bounds(e0: np.ndarray, e1h: np.ndarray, has1: np.ndarray
            ) -> tuple[np.ndarray, np.ndarray]:
    """(f,) regular and interior of the facets: the least and greatest enter of their
    cells (e0 the first's; e1h the second's, for the facets has1; none is inf)."""
    regular, interior = np.empty(len(e0)), np.empty(len(e0))

    def part(lo: int, hi: int, k0: int, k1: int) -> None:
        e1 = np.full(hi - lo, np.inf)
        e1[has1[k0:k1] - lo] = e1h[k0:k1]
        np.minimum(e0[lo:hi], e1, out=regular[lo:hi])
        np.maximum(e0[lo:hi], e1, out=interior[lo:hi])

    _by_facets(part, has1, len(e0))
    return regular, interior


def _flips(i0: np.ndarray, det0: np.ndarray, j1: np.ndarray, det1: np.ndarray,
           has1: np.ndarray) -> np.ndarray:
    """(f,) bool: reverse the facet's last two vertices to face out of its first cell,
    read from the better conditioned of its cells (vertex i0/j1 left out, signs det0/det1)."""
    flip = np.empty(len(i0), dtype=bool)

    def part(lo: int, hi: int, k0: int, k1: int) -> None:
        np.not_equal((i0[lo:hi] & 1).astype(bool), det0[lo:hi] < 0, out=flip[lo:hi])
        second = has1[k0:k1]
        better = np.abs(det1[k0:k1]) > np.abs(det0[second])
        flip_other = ~((j1[k0:k1] & 1).astype(bool) ^ (det1[k0:k1] < 0))
        flip[second[better]] = flip_other[better]

    _by_facets(part, has1, len(i0))
    return flip


def _cell_faces(n_cells: int, width: int, slot0: np.ndarray, t1h: np.ndarray,
                j1: np.ndarray, has1: np.ndarray) -> np.ndarray:
    """(c, w) int32 facet id opposite each vertex of every cell: facet f at slot0[f] of its
    first cell and, for the facets has1, at column j1 of their second cell t1h."""
    cell_faces = np.full((n_cells, width), -1, dtype=np.int32)
    flat = cell_faces.ravel()

    def part(lo: int, hi: int, k0: int, k1: int) -> None:
        flat[slot0[lo:hi]] = np.arange(lo, hi, dtype=np.int32)
        flat[t1h[k0:k1].astype(np.int64) * width + j1[k0:k1]] = has1[k0:k1]

    _by_facets(part, has1, len(slot0))
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


def _edge_incidences(triangles: np.ndarray, n_points: int) -> tuple[np.ndarray, np.ndarray, bool]:
    """Edge keys a*m+b (ascending) and triangle ids of all triangle-edge incidences, and
    whether the ids ascend within each key.

    Packs key and triangle id into one uint64 when they fit, because np.sort is several
    times faster than np.argsort on this machine class (and, vectorised, than two sorted
    halves and a merge); the packing and unpacking run on two threads.
    """
    m = np.uint64(n_points)
    nt = len(triangles)
    key_bits = (n_points * n_points - 1).bit_length()
    tri_bits = max(1, (nt - 1).bit_length())
    pairs = ((0, 1), (0, 2), (1, 2))
    if key_bits + tri_bits <= 64:
        shift = np.uint64(tri_bits)
        packed = np.empty(3 * nt, dtype=np.uint64)

        def pack(lo: int, hi: int) -> None:
            tid = np.arange(lo, hi, dtype=np.uint64)
            cols = [triangles[lo:hi, c].astype(np.uint64) for c in range(3)]
            for k, (i, j) in enumerate(pairs):
                out = packed[k * nt + lo:k * nt + hi]
                np.multiply(cols[i], m, out=out)
                out += cols[j]
                out <<= shift
                out |= tid

        in_chunks(pack, nt, 4 * CACHE_CHUNK)
        packed.sort()
        tri_ids = np.empty(len(packed), dtype=np.int32)

        def unpack(lo: int, hi: int) -> None:
            np.bitwise_and(packed[lo:hi], np.uint64((1 << tri_bits) - 1), out=tri_ids[lo:hi],
                           casting="unsafe")
            packed[lo:hi] >>= shift

        halves(unpack, len(packed), PASSES)
        return packed.view(np.int64), tri_ids, True
    keys = np.concatenate([triangles[:, i].astype(np.int64) * n_points + triangles[:, j]
                           for i, j in pairs])
    order = np.argsort(keys)
    return keys[order], (order % nt).astype(np.int32), False


def _incidences(keys: np.ndarray, tri_ids: np.ndarray, is_start: np.ndarray,
                tris: np.ndarray, bits: np.ndarray | None, m: int
                ) -> tuple[np.ndarray | None, np.ndarray]:
    """For the sorted incidences (edge key, triangle id): (n,) bool attach bit of each
    (the triangle's vertex opposite the edge is inside its diametral sphere; None without
    `bits`) and the (3 t,) int32 edge number of every triangle's three edges; in chunks on
    two threads."""
    inside = None if bits is None else np.empty(len(keys), dtype=bool)
    face_ids = np.empty(tris.size, dtype=np.int32)
    size = 4 * CACHE_CHUNK
    base = np.cumsum([0] + [np.count_nonzero(is_start[lo:lo + size])
                            for lo in range(0, len(keys), size)])
    words = _triangle_words(tris, bits) if m <= WORDS_UP_TO else None

    def part(lo: int, hi: int) -> None:
        t = tri_ids[lo:hi]
        a = keys[lo:hi] // m  # a floor division by a constant: much faster than divmod
        b = keys[lo:hi] - a * m
        if words is None:
            local = np.where(a != tris[t, 0], 0, np.where(b == tris[t, 1], 2, 1))
            if inside is not None:
                inside[lo:hi] = (bits[t] >> local) & 1
        else:  # one random gather per incidence instead of three
            word = np.take(words, t)
            local = np.where(a != word >> FIRST_SHIFT, 0,
                             np.where(b == (word >> 3) & (WORDS_UP_TO - 1), 2, 1))
            if inside is not None:
                inside[lo:hi] = (word >> local) & 1
        edge_of = np.cumsum(is_start[lo:hi], dtype=np.int64) + (int(base[lo // size]) - 1)
        face_ids[3 * t.astype(np.int64) + local] = edge_of

    in_chunks(part, len(keys), size)
    return inside, face_ids


def _triangle_words(tris: np.ndarray, bits: np.ndarray | None) -> np.ndarray:
    """(t,) int64 first vertex << FIRST_SHIFT | second vertex << 3 | attach bits of every
    triangle (vertices below WORDS_UP_TO), so an incidence reads its triangle in one gather;
    in halves."""
    words = np.empty(len(tris), dtype=np.int64)

    def part(lo: int, hi: int) -> None:
        out = words[lo:hi]
        out[:] = tris[lo:hi, 0]
        out <<= VERTEX_BITS
        out += tris[lo:hi, 1]
        out <<= 3
        if bits is not None:
            out |= bits[lo:hi] & 7  # one bit per vertex

    halves(part, len(tris), PASSES)
    return words


def _gathered(source: np.ndarray, ids: np.ndarray | None) -> Callable[[int, int], np.ndarray]:
    """(lo, hi) -> source[ids[lo:hi]] (source[lo:hi] without ids), for reduce_segments."""
    if ids is None:
        return lambda lo, hi: source[lo:hi]
    return lambda lo, hi: np.take(source, ids[lo:hi])


def _edge_enter(points: np.ndarray, simplices: np.ndarray, regular: np.ndarray,
                attached: np.ndarray, check: np.ndarray,
                weights: np.ndarray | None) -> np.ndarray:
    """(e,) enter of the (e, 2) edges `simplices`: their own (half length, or signed radius
    of power) unless attached; the edges `check` get the global attachment test. The half
    lengths in cache-sized chunks, alternate ones in a helper thread."""
    a, b = simplices[:, 0], simplices[:, 1]
    if weights is None:
        half = np.empty(len(simplices))

        def part(lo: int, hi: int) -> None:
            ends = np.take(points, b[lo:hi], axis=0) - np.take(points, a[lo:hi], axis=0)
            half[lo:hi] = 0.5 * np.sqrt((ends ** 2).sum(axis=1))

        in_chunks(part, len(simplices), 4 * CACHE_CHUNK)
        if len(check):
            centres = 0.5 * (points[a[check]] + points[b[check]])
            attached[check] |= any_point_inside(points, centres, half[check] ** 2)
    else:
        power, centres, _ = edge_powers(points, weights, simplices.astype(np.int64))
        half = signed_sqrt(power)
        if len(check):
            attached[check] |= any_point_below(points, weights, centres[check], power[check])
    out = np.empty(len(half))

    def choose(lo: int, hi: int) -> None:
        out[lo:hi] = np.where(attached[lo:hi], regular[lo:hi],
                              np.minimum(half[lo:hi], regular[lo:hi]))

    halves(choose, len(half), PASSES)
    return out


def _starts(keys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(n,) bool: each of the ascending `keys` differs from the one before (the first is a
    start), and (k,) int64 the positions of those starts; on two threads."""
    is_start = np.empty(len(keys), dtype=bool)

    def boundaries(lo: int, hi: int) -> np.ndarray:
        mark = is_start[lo:hi]
        if lo == 0:
            mark[:1] = True
            np.not_equal(keys[1:hi], keys[:max(hi - 1, 0)], out=mark[1:])
        else:
            np.not_equal(keys[lo:hi], keys[lo - 1:hi - 1], out=mark)
        return mark

    return is_start, nonzero(boundaries, len(keys))


def _edge_ends(keys: np.ndarray, starts: np.ndarray, m: int) -> np.ndarray:
    """(k, 2) int32 vertices (a, b) of the edge keys a * m + b at `starts`; in halves."""
    simplices = np.empty((len(starts), 2), dtype=np.int32)

    def part(lo: int, hi: int) -> None:
        edge = np.take(keys, starts[lo:hi])
        simplices[lo:hi, 0] = first = edge // m
        simplices[lo:hi, 1] = edge - first * m

    halves(part, len(starts), PASSES)
    return simplices


def _edges(points: np.ndarray, triangles: Level, near_flat: np.ndarray,
           bits: np.ndarray | None, weights: np.ndarray | None = None,
           sort: bool = True) -> Level:
    """Level 1 (3D) from the triangles: unique edges and their aggregated cofacet values.

    `bits` (bit j: vertex j attaches the opposite edge) come from facet_radii2; edges of
    triangles next to flat cells (`near_flat`) get the global attachment test. bits=None:
    the edges get no values at all ((0,) arrays: a mode supplies them), only their
    vertices and the triangles' face ids.
    """
    m = len(points)
    tris = triangles.simplices
    keys, tri_ids, ids_ascend = _edge_incidences(tris, m)
    is_start, starts = _starts(keys)
    inside, face_ids = _incidences(keys, tri_ids, is_start, tris, bits, m)
    del is_start
    simplices = _edge_ends(keys, starts, m)
    if bits is None:  # a mode supplies every value (core/modes/alpha_modes.py)
        triangles.face_ids = face_ids.reshape(-1, 3)
        return Level(simplices, np.empty(0), np.empty(0), np.empty(0))
    n = len(keys)
    if ids_ascend and sort:  # triangles sorted by enter: each edge's first is its least
        regular = take(triangles.enter, take(tri_ids, starts))
    else:
        regular = reduce_segments(np.minimum, _gathered(triangles.enter, tri_ids), starts, n,
                                  np.float64)
    interior = reduce_segments(np.maximum, _gathered(triangles.interior, tri_ids), starts, n,
                               np.float64)
    attached = reduce_segments(np.logical_or, _gathered(inside, None), starts, n, bool)
    # the edges of the (few) triangles next to flat cells, from their face ids: no gather
    # over all incidences
    check = np.unique(face_ids.reshape(-1, 3)[np.flatnonzero(near_flat)])
    del keys, tri_ids, inside
    enter = _edge_enter(points, simplices, regular, attached, check, weights)
    level = Level(simplices, enter, regular, interior)
    inverse = _permute(level, _order(enter, sort))
    triangles.face_ids = (face_ids if inverse is None else take(inverse, face_ids)).reshape(-1, 3)
    return level


def _vertices(n_points: int, edges: Level, points: np.ndarray | None = None,
              weights: np.ndarray | None = None) -> Level:
    """Level 0: vertices enter at 0 (weighted: at -sqrt(w), or with their first edge when
    a neighbour has negative power to their sphere); regular/interior over their edges.
    Edges without values (a mode's table) give vertices without values."""
    edges.face_ids = edges.simplices[:, ::-1].copy()
    simplices = np.arange(n_points, dtype=np.int32)[:, None]
    if len(edges.enter) < len(edges.simplices):
        return Level(simplices, np.empty(0), np.empty(0), np.empty(0))
    regular = np.full(n_points, np.inf)
    interior = np.full(n_points, -np.inf)
    for col in (0, 1):
        np.minimum.at(regular, edges.simplices[:, col], edges.enter)
        np.maximum.at(interior, edges.simplices[:, col], edges.interior)
    if weights is None:
        return Level(simplices, np.zeros(n_points), regular, interior)
    bits = edge_powers(points, weights, edges.simplices)[2]
    attached = np.zeros(n_points, dtype=bool)
    attached[edges.simplices[(bits & 2) != 0, 0]] = True  # vertex 1 below vertex 0's power
    attached[edges.simplices[(bits & 1) != 0, 1]] = True
    enter = np.where(attached, regular, np.minimum(signed_sqrt(-weights), regular))
    return Level(simplices, enter, regular, interior)


def build_table(points: np.ndarray, cells: np.ndarray, neighbors: np.ndarray,
                progress: Progress | None = None, weights: np.ndarray | None = None,
                exact: bool = True, spheres: CellSpheres | None = None, *,
                sort: bool = True, radii: bool = True, mirror: np.ndarray | None = None
                ) -> Table:
    """The interval table of the Delaunay cells of `points` ((m, d) float64, well scaled).

    With (m,) `weights` (squared radii >= 0, same scale), the cells are the regular
    triangulation's and the values signed radii of powers (module docstring). `exact`: the
    classic table's doubtful sign decisions and ill-conditioned radii are made exact
    (core/build/table_signs.py); False keeps the floating-point ones. `spheres`: the classic
    cells' spheres from the certification's shared pass (core.build.cell_pass), consumed.

    For an alpha mode (core/modes/alpha_modes.py), which supplies its own values and sorts once by
    them: sort=False keeps every level in the order it was built (ids consistent; no
    facet_interior_order), and radii=False (with sort=False) computes no values for the
    faces (their enter, regular and interior are (0,) arrays: the mode computes its own
    from the structure; the cells keep their classic values). `mirror`:
    (t, d+1) int8, each neighbour's column that holds the cell (core.build.delaunay.Triangulation),
    when known: saves finding it by a random gather of the neighbours' rows."""
    if sort and not radii:
        raise ValueError("radii=False is for an unsorted table (sort=False)")
    def step(fraction: float, stage: str) -> None:
        if progress is not None:
            progress(fraction, stage)

    d = points.shape[1]
    step(0.0, "circumspheres of cells")
    exact_counts: list[int] | None = [] if exact else None
    top, neighbors, det, bits, measure, mirror = _cells(points, cells, neighbors, weights,
                                                        exact_counts, spheres, sort, mirror)
    step(0.2, "facets")
    facets, facet_cells, flip, near_flat, obtuse = _facets(points, top, neighbors, det, bits,
                                                           weights, exact_counts, sort, radii,
                                                           mirror)
    del neighbors, mirror
    levels = [facets, top]
    if d == 3:
        step(0.55, "edges")
        levels.insert(0, _edges(points, facets, near_flat, obtuse, weights, sort))
    step(0.9, "vertices")
    # the facets' interior order sorts (GIL released) while the vertices reduce their edges
    interior_order = (together(lambda: argsort_radii(facets.interior).astype(np.int32))
                      if sort else lambda: np.empty(0, dtype=np.int32))
    levels.insert(0, _vertices(len(points), levels[0], points, weights))
    by_interior = interior_order()
    step(1.0, "done")
    return Table(levels, facet_cells, flip, measure, by_interior, sum(exact_counts or []))


"""The edge pass of a 3D interval table: the unique edges of the triangles (their incidences
sorted as packed keys), each edge's value (half its length, or signed radius of power,
unless attached) and its triangles' least enter and greatest interior."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from core.build.levels import Level, permute_level
from core.build.sorting import sort_order
from core.geometry.circumspheres import CACHE_CHUNK, any_point_inside
from core.geometry.power import any_point_below, edge_powers, signed_sqrt
from core.parallel import PASSES, halves, in_chunks, nonzero, reduce_segments, take

#: The edge pass packs each triangle's first vertex, second vertex and 3 attach bits into
#: one int64 (first << FIRST_SHIFT | second << 3 | bits), read by one gather per incidence,
#: for tables of up to WORDS_UP_TO points (the second vertex's VERTEX_BITS bits).
VERTEX_BITS = 29
FIRST_SHIFT = VERTEX_BITS + 3
WORDS_UP_TO = 1 << VERTEX_BITS
#: Edge keys of up to this many bits (up to 65,536 points) are sorted by two passes of a
#: radix sort (_radix_order); longer ones as packed (key, triangle) words.
RADIX_KEY_BITS = 32


def _edge_incidences(triangles: np.ndarray, n_points: int
                     ) -> tuple[np.ndarray, np.ndarray, bool, np.ndarray | None]:
    """Edge keys a*m+b (ascending) and triangle ids of all triangle-edge incidences,
    whether the ids ascend within each key, and (radix sort only; else None) the sorting
    order of the rows 3 i + j (triangle i's edge j: vertices 01, 02, 12), whose j says which
    of the triangle's vertices is opposite the edge.

    Keys of up to RADIX_KEY_BITS bits by a radix sort (_radix_order); longer ones with the
    triangle id packed into one uint64 when they fit, because np.sort is several
    times faster than np.argsort on this machine class (and, vectorised, than two sorted
    halves and a merge); the packing and unpacking run on two threads.
    """
    key_bits = (n_points * n_points - 1).bit_length()
    if key_bits <= RADIX_KEY_BITS:
        keys, order = _radix_order(triangles, n_points, key_bits)
        return take(keys, order), np.floor_divide(order, 3).astype(np.int32), True, order
    m = np.uint64(n_points)
    nt = len(triangles)
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
        return packed.view(np.int64), tri_ids, True, None
    keys = np.concatenate([triangles[:, i].astype(np.int64) * n_points + triangles[:, j]
                           for i, j in pairs])
    order = np.argsort(keys)
    return keys[order], (order % nt).astype(np.int32), False, None


def _radix_order(triangles: np.ndarray, n_points: int, key_bits: int
                 ) -> tuple[np.ndarray, np.ndarray]:
    """(3 t,) int64 edge keys a*m+b of every triangle's edges, triangle by triangle (row
    3 i + j: triangle i's edge j), and the stable order that sorts them: a least significant
    digit radix sort, one stable argsort of 16-bit digits per pass (numpy sorts those by
    counting), so equal keys keep their triangles ascending, as the packed sort orders them."""
    keys = np.empty((len(triangles), 3), dtype=np.int64)
    first = triangles[:, 0].astype(np.int64) * n_points
    np.add(first, triangles[:, 1], out=keys[:, 0])
    np.add(first, triangles[:, 2], out=keys[:, 1])
    np.multiply(triangles[:, 1].astype(np.int64), n_points, out=keys[:, 2])
    keys[:, 2] += triangles[:, 2]
    keys = keys.ravel()
    order = None
    for shift in range(0, key_bits, 16):  # the cast keeps the low 16 bits
        current = keys if order is None else take(keys, order)
        digit = (current >> shift if shift else current).astype(np.uint16)
        step = np.argsort(digit, kind="stable")
        order = step if order is None else take(order, step)
    return keys, order


def _incidences(keys: np.ndarray, tri_ids: np.ndarray, is_start: np.ndarray,
                tris: np.ndarray, bits: np.ndarray | None, m: int,
                order: np.ndarray | None = None) -> tuple[np.ndarray | None, np.ndarray]:
    """For the sorted incidences (edge key, triangle id): (n,) bool attach bit of each
    (the triangle's vertex opposite the edge is inside its diametral sphere; None without
    `bits`) and the (3 t,) int32 edge number of every triangle's three edges; in chunks on
    two threads. `order` (the radix sort's, _edge_incidences) says which vertex is
    opposite each edge without reading the triangles."""
    inside = None if bits is None else np.empty(len(keys), dtype=bool)
    face_ids = np.empty(tris.size, dtype=np.int32)
    size = 4 * CACHE_CHUNK
    base = np.cumsum([0] + [np.count_nonzero(is_start[lo:lo + size])
                            for lo in range(0, len(keys), size)])
    words = _triangle_words(tris, bits) if m <= WORDS_UP_TO and order is None else None

    def part(lo: int, hi: int) -> None:
        t = tri_ids[lo:hi]
        if order is not None:  # row 3 t + j: edge j (01, 02, 12) is opposite vertex 2 - j
            opposite = t.astype(np.int64)  # becomes the vertex opposite each edge
            opposite *= -3
            opposite += order[lo:hi]  # j
            np.subtract(2, opposite, out=opposite)
            if inside is not None:
                inside[lo:hi] = (np.take(bits, t) >> opposite) & 1
            edge_of = np.cumsum(is_start[lo:hi], dtype=np.int64) + (int(base[lo // size]) - 1)
            face_ids[3 * t.astype(np.int64) + opposite] = edge_of
            return
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
                weights: np.ndarray | None) -> tuple[np.ndarray, np.ndarray | None]:
    """(e,) enter of the (e, 2) edges `simplices`: their own (half length, or signed radius
    of power) unless attached; the edges `check` get the global attachment test. The half
    lengths in cache-sized chunks, alternate ones in a helper thread. Second: weighted, the
    (e,) uint8 bits of edge_powers (which vertex lies below the other's power), else None."""
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
        power, centres, below = edge_powers(points, weights, simplices.astype(np.int64))
        half = signed_sqrt(power)
        if len(check):
            attached[check] |= any_point_below(points, weights, centres[check], power[check])
    out = np.empty(len(half))

    def choose(lo: int, hi: int) -> None:
        out[lo:hi] = np.where(attached[lo:hi], regular[lo:hi],
                              np.minimum(half[lo:hi], regular[lo:hi]))

    halves(choose, len(half), PASSES)
    return out, None if weights is None else below


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


def edge_level(points: np.ndarray, triangles: Level, near_flat: np.ndarray,
               bits: np.ndarray | None, weights: np.ndarray | None = None,
               sort: bool = True) -> tuple[Level, np.ndarray | None]:
    """Level 1 (3D) from the triangles: unique edges and their aggregated cofacet values.

    `bits` (bit j: vertex j attaches the opposite edge) come from facet_radii2; edges of
    triangles next to flat cells (`near_flat`) get the global attachment test. bits=None:
    the edges get no values at all ((0,) arrays: a mode supplies them), only their
    vertices and the triangles' face ids. Second: weighted, each edge's (e,) uint8 bits of
    core.geometry.power.edge_powers in the level's order (for the vertex level), else None.
    """
    m = len(points)
    tris = triangles.simplices
    keys, tri_ids, ids_ascend, order = _edge_incidences(tris, m)
    is_start, starts = _starts(keys)
    inside, face_ids = _incidences(keys, tri_ids, is_start, tris, bits, m, order)
    del is_start, order
    simplices = _edge_ends(keys, starts, m)
    if bits is None:  # a mode supplies every value (core/modes/alpha_modes.py)
        triangles.face_ids = face_ids.reshape(-1, 3)
        return Level(simplices, np.empty(0), np.empty(0), np.empty(0)), None
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
    enter, below = _edge_enter(points, simplices, regular, attached, check, weights)
    level = Level(simplices, enter, regular, interior)
    order = sort_order(enter, sort)
    inverse = permute_level(level, order)
    triangles.face_ids = (face_ids if inverse is None else take(inverse, face_ids)).reshape(-1, 3)
    return level, below if below is None or order is None else take(below, order)

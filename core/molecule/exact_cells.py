"""The part of a union of balls inside chosen tetrahedra, exact, clipped to each tetrahedron.

The power cells V_a of the balls tile space, and within V_a a point is in the union exactly
when it is in B_a (a point of V_a inside some ball is inside B_a, whose power there is the
least), so the union inside a tetrahedron T is the disjoint union of the convex pieces
B_a ∩ V_a ∩ T, and its boundary there is the sphere of a inside V_a ∩ T (`clipped`). Only
the balls that meet T count, and of V_a's planes (one per edge ab of the triangulation) only
those that cut both B_a and T. The sector split of `sectors` is exact for a tetrahedron that
no foreign ball meets and whose balls do not cross their opposite facets; the others
(`needs_clipping`) are measured here.
"""

from __future__ import annotations

import itertools

import numpy as np
from scipy.spatial import cKDTree

from core.molecule.clipped import ball_in_polyhedron
from core.tolerances import CAP_BEYOND_RTOL

CHUNK = 1024  # ball pieces per vectorized batch (each holds P(P-1) x P plane tests)
BLOCK = 20_000  # (ball, cell) pairs whose power planes are sorted out at once
NEAR_BLOCK = 4096  # cells whose nearby balls are gathered at once


def length(v: np.ndarray) -> np.ndarray:
    """Euclidean length over the last axis (3) of v, as np.linalg.norm gives it, written
    out: numpy reduces a short last axis row by row, several times slower."""
    return np.sqrt(v[..., 0] * v[..., 0] + v[..., 1] * v[..., 1] + v[..., 2] * v[..., 2])


def cell_planes(c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """((t, 4, 3) outward unit normals, (t, 4) offsets) of the facets opposite each vertex
    of tetrahedra c (t, 4, 3): the cell is {x: N·x <= b}."""
    normals = np.empty(c.shape)
    offsets = np.empty(c.shape[:2])
    for v in range(4):
        i, j, k = (w for w in range(4) if w != v)
        n = np.cross(c[:, j] - c[:, i], c[:, k] - c[:, i])
        n /= length(n)[:, None]
        flip = np.einsum("ij,ij->i", n, c[:, v] - c[:, i]) > 0
        n[flip] *= -1
        normals[:, v] = n
        offsets[:, v] = np.einsum("ij,ij->i", n, c[:, i])
    return normals, offsets


def _distance(corners: np.ndarray, x: np.ndarray) -> np.ndarray:
    """(m,) Euclidean distance from points x (m, 3) to tetrahedra corners (m, 4, 3): 0
    inside, else the least over the facets the point projects into and over the edges."""
    normals, offsets = cell_planes(corners)
    side = np.einsum("mvc,mc->mv", normals, x) - offsets  # > 0: beyond that facet
    best = np.full(len(x), np.inf)
    for v in range(4):
        i, j, k = (w for w in range(4) if w != v)
        y = x - side[:, v, None] * normals[:, v]  # projection onto the facet's plane
        into = np.ones(len(x), bool)
        for a, b, o in ((i, j, k), (j, k, i), (k, i, j)):
            n = np.cross(corners[:, b] - corners[:, a], normals[:, v])
            into &= (np.einsum("mc,mc->m", n, y - corners[:, a])
                     * np.einsum("mc,mc->m", n, corners[:, o] - corners[:, a])) >= 0
        best = np.where(into & (side[:, v] > 0), np.minimum(best, side[:, v]), best)
    for a, b in ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)):
        e = corners[:, b] - corners[:, a]
        t = np.clip(np.einsum("mc,mc->m", x - corners[:, a], e)
                    / np.einsum("mc,mc->m", e, e), 0.0, 1.0)
        best = np.minimum(best, length(x - corners[:, a] - t[:, None] * e))
    return np.where((side <= 0).all(1), 0.0, best)


def near_balls(facts, rows: np.ndarray, tree: cKDTree) -> tuple[np.ndarray, np.ndarray]:
    """Pairs (position in rows, ball) (m,) int64 of the balls of K that meet each cell,
    by position. Cells are taken NEAR_BLOCK at a time: their candidates' temporaries stay
    in cache, where all cells' at once do not."""
    vertex = facts.vertices_in()
    parts = [_near_block(facts, rows[start:start + NEAR_BLOCK], tree, vertex)
             for start in range(0, len(rows), NEAR_BLOCK)]
    if not parts:
        return np.zeros(0, np.int64), np.zeros(0, np.int64)
    return (np.concatenate([i + start for (i, _), start in
                            zip(parts, range(0, len(rows), NEAR_BLOCK), strict=True)]),
            np.concatenate([j for _, j in parts]))


def _near_block(facts, rows: np.ndarray, tree: cKDTree, vertex: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray]:
    """near_balls of a block of rows; vertex (n,) bool: facts.vertices_in()."""
    c = facts.centres[facts.cells[rows]]
    g = c.mean(1)
    reach = length(c - g[:, None]).max(1)
    lists = tree.query_ball_point(g, reach + facts.radii.max())
    count = np.fromiter(map(len, lists), np.int64, len(lists))
    i = np.repeat(np.arange(len(rows)), count)
    j = np.fromiter(itertools.chain.from_iterable(lists), np.int64, int(count.sum()))
    x, r = facts.centres[j], facts.radii[j]
    keep = vertex[j] & (length(x - g[i]) <= reach[i] + r)
    i, j, x, r = i[keep], j[keep], x[keep], r[keep]
    normals, offsets = cell_planes(c)
    side = np.einsum("mvc,mc->mv", normals[i], x) - offsets[i]  # > r: wholly beyond a facet
    i, j, x, r, side = (a[(side <= r[:, None]).all(1)] for a in (i, j, x, r, side))
    keep = (side <= 0).all(1) | (length(c[i] - x[:, None])
                                 <= r[:, None]).any(1)  # holds its centre or a corner
    ask = np.flatnonzero(~keep)
    keep[ask] = _distance(c[i[ask]], x[ask]) <= r[ask]
    return i[keep], j[keep]


def needs_clipping(facts, rows: np.ndarray, pairs: tuple[np.ndarray, np.ndarray]
                   ) -> np.ndarray:
    """(len(rows),) bool: cells whose sector measure may differ from the union inside them
    (a ball reaches over its opposite facet or is no vertex of K, or a foreign ball may
    meet the cell); pairs: `near_balls` of rows."""
    v = facts.cells[rows]
    c = facts.centres[v]
    normals, offsets = cell_planes(c)
    height = offsets - np.einsum("tvc,tvc->tv", normals, c)
    over = (facts.radii[v] > height).any(1) | ~facts.vertices_in()[v].all(1)
    i, j = pairs
    foreign = (v[i] != j[:, None]).all(1)
    over[i[foreign]] = True
    return over


def neighbours(facts) -> tuple[np.ndarray, np.ndarray]:
    """(starts (n+1,), others) int64: the balls joined to each ball by an edge of the
    triangulation, others[starts[a]:starts[a+1]]; their planes bound a's power cell."""
    n = len(facts.radii)
    a = facts.cells[:, [0, 0, 0, 1, 1, 2, 3, 3, 3, 2, 2, 1]].ravel()
    b = facts.cells[:, [1, 2, 3, 2, 3, 3, 0, 1, 2, 0, 1, 0]].ravel()
    key = np.sort(a * n + b)  # distinct by sorting: cheaper than np.unique here
    key = key[np.concatenate(([True], key[1:] != key[:-1]))]
    return np.searchsorted(key // n, np.arange(n + 1)), key % n


def _every(flags: np.ndarray) -> np.ndarray:
    """(m,) flags (m, 4) all true along their rows (as .all(1), written out: faster)."""
    return flags[:, 0] & flags[:, 1] & flags[:, 2] & flags[:, 3]


def _some(flags: np.ndarray) -> np.ndarray:
    """(m,) flags (m, 4) any true along their rows (as .any(1), written out: faster)."""
    return flags[:, 0] | flags[:, 1] | flags[:, 2] | flags[:, 3]


def cap_low(bound: np.ndarray, radius: np.ndarray, cos: np.ndarray) -> np.ndarray:
    """The least of n'·x over the cap {|x| <= radius, n·x >= bound} of a ball about the
    origin, for unit n' at cosine `cos` to n: -radius when the ball's point -radius·n' is in
    the cap, else the least over the cap's disk (centre bound·n, radius sqrt(r² - bound²))."""
    rho = np.sqrt(np.maximum(radius * radius - bound * bound, 0.0))
    low = bound * cos - rho * np.sqrt(np.maximum(1.0 - cos * cos, 0.0))
    return np.where(-radius * cos >= bound, -radius, low)


def _cap_beyond(normal, bound, radius, facet_normals, facet_offsets) -> np.ndarray:
    """(r,) bool: power planes (unit normal, bound about the ball's centre, its radius) whose
    cap lies wholly beyond a facet of the cell (facet_normals (r, 4, 3), facet_offsets (r, 4)
    about the centre), by the margin CAP_BEYOND_RTOL: they cut nothing of the ball inside
    the cell, so they are left out (each plane costs a piece's clipping about P² lines)."""
    cos = np.einsum("mvc,mc->mv", facet_normals, normal)
    return _some(cap_low(bound[:, None], radius[:, None], cos)
                 > facet_offsets + (CAP_BEYOND_RTOL * radius)[:, None])


def _power_planes(facts, pair_i, pair_j, corners, planes, starts, others):
    """(piece (r,), normals (r, 3), offsets (r,) about the piece's centre) of the power
    planes that may cut a piece's ball inside its cell, and (pieces,) bool: the piece is
    empty (its ball or its cell wholly beyond one power plane). A plane is left out when
    the ball or the cell lies on its inner side, or when the cap it cuts off the ball is
    beyond a facet plane of the cell (`_cap_beyond`); planes: `cell_planes(corners)`."""
    count = starts[pair_j + 1] - starts[pair_j]
    piece = np.repeat(np.arange(len(pair_i)), count)
    offset = np.arange(len(piece)) - np.repeat(np.cumsum(count) - count, count)
    ball = pair_j[piece]
    other = others[starts[ball] + offset]
    e = facts.centres[other] - facts.centres[ball]
    dist = length(e)
    ra, rb = facts.radii[ball], facts.radii[other]
    normal = e / dist[:, None]
    bound = (dist * dist + ra * ra - rb * rb) / (2 * dist)
    cell = pair_i[piece]
    side = np.einsum("mvc,mc->mv", corners[cell] - facts.centres[ball][:, None],
                     normal) - bound[:, None]
    empty = np.zeros(len(pair_i), bool)
    empty[piece[(bound <= -ra) | _every(side >= 0)]] = True
    keep = (bound < ra) & _some(side > 0) & ~empty[piece]
    rest = np.flatnonzero(keep)
    facet_normals = planes[0][cell[rest]]
    facet_offsets = planes[1][cell[rest]] - np.einsum("mvc,mc->mv", facet_normals,
                                                      facts.centres[ball[rest]])
    keep[rest[_cap_beyond(normal[rest], bound[rest], ra[rest], facet_normals,
                          facet_offsets)]] = False
    return piece[keep], normal[keep], bound[keep], empty


def clipped_cell_measures(facts, rows: np.ndarray, pairs: tuple[np.ndarray, np.ndarray],
                          neighbours: tuple[np.ndarray, np.ndarray]
                          ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(covered volume (t,), and the exposed sphere area as entries (positions, balls,
    values)) of the union of balls inside each cell `rows` (t,) of the triangulation: the
    sum over the balls meeting a cell of each ball inside its power cell and the cell;
    pairs: `near_balls` of rows; neighbours: `neighbours(facts)`."""
    if len(rows) == 0:
        return np.zeros(0), np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0)
    corners = facts.centres[facts.cells[rows]]
    normals, offsets = cell_planes(corners)
    pair_i, pair_j = pairs
    starts, others = neighbours
    covered = np.zeros(len(rows))
    out_i, out_a, out_v = [], [], []
    for block in range(0, len(pair_i), BLOCK):
        pi, pj = pair_i[block:block + BLOCK], pair_j[block:block + BLOCK]
        piece, normal, bound, empty = _power_planes(facts, pi, pj, corners, (normals, offsets),
                                                    starts, others)
        count = np.bincount(piece, minlength=len(pi))
        first = np.cumsum(count) - count
        for k in np.unique(count[~empty]):
            group = np.flatnonzero((count == k) & ~empty)
            for start in range(0, len(group), CHUNK):
                p = group[start:start + CHUNK]
                i, ball = pi[p], pj[p]
                at = first[p, None] + np.arange(k)
                centre = facts.centres[ball]
                planes = np.concatenate((normals[i], normal[at]), 1)
                limits = np.concatenate(
                    (offsets[i] - np.einsum("tvc,tc->tv", normals[i], centre), bound[at]), 1)
                vol, sphere = ball_in_polyhedron(planes, limits, facts.radii[ball])
                covered += np.bincount(i, weights=vol, minlength=len(rows))
                out_i.append(i)
                out_a.append(ball)
                out_v.append(sphere)
    if not out_i:
        return covered, np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0)
    return covered, np.concatenate(out_i), np.concatenate(out_a), np.concatenate(out_v)

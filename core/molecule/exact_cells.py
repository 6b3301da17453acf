"""The part of a union of balls inside chosen tetrahedra, exact, clipped to each tetrahedron.

The short inclusion–exclusion over the dual complex K holds point by point (Edelsbrunner
1995): 1_∪B = Σ_{σ ∈ K} (-1)^dim σ 1_{∩B_σ}. Restricted to a tetrahedron T it needs every σ
whose balls all meet T, its own faces and the foreign ones. Each ∩B_σ is the union of the
pieces B_a ∩ F_a (F_a: the points where ball a has the largest power among σ's balls, an
intersection of halfspaces), and the sphere of a inside the other balls of σ is its part in
F_a; clipped to T these are a ball or a sphere inside a convex polyhedron (`clipped`). The
sector split of `sectors` is exact for a tetrahedron that no foreign ball meets and whose
balls do not cross their opposite facets; the others (`needs_clipping`) are measured here.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

from core.molecule.clipped import ball_in_polyhedron
from core.molecule.intersections import radical_point

CHUNK = 1024  # ball pieces per vectorized batch (each holds P(P-1) x P plane tests)


def cell_planes(c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """((t, 4, 3) outward unit normals, (t, 4) offsets) of the facets opposite each vertex
    of tetrahedra c (t, 4, 3): the cell is {x: N·x <= b}."""
    normals = np.empty(c.shape)
    offsets = np.empty(c.shape[:2])
    for v in range(4):
        i, j, k = (w for w in range(4) if w != v)
        n = np.cross(c[:, j] - c[:, i], c[:, k] - c[:, i])
        n /= np.linalg.norm(n, axis=1, keepdims=True)
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
        best = np.minimum(best, np.linalg.norm(x - corners[:, a] - t[:, None] * e, axis=1))
    return np.where((side <= 0).all(1), 0.0, best)


def _near_balls(facts, rows: np.ndarray, tree: cKDTree) -> tuple[np.ndarray, np.ndarray]:
    """Pairs (position in rows, ball) of the balls of K that meet each cell."""
    c = facts.centres[facts.cells[rows]]
    g = c.mean(1)
    reach = np.linalg.norm(c - g[:, None], axis=2).max(1)
    vertex = facts.vertices_in()
    lists = tree.query_ball_point(g, reach + facts.radii.max())
    count = np.fromiter(map(len, lists), np.int64, len(lists))
    i = np.repeat(np.arange(len(rows)), count)
    j = np.fromiter((b for near in lists for b in near), np.int64, int(count.sum()))
    keep = vertex[j]
    i, j = i[keep], j[keep]
    keep = _distance(c[i], facts.centres[j]) <= facts.radii[j]
    return i[keep], j[keep]


def needs_clipping(facts, rows: np.ndarray, tree: cKDTree) -> np.ndarray:
    """(len(rows),) bool: cells whose sector measure may differ from the union inside them
    (a ball reaches over its opposite facet or is no vertex of K, or a foreign ball may
    meet the cell)."""
    v = facts.cells[rows]
    c = facts.centres[v]
    normals, offsets = cell_planes(c)
    height = offsets - np.einsum("tvc,tvc->tv", normals, c)
    over = (facts.radii[v] > height).any(1) | ~facts.vertices_in()[v].all(1)
    i, j = _near_balls(facts, rows, tree)
    foreign = (v[i] != j[:, None]).all(1)
    over[i[foreign]] = True
    return over


def _simplices_of_k(facts) -> dict[int, np.ndarray]:
    """{k: (n_k, k+1) int64 ascending rows} of the dual complex K's simplices, k = 1..3."""
    tri = facts.triangles
    pairs = np.concatenate([np.delete(tri, v, axis=1) for v in range(3)])
    ids = facts.tri_edges.T.ravel()
    _, first = np.unique(ids, return_index=True)
    edges = np.zeros((int(ids.max()) + 1 if len(ids) else 0, 2), np.int64)
    edges[ids[first]] = np.sort(pairs[first], 1)
    return {1: edges[facts.edge_in[:len(edges)]], 2: np.sort(tri[facts.facet_in], 1),
            3: np.sort(facts.cells[facts.cell_in], 1)}


def _with_all_vertices(simplices: np.ndarray, pair_i: np.ndarray, pair_j: np.ndarray,
                       n: int) -> tuple[np.ndarray, np.ndarray]:
    """(cell positions, simplex rows): simplices whose vertices are all near a cell, from
    the pairs (cell position, near ball)."""
    if len(simplices) == 0 or len(pair_i) == 0:
        return np.zeros(0, np.int64), np.zeros(0, np.int64)
    order = np.argsort(simplices[:, 0], kind="stable")
    starts = np.searchsorted(simplices[order, 0], np.arange(n + 1))
    count = starts[pair_j + 1] - starts[pair_j]
    cell = np.repeat(pair_i, count)
    offset = np.arange(len(cell)) - np.repeat(np.cumsum(count) - count, count)
    simplex = order[np.repeat(starts[pair_j], count) + offset]
    keys = np.sort(pair_i.astype(np.int64) * n + pair_j)
    keep = np.ones(len(cell), bool)
    for col in range(1, simplices.shape[1]):
        want = cell.astype(np.int64) * n + simplices[simplex, col]
        pos = np.minimum(np.searchsorted(keys, want), len(keys) - 1)
        keep &= keys[pos] == want
    return cell[keep], simplex[keep]


def _common_part_may_meet(facts, members: np.ndarray, corners: np.ndarray) -> np.ndarray:
    """(m,) bool: the balls' common part may meet the cell. When the radical point z of
    the balls lies in the hull of their centres, that part lies within sqrt(-power(z)) of
    z (Σλ_i pow_i(x) = |x - z|² + pow(z) with the weights λ of z, all >= 0)."""
    c, r = facts.centres[members], facts.radii[members]
    z, t = radical_point(c, r)
    e = np.transpose(c[:, 1:] - c[:, :1], (0, 2, 1))  # (m, 3, k)
    gram = np.einsum("mci,mcj->mij", e, e)
    mu = np.linalg.solve(gram, np.einsum("mci,mc->mi", e, z - c[:, 0])[..., None])[..., 0]
    inside = (mu >= 0).all(1) & (mu.sum(1) <= 1)
    out = np.ones(len(members), bool)
    out[inside] = _distance(corners[inside], z[inside]) <= t[inside]
    return out


def clipped_cell_measures(facts, rows: np.ndarray, tree: cKDTree
                          ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(covered volume (t,), and the exposed sphere area as entries (positions, balls,
    values)) of the union of balls inside each cell `rows` (t,) of the triangulation."""
    n = len(facts.radii)
    if len(rows) == 0:
        return np.zeros(0), np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0)
    v = facts.cells[rows]
    origin = facts.centres[v[:, 0]]
    normals, offsets = cell_planes(facts.centres[v] - origin[:, None])
    pair_i, pair_j = _near_balls(facts, rows, tree)
    corners = facts.centres[v]
    covered = np.zeros(len(rows))
    groups = [(0, pair_i, pair_j[:, None])]
    for k, simplices in _simplices_of_k(facts).items():
        cell, simplex = _with_all_vertices(simplices, pair_i, pair_j, n)
        members = simplices[simplex]
        keep = _common_part_may_meet(facts, members, corners[cell])
        groups.append((k, cell[keep], members[keep]))
    out_i, out_a, out_v = [], [], []
    for k, cell, members in groups:
        sign = -1.0 if k % 2 else 1.0
        for a in range(k + 1):
            others = [b for b in range(k + 1) if b != a]
            for start in range(0, len(cell), CHUNK):
                i = cell[start:start + CHUNK]
                ball = members[start:start + CHUNK, a]
                centre = facts.centres[ball] - origin[i]
                ra = facts.radii[ball]
                planes = [normals[i]]
                bounds = [offsets[i] - np.einsum("tvc,tc->tv", normals[i], centre)]
                for b in others:
                    e = facts.centres[members[start:start + CHUNK, b]] - facts.centres[ball]
                    dist = np.linalg.norm(e, axis=1)
                    rb = facts.radii[members[start:start + CHUNK, b]]
                    planes.append((-e / dist[:, None])[:, None])
                    bounds.append((-(dist * dist + ra * ra - rb * rb) / (2 * dist))[:, None])
                vol, sphere = ball_in_polyhedron(np.concatenate(planes, 1),
                                                 np.concatenate(bounds, 1), ra)
                covered += sign * np.bincount(i, weights=vol, minlength=len(rows))
                out_i.append(i)
                out_a.append(ball)
                out_v.append(sign * sphere)
    if not out_i:
        return covered, np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0)
    return covered, np.concatenate(out_i), np.concatenate(out_a), np.concatenate(out_v)

"""Certifies a Delaunay triangulation with exact predicates and repairs it by flips.

Whatever the fast triangulator returned, every interior facet is checked: the vertex across
it must not lie inside the cell's circumsphere (core.geometry.predicates.in_sphere, exactly, with
one symbolic perturbation for cospherical points). Violations are flipped (2D edge flips, 3D 2-3
and 3-2 flips) in rounds: each round flips, all at once, a set of violations whose cells and
neighbours are disjoint, then re-checks only the facets of the new cells.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from core.build.cell_pass import CellSpheres, first_pass
from core.build.delaunay import (
    Triangulation,
    interior_facets,
    regular_triangulate,
    sort_rows,
)
from core.build.rewrap import grow, rewrap, sound
from core.errors import InputError
from core.geometry.predicates import in_sphere, orientations
from core.parallel import PASSES, cast, halves, nonzero, rows_cols

#: Rounds after which a 3D triangulation that still has unflippable violations is left as is.
MAX_ROUNDS = 10_000


@dataclass(frozen=True)
class Certified:
    """A certified triangulation and what certifying it took."""

    triangulation: Triangulation
    exact_predicates: int  # predicate evaluations settled by exact arithmetic
    flips: int  # flips performed (2D edge flips, 3D 2-3 and 3-2 flips)
    uncertified: int  # facets left unchecked or unrepaired (flat cells, stuck 3D flips)
    spheres: CellSpheres | None = None  # the table's cell spheres, when no cell changed
    scale: float = 1.0  # the points were divided by this (core.pipeline: a power of two)


def _folded(n: int, signs: np.ndarray, t, i, u, j) -> np.ndarray:
    """(n,) bool: cells on the same side of a shared facet (t, i, u, j) as their neighbour
    (rows ascending, so the facet's orientation follows from the cell's sign and the
    position left out); the facets in halves (both only ever set True)."""
    out = np.zeros(n, dtype=bool)

    def part(lo: int, hi: int) -> None:
        tt, uu = t[lo:hi], u[lo:hi]
        st, su = signs[tt], signs[uu]
        same = np.where(i[lo:hi] & 1, -st, st) == np.where(j[lo:hi] & 1, -su, su)
        out[tt[same]] = True
        out[uu[same]] = True

    halves(part, len(t), PASSES)
    return out


class _Mesh:
    """Growable cells/neighbours arrays with the predicate counters (certification state)."""

    def __init__(self, points: np.ndarray, tri: Triangulation, ties: np.ndarray) -> None:
        self.points = points
        self.ties = ties
        self.cells = cast(tri.cells, np.int64)
        self.nbs = cast(tri.neighbors, np.int64)
        self.alive = np.ones(len(self.cells), dtype=bool)
        self.mirror = tri.mirror  # valid until the first flip (peeling only cuts links)
        self.first = interior_facets(self.nbs, self.mirror)  # first round's
        t, _, u, j = self.first
        shared = first_pass(points, self.cells, t, self.cells[u, j])
        self.spheres = shared.spheres
        self.side = shared.side, shared.side_doubt  # the first round's in-sphere signs
        self.signs = shared.orient
        doubt = np.flatnonzero(shared.orient_doubt)
        self.signs[doubt], self.exact = orientations(points, self.cells[doubt])
        self.bad = (self.signs == 0) | _folded(len(self.cells), self.signs, *self.first)
        self.flips = 0
        self.touched = np.zeros(len(self.cells), dtype=bool)  # cells changed or relinked
        self.stuck = np.empty(0, dtype=np.int64)  # cells of the last round's stuck flips
        self.concave = np.empty(0, dtype=np.int64)  # cells on unfilled reflex hull ridges
        self._peel()

    def _peel(self) -> None:
        """Drop invalid (flat or folded) cells on the hull until none is left there: slivers
        the triangulator laid flat or inverted on near-coplanar hull faces. The hull repair
        fills what they covered, if anything."""
        while True:
            ids = np.flatnonzero(self.bad & self.alive)
            ids = ids[(self.nbs[ids] < 0).any(axis=1)]
            if not len(ids):
                return
            dropped = np.zeros(len(self.cells), dtype=bool)
            dropped[ids] = True
            cut = dropped[np.maximum(self.nbs, 0)] & (self.nbs >= 0)
            self.touched[cut.any(axis=1)] = True
            self.nbs[cut] = -1
            self.alive[ids] = False
            self.first = interior_facets(self.nbs, self.mirror)
            self.side = None  # the facets changed
            self.bad = self.alive & ((self.signs == 0)
                                     | _folded(len(self.cells), self.signs, *self.first))
            self.flips += len(ids)

    def append(self, rows: np.ndarray) -> np.ndarray:
        ids = np.arange(len(self.cells), len(self.cells) + len(rows))
        self.cells = np.concatenate((self.cells, rows))
        self.nbs = np.concatenate((self.nbs, np.full(rows.shape, -1, dtype=np.int64)))
        self.alive = np.concatenate((self.alive, np.ones(len(rows), dtype=bool)))
        self.touched = np.concatenate((self.touched, np.ones(len(rows), dtype=bool)))
        self.signs = np.concatenate((self.signs, np.zeros(len(rows), dtype=np.int8)))
        self.bad = np.concatenate((self.bad, np.zeros(len(rows), dtype=bool)))
        return ids

    def orient(self, rows: np.ndarray) -> np.ndarray:
        signs, n_exact = orientations(self.points, rows)
        self.exact += n_exact
        return signs


def _facets_of(mesh: _Mesh, pending: np.ndarray) -> tuple[np.ndarray, ...]:
    """Interior facets (t, i, u, j) around the pending cells, each once, flat cells aside."""
    is_pending = np.zeros(len(mesh.cells), dtype=bool)
    is_pending[pending] = True
    rows = np.flatnonzero(is_pending & mesh.alive)
    t = np.repeat(rows, mesh.cells.shape[1])
    i = np.tile(np.arange(mesh.cells.shape[1]), len(rows))
    u = mesh.nbs[t, i]
    keep = (u >= 0) & ~(is_pending[np.maximum(u, 0)] & (u < t))
    t, i, u = t[keep], i[keep], u[keep]
    j = np.argmax(mesh.nbs[u] == t[:, None], axis=1)
    return t, i, u, j


def _violations(mesh: _Mesh, t, i, u, j) -> np.ndarray:
    """Mask of the facets whose opposite vertex is inside the cell's sphere; facets of an
    invalid cell (flat, or folded over its neighbour) are left unchecked."""
    solid = ~mesh.bad[t] & ~mesh.bad[u]
    bad = np.zeros(len(t), dtype=bool)
    q = mesh.cells[u, j]
    inside, n_exact = in_sphere(mesh.points, mesh.cells[t[solid]], q[solid],
                                mesh.signs[t[solid]], mesh.ties)
    mesh.exact += n_exact
    bad[solid] = inside
    return bad


def _first_violations(mesh: _Mesh, t, i, u, j) -> np.ndarray:
    """_violations of the first round's facets from the shared pass's signs (in-sphere
    exactly when V has the sign opposite to the cell's): only the rows its bound left open
    are re-decided, by core.geometry.predicates.in_sphere."""
    side, doubt = mesh.side
    bad = np.empty(len(t), dtype=bool)

    def part(lo: int, hi: int) -> np.ndarray:
        tt = t[lo:hi]
        solid = ~mesh.bad[tt] & ~mesh.bad[u[lo:hi]]
        np.logical_and(solid, side[lo:hi] == -mesh.signs[tt], out=bad[lo:hi])
        return solid & doubt[lo:hi]

    ids = nonzero(part, len(t))
    inside, n_exact = in_sphere(mesh.points, mesh.cells[t[ids]], mesh.cells[u[ids], j[ids]],
                                mesh.signs[t[ids]], mesh.ties)
    mesh.exact += n_exact
    bad[ids] = inside
    return bad


def _independent(mesh: _Mesh, zones: np.ndarray) -> np.ndarray:
    """Mask of candidates (rows of (n, z) zone cells, -1 padded) whose zones meet no zone of a
    smaller-numbered selected candidate; the first candidate is always selected."""
    ids = np.broadcast_to(np.arange(len(zones))[:, None], zones.shape)
    valid = zones >= 0
    claim = np.full(len(mesh.cells), len(zones), dtype=np.int64)
    np.minimum.at(claim, zones[valid], ids[valid])
    return np.all(np.where(valid, claim[np.maximum(zones, 0)] == ids, True), axis=1)


def _relink(mesh: _Mesh, old: np.ndarray, new: np.ndarray) -> None:
    """Re-match the neighbours of the rewritten cells `new` (ids that replace `old`, whose
    neighbour rows are still the old ones) and of the cells around them."""
    width = mesh.cells.shape[1]
    changed = np.zeros(len(mesh.cells), dtype=bool)
    changed[old] = True
    changed[new] = True
    around = mesh.nbs[old].ravel()
    around = np.unique(around[(around >= 0) & ~changed[np.maximum(around, 0)]])
    mesh.touched[new] = mesh.touched[around] = True
    ext_t, ext_k = np.nonzero(changed[np.maximum(mesh.nbs[around], 0)] & (mesh.nbs[around] >= 0))
    slot_cell = np.concatenate((np.repeat(new, width), around[ext_t]))
    slot_k = np.concatenate((np.tile(np.arange(width), len(new)), ext_k))
    others = np.array([[c for c in range(width) if c != k] for k in range(width)])
    keys = np.sort(mesh.cells[slot_cell[:, None], others[slot_k]], axis=1)
    order = np.lexsort(keys.T[::-1])
    keys, slot_cell, slot_k = keys[order], slot_cell[order], slot_k[order]
    same = np.all(keys[1:] == keys[:-1], axis=1)
    mesh.nbs[slot_cell, slot_k] = -1
    first = np.flatnonzero(same)
    mesh.nbs[slot_cell[first], slot_k[first]] = slot_cell[first + 1]
    mesh.nbs[slot_cell[first + 1], slot_k[first + 1]] = slot_cell[first]


def _flip_2d(mesh: _Mesh, t, i, u, j) -> None:
    """Edge flips: triangles (p, a, b) and (q, b, a) become (p, q, a) and (p, q, b)."""
    p, q = mesh.cells[t, i], mesh.cells[u, j]
    a, b = mesh.cells[t, (i + 1) % 3], mesh.cells[t, (i + 2) % 3]
    zones = np.column_stack((t, u, mesh.nbs[t], mesh.nbs[u]))
    pick = _independent(mesh, zones)
    t, u, p, q, a, b = (x[pick] for x in (t, u, p, q, a, b))
    mesh.cells[t] = np.column_stack((p, q, a))
    mesh.cells[u] = np.column_stack((p, q, b))
    changed = np.concatenate((t, u))
    mesh.signs[changed] = mesh.orient(mesh.cells[changed])
    _relink(mesh, changed, changed)
    mesh.flips += len(t)


def _vertex_slot(mesh: _Mesh, cells: np.ndarray, vertex: np.ndarray) -> np.ndarray:
    """Neighbour of each cell opposite `vertex` (-1 for no cell)."""
    ok = cells >= 0
    rows = mesh.cells[np.maximum(cells, 0)]
    out = mesh.nbs[np.maximum(cells, 0), np.argmax(rows == vertex[:, None], axis=1)]
    return np.where(ok & (rows == vertex[:, None]).any(axis=1), out, -1)


def _flip_3d(mesh: _Mesh, t, i, u, j) -> int:
    """Flip the violating facets abc between cells t = abcp and u = abcq where a flip exists:
    2-3 where the segment pq crosses abc; 3-2 where it passes beyond one edge ab shared by
    exactly three cells; through the edge ab itself (p, q, a, b coplanar), 2-2 when ab is on
    the hull and 4-4 when four cells share ab. Returns how many were unflippable."""
    n = len(t)
    others = np.array([[c for c in range(4) if c != k] for k in range(4)])
    p, q = mesh.cells[t, i], mesh.cells[u, j]
    face = np.take_along_axis(mesh.cells[t], others[i], axis=1)  # a, b, c
    side = np.stack([mesh.orient(np.column_stack((p, q, face[:, k], face[:, (k + 1) % 3])))
                     for k in range(3)], axis=1)  # pq against the edges ab, bc, ca
    through = np.all(side == side[:, :1], axis=1) & (side[:, 0] != 0)
    zeros = (side == 0).sum(axis=1)
    odd = (zeros == 0) & (np.abs(side.sum(axis=1)) == 1)
    level = (zeros == 1) & (np.abs(side.sum(axis=1)) == 2)  # through the edge with side 0
    majority = np.sign(side.sum(axis=1))
    edge = np.where(level, np.argmax(side == 0, axis=1),
                    np.argmax(side != majority[:, None], axis=1))
    rows = np.arange(n)
    a, b, c = (face[rows, (edge + k) % 3] for k in range(3))
    v, v_u = _vertex_slot(mesh, t, c), _vertex_slot(mesh, u, c)
    x = np.where(v >= 0, mesh.cells[np.maximum(v, 0)].sum(axis=1) - a - b - p, -1)
    y = np.where(v_u >= 0, mesh.cells[np.maximum(v_u, 0)].sum(axis=1) - a - b - q, -1)
    three_two = odd & (v >= 0) & (v == v_u)
    two_two = level & (v < 0) & (v_u < 0)
    four = level & (v >= 0) & (v_u >= 0) & (x == y) & (_vertex_slot(mesh, v, p) == v_u)
    flippable = through | three_two | two_two | four
    mesh.stuck = np.concatenate((t[~flippable], u[~flippable]))
    v = np.where(three_two | four, v, -1)
    v_u = np.where(four, v_u, -1)
    around = [np.where((cell >= 0)[:, None], mesh.nbs[np.maximum(cell, 0)], -1)
              for cell in (t, u, v, v_u)]
    zones = np.column_stack((t, u, v, v_u, *around))
    keep = np.flatnonzero(flippable)[_independent(mesh, zones[flippable])]
    t, u, p, q, face, a, b, c, v, v_u, x, through, four = (
        arr[keep] for arr in (t, u, p, q, face, a, b, c, v, v_u, x, through, four))
    w = mesh.append(np.column_stack((p, q, face[:, 2], face[:, 0]))[through])
    mesh.cells[t] = np.where(through[:, None], np.column_stack((p, q, face[:, 0], face[:, 1])),
                             np.column_stack((c, p, q, a)))
    mesh.cells[u] = np.where(through[:, None], np.column_stack((p, q, face[:, 1], face[:, 2])),
                             np.column_stack((c, p, q, b)))
    mesh.cells[v[four]] = np.column_stack((x, p, q, a))[four]
    mesh.cells[v_u[four]] = np.column_stack((x, p, q, b))[four]
    dead = v[(v >= 0) & ~four]
    mesh.alive[dead] = False
    new = np.concatenate((t, u, w, v[four], v_u[four]))
    mesh.signs[new] = mesh.orient(mesh.cells[new])
    _relink(mesh, np.concatenate((t, u, dead, v[four], v_u[four])), new)
    mesh.nbs[dead] = -1
    mesh.flips += len(t)
    return int((~flippable).sum())


def _facet_columns(d: int) -> np.ndarray:
    """(d + 1, d) int: row j, the columns of a d-cell's row but j (its facet opposite vertex
    j)."""
    return np.array([[c for c in range(d + 1) if c != j] for j in range(d + 1)])


def _hull_slots(mesh: _Mesh) -> tuple[np.ndarray, np.ndarray]:
    """(cells, slots) of the hull facets (neighbour -1) of the live cells not flagged bad."""
    d = mesh.cells.shape[1] - 1
    t, k = rows_cols(nonzero(lambda lo, hi: mesh.nbs[lo:hi] < 0, len(mesh.nbs)), d + 1)
    keep = mesh.alive[t] & ~mesh.bad[t]
    return t[keep], k[keep]


def _fill_reflex_hull(mesh: _Mesh) -> int:
    """Cells over reflex ridges of the hull: where the vertex g of a hull facet G lies
    strictly outside the plane of the neighbouring hull facet F, the cell F + g belongs to
    the Delaunay triangulation (near-collinear or near-coplanar hull points Qhull left out).
    Returns how many reflex ridges are left unfilled (the hull is then not convex there)."""
    d = mesh.cells.shape[1] - 1
    mesh.concave = np.empty(0, dtype=np.int64)
    t, k = _hull_slots(mesh)
    if not len(t):
        return 0
    others = _facet_columns(d)
    facets = np.take_along_axis(mesh.cells[t], others[k], axis=1)  # (h, d)
    ridges = np.concatenate([np.sort(facets[:, others[r][: d - 1]], axis=1)
                             for r in range(d)])  # each hull facet without its vertex r
    owner = np.tile(np.arange(len(t)), d)
    lonely = np.repeat(np.arange(d), len(t))  # the facet's vertex off the ridge
    order = np.lexsort(ridges.T[::-1])
    ridges, owner, lonely = ridges[order], owner[order], lonely[order]
    first = np.flatnonzero(np.all(ridges[1:] == ridges[:-1], axis=1))
    f, g = owner[first], owner[first + 1]
    apex = facets[g, lonely[first + 1]]
    inner = mesh.cells[t[f], k[f]]
    outer = np.column_stack((facets[f], apex))
    outer_sign = mesh.orient(outer)
    reflex = (outer_sign == -mesh.orient(np.column_stack((facets[f], inner)))) & (outer_sign != 0)
    found = int(reflex.sum())
    mesh.concave = np.concatenate((t[f[reflex]], t[g[reflex]]))
    if d == 3:  # the new hull facets (x, y, a), (x, y, b) must face away from the cell below,
        # unless they are hull facets already (then glued: a hull vertex under three facets)
        x, (a, b) = facets[f, lonely[first]], ridges[first].T
        hull = {tuple(r) for r in np.sort(facets, axis=1)[reflex_owner(f, g, reflex)].tolist()}
        s_ab = mesh.orient(np.column_stack((x, apex, a, b)))
        for c, sign in ((a, s_ab), (b, -s_ab)):
            glued = np.array([tuple(r) in hull for r in
                              np.sort(np.column_stack((x, apex, c)), axis=1).tolist()], bool)
            reflex &= glued | (mesh.orient(np.column_stack((x, apex, c, inner))) == sign)
    f, g, outer = f[reflex], g[reflex], outer[reflex]
    if not len(f):
        return found
    zones = np.column_stack((t[f], t[g], mesh.nbs[t[f]], mesh.nbs[t[g]]))
    outer = outer[_independent(mesh, zones)]
    outer = outer[np.unique(np.sort(outer, axis=1), axis=0, return_index=True)[1]]
    w = mesh.append(outer)
    mesh.signs[w] = mesh.orient(outer)
    mesh.alive[w[_overlapping(mesh, w)]] = False  # it would overlap a cell: not a reflex ridge
    _glue_hull(mesh)
    mesh.flips += int(mesh.alive[w].sum())
    return found - int(mesh.alive[w].sum())


def _hull_not_convex(mesh: _Mesh) -> np.ndarray:
    """Cells whose hull facet leaves the points' centroid o on its outer side or on its plane
    (exact orientations), or every hull cell when the hull facets, all facing o, wrap around
    it more than once (their angles seen from o sum to 2, 4pi or more). Local convexity at every
    ridge (_fill_reflex_hull) misses a hull folded over itself at a vertex; with this global
    check a hull that passes is convex (a locally convex closed surface star-shaped once
    around o)."""
    d = mesh.cells.shape[1] - 1
    t, k = _hull_slots(mesh)
    if not len(t):
        return t
    others = _facet_columns(d)
    facets = np.take_along_axis(mesh.cells[t], others[k], axis=1)
    verts, local = np.unique(np.concatenate((facets.ravel(), mesh.cells[t, k])),
                             return_inverse=True)
    centre = mesh.points.mean(axis=0)  # every point is a vertex: strictly inside the hull
    pts = np.vstack((mesh.points[verts], centre))
    local_facets = local[: facets.size].reshape(facets.shape)
    inner = local[facets.size:]
    o = np.full(len(t), len(verts))
    side, n_side = orientations(pts, np.column_stack((local_facets, o)))
    inside, n_inside = orientations(pts, np.column_stack((local_facets, inner)))
    mesh.exact += n_side + n_inside
    wrong = side != inside
    if wrong.any():
        return t[wrong]
    rays = [pts[local_facets[:, i]] - centre for i in range(d)]
    if d == 2:
        a, b = rays
        turns = np.arctan2(np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]),
                           np.einsum("ij,ij->i", a, b)).sum() / (2 * np.pi)
    else:
        a, b, c = rays
        la, lb, lc = (np.linalg.norm(x, axis=1) for x in rays)
        den = (la * lb * lc + np.einsum("ij,ij->i", a, b) * lc
               + np.einsum("ij,ij->i", a, c) * lb + np.einsum("ij,ij->i", b, c) * la)
        num = np.abs(np.einsum("ij,ij->i", a, np.cross(b, c)))
        turns = (2 * np.arctan2(num, den)).sum() / (4 * np.pi)
    return t if turns > 1.5 else t[:0]


def reflex_owner(f: np.ndarray, g: np.ndarray, reflex: np.ndarray) -> np.ndarray:
    """Hull facet rows on a reflex ridge (either side): the only candidates to be glued."""
    return np.unique(np.concatenate((f[reflex], g[reflex])))


def _overlapping(mesh: _Mesh, new: np.ndarray) -> np.ndarray:
    """(n,) bool: new cells with a facet that two other cells already share (the new cell
    would overlap them); only the cells around the new cells' vertices are searched."""
    width = mesh.cells.shape[1]
    touch = np.zeros(mesh.cells.max() + 1, dtype=bool)
    touch[mesh.cells[new].ravel()] = True
    near = np.flatnonzero(mesh.alive & touch[mesh.cells].any(axis=1))
    others = np.array([[c for c in range(width) if c != k] for k in range(width)])
    keys = np.sort(np.concatenate([mesh.cells[near][:, o] for o in others]), axis=1)
    owner = np.tile(near, width)
    _, inverse, counts = np.unique(keys, axis=0, return_inverse=True, return_counts=True)
    crowded = counts[inverse.ravel()] > 2
    is_new = np.zeros(len(mesh.cells), dtype=bool)
    is_new[new] = True
    out = np.zeros(len(mesh.cells), dtype=bool)
    out[owner[crowded & is_new[owner]]] = True
    return out[new]


def _glue_hull(mesh: _Mesh) -> None:
    """Link every pair of hull slots (neighbour -1) that hold the same facet."""
    d = mesh.cells.shape[1] - 1
    t, k = np.nonzero((mesh.nbs < 0) & mesh.alive[:, None])
    others = _facet_columns(d)
    keys = np.sort(np.take_along_axis(mesh.cells[t], others[k], axis=1), axis=1)
    order = np.lexsort(keys.T[::-1])
    keys, t, k = keys[order], t[order], k[order]
    first = np.flatnonzero(np.all(keys[1:] == keys[:-1], axis=1))
    mesh.nbs[t[first], k[first]] = t[first + 1]
    mesh.nbs[t[first + 1], k[first + 1]] = t[first]
    mesh.touched[t[first]] = mesh.touched[t[first + 1]] = True


def _valid(mesh: _Mesh) -> bool:
    """Whether the cells certification touched form a valid triangulation with the rest:
    no facet in more than two cells, links symmetric, and across every interior facet the
    two opposite vertices strictly on opposite sides (exact orientations)."""
    ids = np.flatnonzero(mesh.touched & mesh.alive)
    if not len(ids):
        return True
    if _overlapping(mesh, ids).any():
        return False
    width = mesh.cells.shape[1]
    t, k = np.repeat(ids, width), np.tile(np.arange(width), len(ids))
    u = mesh.nbs[t, k]
    t, k, u = t[u >= 0], k[u >= 0], u[u >= 0]
    back = mesh.nbs[u] == t[:, None]
    if not (mesh.alive[u].all() and (back.sum(axis=1) == 1).all()):
        return False
    j = np.argmax(back, axis=1)
    others = np.array([[c for c in range(width) if c != i] for i in range(width)])
    facet = np.take_along_axis(mesh.cells[t], others[k], axis=1)
    if not (np.sort(facet, axis=1) == np.sort(np.take_along_axis(
            mesh.cells[u], others[j], axis=1), axis=1)).all():
        return False
    solid = ~mesh.bad[t] & ~mesh.bad[u]
    facet, t, k, u, j = facet[solid], t[solid], k[solid], u[solid], j[solid]
    side_p = mesh.orient(np.column_stack((facet, mesh.cells[t, k])))
    side_q = mesh.orient(np.column_stack((facet, mesh.cells[u, j])))
    return bool(((side_p * side_q) < 0).all())


def _compact(mesh: _Mesh, tri: Triangulation) -> Triangulation:
    """The live cells renumbered, rows ascending (the table's canonical form)."""
    new_id = np.cumsum(mesh.alive) - 1
    cells = np.ascontiguousarray(mesh.cells[mesh.alive], dtype=np.int32)
    nbs = mesh.nbs[mesh.alive]
    nbs = np.ascontiguousarray(np.where(nbs >= 0, new_id[np.maximum(nbs, 0)], -1),
                               dtype=np.int32)
    sort_rows(cells, nbs)
    return replace(tri, cells=cells, neighbors=nbs, mirror=None)


def tie_weights(m: int) -> np.ndarray:
    """(m,) fixed pseudo-random weights in [0, 1) of the symbolic perturbation (one set for
    every build of m points: the certified triangulation is deterministic)."""
    return np.random.default_rng(14).random(m)


def point_ties(points: np.ndarray) -> np.ndarray:
    """(m,) weights in [0, 1) (multiples of 2**-53) of the symbolic perturbation, each a hash
    of its point's coordinates alone: any subset of the points (a tile with its margin,
    core.tiled) resolves cospherical ties as the whole set does."""
    bits = np.ascontiguousarray(points, dtype=np.float64) + 0.0  # -0.0 folded into 0.0
    words = bits.view(np.uint64).reshape(len(points), -1)
    h = np.full(len(points), 0x9E3779B97F4A7C15, dtype=np.uint64)
    with np.errstate(over="ignore"):
        for column in words.T:  # splitmix64 rounds over the coordinates' bits
            h = (h ^ column) * np.uint64(0xBF58476D1CE4E5B9)
            h ^= h >> np.uint64(31)
            h *= np.uint64(0x94D049BB133111EB)
            h ^= h >> np.uint64(29)
    return (h >> np.uint64(11)).astype(np.float64) * 2.0**-53


def certify(points: np.ndarray, tri: Triangulation, ties: np.ndarray | None = None,
            *, repair: bool = True) -> Certified:
    """Check every interior facet of `tri` (cells of the (m, d) `points`) for the local
    Delaunay condition, exactly, and flip until all hold (module docstring); what flips
    cannot repair is re-triangulated locally (core.build.rewrap) unless `repair` is False. `ties`:
    the points' perturbation weights (default tie_weights(m))."""
    ties = tie_weights(len(points)) if ties is None else ties
    mesh = _Mesh(points, tri, ties)
    d = points.shape[1]
    pending = None
    stuck = concave = 0
    for _ in range(MAX_ROUNDS):
        if pending is None:
            t, i, u, j = mesh.first
            bad = (_violations if mesh.side is None else _first_violations)(mesh, t, i, u, j)
        else:
            t, i, u, j = _facets_of(mesh, pending)
            bad = _violations(mesh, t, i, u, j)
        t, i, u, j = (x[bad] for x in (t, i, u, j))
        before, size = mesh.flips, len(mesh.cells)
        if d == 2 and len(t):
            _flip_2d(mesh, t, i, u, j)
        elif len(t):
            stuck = _flip_3d(mesh, t, i, u, j)
        if mesh.flips == before:  # nothing (more) to flip: fill reflex hull ridges, if any
            concave = _fill_reflex_hull(mesh)
            if mesh.flips == before:
                break
        pending = np.unique(np.concatenate((t, u, np.arange(size, len(mesh.cells)))))
    folded = np.setdiff1d(_hull_not_convex(mesh), mesh.concave)  # a cell counted once
    mesh.concave = np.concatenate((mesh.concave, folded))
    concave += len(folded)
    broken = bool(mesh.flips) and not _valid(mesh)
    # a repair went wrong: the backend's cells, unless the local re-triangulation mends it
    backend = Certified(tri, mesh.exact, 0, int((tri.neighbors >= 0).sum()) // 2)
    if broken and not repair:
        return backend
    out = _compact(mesh, tri) if mesh.flips else tri
    bad = np.flatnonzero(mesh.bad & mesh.alive)
    invalid = int(np.sum(mesh.nbs[bad] >= 0))
    result = Certified(out, mesh.exact, mesh.flips, stuck + invalid + concave,
                       None if mesh.flips else mesh.spheres)
    if not (result.uncertified or broken) or not repair:
        return result
    seeds = np.zeros(len(mesh.cells), dtype=bool)
    seeds[np.concatenate((bad, mesh.stuck, mesh.concave))] = True
    if broken:
        touched = np.flatnonzero(mesh.touched & mesh.alive)
        seeds[touched[_overlapping(mesh, touched)]] = True
        result = replace(result, uncertified=backend.uncertified)
    fixed = _rewrapped(points, ties, result, seeds[mesh.alive])
    if broken and fixed.uncertified:
        return replace(backend, exact_predicates=fixed.exact_predicates)
    return fixed


#: Rings of cells (sharing a vertex) added around the unrepaired cells, one per attempt.
REWRAP_RINGS = 3


def _rewrapped(points: np.ndarray, ties: np.ndarray, before: Certified,
               seeds: np.ndarray) -> Certified:
    """`before` with the cells around `seeds` (their unrepaired cells, (n,) bool) exactly
    re-triangulated (core.build.rewrap), kept only if the whole result then certifies; the region
    grows by a ring of cells on each failed attempt."""
    tri, region, exact = before.triangulation, seeds, 0
    for _ in range(REWRAP_RINGS):
        region = grow(tri.cells, region)
        fixed, n_exact = rewrap(points, tri, ties, region)
        exact += n_exact
        if fixed is None or not sound(fixed, len(region) - int(region.sum())):
            continue
        again = certify(points, fixed, ties, repair=False)
        exact += again.exact_predicates
        if not again.uncertified:
            made = len(fixed.cells) - len(tri.cells) + int(region.sum())
            return replace(again, exact_predicates=before.exact_predicates + exact,
                           flips=before.flips + made + again.flips)
    return replace(before, exact_predicates=before.exact_predicates + exact)


#: Lifted heights of the retry are lowered by up to this times the squared extent: enough to
#: break Qhull's near-ties (which it merges into folded cells), far below any point's margin.
JITTER_RTOL = 1e-9


def _certified_cells(points: np.ndarray, tri: Triangulation, ties: np.ndarray,
                     repair: bool = False) -> Certified:
    """`certify` on the points that are vertices, with the points' (m,) perturbation
    weights `ties`; points the triangulator merged into a neighbour count as uncertified
    (an exact triangulation keeps every distinct point)."""
    out = certify(points[tri.kept], tri, ties[tri.kept], repair=repair)
    return replace(out, uncertified=out.uncertified + len(points) - len(tri.kept))


def certified_triangulation(points: np.ndarray, tri: Triangulation,
                            ties: np.ndarray | None = None) -> Certified:
    """Certify the backend's triangulation `tri` of the (m, d) distinct `points` (the exact
    coordinates, scaled by a power of two at most; signs are decided on these). `ties`:
    the points' (m,) perturbation weights (default tie_weights(m); core.pipeline passes
    point_ties of the unscaled points, so that ties do not depend on the points' order).

    Where the backend merged near-cospherical groups into flat or folded cells (which no flip
    repairs), Qhull runs once more on the points lifted with tiny weights, the same that
    break exact ties in the symbolic perturbation (so it resolves them the same way), and the
    certified result with fewer uncertified facets is kept (the first on a tie). What is
    still uncertified then is re-triangulated locally and exactly (core.build.rewrap)."""
    ties = tie_weights(len(points)) if ties is None else ties
    first = _certified_cells(points, tri, ties)
    if not first.uncertified:
        return first
    best = _retried(points, ties, first)
    if not best.uncertified:
        return best
    again = _certified_cells(points, best.triangulation, ties, repair=True)
    kept = again if again.uncertified < best.uncertified else best
    return replace(kept, exact_predicates=best.exact_predicates + again.exact_predicates,
                   flips=best.flips + again.flips)


def _retried(points: np.ndarray, ties: np.ndarray, first: Certified) -> Certified:
    """Qhull once more on the points lifted by tiny weights (certified_triangulation), the
    result with fewer uncertified facets kept."""
    centred = points - 0.5 * (points.min(axis=0) + points.max(axis=0))
    centred /= float(np.abs(centred).max())
    weights = JITTER_RTOL * ties
    try:
        retry = regular_triangulate(centred, weights)
    except InputError:
        return first
    if (retry.vertex_of_point < 0).any():  # a point hidden by the weights: not Delaunay
        return first
    second = _certified_cells(points, retry, ties)
    best = second if second.uncertified < first.uncertified else first
    return replace(best, exact_predicates=first.exact_predicates + second.exact_predicates,
                   flips=first.flips + second.flips)

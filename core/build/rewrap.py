"""Local exact re-triangulation of the cells certification could not repair by flips.

Qhull folds slivers onto nearly flat faces of the convex hull (jittered lattices, quantized
scans) where no flip is valid. Around such cells a region is cut out (the cells that share a
vertex with them) and re-triangulated by gift wrapping with the exact predicates of
core.geometry.predicates: from each facet on the region's boundary the Delaunay cell beyond it is
the one through the point whose sphere is empty (found by a float guess, then exact in-sphere tests
with the symbolic perturbation until no point is inside); a facet with no point beyond is a
facet of the exact convex hull. The new cells are linked to the kept ones; the caller
re-certifies the whole result (core.build.certify) and keeps it only if it is certified.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from core.build.delaunay import Triangulation, sort_rows
from core.geometry.predicates import in_sphere, orientations

#: Regions with more cells than this are not re-triangulated (the Python wrap is for a few
#: hundred cells; beyond, the triangulation is kept as the flips left it, counted uncertified).
MAX_REGION_CELLS = 3000
#: New cells per region cell after which the wrap is abandoned (it ran away: an invalid seed).
MAX_GROWTH = 8
#: Above this many points the pivot candidates are those near the region, not all points.
ALL_CANDIDATES = 4096


class WrapFailed(Exception):
    """The region's boundary is not a valid start (a kept cell is not Delaunay)."""


@dataclass
class _Wrap:
    """The wrap's state: points, the candidate pivots, the cells made and the open facets."""

    points: np.ndarray
    ties: np.ndarray
    candidates: np.ndarray  # (c,) point ids a pivot may pick
    others: np.ndarray  # the point ids that are not candidates (checked only for hull facets)
    cells: list  # new cells' vertex rows (final ids start at `base`)
    links: dict  # (cell, slot) -> (cell, slot) for every glued facet, both ways
    open: dict  # sorted facet -> (cell, slot, apex) waiting for the cell beyond
    kept_hull: dict  # sorted facet -> (cell, slot): hull facets of kept cells near the region
    kept_inner: set  # sorted facets of kept cells shared by two kept cells
    base: int  # final id of the first new cell
    exact: int = 0  # predicates settled by exact arithmetic


def _orient(wrap: _Wrap, rows: np.ndarray) -> np.ndarray:
    """Exact orientation signs of (n, d+1) rows, counting the exact evaluations."""
    signs, n_exact = orientations(wrap.points, rows)
    wrap.exact += n_exact
    return signs


def _float_heights(points: np.ndarray, facet: np.ndarray, normal_sign: int,
                   ids: np.ndarray) -> np.ndarray:
    """(c,) float guesses of where the sphere through `facet` and each point has its centre
    along the facet's normal (towards the side `normal_sign`): the smallest is the Delaunay
    pivot. Only a starting guess: the exact tests decide."""
    corners = points[facet]
    a = corners[0]
    rel = points[ids] - a
    if len(facet) == 2:  # 2D: the edge's perpendicular bisector
        u = corners[1] - a
        normal = np.array([-u[1], u[0]])
        centre = 0.5 * u
    else:
        u, v = corners[1] - a, corners[2] - a
        normal = np.cross(u, v)
        with np.errstate(all="ignore"):  # a near-collinear facet: the exact tests decide
            centre = ((u @ u * np.cross(v, normal) + v @ v * np.cross(normal, u))
                      / (2 * normal @ normal))
    normal = normal * normal_sign
    with np.errstate(all="ignore"):
        out = ((rel - centre) ** 2).sum(axis=1) - centre @ centre
        out = out / (2 * (rel - centre) @ normal)
    return np.nan_to_num(out, nan=np.inf, posinf=np.inf, neginf=-np.inf)


def _pivot(wrap: _Wrap, facet: np.ndarray, apex: int) -> int:
    """The point beyond `facet` (away from `apex`) whose cell with it is Delaunay, or -1 when
    no point is beyond (a hull facet)."""
    pool = wrap.candidates
    ids = np.append(pool, apex)
    signs = _orient(wrap, np.column_stack((np.tile(facet, (len(ids), 1)), ids)))
    side = -int(signs[-1])
    if side == 0:  # a flat cell (or a facet with collinear corners) on the region's boundary
        raise WrapFailed("a flat cell on the region's boundary")
    beyond = pool[signs[:-1] == side]  # the cell facet + p has orientation `side`
    if not len(beyond):
        if len(wrap.others):  # a hull facet of the region: of all the points?
            rows = np.column_stack((np.tile(facet, (len(wrap.others), 1)), wrap.others))
            if (_orient(wrap, rows) == side).any():
                raise WrapFailed("a point beyond the region's hull")
        return -1
    heights = _float_heights(wrap.points, facet, side, beyond)
    best = int(beyond[np.argmin(heights)])
    signs = np.full(len(beyond) - 1, side, dtype=np.int8)
    for _ in range(len(beyond)):
        rest = beyond != best
        cells = np.tile(np.append(facet, best), (len(signs), 1))
        inside, n_exact = in_sphere(wrap.points, cells, beyond[rest], signs, wrap.ties)
        wrap.exact += n_exact
        if not inside.any():
            return best
        best = int(beyond[rest][inside][np.argmin(heights[rest][inside])])
    raise WrapFailed("the pivot did not settle")


def _glue(wrap: _Wrap, cell: int, slot: int, key: tuple, apex: int) -> None:
    """Link facet `key` of new `cell` (opposite its `slot`) with what waits for it."""
    if key in wrap.open:
        other, other_slot, _ = wrap.open.pop(key)
    elif key in wrap.kept_hull:
        other, other_slot = wrap.kept_hull.pop(key)
    elif key in wrap.kept_inner:
        raise WrapFailed("a new cell overlaps the kept cells")
    else:
        wrap.open[key] = (cell, slot, apex)
        return
    wrap.links[(cell, slot)] = (other, other_slot)
    wrap.links[(other, other_slot)] = (cell, slot)


def _run(wrap: _Wrap, limit: int) -> None:
    """Wrap until no facet is open (each open facet gets its cell beyond, or is hull)."""
    queue = list(wrap.open)
    while queue:
        key = queue.pop()
        if key not in wrap.open:
            continue
        owner, slot, apex = wrap.open.pop(key)
        facet = np.array(key)
        best = _pivot(wrap, facet, apex)
        if best < 0:
            continue
        if len(wrap.cells) >= limit:
            raise WrapFailed("the wrap made too many cells")
        row = np.append(facet, best)
        cell = wrap.base + len(wrap.cells)
        wrap.cells.append(row)
        last = len(row) - 1
        wrap.links[(cell, last)] = (owner, slot)
        wrap.links[(owner, slot)] = (cell, last)
        for k in range(last):
            face = tuple(sorted(np.delete(row, k).tolist()))
            before = len(wrap.open)
            _glue(wrap, cell, k, face, int(row[k]))
            if len(wrap.open) > before:
                queue.append(face)


def _facet_keys(cells: np.ndarray, ids: np.ndarray) -> list:
    """Sorted facet tuples of cells `ids`, (cell, slot, key) for every slot."""
    width = cells.shape[1]
    return [(int(c), k, tuple(sorted(np.delete(cells[c], k).tolist())))
            for c in ids.tolist() for k in range(width)]


def _start(points: np.ndarray, ties: np.ndarray, tri: Triangulation,
           region: np.ndarray) -> tuple[_Wrap, np.ndarray]:
    """The wrap's state for cutting out the cells `region` (bool mask), and the kept cells'
    old ids (their final ids are their positions)."""
    cells, nbs = tri.cells, tri.neighbors
    kept = np.flatnonzero(~region)
    final = np.cumsum(~region) - 1
    verts = np.unique(cells[region])
    near = np.zeros(len(points), dtype=bool)
    near[verts] = True
    touching = kept[near[cells[kept]].any(axis=1)]
    pool = _candidates(points, verts)
    others = np.setdiff1d(np.arange(len(points)), pool, assume_unique=True)
    wrap = _Wrap(points, ties, pool, others, [], {}, {}, {}, set(), len(kept))
    for c, k, key in _facet_keys(cells, touching):
        other = int(nbs[c, k])
        if other < 0:
            wrap.kept_hull[key] = (int(final[c]), k)
        elif region[other]:
            wrap.open[key] = (int(final[c]), k, int(cells[c, k]))
        else:
            wrap.kept_inner.add(key)
    return wrap, kept


def _candidates(points: np.ndarray, verts: np.ndarray) -> np.ndarray:
    """Point ids a pivot may pick: all of them for small inputs, else those in the region's
    bounding box grown by its size on every side (the result is re-certified anyway)."""
    if len(points) <= ALL_CANDIDATES:
        return np.arange(len(points))
    lo, hi = points[verts].min(axis=0), points[verts].max(axis=0)
    pad = (hi - lo).max()
    inside = np.all((points >= lo - pad) & (points <= hi + pad), axis=1)
    return np.flatnonzero(inside)


def _assemble(tri: Triangulation, wrap: _Wrap, kept: np.ndarray,
              region: np.ndarray) -> Triangulation:
    """The kept cells (renumbered) and the new ones, neighbours from the wrap's links."""
    final = np.cumsum(~region) - 1
    old = tri.neighbors[kept].astype(np.int64)
    nbs_kept = np.where(old >= 0, final[np.maximum(old, 0)], -1)
    nbs_kept[(old >= 0) & region[np.maximum(old, 0)]] = -1
    new = np.array(wrap.cells, dtype=np.int64).reshape(-1, tri.cells.shape[1])
    cells = np.concatenate((tri.cells[kept].astype(np.int64), new))
    nbs = np.concatenate((nbs_kept, np.full(new.shape, -1, dtype=np.int64)))
    if wrap.links:
        pairs = np.array([(*a, *b) for a, b in wrap.links.items()], dtype=np.int64)
        nbs[pairs[:, 0], pairs[:, 1]] = pairs[:, 2]
    cells, nbs = cells.astype(np.int32), nbs.astype(np.int32)
    sort_rows(cells, nbs)
    return replace(tri, cells=cells, neighbors=nbs, mirror=None)


def grow(cells: np.ndarray, region: np.ndarray) -> np.ndarray:
    """(n,) bool: the cells sharing a vertex with a cell of `region`."""
    touch = np.zeros(cells.max() + 1, dtype=bool)
    touch[cells[region].ravel()] = True
    return touch[cells].any(axis=1)


def rewrap(points: np.ndarray, tri: Triangulation, ties: np.ndarray,
           region: np.ndarray) -> tuple[Triangulation | None, int]:
    """Re-triangulate the cells `region` ((n,) bool) of `tri` (cells of the (m, d) `points`
    with tie weights `ties`) exactly; returns the new triangulation (None when the region is
    too large or its boundary is not valid) and how many predicates needed exact arithmetic."""
    count = int(region.sum())
    if not count or count > MAX_REGION_CELLS:
        return None, 0
    wrap, kept = _start(points, ties, tri, region)
    if not wrap.open:  # the region is everything: no boundary facet to wrap from
        return None, 0
    try:
        _run(wrap, MAX_GROWTH * count + 64)
    except WrapFailed:
        return None, wrap.exact
    out = _assemble(tri, wrap, kept, region)
    used = np.zeros(len(points), dtype=bool)
    used[out.cells.ravel()] = True
    if not used[tri.cells[region].ravel()].all():  # a vertex left out: not a triangulation
        return None, wrap.exact
    return out, wrap.exact


def sound(tri: Triangulation, first_new: int) -> bool:
    """Whether the cells around the new ones (rows from `first_new` on) share every facet
    with at most one other cell, linked both ways (the re-certification's local checks
    assume a triangulation whose links are right)."""
    width = tri.cells.shape[1]
    touch = np.zeros(tri.cells.max() + 1, dtype=bool)
    touch[tri.cells[first_new:].ravel()] = True
    near = np.flatnonzero(touch[tri.cells].any(axis=1))
    if not len(near):
        return True
    others = np.array([[c for c in range(width) if c != k] for k in range(width)])
    keys = np.sort(np.concatenate([tri.cells[near][:, o] for o in others]), axis=1)
    _, counts = np.unique(keys, axis=0, return_counts=True)
    nbs = tri.neighbors[near]
    t, k = np.nonzero(nbs >= 0)
    back = (tri.neighbors[nbs[t, k]] == near[t][:, None]).sum(axis=1)
    return bool(counts.max() <= 2 and (back == 1).all())

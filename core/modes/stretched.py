"""The anisotropic own values of a table's simplices (core/modes/anisotropy.py's test), level by
level.

One pass over each level in chunks, every value from the points and normals of the
simplex's own vertices (contiguous coordinate columns, no per-face arrays gathered at random):

- cells: the stretched smallest-sphere radius;
- facets: the same, and attached when the opposite vertex of one of the (at most two) cells
  in `facet_cells` lies strictly inside the stretched sphere (inf then);
- edges of 3D tables: the stretched half length; attachment is tested in the triangle pass,
  where each triangle's third vertex is inside the edge's stretched diametral sphere exactly
  when the stretched angle there is obtuse: S(p - e0) . S(p - e1) < 0, with S the edge's
  stretch (|Sv|² = |v|² + gain (n.v)², gain = (1 + extra)² - 1).
"""

from __future__ import annotations

import numpy as np

from core.build.levels import Table
from core.modes.anisotropy import (
    Vec,
    combined_normals,
    dot,
    minus,
    signed_sums,
    sphere_centres,
    stretch,
)
from core.parallel import in_chunks
from core.tolerances import ON_SPHERE_RTOL

ROWS = 1 << 13  #: simplices per chunk: a chunk's columns stay in the cache


class _Corners:
    """Point and normal coordinate columns, gathered per vertex of a chunk of simplices."""

    def __init__(self, points: np.ndarray, normals: np.ndarray) -> None:
        self.points = [np.ascontiguousarray(points[:, c]) for c in range(points.shape[1])]
        self.normals = [np.ascontiguousarray(normals[:, c]) for c in range(normals.shape[1])]

    def at(self, ids: np.ndarray) -> Vec:
        """Points of the vertices `ids` (n,)."""
        return [np.take(c, ids) for c in self.points]

    def of(self, ids: np.ndarray) -> tuple[Vec, Vec]:
        """Points and normals of the vertices `ids` (n,)."""
        return ([np.take(c, ids) for c in self.points], [np.take(c, ids) for c in self.normals])


def _pairs(width: int) -> list[tuple[int, int]]:
    return [(i, j) for i in range(width) for j in range(i + 1, width)]


def _columns(rows: np.ndarray) -> list[np.ndarray]:
    """The vertex columns (n,) intp of a chunk of (n, k+1) simplices."""
    return [rows[:, i].astype(np.intp) for i in range(rows.shape[1])]


def _simplex_frames(corners: _Corners, ids: list[np.ndarray], extra: float):
    """For a chunk of simplices given by their vertex columns `ids` (_columns): their
    vertices, vertex normals, pairwise normal dots, unit normals and stretched edge vectors
    from the first vertex."""
    width = len(ids)
    gathered = [corners.of(column) for column in ids]
    points = [p for p, _ in gathered]
    normals = [n for _, n in gathered]
    dots = {(i, j): dot(normals[i], normals[j]) for i, j in _pairs(width)}
    unit = combined_normals(normals, dots)
    edges = [stretch(minus(p, points[0]), unit, extra) for p in points[1:]]
    return points, normals, dots, unit, edges


def _inside(centre: Vec, radii2: np.ndarray, unit: Vec, offset: Vec, extra: float) -> np.ndarray:
    """(n,) bool: the points at `offset` from the first vertex, stretched, lie strictly inside
    the stretched spheres."""
    rel = minus(stretch(offset, unit, extra), centre)
    return dot(rel, rel) < radii2 * (1 - 2 * ON_SPHERE_RTOL)


def _cells(table: Table, corners: _Corners, extra: float) -> np.ndarray:
    """(c,) stretched radii of the cells."""
    simplices = table.levels[-1].simplices
    out = np.empty(len(simplices))

    def part(lo: int, hi: int) -> None:
        edges = _simplex_frames(corners, _columns(simplices[lo:hi]), extra)[4]
        out[lo:hi] = np.sqrt(sphere_centres(edges)[1])

    in_chunks(part, len(simplices), ROWS)
    return out


def _facets(table: Table, corners: _Corners, extra: float,
            edge_attached: np.ndarray | None) -> np.ndarray:
    """(f,) stretched radii of the facets, inf where a cell's opposite vertex attaches them;
    in 3D also sets `edge_attached` for edges whose stretched sphere holds a triangle's third
    vertex."""
    level = table.levels[-2]
    simplices, cells = level.simplices, table.levels[-1].simplices
    cell_sums = cells.sum(axis=1, dtype=np.int64)
    facet_cells = table.facet_cells
    out = np.empty(len(simplices))
    gain = (1.0 + extra) ** 2 - 1.0

    def part(lo: int, hi: int) -> None:
        ids = _columns(simplices[lo:hi])
        points, normals, dots, unit, edges = _simplex_frames(corners, ids, extra)
        centre, radii2 = sphere_centres(edges)
        sums = ids[0] + ids[1]  # vertex sums: the far vertex is a cell's sum minus them
        for column in ids[2:]:
            sums += column
        attached = np.zeros(hi - lo, dtype=bool)
        for side in (0, 1):  # no cell beyond the hull (-1): the first vertex, not inside
            cell = facet_cells[lo:hi, side]
            far = np.take(cell_sums, cell) - sums if side == 0 else np.where(
                cell >= 0, np.take(cell_sums, np.maximum(cell, 0)) - sums, ids[0])
            inside = _inside(centre, radii2, unit, minus(corners.at(far), points[0]), extra)
            attached |= inside & (cell >= 0) if side else inside
        out[lo:hi] = np.where(attached, np.inf, np.sqrt(radii2))
        if edge_attached is not None:
            _edge_tests(points, normals, dots, gain, level.face_ids[lo:hi], edge_attached)

    in_chunks(part, len(simplices), ROWS)
    return out


def _edge_tests(points: list[Vec], normals: list[Vec], dots: dict, gain: float,
                face_ids: np.ndarray, edge_attached: np.ndarray) -> None:
    """Set edge_attached[e] for the edges e of a chunk of triangles whose stretched diametral
    sphere holds the triangle's third vertex (module doc); face_ids (n, 3) is the edge
    opposite each vertex. The edge's normal is its unit combined normal m / |m|, so
    gain (n.q)(n.w) = gain (m.q)(m.w) / |m|²."""
    sides = {(0, 1): minus(points[1], points[0]), (0, 2): minus(points[2], points[0]),
             (1, 2): minus(points[2], points[1])}
    for i, j, far in ((0, 1, 2), (0, 2, 1), (1, 2, 0)):
        m = signed_sums([normals[i], normals[j]], {(0, 1): dots[i, j]})
        q = sides[min(i, far), max(i, far)]  # p_far - p_i, or both it and w reversed
        w = sides[min(j, far), max(j, far)]  # p_far - p_j, reversed alone when i < far < j
        sign = -1.0 if i < far < j else 1.0
        mq, mw = dot(m, q), dot(m, w)
        mm = dot(m, m)
        scaled = gain / np.where(mm > 0, mm, 1.0)
        along = mq - sign * mw
        limit = dot(sides[i, j], sides[i, j])
        limit += scaled * along * along
        angle = dot(q, w) + scaled * mq * mw
        if sign < 0:
            angle = -angle
        hit = angle < -0.5 * ON_SPHERE_RTOL * limit
        edge_attached[face_ids[hit, far]] = True


def _edges(table: Table, corners: _Corners, extra: float, attached: np.ndarray) -> np.ndarray:
    """(e,) stretched half lengths of a 3D table's edges, inf where attached."""
    simplices = table.levels[1].simplices
    out = np.empty(len(simplices))

    def part(lo: int, hi: int) -> None:
        edges = _simplex_frames(corners, _columns(simplices[lo:hi]), extra)[4]
        out[lo:hi] = np.sqrt(sphere_centres(edges)[1])

    in_chunks(part, len(simplices), ROWS)
    out[attached] = np.inf
    return out


def stretched_values(table: Table, points: np.ndarray, normals: np.ndarray,
                     tau: float) -> list[np.ndarray]:
    """Per level k >= 1 of `table` (of (m, d) `points`, d = 2 or 3): (n_k,) the stretched
    radius of each cell and unattached face, inf for attached faces; `normals` (m, d) unit
    (or 0: no direction) point normals, tau in (0, 1) the compression."""
    extra = 1.0 / (1.0 - tau) - 1.0
    corners = _Corners(points, normals)
    d = points.shape[1]
    edge_attached = np.zeros(len(table.levels[1].simplices), dtype=bool) if d == 3 else None
    facets = _facets(table, corners, extra, edge_attached)
    cells = _cells(table, corners, extra)
    if edge_attached is None:
        return [facets, cells]
    return [_edges(table, corners, extra, edge_attached), facets, cells]

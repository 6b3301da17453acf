"""The cells gmsh leaves out near the convex hull, found again exactly.

gmsh's tetrahedralize/triangulate returns a subset of the Delaunay cells: it drops those whose
circumsphere reaches its internal bounding box. Every dropped cell has all its vertices on the
boundary of gmsh's union of cells, so it is a cell of the Delaunay triangulation of those
boundary vertices, on the outer side of gmsh's boundary. The result is checked afterwards
(core.backends.certify: every inner facet locally Delaunay, the outer facets the hull), so a
case this reasoning misses makes the build use Qhull instead; it cannot pass.
core.backends.split restores the band its two halves leave out the same way (`outside`,
`joined`).
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import Delaunay, QhullError

from core.arrays import row_index
from core.backends.facets import paired
from core.build.delaunay import sort_rows


def _side(points: np.ndarray, facets: np.ndarray, apex: np.ndarray) -> np.ndarray:
    """(n,) float64 whose sign tells on which side of each (n, d) facet its apex lies."""
    base = points[facets[:, 0]]
    rows = [points[facets[:, k]] - base for k in range(1, facets.shape[1])]
    return np.linalg.det(np.stack([*rows, points[apex] - base], axis=1))


def boundary_facets(cells: np.ndarray, nbrs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(b, d) ascending rows: the facets with no cell across, and (b,) the vertex of the
    cell behind each (on the inner side)."""
    t, i = np.nonzero(nbrs < 0)
    keep = np.arange(cells.shape[1])[None, :] != i[:, None]
    return cells[t][keep].reshape(len(t), -1), cells[t, i]


def _missing(points: np.ndarray, cells: np.ndarray, outer: np.ndarray,
             behind: np.ndarray) -> np.ndarray:
    """(k, d+1) ascending cells of the Delaunay triangulation of the vertices of the
    `outer` facets that lie outside gmsh's union of `cells` (`outside`)."""
    corners = np.unique(outer)
    try:
        local = Delaunay(points[corners])
    except (QhullError, ValueError):
        return np.empty((0, cells.shape[1]), dtype=np.int32)
    simplices = np.ascontiguousarray(corners[local.simplices], dtype=np.int32)
    around = np.ascontiguousarray(local.neighbors, dtype=np.int32)
    sort_rows(simplices, around)
    return outside(points, cells, outer, behind, simplices, around)


def outside(points: np.ndarray, cells: np.ndarray, outer: np.ndarray, behind: np.ndarray,
            simplices: np.ndarray, around: np.ndarray) -> np.ndarray:
    """(k, d+1) the cells of a small triangulation (`simplices` ascending, in point ids,
    their neighbour table `around`) that lie outside the union of `cells`, whose boundary
    is the (b, d) `outer` facets with the vertex `behind` each: those on the far side of an
    outer facet from its vertex `behind`, and those reached from them without crossing
    another outer facet (a flood over that small triangulation)."""
    width = cells.shape[1]
    corners = np.unique(simplices)
    on_corners = np.zeros(len(points), dtype=bool)
    on_corners[corners] = True
    inside = row_index(cells[on_corners[cells].all(axis=1)], simplices) >= 0
    keep = np.arange(width)[None, :] != np.arange(width)[:, None]
    faces = simplices[:, None, :].repeat(width, axis=1)[:, keep].reshape(-1, width - 1)
    wall = row_index(outer, faces)
    at = np.flatnonzero(wall >= 0)
    apex = simplices.ravel()[at]  # face k of a cell is opposite its vertex k
    beyond = np.sign(_side(points, faces[at], apex)) * np.sign(
        _side(points, faces[at], behind[wall[at]])) < 0
    reached = np.zeros(len(simplices), dtype=bool)
    reached[at[beyond] // width] = True
    reached &= ~inside
    wall = (wall >= 0).reshape(len(simplices), width)
    frontier = np.flatnonzero(reached)
    while len(frontier):
        step = np.where(wall[frontier], -1, around[frontier]).ravel()
        step = np.unique(step[step >= 0])
        frontier = step[~reached[step] & ~inside[step]]
        reached[frontier] = True
    return simplices[reached]


def joined(points: np.ndarray, cells: np.ndarray, nbrs: np.ndarray, extra: np.ndarray,
           mirror: np.ndarray | None = None
           ) -> tuple[np.ndarray, np.ndarray, np.ndarray | None, bool]:
    """`cells` + `extra`, their neighbours, their mirror (facets.paired; None without
    `mirror` for `cells`) and whether no facet is in three cells: only the cells that can
    share a facet with an extra cell (d vertices among the extra cells' vertices) are
    matched again."""
    d = cells.shape[1] - 1
    touched = np.zeros(len(points), dtype=bool)
    touched[extra] = True
    near = np.flatnonzero(np.count_nonzero(touched[cells], axis=1) >= d)
    local, back, manifold = paired(np.concatenate((cells[near], extra)), len(points))
    ids = np.concatenate((near, len(cells) + np.arange(len(extra)))).astype(np.int32)
    local = np.where(local >= 0, ids[np.maximum(local, 0)], -1)
    table = np.concatenate((nbrs, local[len(near):]))
    matched = local[:len(near)] >= 0
    table[near] = np.where(matched, local[:len(near)], nbrs[near])
    if mirror is not None:
        mirror = np.concatenate((mirror, back[len(near):]))
        mirror[near] = np.where(matched, back[:len(near)], mirror[near])
    return np.concatenate((cells, extra)), table.astype(np.int32), mirror, manifold


def restored(points: np.ndarray, cells: np.ndarray, nbrs: np.ndarray, mirror: np.ndarray
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray, bool]:
    """gmsh's (t, d+1) ascending `cells` (with their neighbour table and its mirror,
    facets.paired, manifold) plus the Delaunay cells it dropped near the hull, their
    neighbour table ((t', d+1) int32, -1 = none), its mirror and whether every facet is in
    at most two cells."""
    extra = _missing(points, cells, *boundary_facets(cells, nbrs))
    if not len(extra):
        return cells, nbrs, mirror, True
    return joined(points, cells, nbrs, extra, mirror)

"""Exact volume and lining area of regions of empty tetrahedra (voids, pockets), and the
complex's facts they are computed from (which cells, facets and edges are in it)."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.sparse import coo_matrix
from scipy.spatial import cKDTree

from core.molecule.exact_cells import clipped_cell_measures, near_balls, needs_clipping, neighbours
from core.molecule.measures import in_complex
from core.molecule.sectors import tet_edge_ids, tet_pieces, tet_volumes
from core.parallel import both

CHUNK = 100_000  # tetrahedra per vectorized batch


@dataclass(frozen=True, eq=False)
class DualFacts:
    """The weighted 3D complex at one alpha², as plain arrays.

    centres (n, 3) float64, radii (n,) float64 (sqrt(weight + alpha²)); cells (c, 4) int64;
    cell_in (c,) bool in the complex; tet_faces (c, 4) int64 facet opposite each vertex;
    facet_cells (f, 2) int64 cells beside each facet (-1 = beyond the hull); facet_in (f,)
    bool; tet_edges (c, 6) int64 (sectors.TET_EDGES order); edge_in (e,) bool; triangles
    (f, 3) int64 and tri_edges (f, 3) int64 the edge opposite each of their vertices;
    vertex_in (n,) bool the balls in the complex (None: all; a ball the others cover so that
    it never reaches its own power cell is a vertex of the triangulation but not of K).
    """

    centres: np.ndarray
    radii: np.ndarray
    cells: np.ndarray
    cell_in: np.ndarray
    tet_faces: np.ndarray
    facet_cells: np.ndarray
    facet_in: np.ndarray
    tet_edges: np.ndarray
    edge_in: np.ndarray
    triangles: np.ndarray
    tri_edges: np.ndarray
    vertex_in: np.ndarray | None = None

    @cached_property
    def tree(self) -> cKDTree:
        """KD-tree of the centres, built once for the voids and the pockets."""
        return cKDTree(self.centres)

    @cached_property
    def around(self) -> tuple[np.ndarray, np.ndarray]:
        """exact_cells.neighbours of the triangulation, found once for the voids and the
        pockets."""
        return neighbours(self)

    def vertices_in(self) -> np.ndarray:
        """(n,) bool: the balls that are vertices of K."""
        out = np.zeros(len(self.radii), bool)
        out[self.cells.ravel()] = True
        return out if self.vertex_in is None else out & self.vertex_in


def dual_facts(ac, alpha2: float = 0.0) -> DualFacts:
    """DualFacts of a weighted 3D AlphaComplex at alpha²."""
    def inside(k):
        return in_complex(ac, k, alpha2)

    tet_faces = np.asarray(ac.face_ids(3), np.int64)
    vertex_in = np.zeros(len(ac.points), bool)
    vertex_in[np.asarray(ac.simplices(0))[inside(0), 0]] = True
    return DualFacts(
        centres=np.asarray(ac.points, np.float64), radii=np.sqrt(ac.weights + alpha2),
        cells=np.asarray(ac.simplices(3), np.int64), cell_in=inside(3), tet_faces=tet_faces,
        facet_cells=np.asarray(ac.facet_cells(), np.int64), facet_in=inside(2),
        tet_edges=tet_edge_ids(tet_faces, ac.face_ids(2)), edge_in=inside(1),
        triangles=np.asarray(ac.simplices(2), np.int64),
        tri_edges=np.asarray(ac.face_ids(2), np.int64), vertex_in=vertex_in)


@dataclass(frozen=True, eq=False)
class RegionMeasures:
    """volume (k,) float64 empty space of each region (Å³), area (k,) float64 the surface
    of the union of balls lining it (Å²), atom_area (k, n) sparse CSR area of each ball
    lining each region."""

    volume: np.ndarray
    area: np.ndarray
    atom_area: object


def region_measures(facts: DualFacts, labels: np.ndarray, count: int) -> RegionMeasures:
    """Exact measures of the regions `labels` (c,) int64 (-1 = none; labels < count) of
    empty cells: their tetrahedra's volume minus the union of balls inside them (the sector
    split where it is exact, the balls clipped to the cell elsewhere: `exact_cells`)."""
    rows = np.flatnonzero(labels >= 0)
    volume, area = np.zeros(count), np.zeros(count)
    parts = []
    pairs = near_balls(facts, rows, facts.tree) if len(rows) else None
    clip = needs_clipping(facts, rows, pairs) if len(rows) else np.zeros(0, bool)
    sector_rows = rows[~clip]
    for start in range(0, len(sector_rows), CHUNK):
        cell = sector_rows[start:start + CHUNK]
        v = facts.cells[cell]
        c = facts.centres[v]
        c = c - c[:, :1]
        covered, sphere = tet_pieces(c, facts.radii[v], facts.edge_in[facts.tet_edges[cell]],
                                     facts.facet_in[facts.tet_faces[cell]])
        lab = labels[cell]
        volume += np.bincount(lab, weights=tet_volumes(c) - covered, minlength=count)
        area += np.bincount(lab, weights=sphere.sum(1), minlength=count)
        parts.append((np.repeat(lab, 4), v.ravel(), sphere.ravel()))
    clipped = rows[clip]
    half = len(clipped) // 2
    halves = (clipped[:half], clipped[half:])
    if len(clipped):
        at = np.cumsum(clip) - 1  # position among the clipped cells
        mine = clip[pairs[0]]
        i, j = at[pairs[0][mine]], pairs[1][mine]
        pairs = ((i[i < half], j[i < half]), (i[i >= half] - half, j[i >= half]))
        around = facts.around
    else:
        around = None
        pairs = ((np.zeros(0, np.int64),) * 2,) * 2
    # the clipped cells (the costly part) in two halves, one in a helper thread
    for cell, (covered, pos, ball, sphere) in zip(halves, both(
            lambda: clipped_cell_measures(facts, halves[0], pairs[0], around),
            lambda: clipped_cell_measures(facts, halves[1], pairs[1], around)), strict=True):
        c = facts.centres[facts.cells[cell]]
        lab = labels[cell]
        volume += np.bincount(lab, weights=tet_volumes(c - c[:, :1]) - covered,
                              minlength=count)
        area += np.bincount(lab[pos], weights=sphere, minlength=count)
        parts.append((lab[pos], ball, sphere))
    if parts:
        lab, atom, value = (np.concatenate(x) for x in zip(*parts, strict=True))
    else:
        lab, atom, value = np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0)
    atom_area = coo_matrix((value, (lab, atom)), shape=(count, len(facts.radii))).tocsr()
    return RegionMeasures(volume, area, atom_area)


def lining_atoms(measures: RegionMeasures, region: int, min_area: float = 1e-9
                 ) -> np.ndarray:
    """(k,) int64 rows of the balls with exposed area in `region`, by decreasing area."""
    row = measures.atom_area.getrow(region)
    keep = row.data > min_area
    idx, val = row.indices[keep], row.data[keep]
    return idx[np.argsort(-val, kind="stable")].astype(np.int64)

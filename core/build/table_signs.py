"""The interval table's sign decisions and ill-conditioned radii, made exact.

The table first decides in floating point (core.geometry.circumspheres); this module re-decides,
with the filtered predicates of core.geometry.predicates, every decision that floating point may
have got wrong: - which cells are flat (exact orientation) and the radii of ill-conditioned cells
  and of their facets (rational arithmetic, rounded once), so enter² matches an exact computation;
- whether a cofacet's vertex is strictly inside a facet's smallest sphere (attachment), for
  the facets whose sphere is nearly the cell's (the only ones where the float sign is in
  doubt), with "exactly on it" giving the facet the cell's radius exactly (equal radii);
- which triangle vertex is strictly inside the diametral sphere of the opposite edge (3D edge
  attachment), for every triangle (a cheap degree-2 predicate, filtered).
"""

from __future__ import annotations

import numpy as np

from core.geometry.circumspheres import edge_vectors
from core.geometry.exact import exact_radii
from core.geometry.predicates import (
    diametral_formula,
    diametral_signs,
    filtered_signs,
    orientations,
)
from core.parallel import nonzero, rows_cols
from core.tolerances import EXACT_RADIUS_SHAPE, NEAR_SPHERE_RTOL, SLIVER_RTOL


def slivers(det: np.ndarray, radius: np.ndarray, d: int) -> np.ndarray:
    """(n,) bool: cells whose |det| (d! volume) is below SLIVER_RTOL * r^d: ill-conditioned
    spheres (slivers, caps, needles), and cells float arithmetic called flat."""
    with np.errstate(over="ignore", invalid="ignore"):
        return ~(np.abs(det) > SLIVER_RTOL * radius**d)


def shapes(points: np.ndarray, simplices: np.ndarray) -> np.ndarray:
    """(n,) |det| / prod |v_i| of (n, k+1) simplices (k = d: cells; k = 2: triangles): 0 for
    flat, about 1 for well-shaped; the conditioning of their sphere's linear system."""
    vec = edge_vectors(points, simplices)
    lengths = np.sqrt(np.prod(np.einsum("nkd,nkd->nk", vec, vec), axis=1))
    if vec.shape[1] == vec.shape[2]:
        size = np.abs(np.linalg.det(vec))
    else:
        size = np.linalg.norm(np.cross(vec[:, 0], vec[:, 1]), axis=-1)
    return size / np.where(lengths > 0, lengths, 1.0)


def settle_cells(points: np.ndarray, cells: np.ndarray, enter: np.ndarray, det: np.ndarray,
                 flat: np.ndarray) -> int:
    """Exact flatness, determinant signs and radii (`enter`) of the ill-conditioned cells,
    in place; returns how many predicates needed exact arithmetic."""
    ids = np.flatnonzero(slivers(det, enter, points.shape[1]))
    if not len(ids):
        return 0
    signs, n_exact = orientations(points, cells[ids])
    solid = signs != 0
    poor = ids[solid & (shapes(points, cells[ids]) < EXACT_RADIUS_SHAPE["cell"])]
    flat[ids] = ~solid
    tiny = np.finfo(np.float64).tiny
    det[ids] = np.where(solid, signs * np.maximum(np.abs(det[ids]), tiny), 0.0)
    enter[poor] = exact_radii(points, cells[poor])
    return n_exact + len(poor)


def settle_obtuse(points: np.ndarray, triangles: np.ndarray, bits: np.ndarray,
                  doubt: np.ndarray) -> tuple[np.ndarray, int]:
    """The (n,) uint8 obtuse bits of (n, 3) triangles (bit j: vertex j strictly inside the
    diametral sphere of the opposite edge) with the (n, 3) `doubt` corners decided exactly
    (core.geometry.circumspheres.facet_radii2 with exact=True gives bits and doubt); and how
    many."""
    rows, corner = rows_cols(nonzero(lambda lo, hi: doubt[lo:hi], len(doubt)), 3)
    for j in range(3):
        ids = rows[corner == j]
        rest = [i for i in range(3) if i != j]
        signs, _ = filtered_signs(diametral_formula, points, triangles[ids, j],
                                  triangles[ids][:, rest])
        bits[ids] = (bits[ids] & ~np.uint8(1 << j)) | ((signs < 0).astype(np.uint8) << j)
    return bits, len(rows)


def _in_doubt(radius: np.ndarray, rows: np.ndarray | slice, cell: np.ndarray,
              enter: np.ndarray, sliver: np.ndarray) -> np.ndarray:
    """(k,) int64 positions in one side's list (settle_facets) of the decisions in doubt:
    the facet's sphere nearly the cell's (r_f² >~ r_c²) or the cell a sliver; in halves."""
    whole = isinstance(rows, slice)

    def near(lo: int, hi: int) -> np.ndarray:
        own = radius[lo:hi] if whole else np.take(radius, rows[lo:hi])
        out = own >= (1.0 - 0.5 * NEAR_SPHERE_RTOL) * enter[lo:hi]
        out |= np.take(sliver, cell[lo:hi])
        return out

    return nonzero(near, len(cell))


def settle_facets(points: np.ndarray, cells: np.ndarray, cell_enter: np.ndarray,
                  det: np.ndarray, facets: np.ndarray, radius: np.ndarray,
                  sides: list[tuple[np.ndarray, ...]]) -> tuple[np.ndarray, int]:
    """(n,) bool attachment of the facets (each side's float decision re-decided where in
    doubt) and how many predicates needed exact arithmetic; `radius` is updated in place:
    exactly (rationals) for facets of ill-conditioned cells, and equal to the cell's radius
    where the cell's vertex lies exactly on the facet's sphere.

    `sides`: (rows, cell, k, inside, enter) per side: the facet rows seen from `cell` (ids, or
    slice(None) for all), whose vertex k is opposite, the float decision `inside` (vertex strictly
    inside the sphere) and cell_enter[cell]. A decision is in doubt where the facet's sphere
    is nearly the cell's (the cell's centre near the facet's plane) or the cell is
    ill-conditioned (a sliver); there the exact diametral sign decides, and "exactly on the
    sphere" makes the facet's radius exactly the cell's."""
    d = points.shape[1]
    sliver = slivers(det, cell_enter, d) & (det != 0)  # once per cell, gathered per side
    attached = np.zeros(len(facets), dtype=bool)
    total = 0
    if d == 3:
        poor = np.zeros(len(facets), dtype=bool)
        for rows, cell, _, _, _ in sides:
            poor[rows] |= sliver[cell]
        ids = np.flatnonzero(poor)
        ids = ids[shapes(points, facets[ids]) < EXACT_RADIUS_SHAPE["triangle"]]
        radius[ids] = exact_radii(points, facets[ids])
        total += len(ids)
    for rows, cell, k, inside, enter in sides:
        ids = _in_doubt(radius, rows, cell, enter, sliver)
        decided = inside.copy()
        if len(ids):
            at = ids if isinstance(rows, slice) else rows[ids]
            signs, n_exact = diametral_signs(points, facets[at], cells[cell[ids], k[ids]])
            decided[ids] = signs < 0
            on = (signs == 0) & (det[cell[ids]] != 0)
            radius[at[on]] = enter[ids[on]]
            total += n_exact
        attached[rows] |= decided
    return attached, total

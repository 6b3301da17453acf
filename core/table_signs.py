"""The interval table's sign decisions and ill-conditioned radii, made exact.

The table first decides in floating point (core.geometry); this module re-decides, with the
filtered predicates of core.predicates, every decision that floating point may have got wrong:
- which cells are flat (exact orientation) and the radii of ill-conditioned cells and of their
  facets (rational arithmetic, rounded once), so enter² matches an exact computation;
- whether a cofacet's vertex is strictly inside a facet's smallest sphere (attachment), for
  the facets whose sphere is nearly the cell's (the only ones where the float sign is in
  doubt), with "exactly on it" giving the facet the cell's radius exactly (equal radii);
- which triangle vertex is strictly inside the diametral sphere of the opposite edge (3D edge
  attachment), for every triangle (a cheap degree-2 predicate, filtered).
"""

from __future__ import annotations

import numpy as np

from .exact import exact_radii
from .predicates import diametral_formula, diametral_signs, filtered_signs, orientations
from .tolerances import NEAR_SPHERE_RTOL, SLIVER_RTOL


def slivers(det: np.ndarray, radius: np.ndarray, d: int) -> np.ndarray:
    """(n,) bool: cells whose |det| (d! volume) is tiny against r^d: ill-conditioned spheres
    (slivers, caps, needles), and cells float arithmetic called flat."""
    with np.errstate(over="ignore", invalid="ignore"):
        return ~(np.abs(det) > SLIVER_RTOL * radius**d)


def settle_cells(points: np.ndarray, cells: np.ndarray, enter: np.ndarray, det: np.ndarray,
                 flat: np.ndarray) -> int:
    """Exact flatness, determinant signs and radii (`enter`) of the ill-conditioned cells,
    in place; returns how many predicates needed exact arithmetic."""
    ids = np.flatnonzero(slivers(det, enter, points.shape[1]))
    if not len(ids):
        return 0
    signs, n_exact = orientations(points, cells[ids])
    solid = signs != 0
    flat[ids] = ~solid
    tiny = np.finfo(np.float64).tiny
    det[ids] = np.where(solid, signs * np.maximum(np.abs(det[ids]), tiny), 0.0)
    enter[ids[solid]] = exact_radii(points, cells[ids[solid]])
    return n_exact + int(solid.sum())


def settle_attachment(points: np.ndarray, facets: np.ndarray, apex: np.ndarray,
                      inside: np.ndarray, facet_radius: np.ndarray, cell_radius: np.ndarray,
                      cell_det: np.ndarray) -> tuple[np.ndarray, np.ndarray, int]:
    """Re-decide `inside` (apex strictly inside the facet's smallest sphere) where the facet's
    sphere is nearly the cell's (the cell's centre near the facet's plane) or the cell is
    ill-conditioned; returns it, the (n,) bool rows found exactly ON the sphere (the facet's
    radius is then exactly the cell's), and how many needed exact arithmetic."""
    d = points.shape[1]
    near = facet_radius >= (1.0 - 0.5 * NEAR_SPHERE_RTOL) * cell_radius  # r_f² >~ r_c²
    near |= slivers(cell_det, cell_radius, d) & (cell_det != 0)
    ids = np.flatnonzero(near)
    on = np.zeros(len(inside), dtype=bool)
    if not len(ids):
        return inside, on, 0
    exact, n_exact = diametral_signs(points, facets[ids], apex[ids])
    inside = inside.copy()
    inside[ids] = exact < 0
    on[ids] = exact == 0
    return inside, on, n_exact


def obtuse_bits(points: np.ndarray, triangles: np.ndarray) -> tuple[np.ndarray, int]:
    """(n,) uint8 bits for (n, 3) triangles, bit j: vertex j strictly inside the diametral
    sphere of the opposite edge (the angle at j is obtuse), exactly; and how many predicates
    needed exact arithmetic."""
    bits = np.zeros(len(triangles), dtype=np.uint8)
    total = 0
    for j in range(3):
        rest = [c for c in range(3) if c != j]
        signs, exact = filtered_signs(diametral_formula, points, triangles[:, j],
                                      triangles[:, rest])
        bits |= (signs < 0).astype(np.uint8) << j
        total += int(exact.sum())
    return bits, total



def settle_facets(points: np.ndarray, cells: np.ndarray, cell_enter: np.ndarray,
                  det: np.ndarray, facets: np.ndarray, radius: np.ndarray,
                  sides: list[tuple[np.ndarray, ...]]) -> tuple[np.ndarray, int]:
    """(n,) bool attachment of the facets (each side's float decision re-decided where in
    doubt) and how many predicates needed exact arithmetic; `radius` is updated in place:
    exactly (rationals) for facets of ill-conditioned cells, and equal to the cell's radius
    where the cell's vertex lies exactly on the facet's sphere.

    `sides`: (rows, cell, k, inside) per side: the facet rows seen from `cell`, whose vertex
    k is opposite, and the float decision `inside` (vertex strictly inside the sphere)."""
    d = points.shape[1]
    attached = np.zeros(len(facets), dtype=bool)
    total = 0
    if d == 3:
        poor = np.zeros(len(facets), dtype=bool)
        for rows, cell, _, _ in sides:
            poor[rows] |= slivers(det[cell], cell_enter[cell], d) & (det[cell] != 0)
        ids = np.flatnonzero(poor)
        radius[ids] = exact_radii(points, facets[ids])
        total += len(ids)
    for rows, cell, k, inside in sides:
        decided, on, n_exact = settle_attachment(
            points, facets[rows], cells[cell, k], inside, radius[rows], cell_enter[cell],
            det[cell])
        attached[rows] |= decided
        on &= det[cell] != 0
        radius[rows[on]] = cell_enter[cell[on]]
        total += n_exact
    return attached, total

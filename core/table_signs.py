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
from .geometry import CHUNK, edge_vectors
from .predicates import diametral_formula, diametral_signs, filtered_signs, orientations
from .tolerances import EXACT_RADIUS_SHAPE, NEAR_SPHERE_RTOL, SLIVER_RTOL

#: The float dot product of two side differences (d <= 3 products, d - 1 sums, leaves
#: rounded once) is within 5 u of the exact value times the sum of |products| (u = 2**-53,
#: with room for the bound's own rounding); below TINY underflow could hide digits.
ANGLE_BOUND = 12 * 2.0**-53
TINY = 1e-250


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
    needed exact arithmetic. The dot products of the sides at each corner are filtered by
    their bound (4 roundings: side differences, products, two sums) in one pass."""
    bits = np.zeros(len(triangles), dtype=np.uint8)
    doubt = np.zeros((len(triangles), 3), dtype=bool)
    columns = [np.ascontiguousarray(points[:, c]) for c in range(points.shape[1])]
    for lo in range(0, len(triangles), CHUNK):
        tri = triangles[lo:lo + CHUNK]
        corners = [[np.take(col, tri[:, j]) for col in columns] for j in range(3)]
        for j in range(3):
            here, (one, two) = corners[j], [corners[i] for i in range(3) if i != j]
            value = perm = 0.0
            for c in range(len(columns)):
                a, b = one[c] - here[c], two[c] - here[c]
                value = value + a * b
                perm = perm + np.abs(a * b)
            bits[lo:lo + CHUNK] |= (value < 0).astype(np.uint8) << j
            doubt[lo:lo + CHUNK, j] = ~(np.abs(value) > ANGLE_BOUND * perm) | (perm < TINY)
    rows, corner = np.nonzero(doubt)
    for j in range(3):
        ids = rows[corner == j]
        rest = [i for i in range(3) if i != j]
        signs, _ = filtered_signs(diametral_formula, points, triangles[ids, j],
                                  triangles[ids][:, rest])
        bits[ids] = (bits[ids] & ~np.uint8(1 << j)) | ((signs < 0).astype(np.uint8) << j)
    return bits, len(rows)


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
        ids = ids[shapes(points, facets[ids]) < EXACT_RADIUS_SHAPE["triangle"]]
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

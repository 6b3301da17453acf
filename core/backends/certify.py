"""Is a set of cells THE Delaunay triangulation (the one Qhull returns)? Checked, never assumed.

A set of cells is the Delaunay triangulation of the points when it is a triangulation of
their convex hull (every point a vertex, every cell properly oriented, the two cells of every
inner facet on opposite sides, the outer facets exactly the hull's) and every inner facet is
locally Delaunay (the Delaunay lemma). A sign is settled in float64 when it exceeds a margin
relative to the magnitude of its terms (tolerances.BACKEND_CERTAIN_RTOL, 1e-12: some 300x
Shewchuk's float64 error bounds for these determinants); the few rows within the margin (2 of
12M facets on the 1M bunny scan) are settled exactly on the same float64 values
(core.geometry.predicates: exact integers), unweighted only. A facet is accepted only when its
vertex across is strictly outside (exactly): then every cell's circumsphere is strictly empty, the
triangulation is the unique Delaunay one, and every exact triangulator returns it.

Qhull, in floating point, may triangulate such a near-cospherical group otherwise; the table
never sees that difference: core.build.certify checks every facet of either backend's cells with
the same exact predicates (ties broken by one symbolic perturbation, which leaves strict signs
as they are) and flips until all hold, so Qhull's cells become these same unique cells, and
the table passes (which sort the cells) give the same arrays bit for bit. Exactly cospherical
facets (sign 0: more than one Delaunay triangulation), exactly flat cells and wrong signs are
refused, and weighted points with an undecided power test too: the caller falls back to Qhull.
Tested on random, clustered, surface and real-scan sets (tests/test_backends.py).
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import ConvexHull, QhullError

from core.build.delaunay import interior_facets
from core.geometry.circumspheres import CACHE_CHUNK
from core.geometry.predicates import in_sphere_sides
from core.geometry.predicates import orientations as exact_orientations
from core.parallel import PASSES, halves, nonzero, rows_cols, slot_of
from core.tolerances import BACKEND_CERTAIN_RTOL


def _orient(cols: list[np.ndarray], cells: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """det[v1 - v0, ..., vd - v0] of (n, d+1) cells and the same sum of absolute terms,
    from the points' coordinate columns `cols`."""
    rel = [[np.take(col, cells[:, k]) - np.take(col, cells[:, 0]) for col in cols]
           for k in range(1, cells.shape[1])]
    if len(cols) == 2:
        (bx, by), (cx, cy) = rel
        return bx * cy - by * cx, np.abs(bx * cy) + np.abs(by * cx)
    (bx, by, bz), (cx, cy, cz), (dx, dy, dz) = rel
    det = bx * (cy * dz - cz * dy) - by * (cx * dz - cz * dx) + bz * (cx * dy - cy * dx)
    perm = (np.abs(bx) * (np.abs(cy * dz) + np.abs(cz * dy))
            + np.abs(by) * (np.abs(cx * dz) + np.abs(cz * dx))
            + np.abs(bz) * (np.abs(cx * dy) + np.abs(cy * dx)))
    return det, perm


def _lifted(cols: list[np.ndarray], cells: np.ndarray, query: np.ndarray,
            weights: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The in-sphere determinant of each query point against its (n, d+1) cell (Shewchuk's
    incircle/insphere layout, relative to the query point) and its sum of absolute terms;
    with `weights`, the power (orthosphere) test: each lift |p - q|² less w_p - w_q."""
    q = [np.take(col, query) for col in cols]
    rel = [[np.take(col, cells[:, k]) - qc for col, qc in zip(cols, q, strict=True)]
           for k in range(cells.shape[1])]
    lift = [sum(c * c for c in r) for r in rel]
    mag = lift
    if weights is not None:
        dw = [np.take(weights, cells[:, k]) - np.take(weights, query)
              for k in range(cells.shape[1])]
        mag = [a + np.abs(b) for a, b in zip(lift, dw, strict=True)]
        lift = [a - b for a, b in zip(lift, dw, strict=True)]
    if len(cols) == 2:
        (ax, ay), (bx, by), (cx, cy) = rel
        minors = ((bx * cy, cx * by), (cx * ay, ax * cy), (ax * by, bx * ay))
        det = sum(w * (u - v) for w, (u, v) in zip(lift, minors, strict=True))
        perm = sum(w * (np.abs(u) + np.abs(v)) for w, (u, v) in zip(mag, minors, strict=True))
        return det, perm
    (ax, ay, az), (bx, by, bz), (cx, cy, cz), (dx, dy, dz) = rel
    minor = {}
    for name, (ux, uy), (vx, vy) in (("ab", (ax, ay), (bx, by)), ("bc", (bx, by), (cx, cy)),
                                     ("cd", (cx, cy), (dx, dy)), ("da", (dx, dy), (ax, ay)),
                                     ("ac", (ax, ay), (cx, cy)), ("bd", (bx, by), (dx, dy))):
        u, v = ux * vy, vx * uy
        minor[name] = (u - v, np.abs(u) + np.abs(v))
    det = {k: v[0] for k, v in minor.items()}
    perm = {k: v[1] for k, v in minor.items()}
    abc = az * det["bc"] - bz * det["ac"] + cz * det["ab"]
    bcd = bz * det["cd"] - cz * det["bd"] + dz * det["bc"]
    cda = cz * det["da"] + dz * det["ac"] + az * det["cd"]
    dab = dz * det["ab"] + az * det["bd"] + bz * det["da"]
    az, bz, cz, dz = np.abs(az), np.abs(bz), np.abs(cz), np.abs(dz)
    abc_p = az * perm["bc"] + bz * perm["ac"] + cz * perm["ab"]
    bcd_p = bz * perm["cd"] + cz * perm["bd"] + dz * perm["bc"]
    cda_p = cz * perm["da"] + dz * perm["ac"] + az * perm["cd"]
    dab_p = dz * perm["ab"] + az * perm["bd"] + bz * perm["da"]
    a, b, c, d = lift
    ma, mb, mc, md = mag
    return ((d * abc - c * dab) + (b * cda - a * bcd),
            md * abc_p + mc * dab_p + mb * cda_p + ma * bcd_p)


def _columns(points: np.ndarray) -> list[np.ndarray]:
    return [np.ascontiguousarray(points[:, k]) for k in range(points.shape[1])]


def orientations(points: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """(t,) int8 sign of det[v1 - v0, ..., vd - v0] of every cell, 0 = not certain."""
    cols = _columns(points)
    sign = np.empty(len(cells), dtype=np.int8)

    def part(start: int, stop: int) -> None:
        for lo in range(start, stop, CACHE_CHUNK):
            det, perm = _orient(cols, cells[lo:min(lo + CACHE_CHUNK, stop)])
            sign[lo:lo + len(det)] = np.where(np.abs(det) > BACKEND_CERTAIN_RTOL * perm,
                                              np.sign(det), 0)
    halves(part, len(cells))
    return sign


def in_sphere(points: np.ndarray, cells: np.ndarray, query: np.ndarray,
              orientation: np.ndarray, weights: np.ndarray | None = None) -> np.ndarray:
    """(n,) int8: +1 where point query[i] is certainly outside the circumsphere of cells[i]
    (with (m,) `weights`: has certainly positive power to its orthosphere), -1 certainly
    inside, 0 undecided (within the margin); `orientation` (n,) is the sign of each cell
    (orientations)."""
    cols = _columns(points)
    out = np.empty(len(cells), dtype=np.int8)

    def part(start: int, stop: int) -> None:
        for lo in range(start, stop, CACHE_CHUNK):
            hi = min(lo + CACHE_CHUNK, stop)
            det, perm = _lifted(cols, cells[lo:hi], query[lo:hi], weights)
            # Shewchuk's incircle is > 0 inside a triangle with det > 0; his insphere is > 0
            # inside a tetrahedron with det[v1 - v0, v2 - v0, v3 - v0] < 0
            side = np.sign(det) * orientation[lo:hi] * (1 if len(cols) == 3 else -1)
            out[lo:hi] = np.where(np.abs(det) > BACKEND_CERTAIN_RTOL * perm, side, 0)
    halves(part, len(cells))
    return out


def _near_pairs(neighbors: np.ndarray, near: np.ndarray) -> tuple[np.ndarray, ...]:
    """Each inner facet of a cell in the (t,) bool mask `near` once (a facet between two
    near cells once), as core.build.delaunay.interior_facets gives all: (t, i, u, j)."""
    rows = np.flatnonzero(near)
    row, i = np.nonzero(neighbors[rows] >= 0)
    t = rows[row]
    u = neighbors[t, i]
    once = ~near[u] | (u > t)
    t, i, u = t[once], i[once], u[once]
    return t, i, u, slot_of(neighbors, u, t)


def _outer_facets_are_hull(points: np.ndarray, cells: np.ndarray,
                           neighbors: np.ndarray) -> bool:
    """The facets with no cell across are exactly the (triangulated) convex hull facets of
    their own vertices, i.e. the union of the cells is convex."""
    width = cells.shape[1]
    t, i = rows_cols(nonzero(lambda lo, hi: neighbors[lo:hi] < 0, len(neighbors)), width)
    columns = np.array([[j for j in range(width) if j != k] for k in range(width)])
    outer = np.take_along_axis(cells[t], columns[i], axis=1)
    corners = np.unique(outer)
    if len(corners) < width:
        return False
    try:
        hull = ConvexHull(points[corners])
    except (QhullError, ValueError):
        return False
    facets = np.sort(corners[hull.simplices], axis=1)
    if len(facets) != len(outer):
        return False
    return bool(np.array_equal(np.unique(facets, axis=0), np.unique(outer, axis=0)))


def _oriented(points: np.ndarray, cells: np.ndarray, pairs: tuple[np.ndarray, ...],
              some: np.ndarray | slice) -> tuple[str, np.ndarray]:
    """The cells' orientation signs ((t,) int8, computed on the cells `some` only) and
    "" when they are all certain and the two cells of every facet pair (t, i, u, j) lie on
    opposite sides of it, else the reason."""
    t, i, u, j = pairs
    sign = np.zeros(len(cells), dtype=np.int8)
    sign[some] = orientations(points, cells[some])
    # the rows the float margin left undecided, among those computed (`some`: ids or all)
    doubt = np.flatnonzero(sign == 0) if isinstance(some, slice) else some[sign[some] == 0]
    if len(doubt):
        sign[doubt] = exact_orientations(points, cells[doubt])[0]
    if not sign[some].all():
        return f"{int(np.count_nonzero(sign[some] == 0))} cells are flat", sign
    same_side = ((i + j) % 2 == 1) == (sign[t] != sign[u])
    if same_side.any():
        return f"{int(np.count_nonzero(same_side))} pairs of cells overlap", sign
    return "", sign


def _spheres_empty(points: np.ndarray, cells: np.ndarray, pairs: tuple[np.ndarray, ...],
                   sign: np.ndarray, weights: np.ndarray | None) -> str:
    """"" when the vertex across every facet pair (t, i, u, j) is certainly outside cell
    t's circumsphere (power test with `weights`), else the reason."""
    t, _, u, j = pairs
    side = in_sphere(points, cells[t], cells[u, j], sign[t], weights)
    doubt = np.flatnonzero(side == 0)
    if len(doubt) and weights is None:
        side[doubt] = exact_sides(points, cells[t[doubt]], cells[u[doubt], j[doubt]],
                                  sign[t[doubt]])
    if (side <= 0).any():
        near = "cospherical" if weights is None else "near-cospherical"  # weighted: float only
        return (f"{int(np.count_nonzero(side <= 0))} facets are not certainly Delaunay "
                f"({near} points)")
    return ""


def exact_sides(points: np.ndarray, cells: np.ndarray, query: np.ndarray,
                orientation: np.ndarray) -> np.ndarray:
    """in_sphere's (n,) int8 answer settled exactly (core.geometry.predicates on the same float64
    values): +1 outside, -1 inside, 0 exactly on the circumsphere; for the few rows in_sphere
    leaves at 0."""
    return in_sphere_sides(points, cells, query, orientation)[0]


def why_not_locally_delaunay(points: np.ndarray, cells: np.ndarray, neighbors: np.ndarray,
                             mirror: np.ndarray | None = None) -> str:
    """The local half of why_not_delaunay on every inner facet of (t, d+1) ascending `cells`
    (certain orientations, the two cells of a facet on opposite sides, the vertex across
    outside the sphere), without its global checks (every point a vertex, the outer facets
    the hull): gmsh's own cells are checked so while the cells it dropped are restored."""
    pairs = interior_facets(neighbors, mirror)
    reason, sign = _oriented(points, cells, pairs, slice(None))
    return reason or _spheres_empty(points, cells, pairs, sign, None)


def why_not_delaunay(points: np.ndarray, cells: np.ndarray, neighbors: np.ndarray, *,
                     weights: np.ndarray | None = None, hidden: np.ndarray | None = None,
                     near: np.ndarray | None = None, mirror: np.ndarray | None = None) -> str:
    """"" when (t, d+1) ascending `cells` with their neighbour table are certainly the unique
    Delaunay triangulation of all (m, d) `points` (regular triangulation, with (m,)
    `weights`); else the first reason found.

    `hidden` (m,) bool: points known to be hidden (in no cell). `near` (t,) bool: check
    orientation and local Delaunay-ness only on the facets of these cells, and trust the
    others (the halves of core.backends.split: as Qhull made them; gmsh's own cells: checked
    by why_not_locally_delaunay): for the split the answer is then "the same cells as one
    Qhull call, given Qhull's own facets", not a proof for those facets.
    `mirror`: the neighbours' columns that point back (core.backends.facets.paired), if known.
    """
    used = np.zeros(len(points), dtype=bool)
    flat = cells.ravel()

    def mark(lo: int, hi: int) -> None:
        used[flat[lo:hi]] = True  # both halves only ever set True

    halves(mark, len(flat), PASSES)
    if hidden is not None:
        if (used & hidden).any():
            return f"{int(np.count_nonzero(used & hidden))} hidden points are vertices"
        used |= hidden
    if not used.all():
        return f"{int(np.count_nonzero(~used))} points are in no cell"
    pairs = interior_facets(neighbors, mirror) if near is None else _near_pairs(neighbors, near)
    some = slice(None) if near is None else np.unique(np.concatenate((pairs[0], pairs[2],
                                                                      np.flatnonzero(near))))
    reason, sign = _oriented(points, cells, pairs, some)
    if reason:
        return reason
    if not _outer_facets_are_hull(points, cells, neighbors):
        return "the outer facets are not the convex hull"
    return _spheres_empty(points, cells, pairs, sign, weights)

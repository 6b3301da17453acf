"""Vectorized smallest circumspheres and in-sphere tests for simplices, relative to a vertex.

Centres are computed as offsets from each simplex's first vertex, which keeps the arithmetic
small for scans far from the origin; degenerate simplices fall back to least squares.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from core.geometry.predicates import error_coefficient, uncertain
from core.parallel import in_chunks
from core.tolerances import (
    DEGENERATE_RTOL,
    EXTENDED_DEGENERATE_RTOL,
    ILL_CONDITIONED_RTOL,
    ON_SPHERE_RTOL,
)

CHUNK = 1 << 19
#: Rows per chunk of the arithmetic passes with many (n, 3) temporaries: small enough that
#: they stay in the caches (1.7-2.5x faster at 1M rows than CHUNK chunks; rowwise, so the
#: chunking never changes a value).
CACHE_CHUNK = 1 << 14


_CROSS = ((1, 2), (2, 0), (0, 1))  # component i of a x b is a[j] b[k] - a[k] b[j]


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(n, 3) a x b of (n, 3) rows."""
    out = np.empty((len(a), 3), dtype=np.result_type(a, b))
    for i, (j, k) in enumerate(_CROSS):
        np.subtract(a[:, j] * b[:, k], a[:, k] * b[:, j], out=out[:, i])
    return out


def _duals(vec: np.ndarray) -> np.ndarray:
    """(3, n, 3) b x c, c x a, a x b of the rows a, b, c of (n, 3, 3) `vec`: the same
    products as _cross, read from contiguous coordinate planes instead of strided columns."""
    planes = np.ascontiguousarray(vec.transpose(1, 2, 0))  # (vector, coordinate, n)
    out = np.empty((3, len(vec), 3), dtype=vec.dtype)
    for slot, (u, w) in enumerate(_CROSS):
        first, second = planes[u], planes[w]
        for i, (j, k) in enumerate(_CROSS):
            np.subtract(first[j] * second[k], first[k] * second[j], out=out[slot, :, i])
    return out


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.einsum("ij,ij->i", a, b)


def edge_vectors(points: np.ndarray, simplices: np.ndarray) -> np.ndarray:
    """(n, k, d) vectors from each simplex's first vertex to its others."""
    n, width = simplices.shape
    corners = np.take(points, simplices.ravel(), axis=0).reshape(n, width, points.shape[1])
    first = corners[:, 0].copy()  # one vertex at a time: no overlapping broadcast copy
    for j in range(1, width):
        np.subtract(corners[:, j], first, out=corners[:, j])
    return corners[:, 1:]


def extended(points: np.ndarray, simplices: np.ndarray,
             weights: np.ndarray | None = None) -> tuple[np.ndarray, ...]:
    """Centre offsets, determinants and degeneracy flags of ill-conditioned simplices,
    computed in extended precision: only what is flat there is treated as flat.

    With (m,) `weights` (squared radii) the centres are those of the orthogonal spheres."""
    wide = points.astype(np.longdouble)
    vec = wide[simplices[:, 1:]] - wide[simplices[:, :1]]
    rhs = None
    if weights is not None:
        wide_w = weights.astype(np.longdouble)
        rhs = (np.einsum("nid,nid->ni", vec, vec)
               - (wide_w[simplices[:, 1:]] - wide_w[simplices[:, :1]]))
    wider = np.finfo(np.longdouble).eps < 1e-18  # else long double is plain double
    c0, det, bad = solve_centres(vec, EXTENDED_DEGENERATE_RTOL if wider else DEGENERATE_RTOL,
                                 rhs)[:3]
    return c0.astype(np.float64), det.astype(np.float64), bad


def least_squares(vec: np.ndarray, rel_weights: np.ndarray | None = None
                  ) -> tuple[np.ndarray, np.ndarray]:
    """Offsets and squared radii of the smallest spheres through degenerate simplices.

    With (n, k+1) `rel_weights` (each vertex's weight minus the first vertex's), the smallest
    orthogonal spheres instead, and their powers relative to the first vertex's weight."""
    gram = np.einsum("nid,njd->nij", vec, vec)
    rhs = 0.5 * np.einsum("nid,nid->ni", vec, vec)
    if rel_weights is not None:
        rhs -= 0.5 * rel_weights[:, 1:]
    lam = np.einsum("nij,nj->ni", np.linalg.pinv(gram), rhs)
    c0 = np.einsum("ni,nid->nd", lam, vec)
    dist2 = np.einsum("nid,nid->ni", vec - c0[:, None, :], vec - c0[:, None, :])
    if rel_weights is not None:
        dist2 -= rel_weights[:, 1:]
    return c0, np.maximum(np.einsum("nd,nd->n", c0, c0), dist2.max(axis=1))


class Terms(NamedTuple):
    """The raw float64 terms of the circumcentre systems of (n, k+1) simplices, before any
    division or fallback: centre = num / (2 det) (core.build.cell_pass bounds their errors)."""

    vec: np.ndarray  # (n, k, d) edge vectors from the first vertex
    sq: np.ndarray  # (n, k) their squared lengths
    num: np.ndarray  # (n, d) numerators of the centre offsets
    det: np.ndarray  # (n,) determinants (|a x b|² for triangles in 3D)
    scale: np.ndarray  # (n,) what |det| is compared with for the shape
    duals: np.ndarray | None  # (k, n, d) for d-simplices: dual_i . vec_j = det if i == j


def centre_terms(vec: np.ndarray, rhs: np.ndarray | None = None,
                 sq: np.ndarray | None = None) -> Terms:
    """The centre system's terms for (n, k, d) edge vectors, k >= 2 (solve_centres); `sq`:
    their (n, k) squared lengths when the caller has them."""
    k, d = vec.shape[1], vec.shape[2]
    sq = np.einsum("nid,nid->ni", vec, vec) if sq is None else sq
    rhs = sq if rhs is None else rhs
    a, b = vec[:, 0], vec[:, 1]
    if k == 2 and d == 2:
        det = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
        num = np.stack((b[:, 1] * rhs[:, 0] - a[:, 1] * rhs[:, 1],
                        a[:, 0] * rhs[:, 1] - b[:, 0] * rhs[:, 0]), axis=1)
        scale = np.sqrt(sq[:, 0] * sq[:, 1])
        duals = np.stack([np.stack((b[:, 1], -b[:, 0]), axis=1),
                          np.stack((-a[:, 1], a[:, 0]), axis=1)])
    elif k == 2:
        n = _cross(a, b)
        det = _dot(n, n)
        num = rhs[:, :1] * _cross(b, n) + rhs[:, 1:2] * _cross(n, a)
        scale = np.sqrt(det * sq[:, 0] * sq[:, 1])  # det is |a x b|²: compare |a x b|
        duals = None
    else:
        duals = _duals(vec)
        det = _dot(a, duals[0])
        num = rhs[:, :1] * duals[0] + rhs[:, 1:2] * duals[1] + rhs[:, 2:3] * duals[2]
        scale = np.sqrt(sq[:, 0] * sq[:, 1] * sq[:, 2])
    return Terms(vec, sq, num, det, scale, duals)


def solve_centres(vec: np.ndarray, degenerate_rtol: float = DEGENERATE_RTOL,
                  rhs: np.ndarray | None = None, sq: np.ndarray | None = None
                  ) -> tuple[np.ndarray, ...]:
    """Centre offsets (n, d), determinants (n,), flags (degenerate, ill-conditioned), and for
    d-simplices the dual vectors (k, n, d): dual_i . vec_j = det if i == j else 0.

    The centre c solves 2 vec_i . c = rhs_i in the simplex's span; rhs defaults to |vec_i|²
    (circumcentres); |vec_i|² - (w_i - w_0) gives the centres of orthogonal spheres. `sq`:
    the (n, k) |vec_i|² when the caller has them."""
    if vec.shape[1] == 1:
        sq = np.einsum("nid,nid->ni", vec, vec) if sq is None else sq
        zero = sq[:, 0] == 0.0
        if rhs is None:
            return 0.5 * vec[:, 0], np.ones(len(vec)), zero, zero, None
        ratio = rhs[:, 0] / (2.0 * np.where(zero, 1.0, sq[:, 0]))
        return ratio[:, None] * vec[:, 0], np.ones(len(vec)), zero, zero, None
    return _solved(centre_terms(vec, rhs, sq), degenerate_rtol)


def _solved(terms: Terms, degenerate_rtol: float = DEGENERATE_RTOL) -> tuple[np.ndarray, ...]:
    """solve_centres' outputs from the terms (the arrays are fresh, not the terms')."""
    det = terms.det.copy()
    shape = np.abs(det) / np.where(terms.scale > 0, terms.scale, 1.0)  # 0 flat .. 1 well-shaped
    degenerate = shape <= degenerate_rtol
    safe = np.where(degenerate, 1.0, det)
    return (terms.num / (2.0 * safe)[:, None], det, degenerate, shape <= ILL_CONDITIONED_RTOL,
            terms.duals)


def _spheres(points: np.ndarray, simplices: np.ndarray) -> tuple[np.ndarray, ...]:
    """One chunk: centre offsets, radii², determinants, degenerate flags and attach bits
    (for d-simplices; else None), with extended precision and least squares where needed."""
    vec = edge_vectors(points, simplices)
    if vec.shape[1] == 1:
        return _finished(points, simplices, vec, solve_centres(vec))
    return spheres_of(points, simplices, centre_terms(vec))


def spheres_of(points: np.ndarray, simplices: np.ndarray, terms: Terms
               ) -> tuple[np.ndarray, ...]:
    """_spheres of (n, k+1) simplices (k >= 2) from their centre_terms (left unchanged)."""
    return _finished(points, simplices, terms.vec, _solved(terms))


def _finished(points: np.ndarray, simplices: np.ndarray, vec: np.ndarray,
              solved: tuple[np.ndarray, ...]) -> tuple[np.ndarray, ...]:
    c0, det, bad, poor, duals = solved
    if poor.any():
        c0[poor], det[poor], bad[poor] = extended(points, simplices[poor])
    r2 = np.einsum("nd,nd->n", c0, c0)
    bits = None if duals is None else barycentric_signs(duals, c0, det)
    if bad.any():
        c0[bad], r2[bad] = least_squares(vec[bad])
        if bits is not None:
            bits[bad] = 0
    return c0, r2, det, bad, bits


def circumspheres(
    points: np.ndarray, simplices: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Smallest circumspheres: centre offsets from the first vertex (n, d), radii² (n,), the
    determinant of the edge vectors (n,) (d! times the signed measure for d-simplices), and
    (n,) bool flags for degenerate simplices (no unique circumsphere: least squares used).

    Works for k-simplices in d dimensions with k < d too (the sphere centred in their hull).
    """
    parts = [_spheres(points, simplices[lo : lo + CHUNK]) for lo in range(0, len(simplices), CHUNK)]
    if not parts:
        return np.empty((0, points.shape[1])), np.empty(0), np.empty(0), np.empty(0, bool)
    return tuple(np.concatenate([p[i] for p in parts]) for i in range(4))


def any_point_inside(points: np.ndarray, centres: np.ndarray, r2: np.ndarray) -> np.ndarray:
    """(n,) bool: some point of the whole set lies strictly inside each sphere.

    The exact (global) attachment test, for the few simplices next to flat cells, where
    testing the cofacets' vertices is not enough.
    """
    from scipy.spatial import cKDTree

    centroid = points.mean(axis=0)
    dist, _ = cKDTree(points - centroid).query(centres - centroid, k=1)
    return dist * dist < r2 * (1.0 - 2.0 * ON_SPHERE_RTOL)


def barycentric_signs(duals: np.ndarray, c0: np.ndarray, det: np.ndarray) -> np.ndarray:
    """(n,) uint8, bit i set when the circumcentre's barycentric coordinate i is negative.

    For a cell, coordinate i < 0 means the centre lies beyond facet i, away from vertex i:
    exactly when vertex i is strictly inside that facet's smallest circumsphere (the two
    spheres share the facet's circle), so the bit says "vertex i attaches facet i".
    """
    rest = np.einsum("knd,nd->kn", duals, c0) / np.where(det == 0, 1.0, det)
    bits = ((1.0 - rest.sum(axis=0)) < -ON_SPHERE_RTOL).astype(np.uint8)
    for i, row in enumerate(rest, start=1):
        bits |= (row < -ON_SPHERE_RTOL).astype(np.uint8) << i
    return bits


def cell_spheres(
    points: np.ndarray, cells: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """For d-simplices: radii² (n,), determinants (n,) (d! x signed measure), flat flags (n,)
    and (n,) uint8 attach bits (bit i: vertex i strictly inside facet i's smallest sphere;
    always 0 for flat cells, which need the global test)."""
    n = len(cells)
    r2, dets = np.empty(n), np.empty(n)
    flat, bits = np.empty(n, dtype=bool), np.empty(n, dtype=np.uint8)

    def part(lo: int, hi: int) -> None:
        _, r2[lo:hi], dets[lo:hi], flat[lo:hi], bits[lo:hi] = _spheres(points, cells[lo:hi])

    in_chunks(part, n, CACHE_CHUNK)
    return r2, dets, flat, bits


def facet_radii2(points: np.ndarray, facets: np.ndarray, exact: bool = False
                 ) -> tuple[np.ndarray, np.ndarray | None]:
    """(n,) squared radii of the smallest circumspheres of edges or triangles, from side
    lengths; for triangles also (n,) uint8 obtuse bits (bit j: vertex j lies strictly inside
    the diametral sphere of the opposite edge, so it attaches that edge).

    Every side is its own difference of points and every angle's dot product uses that
    angle's own sides: deriving a side from the other two (|b - a|² = |a|² + |b|² - 2 a.b)
    cancels catastrophically on a needle (two long sides, a short one) and can go negative.
    The area comes from the two shortest sides, the best conditioned cross product.
    `exact`: the bits are the float signs of the angles' dot products without tolerance, and
    the (n, 3) bool corners whose sign the forward error bound leaves open are returned
    third (core.build.table_signs.settle_obtuse decides those exactly).
    """
    if facets.shape[1] == 2:
        diff = np.take(points, facets[:, 1], 0) - np.take(points, facets[:, 0], 0)
        return 0.25 * np.einsum("nd,nd->n", diff, diff), None
    out = np.empty(len(facets))
    bits = np.empty(len(facets), dtype=np.uint8)
    doubt = np.empty((len(facets), 3), dtype=bool) if exact else None

    def part(lo: int, hi: int) -> None:
        out[lo:hi], bits[lo:hi] = _triangle_radii2(
            points, facets[lo:hi], None if doubt is None else doubt[lo:hi])

    in_chunks(part, len(facets), CACHE_CHUNK)
    return (out, bits) if doubt is None else (out, bits, doubt)


def _triangle_radii2(points: np.ndarray, facets: np.ndarray, doubt: np.ndarray | None = None
                     ) -> tuple[np.ndarray, np.ndarray]:
    """One chunk of facet_radii2 for triangles: (n,) radii² and (n,) uint8 obtuse bits (with
    (n, 3) `doubt` to fill: filtered signs, facet_radii2's `exact`)."""
    p0, p1, p2 = (np.take(points, facets[:, i], 0) for i in range(3))
    a, b, c = p1 - p0, p2 - p0, p2 - p1
    del p0, p1, p2
    saa, sbb, scc = _dot(a, a), _dot(b, b), _dot(c, c)
    # the longest side is left out of the cross product: a x b = a x c = b x c exactly
    longest_a = (saa >= sbb) & (saa >= scc)
    first = np.where(longest_a[:, None], b, a)
    second = np.where(((sbb >= saa) & (sbb >= scc) | longest_a)[:, None], c, b)
    n = _cross(first, second)
    nn, short = _dot(n, n), _dot(first, first) * _dot(second, second)
    bad = nn <= (DEGENERATE_RTOL ** 2) * short
    out = saa * sbb * scc / (4.0 * np.where(bad, 1.0, nn))
    if bad.any():
        out[bad] = least_squares(np.stack((a[bad], b[bad]), axis=1))[1]
    if doubt is not None:
        return out, _angle_signs(a, b, c, (saa, sbb, scc), doubt)
    tol = ON_SPHERE_RTOL
    bits = (_dot(a, b) < -tol * (saa + sbb)).astype(np.uint8)  # angle at p0
    bits |= (_dot(a, c) > tol * (saa + scc)).astype(np.uint8) << 1  # p1: (-a).c < 0
    bits |= (_dot(b, c) < -tol * (sbb + scc)).astype(np.uint8) << 2  # p2: (-b).(-c)
    return out, bits


def _angle_signs(a: np.ndarray, b: np.ndarray, c: np.ndarray, lengths2: tuple,
                 doubt: np.ndarray) -> np.ndarray:
    """(n,) uint8 bits of the obtuse angles at p0, p1, p2 of triangles with sides a = p1 - p0,
    b = p2 - p0, c = p2 - p1 and their float squared lengths (float signs of the dot products
    of each corner's own sides), and in (n, 3) `doubt` the corners whose sign the forward
    bound cannot settle. A dot product (leaves rounded once, products, two sums: 5
    roundings) is off by at most gamma_5 times sum |u_k w_k| <= |u| |w| (Cauchy-Schwarz);
    sqrt of the float squared lengths' product is that within a few u, far inside the
    margin error_coefficient(5) = 12 u leaves over gamma_5."""
    coef = error_coefficient(5)
    saa, sbb, scc = lengths2
    bits = np.zeros(len(a), dtype=np.uint8)
    corners = ((_dot(a, b), saa * sbb), (-_dot(a, c), saa * scc),  # p1: (-a).c
               (_dot(b, c), sbb * scc))  # p2: (-b).(-c)
    for j, (value, product) in enumerate(corners):
        bits |= (value < 0).astype(np.uint8) << j
        doubt[:, j] = uncertain(value, np.sqrt(product), coef)
    return bits


def facet_sizes(points: np.ndarray, facets: np.ndarray) -> np.ndarray:
    """(n,) float64 length (edges) or area (triangles in 3D) of (n, 2|3) int facets, in
    chunks on two threads: three row gathers per chunk instead of one (n, k, d) fancy index."""
    out = np.empty(len(facets))

    def part(lo: int, hi: int) -> None:
        rows = facets[lo:hi]
        first = np.take(points, rows[:, 0], 0)
        side = np.take(points, rows[:, 1], 0) - first
        if rows.shape[1] == 3:
            side = _cross(side, np.take(points, rows[:, 2], 0) - first)
        np.sqrt(np.add.reduce(side * side, axis=1), out=out[lo:hi])
        if rows.shape[1] == 3:
            out[lo:hi] /= 2.0

    in_chunks(part, len(facets), CACHE_CHUNK)
    return out

"""Orthogonal spheres of weighted simplices (power distance |x - p|² - w), vectorized.

The weighted twin of core.geometry.circumspheres: a simplex's smallest orthogonal sphere has its
centre in the simplex's span, at equal power from all its vertices; its "radius²" is that power,
which may be negative. A vertex q attaches a face when its power to the face's sphere is negative;
as for circumspheres, that is exactly when the cofacet's orthocentre has a negative
barycentric coordinate at q, so the attach bits come from the same signs.
"""

from __future__ import annotations

import numpy as np

from core.geometry.circumspheres import (
    CACHE_CHUNK,
    barycentric_signs,
    edge_vectors,
    extended,
    least_squares,
    solve_centres,
)
from core.tolerances import (
    DEGENERATE_RTOL,
    ON_SPHERE_RTOL,
    POWER_CANCEL_RTOL,
    POWER_EXACT_RTOL,
)


def signed_sqrt(values: np.ndarray) -> np.ndarray:
    """sign(v) * sqrt(|v|): squared radii (powers) to the table's signed radii, monotone."""
    return np.copysign(np.sqrt(np.abs(values)), values) + 0.0  # + 0.0 folds -0.0 into 0.0


def signed_square(values: np.ndarray) -> np.ndarray:
    """v * |v|: the inverse of signed_sqrt (signed radii back to powers)."""
    return values * np.abs(values)


def _relative(weights: np.ndarray, simplices: np.ndarray) -> np.ndarray:
    """(n, k+1) each vertex's weight minus the simplex's first vertex's."""
    w = np.take(weights, simplices)
    return w - w[:, :1]


def _precise_powers(points: np.ndarray, weights: np.ndarray, simplices: np.ndarray
                    ) -> np.ndarray:
    """(n,) powers of (n, k+1) non-degenerate simplices computed in extended precision
    throughout (centre and |c|² - w), for values near zero that cancellation would spoil."""
    wide = points.astype(np.longdouble)
    wide_w = weights.astype(np.longdouble)
    vec = wide[simplices[:, 1:]] - wide[simplices[:, :1]]
    rhs = np.einsum("nid,nid->ni", vec, vec) - (wide_w[simplices[:, 1:]]
                                                 - wide_w[simplices[:, :1]])
    c0 = solve_centres(vec, DEGENERATE_RTOL, rhs)[0]
    return (np.einsum("nd,nd->n", c0, c0) - wide_w[simplices[:, 0]]).astype(np.float64)


def exact_power(corners: np.ndarray, weights: np.ndarray) -> float | None:
    """Power of the smallest sphere orthogonal to (k+1, d) weighted points, in rational
    arithmetic, rounded once to float64; None for affinely dependent points."""
    from fractions import Fraction

    p = [[Fraction(float(x)) for x in row] for row in corners]
    w = [Fraction(float(x)) for x in weights]
    vec = [[a - b for a, b in zip(row, p[0], strict=True)] for row in p[1:]]
    gram = [[sum(a * b for a, b in zip(u, v, strict=True)) for v in vec] for u in vec]
    rhs = [(sum(a * a for a in v) - (wi - w[0])) / 2 for v, wi in zip(vec, w[1:], strict=True)]
    y = _solve_exactly(gram, rhs)
    if y is None:
        return None
    centre = [sum(yi * v[j] for yi, v in zip(y, vec, strict=True)) for j in range(len(p[0]))]
    return float(sum(c * c for c in centre) - w[0])


def _solve_exactly(matrix: list, rhs: list) -> list | None:
    """Gaussian elimination over Fractions; None when the matrix is singular."""
    n = len(rhs)
    rows = [[*row, b] for row, b in zip(matrix, rhs, strict=True)]
    for col in range(n):
        pivot = next((r for r in range(col, n) if rows[r][col] != 0), None)
        if pivot is None:
            return None
        rows[col], rows[pivot] = rows[pivot], rows[col]
        for r in range(n):
            if r != col and rows[r][col] != 0:
                factor = rows[r][col] / rows[col][col]
                rows[r] = [a - factor * b for a, b in zip(rows[r], rows[col], strict=True)]
    return [rows[i][n] / rows[i][i] for i in range(n)]


def _refine(power: np.ndarray, size: np.ndarray, points: np.ndarray, weights: np.ndarray,
            simplices: np.ndarray, skip: np.ndarray | None = None) -> None:
    """Recompute in place the powers that cancellation made inaccurate (|p| small against
    `size`, the magnitudes subtracted), except the `skip` ones: in extended precision, and
    exactly where even that keeps too few digits."""
    cancel = np.abs(power) < POWER_CANCEL_RTOL * size
    if skip is not None:
        cancel &= ~skip
    if not cancel.any():
        return
    ids = np.flatnonzero(cancel)
    power[ids] = _precise_powers(points, weights, simplices[ids])
    for i in ids[np.abs(power[ids]) < POWER_EXACT_RTOL * size[ids]]:  # rare: near-zero ones
        value = exact_power(points[simplices[i]], weights[simplices[i]])
        if value is not None:
            power[i] = value


def _orthospheres(points: np.ndarray, weights: np.ndarray, simplices: np.ndarray,
                  vec: np.ndarray | None = None, sq: np.ndarray | None = None):
    """One chunk: centre offsets, powers, determinants, degenerate flags and (d-simplices)
    attach bits, with extended precision and least squares where needed. `vec`, `sq`: the
    chunk's edge_vectors and their squared lengths, when the caller has them already."""
    vec = edge_vectors(points, simplices) if vec is None else vec
    sq = np.einsum("nid,nid->ni", vec, vec) if sq is None else sq  # once, for both uses
    rel = _relative(weights, simplices)
    rhs = sq - rel[:, 1:]
    c0, det, bad, poor, duals = solve_centres(vec, DEGENERATE_RTOL, rhs, sq)
    if poor.any():
        c0[poor], det[poor], bad[poor] = extended(points, simplices[poor], weights)
    bits = None if duals is None else barycentric_signs(duals, c0, det)
    power = np.einsum("nd,nd->n", c0, c0)
    if bad.any():
        c0[bad], power[bad] = least_squares(vec[bad], rel[bad])
        if bits is not None:
            bits[bad] = 0
    w0 = np.take(weights, simplices[:, 0])
    size = power + np.abs(w0)
    power -= w0
    _refine(power, size, points, weights, simplices, skip=bad)
    return c0, power, det, bad, bits


def orthospheres(points: np.ndarray, weights: np.ndarray, simplices: np.ndarray):
    """Smallest orthogonal spheres of (n, k+1) simplices: centre offsets from the first vertex
    (n, d), powers (n,) (may be < 0), determinants (n,) and (n,) bool degenerate flags."""
    parts = [_orthospheres(points, weights, simplices[lo:lo + CACHE_CHUNK])[:4]
             for lo in range(0, len(simplices), CACHE_CHUNK)]
    if not parts:
        return np.empty((0, points.shape[1])), np.empty(0), np.empty(0), np.empty(0, bool)
    return tuple(np.concatenate([p[i] for p in parts]) for i in range(4))


def cell_orthospheres(points: np.ndarray, weights: np.ndarray, cells: np.ndarray):
    """For d-simplices: powers (n,), determinants (n,), flat flags (n,) and (n,) uint8 attach
    bits (bit i: vertex i has negative power to facet i's orthogonal sphere)."""
    n = len(cells)
    power, dets = np.empty(n), np.empty(n)
    flat, bits = np.empty(n, dtype=bool), np.empty(n, dtype=np.uint8)
    for lo in range(0, n, CACHE_CHUNK):
        sl = slice(lo, lo + CACHE_CHUNK)
        _, power[sl], dets[sl], flat[sl], bits[sl] = _orthospheres(points, weights, cells[sl])
    return power, dets, flat, bits


def edge_powers(points: np.ndarray, weights: np.ndarray, edges: np.ndarray):
    """(n,) powers of the orthogonal spheres of (n, 2) edges, (n, d) their centres, and (n,)
    uint8 bits (bit j: vertex j has negative power to the other vertex's sphere, -w)."""
    a = np.take(points, edges[:, 0], 0)
    vec = np.take(points, edges[:, 1], 0) - a
    sq = np.einsum("nd,nd->n", vec, vec)
    w0 = np.take(weights, edges[:, 0])
    t = (sq - (np.take(weights, edges[:, 1]) - w0)) / (2.0 * np.where(sq > 0, sq, 1.0))
    bits = ((1.0 - t) < -ON_SPHERE_RTOL).astype(np.uint8)
    bits |= (t < -ON_SPHERE_RTOL).astype(np.uint8) << 1
    near = t * t * sq
    power = near - w0
    _refine(power, near + np.abs(w0), points, weights, edges, skip=sq == 0)
    return power, a + t[:, None] * vec, bits


def triangle_powers(points: np.ndarray, weights: np.ndarray, triangles: np.ndarray):
    """(n,) powers of the orthogonal spheres of (n, 3) triangles in 3D and (n,) uint8 bits
    (bit j: vertex j has negative power to the opposite edge's orthogonal sphere)."""
    power = np.empty(len(triangles))
    bits = np.empty(len(triangles), dtype=np.uint8)
    for lo in range(0, len(triangles), CACHE_CHUNK):
        sl = slice(lo, lo + CACHE_CHUNK)
        vec = edge_vectors(points, triangles[sl])
        sq = np.einsum("nid,nid->ni", vec, vec)
        c0, power[sl], _, bad, _ = _orthospheres(points, weights, triangles[sl], vec, sq)
        lam = _coordinates(vec, c0, sq)
        chunk = ((1.0 - lam.sum(axis=1)) < -ON_SPHERE_RTOL).astype(np.uint8)
        chunk |= (lam[:, 0] < -ON_SPHERE_RTOL).astype(np.uint8) << 1
        chunk |= (lam[:, 1] < -ON_SPHERE_RTOL).astype(np.uint8) << 2
        chunk[bad] = 0
        bits[sl] = chunk
    return power, bits


def _coordinates(vec: np.ndarray, c0: np.ndarray, sq: np.ndarray) -> np.ndarray:
    """(n, 2) coefficients of offsets c0 in the (n, 2, 3) edge vectors of triangles, whose
    (n, 2) squared lengths are `sq` (the same sums as an einsum of each vector's own)."""
    a, b = vec[:, 0], vec[:, 1]
    aa, bb, ab = sq[:, 0], sq[:, 1], np.einsum("nd,nd->n", a, b)
    ca, cb = np.einsum("nd,nd->n", c0, a), np.einsum("nd,nd->n", c0, b)
    det = aa * bb - ab * ab
    det = np.where(det > 0, det, 1.0)
    return np.stack(((bb * ca - ab * cb) / det, (aa * cb - ab * ca) / det), axis=1)


def any_point_below(points: np.ndarray, weights: np.ndarray, centres: np.ndarray,
                    power: np.ndarray) -> np.ndarray:
    """(n,) bool: some point of the whole set has power |c - q|² - w_q below each sphere's.

    The exact (global) attachment test, for the few faces next to flat cells.
    """
    from scipy.spatial import cKDTree

    out = np.zeros(len(centres), dtype=bool)
    reach2 = power + float(weights.max())
    candidates = np.flatnonzero(reach2 > 0)
    if len(candidates) == 0:
        return out
    centroid = points.mean(axis=0)
    tree = cKDTree(points - centroid)
    near = tree.query_ball_point(centres[candidates] - centroid, np.sqrt(reach2[candidates]))
    for row, ids in zip(candidates, near, strict=True):  # rare: degenerate input only
        if ids:
            d2 = ((points[ids] - centres[row]) ** 2).sum(axis=1)
            gap = d2 - weights[ids] - power[row]
            out[row] = bool((gap < -ON_SPHERE_RTOL * (d2 + np.abs(weights[ids])
                                                       + abs(power[row]))).any())
    return out

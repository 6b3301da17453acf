"""The anisotropic alpha test (Teichmann & Capps 1998): a ball compressed along the surface.

Each simplex gets one normal n (its vertices' normals summed with the signs that make the sum
longest, so point orientation does not matter). The alpha ball compressed along n to half-axis
(1 - tau) alpha is an ellipsoid; a point set fits in it exactly when, stretched along n by
1 / (1 - tau) about the simplex's first vertex, it fits in the ball of radius alpha. So the
simplex's test radius is the smallest-circumsphere radius of its stretched vertices, and it is
attached when a Delaunay cofacet's opposite vertex, stretched the same way, lies strictly
inside that sphere (close parallel sheets then leave each other's triangles unattached).

The functions work on chunks of simplices held as coordinate columns: `Vec` is a list of d
(n,) float64 arrays, one per coordinate, so every step is a flat, contiguous numpy pass.
"""

from __future__ import annotations

import numpy as np

from core.geometry.circumspheres import circumspheres
from core.tolerances import ILL_CONDITIONED_RTOL

Vec = list[np.ndarray]  #: d coordinate columns (n,) float64 of n vectors

#: Sign patterns whose squared sums differ by at most this (of the order of width² = 16) are
#: near-ties, settled by the explicit loop as rounding settled them before the fast path.
_NEAR_TIE = 1e-9


def dot(u: Vec, w: Vec) -> np.ndarray:
    """(n,) row dot products of two column vectors."""
    out = u[0] * w[0]
    for a, b in zip(u[1:], w[1:], strict=True):
        out += a * b
    return out


def minus(u: Vec, w: Vec) -> Vec:
    """u - w, column by column."""
    return [a - b for a, b in zip(u, w, strict=True)]


def cross(u: Vec, w: Vec) -> Vec:
    """u x w of 3D column vectors."""
    return [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]


def signed_sums(corners: list[Vec], dots: dict[tuple[int, int], np.ndarray]) -> Vec:
    """The sums of simplices' vertex normals `corners` (one Vec per vertex) with the signs
    (the first fixed) that make them longest, from their pairwise dots {(i, j): (n,)}. The
    squared length of a signed sum is constant + 2 sum s_i s_j n_i.n_j, so the dots pick the
    signs; near-ties (e.g. perpendicular normals) take the loop over the sign patterns, whose
    rounding decides which of the equally long sums wins."""
    width = len(corners)
    if width == 2:  # the pattern loop's result for two, in fewer passes
        flip = dots[0, 1] < 0
        total = [a + np.where(flip, -b, b) for a, b in zip(*corners, strict=True)]
        near = np.flatnonzero(np.abs(dots[0, 1]) <= 0.5 * _NEAR_TIE)
    else:
        total = [c.copy() for c in corners[0]]
        near = np.empty(0, dtype=np.intp) if width == 1 else _pick_signs(corners, dots, total)
    if len(near):
        fixed = _longest_sum(np.stack([np.stack([c[near] for c in v], axis=1)
                                       for v in corners], axis=1))
        for i, t in enumerate(total):
            t[near] = fixed[:, i]
    return total


def _pick_signs(corners: list[Vec], dots: dict[tuple[int, int], np.ndarray],
                total: Vec) -> np.ndarray:
    """Add the other corners to `total` (the first's copy) with the longest sum's signs;
    return the rows whose best and second best sign patterns are near-ties."""
    width = len(corners)
    best, second, pattern = None, None, None
    for combo in range(2 ** (width - 1)):  # sign patterns, not simplices
        signs = [1.0] + [-1.0 if combo >> (j - 1) & 1 else 1.0 for j in range(1, width)]
        value = None
        for i, j in sorted(dots):  # sum s_i s_j n_i.n_j, adding or subtracting
            if value is None:
                value = dots[i, j].copy() if signs[i] == signs[j] else -dots[i, j]
            elif signs[i] == signs[j]:
                value += dots[i, j]
            else:
                value -= dots[i, j]
        if best is None:
            best, second = value, np.full(len(value), -np.inf)
            pattern = np.zeros(len(value), dtype=np.int8)
            continue
        better = value > best
        second = np.where(better, best, np.maximum(second, value))
        best = np.maximum(best, value)
        pattern[better] = combo
    for j in range(1, width):
        sign = np.where(pattern >> (j - 1) & 1, -1.0, 1.0)
        for t, c in zip(total, corners[j], strict=True):
            t += sign * c
    return np.flatnonzero(best - second <= _NEAR_TIE)


def combined_normals(corners: list[Vec], dots: dict[tuple[int, int], np.ndarray]) -> Vec:
    """Unit normal columns of simplices: signed_sums scaled to length 1 (0 where the vertex
    normals cancel)."""
    total = signed_sums(corners, dots)
    length = np.sqrt(dot(total, total))
    length[length == 0] = 1.0
    return [t / length for t in total]


def _longest_sum(corner_normals: np.ndarray) -> np.ndarray:
    """(n, d) signed sums of (n, k+1, d) vertex normals by trying every sign pattern (the
    first longest wins): for the few near-ties."""
    n, width, _ = corner_normals.shape
    best, best_value = corner_normals[:, 0].copy(), np.full(n, -np.inf)
    for combo in range(2 ** (width - 1)):  # sign patterns, not simplices
        total = corner_normals[:, 0].copy()
        for j in range(1, width):
            if combo >> (j - 1) & 1:
                total -= corner_normals[:, j]
            else:
                total += corner_normals[:, j]
        value = np.einsum("nd,nd->n", total, total)
        better = value > best_value
        best[better], best_value[better] = total[better], value[better]
    return best


def stretch(vector: Vec, normal: Vec, extra: float) -> Vec:
    """`vector` (in place) with its component along the unit `normal` scaled by 1 + extra."""
    along = dot(vector, normal)
    along *= extra
    for v, n in zip(vector, normal, strict=True):
        v += along * n
    return vector


def sphere_centres(edges: list[Vec]) -> tuple[Vec, np.ndarray]:
    """Centre offsets (from the first vertex) and radii² of the smallest spheres of simplices
    given by their edge vectors from the first vertex (k = 1..d of them, d = 2 or 3): the
    closed forms, and circumspheres (extended precision, least squares) for the
    ill-conditioned few."""
    sq = [dot(e, e) for e in edges]
    if len(edges) == 1:
        centre = [0.5 * c for c in edges[0]]
        return centre, dot(centre, centre)
    a, b = edges[0], edges[1]
    if len(edges) == 2 and len(a) == 2:
        det = a[0] * b[1] - a[1] * b[0]
        num = [b[1] * sq[0] - a[1] * sq[1], a[0] * sq[1] - b[0] * sq[0]]
        scale = np.sqrt(sq[0] * sq[1])
    elif len(edges) == 2:
        n = cross(a, b)
        det = dot(n, n)
        first, second = cross(b, n), cross(n, a)
        num = [sq[0] * f + sq[1] * s for f, s in zip(first, second, strict=True)]
        scale = np.sqrt(det * sq[0] * sq[1])  # det is |a x b|²: compare |a x b|
    else:
        c = edges[2]
        duals = cross(b, c), cross(c, a), cross(a, b)
        det = dot(a, duals[0])
        num = [sq[0] * u + sq[1] * v + sq[2] * w for u, v, w in zip(*duals, strict=True)]
        scale = np.sqrt(sq[0] * sq[1] * sq[2])
    poor = np.abs(det) <= ILL_CONDITIONED_RTOL * scale
    half = 0.5 / np.where(poor, 1.0, det)
    centre = [x * half for x in num]
    radii2 = dot(centre, centre)
    if poor.any():  # as whole simplices (first vertex at 0) for the exact fallbacks
        _redo(edges, np.flatnonzero(poor), centre, radii2)
    return centre, radii2


def _redo(edges: list[Vec], rows: np.ndarray, centre: Vec, radii2: np.ndarray) -> None:
    """Centres and radii² of the simplices `rows` by core.geometry.circumspheres.circumspheres, in
    place."""
    d, width = len(centre), len(edges) + 1
    corners = np.zeros((len(rows), width, d))
    for i, e in enumerate(edges, start=1):
        corners[:, i] = np.stack([c[rows] for c in e], axis=1)
    ids = np.arange(len(rows) * width, dtype=np.int64).reshape(-1, width)
    offsets, radii2[rows] = circumspheres(corners.reshape(-1, d), ids)[:2]
    for i, c in enumerate(centre):
        c[rows] = offsets[:, i]

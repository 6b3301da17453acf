"""The anisotropic alpha test (Teichmann & Capps 1998): a ball compressed along the surface.

Each simplex gets one normal n (its vertices' normals summed with the signs that make the sum
longest, so point orientation does not matter). The alpha ball compressed along n to half-axis
(1 - tau) alpha is an ellipsoid; a point set fits in it exactly when, stretched along n by
1 / (1 - tau) about the simplex's first vertex, it fits in the ball of radius alpha. So the
simplex's test radius is the smallest-circumsphere radius of its stretched vertices, and it is
attached when a Delaunay cofacet's opposite vertex, stretched the same way, lies strictly
inside that sphere (close parallel sheets then leave each other's triangles unattached).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .geometry import CHUNK, circumspheres, edge_vectors, solve_centres
from .parallel import halves
from .tolerances import ON_SPHERE_RTOL

#: Sign patterns whose squared sums differ by at most this (of the order of width² = 16) are
#: near-ties, settled by the explicit loop as rounding settled them before the fast path.
_NEAR_TIE = 1e-9


@dataclass(frozen=True)
class Spheres:
    """Smallest spheres of stretched simplices: centres as offsets from each simplex's first
    vertex in stretched coordinates (n, d), radii² (n,), and the unit normals used (n, d)."""

    centres: np.ndarray
    radii2: np.ndarray
    normals: np.ndarray


def combined_normals(corner_normals: np.ndarray) -> np.ndarray:
    """(n, d) unit normal of each simplex from its (n, k+1, d) vertex normals (0 where they
    cancel): their sum with the signs (the first fixed) that make it longest. The squared
    length of a signed sum is constant + 2 sum s_i s_j n_i.n_j, so the pairwise dots pick the
    signs; near-ties (e.g. perpendicular normals) take the loop over the sign patterns, whose
    rounding decides which of the equally long sums wins."""
    n, width, _ = corner_normals.shape
    best = corner_normals[:, 0].copy()
    if width > 1:
        signs = np.array([[1.0] + [-1.0 if combo >> (j - 1) & 1 else 1.0
                                   for j in range(1, width)]
                          for combo in range(2 ** (width - 1))])  # (patterns, width)
        pairs = [(i, j) for i in range(width) for j in range(i + 1, width)]
        dots = np.empty((n, len(pairs)))
        for p, (i, j) in enumerate(pairs):
            dots[:, p] = np.einsum("nd,nd->n", corner_normals[:, i], corner_normals[:, j])
        products = np.array([[s[i] * s[j] for i, j in pairs] for s in signs]).T
        values = np.einsum("np,pc->nc", dots, products)
        chosen = signs[np.argmax(values, axis=1)]
        for j in range(1, width):
            best += chosen[:, j, None] * corner_normals[:, j]
        if len(signs) > 1:
            top2 = np.partition(values, -2, axis=1)[:, -2:]
            near = np.flatnonzero(top2[:, 1] - top2[:, 0] <= _NEAR_TIE)
            if len(near):
                best[near] = _longest_sum(corner_normals[near])
    length = np.sqrt(np.einsum("nd,nd->n", best, best))
    return best / np.where(length > 0, length, 1.0)[:, None]


def _longest_sum(corner_normals: np.ndarray) -> np.ndarray:
    """combined_normals before normalising, by trying every sign pattern (the first longest
    wins): for the few near-ties."""
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


def _stretch(vectors: np.ndarray, normal: np.ndarray, extra: float) -> np.ndarray:
    """(n, j, d) vectors (in place) with their component along each (n, d) normal scaled by
    1 + extra."""
    along = np.einsum("njd,nd->nj", vectors, normal)
    vectors += extra * along[:, :, None] * normal[:, None, :]
    return vectors


def stretched_spheres(points: np.ndarray, simplices: np.ndarray, normals: np.ndarray,
                      tau: float) -> Spheres:
    """Smallest spheres of (n, k+1) simplices of `points` stretched by 1 / (1 - tau) along
    their combined normals (from (m, d) point `normals`). The closed-form centres of the
    stretched edge vectors serve all but the ill-conditioned few, which go through
    circumspheres (extended precision, least squares) as whole simplices."""
    n, d = len(simplices), points.shape[1]
    extra = 1.0 / (1.0 - tau) - 1.0
    centres, radii2, unit = np.empty((n, d)), np.empty(n), np.empty((n, d))

    def part(start: int, stop: int) -> None:
        for lo in range(start, stop, CHUNK):
            _sphere_chunk(points, simplices, normals, extra, slice(lo, min(lo + CHUNK, stop)),
                          (centres, radii2, unit))

    halves(part, n)
    return Spheres(centres, radii2, unit)


def _sphere_chunk(points: np.ndarray, simplices: np.ndarray, normals: np.ndarray,
                  extra: float, sl: slice, out: tuple[np.ndarray, ...]) -> None:
    """stretched_spheres on the rows `sl`, written into out = (centres, radii2, unit)."""
    centres, radii2, unit = out
    width, d = simplices.shape[1], points.shape[1]
    chunk = simplices[sl]
    unit[sl] = combined_normals(normals[chunk])
    vec = _stretch(edge_vectors(points, chunk), unit[sl], extra)
    if width == 2:
        centres[sl] = 0.5 * vec[:, 0]
        radii2[sl] = np.einsum("nd,nd->n", centres[sl], centres[sl])
        return
    c0, _, _, poor, _ = solve_centres(vec)
    radii2[sl] = np.einsum("nd,nd->n", c0, c0)
    if poor.any():  # as whole simplices (first vertex at 0) for the exact fallbacks
        redo = np.concatenate((np.zeros((int(poor.sum()), 1, d)), vec[poor]), axis=1)
        ids = np.arange(redo.shape[0] * width, dtype=np.int64).reshape(-1, width)
        c0[poor], radii2[sl][poor] = circumspheres(redo.reshape(-1, d), ids)[:2]
    centres[sl] = c0


def attached(points: np.ndarray, faces: np.ndarray, spheres: Spheres, cofaces: np.ndarray,
             face_ids: np.ndarray, tau: float) -> np.ndarray:
    """(n_faces,) bool: some cofacet's opposite vertex, stretched with the face, lies strictly
    inside the face's stretched sphere. `cofaces` (c, k+2) and `face_ids` (c, k+2): the
    cofacet level's simplices and the row in `faces` opposite each of their vertices.

    The stretch S is linear, so |S(p - v0) - c| = |S(p - o)| with o = v0 + S^-1 c, the sphere's
    centre in the original coordinates: |p - o|² + ((1 + extra)² - 1) (n.(p - o))²."""
    extra = 1.0 / (1.0 - tau) - 1.0
    normals = spheres.normals
    along = np.einsum("nd,nd->n", spheres.centres, normals) * (extra / (1.0 + extra))
    origins = points[faces[:, 0]] + spheres.centres - along[:, None] * normals
    gain = (1.0 + extra) ** 2 - 1.0
    limit = spheres.radii2 * (1 - 2 * ON_SPHERE_RTOL)
    out = np.zeros(len(faces), dtype=bool)

    def part(start: int, stop: int) -> None:  # the halves only ever set True: no race
        for lo in range(start, stop, CHUNK):
            hi = min(lo + CHUNK, stop)
            face = face_ids[lo:hi].ravel()
            vec = points[cofaces[lo:hi].ravel()]
            vec -= origins[face]
            dist2 = np.einsum("nd,nd->n", vec, normals[face])
            dist2 *= dist2
            dist2 *= gain
            dist2 += np.einsum("nd,nd->n", vec, vec)
            out[face[dist2 < limit[face]]] = True

    halves(part, len(cofaces))
    return out

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

from .geometry import CHUNK, circumspheres
from .tolerances import ON_SPHERE_RTOL


@dataclass(frozen=True)
class Spheres:
    """Smallest spheres of stretched simplices: centres as offsets from each simplex's first
    vertex in stretched coordinates (n, d), radii² (n,), and the unit normals used (n, d)."""

    centres: np.ndarray
    radii2: np.ndarray
    normals: np.ndarray


def combined_normals(corner_normals: np.ndarray) -> np.ndarray:
    """(n, d) unit normal of each simplex from its (n, k+1, d) vertex normals (0 where they
    cancel): their sum with the signs (the first fixed) that make it longest."""
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
    length = np.sqrt(np.maximum(best_value, 0.0))
    return best / np.where(length > 0, length, 1.0)[:, None]


def _stretch(vectors: np.ndarray, normal: np.ndarray, extra: float) -> np.ndarray:
    """(n, j, d) vectors (in place) with their component along each (n, d) normal scaled by
    1 + extra."""
    along = np.einsum("njd,nd->nj", vectors, normal)
    vectors += extra * along[:, :, None] * normal[:, None, :]
    return vectors


def stretched_spheres(points: np.ndarray, simplices: np.ndarray, normals: np.ndarray,
                      tau: float) -> Spheres:
    """Smallest spheres of (n, k+1) simplices of `points` stretched by 1 / (1 - tau) along
    their combined normals (from (m, d) point `normals`)."""
    n, width = simplices.shape
    d = points.shape[1]
    extra = 1.0 / (1.0 - tau) - 1.0
    centres, radii2, unit = np.empty((n, d)), np.empty(n), np.empty((n, d))
    for lo in range(0, n, CHUNK):
        sl = slice(lo, lo + CHUNK)
        chunk = simplices[sl]
        unit[sl] = combined_normals(normals[chunk])
        corners = points[chunk]
        corners -= corners[:, :1]
        _stretch(corners[:, 1:], unit[sl], extra)
        if width == 2:
            centres[sl] = 0.5 * corners[:, 1]
            radii2[sl] = np.einsum("nd,nd->n", centres[sl], centres[sl])
            continue
        flat = corners.reshape(-1, d)
        ids = np.arange(len(flat), dtype=np.int64).reshape(-1, width)
        centres[sl], radii2[sl] = circumspheres(flat, ids)[:2]
    return Spheres(centres, radii2, unit)


def attached(points: np.ndarray, faces: np.ndarray, spheres: Spheres, cofaces: np.ndarray,
             face_ids: np.ndarray, tau: float) -> np.ndarray:
    """(n_faces,) bool: some cofacet's opposite vertex, stretched with the face, lies strictly
    inside the face's stretched sphere. `cofaces` (c, k+2) and `face_ids` (c, k+2): the
    cofacet level's simplices and the row in `faces` opposite each of their vertices."""
    extra = 1.0 / (1.0 - tau) - 1.0
    out = np.zeros(len(faces), dtype=bool)
    for lo in range(0, len(cofaces), CHUNK):
        face = face_ids[lo:lo + CHUNK].ravel()
        vec = points[cofaces[lo:lo + CHUNK].ravel()] - points[faces[face, 0]]
        vec = _stretch(vec[:, None, :], spheres.normals[face], extra)[:, 0]
        vec -= spheres.centres[face]
        inside = np.einsum("nd,nd->n", vec, vec) < spheres.radii2[face] * (1 - 2 * ON_SPHERE_RTOL)
        out[face[inside]] = True
    return out

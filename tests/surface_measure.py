"""How well a shape's triangles match a reference surface: distance and coverage in spacings.

Both surfaces are sampled densely (uniform in area, a fixed seed) and compared with scipy's
cKDTree, independently of the complex: distance = how far the shape's samples lie from the
reference surface, coverage = share of the reference's samples near some shape triangle.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

SAMPLES_PER_SPACING_SQ = 8  # sample density: about spacing / 3 between samples
FAR = 4.0  # distances beyond FAR spacings are not measured (reported as inf)


def triangle_areas(vertices: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """(t,) float64 areas of (t, 3) triangles on (n, 3) vertices."""
    corners = np.asarray(vertices, dtype=np.float64)[np.asarray(triangles)]
    normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    return 0.5 * np.linalg.norm(normal, axis=1)


def sample_triangles(vertices: np.ndarray, triangles: np.ndarray, spacing: float,
                     seed: int = 0) -> np.ndarray:
    """(s, 3) points uniform in area over the triangles, SAMPLES_PER_SPACING_SQ per spacing²,
    plus their vertices (so even tiny triangles are represented)."""
    rng = np.random.default_rng(seed)
    vertices = np.asarray(vertices, dtype=np.float64)
    triangles = np.asarray(triangles, dtype=np.int64)
    areas = triangle_areas(vertices, triangles)
    count = int(np.ceil(areas.sum() * SAMPLES_PER_SPACING_SQ / spacing**2))
    if count == 0 or areas.sum() == 0:
        return vertices[np.unique(triangles)]
    chosen = rng.choice(len(triangles), size=count, p=areas / areas.sum())
    u, v = rng.random(count), rng.random(count)
    flip = u + v > 1
    u[flip], v[flip] = 1 - u[flip], 1 - v[flip]
    a, b, c = (vertices[triangles[chosen, j]] for j in range(3))
    inside = a + u[:, None] * (b - a) + v[:, None] * (c - a)
    return np.concatenate([inside, vertices[np.unique(triangles)]])


def surface_match(shape_vertices: np.ndarray, shape_triangles: np.ndarray,
                  ref_vertices: np.ndarray, ref_triangles: np.ndarray, spacing: float,
                  near: float = 1.5) -> tuple[float, float]:
    """(95th percentile distance of the shape from the reference, in spacings; share of the
    reference within `near` spacings of the shape). A distance beyond FAR spacings is inf."""
    if len(shape_triangles) == 0:
        return float("inf"), 0.0
    shape = sample_triangles(shape_vertices, shape_triangles, spacing, seed=1)
    reference = sample_triangles(ref_vertices, ref_triangles, spacing, seed=2)
    distance, _ = cKDTree(reference).query(shape, distance_upper_bound=FAR * spacing)
    gap, _ = cKDTree(shape).query(reference, distance_upper_bound=near * spacing)
    p95 = float(np.percentile(distance, 95, method="inverted_cdf"))
    return p95 / spacing, float(np.mean(gap <= near * spacing))

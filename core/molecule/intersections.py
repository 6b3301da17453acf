"""Exact volume and sphere areas of the intersection of 2, 3 or 4 balls, vectorized.

Each intersection I of the balls of a simplex is cut by the radical planes of its balls into
pieces I ∩ F_a, where F_a is the (farthest) power cell in which ball a bounds I. The
divergence theorem about centre c_a gives vol(B_a ∩ F_a) = (r_a A_a - Σ_b s_ab W_ab) / 3: A_a
is the area of sphere a on I's boundary, W_ab the planar face shared with b, and s_ab the
distance from c_a to the radical plane of a and b. A_a follows from Gauss–Bonnet on the
sphere: r² (2π - Σ exterior angles) - r Σ s_ab θ_ab (geodesic curvature of each circle arc of
angle θ_ab). The inputs are balls of a dual-complex simplex, so their spheres meet: the radical
point of each simplex has power <= 0 (Edelsbrunner, "The union of balls and its dual shape",
1995; the same cut by power cells as Edelsbrunner & Fu, 1994).

Arrays: centres (m, k, 3) float64 (k = 2, 3, 4 balls per row), radii (m, k) float64.
Returns volumes (m,) and areas (m, k): the area of sphere i inside all the other balls.
"""

from __future__ import annotations

import numpy as np

TWO_PI = 2.0 * np.pi


def _unit(v: np.ndarray) -> np.ndarray:
    """Rows of v scaled to length 1 (zero rows stay zero)."""
    norm = np.linalg.norm(v, axis=-1, keepdims=True)
    return v / np.where(norm > 0, norm, 1.0)


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.einsum("...i,...i->...", a, b)


def pair_geometry(ca, ra, cb, rb):
    """(d, u, s, rho2, m): distance, unit axis a->b, distance c_a -> radical plane along u,
    squared radius of the circle where the spheres meet (>= 0), and that circle's centre."""
    u = cb - ca
    d = np.linalg.norm(u, axis=-1)
    u = u / d[..., None]
    s = (d * d + ra * ra - rb * rb) / (2.0 * d)
    rho2 = np.maximum(ra * ra - s * s, 0.0)
    return d, u, s, rho2, ca + s[..., None] * u


def radical_point(c: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(z, t): the point of equal power in the affine hull of 2-4 centres, and sqrt(-power).

    c (m, k, 3), r (m, k). Solved relative to the first centre (normal equations in the
    hull's own basis), so the coordinates' magnitude costs no digits.
    """
    p = c[:, 1:] - c[:, :1]  # (m, k-1, 3)
    g = 0.5 * (_dot(p, p) - r[:, 1:] ** 2 + r[:, :1] ** 2)  # (m, k-1)
    gram = np.einsum("mij,mkj->mik", p, p)
    coef = np.linalg.solve(gram, g[..., None])[..., 0]
    y = np.einsum("mi,mij->mj", coef, p)
    t2 = r[:, 0] ** 2 - _dot(y, y)
    return c[:, 0] + y, np.sqrt(np.maximum(t2, 0.0))


def _exterior_angle(corner, ca, ra, ub, uc):
    """Angle between the inward conormals, on sphere a at `corner`, of the caps toward b, c."""
    e = (corner - ca) / ra[..., None]
    nb = ub - _dot(ub, e)[..., None] * e
    nc = uc - _dot(uc, e)[..., None] * e
    return np.arctan2(np.linalg.norm(np.cross(nb, nc), axis=-1), _dot(nb, nc))


def two_balls(c: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Lens volume (m,) and the cap areas (m, 2) of each sphere inside the other ball."""
    d, _, s, rho2, _ = pair_geometry(c[:, 0], r[:, 0], c[:, 1], r[:, 1])
    caps = TWO_PI * r * (r - np.stack((s, d - s), axis=1))
    volume = (_dot(r, caps) - d * np.pi * rho2) / 3.0
    return volume, caps


TRIANGLE_PAIRS = ((0, 1, 2), (1, 2, 0), (0, 2, 1))  # (a, b, third)


def three_balls(c: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Volume (m,) of three balls' intersection and each sphere's area inside the other two."""
    z, t = radical_point(c, r)
    normal = _unit(np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0]))
    corner = z + t[:, None] * normal
    arc, s_from, units = {}, {}, {}
    volume = np.zeros(len(c))
    for a, b, o in TRIANGLE_PAIRS:
        d, u, s, rho2, m = pair_geometry(c[:, a], r[:, a], c[:, b], r[:, b])
        w = c[:, o] - c[:, a]
        w = _unit(w - _dot(w, u)[:, None] * u)
        e = _dot(z - m, w)
        theta = 2.0 * np.arctan2(t, e)  # arc of circle ab inside ball o
        volume -= d * (0.5 * rho2 * theta - e * t)  # d * (segment of the disk inside ball o)
        arc[a, b] = arc[b, a] = theta
        s_from[a, b], s_from[b, a] = s, d - s
        units[a, b], units[b, a] = u, -u
    areas = np.empty_like(r)
    for a, b, o in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
        ext = _exterior_angle(corner, c[:, a], r[:, a], units[a, b], units[a, o])
        geodesic = s_from[a, b] * arc[a, b] + s_from[a, o] * arc[a, o]
        areas[:, a] = r[:, a] ** 2 * (TWO_PI - 2.0 * ext) - r[:, a] * geodesic
    volume += _dot(r, areas)
    return volume / 3.0, areas


TETRA_FACES = ((1, 2, 3, 0), (0, 2, 3, 1), (0, 1, 3, 2), (0, 1, 2, 3))  # (x, y, z, opposite)
TETRA_PAIRS = ((0, 1, 2, 3), (0, 2, 1, 3), (0, 3, 1, 2), (1, 2, 0, 3), (1, 3, 0, 2),
               (2, 3, 0, 1))  # (a, b, p, q)


def _face_corners(c: np.ndarray, r: np.ndarray) -> dict:
    """For each face of each tetrahedron, the point where its three spheres meet on the side
    of the opposite centre, keyed by the face's sorted vertex triple."""
    corners = {}
    for x, y, w, o in TETRA_FACES:
        idx = [x, y, w]
        z, t = radical_point(c[:, idx], r[:, idx])
        normal = _unit(np.cross(c[:, y] - c[:, x], c[:, w] - c[:, x]))
        normal *= np.sign(_dot(normal, c[:, o] - c[:, x]))[:, None]
        corners[frozenset(idx)] = z + t[:, None] * normal
    return corners


def four_balls(c: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Volume (m,) of four balls' intersection and each sphere's area inside the other three."""
    z, _ = radical_point(c, r)
    corners = _face_corners(c, r)
    arc, s_from, units = {}, {}, {}
    volume = np.zeros(len(c))
    for a, b, p, q in TETRA_PAIRS:
        d, u, s, rho2, m = pair_geometry(c[:, a], r[:, a], c[:, b], r[:, b])
        # The face of planes a|b is the disk ab cut by a wedge with apex z whose rays end at
        # the corners abp and abq; order them counter-clockwise about u.
        first, second = corners[frozenset((a, b, p))], corners[frozenset((a, b, q))]
        ccw = _dot(np.cross(first - z, second - z), u) >= 0
        p1 = np.where(ccw[:, None], first, second)
        p2 = np.where(ccw[:, None], second, first)
        theta = np.arctan2(_dot(np.cross(p1 - m, p2 - m), u), _dot(p1 - m, p2 - m))
        theta = np.mod(theta, TWO_PI)
        face = 0.5 * (rho2 * theta + _dot(np.cross(m - z, p2 - p1), u))
        volume -= d * face
        arc[a, b] = arc[b, a] = theta
        s_from[a, b], s_from[b, a] = s, d - s
        units[a, b], units[b, a] = u, -u
    areas = np.empty_like(r)
    for a in range(4):
        others = [b for b in range(4) if b != a]
        ext = sum(_exterior_angle(corners[frozenset((a, b, o))], c[:, a], r[:, a],
                                  units[a, b], units[a, o])
                  for b, o in ((others[0], others[1]), (others[0], others[2]),
                               (others[1], others[2])))
        geodesic = sum(s_from[a, b] * arc[a, b] for b in others)
        areas[:, a] = r[:, a] ** 2 * (TWO_PI - ext) - r[:, a] * geodesic
    volume += _dot(r, areas)
    return volume / 3.0, areas

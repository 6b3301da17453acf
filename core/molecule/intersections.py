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
Inside, vectors are component-major (3, m) arrays: each arithmetic pass is contiguous.
"""

from __future__ import annotations

import numpy as np

TWO_PI = 2.0 * np.pi


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(m,) dot products of (3, m) vectors."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(3, m) cross products of (3, m) vectors."""
    return np.stack((a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                     a[0] * b[1] - a[1] * b[0]))


def _norm(v: np.ndarray) -> np.ndarray:
    return np.sqrt(_dot(v, v))


def _unit(v: np.ndarray) -> np.ndarray:
    """(3, m) vectors scaled to length 1 (zero vectors stay zero)."""
    norm = _norm(v)
    return v / np.where(norm > 0, norm, 1.0)


def _split(c: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(k, 3, m) centres and (k, m) radii from (m, k, 3) and (m, k)."""
    return np.ascontiguousarray(np.transpose(c, (1, 2, 0))), np.ascontiguousarray(r.T)


def pair_geometry(ca, ra, cb, rb):
    """(d, u, s, rho2, m): distance, unit axis a->b, distance c_a -> radical plane along u,
    squared radius of the circle where the spheres meet (>= 0), and that circle's centre."""
    u = cb - ca
    d = _norm(u)
    u = u / d
    s = (d * d + ra * ra - rb * rb) / (2.0 * d)
    rho2 = np.maximum(ra * ra - s * s, 0.0)
    return d, u, s, rho2, ca + s * u


def _radical(c: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """radical_point on (k, 3, m) centres and (k, m) radii; returns (3, m) and (m,)."""
    p = c[1:] - c[:1]  # (k-1, 3, m)
    g = [0.5 * (_dot(q, q) - r[i + 1] ** 2 + r[0] ** 2) for i, q in enumerate(p)]
    if len(p) == 1:
        y = g[0] / _dot(p[0], p[0]) * p[0]
    elif len(p) == 2:
        a, b, d = _dot(p[0], p[0]), _dot(p[0], p[1]), _dot(p[1], p[1])
        det = a * d - b * b
        y = (g[0] * d - g[1] * b) / det * p[0] + (a * g[1] - b * g[0]) / det * p[1]
    else:
        c12, c20, c01 = _cross(p[1], p[2]), _cross(p[2], p[0]), _cross(p[0], p[1])
        y = (g[0] * c12 + g[1] * c20 + g[2] * c01) / _dot(p[0], c12)
    return c[0] + y, np.sqrt(np.maximum(r[0] ** 2 - _dot(y, y), 0.0))


def radical_point(c: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(z (m, 3), t (m,)): the point of equal power in the affine hull of 2-4 centres
    (c (m, k, 3), r (m, k)), and sqrt(-power). Closed form (Cramer's rule in the hull's own
    basis) relative to the first centre, so the coordinates' magnitude costs no digits."""
    z, t = _radical(*_split(np.asarray(c, np.float64), np.asarray(r, np.float64)))
    return z.T, t


def _exterior_angle(corner, ca, ra, ub, uc):
    """Angle between the inward conormals, on sphere a at `corner`, of the caps toward b, c."""
    e = (corner - ca) / ra
    nb = ub - _dot(ub, e) * e
    nc = uc - _dot(uc, e) * e
    return np.arctan2(_norm(_cross(nb, nc)), _dot(nb, nc))


def two_balls(c: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Lens volume (m,) and the cap areas (m, 2) of each sphere inside the other ball."""
    volume, areas = _two_planes(*_split(c, r))
    return volume, areas.T


def _two_planes(c: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """two_balls on (k, 3, m) centres and (k, m) radii; areas (k, m)."""
    d, _, s, rho2, _ = pair_geometry(c[0], r[0], c[1], r[1])
    caps = TWO_PI * r * (r - np.stack((s, d - s)))
    volume = (r[0] * caps[0] + r[1] * caps[1] - d * np.pi * rho2) / 3.0
    return volume, caps


TRIANGLE_PAIRS = ((0, 1, 2), (1, 2, 0), (0, 2, 1))  # (a, b, third)


def three_balls(c: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Volume (m,) of three balls' intersection and each sphere's area inside the other two."""
    volume, areas = _three_planes(*_split(c, r))
    return volume, areas.T


def _three_planes(c: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """three_balls on (k, 3, m) centres and (k, m) radii; areas (k, m)."""
    z, t = _radical(c, r)
    corner = z + t * _unit(_cross(c[1] - c[0], c[2] - c[0]))
    arc, s_from, units = {}, {}, {}
    volume = np.zeros(r.shape[1])
    for a, b, o in TRIANGLE_PAIRS:
        d, u, s, rho2, m = pair_geometry(c[a], r[a], c[b], r[b])
        w = c[o] - c[a]
        w = _unit(w - _dot(w, u) * u)
        e = _dot(z - m, w)
        theta = 2.0 * np.arctan2(t, e)  # arc of circle ab inside ball o
        volume -= d * (0.5 * rho2 * theta - e * t)  # d * (segment of the disk inside ball o)
        arc[a, b] = arc[b, a] = theta
        s_from[a, b], s_from[b, a] = s, d - s
        units[a, b], units[b, a] = u, -u
    areas = np.empty_like(r)
    for a, b, o in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
        ext = _exterior_angle(corner, c[a], r[a], units[a, b], units[a, o])
        geodesic = s_from[a, b] * arc[a, b] + s_from[a, o] * arc[a, o]
        areas[a] = r[a] ** 2 * (TWO_PI - 2.0 * ext) - r[a] * geodesic
        volume += r[a] * areas[a]
    return volume / 3.0, areas


TETRA_FACES = ((1, 2, 3, 0), (0, 2, 3, 1), (0, 1, 3, 2), (0, 1, 2, 3))  # (x, y, z, opposite)
TETRA_PAIRS = ((0, 1, 2, 3), (0, 2, 1, 3), (0, 3, 1, 2), (1, 2, 0, 3), (1, 3, 0, 2),
               (2, 3, 0, 1))  # (a, b, p, q)


def _face_corners(c: np.ndarray, r: np.ndarray) -> dict:
    """For each face of each tetrahedron, the point where its three spheres meet on the side
    of the opposite centre, keyed by the face's vertex set."""
    corners = {}
    for x, y, w, o in TETRA_FACES:
        idx = [x, y, w]
        z, t = _radical(c[idx], r[idx])
        normal = _unit(_cross(c[y] - c[x], c[w] - c[x]))
        normal *= np.sign(_dot(normal, c[o] - c[x]))
        corners[frozenset(idx)] = z + t * normal
    return corners


def four_balls(c: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Volume (m,) of four balls' intersection and each sphere's area inside the other three."""
    volume, areas = _four_planes(*_split(c, r))
    return volume, areas.T


def _four_planes(c: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """four_balls on (k, 3, m) centres and (k, m) radii; areas (k, m)."""
    z, _ = _radical(c, r)
    corners = _face_corners(c, r)
    arc, s_from, units = {}, {}, {}
    volume = np.zeros(r.shape[1])
    for a, b, p, q in TETRA_PAIRS:
        d, u, s, rho2, m = pair_geometry(c[a], r[a], c[b], r[b])
        # The face of planes a|b is the disk ab cut by a wedge with apex z whose rays end at
        # the corners abp and abq; order them counter-clockwise about u.
        first, second = corners[frozenset((a, b, p))], corners[frozenset((a, b, q))]
        ccw = _dot(_cross(first - z, second - z), u) >= 0
        p1, p2 = np.where(ccw, first, second), np.where(ccw, second, first)
        theta = np.mod(np.arctan2(_dot(_cross(p1 - m, p2 - m), u), _dot(p1 - m, p2 - m)),
                       TWO_PI)
        volume -= d * 0.5 * (rho2 * theta + _dot(_cross(m - z, p2 - p1), u))
        arc[a, b] = arc[b, a] = theta
        s_from[a, b], s_from[b, a] = s, d - s
        units[a, b], units[b, a] = u, -u
    areas = np.empty_like(r)
    for a in range(4):
        o = [b for b in range(4) if b != a]
        ext = sum(_exterior_angle(corners[frozenset((a, b, e))], c[a], r[a],
                                  units[a, b], units[a, e])
                  for b, e in ((o[0], o[1]), (o[0], o[2]), (o[1], o[2])))
        geodesic = sum(s_from[a, b] * arc[a, b] for b in o)
        areas[a] = r[a] ** 2 * (TWO_PI - ext) - r[a] * geodesic
        volume += r[a] * areas[a]
    return volume / 3.0, areas


PLANES = {2: _two_planes, 3: _three_planes, 4: _four_planes}


def ball_terms(c: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """two_balls, three_balls or four_balls (by k) on centres already component-major,
    (k, 3, m), and (k, m) radii: volumes (m,) and areas (k, m), no transposed copies."""
    return PLANES[len(r)](c, r)

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
    out = a[0] * b[0]
    out += a[1] * b[1]
    out += a[2] * b[2]
    return out


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(3, m) cross products of (3, m) vectors (written in place: no stacked copy)."""
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    for i, (j, k) in enumerate(((1, 2), (2, 0), (0, 1))):
        np.multiply(a[j], b[k], out=out[i])
        out[i] -= a[k] * b[j]
    return out


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


def _meeting(cx, cy, cw, rx, ry, rw):
    """Where three balls' spheres meet: the radical point z (3, m) of the three, t (m,) the
    distance from z to either meeting point, n = (cy - cx) x (cw - cx) (3, m), |n| (m,) (twice
    the triangle's area), and the dot products of the two edge vectors at x, at y and at w."""
    p, q = cy - cx, cw - cx
    pp, pq, qq = _dot(p, p), _dot(p, q), _dot(q, q)
    g0 = 0.5 * (pp - ry * ry + rx * rx)
    g1 = 0.5 * (qq - rw * rw + rx * rx)
    det = pp * qq - pq * pq
    y = (g0 * qq - g1 * pq) / det * p + (pp * g1 - pq * g0) / det * q
    t = np.sqrt(np.maximum(rx * rx - _dot(y, y), 0.0))
    n = _cross(p, q)
    return cx + y, t, n, _norm(n), (pq, pp - pq, qq - pq)


def _corner_angle(area_t, ra, dot_a, h_ab, h_ae):
    """Exterior angle, on sphere a at a point where it meets spheres b and e, between the
    inward conormals of its caps toward b and e. With e = (corner - c_a) / r_a and the unit
    axes u_b, u_e: atan2(|e . (u_b x u_e)|, u_b . u_e - (u_b . e)(u_e . e)); the corner lies
    on both radical planes (u_b . e = s_ab / r_a) and t from the centres' plane, so scaled
    by r_a² d_ab d_ae that is atan2(2 A t r_a, r_a² (v_ab . v_ae) - h_ab h_ae), with
    `area_t` = 2 A t (A the area of the centres' triangle), `dot_a` = v_ab . v_ae (the edge
    vectors from c_a) and h_ab = s_ab d_ab = (d_ab² + r_a² - r_b²) / 2."""
    return np.arctan2(area_t * ra, ra * ra * dot_a - h_ab * h_ae)


def _pair(ca, ra, cb, rb):
    """pair_geometry, and h = s d and d² - h (s d from each end: _corner_angle's h)."""
    u = cb - ca
    d2 = _dot(u, u)
    d = np.sqrt(d2)
    u = u / d
    ra2, rb2 = ra * ra, rb * rb
    h = 0.5 * (d2 + ra2 - rb2)
    s = h / d
    rho2 = np.maximum(ra2 - s * s, 0.0)
    return d, u, s, rho2, ca + s * u, (h, 0.5 * (d2 + rb2 - ra2))


def three_balls(c: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Volume (m,) of three balls' intersection and each sphere's area inside the other two."""
    volume, areas = _three_planes(*_split(c, r))
    return volume, areas.T


def _three_planes(c: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """three_balls on (k, 3, m) centres and (k, m) radii; areas (k, m)."""
    z, t, _, area2, dots = _meeting(c[0], c[1], c[2], r[0], r[1], r[2])
    height = t / np.where(area2 > 0, area2, 1.0)  # t / (2 A)
    arc, s_from, h = {}, {}, {}
    volume = np.zeros(r.shape[1])
    for a, b, o in TRIANGLE_PAIRS:
        d, _, s, rho2, m, (h_ab, h_ba) = _pair(c[a], r[a], c[b], r[b])
        # signed distance from the circle's centre m to z, toward ball o: (z - m) is normal
        # to the axis, and c_o's distance from the axis is 2 A / d
        e = _dot(z - m, c[o] - c[a]) * d
        theta = 2.0 * np.arctan2(t * area2, e)  # arc of circle ab inside ball o
        volume -= d * (0.5 * rho2 * theta - e * height)  # d * (segment of the disk inside o)
        arc[a, b] = arc[b, a] = theta
        s_from[a, b], s_from[b, a] = s, d - s
        h[a, b], h[b, a] = h_ab, h_ba
    areas = np.empty_like(r)
    area_t = area2 * t
    for a, b, o in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
        ext = _corner_angle(area_t, r[a], dots[a], h[a, b], h[a, o])
        geodesic = s_from[a, b] * arc[a, b] + s_from[a, o] * arc[a, o]
        areas[a] = r[a] ** 2 * (TWO_PI - 2.0 * ext) - r[a] * geodesic
        volume += r[a] * areas[a]
    return volume / 3.0, areas


TETRA_FACES = ((1, 2, 3, 0), (0, 2, 3, 1), (0, 1, 3, 2), (0, 1, 2, 3))  # (x, y, z, opposite)
TETRA_PAIRS = ((0, 1, 2, 3), (0, 2, 1, 3), (0, 3, 1, 2), (1, 2, 0, 3), (1, 3, 0, 2),
               (2, 3, 0, 1))  # (a, b, p, q)


def _face_corners(c: np.ndarray, r: np.ndarray) -> dict:
    """For each face (x, y, w) (ascending) of each tetrahedron: the point where its three
    spheres meet on the side of the opposite centre, 2 A t (_corner_angle's area_t) and the
    edge vectors' dot products at its vertices ({x: ., y: ., w: .})."""
    faces = {}
    for x, y, w, o in TETRA_FACES:
        z, t, n, area2, dots = _meeting(c[x], c[y], c[w], r[x], r[y], r[w])
        side = np.sign(_dot(n, c[o] - c[x]))
        corner = z + (t * side / np.where(area2 > 0, area2, 1.0)) * n
        faces[x, y, w] = corner, area2 * t, dict(zip((x, y, w), dots, strict=True))
    return faces


def four_balls(c: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Volume (m,) of four balls' intersection and each sphere's area inside the other three."""
    volume, areas = _four_planes(*_split(c, r))
    return volume, areas.T


def _four_planes(c: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """four_balls on (k, 3, m) centres and (k, m) radii; areas (k, m)."""
    z, _ = _radical(c, r)
    faces = _face_corners(c, r)
    arc, s_from, h = {}, {}, {}
    volume = np.zeros(r.shape[1])
    for a, b, p, q in TETRA_PAIRS:
        d, u, s, rho2, m, (h_ab, h_ba) = _pair(c[a], r[a], c[b], r[b])
        # The face of planes a|b is the disk ab cut by a wedge with apex z whose rays end at
        # the corners abp and abq, taken counter-clockwise about u: with f, g those corners
        # seen from m, the order is counter-clockwise when [f - (z - m), g - (z - m), u] =
        # [f, g, u] + [m - z, g - f, u] >= 0, else f and g swap (both products change sign).
        f = faces[tuple(sorted((a, b, p)))][0] - m
        g = faces[tuple(sorted((a, b, q)))][0] - m
        turn = _dot(_cross(f, g), u)
        wedge = _dot(_cross(m - z, g - f), u)
        sign = np.where(turn + wedge >= 0, 1.0, -1.0)
        theta = np.mod(np.arctan2(sign * turn, _dot(f, g)), TWO_PI)
        volume -= d * 0.5 * (rho2 * theta + sign * wedge)
        arc[a, b] = arc[b, a] = theta
        s_from[a, b], s_from[b, a] = s, d - s
        h[a, b], h[b, a] = h_ab, h_ba
    areas = np.empty_like(r)
    for a in range(4):
        o = [b for b in range(4) if b != a]
        ext = 0.0
        for b, e in ((o[0], o[1]), (o[0], o[2]), (o[1], o[2])):
            _, area_t, dots = faces[tuple(sorted((a, b, e)))]
            ext = ext + _corner_angle(area_t, r[a], dots[a], h[a, b], h[a, e])
        geodesic = sum(s_from[a, b] * arc[a, b] for b in o)
        areas[a] = r[a] ** 2 * (TWO_PI - ext) - r[a] * geodesic
        volume += r[a] * areas[a]
    return volume / 3.0, areas


PLANES = {2: _two_planes, 3: _three_planes, 4: _four_planes}


def ball_terms(c: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """two_balls, three_balls or four_balls (by k) on centres already component-major,
    (k, 3, m), and (k, m) radii: volumes (m,) and areas (k, m), no transposed copies."""
    return PLANES[len(r)](c, r)

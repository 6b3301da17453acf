"""Exact volume of a ball and area of its sphere inside a convex polyhedron (an intersection
of halfspaces), in closed form, vectorized.

With the ball's centre O as origin and each halfspace N·x <= β (N unit), the polyhedron Q is
the signed sum of the pyramids from O over its faces, sign β_f, and each face is the signed
fan of triangles (p, a, b) over its directed edges from the foot p = β_f N_f of O on its
plane. A triangle (p, a, b) is the difference of two right triangles at q, the foot of p on
the line ab. Over a right triangle with legs d = |pq| and t (along the edge), angle
Θ = atan(t/d) at p, a plane at distance h from O and ρ² = r² - h², in polar angle θ about p:

    solid angle of the cone from O     Ω = Θ - asin(k sin Θ),          k = h / sqrt(h² + d²)
    sphere area beyond the plane in it  A = r² (θ₁ - asin(k sin θ₁)) + r (r - h) (Θ - θ₁)
    plane area within ρ of p            P = (d² tan θ₁ + ρ² (Θ - θ₁)) / 2

with θ₁ = min(Θ, acos(d/ρ)) (the edge runs inside the disk of radius ρ up to θ₁). The sphere
inside Q has area Σ sign·(r² Ω - A); the divergence theorem about O gives the ball's volume
inside Q, (r · sphere area + Σ_f β_f · area of face f inside the ball) / 3.
"""

from __future__ import annotations

import numpy as np


def _right(h, d, t, r):
    """(Ω, A, P) of right triangles (legs d >= 0 and t, odd in t), all arrays broadcast."""
    at = np.abs(t)
    theta = np.arctan2(at, d)
    rho2 = np.maximum(r * r - h * h, 0.0)
    reach = np.sqrt(np.maximum(rho2 - d * d, 0.0))
    run = np.minimum(at, reach)
    theta1 = np.arctan2(run, d)
    hd = np.hypot(h, d)
    k = np.where(hd > 0, h / np.where(hd > 0, hd, 1.0), 0.0)
    omega = theta - np.arcsin(np.clip(k * np.sin(theta), -1.0, 1.0))
    area = (r * r * (theta1 - np.arcsin(np.clip(k * np.sin(theta1), -1.0, 1.0)))
            + r * np.maximum(r - h, 0.0) * (theta - theta1))
    plane = 0.5 * (d * run + rho2 * (theta - theta1))
    s = np.sign(t)
    return s * omega, s * area, s * plane


def _cross(a, b):
    return np.stack((a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1],
                     a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2],
                     a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]), -1)


def _dot(a, b):
    """a·b over the last axis (3), written out: a sum over a last axis of 3 is several
    times slower in numpy."""
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1] + a[..., 2] * b[..., 2]


def _edge_terms(a, b, normal, offset, rr):
    """(sphere area, plane term) of the directed edges a -> b (e, 3) on faces (normal,
    offset) (e, 3), (e,), balls rr (e,): each the fan triangle from the face's foot point."""
    p = offset[..., None] * normal
    span = b - a
    length = np.sqrt(_dot(span, span))
    u = span / np.where(length > 0, length, 1.0)[..., None]
    ta, tb = _dot(a - p, u), _dot(b - p, u)
    foot = a - ta[..., None] * u
    d = np.sqrt(_dot(foot - p, foot - p))
    orient = np.sign(_dot(normal, _cross(a - p, b - p)))
    h = np.abs(offset)
    oa, aa, pa = _right(h, d, ta, rr)
    ob, ab, pb = _right(h, d, tb, rr)
    return (np.sign(offset) * orient * (rr * rr * (ob - oa) - (ab - aa)),
            offset * orient * (pb - pa))


def _clip_lines(normals, offsets, direction, x0, f, g):
    """((m, E) lower, upper) the part of each line x0 + s·direction (m, E, 3) inside every
    halfspace but its own two (planes f, g (E,)): lower <= s <= upper; upper is -inf where
    a plane parallel to the line leaves it outside. One plane at a time: (m, E) arrays stay
    in cache, where (m, P, E) ones did not (and numpy reduces a short axis slowly)."""
    m, edges = direction.shape[:2]
    lower, upper = np.full((m, edges), -np.inf), np.full((m, edges), np.inf)
    d = [np.ascontiguousarray(direction[..., c]) for c in range(3)]
    x = [np.ascontiguousarray(x0[..., c]) for c in range(3)]
    for p in range(offsets.shape[1]):
        n = [normals[:, p, c, None] for c in range(3)]
        slope = d[0] * n[0] + d[1] * n[1] + d[2] * n[2]
        room = offsets[:, p, None] - (x[0] * n[0] + x[1] * n[1] + x[2] * n[2])
        slope[:, (f == p) | (g == p)] = np.nan  # the line's own planes bound nothing
        with np.errstate(divide="ignore", invalid="ignore"):
            bound = room / slope
        np.minimum(upper, bound, out=upper, where=slope > 0)
        np.maximum(lower, bound, out=lower, where=slope < 0)
        parallel = slope == 0
        if parallel.any():
            upper[parallel & (room < 0)] = -np.inf
    return lower, upper


def ball_in_polyhedron(normals: np.ndarray, offsets: np.ndarray, r: np.ndarray
                       ) -> tuple[np.ndarray, np.ndarray]:
    """(volume (m,), sphere area (m,)) of balls of radii r (m,) centred at the origin inside
    the bounded polyhedra {x: normals[i, f]·x <= offsets[i, f] for all f}: normals (m, P, 3)
    unit, offsets (m, P). An empty polyhedron gives 0."""
    m, planes = offsets.shape
    f, g = np.triu_indices(planes, 1)  # each pair of faces: one line, an edge of both
    nf, ng = normals[:, f], normals[:, g]  # (m, E, 3)
    bf, bg = offsets[:, f], offsets[:, g]
    direction = _cross(nf, ng)
    sin2 = _dot(direction, direction)
    cos = _dot(nf, ng)
    ok = sin2 > 1e-20
    safe = np.where(ok, sin2, 1.0)
    x0 = (((bf - bg * cos) / safe)[..., None] * nf + ((bg - bf * cos) / safe)[..., None] * ng)
    lower, upper = _clip_lines(normals, offsets, direction, x0, f, g)
    ok &= (upper > lower) & np.isfinite(upper) & np.isfinite(lower)
    row, pair = np.nonzero(ok)  # the polyhedra's edges only
    direction, x0 = direction[row, pair], x0[row, pair]
    a = x0 + lower[row, pair, None] * direction
    b = x0 + upper[row, pair, None] * direction
    rr = r[row]
    # direction nf x ng leaves face f's inside on its left (seen from outside): a -> b on
    # face f, b -> a on face g
    sphere_f, plane_f = _edge_terms(a, b, nf[row, pair], bf[row, pair], rr)
    sphere_g, plane_g = _edge_terms(b, a, ng[row, pair], bg[row, pair], rr)
    sphere = np.bincount(row, weights=sphere_f + sphere_g, minlength=m)
    plane = np.bincount(row, weights=plane_f + plane_g, minlength=m)
    return (r * sphere + plane) / 3.0, sphere

"""Triangle circumradii of needles (two long sides, one very short) against exact rationals."""

from __future__ import annotations

from fractions import Fraction

import numpy as np

from core.geometry.circumspheres import facet_radii2


def exact_radius2(corners: np.ndarray) -> Fraction:
    """|a|²|b|²|c|² / (4 |a x b|²) of one triangle in rational arithmetic."""
    p = [[Fraction(float(x)) for x in row] for row in corners]
    a, b, c = ([q[k] - o[k] for k in range(3)] for o, q in ((p[0], p[1]), (p[0], p[2]),
                                                             (p[1], p[2])))
    cross = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]

    def dot(u, v):
        return sum(x * y for x, y in zip(u, v, strict=True))
    return dot(a, a) * dot(b, b) * dot(c, c) / (4 * dot(cross, cross))


def test_needle_radii_match_exact_arithmetic() -> None:
    """Any vertex may come first: the short side must not be |a|² + |b|² - 2 a.b."""
    rng = np.random.default_rng(3)
    n = 300
    base = rng.normal(size=(n, 3)) * 50
    far = base + rng.normal(size=(n, 3)) * 30
    near = base + rng.normal(size=(n, 3)) * 10.0 ** rng.uniform(-9, -2, (n, 1))
    points = np.concatenate([far, base, near])
    tris = np.arange(3 * n).reshape(3, n).T  # the far vertex first: the worst order
    radius2, _ = facet_radii2(points, tris)
    errors = [abs(float((Fraction(float(r)) - exact) / exact)) for r, exact in
              zip(radius2, (exact_radius2(points[t]) for t in tris), strict=True)]
    assert max(errors) < 1e-12

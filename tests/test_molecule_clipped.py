"""A ball and its sphere inside a convex polyhedron (core.molecule.clipped): known answers
(a cube's corner, edge and face, a cap, the lens of two balls split at their radical plane)
and random polyhedra against 10^6 uniform samples."""

from __future__ import annotations

import numpy as np
import pytest

from core.molecule.clipped import ball_in_polyhedron
from core.molecule.intersections import two_balls

AXES = np.array([[1.0, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]])


def _box(low, high) -> tuple[np.ndarray, np.ndarray]:
    """Halfspaces (6, 3), (6,) of the box low <= x <= high (relative to the ball's centre)."""
    low, high = np.asarray(low, float), np.asarray(high, float)
    return AXES, np.array([high[0], -low[0], high[1], -low[1], high[2], -low[2]])


@pytest.mark.parametrize(("low", "fraction"), [
    ((-5, -5, -5), 1.0),  # the whole ball
    ((0, 0, 0), 1 / 8),  # centre at a corner
    ((0, 0, -5), 1 / 4),  # on an edge
    ((0, -5, -5), 1 / 2),  # on a face
])
def test_ball_at_a_box_corner_edge_face(low, fraction):
    r = 2.0
    normals, offsets = _box(low, (5, 5, 5))
    volume, area = ball_in_polyhedron(normals[None], offsets[None], np.array([r]))
    assert volume[0] == pytest.approx(fraction * 4 / 3 * np.pi * r ** 3, rel=1e-12)
    assert area[0] == pytest.approx(fraction * 4 * np.pi * r ** 2, rel=1e-12)


def test_ball_less_a_cap_and_an_empty_box():
    r, h = 2.0, 0.7  # one face 0.7 from the centre: the ball less a cap of height r - h
    normals, offsets = _box((-5, -5, -5), (h, 5, 5))
    cap = r - h
    volume, area = ball_in_polyhedron(normals[None], offsets[None], np.array([r]))
    assert volume[0] == pytest.approx(4 / 3 * np.pi * r ** 3 - np.pi * cap ** 2 * (3 * r - cap) / 3,
                                      rel=1e-12)
    assert area[0] == pytest.approx(4 * np.pi * r ** 2 - 2 * np.pi * r * cap, rel=1e-12)
    normals, offsets = _box((3, 3, 3), (5, 5, 5))  # beyond the ball
    assert np.allclose(ball_in_polyhedron(normals[None], offsets[None], np.array([r])), 0)


def test_lens_is_two_balls_each_beyond_the_radical_plane():
    """Each ball's part beyond the radical plane (toward the other) sums to the lens."""
    ra, rb, d = 2.0, 1.5, 2.5
    s = (d * d + ra * ra - rb * rb) / (2 * d)  # centre a to the radical plane
    normals, offsets = _box((-9, -9, -9), (9, 9, 9))
    normals = np.vstack([normals, [-1.0, 0, 0]])
    va, aa = ball_in_polyhedron(normals[None], np.append(offsets, -s)[None], np.array([ra]))
    vb, ab = ball_in_polyhedron(normals[None], np.append(offsets, -(d - s))[None],
                                np.array([rb]))
    lens, caps = two_balls(np.array([[[0.0, 0, 0], [d, 0, 0]]]), np.array([[ra, rb]]))
    assert va[0] + vb[0] == pytest.approx(lens[0], rel=1e-12)
    assert (aa[0], ab[0]) == pytest.approx(tuple(caps[0]), rel=1e-12)


def test_random_polyhedra_against_sampling():
    """A tetrahedron cut by up to three more planes, the ball's centre inside or outside it:
    volume and sphere area against 10^6 samples of the ball and of its sphere (4 sigma)."""
    rng = np.random.default_rng(11)
    n = 1_000_000
    for trial in range(6):
        corners = rng.uniform(-3, 3, (4, 3))
        normals, offsets = [], []
        for v in range(4):
            i, j, k = (w for w in range(4) if w != v)
            u = np.cross(corners[j] - corners[i], corners[k] - corners[i])
            u /= np.linalg.norm(u)
            u = -u if u @ (corners[v] - corners[i]) > 0 else u
            normals.append(u)
            offsets.append(u @ corners[i])
        for _ in range(trial % 4):
            u = rng.normal(size=3)
            u /= np.linalg.norm(u)
            normals.append(u)
            offsets.append(u @ corners.mean(0) + rng.uniform(-0.5, 0.5))
        normals, offsets = np.array(normals), np.array(offsets)
        centre = corners.mean(0) + rng.uniform(-1.5, 1.5, 3)
        r = rng.uniform(1.0, 3.0)
        volume, area = ball_in_polyhedron(normals[None], (offsets - normals @ centre)[None],
                                          np.array([r]))
        u = rng.normal(size=(n, 3))
        u /= np.linalg.norm(u, axis=1, keepdims=True)
        x = centre + r * rng.uniform(size=(n, 1)) ** (1 / 3) * u
        p = (x @ normals.T <= offsets).all(1).mean()
        ball = 4 / 3 * np.pi * r ** 3
        assert abs(volume[0] - p * ball) <= 4 * ball * np.sqrt(p * (1 - p) / n) + 1e-12
        q = ((centre + r * u) @ normals.T <= offsets).all(1).mean()
        sphere = 4 * np.pi * r ** 2
        assert abs(area[0] - q * sphere) <= 4 * sphere * np.sqrt(q * (1 - q) / n) + 1e-12


def test_the_least_of_a_direction_over_a_cap_against_its_points():
    """exact_cells.cap_low (what decides that a power plane's cap lies beyond a facet, so
    the plane is left out of the clipping) is the least of n'·x over the cap's points: over
    the cap's disk, or at the sphere's point opposite n' when that point is in the cap."""
    from core.molecule.exact_cells import cap_low

    rng = np.random.default_rng(7)
    x = rng.normal(size=(200_000, 3))
    x *= (rng.uniform(size=len(x)) ** (1 / 3) / np.linalg.norm(x, axis=1))[:, None]
    n = np.array([0.0, 0.0, 1.0])
    for bound in (-0.6, -0.1, 0.0, 0.3, 0.8):
        cap = x[x @ n >= bound]
        for cos in (-1.0, -0.9, -0.5, 0.0, 0.4, 1.0):
            other = np.array([np.sqrt(1 - cos * cos), 0.0, cos])
            low = float(cap_low(np.array(bound), np.array(1.0), np.array(cos)))
            sampled = float((cap @ other).min())
            assert low <= sampled + 1e-12, (bound, cos)
            assert sampled - low < 0.05, (bound, cos)  # reached by the samples nearly

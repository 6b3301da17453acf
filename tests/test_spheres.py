"""core.query.spheres against brute force: a simplex's spoon passes through its vertices, has its
enter alpha as radius and holds no point; find_simplex inverts simplices(k)."""

from __future__ import annotations

import numpy as np
import pytest

from core import AlphaComplex, InputError
from core.query.spheres import find_simplex, simplex_sphere, spoon_simplex


@pytest.fixture(scope="module", params=[2, 3], ids=["2d", "3d"])
def complex_(request) -> AlphaComplex:
    """Random points with clusters (so plenty of attached simplices)."""
    rng = np.random.default_rng(request.param)
    points = np.concatenate([rng.normal(size=(150, request.param)),
                             0.1 * rng.normal(size=(60, request.param)) + 2.0])
    return AlphaComplex.from_points(points)


def sample_rows(ac, k: int, count: int = 60) -> np.ndarray:
    """A spread of rows of simplices(k), first and last included."""
    return np.unique(np.linspace(0, len(ac.simplices(k)) - 1, count).astype(int))


def test_spoon_is_an_empty_sphere_through_the_vertices_of_radius_enter(complex_) -> None:
    """Brute force over all points: on the sphere are the vertices, inside it nothing."""
    ac = complex_
    tol = 1e-9
    for k in range(1, ac.dim + 1):
        for row in sample_rows(ac, k):
            centre, radius = simplex_sphere(ac, k, row)
            enter = ac.intervals(k)[row, 0]
            assert radius == pytest.approx(enter, rel=1e-9)
            dist = np.linalg.norm(ac.points - centre, axis=1)
            np.testing.assert_allclose(dist[ac.simplices(k)[row]], radius, rtol=1e-9)
            assert dist.min() >= radius * (1 - tol)


def test_attached_simplices_take_their_cofaces_spoon(complex_) -> None:
    """Attached simplices (enter > own circumradius) exist here and are handed a coface."""
    ac = complex_
    k = ac.dim - 1
    moved = [row for row in sample_rows(ac, k, 400) if spoon_simplex(ac, k, row)[0] > k]
    assert moved
    for row in moved[:20]:
        k2, row2 = spoon_simplex(ac, k, row)
        assert set(ac.simplices(k)[row]) <= set(ac.simplices(k2)[row2])
        assert ac.intervals(k2)[row2, 0] == ac.intervals(k)[row, 0]


def test_vertex_spoon_is_the_point(complex_) -> None:
    """A vertex enters at 0: its spoon is the point itself."""
    centre, radius = simplex_sphere(complex_, 0, 5)
    np.testing.assert_array_equal(centre, complex_.points[complex_.simplices(0)[5, 0]])
    assert radius == 0.0


def test_find_simplex_inverts_the_table(complex_) -> None:
    """Vertices in any order give back (k, row); unknown or malformed ones are InputErrors."""
    ac = complex_
    rng = np.random.default_rng(0)
    for k in range(ac.dim + 1):
        for row in sample_rows(ac, k, 25):
            assert find_simplex(ac, rng.permutation(ac.simplices(k)[row])) == (k, row)
    with pytest.raises(InputError):
        find_simplex(ac, [0, 0])
    with pytest.raises(InputError):
        find_simplex(ac, list(range(ac.dim + 2)))
    with pytest.raises(InputError):
        simplex_sphere(ac, 1, len(ac.simplices(1)))
    linked = set(ac.simplices(1)[ac.simplices(1)[:, 0] == 0, 1])
    stranger = next(v for v in range(1, len(ac.points)) if v not in linked)
    with pytest.raises(InputError, match="no 1-simplex"):
        find_simplex(ac, [0, stranger])


def test_weighted_complexes_have_no_spoon() -> None:
    """A weighted simplex's ball is an orthogonal sphere: asking for its spoon is refused."""
    rng = np.random.default_rng(3)
    ac = AlphaComplex.from_points(rng.normal(size=(60, 3)), weights=rng.uniform(0, 0.05, 60))
    with pytest.raises(InputError, match="weighted"):
        simplex_sphere(ac, 1, 0)

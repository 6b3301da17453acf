"""Signature curves, optimal alpha, suggestions and point location against direct computation."""

from __future__ import annotations

import numpy as np
import pytest
from reference import data_dir, needs_data
from scipy.spatial import ConvexHull, Delaunay

from core import AlphaComplex, InputError
from core.topology.suggest import stable_ranges

DATA = data_dir()


@pytest.fixture(scope="module", params=[2, 3])
def ac(request) -> AlphaComplex:
    rng = np.random.default_rng(request.param)
    return AlphaComplex.from_points(rng.random((300, request.param)))


@pytest.fixture(scope="module")
def two_blobs() -> AlphaComplex:
    rng = np.random.default_rng(7)
    pts = np.concatenate([rng.normal(size=(120, 3)), rng.normal(size=(80, 3)) + 8.0])
    return AlphaComplex.from_points(pts)


def sample_rows(n: int, count: int = 40) -> np.ndarray:
    """About `count` spread-out row indices of an (n,) array, first and last included."""
    return np.unique(np.linspace(0, n - 1, count).astype(int))


def areas(points: np.ndarray, facets: np.ndarray) -> np.ndarray:
    """(f,) lengths of 2D edges or areas of 3D triangles, written out independently."""
    p = np.asarray(points)[np.asarray(facets)]
    if p.shape[1] == 2:
        return np.sqrt(((p[:, 1] - p[:, 0]) ** 2).sum(axis=1))
    return 0.5 * np.sqrt((np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]) ** 2).sum(axis=1))


def test_measures_equal_sums_over_the_shape(ac: AlphaComplex) -> None:
    sig = ac.signatures()
    for i in sample_rows(len(sig.alphas)):
        alpha = sig.alphas[i]
        shape = ac.shape(alpha)
        cells = ac.cell_measures()[ac.intervals(ac.dim)[:, 0] <= alpha].sum()
        assert sig.measure[i] == pytest.approx(cells, rel=1e-9, abs=1e-15)
        assert sig.measure[i] == pytest.approx(shape.measure, rel=1e-9, abs=1e-15)
        boundary = areas(ac.points, shape.regular_facets).sum()
        assert sig.boundary_measure[i] == pytest.approx(boundary, rel=1e-9, abs=1e-12)


def test_measure_at_the_end_is_the_hull(ac: AlphaComplex) -> None:
    hull = ConvexHull(ac.points)
    sig = ac.signatures()
    assert sig.measure[-1] == pytest.approx(hull.volume, rel=1e-9)
    assert sig.boundary_measure[-1] == pytest.approx(hull.area, rel=1e-9)
    assert sig.measure[0] == 0.0 and sig.boundary_measure[0] == 0.0


def test_counts_equal_classify(ac: AlphaComplex) -> None:
    sig = ac.signatures()
    rows = sample_rows(len(sig.alphas))
    for k in range(ac.dim + 1):
        counts = sig.counts(k)
        for i in rows:
            want = np.bincount(ac.classify(sig.alphas[i], k), minlength=4)
            np.testing.assert_array_equal(counts[i], want, err_msg=f"k={k} alpha={sig.alphas[i]}")
    alpha = float(np.mean(sig.alphas[rows[len(rows) // 2:][:2]]))
    want = np.stack([np.bincount(ac.classify(alpha, k), minlength=4) for k in range(ac.dim + 1)])
    np.testing.assert_array_equal(sig.counts_at(alpha), want)


def test_index_and_immutability(ac: AlphaComplex) -> None:
    sig = ac.signatures()
    assert ac.signatures() is sig
    np.testing.assert_array_equal(sig.alphas, ac.spectrum())
    assert sig.betti.shape == (len(sig.alphas), ac.dim)
    assert sig.index(-1.0) == -1
    assert sig.index(sig.alphas[5]) == 5
    assert sig.index(np.nextafter(sig.alphas[6], 0)) == 5
    for name in ("alphas", "betti", "solid_components", "measure", "boundary_measure"):
        with pytest.raises(ValueError):
            getattr(sig, name)[0] = 1
    with pytest.raises(AttributeError):
        sig.dim = 5
    pairs = ac.persistence().diagram(0)
    with pytest.raises(ValueError):
        pairs[0, 0] = 1.0
    assert ac.persistence() is ac.persistence()
    with pytest.raises(InputError):
        ac.persistence().diagram(ac.dim)


def brute_optimal(ac: AlphaComplex, n_components: int) -> float:
    """First spectrum alpha where every point lies in a cell and the cells form <= n groups."""
    from test_topology import brute_solid_components

    cells = np.asarray(ac.simplices(ac.dim))
    enter = ac.intervals(ac.dim)[:, 0]
    used = np.bincount(cells.ravel(), minlength=len(ac.points)) > 0
    for alpha in ac.spectrum():
        covered = np.bincount(cells[enter <= alpha].ravel(), minlength=len(ac.points)) > 0
        if (used & ~covered).any():
            continue
        if brute_solid_components(ac, alpha) <= n_components:
            return float(alpha)
    raise AssertionError("no alpha satisfies the rule")


@pytest.mark.parametrize("n_components", [1, 2, 3])
def test_optimal_alpha_equals_brute_force(two_blobs: AlphaComplex, n_components: int) -> None:
    assert two_blobs.optimal_alpha(n_components) == brute_optimal(two_blobs, n_components)


def test_optimal_alpha_separates_two_blobs(two_blobs: AlphaComplex) -> None:
    one, two = two_blobs.optimal_alpha(1), two_blobs.optimal_alpha(2)
    assert two < one
    assert two_blobs.betti(two)[0] == 2
    assert two_blobs.signatures().solid_components[two_blobs.signatures().index(two)] == 2


def test_optimal_alpha_random(ac: AlphaComplex) -> None:
    assert ac.optimal_alpha() == brute_optimal(ac, 1)


@pytest.mark.parametrize("bad", [0, -1, 1.5, "two", None, True])
def test_optimal_alpha_rejects_bad_counts(ac: AlphaComplex, bad) -> None:
    with pytest.raises(InputError):
        ac.optimal_alpha(bad)


def test_suggestions_are_ranked_constant_ranges(ac: AlphaComplex) -> None:
    sig = ac.signatures()
    ranges = ac.suggest_alphas(k=5)
    assert 1 <= len(ranges) <= 5
    spans = [r.log_span for r in ranges]
    assert spans == sorted(spans, reverse=True)
    for r in ranges:
        assert 0 < r.low < r.alpha < r.high < np.inf
        assert r.log_span == pytest.approx(np.log(r.high / r.low))
        inside = (sig.alphas >= r.low) & (sig.alphas < r.high)
        assert {tuple(b) for b in sig.betti[inside]} == {r.betti}
        assert ac.betti(r.alpha) == r.betti
        assert 2 * r.betti[0] <= len(ac.points)
        assert tuple(sig.betti[sig.index(r.high)]) != r.betti
    assert len({r.betti for r in ranges}) == len(ranges)
    everything = stable_ranges(sig, distinct=False)
    assert len(everything) >= len(ranges)
    for r in ranges:
        assert r.log_span == max(x.log_span for x in everything if x.betti == r.betti)
    assert ac.suggest_alphas(k=0) == ()
    with pytest.raises(InputError):
        ac.suggest_alphas(k=-1)


def test_suggestion_finds_the_void_of_a_sphere() -> None:
    from test_topology import sphere

    ac = AlphaComplex.from_points(sphere(np.random.default_rng(1)))
    best = ac.suggest_alphas(k=1)[0]
    assert best.betti == (1, 0, 1)
    assert best.low < 0.3 < best.high


def delaunay_cells(ac: AlphaComplex, queries: np.ndarray) -> np.ndarray:
    """Our cell row holding each query by scipy's find_simplex (-1 outside), matched by vertices."""
    tri = Delaunay(ac.points)
    ours = {tuple(r): i for i, r in enumerate(np.sort(ac.simplices(ac.dim), axis=1).tolist())}
    keys = [tuple(r) for r in np.sort(tri.simplices, axis=1).tolist()]
    found = tri.find_simplex(queries)
    return np.array([ours[keys[s]] if s >= 0 else -1 for s in found.tolist()], dtype=np.int64)


def test_contains_agrees_with_find_simplex(ac: AlphaComplex) -> None:
    rng = np.random.default_rng(11)
    queries = rng.uniform(-0.2, 1.2, size=(2000, ac.dim))
    cells = delaunay_cells(ac, queries)
    enter = ac.intervals(ac.dim)[:, 0]
    for alpha in (0.0, *np.quantile(enter, [0.1, 0.5, 0.9]), np.inf):
        got = ac.contains(queries, alpha)
        assert got.dtype == bool and got.shape == (2000,)
        np.testing.assert_array_equal(got, (cells >= 0) & (enter[cells] <= alpha))


def test_contains_vertices_and_bad_input(ac: AlphaComplex) -> None:
    assert ac.contains(ac.points, np.inf).all()
    assert not ac.contains(ac.points, 0.0).any()
    assert ac.contains(np.full(ac.dim, 0.5), np.inf).tolist() == [True]
    for bad in (np.zeros((3, 4)), [[np.nan] * ac.dim], "points", np.zeros((2, 2, 2))):
        with pytest.raises(InputError):
            ac.contains(bad, 1.0)
    for alpha in (-1.0, float("nan"), "big", None):
        with pytest.raises(InputError):
            ac.contains(ac.points[:2], alpha)
        with pytest.raises(InputError):
            ac.betti(alpha)


def test_planar_3d_input_matches_its_2d_complex() -> None:
    rng = np.random.default_rng(3)
    flat = rng.random((300, 2))
    basis = np.array([[0.6, 0.0, 0.8], [0.0, 1.0, 0.0]])
    tilted = AlphaComplex.from_points(flat @ basis + [1.0, 2.0, 3.0])
    plain = AlphaComplex.from_points(flat)
    assert (tilted.dim, tilted.ambient_dim) == (2, 3)
    one, two = tilted.signatures(), plain.signatures()
    for alpha in np.quantile(two.alphas, [0.01, 0.2, 0.5, 0.8]) * (1 + 1e-7):
        assert tilted.betti(alpha) == plain.betti(alpha)
        assert one.measure[one.index(alpha)] == pytest.approx(two.measure[two.index(alpha)])
        queries = rng.random((500, 2))
        np.testing.assert_array_equal(tilted.contains(queries @ basis + [1.0, 2.0, 3.0], alpha),
                                      plain.contains(queries, alpha))
    assert tilted.optimal_alpha() == pytest.approx(plain.optimal_alpha())


@needs_data
@pytest.mark.parametrize("name, columns", [("us_airports.csv", "longitude,latitude"),
                                           ("milk.pcd", None)])
def test_real_scans(name: str, columns) -> None:
    from core.io import read_points

    pts = read_points(DATA / name, columns=columns, subsample=4000).points
    ac = AlphaComplex.from_points(pts)
    sig = ac.signatures()
    assert tuple(sig.betti[0]) == (len(ac.points),) + (0,) * (ac.dim - 1)
    assert tuple(sig.betti[-1]) == (1,) + (0,) * (ac.dim - 1)
    assert sig.measure[-1] == pytest.approx(ConvexHull(ac.points).volume, rel=1e-9)
    best = ac.optimal_alpha()
    assert sig.solid_components[sig.index(best)] == 1
    rows = sample_rows(len(sig.alphas), 15)
    for k in range(ac.dim + 1):
        for i in rows:
            want = np.bincount(ac.classify(sig.alphas[i], k), minlength=4)
            np.testing.assert_array_equal(sig.counts(k)[i], want)

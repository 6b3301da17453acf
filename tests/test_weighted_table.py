"""Weighted tables by definition: classic equivalence, brute-force orthogonal spheres and power
distances, degenerate inputs, and monotone classes (hypothesis)."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from weighted_reference import orthosphere, power

from core import AlphaComplex

LEVEL_ARRAYS = ("simplices", "intervals", "face_ids")


def assert_same_table(a: AlphaComplex, b: AlphaComplex) -> None:
    """Every array of the two complexes equal, bit for bit."""
    assert a.dim == b.dim
    for name in ("points", "input_index"):
        assert np.array_equal(getattr(a, name), getattr(b, name))
    for k in range(a.dim + 1):
        for name in LEVEL_ARRAYS if k else LEVEL_ARRAYS[:2]:
            x, y = getattr(a, name)(k), getattr(b, name)(k)
            assert x.dtype == y.dtype and np.array_equal(x, y), f"{name}({k}) differs"
    for name in ("facet_cells", "cell_measures", "spectrum"):
        assert np.array_equal(getattr(a, name)(), getattr(b, name)())


@pytest.mark.parametrize("dim", [2, 3])
def test_zero_weights_give_the_classic_table_bit_for_bit(dim: int) -> None:
    pts = np.random.default_rng(dim).random((500, dim))
    classic = AlphaComplex.from_points(pts)
    for weights in (None, np.zeros(500), [0] * 500):
        ac = AlphaComplex.from_points(pts, weights=weights)
        assert ac.weights is None
        assert_same_table(ac, classic)
    assert np.array_equal(classic.intervals_sq(1), classic.intervals(1) ** 2)
    assert np.array_equal(classic.spectrum_sq(), classic.spectrum() ** 2)


@pytest.mark.parametrize("dim", [2, 3])
def test_zero_weights_on_a_lattice_are_the_classic_table(dim: int) -> None:
    axes = np.meshgrid(*[np.arange(5.0)] * dim, indexing="ij")
    pts = np.column_stack([a.ravel() for a in axes])
    assert_same_table(AlphaComplex.from_points(pts, weights=np.zeros(len(pts))),
                      AlphaComplex.from_points(pts))


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("lattice", [False, True])
def test_equal_weights_shift_the_classic_table(dim: int, lattice: bool) -> None:
    if lattice:
        axes = np.meshgrid(*[np.arange(5.0)] * dim, indexing="ij")
        pts = np.column_stack([a.ravel() for a in axes])
    else:
        pts = np.random.default_rng(9).random((400, dim))
    c = 0.01 if not lattice else 0.2
    classic = AlphaComplex.from_points(pts)
    ac = AlphaComplex.from_points(pts, weights=np.full(len(pts), c))
    assert np.array_equal(ac.input_index, classic.input_index)
    for k in range(dim + 1):
        ours = dict(zip(map(tuple, ac.simplices(k).tolist()), ac.intervals_sq(k), strict=True))
        base = dict(zip(map(tuple, classic.simplices(k).tolist()), classic.intervals_sq(k),
                        strict=True))
        assert ours.keys() == base.keys()
        keys = list(base)
        np.testing.assert_allclose(np.array([ours[t] for t in keys]),
                                   np.array([base[t] for t in keys]) - c, rtol=1e-12, atol=1e-14)
    assert ac.betti(alpha2=-c) == tuple([len(pts)] + [0] * (dim - 1))


def brute_enter_sq(points: np.ndarray, weights: np.ndarray, simplices: dict, dim: int) -> dict:
    """enter² by the definition: a simplex's own orthogonal sphere's power when no point has
    smaller power at its centre (global test, all non-hidden points), else its smallest
    cofacet's enter²."""
    enter = {dim: {}}
    for k in range(dim, -1, -1):
        enter[k] = {}
        for s in simplices[k]:
            c, p = orthosphere(points[list(s)], weights[list(s)])
            others = np.delete(np.arange(len(points)), list(s))
            free = (power(points[others], weights[others], c) >= p - 1e-12).all()
            if k == dim or free:
                enter[k][s] = p
            else:
                cof = [enter[k + 1][t] for t in simplices[k + 1] if set(s) <= set(t)]
                enter[k][s] = min(cof)
    return enter


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("seed", range(4))
def test_small_inputs_equal_the_brute_force_definition(dim: int, seed: int) -> None:
    rng = np.random.default_rng(seed)
    pts = rng.random((14 if dim == 2 else 12, dim))
    w = rng.uniform(0.0, 0.04, len(pts))
    ac = AlphaComplex.from_points(pts, weights=w)
    shown = np.flatnonzero(ac.input_index >= 0)
    row = np.empty(len(ac.points), dtype=np.int64)
    row[ac.input_index[shown]] = shown
    vp, vw = pts[shown], w[shown]
    local = {r: i for i, r in enumerate(shown)}
    simplices = {k: [tuple(sorted(local[v] for v in row[s])) for s in ac.simplices(k).tolist()]
                 for k in range(dim + 1)}
    # the cells are the regular triangulation: no point (hidden ones too) below a cell's sphere
    for s in simplices[dim]:
        c, p = orthosphere(vp[list(s)], vw[list(s)])
        assert (power(pts, w, c) >= p - 1e-12).all()
    hidden = np.flatnonzero(ac.input_index < 0)  # inside the hull of the others
    assert ac.contains(pts[hidden], np.inf).all()
    enter = brute_enter_sq(vp, vw, simplices, dim)
    for k in range(dim + 1):
        expected = np.array([enter[k][s] for s in simplices[k]])
        np.testing.assert_allclose(ac.intervals_sq(k)[:, 0], expected, rtol=1e-9, atol=1e-13)


def test_a_ball_inside_another_is_hidden() -> None:
    axes = np.meshgrid(np.arange(6.0), np.arange(6.0), indexing="ij")
    pts = np.column_stack([a.ravel() for a in axes]) + 0.01 * np.random.default_rng(1).random(
        (36, 2))
    pts = np.vstack([pts, [[2.5, 2.5], [2.6, 2.5]]])
    w = np.full(len(pts), 0.05)
    w[-2:] = 0.3, 0.01  # radius 0.55 around (2.5, 2.5) holds radius 0.1 around (2.6, 2.5)
    ac = AlphaComplex.from_points(pts, weights=w)
    assert ac.input_index[-1] == -1
    assert (ac.input_index[:-1] >= 0).all()
    import gudhi

    tree = gudhi.AlphaComplex(points=pts, weights=w.tolist()).create_simplex_tree()
    assert sorted(s[0] for s, _ in tree.get_skeleton(0)) == list(range(len(pts) - 1))


@pytest.mark.parametrize("dim", [2, 3])
def test_all_points_hidden_but_one_cell(dim: int) -> None:
    rng = np.random.default_rng(5)
    corners = np.vstack([np.zeros(dim), 10 * np.eye(dim)]) - 2.0
    inner = rng.random((50, dim))
    pts = np.vstack([corners, inner])
    w = np.concatenate([np.full(dim + 1, 400.0), np.zeros(50)])
    ac = AlphaComplex.from_points(pts, weights=w)
    assert ac.counts() == ((3, 3, 1) if dim == 2 else (4, 6, 4, 1))
    assert (ac.input_index[dim + 1:] == -1).all()
    assert np.array_equal(np.sort(ac.input_index[:dim + 1]), np.arange(dim + 1))


def test_duplicates_keep_the_heaviest_ball() -> None:
    pts = np.random.default_rng(3).random((40, 2))
    pts = np.vstack([pts, pts[:3], pts[3:5]])
    w = np.full(45, 1e-4)
    w[40:43] = 0.0  # lighter copies: hidden
    w[43:45] = 1e-4  # equal copies: merged
    ac = AlphaComplex.from_points(pts, weights=w)
    assert (ac.input_index[40:43] == -1).all()
    assert np.array_equal(ac.input_index[43:45], ac.input_index[3:5])


@st.composite
def weighted_sets(draw):
    dim = draw(st.sampled_from([2, 3]))
    n = draw(st.integers(dim + 2, 25))
    seed = draw(st.integers(0, 2**31 - 1))
    rng = np.random.default_rng(seed)
    pts = rng.random((n, dim))
    top = draw(st.sampled_from([0.0, 1e-3, 0.02, 0.2]))
    return pts, rng.uniform(0.0, top, n) if top else rng.uniform(0, 1e-3, n)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(weighted_sets(), st.lists(st.floats(-0.3, 0.5), min_size=2, max_size=6))
def test_classes_grow_monotonically_and_faces_come_first(data, values) -> None:
    pts, w = data
    ac = AlphaComplex.from_points(pts, weights=w)
    values = sorted(values)
    for k in range(ac.dim + 1):
        iv = ac.intervals_sq(k)
        assert (iv[:, 0] <= iv[:, 1]).all() and (iv[:, 1] <= iv[:, 2]).all()
        classes = [ac.classify(alpha2=v, k=k) for v in values]
        for lo, hi in itertools.pairwise(classes):
            assert (lo <= hi).all()
        if k:
            faces = ac.face_ids(k)
            below = ac.intervals(k - 1)[faces, 0]
            assert (below <= ac.intervals(k)[:, [0]]).all()


@pytest.mark.parametrize("k", [1, 2, 3])
def test_exact_power_equals_the_linear_algebra_reference(k: int) -> None:
    from core.geometry.power import exact_power

    rng = np.random.default_rng(k)
    corners, w = rng.random((k + 1, 3)), rng.uniform(0, 0.1, k + 1)
    assert exact_power(corners, w) == pytest.approx(orthosphere(corners, w)[1], rel=1e-12)
    flat = np.vstack([corners[:2], 2 * corners[1] - corners[0]])  # three collinear points
    assert exact_power(flat, np.zeros(3)) is None

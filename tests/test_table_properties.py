"""Hypothesis properties of the interval table and of the shape at one alpha."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, example, given, settings
from hypothesis import strategies as st
from reference import (
    assert_valid_table,
    canonical,
    cofacet_pairs,
    expected_classes,
    hull_simplices,
    simplex_measures,
)
from scipy.spatial import ConvexHull

from core import AlphaComplex
from core.errors import InputError

SETTINGS = settings(max_examples=40, deadline=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])


@st.composite
def point_sets(draw, general: bool = False):
    """(n, dim) float64, 4..30 points: floats when `general`, else a coarse grid (degenerate)."""
    dim = draw(st.sampled_from([2, 3]))
    n = draw(st.integers(dim + 2, 30))
    if general:
        coord = st.floats(-100, 100, allow_nan=False, allow_infinity=False, allow_subnormal=False)
    else:
        coord = st.integers(-6, 6).map(float)
    rows = draw(st.lists(st.tuples(*[coord] * dim), min_size=n, max_size=n))
    return np.array(rows, dtype=np.float64)


@st.composite
def random_sets(draw):
    """(n, dim) float64 in general position almost surely: seeded uniform or stretched clouds."""
    dim = draw(st.sampled_from([2, 3]))
    n = draw(st.integers(dim + 2, 30))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    stretch = draw(st.sampled_from([1.0, 0.1, 30.0]))
    pts = rng.uniform(-1, 1, (n, dim))
    pts[:, 0] *= stretch
    return pts


def build(points: np.ndarray) -> AlphaComplex:
    """The complex, or a rejected draw when the input is legitimately unusable (e.g. collinear)."""
    try:
        return AlphaComplex.from_points(points)
    except InputError:
        assume(False)
        raise


def general_position(points: np.ndarray, ac) -> bool:
    """Full-dimensional, no duplicates, hull facets not coplanar with one another, no slivers."""
    if ac.dim != points.shape[1] or len(ac.points) != len(points):
        return False
    hull = ConvexHull(points)
    planes = np.round(hull.equations / np.abs(hull.equations).max(), 9)
    if len(np.unique(planes, axis=0)) != len(planes):
        return False
    vol = simplex_measures(ac.points, ac.simplices(ac.dim))
    scale = np.ptp(points, axis=0).max() ** ac.dim
    return bool(vol.min() > 1e-6 * scale)


def probe_alphas(ac) -> np.ndarray:
    """Sorted alphas: 0, every interval value, midpoints, and beyond the largest."""
    vals = np.concatenate([np.asarray(ac.intervals(k)).ravel() for k in range(ac.dim + 1)])
    vals = np.unique(vals[np.isfinite(vals)])
    mids = (vals[:-1] + vals[1:]) / 2
    return np.unique(np.concatenate([[0.0], vals, mids, [vals[-1] * 2 + 1]]))


@SETTINGS
@given(point_sets())
def test_table_valid_on_grid_input(points) -> None:
    assert_valid_table(build(points))


@SETTINGS
@given(point_sets(general=True))
@example(np.array([[0, 0, 0], [0, 0, 1], [0, 0.85, -55.5880345], [0, -5.96046448e-08, 0],
                   [1, 0, 0]]))  # a needle triangle: its radius² once cancelled below zero
def test_table_valid_on_float_input(points) -> None:
    assert_valid_table(build(points))


@SETTINGS
@given(point_sets())
def test_classes_follow_intervals_and_never_decrease(points) -> None:
    ac = build(points)
    alphas = probe_alphas(ac)
    for k in range(ac.dim + 1):
        iv = np.asarray(ac.intervals(k))
        classes = np.array([ac.classify(a, k) for a in alphas])
        assert classes.dtype == np.int8
        assert (np.diff(classes.astype(int), axis=0) >= 0).all(), "a class decreased"
        for a, got in zip(alphas, classes, strict=True):
            np.testing.assert_array_equal(got, expected_classes(iv, a), err_msg=f"k={k} a={a!r}")


@SETTINGS
@given(point_sets())
def test_alpha_zero_leaves_isolated_points(points) -> None:
    ac = build(points)
    assert (np.asarray(ac.classify(0.0, 0)) == 1).all()
    for k in range(1, ac.dim + 1):
        assert (np.asarray(ac.classify(0.0, k)) == 0).all()
    shape = ac.shape(0.0)
    assert len(shape.cells) == 0 and shape.measure == 0
    assert len(shape.singular(0)) == len(ac.points)


@SETTINGS
@given(random_sets())
def test_large_alpha_gives_convex_hull(points) -> None:
    ac = build(points)
    assume(general_position(points, ac))
    hull = hull_simplices(ac.points, ac.dim)
    top = np.asarray(ac.spectrum())[-1]
    for alpha in (top, top * 10):
        assert (np.asarray(ac.classify(alpha, ac.dim)) == 3).all()
        for k in range(ac.dim):
            rows, order = canonical(ac.simplices(k))
            on_hull = np.isin(_keys(rows, len(ac.points)), _keys(hull[k], len(ac.points)))
            classes = np.asarray(ac.classify(alpha, k))[order]
            np.testing.assert_array_equal(classes, np.where(on_hull, 2, 3), err_msg=f"k={k}")
        assert ac.shape(alpha).measure == pytest.approx(ConvexHull(ac.points).volume, rel=1e-9)


def _keys(rows: np.ndarray, base: int) -> np.ndarray:
    """int64 keys of sorted rows (for set membership)."""
    from reference import row_keys

    return row_keys(rows, base)


@SETTINGS
@given(point_sets(), st.floats(0.0, 1.0))
def test_shape_parts_match_classes(points, frac: float) -> None:
    ac = build(points)
    alphas = probe_alphas(ac)
    alpha = float(alphas[int(frac * (len(alphas) - 1))])
    shape, d = ac.shape(alpha), ac.dim
    assert shape.alpha == alpha and shape.dim == d
    cells = np.asarray(ac.simplices(d))
    in_cx = np.asarray(ac.classify(alpha, d)) > 0
    assert np.array_equal(np.sort(shape.cell_ids), np.nonzero(in_cx)[0])
    assert np.array_equal(np.asarray(shape.cells), cells[shape.cell_ids])
    fclass = np.asarray(ac.classify(alpha, d - 1))
    facets = np.asarray(ac.simplices(d - 1))
    _same_rows(shape.boundary_facets, facets[(fclass == 1) | (fclass == 2)])
    _same_rows(shape.regular_facets, facets[fclass == 2])
    for k in range(d):
        singular = np.asarray(ac.classify(alpha, k)) == 1
        _same_rows(shape.singular(k), np.asarray(ac.simplices(k))[singular])
    ref_measure = simplex_measures(ac.points, cells[in_cx]).sum()
    assert shape.measure == pytest.approx(ref_measure, rel=1e-9, abs=1e-12)


def _same_rows(got, want) -> None:
    """Equal as sets of vertex sets (any order of rows or of vertices in a row)."""
    got = canonical(np.asarray(got).reshape(-1, np.asarray(want).shape[1]))[0]
    np.testing.assert_array_equal(got, canonical(want)[0])


@SETTINGS
@given(point_sets(), st.floats(0.0, 1.0))
def test_boundary_facets_are_the_boundary_of_the_complex(points, frac: float) -> None:
    ac = build(points)
    alphas = probe_alphas(ac)
    alpha = float(alphas[int(frac * (len(alphas) - 1))])
    d, m = ac.dim, len(ac.points)
    facets = np.asarray(ac.simplices(d - 1), dtype=np.int64)
    cells = np.asarray(ac.simplices(d), dtype=np.int64)
    f, c = cofacet_pairs(facets, cells, m)
    in_cx = np.asarray(ac.classify(alpha, d)) > 0
    n_in = np.bincount(f, weights=in_cx[c], minlength=len(facets)).astype(int)
    facet_in = np.asarray(ac.classify(alpha, d - 1)) > 0
    _same_rows(ac.shape(alpha).regular_facets, facets[facet_in & (n_in == 1)])
    _same_rows(ac.shape(alpha).boundary_facets, facets[facet_in & (n_in < 2)])


@SETTINGS
@given(random_sets(), st.floats(0.0, 1.0))
def test_regular_facets_point_outward(points, frac: float) -> None:
    ac = build(points)
    assume(general_position(points, ac))
    check_orientation(ac, frac)


@SETTINGS
@given(point_sets(), st.floats(0.0, 1.0))
def test_regular_facets_point_outward_on_grid_input(points, frac: float) -> None:
    ac = build(points)
    vol = simplex_measures(ac.points, ac.simplices(ac.dim))
    assume(vol.min() > 1e-9 * vol.max())
    check_orientation(ac, frac)


def check_orientation(ac, frac: float) -> None:
    """Regular facets: normal away from their cell; they enclose exactly the shape's measure."""
    alphas = probe_alphas(ac)
    shape = ac.shape(float(alphas[int(frac * (len(alphas) - 1))]))
    pts, reg = np.asarray(ac.points), np.asarray(shape.regular_facets, dtype=np.int64)
    cells = np.asarray(shape.cells, dtype=np.int64)
    if len(reg) == 0:
        assert len(cells) == 0
        return
    f, c = _own_cells(reg, cells)
    opposite = np.array([np.setdiff1d(cells[ci], reg[fi])[0] for fi, ci in zip(f, c, strict=True)])
    a = pts[reg[f, 0]]
    if ac.dim == 3:
        normal = np.cross(pts[reg[f, 1]] - a, pts[reg[f, 2]] - a)
        side = np.einsum("ij,ij->i", normal, pts[opposite] - a)
    else:
        e, w = pts[reg[f, 1]] - a, pts[opposite] - a
        side = -(e[:, 0] * w[:, 1] - e[:, 1] * w[:, 0])  # > 0: cell on the right
    assert (side < 0).all(), "a regular facet's normal points into its cell"
    assert _enclosed_measure(pts, reg, ac.dim) == pytest.approx(shape.measure, rel=1e-7, abs=1e-9)


def _own_cells(reg: np.ndarray, cells: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(facet index, cell index) pairs: the cell of the shape that holds each regular facet."""
    pairs = [(i, j) for i, r in enumerate(reg) for j, cl in enumerate(cells) if set(r) <= set(cl)]
    f, c = np.array(pairs, dtype=np.int64).T
    assert np.array_equal(np.bincount(f, minlength=len(reg)), np.ones(len(reg))), \
        "a regular facet must lie on exactly one cell of the shape"
    return f, c


def _enclosed_measure(pts: np.ndarray, facets: np.ndarray, dim: int) -> float:
    """Volume (3D) / area (2D) enclosed by oriented boundary facets, by the divergence theorem."""
    o = pts.mean(axis=0)
    p = [pts[facets[:, j]] - o for j in range(dim)]
    if dim == 3:
        return float(np.einsum("ij,ij->i", p[0], np.cross(p[1], p[2])).sum() / 6)
    return float((p[0][:, 0] * p[1][:, 1] - p[0][:, 1] * p[1][:, 0]).sum() / 2)


@SETTINGS
@given(point_sets())
def test_spectrum_holds_every_enter_value(points) -> None:
    ac = build(points)
    spec = np.asarray(ac.spectrum())
    assert spec.dtype == np.float64 and spec[0] == 0.0
    assert (np.diff(spec) > 0).all() and np.isfinite(spec).all()
    every = np.concatenate([np.asarray(ac.intervals(k)) for k in range(ac.dim + 1)]).ravel()
    enters = np.concatenate([np.asarray(ac.intervals(k))[:, 0] for k in range(ac.dim + 1)])
    assert np.isin(enters, spec).all(), "an enter value is missing from the spectrum"
    assert np.isin(spec, every).all(), "a spectrum value that is no interval bound"


@SETTINGS
@given(point_sets())
def test_cell_measures_and_facet_cells(points) -> None:
    ac = build(points)
    d, m = ac.dim, len(ac.points)
    cells = np.asarray(ac.simplices(d), dtype=np.int64)
    facets = np.asarray(ac.simplices(d - 1), dtype=np.int64)
    want_measures = simplex_measures(ac.points, cells)
    np.testing.assert_allclose(ac.cell_measures(), want_measures, rtol=1e-9,
                               atol=1e-12 * want_measures.max())
    fc = np.asarray(ac.facet_cells())
    assert fc.shape == (len(facets), 2)
    f, c = cofacet_pairs(facets, cells, m)
    want = np.full((len(facets), 2), -1)
    count = np.zeros(len(facets), dtype=int)
    for fi, ci in zip(f, c, strict=True):
        want[fi, count[fi]] = ci
        count[fi] += 1
    np.testing.assert_array_equal(np.sort(fc, axis=1), np.sort(want, axis=1))


@settings(max_examples=10, deadline=None)
@given(point_sets())
def test_handed_out_arrays_are_read_only(points) -> None:
    ac = build(points)
    shape = ac.shape(float(np.asarray(ac.spectrum())[-1]))
    arrays = [ac.points, ac.input_index, ac.spectrum(), ac.cell_measures(), ac.facet_cells(),
              shape.cells, shape.cell_ids, shape.boundary_facets, shape.regular_facets]
    arrays += [ac.simplices(k) for k in range(ac.dim + 1)]
    arrays += [ac.intervals(k) for k in range(ac.dim + 1)]
    for arr in arrays:
        assert isinstance(arr, np.ndarray) and not arr.flags.writeable
    with pytest.raises(ValueError):
        np.asarray(ac.intervals(1))[0, 0] = -1.0

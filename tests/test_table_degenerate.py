"""Degenerate input: lattices, cospherical points, slivers, duplicates, planes, bad input."""

from __future__ import annotations

import numpy as np
import pytest
from reference import (
    SQ_RTOL,
    assert_valid_table,
    canonical,
    facet_measures,
    gudhi_boundary_measure,
    gudhi_measure,
    gudhi_table,
    ours_by_input_ids,
    simplex_measures,
)
from scipy.spatial import ConvexHull

from core import AlphaComplex
from core.errors import Cancelled, InputError


def lattice(*sizes: int, spacing: float = 1.0) -> np.ndarray:
    """(prod(sizes), len(sizes)) float64 integer lattice times spacing."""
    axes = np.meshgrid(*[np.arange(s, dtype=np.float64) for s in sizes], indexing="ij")
    return np.column_stack([a.ravel() for a in axes]) * spacing


def jittered(pts: np.ndarray, amount: float = 1e-3, seed: int = 0) -> np.ndarray:
    """The points moved by uniform noise of +-amount (lattice spacing 1)."""
    return pts + np.random.default_rng(seed).uniform(-amount, amount, pts.shape)


def fibonacci_sphere(n: int) -> np.ndarray:
    """(n, 3) points on the unit sphere (cospherical up to rounding)."""
    i = np.arange(n) + 0.5
    phi, theta = np.arccos(1 - 2 * i / n), np.pi * (1 + 5**0.5) * i
    return np.column_stack([np.cos(theta) * np.sin(phi), np.sin(theta) * np.sin(phi), np.cos(phi)])


def terraces(seed: int = 0) -> np.ndarray:
    """12x12 unit lattice in xy on two z levels: masses of coplanar and cospherical subsets."""
    xy = lattice(12, 12)
    z = np.random.default_rng(seed).integers(0, 2, len(xy)) * 0.25
    return np.column_stack([xy, z])


def circle_and_centre(n: int = 16) -> np.ndarray:
    """(n+1, 2) a regular n-gon and its centre (cocircular)."""
    t = 2 * np.pi * np.arange(n) / n
    return np.vstack([np.column_stack([np.cos(t), np.sin(t)]), [[0.0, 0.0]]])


CUBE = lattice(2, 2, 2)
OCTAHEDRON = np.vstack([np.eye(3), -np.eye(3)])

VOLUME_CASES = {
    "lattice-3x3x3": lattice(3, 3, 3),
    "lattice-4x5x6": lattice(4, 5, 6),
    "lattice-10x10": lattice(10, 10),
    "jittered-3x3x3": jittered(lattice(3, 3, 3)),
    "jittered-4x5x6": jittered(lattice(4, 5, 6), seed=1),
    "jittered-10x10": jittered(lattice(10, 10), seed=2),
    "cube-corners": CUBE,
    "octahedron": OCTAHEDRON,
    "circle": circle_and_centre(),
    "terraces": terraces(),
    "huge-offset-lattice": lattice(4, 4, 3, spacing=0.01) + 1e6,
}

VALID_CASES = {
    **VOLUME_CASES,
    "sphere-60": fibonacci_sphere(60),
    "sphere-60-centre": np.vstack([fibonacci_sphere(60), [[0.0, 0.0, 0.0]]]),
    "slab-1e-6": np.column_stack([np.random.default_rng(4).random((80, 2)),
                                  np.random.default_rng(5).integers(0, 2, 80) * 1e-6]),
    "needle": np.column_stack([np.random.default_rng(6).random(40) * 1e3,
                               np.random.default_rng(7).random((40, 2)) * 1e-3]),
    "lattice-2x2x9": lattice(2, 2, 9),
}


@pytest.mark.parametrize("name", sorted(VALID_CASES))
def test_degenerate_input_gives_valid_table(name: str) -> None:
    ac = AlphaComplex.from_points(VALID_CASES[name])
    assert_valid_table(ac)
    hull = ConvexHull(ac.points).volume
    top = float(np.asarray(ac.spectrum())[-1])
    assert ac.shape(top).measure == pytest.approx(hull, rel=1e-9), "the complex at inf != hull"


def probe_alphas(*critical: np.ndarray, rel: float = 1e-7) -> np.ndarray:
    """Alphas away from every critical value (clusters merged at rel): midpoints, and just above."""
    vals = np.unique(np.concatenate(critical))
    vals = vals[np.isfinite(vals) & (vals > 0)]
    keep = np.r_[True, np.diff(vals) > rel * vals[1:]]
    starts = vals[keep]
    ends = np.r_[vals[np.nonzero(keep)[0][1:] - 1], vals[-1]]
    return np.concatenate([[0.0], (ends[:-1] + starts[1:]) / 2, ends * (1 + 2 * rel)])


@pytest.mark.parametrize("name", sorted(VOLUME_CASES))
def test_measure_equals_gudhi_exact_at_every_alpha(name: str) -> None:
    pts = VOLUME_CASES[name]
    ac = AlphaComplex.from_points(pts)
    ref = gudhi_table(pts, precision="exact")
    assert ac.dim == ref["dim"]
    g_vals = np.sqrt(np.concatenate([ref[k][1] for k in range(ref["dim"] + 1)]))
    total = ConvexHull(pts).volume
    for alpha in probe_alphas(np.asarray(ac.spectrum()), g_vals):
        got = ac.shape(alpha).measure
        want = gudhi_measure(pts, ref, alpha)
        assert got == pytest.approx(want, rel=1e-9, abs=1e-9 * total), f"at alpha={alpha!r}"


@pytest.mark.parametrize("name", sorted(VOLUME_CASES))
def test_boundary_area_equals_gudhi_exact_at_every_alpha(name: str) -> None:
    """Regular facets bound the union of cells: their area is independent of the triangulation."""
    pts = VOLUME_CASES[name]
    ac = AlphaComplex.from_points(pts)
    ref = gudhi_table(pts, precision="exact")
    g_vals = np.sqrt(np.concatenate([ref[k][1] for k in range(ref["dim"] + 1)]))
    scale = facet_measures(pts, ref[ref["dim"] - 1][0]).sum()
    for alpha in probe_alphas(np.asarray(ac.spectrum()), g_vals):
        shape = ac.shape(alpha)
        got = facet_measures(ac.to_ambient(ac.points), shape.regular_facets).sum()
        want = gudhi_boundary_measure(pts, ref, alpha)
        assert got == pytest.approx(want, rel=1e-9, abs=1e-9 * scale), (
            f"boundary at alpha={alpha!r}: {len(shape.regular_facets)} regular facets, "
            f"{int((np.asarray(ac.cell_measures())[shape.cell_ids] == 0).sum())} flat cells")


def test_spectrum_of_lattice_equals_gudhi() -> None:
    pts = lattice(4, 5, 6)
    ac, ref = AlphaComplex.from_points(pts), gudhi_table(pts, precision="exact")
    g_vals = np.unique(np.sqrt(np.concatenate([ref[k][1] for k in range(4)])))
    np.testing.assert_allclose(np.asarray(ac.spectrum()), g_vals, rtol=1e-12)


@pytest.mark.parametrize("dim", [2, 3])
def test_huge_coordinates_match_gudhi(dim: int) -> None:
    rng = np.random.default_rng(9)
    pts = 1e6 + rng.random((300, dim)) * 0.01 * 300 ** (1 / dim)
    ac = AlphaComplex.from_points(pts)
    assert_valid_table(ac)
    ref = gudhi_table(pts, precision="exact")
    n = len(pts)
    inv = np.empty(n, dtype=np.int64)
    inv[np.asarray(ac.input_index)] = np.arange(n)
    for k in range(dim + 1):
        rows = np.sort(inv[np.asarray(ac.simplices(k))], axis=1)
        order = np.lexsort(rows.T[::-1])
        np.testing.assert_array_equal(rows[order], ref[k][0])
        enter = np.asarray(ac.intervals(k))[order, 0]
        np.testing.assert_allclose(enter**2, ref[k][1], rtol=1e-6, err_msg=f"k={k}")


def test_needle_matches_gudhi_exact() -> None:
    """40 points, 1000 long and 1e-3 thick: thin but genuine cells keep their volume and radius."""
    pts = VALID_CASES["needle"]
    ac = AlphaComplex.from_points(pts)
    ref = gudhi_table(pts, precision="exact")
    cells, _ = ours_by_input_ids(ac, 3)
    np.testing.assert_array_equal(cells, ref[3][0])
    inv = np.argsort(np.asarray(ac.input_index))
    order = canonical(inv[np.asarray(ac.simplices(3))])[1]
    np.testing.assert_allclose(np.asarray(ac.cell_measures())[order],
                               simplex_measures(pts, ref[3][0]), rtol=1e-6)
    for k in range(4):
        _, iv = ours_by_input_ids(ac, k)
        fin = ref[k][1] > 0
        np.testing.assert_allclose(iv[fin, 0] ** 2, ref[k][1][fin], rtol=1e-6, err_msg=f"k={k}")


@pytest.mark.parametrize("dim", [2, 3])
def test_duplicates_are_merged_and_mapped_back(dim: int) -> None:
    rng = np.random.default_rng(dim)
    unique = rng.random((60, dim))
    picks = rng.permutation(np.concatenate([np.arange(60), rng.integers(0, 60, 90)]))
    pts = unique[picks]
    ac = AlphaComplex.from_points(pts)
    assert len(ac.points) == 60 and len(ac.input_index) == len(pts)
    np.testing.assert_array_equal(np.asarray(ac.points)[ac.input_index], pts)
    plain = AlphaComplex.from_points(unique)
    ref = gudhi_table(unique, precision="exact")
    for k in range(dim + 1):
        ours = np.sort(np.asarray(ac.intervals(k))[:, 0])
        np.testing.assert_allclose(ours, np.sort(np.asarray(plain.intervals(k))[:, 0]), rtol=1e-12)
        np.testing.assert_allclose(ours**2, np.sort(ref[k][1]), rtol=SQ_RTOL)
    assert_valid_table(ac)


def test_points_in_a_tilted_plane_make_a_2d_complex() -> None:
    rng = np.random.default_rng(3)
    frame = np.linalg.qr(rng.normal(size=(3, 3)))[0][:, :2]
    uv = rng.random((120, 2))
    pts = uv @ frame.T + np.array([10.0, -4.0, 7.0])
    ac = AlphaComplex.from_points(pts)
    assert (ac.dim, ac.ambient_dim) == (2, 3)
    assert np.asarray(ac.points).shape == (120, 2)
    assert_valid_table(ac)
    back = np.asarray(ac.to_ambient(ac.points))
    assert back.shape == (120, 3)
    np.testing.assert_allclose(back[ac.input_index], pts, atol=1e-9)
    top = float(np.asarray(ac.spectrum())[-1])
    assert ac.shape(top).measure == pytest.approx(ConvexHull(uv).volume, rel=1e-9)
    ref = gudhi_table(uv, precision="exact")
    for k in range(3):
        rows, iv = ours_by_input_ids(ac, k)
        np.testing.assert_array_equal(rows, ref[k][0])
        np.testing.assert_allclose(iv[:, 0] ** 2, ref[k][1], rtol=1e-7, err_msg=f"k={k}")


def test_three_points_in_space_make_one_triangle() -> None:
    ac = AlphaComplex.from_points([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 1.0]])
    assert ac.dim == 2 and len(ac.simplices(2)) == 1
    assert_valid_table(ac)


BAD_INPUT = {
    "empty-list": ([], r"(?i)empty|no points|0 points|at least|shape"),
    "empty-2d": (np.zeros((0, 2)), r"(?i)empty|no points|0 points|at least"),
    "empty-3d": (np.zeros((0, 3)), r"(?i)empty|no points|0 points|at least"),
    "nan": ([[0.0, 0.0], [1.0, 0.0], [0.0, np.nan]], r"(?i)nan|finite"),
    "inf": ([[0.0, 0.0, 0.0], [1, 0, 0], [0, 1, 0], [0, 0, np.inf]], r"(?i)inf|finite"),
    "collinear-2d": ([[0.0, 0.0], [1.0, 1.0], [2.0, 2.0], [3.5, 3.5]], r"(?i)collinear|line"),
    "collinear-3d": ([[0.0, 0.0, 0.0], [1, 2, 3], [2, 4, 6], [-1, -2, -3]],
                     r"(?i)collinear|line"),
    "one-point": ([[1.0, 2.0, 3.0]], r"(?i)distinct|at least|too few|fewer|one point|1 point"),
    "two-points-2d": ([[0.0, 0.0], [1.0, 1.0]], r"(?i)distinct|at least|too few|fewer|collinear"),
    "two-distinct-3d": ([[0.0, 0.0, 0.0]] * 4 + [[1.0, 1.0, 1.0]] * 3,
                        r"(?i)distinct|at least|too few|fewer|collinear"),
    "four-columns": (np.ones((5, 4)), r"(?i)2|3|column|dimension|shape"),
    "one-column": (np.ones((5, 1)), r"(?i)2|3|column|dimension|shape"),
    "flat-vector": (np.arange(6.0), r"(?i)2|3|column|dimension|shape"),
    "strings": ([["a", "b"], ["c", "d"], ["e", "f"]], r"(?i)number|numeric|float|convert"),
}


@pytest.mark.parametrize("name", sorted(BAD_INPUT))
def test_bad_input_raises_a_clear_input_error(name: str) -> None:
    points, pattern = BAD_INPUT[name]
    with pytest.raises(InputError, match=pattern) as info:
        AlphaComplex.from_points(points)
    assert isinstance(info.value, ValueError)
    assert len(str(info.value)) > 10 and "Traceback" not in str(info.value)


def test_progress_reports_fractions_and_cancel_stops_the_build() -> None:
    pts = np.random.default_rng(0).random((500, 3))
    seen: list[tuple[float, str]] = []
    AlphaComplex.from_points(pts, progress=lambda f, stage: seen.append((f, stage)))
    assert seen, "progress was never called"
    fractions = [f for f, _ in seen]
    assert all(0.0 <= f <= 1.0 for f in fractions) and fractions == sorted(fractions)
    assert all(isinstance(stage, str) and stage for _, stage in seen)

    def cancel(fraction: float, stage: str) -> None:
        raise Cancelled("user pressed cancel")

    with pytest.raises(Cancelled):
        AlphaComplex.from_points(pts, progress=cancel)


@pytest.mark.parametrize(("dim", "extent"), [(2, 1e160), (3, 1e110)])
def test_extents_whose_measures_overflow_are_an_input_error(dim, extent):
    points = np.random.default_rng(3).random((50, dim)) * extent
    with pytest.raises(InputError, match="too large"):
        AlphaComplex.from_points(points)

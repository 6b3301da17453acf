"""The interval table on the shared real scans (skipped when ../shared/data is absent)."""

from __future__ import annotations

import numpy as np
import pytest
from reference import (
    assert_valid_table,
    data_dir,
    gudhi_measure,
    gudhi_table,
    needs_data,
    ours_by_input_ids,
    read_scan,
    read_scan_raw,
    row_keys,
    shared_file,
    simplex_measures,
    smallest_circumspheres,
)

from core import AlphaComplex

DATA = data_dir()
pytestmark = [
    pytest.mark.slow,
    needs_data,
]


def scan(name: str) -> np.ndarray:
    """(n, 3) float64 points of one shared scan."""
    return read_scan(shared_file(name))


@pytest.mark.parametrize("name", ["bun000_rangegrid.ply", "milk.pcd"])
def test_grid_like_scan_builds_a_valid_table(name: str) -> None:
    pts = scan(name)
    ac = AlphaComplex.from_points(pts)
    assert ac.dim == 3 and len(ac.points) == len(np.unique(pts, axis=0))
    assert_valid_table(ac)


def test_flat_lidar_patch_with_duplicates_builds() -> None:
    """plane_flat.laz read record by record: 28,185 records, 18,335 unique, 5 z levels."""
    path = shared_file("plane_flat.laz")
    pts = read_scan_raw(path)
    ac = AlphaComplex.from_points(pts)
    assert len(ac.input_index) == len(pts)
    assert len(ac.points) == len(np.unique(pts, axis=0))
    np.testing.assert_allclose(ac.to_ambient(np.asarray(ac.points))[ac.input_index], pts,
                               rtol=0, atol=1e-6)
    assert_valid_table(ac)


def test_bunny_equals_gudhi() -> None:
    pts = scan("bunny.ply")
    assert len(np.unique(pts, axis=0)) == len(pts)
    ac = AlphaComplex.from_points(pts)
    ref = gudhi_table(pts, precision="fast")
    for k in range(4):
        rows, iv = ours_by_input_ids(ac, k)
        np.testing.assert_array_equal(rows, ref[k][0], err_msg=f"{k}-simplices differ")
        for col in range(3):
            theirs = ref[k][col + 1]
            fin = np.isfinite(theirs)
            assert np.array_equal(np.isinf(iv[:, col]), ~fin)
            np.testing.assert_allclose(iv[fin, col] ** 2, theirs[fin], rtol=1e-6)


def test_milk_agrees_with_gudhi_up_to_its_degeneracy() -> None:
    """milk.pcd has 97 z levels: where Qhull and CGAL triangulate cospherical groups differently,
    each differing cell is flat or has a fifth point on its circumsphere, both sides cover the
    same volume, and the volume of the complex equals gudhi's at alphas between its values."""
    pts = scan("milk.pcd")
    n = len(pts)
    ac = AlphaComplex.from_points(pts)
    ref = gudhi_table(pts, precision="safe")
    rows, iv = ours_by_input_ids(ac, 3)
    ours_only = ~np.isin(row_keys(rows, n), row_keys(ref[3][0], n))
    theirs_only = ~np.isin(row_keys(ref[3][0], n), row_keys(rows, n))
    for cells in (rows[ours_only], ref[3][0][theirs_only]):
        assert_cospherical_or_flat(pts, cells)
    assert simplex_measures(pts, rows[ours_only]).sum() == pytest.approx(
        simplex_measures(pts, ref[3][0][theirs_only]).sum(), rel=1e-9)
    common = np.isin(row_keys(ref[3][0], n), row_keys(rows, n))
    np.testing.assert_allclose(iv[~ours_only, 0] ** 2, ref[3][1][common], rtol=1e-6)
    vals = np.unique(np.sqrt(ref[3][1]))
    wide = np.diff(vals) > 1e-5 * vals[1:]  # gudhi 'safe' is good to ~1e-6 here
    mids = ((vals[:-1] + vals[1:]) / 2)[wide]
    for alpha in mids[np.linspace(0, len(mids) - 1, 25).astype(int)]:
        want = gudhi_measure(pts, ref, alpha)
        assert ac.shape(alpha).measure == pytest.approx(want, rel=1e-9), f"alpha={alpha!r}"


def assert_cospherical_or_flat(pts: np.ndarray, cells: np.ndarray) -> None:
    """Every (c, 4) cell is flat or has a non-vertex point on its circumsphere (rel 1e-7)."""
    vol = simplex_measures(pts, cells)
    edge = np.linalg.norm(pts[cells[:, 1]] - pts[cells[:, 0]], axis=1)
    flat = vol <= 1e-9 * edge**3
    centres, radii = smallest_circumspheres(pts, cells[~flat])
    on_sphere = np.zeros(len(centres), dtype=bool)
    for start in range(0, len(centres), 256):
        sl = slice(start, start + 256)
        d = np.linalg.norm(pts[None, :, :] - centres[sl, None, :], axis=2)
        near = np.abs(d - radii[sl, None]) <= 1e-7 * radii[sl, None]
        on_sphere[sl] = near.sum(axis=1) >= 5
    assert on_sphere.all(), f"{int((~on_sphere).sum())} differing cells are in general position"


@pytest.mark.parametrize("name", ["milk.pcd", "plane_flat.laz"])
def test_slider_cursor_walk_matches_classify_on_a_real_scan(name: str) -> None:
    """The slider's incremental shapes on real data (ties, duplicates, a planar patch built
    in 2D) hold exactly classify()'s REGULAR facets and SINGULAR simplices at every stop."""
    from core import REGULAR, SINGULAR

    ac = AlphaComplex.from_points(read_scan_raw(shared_file(name)))
    spectrum = ac.spectrum()
    n = len(spectrum)
    optimal = int(np.searchsorted(spectrum, ac.optimal_alpha(), side="right")) - 1
    stops = [optimal, *range(optimal + 1, optimal + 30), *(optimal - n // 50 * np.arange(1, 8)),
             n // 3, n - 1, 0, optimal]
    cursor = ac.cursor()
    for index in stops:
        alpha = float(spectrum[int(np.clip(index, 0, n - 1))])
        shape = cursor.move(alpha)
        regular = np.flatnonzero(ac.classify(alpha, ac.dim - 1) == REGULAR)
        np.testing.assert_array_equal(np.sort(shape.regular_facet_ids), regular)
        for k in range(ac.dim):
            np.testing.assert_array_equal(np.sort(shape.singular_ids(k)),
                                          np.flatnonzero(ac.classify(alpha, k) == SINGULAR))

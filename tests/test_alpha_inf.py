"""alpha = inf is the convex hull: hull simplices stay REGULAR (their `interior` inf means never).

Every query at inf must equal the same query at a finite alpha beyond the whole spectrum, and
the hull's boundary must be the convex hull scipy computes (an independent reference).
"""

from __future__ import annotations

import json

import numpy as np
import pytest
import shapely
from scipy.spatial import ConvexHull

from app.cli import main
from core import AlphaComplex
from core.export import write_shape
from core.export.surface import surface_arrays

BEYOND = 1e150  # past every spectrum value below, and alpha² (1e300) is still finite
CASES = [(dim, weighted) for dim in (2, 3) for weighted in (False, True)]


def complex_of(dim: int, weighted: bool) -> AlphaComplex:
    """60 random points (weighted: random squared radii), a general-position hull."""
    rng = np.random.default_rng(10 * dim + weighted)
    points = rng.random((60, dim))
    return AlphaComplex.from_points(points, weights=rng.random(60) * 1e-3 if weighted else None)


def at(ac: AlphaComplex, value: float, weighted: bool, how):
    """how(ac, alpha=value) for a classic complex, how(ac, alpha2=value²) for a weighted one."""
    return how(ac, alpha2=value * value) if weighted else how(ac, alpha=value)


def sorted_rows(rows: np.ndarray) -> np.ndarray:
    rows = np.sort(np.asarray(rows), axis=1)
    return rows[np.lexsort(rows.T[::-1])]


@pytest.mark.parametrize(("dim", "weighted"), CASES)
def test_inf_classes_equal_beyond_spectrum(dim, weighted):
    ac = complex_of(dim, weighted)
    assert ac.spectrum()[-1] < BEYOND
    for k in range(dim + 1):
        inf = at(ac, np.inf, weighted, lambda c, k=k, **kw: c.classify(k=k, **kw))
        big = at(ac, BEYOND, weighted, lambda c, k=k, **kw: c.classify(k=k, **kw))
        np.testing.assert_array_equal(inf, big)
    facets = ac.classify(np.inf, dim - 1)
    hull = ConvexHull(ac.points)
    assert np.count_nonzero(facets == 2) == len(hull.simplices) > 0  # REGULAR = hull facets
    assert at(ac, np.inf, weighted, AlphaComplex.betti) == at(ac, BEYOND, weighted,
                                                               AlphaComplex.betti)
    counts = ac.signatures().counts_at(np.inf)
    np.testing.assert_array_equal(counts, ac.signatures().counts_at(BEYOND))


def same_shape(a, b, dim: int) -> None:
    np.testing.assert_array_equal(sorted_rows(a.regular_facets), sorted_rows(b.regular_facets))
    np.testing.assert_array_equal(sorted_rows(a.cells), sorted_rows(b.cells))
    for k in range(dim):
        np.testing.assert_array_equal(sorted_rows(a.singular(k)), sorted_rows(b.singular(k)))
    assert a.measure == b.measure


@pytest.mark.parametrize(("dim", "weighted"), CASES)
def test_inf_shape_and_cursor_are_the_hull(dim, weighted):
    ac = complex_of(dim, weighted)
    inf = at(ac, np.inf, weighted, AlphaComplex.shape)
    big = at(ac, BEYOND, weighted, AlphaComplex.shape)
    same_shape(inf, big, dim)
    hull = ConvexHull(ac.points)
    assert inf.measure == pytest.approx(hull.volume, rel=1e-12)
    np.testing.assert_array_equal(sorted_rows(inf.regular_facets), sorted_rows(hull.simplices))
    cursor = ac.cursor()
    middle = float(ac.spectrum()[len(ac.spectrum()) // 2])
    for value in (np.inf, middle, np.inf, BEYOND, np.inf, np.inf, middle):  # fresh, down, up
        moved = at(cursor, value, weighted, type(cursor).move)
        same_shape(moved, at(ac, value, weighted, AlphaComplex.shape), dim)


def test_inf_surface_export_is_the_closed_hull(tmp_path):
    ac = complex_of(3, False)
    vertices, faces, _ = surface_arrays(ac, ac.shape(np.inf), manifold=True)
    corners = vertices[faces]
    volume = np.einsum("ij,ij->i", corners[:, 0], np.cross(corners[:, 1], corners[:, 2])).sum() / 6
    assert volume == pytest.approx(ConvexHull(ac.points).volume, rel=1e-12)  # outward, closed
    report = write_shape(ac, np.inf, tmp_path / "hull.ply")
    assert report.closed and report.n_faces == len(ConvexHull(ac.points).simplices)
    big = write_shape(ac, BEYOND, tmp_path / "big.ply")
    assert (report.n_vertices, report.n_faces, report.measure) == (
        big.n_vertices, big.n_faces, big.measure)


@pytest.mark.parametrize("weighted", [False, True])
def test_inf_geojson_is_the_hull_polygon(tmp_path, weighted):
    ac = complex_of(2, weighted)
    kind = {"alpha2": np.inf} if weighted else {}
    write_shape(ac, None if weighted else np.inf, tmp_path / "inf.geojson", **kind)
    write_shape(ac, None if weighted else BEYOND, tmp_path / "big.geojson",
                **({"alpha2": BEYOND**2} if weighted else {}))

    def refuse(name):
        raise ValueError(f"{name} is not JSON")

    docs = [json.loads((tmp_path / f"{n}.geojson").read_text(), parse_constant=refuse)
            for n in ("inf", "big")]
    shapes = [shapely.geometry.shape(d["features"][0]["geometry"]) for d in docs]
    hull = shapely.Polygon(ac.points[ConvexHull(ac.points).vertices])
    assert shapes[0].equals(hull) and shapes[0].equals(shapes[1])
    assert shapes[0].area == pytest.approx(hull.area, rel=1e-12)
    assert docs[0]["features"][0]["properties"]["alpha"] is None  # JSON has no infinity


def test_cli_refuses_infinite_alpha_in_one_line(capsys, tmp_path):
    source = tmp_path / "p.xyz"
    np.savetxt(source, np.random.default_rng(0).random((20, 3)))
    code = main(["export", str(source), "-o", str(tmp_path / "o.ply"), "--alpha", "inf"])
    out, err = capsys.readouterr()
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1
    assert "finite" in err and not (tmp_path / "o.ply").exists()

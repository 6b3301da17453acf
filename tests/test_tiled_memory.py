"""Tiled shapes equal the in-memory ones simplex for simplex (core.tiled, in memory)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from core import AlphaComplex
from core.build.points import canonical_order
from core.io import read_points
from core.tiled import tiled_shape
from core.tiled.memory import plan_for, prepared
from core.tiled.plan import TilePlan, margin_for
from tests.tiled_reference import differences, mid_gap_alpha

SHARED = Path(__file__).resolve().parents[2] / "shared" / "data"
SHARED = SHARED if SHARED.is_dir() else Path("/work/shared/data")
CORPUS = Path(__file__).parent / "data" / "corpus"


def same(points, at: dict, weights=None, **options):
    """The tiled shape, after checking it against the in-memory complex at `at`."""
    ac = AlphaComplex.from_points(points, weights=weights)
    tiled = tiled_shape(points, weights=weights, **at, **options)
    assert differences(ac, tiled, at) == []
    shape = ac.shape(**at)
    assert tiled.measure == pytest.approx(shape.measure, rel=1e-9, abs=1e-12)
    assert tiled.components == ac.betti(**at)[0]
    assert tiled.boundary_measure == pytest.approx(boundary(ac, shape), rel=1e-9, abs=1e-12)
    return tiled


def boundary(ac, shape) -> float:
    """Area (3D) or length (2D) of the in-memory shape's REGULAR facets."""
    p = np.asarray(ac.points)[np.asarray(shape.regular_facets)]
    if ac.dim == 2:
        return float(np.linalg.norm(p[:, 1] - p[:, 0], axis=1).sum())
    return float(0.5 * np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]),
                                      axis=1).sum())


def grid(n: int, dim: int) -> np.ndarray:
    """A lattice of n^dim points (cospherical everywhere: the ties test)."""
    axes = np.meshgrid(*[np.arange(n)] * dim, indexing="ij")
    return np.stack(axes, -1).reshape(-1, dim).astype(np.float64)


@pytest.mark.parametrize("dim, alpha", [(2, 0.02), (3, 0.06)])
def test_random_points_many_seams(dim, alpha):
    points = np.random.default_rng(3).random((2500, dim))
    tiled = same(points, {"alpha": alpha}, tile_points=150)
    assert tiled.n_tiles >= 16


@pytest.mark.parametrize("dim, alpha", [(2, 0.75), (3, 0.9)])
def test_lattice_ties_resolved_alike(dim, alpha):
    """Cospherical lattice points: the tiles pick the same triangulation as the whole set
    (the perturbation's weights are a hash of the point, not of its position)."""
    same(grid(24 if dim == 2 else 7, dim), {"alpha": alpha}, tile_points=50)


def test_points_exactly_on_tile_boundaries():
    points = grid(24, 2)  # tile side 4: every fourth row and column on a tile boundary
    at = {"alpha": 0.8}
    plan = TilePlan((0.0, 0.0), 4.0, (6, 6), margin_for(0.64))
    tiled = same(points, at, plan=plan)
    assert tiled.n_tiles == 36


def test_margin_of_two_alpha_is_needed():
    """At the margin 2 alpha (+ slack) the union is exact; at 1 alpha it is not."""
    points = np.random.default_rng(5).random((3000, 3))
    at = {"alpha": 0.07}
    ac = AlphaComplex.from_points(points)
    coords = prepared(points)[0]
    exact = plan_for(coords, margin_for(0.07**2), 200, None)
    assert differences(ac, tiled_shape(points, **at, plan=exact), at) == []
    short = TilePlan(exact.origin, exact.side, exact.shape, 0.07)
    assert differences(ac, tiled_shape(points, **at, plan=short), at) != []


@pytest.mark.parametrize("at", [{"alpha2": 0.002}, {"alpha2": -0.0002}, {"alpha": 0.03}])
def test_weighted_points(at):
    rng = np.random.default_rng(7)
    points = rng.random((2500, 3))
    weights = rng.random(2500) * 1e-3
    same(points, at, weights=weights, tile_points=200)


def test_duplicates_and_flat_tiles():
    """Repeated rows (the first row is the global id) and tiles whose points all lie on
    one plane inside a 3D set (classes as in 3D: nothing interior)."""
    rng = np.random.default_rng(11)
    flat = np.column_stack([rng.random((1500, 2)) * 4, np.zeros(1500)])
    bump = np.column_stack([rng.random((300, 2)) * 0.5, 0.2 + 0.1 * rng.random(300)])
    points = np.concatenate([flat, bump, flat[:400]])
    same(points, {"alpha": 0.12}, tile_points=150)


def test_planar_3d_input_projected_once():
    rng = np.random.default_rng(13)
    uv = rng.random((2000, 2))
    points = np.column_stack([uv, uv @ [0.3, -0.2] + 1.0])
    tiled = same(points, {"alpha": 0.03}, tile_points=150)
    assert tiled.dim == 2 and tiled.ambient_dim == 3 and tiled.frame is not None


def real(path: Path) -> np.ndarray:
    """The points of a real file as the CLI reads them."""
    if not path.exists():
        pytest.skip(f"{path} is not here")
    return read_points(path).points


def cropped(points: np.ndarray, share: float) -> np.ndarray:
    """The part of a real scan below the `share` quantile of its first coordinate: a
    contiguous piece of it, with its real spacing, noise and edges."""
    return points[points[:, 0] <= np.quantile(points[:, 0], share)]


@pytest.mark.slow
@pytest.mark.parametrize("name, share, quantile, tile_points", [
    ("bunny.ply", 0.4, 0.6, 1500), ("milk.pcd", 0.5, 0.7, 700),
    ("us_airports.csv", 1.0, 0.8, 300)])
def test_real_scans(name, share, quantile, tile_points):
    """Pieces of real scans (3D surfaces, a 2D geographic set) in many small tiles; the
    lattice scan plane_flat.laz is in test_lattice_scan_ties_round_alike."""
    points = cropped(real(SHARED / name), share)
    alpha = mid_gap_alpha(AlphaComplex.from_points(points), quantile)
    tiled = same(points, {"alpha": alpha}, tile_points=tile_points)
    assert tiled.n_tiles >= 4


def test_lattice_scan_ties_round_alike():
    """A 0.8 m square of plane_flat.laz (a 1 cm lattice: many congruent cells, whose radii
    are equal up to rounding) at an alpha between two roundings of one radius: a tile
    numbers a cell's vertices in the same order as the whole set
    (core.build.points.canonical_order), so its radius rounds alike and the cell is on the
    same side of alpha (numbered by the set's box, 1 to 2 cells differed here)."""
    points = real(SHARED / "plane_flat.laz")
    centre = np.array([1423216.1425, 4189098.205])  # between two cells of one radius
    piece = points[np.all(np.abs(points[:, :2] - centre) <= 0.4, axis=1)]
    for tile_points in (300, 600, 1200):
        tiled = same(piece, {"alpha": 0.030686587533434066}, tile_points=tile_points)
        assert tiled.n_tiles >= 4  # the piece is split: cells are numbered tile by tile


def test_canonical_order_of_a_subset_is_the_sets():
    """Two points are ordered by their own coordinates: any subset keeps the set's order
    (the bounding box of the set, or of a tile, changes nothing)."""
    rng = np.random.default_rng(21)
    points = np.unique(np.round(rng.normal(size=(20_000, 3)) * [1.0, 1e-3, 1e5], 2), axis=0)
    points += [1.4e6, -4.1e6, 0.0]
    rank = np.empty(len(points), dtype=np.int64)
    rank[canonical_order(points)] = np.arange(len(points))
    for size in (5, 700, 9000):
        subset = rng.choice(len(points), size, replace=False)
        assert np.all(np.diff(rank[subset][canonical_order(points[subset])]) > 0)


@pytest.mark.parametrize("name", ["las/pdal_autzen_point_format_3.las",
                                  "text/pdal_bunny_8.pts", "ply/pdal_simple_binary.ply"])
def test_corpus_files(name):
    points = real(CORPUS / name)
    alpha = mid_gap_alpha(AlphaComplex.from_points(points), 0.6)
    same(points, {"alpha": alpha}, tile_points=max(50, len(points) // 12))

"""What each mode is for, on small made-up sets: density scaling fills a sparse part without
joining it to a dense neighbour; anisotropy keeps close parallel sheets apart while each is
closed; on the real scans both modes build and split no less than classic alpha."""

from __future__ import annotations

import numpy as np
import pytest
from reference import DATA_ABSENT, assert_valid_table, data_dir, read_scan
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from core import AlphaComplex


def _jittered_grid(step: float, size: float, rng) -> np.ndarray:
    """(n, 2) grid over [0, size]² moved by up to a quarter step."""
    axis = np.arange(0.0, size + 1e-9, step)
    grid = np.stack(np.meshgrid(axis, axis), axis=-1).reshape(-1, 2)
    return grid + rng.uniform(-0.25 * step, 0.25 * step, grid.shape)


def _disk(step: float, centre: tuple, rng) -> np.ndarray:
    grid = _jittered_grid(step, 2.0, rng) - 1.0
    return grid[(grid**2).sum(axis=1) <= 1.0] + np.asarray(centre)


def _covered_from(ac, k: int) -> float:
    """Smallest alpha at which every point is a vertex of some k-simplex of the complex."""
    first = np.full(len(ac.points), np.inf)
    for column in ac.simplices(k).T:
        np.minimum.at(first, column, ac.intervals(k)[:, 0])
    return float(first.max())


def _alphas_where(ac, betti: tuple, solid: int | None, covered_k: int) -> np.ndarray:
    """Critical alphas at which every point is covered and the Betti numbers (and solid
    components) are as given."""
    sig = ac.signatures()
    ok = (sig.alphas >= _covered_from(ac, covered_k)) & (sig.betti == betti).all(axis=1)
    if solid is not None:
        ok &= sig.solid_components == solid
    return sig.alphas[ok]


def test_density_scaling_fills_a_sparse_disk_without_joining_a_dense_one():
    rng = np.random.default_rng(3)
    dense, sparse = _disk(0.04, (0.0, 0.0), rng), _disk(0.25, (2.2, 0.0), rng)
    points = np.vstack([dense, sparse])
    classic = AlphaComplex.from_points(points)
    assert len(_alphas_where(classic, (2, 0), 2, 2)) == 0  # never two solid disks apart
    scaled = AlphaComplex.from_points(points, density=8)
    good = _alphas_where(scaled, (2, 0), 2, 2)
    assert len(good) > 0
    shape = scaled.shape(good[0])  # both disks solid: every point in a triangle, no holes
    assert scaled.betti(good[0]) == (2, 0)
    assert np.isin(np.arange(len(points)), shape.cells).all()


def _sheets(rng, size: int = 12, gap: float = 0.5, noise: float = 0.02) -> np.ndarray:
    """Two jittered unit-spacing sheets `gap` apart (closer than their spacing), noisy in z."""
    lower, upper = _jittered_grid(1.0, size, rng), _jittered_grid(1.0, size, rng)
    return np.vstack([np.column_stack([lower, rng.normal(0, noise, len(lower))]),
                      np.column_stack([upper, gap + rng.normal(0, noise, len(upper))])])


@pytest.mark.parametrize("seed", [0, 1])
@pytest.mark.parametrize("given_normals", [False, True])
def test_anisotropy_keeps_close_parallel_sheets_apart(seed, given_normals):
    points = _sheets(np.random.default_rng(seed))
    classic = AlphaComplex.from_points(points)
    assert len(_alphas_where(classic, (2, 0, 0), None, 2)) == 0  # closed sheets are joined
    normals = np.tile([0.0, 0.0, 1.0], (len(points), 1)) if given_normals else None
    ac = AlphaComplex.from_points(points, anisotropy=0.9, normals=normals)
    good = _alphas_where(ac, (2, 0, 0), None, 2)
    assert len(good) > 0
    alpha = good[0]
    lower = ac.points[:, 2] < 0.25
    edges = ac.simplices(1)[: np.searchsorted(ac.intervals(1)[:, 0], alpha, "right")]
    assert (lower[edges[:, 0]] == lower[edges[:, 1]]).all()  # no edge between the sheets


def _point_clusters(points: np.ndarray, k: int = 8) -> np.ndarray:
    """(n,) label of each point's component in the symmetric k-nearest-neighbour graph."""
    _, ids = cKDTree(points).query(points, k=k + 1)
    rows = np.repeat(np.arange(len(points)), k)
    graph = coo_matrix((np.ones(len(rows)), (rows, ids[:, 1:].ravel())), shape=(len(points),) * 2)
    return connected_components(graph, directed=False)[1]


def _solid_per_cluster(ac, alpha: float, clusters: np.ndarray) -> np.ndarray:
    """(c,) number of solid components (cells joined through facets) touching each cluster."""
    n_cells = int(np.searchsorted(ac.intervals(ac.dim)[:, 0], alpha, "right"))
    fc = ac.facet_cells()
    inner = (fc[:, 1] >= 0) & (fc[:, 1] < n_cells) & (fc[:, 0] < n_cells)
    graph = coo_matrix((np.ones(inner.sum()), (fc[inner, 0], fc[inner, 1])),
                       shape=(n_cells, n_cells))
    solid = connected_components(graph, directed=False)[1]
    cells = ac.simplices(ac.dim)[:n_cells]
    pairs = np.unique(np.stack([clusters[cells[:, 0]], solid]), axis=1)
    return np.bincount(pairs[0], minlength=clusters.max() + 1)


SCANS = ["bunny.ply", "milk.pcd", "bun000_rangegrid.ply", "plane_flat.laz", "us_airports.csv"]


@pytest.mark.slow
@pytest.mark.parametrize("name", SCANS)
def test_modes_on_real_scans(name):
    folder = data_dir()
    if folder is None:
        pytest.skip(DATA_ABSENT)
    points = read_scan(folder / name)
    classic = AlphaComplex.from_points(points)
    clusters = _point_clusters(classic.points)
    base = _solid_per_cluster(classic, classic.optimal_alpha(), clusters)
    for kwargs in (dict(density=8), dict(anisotropy=0.5)):
        ac = AlphaComplex.from_points(points, **kwargs)
        assert_valid_table(ac)
        assert np.array_equal(ac.points, classic.points)
        got = _solid_per_cluster(ac, ac.optimal_alpha(), clusters)
        assert (got >= base).all()

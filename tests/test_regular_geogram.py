"""geogram's regular triangulation (core.backends.geogram, compiled at install from the vendored
sources) against Qhull's (core.build.delaunay.regular_cells) and brute force: the same cells and
neighbours on random weighted sets and a molecule, valid triangulations of degenerate input,
the same tables through the pipeline, and the fallback to Qhull where the library is missing.
In CI the library must be built: a skip for its absence fails the run (tests/skip_guard.py)."""

from __future__ import annotations

import threading

import numpy as np
import pytest
from reference import shared_file
from scipy.spatial import ConvexHull
from test_weighted_gudhi import assert_matches_gudhi, spacing_weights
from test_weighted_table import assert_same_table
from weighted_reference import gudhi_weighted_table

from core import AlphaComplex, backends
from core.backends import geogram
from core.build.delaunay import regular_cells
from core.errors import InputError

NOT_BUILT = ("geogram's library (core.backends._geogram) was not built: no C++ compiler at "
             "install; weighted builds fall back to Qhull")
needs_geogram = pytest.mark.skipif(not geogram.available(), reason=NOT_BUILT)
pytestmark = needs_geogram


def rows(cells: np.ndarray) -> set[tuple[int, ...]]:
    """The cells as a set of sorted vertex tuples."""
    return set(map(tuple, np.sort(cells, axis=1).tolist()))


def adjacency(cells: np.ndarray, neighbors: np.ndarray) -> set[tuple]:
    """{(cell, vertex left out, cell across or None)} with cells as sorted vertex tuples."""
    keys = [tuple(r) for r in np.sort(cells, axis=1).tolist()]
    order = np.argsort(cells, axis=1)
    out = set()
    for c, key in enumerate(keys):
        for slot in order[c]:
            across = int(neighbors[c, slot])
            out.add((key, int(cells[c, slot]), None if across < 0 else keys[across]))
    return out


def assert_valid_neighbours(cells: np.ndarray, neighbors: np.ndarray) -> None:
    """Rows ascending; neighbour i shares every vertex but i and points back; each facet
    with no neighbour is in one cell only (the hull)."""
    assert cells.dtype == neighbors.dtype == np.int32
    assert np.all(np.diff(cells, axis=1) > 0)
    width = cells.shape[1]
    facets: dict[tuple, int] = {}
    for c in range(len(cells)):
        for i in range(width):
            facet = tuple(np.delete(cells[c], i))
            facets[facet] = facets.get(facet, 0) + 1
            u = neighbors[c, i]
            if u < 0:
                continue
            assert set(facet) <= set(cells[u].tolist())
            assert c in neighbors[u]
    hull = {f for c in range(len(cells)) for i in range(width) if neighbors[c, i] < 0
            for f in [tuple(np.delete(cells[c], i))]}
    assert all(facets[f] == 1 for f in hull)
    assert all(n == 2 for f, n in facets.items() if f not in hull)


def assert_same_as_qhull(points: np.ndarray, weights: np.ndarray) -> None:
    cells, neighbors = geogram.regular_cells(points, weights)
    q_cells, q_neighbors = regular_cells(points, weights)
    assert rows(cells) == rows(q_cells)
    assert adjacency(cells, neighbors) == adjacency(q_cells, q_neighbors)
    assert_valid_neighbours(cells, neighbors)


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize(("n", "top"), [(5, 0.5), (60, 1.0), (2000, 0.5), (2000, 4.0)])
def test_cells_and_neighbours_equal_qhulls(dim: int, n: int, top: float) -> None:
    rng = np.random.default_rng(10 * dim + n + int(top))
    points = rng.random((n, dim)) - 0.5
    weights = spacing_weights(rng, points, top)
    assert_same_as_qhull(points, weights)
    if top > 1:  # heavy balls hide others: the same points are in no cell
        hidden = np.setdiff1d(np.arange(n), geogram.regular_cells(points, weights)[0])
        assert len(hidden) > n // 20
        assert np.array_equal(hidden, np.setdiff1d(np.arange(n), regular_cells(points,
                                                                               weights)[0]))


@pytest.mark.parametrize("dim", [2, 3])
def test_fewest_points(dim: int) -> None:
    """d + 1 points (one cell, where Qhull's lifted hull is flat and fails) and d + 2."""
    rng = np.random.default_rng(3)
    cells, neighbors = geogram.regular_cells(rng.random((dim + 1, dim)), rng.random(dim + 1) * 0.01)
    assert cells.tolist() == [list(range(dim + 1))] and np.all(neighbors == -1)
    points = rng.random((dim + 2, dim))
    assert_same_as_qhull(points, rng.random(dim + 2) * 0.01)


def molecule_centres_weights(probe: float = 1.4) -> tuple[np.ndarray, np.ndarray]:
    """1A8O's atoms as the pipeline hands them to the triangulator: centred, divided by a
    power of two, weights (radius + probe)² likewise."""
    from core.io.molecule import read_molecule
    from core.pipeline import power_of_two_scale

    mol = read_molecule(shared_file("1A8O.pdb"))
    centres = mol.centres - 0.5 * (mol.centres.min(0) + mol.centres.max(0))
    scale = power_of_two_scale(centres)
    return centres / scale, (mol.vdw_radii + probe) ** 2 / scale**2


@pytest.mark.parametrize("probe", [0.0, 1.4])
def test_molecule_cells_equal_qhulls(probe: float) -> None:
    assert_same_as_qhull(*molecule_centres_weights(probe))


def test_molecule_table_equals_qhulls_bit_for_bit() -> None:
    from core.io.molecule import read_molecule

    mol = read_molecule(shared_file("1A8O.pdb"))
    weights = (mol.vdw_radii + 1.4) ** 2
    ours = AlphaComplex.from_points(mol.centres, weights=weights)
    assert ours.build_info.backend == "geogram"
    assert_same_table(ours, AlphaComplex.from_points(mol.centres, weights=weights,
                                                     backend="qhull"))


@pytest.mark.parametrize("dim", [2, 3])
def test_tables_equal_qhulls_and_gudhis(dim: int) -> None:
    rng = np.random.default_rng(50 + dim)
    points = rng.random((1500, dim)) * 40 + 7
    weights = spacing_weights(rng, points, 2.0)
    ours = AlphaComplex.from_points(points, weights=weights)
    by_qhull = AlphaComplex.from_points(points, weights=weights, backend="qhull")
    assert (ours.build_info.backend, by_qhull.build_info.backend) == ("geogram", "qhull")
    assert_same_table(ours, by_qhull)
    assert_matches_gudhi(ours, gudhi_weighted_table(points, weights), len(points))


def power_valid(points: np.ndarray, weights: np.ndarray, cells: np.ndarray) -> bool:
    """Every cell's orthosphere has no point with a smaller power than its vertices (up to
    rounding): a regular triangulation, by brute force over all points."""
    p0 = points[cells[:, 0]]
    edges = points[cells[:, 1:]] - p0[:, None]
    rhs = 0.5 * (np.einsum("nid,nid->ni", edges, edges) - (weights[cells[:, 1:]]
                                                            - weights[cells[:, :1]]))
    centre = np.linalg.solve(edges, rhs[..., None])[..., 0] + p0
    size = np.einsum("nd,nd->n", centre - p0, centre - p0) - weights[cells[:, 0]]
    power = ((centre[:, None, :] - points[None]) ** 2).sum(-1) - weights[None] - size[:, None]
    scale = np.abs(points).max() ** 2 + np.abs(weights).max()
    return bool(np.all(power >= -1e-9 * scale))


def covers_hull(points: np.ndarray, cells: np.ndarray) -> bool:
    """The cells' volumes add up to the convex hull's, none of them flat."""
    edges = points[cells[:, 1:]] - points[cells[:, :1]]
    volumes = np.abs(np.linalg.det(edges))
    fact = 6.0 if points.shape[1] == 3 else 2.0
    return bool(volumes.min() > 0 and np.isclose(volumes.sum() / fact,
                                                 ConvexHull(points).volume, rtol=1e-12))


def grid(k: int, dim: int) -> np.ndarray:
    axes = np.meshgrid(*[np.arange(float(k))] * dim, indexing="ij")
    return np.column_stack([a.ravel() for a in axes])


DEGENERATE = {
    "grid, equal weights": lambda dim: (grid(5, dim), np.full(5**dim, 0.1)),
    "grid, two weights": lambda dim: (grid(5, dim), np.tile([0.0, 0.25], 5**dim)[:5**dim]),
    "cospherical, equal weights": lambda dim: (
        np.vstack([sphere(40, dim), np.zeros((1, dim))]), np.zeros(41)),
    "coplanar layers": lambda dim: (layers(dim), np.zeros(len(layers(dim)))),
}


def sphere(n: int, dim: int) -> np.ndarray:
    """n points exactly on the unit sphere (Pythagorean-style rational directions)."""
    rng = np.random.default_rng(1)
    raw = rng.integers(-9, 10, (4 * n, dim)).astype(float)
    raw = raw[np.einsum("nd,nd->n", raw, raw) > 0]
    if dim == 2:  # (a² - b², 2ab) / (a² + b²): exact to rounding, on one circle
        a, b = raw[:, 0], raw[:, 1]
        pts = np.column_stack([a * a - b * b, 2 * a * b]) / (a * a + b * b)[:, None]
    else:
        a, b, c = raw.T
        s = a * a + b * b + c * c
        pts = np.column_stack([2 * a * c, 2 * b * c, a * a + b * b - c * c]) / s[:, None]
    return np.unique(pts, axis=0)[:n]


def layers(dim: int) -> np.ndarray:
    """Random points on three parallel lines or planes."""
    rng = np.random.default_rng(2)
    pts = rng.random((90, dim))
    pts[:, -1] = np.repeat([0.0, 0.5, 1.0], 30)
    return pts


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("name", sorted(DEGENERATE))
def test_degenerate_input_gives_a_valid_regular_triangulation(name: str, dim: int) -> None:
    """Ties (co-orthospherical groups): geogram's symbolic perturbation picks one regular
    triangulation, no flat cell, covering the hull, every orthosphere empty; where Qhull
    picks another, both are regular triangulations of the same points."""
    points, weights = DEGENERATE[name](dim)
    points = points - 0.5 * (points.min(0) + points.max(0))
    points /= np.abs(points).max()
    cells, neighbors = geogram.regular_cells(points, weights)
    assert_valid_neighbours(cells, neighbors)
    assert covers_hull(points, cells)
    assert power_valid(points, weights, cells)


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("values", [(0.0, 0.25), (0.0, 0.05, 0.2)])
def test_degenerate_lattice_tables_have_gudhis_betti_numbers_and_measures(dim: int,
                                                                          values) -> None:
    """Exact lattices with a few weight values are degenerate (co-orthospherical groups): the
    triangulation is one of several, the complex at every alpha is not: its measure and all
    its Betti numbers are gudhi's. (Qhull's lifted hull leaves flat cells in such groups
    and its tables showed voids that are not there.)"""
    from reference import simplex_measures
    from test_weighted_gudhi import between_values
    from weighted_reference import gudhi_betti

    points = grid(5, dim) * 0.75 - 1.0
    weights = np.random.default_rng(0).choice(values, len(points))
    ours = AlphaComplex.from_points(points, weights=weights)
    assert ours.build_info.backend == "geogram"
    ref = gudhi_weighted_table(points, weights)
    at = between_values(ref)
    cells, enter = ref[dim][0], ref[dim][1]
    theirs = [simplex_measures(points, cells[enter <= a]).sum() for a in at]
    np.testing.assert_allclose([ours.shape(alpha2=float(a)).measure for a in at], theirs,
                               rtol=1e-12, atol=1e-12)
    np.testing.assert_array_equal([ours.betti(alpha2=float(a)) for a in at],
                                  gudhi_betti(ref["st"], dim, at))


def test_duplicates_with_different_weights_keep_the_heaviest() -> None:
    rng = np.random.default_rng(4)
    points = rng.random((300, 3))
    weights = spacing_weights(rng, points, 0.5)
    twins = np.vstack([points, points[:50]])
    twin_weights = np.concatenate([weights, weights[:50] * 0.5])
    cells, _ = geogram.regular_cells(twins, twin_weights)
    assert not np.isin(np.arange(300, 350), cells).any()
    assert_same_as_qhull(twins, twin_weights)
    ours = AlphaComplex.from_points(twins, weights=twin_weights)
    assert np.all(ours.input_index[300:] < 0)
    assert_same_table(ours, AlphaComplex.from_points(twins, weights=twin_weights,
                                                     backend="qhull"))


@pytest.mark.parametrize("size", [1e-150, 1e90])
def test_huge_and_tiny_coordinates(size: float) -> None:
    """The pipeline scales by a power of two before triangulating: the same table as Qhull's
    at any magnitude."""
    rng = np.random.default_rng(6)
    points = (rng.random((500, 3)) + 3.0) * size
    weights = spacing_weights(rng, points, 1.0)
    ours = AlphaComplex.from_points(points, weights=weights)
    assert ours.build_info.backend == "geogram"
    assert_same_table(ours, AlphaComplex.from_points(points, weights=weights, backend="qhull"))


def test_flat_input_is_an_input_error() -> None:
    rng = np.random.default_rng(7)
    points = np.column_stack([rng.random((30, 2)), np.zeros(30)])
    with pytest.raises(InputError, match="span no cell"):
        geogram.regular_cells(points, rng.random(30) * 0.01)
    with pytest.raises(InputError, match="span no cell"):
        geogram.regular_cells(np.outer(rng.random(20), [1.0, 2.0]), rng.random(20) * 0.01)


def test_same_result_every_call_and_from_two_threads_at_once() -> None:
    """geogram's random insertion order is reset before each call, so the cells come in the
    same order every time, also from two threads at once (each call waits for the other)."""
    rng = np.random.default_rng(8)
    points = rng.random((20_000, 3))
    weights = spacing_weights(rng, points, 1.0)
    first = geogram.regular_cells(points, weights)
    results: list = [None] * 4

    def work(k: int) -> None:
        results[k] = geogram.regular_cells(points, weights)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for cells, neighbors in results:
        assert np.array_equal(cells, first[0]) and np.array_equal(neighbors, first[1])


def test_weighted_builds_fall_back_to_qhull_without_the_library(monkeypatch) -> None:
    rng = np.random.default_rng(9)
    points = rng.random((400, 3))
    weights = spacing_weights(rng, points, 1.0)
    ours = AlphaComplex.from_points(points, weights=weights)
    monkeypatch.setattr(geogram, "_library", lambda: None)
    assert not geogram.available()
    fallback = AlphaComplex.from_points(points, weights=weights)
    assert (fallback.build_info.backend, fallback.build_info.backend_note) == ("qhull", "")
    assert_same_table(ours, fallback)


def test_a_geogram_failure_falls_back_to_qhull_and_says_why(monkeypatch) -> None:
    def failing(points, weights):
        raise geogram.GeogramError("geogram's regular triangulation failed (code 4)")

    monkeypatch.setattr(geogram, "regular_cells", failing)
    rng = np.random.default_rng(10)
    points = rng.random((100, 3))
    tri, choice = backends.regular(points, spacing_weights(rng, points, 1.0))
    assert choice == backends.Choice("qhull", "geogram not used: geogram's regular "
                                              "triangulation failed (code 4)")
    assert len(tri.cells)


def test_more_points_than_geograms_indices_take_fall_back_to_qhull(monkeypatch) -> None:
    monkeypatch.setitem(geogram.MAX_POINTS, 3, 99)
    rng = np.random.default_rng(12)
    points = rng.random((100, 3))
    weights = spacing_weights(rng, points, 1.0)
    tri, choice = backends.regular(points, weights)
    assert choice == backends.Choice(
        "qhull", "geogram not used: 100 points are more than geogram's 32-bit cell arrays "
                 "take (99 at most in 3D)")
    assert len(tri.cells)
    assert backends.regular(points[:99], weights[:99])[1].backend == "geogram"


def test_forced_qhull_uses_qhull() -> None:
    rng = np.random.default_rng(11)
    points = rng.random((100, 3))
    weights = spacing_weights(rng, points, 1.0)
    assert backends.regular(points, weights, "qhull")[1] == backends.Choice("qhull")
    assert backends.regular(points, weights)[1] == backends.Choice("geogram")


def test_loading_the_library_keeps_ctrl_c_a_keyboard_interrupt() -> None:
    """geogram's initialisation resets SIGINT to its default (death); the library puts
    Python's handler back, so Ctrl-C after a weighted build still raises KeyboardInterrupt."""
    import os
    import subprocess
    import sys
    from pathlib import Path

    script = ("import os, signal, time\n"
              "from core.backends import geogram\n"
              "assert geogram.available()\n"
              "try:\n"
              "    os.kill(os.getpid(), signal.SIGINT)\n"
              "    time.sleep(5)\n"
              "except KeyboardInterrupt:\n"
              "    print('interrupted')\n")
    root = Path(__file__).resolve().parent.parent
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        filter(None, (str(root), os.environ.get("PYTHONPATH")))))
    done = subprocess.run([sys.executable, "-c", script], cwd=root, env=env,
                          capture_output=True, text=True, timeout=60)
    assert (done.returncode, done.stdout.strip()) == (0, "interrupted"), done.stderr


@pytest.mark.parametrize("zero", [0.0, -0.0])
def test_a_heavier_twin_later_in_the_input_is_the_one_kept(zero: float) -> None:
    """The heaviest of coincident points is kept wherever it comes in the input, also where
    the twins' coordinates differ only in the sign of a zero (equal numbers): the same cells
    as with twins equal bit for bit."""
    rng = np.random.default_rng(12)
    points = rng.random((300, 3)) + 1.0
    points[:50, 0] = 0.0
    weights = spacing_weights(rng, points, 0.5)
    later = points[:50].copy()
    later[:, 0] = zero
    twins = np.vstack([points, later])
    twin_weights = np.concatenate([weights, weights[:50] * 2.0])
    cells, neighbors = geogram.regular_cells(twins, twin_weights)
    assert not np.isin(np.arange(50), cells).any()
    assert_valid_neighbours(cells, neighbors)
    same = np.vstack([points, points[:50]])
    assert adjacency(cells, neighbors) == adjacency(*geogram.regular_cells(same, twin_weights))


def test_weights_not_one_per_point_are_refused() -> None:
    """The library reads one weight a point: another count is a ValueError, not a read
    past the array."""
    points = np.random.default_rng(13).random((20, 3))
    with pytest.raises(ValueError, match=r"20 points need \(20,\) weights"):
        geogram.regular_cells(points, np.zeros(19))

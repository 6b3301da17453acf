"""Qhull in two halves (core.backends.split): the joined cells are the single Qhull call's
simplex for simplex (classic and weighted, hidden points too), or the build makes that call."""

from __future__ import annotations

import numpy as np
import pytest
from reference import DATA_ABSENT, data_dir, read_scan
from test_backends import CASES, DEGENERATE, cell_set, clustered, lattice, prepared
from weighted_reference import gudhi_weighted_table

import core.backends as backends
import core.backends.split as split
from core import AlphaComplex
from core.build.delaunay import Triangulation, regular_triangulate, triangulate
from core.parallel import unsplit


def assert_same_cells(tri: Triangulation, ref: Triangulation) -> None:
    """Same cells (by vertex rows), same vertices and hidden points, same neighbour across
    every facet."""
    assert np.array_equal(tri.kept, ref.kept)
    assert np.array_equal(tri.vertex_of_point, ref.vertex_of_point)
    assert np.array_equal(cell_set(tri.cells), cell_set(ref.cells))
    ours, theirs = np.lexsort(tri.cells.T[::-1]), np.lexsort(ref.cells.T[::-1])
    row = np.empty(len(ours), dtype=np.int64)
    row[ours] = theirs
    across = np.where(tri.neighbors >= 0, row[np.maximum(tri.neighbors, 0)], -1)
    assert np.array_equal(ref.neighbors[row], across)


def splits_counted(monkeypatch) -> list[str]:
    """Two CPUs as far as split.worth_splitting can tell (a one-CPU machine would never try
    the halves, and a test could not tell that from a split), and the outcome of every
    split_triangulation call the builds make: "split", or the reason it fell back."""
    monkeypatch.setattr(split.os, "sched_getaffinity", lambda pid: {0, 1}, raising=False)
    original, outcomes = split.split_triangulation, []

    def counted(*args, **kwargs):
        tri = original(*args, **kwargs)
        outcomes.append("split" if isinstance(tri, Triangulation) else tri)
        return tri

    monkeypatch.setattr(split, "split_triangulation", counted)
    return outcomes


def split_equals_qhull(points: np.ndarray, weights: np.ndarray | None = None) -> None:
    tri = split.split_triangulation(points, weights)
    assert isinstance(tri, Triangulation), tri
    assert_same_cells(tri, triangulate(points) if weights is None
                      else regular_triangulate(points, weights))


def spacing_weights(rng: np.random.Generator, points: np.ndarray, top: float) -> np.ndarray:
    """Weights from 0 to `top` times each point's squared nearest-neighbour distance (large
    `top` hides many points)."""
    from scipy.spatial import cKDTree

    dist, _ = cKDTree(points).query(points, k=2)
    return rng.uniform(0.0, top, len(points)) * dist[:, 1] ** 2


def on_surface(rng: np.random.Generator, n: int) -> np.ndarray:
    """A noisy sphere surface: every cell is long and thin across the split."""
    p = rng.normal(size=(n, 3))
    return p / np.linalg.norm(p, axis=1)[:, None] * rng.normal(1.0, 0.002, (n, 1))


SPLITTABLE = {
    **CASES,
    "sphere surface 3D": lambda rng: on_surface(rng, 5000),
    "two far clusters 3D": lambda rng: np.concatenate(
        (rng.uniform(size=(2000, 3)), rng.uniform(size=(2000, 3)) + np.array([50.0, 0.0, 0.0]))),
    "equal coordinates at the split 2D": lambda rng: np.concatenate(
        (rng.uniform(size=(3000, 2)), np.column_stack((np.full(400, 0.5),
                                                       rng.uniform(size=400))))),
    "equal coordinates at the split 3D": lambda rng: np.concatenate(
        (rng.uniform(size=(3000, 3)), np.column_stack(
            (np.full(500, 0.5), rng.uniform(size=(500, 2)))))),
}


@pytest.mark.parametrize("name", list(SPLITTABLE))
def test_split_equals_one_qhull_call(name: str) -> None:
    split_equals_qhull(prepared(SPLITTABLE[name](np.random.default_rng(17))))


@pytest.mark.parametrize("d", [2, 3])
@pytest.mark.parametrize(("kind", "top"), [("uniform", 1.0), ("uniform", 4.0),
                                           ("clustered", 2.0)])
def test_weighted_split_equals_one_qhull_call(d: int, kind: str, top: float) -> None:
    rng = np.random.default_rng(d * 10 + int(top))
    points = prepared(rng.uniform(size=(4000, d)) if kind == "uniform"
                      else clustered(rng, 4000, d))
    weights = spacing_weights(rng, points, top)
    split_equals_qhull(points, weights)
    if top >= 4.0:
        assert (regular_triangulate(points, weights).vertex_of_point < 0).sum() > 100


@pytest.mark.slow
@pytest.mark.parametrize("name", ["bunny.ply", "bunny_dupverts.stl", "autzen_trim.las"])
def test_split_equals_one_qhull_call_on_real_scans(name: str) -> None:
    folder = data_dir()
    if folder is None:
        pytest.skip(DATA_ABSENT)
    split_equals_qhull(prepared(read_scan(folder / name)))


@pytest.mark.parametrize("name", list(DEGENERATE))
def test_degenerate_input_falls_back_to_one_call(name: str, monkeypatch) -> None:
    """Lattices, cospherical points, near duplicates: the halves cannot promise the one
    call's cells, so the build makes that call (the reason in the note)."""
    points = prepared(DEGENERATE[name](np.random.default_rng(3)))
    monkeypatch.setattr(backends, "GMSH_FROM_POINTS", 1 << 40)
    monkeypatch.setattr(split, "SPLIT_FROM_POINTS", 0)
    outcomes = splits_counted(monkeypatch)
    tri, choice = backends.delaunay(points, "qhull")
    ref = triangulate(points)
    assert len(outcomes) == 1 and outcomes[0] != "split"  # tried, and it fell back
    assert choice == backends.Choice("qhull", f"not split in two halves: {outcomes[0]}")
    assert np.array_equal(tri.cells, ref.cells)
    assert np.array_equal(tri.neighbors, ref.neighbors)


def test_lattices_fall_back(monkeypatch) -> None:
    """Cospherical groups across the split: no cell there is certainly one of the whole."""
    monkeypatch.setattr(split, "SPLIT_FROM_POINTS", 0)
    for points in (lattice(25, 2), lattice(9, 3)):
        reason = split.split_triangulation(prepared(points))
        assert isinstance(reason, str) and reason
        _, choice = backends.delaunay(prepared(points), "qhull")
        assert choice.note == f"not split in two halves: {reason}"


def test_a_wrong_band_is_caught(monkeypatch) -> None:
    """The check catches a band restored wrongly (one band cell dropped): no silent
    difference, the reason is given."""
    original = split.outside

    def one_short(*args):
        cells = original(*args)
        return cells[1:]

    monkeypatch.setattr(split, "outside", one_short)
    points = prepared(np.random.default_rng(4).uniform(size=(3000, 3)))
    reason = split.split_triangulation(points)
    assert isinstance(reason, str) and reason


def test_too_few_points_are_not_split() -> None:
    assert split.split_triangulation(prepared(np.random.default_rng(0).uniform(
        size=(9, 3)))) == "too few points to split"


@pytest.mark.parametrize("weighted", [False, True])
def test_build_is_the_same_split_or_not(weighted: bool, monkeypatch) -> None:
    """The whole table (classic: after certification) is the same with the split."""
    rng = np.random.default_rng(8)
    points = rng.uniform(size=(3000, 3)) * 20.0 + 3.0
    weights = spacing_weights(rng, points, 3.0) if weighted else None
    backend = "qhull" if weighted else None  # weighted points split with Qhull only
    monkeypatch.setattr(backends, "GMSH_FROM_POINTS", 1 << 40)
    outcomes = splits_counted(monkeypatch)
    whole = AlphaComplex.from_points(points, weights=weights, backend=backend)
    assert outcomes == []  # 3,000 points: one call
    monkeypatch.setattr(split, "SPLIT_FROM_POINTS", 1000)
    halves = AlphaComplex.from_points(points, weights=weights, backend=backend)
    assert outcomes == ["split"] and halves.build_info.backend_note == ""
    assert np.array_equal(whole.input_index, halves.input_index)
    assert whole.counts() == halves.counts()
    for k in range(4):
        (a, ia), (b, ib) = (by_rows(ac.simplices(k), ac.intervals_sq(k))
                            for ac in (whole, halves))
        assert np.array_equal(a, b) and np.array_equal(ia, ib)


def by_rows(simplices: np.ndarray, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Simplices with ascending rows in lexicographic order, their values alongside."""
    rows = np.sort(simplices, axis=1)
    order = np.lexsort(rows.T[::-1])
    return rows[order], values[order]


@pytest.mark.parametrize("d", [2, 3])
def test_weighted_split_build_equals_gudhi(d: int, monkeypatch) -> None:
    """Hidden points and every simplex as gudhi's weighted alpha complex (Qhull's split:
    geogram, where built, triangulates weighted points in one call)."""
    from test_weighted_gudhi import assert_matches_gudhi

    rng = np.random.default_rng(30 + d)
    points = rng.uniform(size=(3000, d))
    weights = spacing_weights(rng, points, 3.0)
    monkeypatch.setattr(split, "SPLIT_FROM_POINTS", 1000)
    outcomes = splits_counted(monkeypatch)
    ac = AlphaComplex.from_points(points, weights=weights, backend="qhull")
    assert outcomes == ["split"] and ac.build_info.backend_note == ""
    assert (np.asarray(ac.input_index) < 0).sum() > 50
    assert_matches_gudhi(ac, gudhi_weighted_table(points, weights), len(points))


@pytest.mark.parametrize("d", [2, 3])
def test_weighted_certification_tells_regular_from_delaunay(d: int) -> None:
    """core.backends.certify with weights: Qhull's regular triangulation passes; the
    Delaunay triangulation of the same points (not regular for these weights) does not."""
    from core.backends.certify import why_not_delaunay
    from core.build.delaunay import delaunay_cells, regular_cells

    rng = np.random.default_rng(40 + d)
    points = prepared(rng.uniform(size=(800, d)))
    weights = spacing_weights(rng, points, 2.0)
    cells, nbrs = regular_cells(points, weights)
    hidden = np.ones(len(points), dtype=bool)
    hidden[cells.ravel()] = False
    assert hidden.any()
    assert why_not_delaunay(points, cells, nbrs, weights=weights, hidden=hidden) == ""
    plain, around = delaunay_cells(points)
    assert why_not_delaunay(points, plain, around, weights=weights) != ""
    assert why_not_delaunay(points, plain, around) == ""


def test_one_cpu_never_splits(monkeypatch) -> None:
    monkeypatch.setattr(split.os, "sched_getaffinity", lambda pid: {0}, raising=False)
    assert not split.worth_splitting(10 * split.SPLIT_FROM_POINTS)
    monkeypatch.setattr(split.os, "sched_getaffinity", lambda pid: {0, 1}, raising=False)
    assert split.worth_splitting(split.SPLIT_FROM_POINTS)
    assert not split.worth_splitting(split.SPLIT_FROM_POINTS - 1)


def test_an_unsplit_job_never_splits(monkeypatch) -> None:
    """A job beside others (a tile on a worker: core.parallel.unsplit) takes no second core,
    so it triangulates in one call whatever its size."""
    monkeypatch.setattr(split.os, "sched_getaffinity", lambda pid: {0, 1}, raising=False)
    assert split.worth_splitting(10 * split.GMSH_SPLIT_FROM_POINTS, "gmsh")
    for backend in ("qhull", "gmsh"):
        assert not unsplit(lambda b=backend: split.worth_splitting(
            10 * split.GMSH_SPLIT_FROM_POINTS, b))

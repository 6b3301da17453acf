"""Triangulation backends (core.backends): gmsh's cells, completed near the hull, are exactly
Qhull's simplex for simplex, or the build falls back to Qhull (automatic) or refuses (forced)."""

from __future__ import annotations

import ctypes
import os
import signal
import threading
from pathlib import Path

import numpy as np
import pytest
from reference import DATA_ABSENT, data_dir, read_scan

import core.backends as backends
from benchmarks.datasets import noisy_torus
from core import parallel
from core.backends import facets, geogram
from core.backends.certify import why_not_delaunay
from core.backends.facets import neighbours
from core.build.delaunay import triangulate
from core.build.points import check_spread, merge_duplicates, spatial_order
from core.errors import InputError

needs_gmsh = pytest.mark.skipif(not backends.gmsh_backend.installed(),
                                reason="the optional gmsh package is not installed")


def prepared(raw: np.ndarray) -> np.ndarray:
    """Points as the build hands them to a backend: distinct, planar 3D in 2D, spatially
    ordered, centred and scaled by a power of two."""
    unique, _ = merge_duplicates(np.asarray(raw, dtype=np.float64))
    frame = check_spread(unique)
    coords = unique if frame is None else (unique - frame.origin) @ frame.basis.T
    coords = coords[spatial_order(coords)]
    coords = coords - 0.5 * (coords.min(axis=0) + coords.max(axis=0))
    return coords / 2.0 ** np.floor(np.log2(np.abs(coords).max()))


def cell_set(cells: np.ndarray) -> np.ndarray:
    """Rows sorted lexicographically (cells' rows are ascending already)."""
    return cells[np.lexsort(cells.T[::-1])]


def assert_same_as_qhull(points: np.ndarray) -> None:
    tri, choice = backends.delaunay(points, "gmsh")
    ref = triangulate(points)
    assert choice == backends.Choice("gmsh")
    assert np.array_equal(cell_set(tri.cells), cell_set(ref.cells))
    assert np.array_equal(tri.vertex_of_point, ref.vertex_of_point)
    assert np.array_equal(tri.kept, ref.kept)
    # the same cell across the same facet: map our cells to Qhull's rows
    ours, theirs = np.lexsort(tri.cells.T[::-1]), np.lexsort(ref.cells.T[::-1])
    row = np.empty(len(ours), dtype=np.int64)
    row[ours] = theirs
    across = np.where(tri.neighbors >= 0, row[np.maximum(tri.neighbors, 0)], -1)
    assert np.array_equal(ref.neighbors[row], across)


def clustered(rng: np.random.Generator, n: int, d: int) -> np.ndarray:
    centres = rng.uniform(size=(8, d))
    return np.concatenate([rng.normal(c, 0.01, size=(n // 8, d)) for c in centres])


CASES = {
    "uniform 3D": lambda rng: rng.uniform(size=(4000, 3)),
    "clustered 3D": lambda rng: clustered(rng, 4000, 3),
    "noisy torus 3D": lambda rng: noisy_torus(5000, 3),
    "uniform 2D": lambda rng: rng.uniform(size=(6000, 2)),
    "clustered 2D": lambda rng: clustered(rng, 6000, 2),
    "noisy circle 2D": lambda rng: np.column_stack(
        (np.cos(t := rng.uniform(0, 2 * np.pi, 5000)), np.sin(t))) * rng.normal(1, 0.003,
                                                                              (5000, 1)),
    "planar in 3D": lambda rng: np.column_stack(
        (rng.uniform(size=(3000, 2)), np.zeros(3000))) @ np.linalg.qr(
            rng.normal(size=(3, 3)))[0],
}


@needs_gmsh
@pytest.mark.parametrize("name", list(CASES))
def test_gmsh_equals_qhull(name: str) -> None:
    assert_same_as_qhull(prepared(CASES[name](np.random.default_rng(7))))


@needs_gmsh
@pytest.mark.slow
@pytest.mark.parametrize("name", ["bunny.ply", "bunny_dupverts.stl", "autzen_trim.las"])
def test_gmsh_equals_qhull_on_real_scans(name: str) -> None:
    folder = data_dir()
    if folder is None:
        pytest.skip(DATA_ABSENT)
    assert_same_as_qhull(prepared(read_scan(folder / name)))


def lattice(n: int, d: int) -> np.ndarray:
    return np.stack(np.meshgrid(*[np.arange(float(n))] * d), axis=-1).reshape(-1, d)


def on_sphere(rng: np.random.Generator, n: int, d: int) -> np.ndarray:
    p = rng.normal(size=(n, d))
    return p / np.linalg.norm(p, axis=1)[:, None]


DEGENERATE = {
    "lattice 3D": lambda rng: lattice(7, 3),
    "lattice 2D": lambda rng: lattice(25, 2),
    "cospherical": lambda rng: on_sphere(rng, 300, 3),
    "cocircular": lambda rng: on_sphere(rng, 60, 2),
    "near duplicates": lambda rng: np.concatenate(
        (p := rng.uniform(size=(2000, 3)), p[:1] + 1e-13)),
    "integer grid": lambda rng: rng.integers(0, 40, size=(4000, 3)).astype(float),
    "cube with corners": lambda rng: np.concatenate((rng.uniform(size=(2000, 3)),
                                                     lattice(2, 3))),
}
#: The DEGENERATE sets (seed 3) whose Delaunay triangulation is not unique (empty spheres with
#: five cospherical points, exactly; the cube's corners: one per face): no gmsh result can be
#: certified, the build always falls back. "near duplicates" has a unique one (no exact tie),
#: which Qhull's floats miss by a few cells: gmsh may be used there (its table is Qhull's).
TIED = [name for name in DEGENERATE if name != "near duplicates"]


@needs_gmsh
@pytest.mark.parametrize("name", TIED)
def test_degenerate_input_falls_back_to_qhull(name: str, monkeypatch) -> None:
    points = prepared(DEGENERATE[name](np.random.default_rng(3)))
    monkeypatch.setattr(backends, "GMSH_FROM_POINTS", 0)
    tri, choice = backends.delaunay(points)
    assert choice.backend == "qhull" and choice.note.startswith("gmsh not used: ")
    ref = triangulate(points)
    assert np.array_equal(tri.cells, ref.cells) and np.array_equal(tri.neighbors, ref.neighbors)
    with pytest.raises(InputError, match="cannot promise Qhull's exact triangulation"):
        backends.delaunay(points, "gmsh")


@needs_gmsh
@pytest.mark.skipif(os.name != "posix", reason="reaches the C library's srand through ctypes")
def test_gmsh_gives_the_same_cells_whatever_calls_came_before(monkeypatch) -> None:
    """gmsh draws from the C library's rand(), whose state earlier calls (gmsh's own or any
    other code's) leave behind: the same points still give the same cells and the same
    choice of backend (the choice once changed from call to call in one process)."""
    points = prepared(DEGENERATE["near duplicates"](np.random.default_rng(3)))
    monkeypatch.setattr(backends, "GMSH_FROM_POINTS", 0)
    srand = ctypes.CDLL(None).srand
    srand.argtypes, srand.restype = [ctypes.c_uint], None
    cells, choices = [], []
    for seed in (1, 2, 3, 48):
        srand(seed)
        cells.append(backends.gmsh_backend.gmsh_cells(points))
        srand(seed)
        choices.append(backends.delaunay(points)[1])
    assert all(np.array_equal(c, cells[0]) for c in cells[1:])
    assert all(choice == choices[0] for choice in choices[1:]), choices


@needs_gmsh
def test_a_near_duplicate_gives_qhulls_table_whichever_backend(monkeypatch) -> None:
    """Two points 1e-13 apart: the Delaunay triangulation is unique (gudhi's exact one), Qhull's
    float cells differ from it near the pair (the table's certification flips them), gmsh's are
    it or are refused. From gmsh's rand() seed 1 it is refused, from 48 used: the table is Qhull's
    bit for bit either way."""
    import gudhi

    import core.pipeline as pipeline
    from core import AlphaComplex

    raw = DEGENERATE["near duplicates"](np.random.default_rng(3))
    qhull = AlphaComplex.from_points(raw, backend="qhull")
    monkeypatch.setattr(backends, "GMSH_FROM_POINTS", 0)
    made = []
    monkeypatch.setattr(pipeline, "delaunay", lambda points, backend: made.append(
        (points, backends.delaunay(points, backend))) or made[-1][1])
    for seed, used in ((1, "qhull"), (48, "gmsh")):
        monkeypatch.setattr(backends.gmsh_backend, "RAND_SEED", seed)
        auto = AlphaComplex.from_points(raw)
        assert auto.build_info.backend == used, (seed, auto.build_info.backend_note)
        for k in range(4):
            assert np.array_equal(auto.simplices(k), qhull.simplices(k))
            assert np.array_equal(auto.intervals_sq(k), qhull.intervals_sq(k))
    points, (tri, _) = made[-1]
    tree = gudhi.AlphaComplex(points=points, precision="exact").create_simplex_tree()
    exact = np.sort(np.array([s for s, _ in tree.get_simplices() if len(s) == 4]), axis=1)
    assert np.array_equal(cell_set(tri.cells), cell_set(exact))
    assert not np.array_equal(cell_set(triangulate(points).cells), cell_set(exact))


@needs_gmsh
@pytest.mark.parametrize("shape", [(5, 3), (6, 3), (8, 3), (4, 2), (5, 2)])
def test_tiny_sets_never_differ(shape: tuple[int, int], monkeypatch) -> None:
    """gmsh finds no cell for some tiny sets, or leaves a point out: Qhull then."""
    monkeypatch.setattr(backends, "GMSH_FROM_POINTS", 0)
    for seed in range(10):
        points = prepared(np.random.default_rng(seed).uniform(size=shape))
        tri, choice = backends.delaunay(points)
        assert np.array_equal(cell_set(tri.cells), cell_set(triangulate(points).cells))
        assert (choice.backend == "gmsh") == (choice.note == "")


@needs_gmsh
def test_automatic_choice_uses_gmsh_from_a_size_on(monkeypatch) -> None:
    points = prepared(np.random.default_rng(1).uniform(size=(3000, 3)))
    assert backends.delaunay(points)[1] == backends.Choice("qhull")
    monkeypatch.setattr(backends, "GMSH_FROM_POINTS", 3000)
    assert backends.delaunay(points)[1] == backends.Choice("gmsh")
    assert backends.delaunay(points, "qhull")[1] == backends.Choice("qhull")


def test_backend_names_are_checked(monkeypatch) -> None:
    points = prepared(np.random.default_rng(1).uniform(size=(50, 3)))
    with pytest.raises(InputError, match="backend must be one of qhull, gmsh"):
        backends.delaunay(points, "cgal")
    monkeypatch.setattr(backends.gmsh_backend, "installed", lambda: False)
    with pytest.raises(InputError, match=r"alphascoop\[fast\]"):
        backends.delaunay(points, "gmsh")
    assert backends.delaunay(points)[1] == backends.Choice("qhull")


@pytest.mark.parametrize("d", [2, 3])
@pytest.mark.parametrize("n_points", [None, 3_000_000])
def test_neighbours_from_cells_equal_qhulls(d: int, n_points: int | None) -> None:
    """Both key layouts (one packed uint64; a lexsort where m**d does not fit)."""
    points = prepared(np.random.default_rng(d).uniform(size=(2000, d)))
    ref = triangulate(points)
    got, manifold = neighbours(ref.cells, n_points or len(points))
    assert manifold and np.array_equal(got, ref.neighbors)


def test_neighbours_report_a_facet_in_three_cells() -> None:
    cells = np.array([[0, 1, 2], [0, 1, 3], [0, 1, 4]], dtype=np.int32)
    assert not neighbours(cells, 5)[1]


@pytest.mark.parametrize("d", [2, 3])
def test_neighbours_matched_on_two_threads_equal_qhulls(d: int, monkeypatch) -> None:
    """The long-input path: keys packed in halves, split at a sampled median and sorted on
    two threads (thresholds lowered so a small set takes it); a repeated cell is caught."""
    monkeypatch.setattr(parallel, "PARALLEL_ABOVE", 64)
    monkeypatch.setattr(facets, "PARALLEL_ABOVE", 64)
    points = prepared(np.random.default_rng(d).uniform(size=(2000, d)))
    ref = triangulate(points)
    nbrs, mirror, manifold = facets.paired(ref.cells, len(points))
    assert manifold and np.array_equal(nbrs, ref.neighbors)
    inner = nbrs >= 0
    rows = np.broadcast_to(np.arange(len(nbrs))[:, None], nbrs.shape)
    assert np.array_equal(inner, mirror >= 0)
    assert np.array_equal(nbrs[nbrs[inner], mirror[inner]], rows[inner])
    inner_cell = int(np.flatnonzero(inner.all(axis=1))[0])
    twice = np.concatenate((ref.cells, ref.cells[inner_cell:inner_cell + 1]))
    assert not facets.paired(twice, len(points))[2]


def _flipped(cells: np.ndarray, nbrs: np.ndarray, t: int) -> np.ndarray:
    """2D cells with the edge between triangle t and its first neighbour flipped (the
    quad's other diagonal), rows ascending."""
    i = int(np.flatnonzero(nbrs[t] >= 0)[0])
    u = int(nbrs[t, i])
    p, q = cells[t, i], int(np.setdiff1d(cells[u], cells[t])[0])
    x, y = np.delete(cells[t], i)
    out = cells.copy()
    out[t], out[u] = np.sort([p, q, x]), np.sort([p, q, y])
    return out


def _first_flipped(cells: np.ndarray, n_points: int) -> np.ndarray:
    """2D cells with the edge of the first triangle that has a neighbour flipped."""
    nbrs, _ = backends.facets.neighbours(cells, n_points)
    return _flipped(cells, nbrs, int(np.flatnonzero((nbrs >= 0).any(axis=1))[0]))


@pytest.mark.parametrize("where", ["gmsh's own cells", "restored cells"])
def test_gmsh_check_covers_own_and_restored_cells(where: str, monkeypatch) -> None:
    """gmsh's own cells are checked beside the restoration and the restored (and relinked)
    ones after it: a wrong edge in either part is caught; hull cells gmsh left out come
    back as Qhull's."""
    points = prepared(np.random.default_rng(9).uniform(size=(400, 2)))
    ref = triangulate(points)
    h = int(np.flatnonzero((ref.neighbors < 0).any(axis=1))[0])
    dropped = [h, int(ref.neighbors[h][ref.neighbors[h] >= 0][0])]  # two adjacent cells
    own = np.delete(ref.cells, dropped, axis=0)
    assert np.isin(np.arange(len(points)), own).all()  # every point still in a cell
    monkeypatch.setattr(backends.gmsh_backend, "gmsh_cells", lambda _: own)
    tri = backends._by_gmsh_whole(points)
    assert np.array_equal(cell_set(tri.cells), cell_set(ref.cells))
    if where == "restored cells":  # the restoration brings one edge back flipped
        missing = backends.restore._missing
        monkeypatch.setattr(backends.restore, "_missing",
                            lambda *args: _first_flipped(missing(*args), len(points)))
    else:  # one edge flipped among gmsh's own cells, away from the dropped ones
        inner = np.flatnonzero((ref.neighbors >= 0).all(axis=1))
        far = inner[~np.isin(inner, np.unique(ref.neighbors[dropped]))][len(inner) // 2]
        own = np.delete(_flipped(ref.cells, ref.neighbors, int(far)), dropped, axis=0)
    assert isinstance(backends._by_gmsh_whole(points), str)


def test_certify_accepts_delaunay_and_rejects_the_rest() -> None:
    rng = np.random.default_rng(5)
    points = prepared(rng.uniform(size=(500, 3)))
    ref = triangulate(points)
    assert why_not_delaunay(points, ref.cells, ref.neighbors) == ""
    # a hull cell missing: the outer facets are no longer the hull (or a point is lost)
    hull_cell = int(np.flatnonzero((ref.neighbors < 0).any(axis=1))[0])
    keep = np.arange(len(ref.cells)) != hull_cell
    cells = ref.cells[keep]
    nbrs, _ = neighbours(cells, len(points))
    assert why_not_delaunay(points, cells, nbrs) != ""


def test_certify_rejects_a_flipped_edge() -> None:
    """Four points where only one diagonal is Delaunay; the other is caught."""
    points = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.1]])
    good = np.array([[0, 1, 2], [1, 2, 3]], dtype=np.int32)
    bad = np.array([[0, 1, 3], [0, 2, 3]], dtype=np.int32)
    assert why_not_delaunay(points, good, neighbours(good, 4)[0]) == ""
    assert "not certainly Delaunay" in why_not_delaunay(points, bad, neighbours(bad, 4)[0])


def assert_same_table(a, b) -> None:
    """Every array of the two complexes equal bit for bit."""
    assert a.counts() == b.counts()
    assert np.array_equal(a.points, b.points) and np.array_equal(a.input_index, b.input_index)
    for k in range(a.dim + 1):
        assert np.array_equal(a.simplices(k), b.simplices(k))
        assert np.array_equal(a.intervals(k), b.intervals(k))
        if k:
            assert np.array_equal(a.face_ids(k), b.face_ids(k))
    assert np.array_equal(a.facet_cells(), b.facet_cells())
    assert np.array_equal(a.cell_measures(), b.cell_measures())


@needs_gmsh
@pytest.mark.parametrize("name", ["uniform 3D", "noisy torus 3D", "uniform 2D", "planar in 3D"])
def test_tables_equal_bit_for_bit_between_backends(name: str) -> None:
    from core import AlphaComplex

    points = CASES[name](np.random.default_rng(11)) * 37.5 + 4.0
    by_gmsh = AlphaComplex.from_points(points, backend="gmsh")
    by_qhull = AlphaComplex.from_points(points, backend="qhull")
    assert by_gmsh.build_info.backend == "gmsh" and by_qhull.build_info.backend == "qhull"
    assert_same_table(by_gmsh, by_qhull)
    assert by_gmsh.betti(alpha=float(np.median(by_gmsh.spectrum()))) == by_qhull.betti(
        alpha=float(np.median(by_qhull.spectrum())))


@needs_gmsh
def test_build_records_the_automatic_choice(monkeypatch) -> None:
    from core import AlphaComplex

    monkeypatch.setattr(backends, "GMSH_FROM_POINTS", 100)
    rng = np.random.default_rng(2)
    info = AlphaComplex.from_points(rng.uniform(size=(500, 3))).build_info
    assert (info.backend, info.backend_note) == ("gmsh", "")
    info = AlphaComplex.from_points(lattice(6, 3)).build_info
    assert info.backend == "qhull" and info.backend_note.startswith("gmsh not used: ")
    weighted = AlphaComplex.from_points(rng.uniform(size=(500, 3)),
                                        weights=rng.uniform(0, 1e-3, 500))
    assert weighted.build_info.backend == ("geogram" if geogram.available() else "qhull")
    with pytest.raises(InputError, match="Delaunay triangulations only"):
        AlphaComplex.from_points(rng.uniform(size=(500, 3)), weights=rng.uniform(0, 1e-3, 500),
                                 backend="gmsh")


@needs_gmsh
def test_2d_real_data_builds_the_same_table_with_both_backends() -> None:
    """US airports (longitude/latitude projected to metres, very uneven density)."""
    from core import AlphaComplex
    from core.io import read_points

    folder = data_dir()
    if folder is None:
        pytest.skip(DATA_ABSENT)
    points = read_points(folder / "us_airports.csv").points
    by_gmsh = AlphaComplex.from_points(points, backend="gmsh")
    assert by_gmsh.build_info.backend == "gmsh"
    assert_same_table(by_gmsh, AlphaComplex.from_points(points, backend="qhull"))


def test_a_mirror_that_does_not_fit_the_neighbours_is_refused():
    """Triangulation checks a backend's mirror against its neighbours: one kept through a
    `replace` that changed the neighbours must fail loudly, not make the facet passes wrong."""
    from dataclasses import replace

    from scipy.spatial import Delaunay

    from core.backends.facets import paired
    from core.build.delaunay import Triangulation, mirror_fits

    points = np.random.default_rng(3).random((400, 3))
    cells = np.sort(Delaunay(points).simplices, axis=1).astype(np.int32)
    nbrs, mirror, manifold = paired(cells, len(points))
    assert manifold and mirror_fits(nbrs, mirror, samples=len(cells))
    tri = Triangulation(cells, nbrs, np.arange(400), np.arange(400), mirror)
    order = np.random.default_rng(4).permutation(len(cells))
    moved = np.argsort(order).astype(np.int32)
    renumbered = np.where(nbrs[order] >= 0, moved[np.maximum(nbrs[order], 0)], -1)
    with pytest.raises(ValueError, match="mirror"):
        replace(tri, cells=cells[order], neighbors=renumbered)  # the old mirror kept
    assert replace(tri, cells=cells[order], neighbors=renumbered, mirror=mirror[order]).mirror \
        is not None


def near_cospherical(seed: int, d: int) -> tuple[np.ndarray, np.ndarray, int]:
    """3000 prepared uniform points with the vertex across one facet of a central Delaunay
    cell moved onto that cell's circumsphere, 1e-14 (relative) outside: the float check
    cannot settle that facet, its exact sign is strict. Also the cell and the vertex."""
    points = prepared(np.random.default_rng(seed).uniform(size=(3000, d)))
    ref = triangulate(points)
    t = int(np.argmin(np.linalg.norm(points[ref.cells].mean(axis=1) - points.mean(axis=0),
                                     axis=1)))
    q = int(np.setdiff1d(ref.cells[ref.neighbors[t, 0]], ref.cells[t])[0])
    corners = points[ref.cells[t]]
    centre = np.linalg.solve(2 * (corners[1:] - corners[0]),
                             (corners[1:] ** 2).sum(axis=1) - (corners[0] ** 2).sum())
    radius = np.linalg.norm(corners[0] - centre)
    away = points[q] - centre
    points[q] = centre + away / np.linalg.norm(away) * radius * (1 + 1e-14)
    return points, ref.cells[t], q


def exact_delaunay_cells(points: np.ndarray) -> np.ndarray:
    """The unique Delaunay cells of points in general position: Qhull's, certified exactly
    (what gmsh returns when its own predicates get every near-cospherical facet right, which
    depends on its internal state; standing in for it keeps these tests deterministic)."""
    from core.build.certify import certified_triangulation

    certified = certified_triangulation(points, triangulate(points))
    assert certified.uncertified == 0
    return np.sort(certified.triangulation.cells, axis=1).astype(np.int32)


@needs_gmsh
@pytest.mark.parametrize(("d", "seed"), [(2, 1), (2, 3), (3, 0), (3, 5)])
def test_near_cospherical_facets_are_settled_exactly(d: int, seed: int, monkeypatch) -> None:
    """The float check leaves the facet at 0, the exact in-sphere sign says strictly outside:
    the exact Delaunay cells are accepted, and Qhull's own cells, which its floating point
    triangulates otherwise for these seeds, are refused (a wrong exact sign)."""
    from core.backends.certify import exact_sides, in_sphere, orientations

    points, cell, q = near_cospherical(seed, d)
    sign = orientations(points, cell[None])
    assert in_sphere(points, cell[None], np.array([q]), sign)[0] == 0
    assert exact_sides(points, cell[None], np.array([q]), sign)[0] == 1
    exact = exact_delaunay_cells(points)
    qhulls = triangulate(points).cells
    assert not np.array_equal(cell_set(exact), cell_set(qhulls))
    monkeypatch.setattr(backends.gmsh_backend, "gmsh_cells", lambda _: exact.copy())
    tri, choice = backends.delaunay(points, "gmsh")
    assert choice == backends.Choice("gmsh")
    assert np.array_equal(cell_set(tri.cells), cell_set(exact))
    monkeypatch.setattr(backends.gmsh_backend, "gmsh_cells",
                        lambda _: np.sort(qhulls, axis=1).astype(np.int32))
    with pytest.raises(InputError, match="facets are not certainly Delaunay"):
        backends.delaunay(points, "gmsh")


@needs_gmsh
@pytest.mark.parametrize(("d", "seed"), [(2, 1), (3, 0)])
def test_near_cospherical_tables_equal_bit_for_bit(d: int, seed: int, monkeypatch) -> None:
    """Qhull's differing cells are flipped by core.build.certify into the same unique cells."""
    from core import AlphaComplex

    points, _, _ = near_cospherical(seed, d)
    monkeypatch.setattr(backends.gmsh_backend, "gmsh_cells", exact_delaunay_cells)
    by_gmsh = AlphaComplex.from_points(points, backend="gmsh")
    assert by_gmsh.build_info.backend == "gmsh"
    by_qhull = AlphaComplex.from_points(points, backend="qhull")
    assert by_qhull.build_info.flips > 0
    assert_same_table(by_gmsh, by_qhull)


@needs_gmsh
def test_exactly_cospherical_facets_still_fall_back(monkeypatch) -> None:
    """A unit square of a lattice is exactly cocircular (exact sign 0): two Delaunay
    triangulations, so gmsh's is refused, and the automatic choice falls back to Qhull."""
    from core.backends.certify import exact_sides

    square = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]])
    assert exact_sides(square, np.array([[0, 1, 2]]), np.array([3]), np.array([1]))[0] == 0
    with pytest.raises(InputError, match=r"facets are not certainly Delaunay \(cospherical"):
        backends.delaunay(prepared(lattice(25, 2)), "gmsh")
    monkeypatch.setattr(backends, "GMSH_FROM_POINTS", 0)  # the automatic choice would try it
    _, choice = backends.delaunay(prepared(lattice(25, 2)))
    assert choice.backend == "qhull" and "not certainly Delaunay" in choice.note


@needs_gmsh
@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="needs /proc (Linux)")
def test_gmsh_leaves_sigpipe_ignored() -> None:
    """gmsh.initialize restores SIGPIPE's default (death); after a gmsh build in a thread
    the process still ignores it, so a write to a closed pipe raises instead of killing
    the window."""
    def sigpipe_ignored() -> bool:
        for line in Path("/proc/self/status").read_text().splitlines():
            if line.startswith("SigIgn:"):
                return bool(int(line.split()[1], 16) & (1 << (signal.SIGPIPE - 1)))
        raise AssertionError("no SigIgn line")

    assert sigpipe_ignored()
    gmsh = backends.gmsh_backend._ready()
    if gmsh.isInitialized():
        gmsh.finalize()  # initialise again, in a thread, as a build does
    worker = threading.Thread(target=backends.gmsh_backend.gmsh_cells,
                              args=(np.random.default_rng(0).uniform(size=(50, 3)),))
    worker.start()
    worker.join()
    assert sigpipe_ignored()
    reader, writer = os.pipe()
    os.close(reader)
    with pytest.raises(BrokenPipeError):
        os.write(writer, b"x")
    os.close(writer)

"""Density-scaled and anisotropic alpha (core/modes/alpha_modes.py): the tables are filtrations,
match a brute force of their definitions, and are exactly the classic table when the mode is off."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from reference import (
    assert_valid_table,
    cofacet_pairs,
    delaunay_simplices,
    derived_intervals,
    ours_by_input_ids,
    smallest_circumspheres,
    strictly_inside,
)

from core import AlphaComplex
from core.cache import points_key
from core.errors import FileFormatError, InputError
from core.modes.alpha_modes import Mode, make_mode
from core.obtain import obtain
from core.storage.compact import unpack

SETTINGS = settings(max_examples=30, deadline=None,
                    suppress_health_check=[HealthCheck.too_slow])
MODES = [dict(density=8), dict(density=3, combine="max"), dict(anisotropy=0.6),
         dict(density=5, anisotropy=0.4)]


def _tables(ac) -> list[np.ndarray]:
    """Every array of the table that a query reads."""
    out = [ac.points, ac.input_index, ac.facet_cells(), ac.cell_measures()]
    for k in range(ac.dim + 1):
        out += [ac.simplices(k), ac.intervals(k)]
        if k:
            out.append(ac.face_ids(k))
    return out


def _cloud(seed: int, n: int, dim: int) -> np.ndarray:
    return np.random.default_rng(seed).uniform(-1, 1, (n, dim))


@pytest.mark.parametrize("dim", [2, 3])
def test_off_is_the_classic_table_bit_for_bit(dim):
    pts = _cloud(0, 400, dim)
    classic = AlphaComplex.from_points(pts)
    normals = np.ones_like(pts)
    for ac in (AlphaComplex.from_points(pts, density=None, combine="max"),
               AlphaComplex.from_points(pts, anisotropy=0.0, normals=normals),
               AlphaComplex.from_points(pts, None, density=None, anisotropy=0.0)):
        assert ac.mode == Mode() and not ac.mode.active and ac.mode.name == "classic"
        for a, b in zip(_tables(classic), _tables(ac), strict=True):
            assert a.dtype == b.dtype and a.tobytes() == b.tobytes()
        assert np.array_equal(ac.spectrum(), classic.spectrum())


@pytest.mark.parametrize("kwargs", MODES)
@pytest.mark.parametrize("dim", [2, 3])
def test_mode_tables_are_valid_filtrations(kwargs, dim):
    ac = AlphaComplex.from_points(_cloud(1, 600, dim), **kwargs)
    assert ac.mode.active
    assert_valid_table(ac)
    iv = ac.intervals(dim - 1)
    cells = ac.intervals(dim)[:, 0]
    fc = ac.facet_cells()
    second = np.where(fc[:, 1] >= 0, cells[np.maximum(fc[:, 1], 0)], np.inf)
    assert np.array_equal(iv[:, 1], np.minimum(cells[fc[:, 0]], second))
    assert np.array_equal(iv[:, 2], np.maximum(cells[fc[:, 0]], second))


def _brute_density(points: np.ndarray, k: int, combine: str) -> dict:
    """The density-scaled table of core/modes.py's rules with every value from scratch: global
    empty-ball attachment, distance-matrix spacing, enter = min over cofaces of own values."""
    dim = points.shape[1]
    simplices = delaunay_simplices(points)
    dist = np.sqrt(((points[:, None] - points[None]) ** 2).sum(axis=2))
    spacing = np.sort(dist, axis=1)[:, k]
    own = {}
    for j in range(dim + 1):
        centres, radii = smallest_circumspheres(points, simplices[j])
        gathered = spacing[simplices[j]]
        rho = radii / (gathered.max(axis=1) if combine == "max" else gathered.mean(axis=1))
        free = ~strictly_inside(points, centres, radii) | (j == dim)
        own[j] = np.where(free, rho, np.inf)
    enter = {dim: own[dim]}
    for j in range(dim - 1, 0, -1):
        f, c = cofacet_pairs(simplices[j], simplices[j + 1], len(points))
        low = own[j].copy()
        np.minimum.at(low, f, enter[j + 1][c])
        enter[j] = low
    enter[0] = np.zeros(len(points))
    regular, interior = derived_intervals(simplices, enter, dim, len(points))
    return {"simplices": simplices, "enter": enter, "regular": regular, "interior": interior}


@pytest.mark.parametrize("combine", ["mean", "max"])
@pytest.mark.parametrize("dim", [2, 3])
def test_density_table_matches_brute_force(combine, dim):
    pts = _cloud(2, 60, dim)
    ac = AlphaComplex.from_points(pts, density=4, combine=combine)
    ref = _brute_density(pts, 4, combine)
    for k in range(dim + 1):
        rows, iv = ours_by_input_ids(ac, k)
        assert np.array_equal(rows, ref["simplices"][k])
        want = np.stack([ref["enter"][k], ref["regular"][k], ref["interior"][k]], axis=1)
        np.testing.assert_allclose(iv, want, rtol=1e-9)


def _brute_stretched_radius(points: np.ndarray, simplex: np.ndarray, normals: np.ndarray,
                            tau: float) -> float:
    """One simplex: best-sign normal sum, stretch, smallest sphere by a least-squares solve."""
    best = max((normals[simplex[0]] + sum(s * normals[v] for s, v in zip(signs, simplex[1:],
                                                                          strict=True))
                for signs in itertools.product((1, -1), repeat=len(simplex) - 1)),
               key=lambda v: float(v @ v))
    unit = best / np.linalg.norm(best)
    rel = points[simplex] - points[simplex[0]]
    rel += (1 / (1 - tau) - 1) * (rel @ unit)[:, None] * unit
    edges = rel[1:]
    lam = np.linalg.lstsq(2 * edges @ edges.T, (edges**2).sum(axis=1), rcond=None)[0]
    return float(np.linalg.norm(lam @ edges))


def _brute_stretched_sphere(points: np.ndarray, simplex: np.ndarray, normals: np.ndarray,
                            tau: float):
    """One simplex: its stretched smallest sphere (centre relative to the first vertex, in
    stretched coordinates, and radius) and the stretch of vectors from its first vertex."""
    best = max((normals[simplex[0]] + sum(s * normals[v] for s, v in zip(signs, simplex[1:],
                                                                          strict=True))
                for signs in itertools.product((1, -1), repeat=len(simplex) - 1)),
               key=lambda v: float(v @ v))
    unit = best / np.linalg.norm(best)

    def stretch(rel: np.ndarray) -> np.ndarray:
        return rel + (1 / (1 - tau) - 1) * (rel @ unit)[..., None] * unit

    edges = stretch(points[simplex[1:]] - points[simplex[0]])
    lam = np.linalg.lstsq(2 * edges @ edges.T, (edges**2).sum(axis=1), rcond=None)[0]
    centre = lam @ edges
    return centre, float(np.linalg.norm(centre)), stretch


def _brute_anisotropic(points: np.ndarray, normals: np.ndarray, tau: float) -> dict:
    """The anisotropic table of the module rules from scratch: every simplex's stretched
    sphere, a face attached when a Delaunay cofacet's opposite vertex, stretched with the
    face, is strictly inside it; enter = min(own value if unattached, cofacets' enters)."""
    dim = points.shape[1]
    simplices = delaunay_simplices(points)
    spheres = {k: [_brute_stretched_sphere(points, s, normals, tau) for s in simplices[k]]
               for k in range(1, dim + 1)}
    enter = {dim: np.array([r for _, r, _ in spheres[dim]])}
    for k in range(dim - 1, 0, -1):
        own = np.array([r for _, r, _ in spheres[k]])
        f, c = cofacet_pairs(simplices[k], simplices[k + 1], len(points))
        for face, coface in zip(f, c, strict=True):
            far = np.setdiff1d(simplices[k + 1][coface], simplices[k][face])[0]
            centre, radius, stretch = spheres[k][face]
            rel = stretch(points[far] - points[simplices[k][face][0]])
            if np.linalg.norm(rel - centre) < radius * (1 - 1e-9):
                own[face] = np.inf
        np.minimum.at(own, f, enter[k + 1][c])
        enter[k] = own
    enter[0] = np.zeros(len(points))
    regular, interior = derived_intervals(simplices, enter, dim, len(points))
    return {"simplices": simplices, "enter": enter, "regular": regular, "interior": interior}


@pytest.mark.parametrize("dim", [2, 3])
def test_anisotropic_table_matches_brute_force(dim):
    """Every value and every attachment (the face passes of core/modes/stretched.py, including the
    3D edges tested from their triangles) against the definition."""
    pts = _cloud(11, 70, dim)
    normals = np.random.default_rng(12).normal(size=pts.shape)
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    ac = AlphaComplex.from_points(pts, anisotropy=0.6, normals=normals)
    ref = _brute_anisotropic(pts, normals, 0.6)
    for k in range(dim + 1):
        rows, iv = ours_by_input_ids(ac, k)
        assert np.array_equal(rows, ref["simplices"][k])
        want = np.stack([ref["enter"][k], ref["regular"][k], ref["interior"][k]], axis=1)
        np.testing.assert_allclose(iv, want, rtol=1e-9)
    faces = ac.intervals(dim - 1)  # some faces are attached and some are not: both tested
    assert (faces[:, 0] == faces[:, 1]).any() and (faces[:, 0] < faces[:, 1]).any()


@pytest.mark.parametrize("dim", [2, 3])
def test_anisotropic_cells_enter_at_their_stretched_radius(dim):
    pts = _cloud(3, 80, dim)
    normals = np.random.default_rng(4).normal(size=pts.shape)
    ac = AlphaComplex.from_points(pts, anisotropy=0.7, normals=normals)
    assert ac.mode.normals == "given"
    inv = np.empty(len(pts), dtype=np.int64)
    inv[ac.input_index] = np.arange(len(pts))
    cells = ac.simplices(dim)
    unit = normals / np.linalg.norm(normals, axis=1)[:, None]
    for row in range(0, len(cells), 7):
        want = _brute_stretched_radius(pts, inv[cells[row]], unit, 0.7)
        assert ac.intervals(dim)[row, 0] == pytest.approx(want, rel=1e-9)


@pytest.mark.parametrize("dim", [2, 3])
def test_anisotropy_with_zero_normals_estimates_them(dim):
    """Zero normals give no direction: they are estimated (as the "estimate" mode does),
    never left to stretch nothing, which is the classic table under an anisotropic label."""
    pts = _cloud(5, 300, dim)
    estimated = AlphaComplex.from_points(pts, anisotropy=0.9)
    ac = AlphaComplex.from_points(pts, anisotropy=0.9, normals=np.zeros_like(pts))
    assert ac.build_info.estimated_normals == len(pts)
    for k in range(dim + 1):
        (ours, ours_values), (theirs, their_values) = by_simplex(ac, k), by_simplex(estimated, k)
        np.testing.assert_array_equal(ours, theirs)
        np.testing.assert_array_equal(ours_values, their_values)


def by_simplex(ac: AlphaComplex, k: int) -> tuple[np.ndarray, np.ndarray]:
    """ac's k-simplices as ascending rows of input point ids, in lexicographic order, and
    their (n, 2) intervals in the same order: two tables compare record by record."""
    rows = np.sort(np.asarray(ac.input_index)[ac.simplices(k)], axis=1)
    order = np.lexsort(rows.T[::-1])
    return rows[order], ac.intervals(k)[order]


@st.composite
def mode_sets(draw):
    dim = draw(st.sampled_from([2, 3]))
    n = draw(st.integers(dim + 3, 40))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    grid = draw(st.booleans())  # degenerate: cospherical grids
    pts = rng.integers(-4, 5, (n, dim)).astype(float) if grid else rng.normal(size=(n, dim))
    kwargs = draw(st.sampled_from([*MODES, dict(density=1), dict(anisotropy=0.95)]))
    return pts, kwargs


@SETTINGS
@given(mode_sets())
def test_property_modes_are_filtrations(case):
    pts, kwargs = case
    try:
        ac = AlphaComplex.from_points(pts, **kwargs)
    except InputError:
        return  # collinear or too few distinct points: no complex in any mode
    assert_valid_table(ac)
    for k in range(1, ac.dim + 1):  # every face enters no later than its cofaces
        faces_enter = ac.intervals(k - 1)[ac.face_ids(k), 0]
        assert (faces_enter <= ac.intervals(k)[:, 0, None]).all()
    for alpha in np.unique(ac.intervals(ac.dim)[:, 0])[::5]:
        shape = ac.shape(alpha)  # classes are monotone: enter <= regular <= interior
        for k in range(ac.dim + 1):
            cls = ac.classify(alpha, k)
            assert (cls[: np.searchsorted(ac.intervals(k)[:, 0], alpha, "right")] >= 1).all()
        assert len(shape.cells) == np.searchsorted(ac.intervals(ac.dim)[:, 0], alpha, "right")


@pytest.mark.parametrize("kwargs, message", [
    (dict(density=0), "density"), (dict(density=2.5), "density"), (dict(density=True), "density"),
    (dict(density=4, combine="median"), "combine"), (dict(anisotropy=1.0), "anisotropy"),
    (dict(anisotropy=-0.1), "anisotropy"), (dict(anisotropy="x"), "anisotropy"),
    (dict(anisotropy=0.5, normals=np.ones((3, 3))), "normals"),
    (dict(anisotropy=0.5, normals=np.full((50, 3), np.nan)), "normals"),
])
def test_bad_mode_parameters_are_input_errors(kwargs, message):
    with pytest.raises(InputError, match=message):
        AlphaComplex.from_points(_cloud(6, 50, 3), **kwargs)


def test_mode_is_saved_with_the_table(tmp_path):
    pts = _cloud(7, 300, 3)
    for kwargs in MODES:
        ac = AlphaComplex.from_points(pts, **kwargs)
        ac.signatures()
        ac.save(tmp_path / "t.npz")
        back = AlphaComplex.load(tmp_path / "t.npz")
        assert back.mode == ac.mode
        for a, b in zip(_tables(ac), _tables(back), strict=True):
            assert np.array_equal(a, b)
        assert back.optimal_alpha() == ac.optimal_alpha()


def test_a_damaged_mode_is_a_format_error(tmp_path):
    ac = AlphaComplex.from_points(_cloud(8, 100, 2), density=4)
    ac.save(tmp_path / "t.npz")
    with np.load(tmp_path / "t.npz") as data:
        arrays = unpack({k: v for k, v in data.items() if k != "checksums"})
    arrays["version"] = np.array(1)  # no checksums: the mode's own check must find it
    arrays["mode_combine"] = np.array("median")
    np.savez(tmp_path / "bad.npz", **arrays)
    with pytest.raises(FileFormatError, match="mode"):
        AlphaComplex.load(tmp_path / "bad.npz")


def test_the_mode_is_part_of_the_cache_key(tmp_path, monkeypatch):
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path))
    pts = _cloud(9, 200, 3)
    normals = np.random.default_rng(1).normal(size=pts.shape)
    keys = {points_key(pts), points_key(pts, make_mode(8)), points_key(pts, make_mode(8, "max")),
            points_key(pts, make_mode(4)), points_key(pts, make_mode(None, "mean", 0.5)),
            points_key(pts, make_mode(None, "mean", 0.5, True), normals),
            points_key(pts, make_mode(None, "mean", 0.5, True), normals + 1)}
    assert len(keys) == 7
    assert points_key(pts, Mode()) == points_key(pts)
    built = obtain(pts, mode=make_mode(6)).complex
    again = obtain(pts, mode=make_mode(6))
    assert again.source == "cache"
    again = again.complex
    classic = obtain(pts).complex
    assert again.mode == built.mode == make_mode(6) and classic.mode == Mode()
    assert np.array_equal(again.intervals(3), built.intervals(3))
    assert len(list(tmp_path.glob("*.npz"))) == 2


def test_mode_describes_itself():
    mode = make_mode(8, "max", 0.25, True)
    assert mode.name == "density+anisotropic"
    assert "k=8" in mode.describe() and "tau=0.25" in mode.describe()
    assert mode.to_dict() == {"name": "density+anisotropic", "density": 8, "combine": "max",
                              "anisotropy": 0.25, "normals": "given"}
    assert make_mode(None, "max", 0.0, True) == Mode()  # unused parameters are reset


def test_estimated_normals_face_out_of_a_sphere():
    """PCA normals oriented over the 8-neighbour spanning tree: on a sphere every normal is
    radial and all face the same way (outward: the root faces away from the centroid)."""
    from core.geometry.neighbourhood import neighbours
    from core.modes.alpha_modes import NORMAL_NEIGHBOURS, point_normals

    pts = np.random.default_rng(13).normal(size=(3000, 3))
    pts /= np.linalg.norm(pts, axis=1)[:, None]
    normals = point_normals(pts, neighbours(pts, NORMAL_NEIGHBOURS)[1])
    assert (np.einsum("nd,nd->n", normals, pts) > 0.99).all()


def test_local_geometry_beside_the_table_is_the_same_and_raises_its_errors():
    from core.modes.alpha_modes import local_geometry, local_geometry_beside

    pts = _cloud(14, 500, 3)
    for mode in (make_mode(4), make_mode(None, "mean", 0.5), make_mode(6, "max", 0.3)):
        want, got = local_geometry(pts, mode), local_geometry_beside(pts, mode)()
        for a, b in ((want.spacing, got.spacing), (want.normals, got.normals)):
            assert (a is None) == (b is None) and (a is None or np.array_equal(a, b))
    bad = pts.copy()
    bad[3] = np.nan  # (the build checks points first; here the k-d tree refuses them)
    wait = local_geometry_beside(bad, make_mode(4))
    with pytest.raises(ValueError, match="finite"):  # an error in the thread reaches the caller
        wait()
    with pytest.raises(InputError, match="two points"):
        local_geometry_beside(pts[:1], make_mode(4))


def test_density_keeps_the_classic_exact_decisions_anisotropy_needs_fewer():
    """Density scaling reads the classic radii (decided exactly where floats doubt, counted
    in build_info as for classic); anisotropy builds its table without them."""
    grid = np.stack(np.meshgrid(*[np.arange(5.0)] * 3), axis=-1).reshape(-1, 3)  # cospherical
    classic = AlphaComplex.from_points(grid).build_info.exact_predicates
    assert classic > 0
    assert AlphaComplex.from_points(grid, density=4).build_info.exact_predicates == classic
    normals = np.tile([0.0, 0.0, 1.0], (len(grid), 1))
    assert AlphaComplex.from_points(grid, anisotropy=0.5,
                                    normals=normals).build_info.exact_predicates < classic

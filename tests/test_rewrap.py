"""The local exact re-triangulation (core/build/rewrap.py): cut out around cells and
wrapped again, a Delaunay triangulation comes back cell for cell (Qhull's on general points,
an independent reference); on the jittered lattices whose folds no flip repairs, certification
with the repair gives gudhi's exact Delaunay cells where it failed without."""

from __future__ import annotations

import numpy as np
import pytest

import core.build.rewrap as rewrap_module
from core.build.certify import certify, tie_weights
from core.build.delaunay import triangulate
from core.build.rewrap import grow, rewrap


def _cell_set(cells: np.ndarray) -> set:
    return {tuple(sorted(row)) for row in cells.tolist()}


def _links_are_symmetric(tri) -> bool:
    nbs = tri.neighbors
    t, k = np.nonzero(nbs >= 0)
    u = nbs[t, k]
    back = (nbs[u] == t[:, None]).sum(axis=1)
    return bool((back == 1).all())


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("where", ["inside", "hull"])
@pytest.mark.parametrize("pool", ["all points", "near the region"])
def test_rewrap_of_a_delaunay_region_gives_the_same_cells(dim: int, where: str, pool: str,
                                                          monkeypatch) -> None:
    if pool == "near the region":  # as for large inputs: pivots among the points nearby
        monkeypatch.setattr(rewrap_module, "ALL_CANDIDATES", 50)
    pts = np.random.default_rng(dim).random((300, dim))
    tri = triangulate(pts)
    hull = (tri.neighbors < 0).any(axis=1)
    centre = np.linalg.norm(pts[tri.cells].mean(axis=1) - 0.5, axis=1)
    seed = np.flatnonzero(hull)[0] if where == "hull" else int(np.argmin(centre))
    region = np.zeros(len(tri.cells), dtype=bool)
    region[seed] = True
    region = grow(tri.cells, grow(tri.cells, region))
    fixed, _ = rewrap(pts, tri, tie_weights(len(pts)), region)
    assert fixed is not None
    assert _cell_set(fixed.cells) == _cell_set(tri.cells)
    assert _links_are_symmetric(fixed)
    assert (fixed.neighbors < 0).sum() == (tri.neighbors < 0).sum()  # the same hull
    again = certify(pts, fixed, repair=False)
    assert again.uncertified == 0 and again.flips == 0


def test_rewrap_declines_a_region_without_a_boundary() -> None:
    pts = np.random.default_rng(0).random((50, 3))
    tri = triangulate(pts)
    fixed, _ = rewrap(pts, tri, tie_weights(len(pts)), np.ones(len(tri.cells), dtype=bool))
    assert fixed is None


@pytest.mark.parametrize("seed", [1, 2, 3, 6, 11])
def test_repair_certifies_folds_flips_cannot(seed: int) -> None:
    import gudhi

    axes = np.meshgrid(*[np.arange(6.0)] * 3, indexing="ij")
    pts = np.column_stack([a.ravel() for a in axes])
    pts = pts + np.random.default_rng(seed).normal(size=pts.shape) * 1e-12
    tri = triangulate(pts)
    assert len(tri.kept) == len(pts)
    assert certify(pts, tri, repair=False).uncertified > 0  # stuck flips (1, 2), or a flip
    # that broke the triangulation (3, 6, 11: without the repair, the backend's cells)
    out = certify(pts, tri)
    assert out.uncertified == 0
    st = gudhi.AlphaComplex(points=pts, precision="exact").create_simplex_tree()
    exact = {tuple(sorted(s)) for s, _ in st.get_simplices() if len(s) == 4}
    assert _cell_set(out.triangulation.cells) == exact
    assert _links_are_symmetric(out.triangulation)


def test_nothing_new_runs_on_a_certified_build(monkeypatch) -> None:
    """The ordinary path: a triangulation that certifies never reaches the re-triangulation."""
    import core.build.certify as certify_module
    from core.pipeline import build_complex

    def refuse(*args, **kwargs):
        raise AssertionError("a repair ran on a build that certifies")

    for name in ("rewrap", "_rewrapped", "_retried"):  # nor the retry before the repair
        monkeypatch.setattr(certify_module, name, refuse)
    built = build_complex(np.random.default_rng(3).random((2000, 3)))
    assert built.info.uncertified == 0


def test_a_flat_cell_on_the_region_boundary_grows_the_region() -> None:
    """Points snapped to a 0.1 lattice (found by the surface export's property test): a flat
    kept cell on the first region's boundary has no side to wrap towards; the attempt is
    declined (no division by its zero normal) and the next ring certifies. The set is exactly
    degenerate (its Delaunay triangulation is not unique), so the check is certification and
    a tiling of the convex hull, not gudhi's cells."""
    from scipy.spatial import ConvexHull

    from core.pipeline import build_complex

    rng = np.random.default_rng(492)
    pts = np.unique(np.round(rng.uniform(size=(150, 3)), 1), axis=0)
    built = build_complex(pts)  # the suite turns core's RuntimeWarnings into errors
    assert built.info.uncertified == 0
    cells = built.table.levels[3].simplices
    corners = built.points[cells]
    volume = np.abs(np.linalg.det(corners[:, 1:] - corners[:, :1])).sum() / 6
    assert volume == pytest.approx(ConvexHull(pts).volume, rel=1e-12)

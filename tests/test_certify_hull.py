"""Certification checks the hull's convexity globally, not only at its ridges: Qhull, given
a range-grid-like set in a Morton order of the points' own float bits, returned a hull folded
over itself at a vertex (convex at every ridge, yet 8 hull facets with a point outside them);
that triangulation was certified and its alpha complex differed from gudhi's exact one."""

from __future__ import annotations

import numpy as np
import pytest
from reference import assert_valid_table, gudhi_table
from test_exact_gudhi import range_grid
from test_table_gudhi import assert_matches_gudhi

import core.pipeline as pipeline
from core import AlphaComplex
from core.build.certify import certified_triangulation, point_ties
from core.build.delaunay import triangulate
from core.build.points import canonical_order
from core.geometry.predicates import orientations


def hull_facets_with_a_point_outside(points: np.ndarray, cells: np.ndarray,
                                     neighbors: np.ndarray) -> int:
    """How many hull facets (neighbour -1) have a point strictly on their outer side (brute
    force: every facet against every point, exact orientations)."""
    d = points.shape[1]
    t, k = np.nonzero(neighbors < 0)
    others = np.array([[c for c in range(d + 1) if c != j] for j in range(d + 1)])
    facets = np.take_along_axis(cells[t].astype(np.int64), others[k], axis=1)
    inner, _ = orientations(points, np.column_stack((facets, cells[t, k])))
    m = len(points)
    rows = np.column_stack((np.repeat(facets, m, axis=0), np.tile(np.arange(m), len(facets))))
    sides = orientations(points, rows)[0].reshape(len(facets), m)
    return int(((sides == -inner[:, None]) & (sides != 0)).any(axis=1).sum())


#: The range-grid set (test_exact_gudhi, 3D, jitter 1e-13, its sweep's first seed) whose
#: hull Qhull folds when given the points in canonical_order.
FOLDED = {"n": 500, "dim": 3, "jitter": 1e-13, "seed": 100}


def certified_convex_cells(pts: np.ndarray) -> np.ndarray:
    """Qhull's cells of pts in their given order, certified: every one certified and no hull
    facet with a point outside it (an exact brute force), where Qhull's own hull had one."""
    tri = triangulate(pts)
    assert len(tri.kept) == len(pts)
    assert hull_facets_with_a_point_outside(pts, tri.cells, tri.neighbors) > 0  # it folded
    out = certified_triangulation(pts, tri, point_ties(pts))
    assert out.uncertified == 0
    cells, nbs = out.triangulation.cells, out.triangulation.neighbors
    assert hull_facets_with_a_point_outside(pts, cells, nbs) == 0
    return cells


def test_a_hull_qhull_folds_is_repaired_to_the_convex_hull() -> None:
    pts = range_grid(**FOLDED)
    certified_convex_cells(pts[canonical_order(pts)])  # the order Qhull folds the hull in


def test_the_folding_order_builds_gudhis_exact_complex(monkeypatch) -> None:
    """The whole build with Qhull given the points in that order (a fixed permutation of the
    set, whatever the default order is): gudhi's exact alpha complex."""
    monkeypatch.setattr(pipeline, "spatial_order", canonical_order)
    pts = range_grid(**FOLDED)
    ac = AlphaComplex.from_points(pts)
    assert ac.build_info.uncertified == 0
    assert_valid_table(ac)
    assert_matches_gudhi(ac, gudhi_table(pts, precision="exact"))


#: Smaller jittered grids (range_grid(n, 3, 1e-13, seed)) whose hull Qhull folds in the given
#: order: canonical_order, or a permutation drawn with the same seed.
SMALL_FOLDS = {"120-canonical": (120, 14, "canonical"), "200-shuffled-4": (200, 4, "shuffled"),
               "200-shuffled-38": (200, 38, "shuffled")}


@pytest.mark.parametrize("case", SMALL_FOLDS.values(), ids=list(SMALL_FOLDS))
def test_small_grids_qhull_folds_certify_convex_hulls(case) -> None:
    import gudhi

    n, seed, how = case
    pts = range_grid(n, 3, 1e-13, seed=seed)
    order = (canonical_order(pts) if how == "canonical"
             else np.random.default_rng(seed).permutation(len(pts)))
    pts = pts[order]
    cells = certified_convex_cells(pts)
    st = gudhi.AlphaComplex(points=pts, precision="exact").create_simplex_tree()
    exact = {tuple(sorted(s)) for s, _ in st.get_simplices() if len(s) == 4}
    assert {tuple(sorted(c)) for c in cells.tolist()} == exact

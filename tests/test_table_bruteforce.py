"""The interval table against a brute force of the definitions (empty-ball tests on all points)."""

from __future__ import annotations

import numpy as np
import pytest
from reference import (
    brute_table,
    canonical,
    delaunay_simplices,
    expected_classes,
    gudhi_table,
    in_complex_by_definition,
    simplex_measures,
    smallest_circumspheres,
    strictly_inside,
)

from core import AlphaComplex

CASES = [(dim, n, seed) for dim in (2, 3) for n in (6, 15, 40) for seed in range(3)]


def random_points(dim: int, n: int, seed: int) -> np.ndarray:
    """(n, dim) float64: uniform, or a squashed cloud for odd seeds (long, thin simplices)."""
    rng = np.random.default_rng(100 * seed + 10 * dim + n)
    pts = rng.random((n, dim))
    if seed % 2:
        pts[:, 0] *= 20.0
    return pts


@pytest.fixture(params=CASES, ids=[f"{d}d-n{n}-s{s}" for d, n, s in CASES])
def built(request):
    """(points, ac, ours as {k: simplices}, brute-force table on our simplices)."""
    dim, n, seed = request.param
    pts = random_points(dim, n, seed)
    ac = AlphaComplex.from_points(pts)
    simplices = {k: np.asarray(ac.simplices(k), dtype=np.int64) for k in range(ac.dim + 1)}
    return np.asarray(ac.points), ac, simplices, brute_table(ac.points, simplices, ac.dim)


def test_cells_are_delaunay(built) -> None:
    pts, ac, simplices, _ = built
    centres, radii = smallest_circumspheres(pts, simplices[ac.dim])
    assert not strictly_inside(pts, centres, radii).any(), "a cell's circumsphere holds a point"
    from scipy.spatial import ConvexHull

    hull = ConvexHull(pts).volume
    assert simplex_measures(pts, simplices[ac.dim]).sum() == pytest.approx(hull, rel=1e-9)


@pytest.mark.parametrize("col", [0, 1, 2], ids=["enter", "regular", "interior"])
def test_intervals_equal_brute_force(built, col: int) -> None:
    _, ac, _, brute = built
    name = ("enter", "regular", "interior")[col]
    for k in range(ac.dim + 1):
        ours = np.asarray(ac.intervals(k))[:, col]
        ref = brute[name][k]
        assert np.array_equal(np.isinf(ours), np.isinf(ref)), f"inf pattern of {name}({k})"
        fin = np.isfinite(ref)
        np.testing.assert_allclose(ours[fin], ref[fin], rtol=1e-9, atol=1e-15,
                                   err_msg=f"{name} of {k}-simplices")


def test_complex_at_alpha_matches_definition(built) -> None:
    pts, ac, simplices, brute = built
    crit = np.unique(np.concatenate([brute["sigma"][k] for k in range(ac.dim + 1)]))
    alphas = np.concatenate([(crit[:-1] + crit[1:]) / 2, [crit[-1] * 2]])
    for alpha in alphas:
        inside = in_complex_by_definition(simplices, brute["sigma"], brute["attached"],
                                          ac.dim, alpha, len(pts))
        for k in range(ac.dim + 1):
            got = np.asarray(ac.classify(alpha, k)) > 0
            assert np.array_equal(got, inside[k]), f"{k}-simplices in C_alpha at {alpha!r}"


def test_classes_equal_brute_force_intervals(built) -> None:
    _, ac, _, brute = built
    vals = np.concatenate([brute[c][k] for c in ("enter", "regular", "interior")
                           for k in range(ac.dim + 1)])
    vals = np.unique(vals[np.isfinite(vals)])
    for alpha in np.concatenate([(vals[:-1] + vals[1:]) / 2, [vals[-1] * 3]]):
        for k in range(ac.dim + 1):
            iv = np.column_stack([brute[c][k] for c in ("enter", "regular", "interior")])
            np.testing.assert_array_equal(ac.classify(alpha, k), expected_classes(iv, alpha),
                                          err_msg=f"classes of {k}-simplices at {alpha!r}")


def test_reference_brute_force_equals_gudhi() -> None:
    """Self-check of the brute force on scipy's own triangulation, against gudhi."""
    for dim in (2, 3):
        pts = random_points(dim, 40, 1)
        simplices = delaunay_simplices(pts)
        brute, ref = brute_table(pts, simplices, dim), gudhi_table(pts)
        for k in range(dim + 1):
            assert np.array_equal(canonical(simplices[k])[0], ref[k][0])
            for col, name in enumerate(("enter", "regular", "interior"), start=1):
                np.testing.assert_allclose(brute[name][k] ** 2, ref[k][col], rtol=1e-9)

"""The certification's shared pass (core.build.cell_pass): the cell spheres are the table's bit for
bit, and every orientation or in-sphere sign it settles in floating point is the exact sign
(checked against exact integer arithmetic on every row of near-degenerate sets, where many
rows are left to the exact path)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import Delaunay
from test_exact_gudhi import cospherical, noisy_lattice, range_grid

from core.build.cell_pass import first_pass
from core.geometry.circumspheres import cell_spheres
from core.geometry.exact import exact_ints, exact_signs
from core.geometry.predicates import insphere_formula, orientation_formula

SETS = {
    "3d-lattice-1e-12": lambda: noisy_lattice(6, 3, 1e-12),
    "3d-lattice-1e-6": lambda: noisy_lattice(6, 3, 1e-6),
    "2d-lattice-1e-13": lambda: noisy_lattice(25, 2, 1e-13),
    "3d-range-grid-1e-13": lambda: range_grid(500, 3, 1e-13, seed=16),
    "3d-cospherical": cospherical,
    "3d-cospherical-decimal": lambda: cospherical() * 0.1 + 0.3,
    "3d-lattice-decimal": lambda: noisy_lattice(5, 3, 0.0) * 0.1 + 0.7,
    "2d-lattice-decimal": lambda: noisy_lattice(12, 2, 0.0) * 0.1 + 0.7,
    "3d-far-from-origin": lambda: np.random.default_rng(3).random((400, 3)) + 1e6,
    "2d-random": lambda: np.random.default_rng(4).random((600, 2)),
}


def _exact(formula, points: np.ndarray, base: np.ndarray, others: np.ndarray) -> np.ndarray:
    """Signs of `formula` on the differences points[others] - points[base], exactly."""
    ints = exact_ints(points[np.column_stack((base, others))])
    diff = ints[:, 1:] - ints[:, :1]
    vectors = [[diff[:, i, c] for c in range(points.shape[1])] for i in range(diff.shape[1])]
    return exact_signs(formula, vectors)


def _facets(tri) -> tuple[np.ndarray, np.ndarray]:
    """(t, q): each interior facet once from its lower cell t, q the vertex across it."""
    cells, nbs = tri.simplices, tri.neighbors
    t, i = np.nonzero(nbs > np.arange(len(cells))[:, None])
    u = nbs[t, i]
    j = np.argmax(nbs[u] == t[:, None], axis=1)
    return t, cells[u, j]


@pytest.mark.parametrize("name", sorted(SETS))
def test_settled_signs_are_exact_and_spheres_are_the_tables(name: str) -> None:
    points = SETS[name]()
    points = points / 2.0 ** np.floor(np.log2(np.abs(points).max()))
    tri = Delaunay(points)
    cells = tri.simplices.astype(np.int64)
    t, q = _facets(tri)
    shared = first_pass(points, cells, t, q)
    d = points.shape[1]

    orient = _exact(orientation_formula, points, cells[:, 0], cells[:, 1:])
    settled = ~shared.orient_doubt
    np.testing.assert_array_equal(shared.orient[settled], orient[settled])

    # inside <=> sign(V) == -cell sign <=> in-sphere determinant (base q) == (-1)^d cell sign
    insphere = _exact(insphere_formula, points, q, cells[t])
    settled = ~shared.side_doubt & (orient[t] != 0)
    np.testing.assert_array_equal(shared.side[settled], (-1) ** (d + 1) * insphere[settled])
    assert shared.side_doubt[(insphere == 0) & (orient[t] != 0)].all()

    r2, det, flat, bits = cell_spheres(points, cells)
    for ours, theirs in zip((shared.spheres.r2, shared.spheres.det, shared.spheres.flat,
                             shared.spheres.bits), (r2, det, flat, bits), strict=True):
        np.testing.assert_array_equal(ours, theirs)


def test_near_degenerate_sets_leave_rows_to_the_exact_path() -> None:
    """The bound is not vacuous: jittered lattices leave some signs open, random points few."""
    points = noisy_lattice(6, 3, 1e-12) / 8.0
    tri = Delaunay(points)
    shared = first_pass(points, tri.simplices.astype(np.int64), *_facets(tri))
    assert shared.side_doubt.any()
    points = np.random.default_rng(5).random((2000, 3))
    tri = Delaunay(points)
    shared = first_pass(points, tri.simplices.astype(np.int64), *_facets(tri))
    assert shared.side_doubt.mean() < 1e-3

"""The forests with the edges that short cycles close left out (core/topology/cycles.py) are the
forests of every edge, and the opening alpha from the triangle-order forest is the one from
the sorted edges; on random, lattice (many ties), weighted and 2D inputs."""

from __future__ import annotations

import numpy as np
import pytest

from core import AlphaComplex
from core.topology.betti import dual_forest, open_facets, vertex_spanning_forest
from core.topology.cycles import open_edges
from core.topology.opening import (
    lowest_enter_cofaces,
    opening_alpha,
    opening_alpha_of,
    reaching_alpha,
    triangle_forest,
    widest_opening,
)


def lattice(side: int, dim: int) -> np.ndarray:
    """(side**dim, dim) float64 grid points: cospherical groups, ties everywhere."""
    return np.stack(np.meshgrid(*[np.arange(float(side))] * dim), -1).reshape(-1, dim)


def complexes() -> list:
    rng = np.random.default_rng(5)
    return [
        ("random 3D", AlphaComplex.from_points(rng.random((1500, 3)))),
        ("random 2D", AlphaComplex.from_points(rng.random((1500, 2)))),
        ("lattice 3D", AlphaComplex.from_points(lattice(7, 3))),
        ("lattice 2D", AlphaComplex.from_points(lattice(20, 2))),
        ("clusters", AlphaComplex.from_points(np.concatenate(
            [rng.normal(c, 0.03, (300, 3)) for c in rng.random((4, 3))]))),
        ("weighted", AlphaComplex.from_points(rng.random((1200, 3)),
                                              weights=rng.random(1200) * 0.003)),
        ("weighted 2D", AlphaComplex.from_points(rng.random((1200, 2)),
                                                 weights=rng.random(1200) * 0.003)),
        ("density mode", AlphaComplex.from_points(rng.random((1500, 3)), density=8)),
        ("anisotropic mode", AlphaComplex.from_points(rng.random((1500, 3)), anisotropy=0.5)),
    ]


@pytest.fixture(scope="module", params=complexes(), ids=lambda c: c[0])
def ac(request) -> AlphaComplex:
    return request.param[1]


def test_open_edges_give_the_vertex_forest_of_all_edges(ac) -> None:
    edges, enter = ac.simplices(1), ac.intervals(1)[:, 0]
    candidates = open_edges(ac.face_ids(2), len(edges))
    assert len(candidates) < len(edges)
    full = vertex_spanning_forest(len(ac.points), edges, enter)
    short = vertex_spanning_forest(len(ac.points), edges, enter, candidates)
    for got, want in zip(short, full, strict=True):
        assert np.array_equal(got, want)


def test_open_facets_give_the_dual_forest_of_all_facets(ac) -> None:
    facet_enter = ac.intervals(ac.dim - 1)[:, 0]
    candidates = open_facets(ac.index, facet_enter)
    assert candidates is not None and len(candidates) < len(facet_enter)
    n_cells = len(ac.simplices(ac.dim))
    full = dual_forest(ac.facet_cells(), facet_enter, n_cells)
    short = dual_forest(ac.facet_cells(), facet_enter, n_cells, candidates)
    for got, want in zip(short, full, strict=True):
        assert got.dtype == want.dtype and np.array_equal(got, want)


def test_opening_from_the_triangle_forest_is_the_sorted_edges_one(ac) -> None:
    index, n = ac.index, len(ac.points)
    edge_first = lowest_enter_cofaces(index.face_ids(2), index.intervals(2)[:, 0],
                               len(index.simplices(1)))
    want = min(opening_alpha(n, index.simplices(1), edge_first),
               widest_opening(index, ac.points), float(index.spectrum()[-1]))
    assert opening_alpha_of(index, ac.points) == want
    a, b, weights = triangle_forest(index, n)
    assert len(a) == n - 1  # one piece (hidden points are not in ac.points)
    assert np.all(np.diff(weights) >= 0)
    for share in (0.1, 0.5, 0.9, 1.0):
        assert reaching_alpha(n, a, b, weights, share) == opening_alpha(
            n, index.simplices(1), edge_first, share)


def test_candidates_are_ignored_when_the_facets_do_not_ascend(ac) -> None:
    """The ring shortcut holds only for facets in row order: shuffled enter values (the
    caller's mistake) give the forest of all facets, not a wrong one."""
    facet_enter = np.random.default_rng(0).permutation(ac.intervals(ac.dim - 1)[:, 0])
    n_cells = len(ac.simplices(ac.dim))
    every = np.arange(len(facet_enter))
    full = dual_forest(ac.facet_cells(), facet_enter, n_cells)
    short = dual_forest(ac.facet_cells(), facet_enter, n_cells, every[::2])
    for got, want in zip(short, full, strict=True):
        assert np.array_equal(got, want)

"""Betti numbers, persistence pairs and solid components against gudhi and brute force."""

from __future__ import annotations

import gudhi
import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from core import AlphaComplex


def torus_surface(rng: np.random.Generator) -> np.ndarray:
    """(600, 3) jittered grid on a torus (R 1, r 0.35): one void, two tunnels at mid alpha."""
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, 40, endpoint=False),
                       np.linspace(0, 2 * np.pi, 15, endpoint=False))
    u, v = u.ravel(), v.ravel()
    ring = 1 + 0.35 * np.cos(v)
    pts = np.stack([ring * np.cos(u), ring * np.sin(u), 0.35 * np.sin(v)], axis=1)
    return pts + rng.normal(scale=2e-3, size=pts.shape)


def solid_torus(rng: np.random.Generator) -> np.ndarray:
    """(700, 3) uniform in a solid torus (R 1, r 0.35): one tunnel at mid alpha."""
    pts = rng.uniform(-1.35, 1.35, size=(6000, 3)) * [1, 1, 0.35 / 1.35]
    dist = np.hypot(np.hypot(pts[:, 0], pts[:, 1]) - 1, pts[:, 2])
    return pts[dist < 0.35][:700]


def sphere(rng: np.random.Generator) -> np.ndarray:
    """(400, 3) Fibonacci sphere, jittered: one void at mid alpha."""
    i = np.arange(400) + 0.5
    phi, theta = np.arccos(1 - 2 * i / 400), np.pi * (1 + 5**0.5) * i
    pts = np.stack([np.cos(theta) * np.sin(phi), np.sin(theta) * np.sin(phi), np.cos(phi)], 1)
    return pts + rng.normal(scale=1e-3, size=pts.shape)


def linked_rings(rng: np.random.Generator) -> np.ndarray:
    """(300, 3) two linked circles: two components and two tunnels at mid alpha."""
    t = np.linspace(0, 2 * np.pi, 150, endpoint=False)
    one = np.stack([np.cos(t), np.sin(t), np.zeros_like(t)], axis=1)
    two = np.stack([1 + np.cos(t), np.zeros_like(t), np.sin(t)], axis=1)
    return np.concatenate([one, two]) + rng.normal(scale=1e-3, size=(300, 3))


def annulus(rng: np.random.Generator) -> np.ndarray:
    """(500, 2) uniform in an annulus: one hole at mid alpha."""
    r, t = np.sqrt(rng.uniform(0.25, 1.0, 500)), rng.uniform(0, 2 * np.pi, 500)
    return np.stack([r * np.cos(t), r * np.sin(t)], axis=1)


SHAPES = {
    "cube3": (lambda rng: rng.random((400, 3)), None),
    "square2": (lambda rng: rng.random((400, 2)), None),
    "torus_surface": (torus_surface, (1, 2, 1)),
    "solid_torus": (solid_torus, (1, 1, 0)),
    "sphere": (sphere, (1, 0, 1)),
    "linked_rings": (linked_rings, (2, 2, 0)),
    "annulus": (annulus, (1, 1)),
}


def between_critical(ac: AlphaComplex, step: int = 1) -> np.ndarray:
    """Alphas strictly inside gaps of the spectrum (log middles), plus one past its end."""
    sp = ac.spectrum()
    lo, hi = sp[1:-1], sp[2:]
    wide = hi > lo * (1 + 1e-6)
    mids = np.sqrt(lo[wide] * hi[wide])[::step]
    return np.concatenate([[sp[1] / 2], mids, [sp[-1] * 2]])


def gudhi_tree(points: np.ndarray):
    """gudhi's alpha simplex tree with persistence computed (filtration = alpha**2)."""
    tree = gudhi.AlphaComplex(points=np.asarray(points)).create_simplex_tree()
    tree.compute_persistence()
    return tree


def gudhi_betti(tree, alphas: np.ndarray, dim: int) -> np.ndarray:
    """(s, dim) Betti numbers from gudhi's persistent_betti_numbers at each alpha."""
    rows = []
    for a in alphas:
        b = list(tree.persistent_betti_numbers(a * a, a * a))[:dim]
        rows.append(b + [0] * (dim - len(b)))
    return np.array(rows, dtype=np.int64)


@pytest.fixture(scope="module", params=sorted(SHAPES))
def case(request):
    make, expected = SHAPES[request.param]
    pts = make(np.random.default_rng(len(request.param)))
    ac = AlphaComplex.from_points(pts)
    return request.param, ac, gudhi_tree(ac.points), expected


def test_betti_equals_gudhi_between_critical_values(case) -> None:
    name, ac, tree, _ = case
    alphas = between_critical(ac, step=max(1, len(ac.spectrum()) // 300))
    ours = ac.signatures().betti[np.searchsorted(ac.spectrum(), alphas, side="right") - 1]
    theirs = gudhi_betti(tree, alphas, ac.dim)
    bad = np.flatnonzero((ours != theirs).any(axis=1))
    assert len(bad) == 0, f"{name}: at alpha {alphas[bad[:3]]} ours {ours[bad[:3]]} gudhi "\
        f"{theirs[bad[:3]]}"
    single = [ac.betti(a) for a in alphas[:: max(1, len(alphas) // 20)]]
    assert single == [tuple(b) for b in theirs[:: max(1, len(alphas) // 20)]]


def test_known_topology_appears(case) -> None:
    name, ac, _, expected = case
    betti = ac.signatures().betti
    assert tuple(betti[0]) == (len(ac.points),) + (0,) * (ac.dim - 1)
    assert tuple(betti[-1]) == (1,) + (0,) * (ac.dim - 1)
    if expected is not None:
        assert expected in {tuple(b) for b in betti}, f"{name}: never has Betti {expected}"


def test_persistence_equals_gudhi(case) -> None:
    name, ac, tree, _ = case
    pers = ac.persistence()
    for k in (0, ac.dim - 1):
        theirs = np.sqrt(tree.persistence_intervals_in_dimension(k))
        theirs = theirs[theirs[:, 1] > theirs[:, 0] * (1 + 1e-9)]
        ours = np.asarray(pers.diagram(k))
        ours = ours[ours[:, 1] > ours[:, 0] * (1 + 1e-9)]
        assert ours.shape == theirs.shape, f"{name} H{k}: {len(ours)} pairs, gudhi {len(theirs)}"
        ours, theirs = (p[np.lexsort((p[:, 1], p[:, 0]))] for p in (ours, theirs))
        np.testing.assert_allclose(ours, theirs, rtol=1e-7, atol=1e-12)


def test_persistence_pairs_count_betti(case) -> None:
    _, ac, _, _ = case
    pers, sig = ac.persistence(), ac.signatures()
    alphas = between_critical(ac, step=max(1, len(ac.spectrum()) // 100))
    rows = sig.betti[np.searchsorted(sig.alphas, alphas, side="right") - 1]
    for col, k in ((0, 0), (ac.dim - 1, ac.dim - 1)):
        pairs = pers.diagram(k)
        alive = ((pairs[:, 0] <= alphas[:, None]) & (alphas[:, None] < pairs[:, 1])).sum(axis=1)
        np.testing.assert_array_equal(alive, rows[:, col])


def test_euler_characteristic_matches_betti(case) -> None:
    _, ac, _, _ = case
    sig = ac.signatures()
    chi = sum((-1) ** k * (sig.counts(k)[:, 1:].sum(axis=1)) for k in range(ac.dim + 1))
    alternating = sum((-1) ** k * sig.betti[:, k] for k in range(ac.dim))
    np.testing.assert_array_equal(chi, alternating)


def brute_solid_components(ac: AlphaComplex, alpha: float) -> int:
    """Cells in the complex joined through shared facets, found by sorted facet keys."""
    d = ac.dim
    cells = np.asarray(ac.simplices(d))[ac.intervals(d)[:, 0] <= alpha]
    if len(cells) == 0:
        return 0
    faces = np.sort(np.concatenate([np.delete(cells, j, axis=1) for j in range(d + 1)]), axis=1)
    owner = np.tile(np.arange(len(cells)), d + 1)
    _, key = np.unique(faces, axis=0, return_inverse=True)
    order = np.argsort(key.ravel(), kind="stable")
    key, owner = key.ravel()[order], owner[order]
    same = key[1:] == key[:-1]
    graph = coo_matrix((np.ones(int(same.sum())), (owner[:-1][same], owner[1:][same])),
                       shape=(len(cells), len(cells)))
    return connected_components(graph, directed=False)[0]


def test_solid_components_equal_brute_force(case) -> None:
    name, ac, _, _ = case
    sig = ac.signatures()
    rows = np.unique(np.linspace(0, len(sig.alphas) - 1, 40).astype(int))
    got = [int(sig.solid_components[i]) for i in rows]
    want = [brute_solid_components(ac, sig.alphas[i]) for i in rows]
    assert got == want, name


def own_complex_tree(ac: AlphaComplex):
    """gudhi SimplexTree of our own simplices, filtered by our enter values, persistence done."""
    tree = gudhi.SimplexTree()
    for k in range(ac.dim + 1):
        rows, enters = ac.simplices(k).tolist(), ac.intervals(k)[:, 0].tolist()
        for simplex, enter in zip(rows, enters, strict=True):
            tree.insert(simplex, enter)
    tree.compute_persistence()
    return tree


@settings(max_examples=25, deadline=None)
@given(
    dim=st.sampled_from([2, 3]),
    cells=st.lists(st.integers(0, 7), min_size=40, max_size=90),
)
def test_betti_on_lattice_points_equals_homology(dim: int, cells: list[int]) -> None:
    """Degenerate input (coarse lattice, cospherical points, duplicates, flat cells).

    The Delaunay triangulation is not unique here, so the reference is the homology of the
    complex we built (gudhi on our own simplices and enter values), not gudhi's alpha complex.
    """
    pts = np.array(cells[: len(cells) // dim * dim], dtype=np.float64).reshape(-1, dim) / 7
    pts = np.concatenate([pts, np.eye(dim + 1, dim)])
    ac = AlphaComplex.from_points(pts)
    assume(ac.dim == dim)
    alphas = between_critical(ac)
    ours = ac.signatures().betti[np.searchsorted(ac.spectrum(), alphas, side="right") - 1]
    tree = own_complex_tree(ac)
    theirs = np.array([(list(tree.persistent_betti_numbers(a, a)) + [0] * dim)[:dim]
                       for a in alphas])
    np.testing.assert_array_equal(ours, theirs)
    for k in (0, dim - 1):
        want = tree.persistence_intervals_in_dimension(k).reshape(-1, 2)
        want = want[want[:, 1] > want[:, 0]]
        got = np.asarray(ac.persistence().diagram(k))
        want, got = (p[np.lexsort((p[:, 1], p[:, 0]))] for p in (want, got))
        np.testing.assert_array_equal(got, want)


def test_betti_outside_spectrum() -> None:
    ac = AlphaComplex.from_points(np.random.default_rng(0).random((50, 3)))
    assert ac.betti(0.0) == (50, 0, 0)
    assert ac.betti(1e9) == (1, 0, 0)
    assert ac.betti(float(np.inf)) == (1, 0, 0)

"""The union-find helpers of core.topology.union_find against a plain Python union-find."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from core.topology.union_find import ordered_forest, rank_forest, spanning_forest, younger_roots


@st.composite
def graphs(draw):
    """(n, u, v, weight): a simple graph with small integer weights (many ties)."""
    n = draw(st.integers(1, 30))
    pairs = draw(st.sets(st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)), max_size=80))
    pairs = sorted((min(a, b), max(a, b)) for a, b in pairs if a != b)
    pairs = sorted(set(pairs))
    weight = draw(st.lists(st.integers(1, 6), min_size=len(pairs), max_size=len(pairs)))
    u = np.array([a for a, _ in pairs], dtype=np.int64)
    v = np.array([b for _, b in pairs], dtype=np.int64)
    return n, u, v, np.array(weight, dtype=np.float64)


def components(n: int, u: np.ndarray, v: np.ndarray) -> int:
    """Connected components of n nodes and edges (u, v), by scipy."""
    graph = coo_matrix((np.ones(len(u)), (u, v)), shape=(n, n))
    return connected_components(graph, directed=False)[0]


@settings(max_examples=200, deadline=None)
@given(graphs())
def test_forest_counts_components_at_every_threshold(graph) -> None:
    n, u, v, weight = graph
    forest, a, b = spanning_forest(n, u, v, weight)
    assert np.all(np.diff(forest) >= 0)
    assert components(n, a, b) == n - len(forest)
    for w in range(7):
        low = weight <= w
        assert components(n, u[low], v[low]) == n - np.count_nonzero(forest <= w)


def python_kruskal(n: int, u: list[int], v: list[int]) -> list[int]:
    """Positions of the edges, in the given order, that join two components (textbook)."""
    parent = list(range(n))

    def find(x: int) -> int:
        while parent[x] != x:
            x = parent[x]
        return x

    joined = []
    for i, (x, y) in enumerate(zip(u, v, strict=True)):
        rx, ry = find(x), find(y)
        if rx != ry:
            parent[rx] = ry
            joined.append(i)
    return joined


@settings(max_examples=200, deadline=None)
@given(st.integers(1, 30).flatmap(lambda n: st.tuples(
    st.just(n), st.lists(st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)), max_size=90))))
def test_ordered_forest_is_kruskal_in_the_given_order(graph) -> None:
    n, pairs = graph  # self-loops, repeats and both orientations included
    u = np.array([a for a, _ in pairs], dtype=np.int64)
    v = np.array([b for _, b in pairs], dtype=np.int64)
    joined = ordered_forest(n, u, v)
    assert joined.dtype == np.int64
    assert joined.tolist() == python_kruskal(n, u.tolist(), v.tolist())


@settings(max_examples=200, deadline=None)
@given(graphs(), st.randoms(use_true_random=False))
def test_rank_forest_joins_as_edges_arrive_with_their_later_node(graph, rnd) -> None:
    n, u, v, _ = graph
    rank = np.arange(1, n + 1, dtype=np.int64)
    rnd.shuffle(rank)
    arrival = np.maximum(rank[u], rank[v])
    order = np.argsort(arrival, kind="stable")
    expected = arrival[order][python_kruskal(n, u[order].tolist(), v[order].tolist())]
    assert rank_forest(rank, u, v).tolist() == expected.tolist()


def python_elder_rule(key: np.ndarray, a: np.ndarray, b: np.ndarray) -> list[int]:
    """Younger root key at each merge, by a textbook union-find that tracks each root's oldest."""
    parent = list(range(len(key)))
    oldest = [int(k) for k in key]

    def find(x: int) -> int:
        while parent[x] != x:
            x = parent[x]
        return x

    out = []
    for x, y in zip(a.tolist(), b.tolist(), strict=True):
        rx, ry = find(x), find(y)
        assert rx != ry, "a forest edge closed a cycle"
        out.append(min(oldest[rx], oldest[ry]))
        parent[rx] = ry
        oldest[ry] = max(oldest[rx], oldest[ry])
    return out


@settings(max_examples=200, deadline=None)
@given(graphs(), st.randoms(use_true_random=False))
def test_younger_roots_equals_union_find(graph, rnd) -> None:
    n, u, v, weight = graph
    _, a, b = spanning_forest(n, u, v, weight)
    key = np.array(rnd.sample(range(n), n), dtype=np.int64)
    assert younger_roots(key, a, b).tolist() == python_elder_rule(key, a, b)


def test_younger_roots_on_a_path_in_both_orders() -> None:
    key = np.array([5, 1, 4, 0, 3, 2])
    a, b = np.arange(5), np.arange(1, 6)
    assert younger_roots(key, a, b).tolist() == [1, 4, 0, 3, 2]
    assert younger_roots(key, a[::-1], b[::-1]).tolist() == [2, 0, 3, 1, 4]
    assert younger_roots(key, a[:0], b[:0]).tolist() == []

"""Betti numbers and solid components of the alpha complex at any alpha, from three forests.

Built once per complex in O(n log n), then every alpha is a handful of `searchsorted` calls:
- b0: vertices minus the edges of the spanning forest (edges in order of entry) already in;
- holes (2D) / voids (3D): by Alexander duality, the regions of the complement minus one. The
  complement is the dual graph (cells plus one outside node, facets as edges) taken in order of
  decreasing alpha, so its regions come from a spanning forest too;
- tunnels (3D): from the Euler characteristic, b1 = b0 + b2 - chi;
- solid components: cells in the complex joined through shared facets (CGAL's definition).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from core.arrays import ascends, owned_readonly
from core.parallel import searchsorted, searchsorted_ascending
from core.query.alpha import radius
from core.query.index import TableIndex
from core.topology.cycles import inner_ridges, open_edges, ring_closers
from core.topology.union_find import later_forest, ordered_forest, rank_forest

Search = Callable[[np.ndarray, np.ndarray, str], np.ndarray]  # np.searchsorted's signature


@dataclass(frozen=True, eq=False)
class Topology:
    """Sorted event arrays from which Betti numbers and solid components follow at any alpha."""

    dim: int
    n_cells: int
    enter_sorted: tuple[np.ndarray, ...]  # per k: (n_k,) float64 ascending enter of k-simplices
    vertex_forest: np.ndarray  # (f0,) float64 ascending enter of edges that join components
    dual_forest: np.ndarray  # (fd,) float64 ascending enter of facets that join complement regions
    dual_edges: np.ndarray  # (fd, 2) int64 their dual nodes (cells; n_cells = outside), by merge
    solid_forest: np.ndarray  # (fs,) float64 ascending alpha at which facets join solid parts

    def betti(self, alpha: float) -> tuple[int, ...]:
        """(b0, b1) in 2D, (b0, b1, b2) in 3D at one alpha (a radius >= 0)."""
        at = np.array([radius(alpha)], dtype=np.float64)
        return tuple(int(b) for b in self.betti_many(at)[0])

    def betti_many(self, alphas: np.ndarray) -> np.ndarray:
        """(s, dim) int32 Betti numbers at every alpha of the (s,) array `alphas`."""
        alphas = np.asarray(alphas, dtype=np.float64)
        return self._betti(alphas, [searchsorted(e, alphas, "right") for e in self.enter_sorted],
                           searchsorted)

    def solid_components(self, alphas: np.ndarray) -> np.ndarray:
        """(s,) int32 number of facet-connected groups of cells in the complex at each alpha."""
        alphas = np.asarray(alphas, dtype=np.float64)
        cells_in = searchsorted(self.enter_sorted[self.dim], alphas, side="right")
        return self._solids(alphas, cells_in, searchsorted)

    def curves(self, alphas: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(betti_many, solid_components, cells in: (s,) intp) at every alpha of the ascending
        (s,) `alphas`, all from one count of the simplices in per dimension."""
        alphas = np.asarray(alphas, dtype=np.float64)
        n_in = [searchsorted_ascending(e, alphas, "right") for e in self.enter_sorted]
        return (self._betti(alphas, n_in, searchsorted_ascending),
                self._solids(alphas, n_in[self.dim], searchsorted_ascending), n_in[self.dim])

    def _betti(self, alphas: np.ndarray, n_in: list[np.ndarray], search: Search) -> np.ndarray:
        """Betti numbers from the (s,) numbers of k-simplices in at each alpha."""
        out = np.empty((len(alphas), self.dim), dtype=np.int32)
        b0 = n_in[0] - search(self.vertex_forest, alphas, "right")
        open_forest = len(self.dual_forest) - search(self.dual_forest, alphas, "right")
        out[:, -1] = cavities = (self.n_cells - n_in[self.dim]) - open_forest
        out[:, 0] = b0
        if self.dim == 3:
            chi = n_in[0] - n_in[1] + n_in[2] - n_in[3]
            out[:, 1] = b0 + cavities - chi
        return out

    def _solids(self, alphas: np.ndarray, cells_in: np.ndarray, search: Search) -> np.ndarray:
        """Solid components from the (s,) numbers of cells in at each alpha."""
        return (cells_in - search(self.solid_forest, alphas, "right")).astype(np.int32)


def build_topology(ac) -> Topology:
    """The Topology of an AlphaComplex, from its public table; O(n log n)."""
    dim = ac.dim
    enter = [np.asarray(ac.index.level(k).enter, dtype=np.float64)
             for k in range(dim + 1)]  # the table's own columns: no stacked (n_k, 3) copy
    facet_cells = np.asarray(ac.facet_cells())
    edges = np.asarray(ac.simplices(1))
    vertex_forest = vertex_spanning_forest(len(enter[0]), edges, enter[1], open_edges(
        ac.face_ids(2), len(edges)))[0]  # edges arrive in row order
    dual_values, dual_edges = dual_forest(facet_cells, enter[dim - 1], len(enter[dim]),
                                          open_facets(ac.index, enter[dim - 1]))
    return Topology(
        dim=dim,
        n_cells=len(enter[dim]),
        enter_sorted=tuple(ascending(e) for e in enter),
        vertex_forest=owned_readonly(vertex_forest),
        dual_forest=owned_readonly(dual_values[::-1]),
        dual_edges=owned_readonly(dual_edges),
        solid_forest=owned_readonly(solid_forest(facet_cells, enter[dim])),
    )


def open_facets(index: TableIndex, facet_enter: np.ndarray) -> np.ndarray | None:
    """(c,) int64 ascending facet rows of the table `index` that no ridge ring closes in the
    dual forest (core/topology/cycles.py); None (all) unless the facets arrive in row order."""
    if not ascends(facet_enter):
        return None
    dim = index.dim
    ridge_ids = index.face_ids(dim - 1)
    inner = inner_ridges(ridge_ids, index.facet_cells(), len(index.simplices(dim - 2)))
    return np.flatnonzero(~ring_closers(index.first_cofaces(dim - 1), inner, len(facet_enter)))


def vertex_spanning_forest(n_vertices: int, edges: np.ndarray, edge_enter: np.ndarray,
                           candidates: np.ndarray | None = None):
    """(enter, a, b) of the edges that join components, by entry: (f,) float64, (f,) int64.

    Edges are (n_e, 2) int sorted by their (n_e,) enter values (ties: in the given order);
    `candidates`: ascending rows that may join (all others close a cycle), None = all.
    """
    rows = np.arange(len(edges)) if candidates is None else candidates
    ends = edges[rows]
    joined = rows[ordered_forest(n_vertices, ends[:, 0], ends[:, 1])]
    return (edge_enter[joined], edges[joined, 0].astype(np.int64),
            edges[joined, 1].astype(np.int64))


def dual_forest(facet_cells: np.ndarray, facet_enter: np.ndarray, n_cells: int,
                candidates: np.ndarray | None = None) -> tuple:
    """Spanning forest of the complement's dual graph taken in decreasing alpha.

    facet_cells: (n_f, 2) int, -1 = outside. Returns (enter, edges): (fd,) float64 facet
    enter values in merge order (descending) and (fd, 2) int64 their dual nodes (cells, and
    n_cells for the outside). A cell with several hull facets keeps its first to arrive.
    `candidates`: ascending facet rows that may join when facet_enter ascends (the others
    close a ring), None = all.
    """
    if candidates is not None and not ascends(facet_enter):
        candidates = None  # rings close by row order only when the rows ascend: take all
    order = (ascending_order(facet_enter) if candidates is None else candidates)[::-1]
    sides = facet_cells[order]
    sides[sides < 0] = n_cells
    u, v = np.minimum(sides[:, 0], sides[:, 1]), np.maximum(sides[:, 0], sides[:, 1])
    del sides
    hull = np.flatnonzero(v == n_cells)
    first_hull = np.full(n_cells + 1, len(order), dtype=np.int64)
    np.minimum.at(first_hull, u[hull], hull)
    keep = u != v
    keep[hull] &= first_hull[u[hull]] == hull
    arrival = np.flatnonzero(keep)
    joined = arrival[ordered_forest(n_cells + 1, u[arrival], v[arrival])]
    facets = order[joined]
    return facet_enter[facets], np.stack([u[joined], v[joined]], axis=1).astype(np.int64)


def solid_forest(facet_cells: np.ndarray, cell_enter: np.ndarray) -> np.ndarray:
    """(fs,) float64 ascending alphas at which an inner facet first joins two separate solids."""
    inner = facet_cells[(facet_cells[:, 0] >= 0) & (facet_cells[:, 1] >= 0)]
    a, b = np.minimum(inner[:, 0], inner[:, 1]), np.maximum(inner[:, 0], inner[:, 1])
    del inner
    if ascends(cell_enter):  # cell x arrives at rank x + 1
        return cell_enter[later_forest(len(cell_enter), b, a)]
    order = ascending_order(cell_enter)
    rank = np.empty(len(cell_enter), dtype=np.int64)
    rank[order] = np.arange(1, len(cell_enter) + 1)
    return cell_enter[order[rank_forest(rank, a, b) - 1]]


def ascending_order(values: np.ndarray) -> np.ndarray:
    """(n,) int64 stable ascending order; the identity (no sort) for already sorted values."""
    if ascends(values):
        return np.arange(len(values))
    return np.argsort(values, kind="stable")


def ascending(values: np.ndarray) -> np.ndarray:
    """(n,) float64 ascending, contiguous and read-only; no sort when already in order."""
    values = np.asarray(values, dtype=np.float64)
    if not ascends(values):
        values = np.sort(values)
    return owned_readonly(values)

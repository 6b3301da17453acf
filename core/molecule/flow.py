"""The discrete flow of empty tetrahedra (Edelsbrunner, Facello, Liang 1998) and the regions
it defines: tetrahedra that flow to infinity (the outside), and the rest split into pockets
(with mouths) and voids (without). See `pockets` for the definitions."""

from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import breadth_first_order, connected_components

from core.molecule.intersections import radical_point
from core.molecule.regions import DualFacts


def barycentric_orthocentres(facts: DualFacts) -> np.ndarray:
    """(c, 4) float64 barycentric coordinates of each cell's orthocentre (the point of equal
    power to its four balls); a negative coordinate j puts the orthocentre beyond the facet
    opposite vertex j. A flat cell (no volume) gets its centroid: it flows nowhere."""
    c = facts.centres[facts.cells]
    c = c - c[:, :1]
    edges = np.transpose(c[:, 1:], (0, 2, 1))  # (c, 3, 3) columns c1-c0, c2-c0, c3-c0
    flat = ~(np.abs(np.linalg.det(edges)) > 0)
    edges[flat] = np.eye(3)
    with np.errstate(all="ignore"):
        z, _ = radical_point(c, facts.radii[facts.cells])
    z[flat] = 0.25
    lam = np.linalg.solve(edges, z[:, :, None])[:, :, 0]
    lam[flat] = 0.25
    return np.concatenate([1.0 - lam.sum(1, keepdims=True), lam], 1)


def _across(facts: DualFacts) -> np.ndarray:
    """(c, 4) int64 the cell beyond the facet opposite each vertex (-1 = beyond the hull)."""
    sides = facts.facet_cells[facts.tet_faces]  # (c, 4, 2)
    own = np.arange(len(facts.cells))[:, None]
    return np.where(sides[..., 0] == own, sides[..., 1], sides[..., 0])


def flow_to_infinity(facts: DualFacts) -> np.ndarray:
    """(c,) bool: empty cells from which the flow reaches beyond the hull.

    An empty cell flows into its neighbour across a facet not in the complex when its
    orthocentre lies strictly beyond that facet; a hull facet leads to infinity."""
    n = len(facts.cells)
    lam = barycentric_orthocentres(facts)
    nb = _across(facts)
    open_facet = ~facts.facet_in[facts.tet_faces]
    step = (~facts.cell_in)[:, None] & open_facet & (lam < 0)
    src = np.repeat(np.arange(n), 4).reshape(n, 4)[step]
    dst = np.where(nb < 0, n, nb)[step]
    backward = coo_matrix((np.ones(len(src)), (dst, src)), shape=(n + 1, n + 1)).tocsr()
    reached = breadth_first_order(backward, n, directed=True, return_predecessors=False)
    out = np.zeros(n + 1, bool)
    out[reached] = True
    return out[:n]


def inner_regions(facts: DualFacts, outside: np.ndarray) -> tuple[np.ndarray, int]:
    """((c,) int64 region of each empty cell that does not flow to infinity, -1 else; count):
    such cells joined across facets not in the complex."""
    n = len(facts.cells)
    inner = ~facts.cell_in & ~outside
    a, b = facts.facet_cells[:, 0], facts.facet_cells[:, 1]
    keep = ~facts.facet_in & (a >= 0) & (b >= 0)
    keep[keep] = inner[a[keep]] & inner[b[keep]]
    graph = coo_matrix((np.ones(int(keep.sum())), (a[keep], b[keep])), shape=(n, n))
    _, comp = connected_components(graph, directed=False)
    _, labels = np.unique(comp[inner], return_inverse=True)
    out = np.full(n, -1, np.int64)
    out[inner] = labels
    return out, int(labels.max()) + 1 if len(labels) else 0


def mouth_facets(facts: DualFacts, regions: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """((m,) int64 facets not in the complex between a region and the outside flow (or
    beyond the hull), (m,) int64 their region)."""
    a, b = facts.facet_cells[:, 0], facts.facet_cells[:, 1]
    ra = np.where(a >= 0, regions[np.maximum(a, 0)], -1)
    rb = np.where(b >= 0, regions[np.maximum(b, 0)], -1)
    mouth = ~facts.facet_in & ((ra >= 0) != (rb >= 0))
    return np.flatnonzero(mouth), np.maximum(ra, rb)[mouth]

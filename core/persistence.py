"""Persistence pairs that union-find gives: components (H0) and holes (2D, H1) or voids (3D, H2).

Components are all born at alpha 0 and die at the edges of the vertex spanning forest. Holes and
voids are the bounded regions of the complement: a region closes (is born) when the facet that
separates it from an older region enters, and dies when its last cell fills in. The elder rule
on the complement's dual forest (processed in decreasing alpha) pairs each closing facet with
the cell that fills the region. Pairs of zero length are left out.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .forest import younger_roots
from .topology import Topology


@dataclass(frozen=True, eq=False)
class Persistence:
    """Persistence diagrams as (n, 2) float64 read-only arrays of (birth, death) alphas.

    Deaths are inf for classes that never die. Rows are sorted by decreasing lifetime.
    """

    dim: int
    components: np.ndarray  # H0
    cavities: np.ndarray  # H1 (holes) in 2D, H2 (voids) in 3D

    def diagram(self, k: int) -> np.ndarray:
        """(n, 2) float64 pairs of homology dimension k (0, or dim - 1)."""
        if k == 0:
            return self.components
        if k == self.dim - 1:
            return self.cavities
        raise ValueError(f"only dimensions 0 and {self.dim - 1} are computed, not {k}")


def compute_persistence(ac, topology: Topology) -> Persistence:
    """Persistence pairs of the components and of the holes/voids of an AlphaComplex."""
    n_vertices = len(topology.enter_sorted[0])
    deaths = topology.vertex_forest
    essential = n_vertices - len(deaths)
    components = np.stack(
        [np.zeros(n_vertices), np.concatenate([deaths, np.full(essential, np.inf)])], axis=1
    )
    cell_enter = np.asarray(ac.intervals(ac.dim)[:, 0], dtype=np.float64)
    return Persistence(
        dim=ac.dim,
        components=_by_lifetime(components),
        cavities=_by_lifetime(cavity_pairs(topology, cell_enter)),
    )


def cavity_pairs(topology: Topology, cell_enter: np.ndarray) -> np.ndarray:
    """(n, 2) float64 (birth, death) of every hole/void: closing facet, filling cell."""
    n_cells = len(cell_enter)
    order = np.argsort(cell_enter, kind="stable")
    key = np.empty(n_cells + 1, dtype=np.int64)
    key[order] = np.arange(n_cells)
    key[n_cells] = n_cells
    edges = topology.dual_edges
    young = younger_roots(key, edges[:, 0], edges[:, 1])
    births = topology.dual_forest[::-1]
    return np.stack([births, cell_enter[order[young]]], axis=1)


def _by_lifetime(pairs: np.ndarray) -> np.ndarray:
    """Pairs with death > birth, longest first (ties by birth), read-only."""
    pairs = pairs[pairs[:, 1] > pairs[:, 0]]
    order = np.lexsort((pairs[:, 0], -(pairs[:, 1] - pairs[:, 0])))
    out = np.ascontiguousarray(pairs[order])
    out.flags.writeable = False
    return out

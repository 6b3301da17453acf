"""Signatures: Betti numbers, solid components, measures and class counts at every critical alpha.

Edelsbrunner's Alpha Shapes viewer plotted these curves to help choose alpha. Everything comes
from sorted event arrays and cumulative sums, so the whole spectrum costs O(n log n).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from core.arrays import readonly
from core.geometry.circumspheres import facet_sizes
from core.query.alpha import threshold
from core.query.index import TableIndex
from core.topology.betti import Topology, ascending, ascending_order
from core.topology.opening import opening_alpha_of


@dataclass(frozen=True, eq=False)
class Signatures:
    """Curves over the spectrum; entry i holds for alpha in [alphas[i], alphas[i+1]).

    All arrays are read-only. `measure` is area (2D) or volume (3D); `boundary_measure` is the
    perimeter (2D) or surface area (3D) of the REGULAR facets.
    """

    dim: int
    alphas: np.ndarray  # (s,) float64 ascending, == ac.spectrum()
    betti: np.ndarray  # (s, dim) int32: b0, b1 (, b2)
    solid_components: np.ndarray  # (s,) int32
    measure: np.ndarray  # (s,) float64
    boundary_measure: np.ndarray  # (s,) float64
    # where triangles put nearly all points in pieces (core.topology.opening)
    opening_alpha: float
    #: per k: the table's own (enter, regular, interior) (n_k,) columns (index.level(k): no
    #: stacked copy of the table)
    intervals: tuple = field(repr=False)
    _sorted: dict = field(default_factory=dict, repr=False)  # k -> sorted thresholds, lazily

    def index(self, alpha: float) -> int:
        """Row of the spectrum entry in force at alpha (-1 below the first entry)."""
        return int(np.searchsorted(self.alphas, alpha, side="right")) - 1

    def counts(self, k: int) -> np.ndarray:
        """(s, 4) int64 numbers of k-simplices per class (core.query.classes order) at every
        entry."""
        return class_counts(self._thresholds(k), self.alphas)

    def counts_at(self, alpha: float) -> np.ndarray:
        """(dim + 1, 4) int64 numbers of k-simplices per class at one alpha."""
        at = np.array([threshold(alpha)], dtype=np.float64)  # inf: the hull stays REGULAR
        return np.concatenate([class_counts(self._thresholds(k), at) for k in range(self.dim + 1)])

    def _thresholds(self, k: int) -> tuple[np.ndarray, ...]:
        """Ascending (enter, regular, interior) of k-simplices, sorted on first use."""
        if k not in self._sorted:
            enter, regular, interior = self.intervals[k]
            enter = ascending(enter)
            rest = (enter, enter) if k == self.dim else (ascending(regular), ascending(interior))
            self._sorted[k] = (enter, *rest)
        return self._sorted[k]


def level_columns(index: TableIndex) -> tuple[tuple[np.ndarray, np.ndarray, np.ndarray], ...]:
    """Per k, the (enter, regular, interior) columns the table `index` holds: what Signatures
    sorts its class thresholds from, shared with the table rather than stacked anew."""
    return tuple((level.enter, level.regular, level.interior)
                 for level in (index.level(k) for k in range(index.dim + 1)))


def compute_signatures(index: TableIndex, points: np.ndarray, topology: Topology) -> Signatures:
    """Signatures over the whole spectrum of the table `index` of a complex with (m, dim)
    `points`, from its `topology`."""
    dim = index.dim
    alphas = np.asarray(index.spectrum(), dtype=np.float64)
    cell_enter = np.asarray(index.level(dim).enter, dtype=np.float64)
    order = ascending_order(cell_enter)
    betti, solids, cells_in = topology.curves(alphas)
    measure = np.concatenate([[0.0], np.cumsum(np.asarray(index.cell_measures())[order])])
    boundary = boundary_sums(index.facet_cells(), order,
                             facet_measures(points, index.simplices(dim - 1)))
    return Signatures(
        dim=dim,
        alphas=readonly(alphas),
        betti=readonly(betti),
        solid_components=readonly(solids),
        measure=readonly(measure[cells_in]),
        boundary_measure=readonly(boundary[cells_in]),
        opening_alpha=opening_alpha_of(index, points),
        intervals=level_columns(index),
    )


def boundary_sums(facet_cells: np.ndarray, cell_order: np.ndarray, sizes: np.ndarray):
    """(c + 1,) float64 size of the REGULAR facets once the first j cells (by enter) are in.

    A facet turns regular with the first of its cells and interior with the second (never on
    the hull), so both events are cell ranks: two bincounts and a cumulative sum, no sort.
    """
    rank = np.empty(len(cell_order), dtype=np.int64)
    rank[cell_order] = np.arange(len(cell_order))
    sides = np.where(facet_cells >= 0, rank[np.maximum(facet_cells, 0)], len(cell_order))
    first, second = np.minimum(sides[:, 0], sides[:, 1]), np.maximum(sides[:, 0], sides[:, 1])
    width = len(cell_order) + 1
    change = np.bincount(first, sizes, width) - np.bincount(second, sizes, width)
    return np.concatenate([[0.0], np.cumsum(change[:-1])])


def class_counts(thresholds: tuple, alphas: np.ndarray) -> np.ndarray:
    """(s, 4) int64 class counts from ascending (enter, regular, interior) arrays."""
    total = len(thresholds[0])
    passed = [np.searchsorted(t, alphas, side="right") for t in thresholds]
    return np.stack(
        [total - passed[0], passed[0] - passed[1], passed[1] - passed[2], passed[2]], axis=1
    ).astype(np.int64)


def facet_measures(points: np.ndarray, facets: np.ndarray) -> np.ndarray:
    """(n_f,) float64 length (2D edges) or area (3D triangles) of (n_f, dim) facets."""
    return facet_sizes(np.asarray(points, dtype=np.float64), np.asarray(facets))

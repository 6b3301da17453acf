"""Signatures: Betti numbers, solid components, measures and class counts at every critical alpha.

Edelsbrunner's Alpha Shapes viewer plotted these curves to help choose alpha. Everything comes
from sorted event arrays and cumulative sums, so the whole spectrum costs O(n log n).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .topology import Topology, ascending

#: Column order of `Signatures.counts`: the four classes of `AlphaComplex.classify`.
CLASSES = ("exterior", "singular", "regular", "interior")


@dataclass(frozen=True, eq=False)
class Signatures:
    """Curves over the spectrum; entry i holds for alpha in [alphas[i], alphas[i+1]).

    All arrays are read-only. `measure` is area (2D) or volume (3D); `boundary_measure` is the
    perimeter (2D) or surface area (3D) of the REGULAR facets.
    """

    dim: int
    alphas: np.ndarray  # (s,) float64 ascending, == ac.spectrum()
    betti: np.ndarray  # (s, dim) int64: b0, b1 (, b2)
    solid_components: np.ndarray  # (s,) int64
    measure: np.ndarray  # (s,) float64
    boundary_measure: np.ndarray  # (s,) float64
    thresholds: tuple = field(repr=False)  # per k: ascending (enter, regular, interior) arrays

    def index(self, alpha: float) -> int:
        """Row of the spectrum entry in force at alpha (-1 below the first entry)."""
        return int(np.searchsorted(self.alphas, alpha, side="right")) - 1

    def counts(self, k: int) -> np.ndarray:
        """(s, 4) int64 numbers of k-simplices per class (CLASSES order) at every entry."""
        return class_counts(self.thresholds[k], self.alphas)

    def counts_at(self, alpha: float) -> np.ndarray:
        """(dim + 1, 4) int64 numbers of k-simplices per class at one alpha."""
        at = np.array([alpha], dtype=np.float64)
        return np.concatenate([class_counts(t, at) for t in self.thresholds])


def compute_signatures(ac, topology: Topology) -> Signatures:
    """Signatures of an AlphaComplex over its whole spectrum."""
    dim = ac.dim
    alphas = np.asarray(ac.spectrum(), dtype=np.float64)
    thresholds = tuple(_thresholds(ac.intervals(k), k == dim) for k in range(dim + 1))
    facet_sizes = facet_measures(ac.points, ac.simplices(dim - 1))
    facet_iv = np.asarray(ac.intervals(dim - 1), dtype=np.float64)
    return Signatures(
        dim=dim,
        alphas=_ro(alphas),
        betti=_ro(topology.betti_many(alphas)),
        solid_components=_ro(topology.solid_components(alphas)),
        measure=_ro(running_sum(ac.intervals(dim)[:, 0], ac.cell_measures(), alphas)),
        boundary_measure=_ro(
            running_sum(facet_iv[:, 1], facet_sizes, alphas)
            - running_sum(facet_iv[:, 2], facet_sizes, alphas)
        ),
        thresholds=thresholds,
    )


def class_counts(thresholds: tuple, alphas: np.ndarray) -> np.ndarray:
    """(s, 4) int64 class counts from ascending (enter, regular, interior) arrays."""
    total = len(thresholds[0])
    passed = [np.searchsorted(t, alphas, side="right") for t in thresholds]
    return np.stack(
        [total - passed[0], passed[0] - passed[1], passed[1] - passed[2], passed[2]], axis=1
    ).astype(np.int64)


def running_sum(events: np.ndarray, weights: np.ndarray, alphas: np.ndarray) -> np.ndarray:
    """(s,) float64 sum of weights whose event alpha <= each alpha; inf events never count."""
    events = np.asarray(events, dtype=np.float64)
    order = np.argsort(events, kind="stable")
    totals = np.concatenate([[0.0], np.cumsum(np.asarray(weights, dtype=np.float64)[order])])
    return totals[np.searchsorted(events[order], alphas, side="right")]


def facet_measures(points: np.ndarray, facets: np.ndarray) -> np.ndarray:
    """(n_f,) float64 length (2D edges) or area (3D triangles) of (n_f, dim) facets."""
    p = np.asarray(points, dtype=np.float64)
    f = np.asarray(facets)
    edges = [p[f[:, j]] - p[f[:, 0]] for j in range(1, f.shape[1])]
    if len(edges) == 1:
        return np.linalg.norm(edges[0], axis=1)
    return np.linalg.norm(np.cross(edges[0], edges[1]), axis=1) / math.factorial(2)


def _thresholds(intervals: np.ndarray, is_cell: bool) -> tuple[np.ndarray, ...]:
    """Ascending (enter, regular, interior) of one dimension (one shared array for cells)."""
    iv = np.asarray(intervals, dtype=np.float64)
    enter = ascending(iv[:, 0])
    if is_cell:
        return enter, enter, enter
    return enter, ascending(iv[:, 1]), ascending(iv[:, 2])


def _ro(array: np.ndarray) -> np.ndarray:
    """The array marked read-only."""
    array.flags.writeable = False
    return array

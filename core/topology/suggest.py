"""Which alpha to look at: CGAL's optimal alpha, and the ranges where the topology holds longest."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.arrays import ascends, first_cofaces
from core.errors import InputError
from core.topology.signatures import Signatures


@dataclass(frozen=True)
class AlphaRange:
    """A range [low, high) of alpha over which the Betti numbers stay `betti`.

    `alpha` is its middle on a log scale; `log_span` = ln(high / low) ranks the ranges.
    """

    alpha: float
    low: float
    high: float
    betti: tuple[int, ...]
    log_span: float

    @property
    def alpha2(self) -> float:
        """`alpha` squared (the squared-radius unit of weighted complexes and gudhi)."""
        return self.alpha * self.alpha

    @property
    def low2(self) -> float:
        """`low` squared."""
        return self.low * self.low

    @property
    def high2(self) -> float:
        """`high` squared."""
        return self.high * self.high


def cover_alpha(cells: np.ndarray, cell_enter: np.ndarray, n_points: int) -> float:
    """Smallest alpha at which every point that belongs to some cell is in a cell of the complex.

    cells: (c, dim + 1) int simplices; cell_enter: (c,) float64. Points in no cell at all (Qhull
    may leave some out of degenerate input) cannot satisfy the rule and are ignored.
    """
    cell_enter = np.asarray(cell_enter, dtype=np.float64)
    if ascends(cell_enter):  # the first cell of a point is its lowest row: no float scatter
        first_row = first_cofaces(np.asarray(cells), n_points)
        held = first_row[first_row < len(cells)]
        return float(cell_enter[held.max()]) if len(held) else 0.0
    first = np.full(n_points, np.inf)
    np.minimum.at(first, np.asarray(cells, dtype=np.int64).ravel(),
                  np.repeat(cell_enter, cells.shape[1]))
    finite = first[np.isfinite(first)]
    return float(finite.max()) if len(finite) else 0.0


def optimal_alpha(signatures: Signatures, cover: float, n_components: int = 1) -> float:
    """Smallest spectrum alpha >= cover with at most n_components solid components (CGAL)."""
    n_components = whole_number(n_components, "n_components", 1)
    alphas = signatures.alphas
    ok = (alphas >= cover) & (signatures.solid_components <= n_components)
    hits = np.flatnonzero(ok)
    return float(alphas[hits[0]]) if len(hits) else float(alphas[-1])


def stable_ranges(signatures: Signatures, k: int | None = None,
                  distinct: bool = True) -> list[AlphaRange]:
    """The k (default all) longest maximal ranges of constant Betti numbers on a log scale.

    Left out, as no shape worth suggesting: the range starting at alpha 0 (bare points), the
    unbounded last one (the hull), and dust (more components than half the points). With
    `distinct`, only the longest range of each Betti tuple is kept: noise that briefly opens
    and closes a small void would otherwise split one shape into several suggestions.
    """
    alphas, betti = signatures.alphas, signatures.betti
    if len(alphas) < 2:
        return []
    n_points = int(betti[0, 0])
    starts = np.concatenate([[0], np.flatnonzero((betti[1:] != betti[:-1]).any(axis=1)) + 1])
    ends = np.concatenate([starts[1:], [len(alphas)]])
    bounded = (ends < len(alphas)) & (alphas[starts] > 0) & (2 * betti[starts, 0] <= n_points)
    starts, ends = starts[bounded], ends[bounded]
    low, high = alphas[starts], alphas[ends]
    span = np.log(high / low)
    chosen = longest_per_tuple(betti[starts], span) if distinct else np.arange(len(span))
    order = chosen[np.lexsort((low[chosen], -span[chosen]))][:k]
    return [
        AlphaRange(
            alpha=float(np.sqrt(low[i] * high[i])),
            low=float(low[i]),
            high=float(high[i]),
            betti=tuple(int(b) for b in betti[starts[i]]),
            log_span=float(span[i]),
        )
        for i in order
    ]


def longest_per_tuple(betti: np.ndarray, span: np.ndarray) -> np.ndarray:
    """(g,) int64 row of the longest span among the rows of each distinct (m, d) Betti tuple."""
    if len(span) == 0:
        return np.zeros(0, dtype=np.int64)
    order = np.lexsort((-span, *betti.T[::-1]))
    grouped = betti[order]
    first = np.concatenate([[True], (grouped[1:] != grouped[:-1]).any(axis=1)])
    return order[first]


def suggest_alphas(signatures: Signatures, k: int = 5) -> tuple[AlphaRange, ...]:
    """The k longest ranges of distinct Betti numbers (log scale), best first."""
    return tuple(stable_ranges(signatures, whole_number(k, "k", 0)))


def whole_number(value: object, name: str, minimum: int) -> int:
    """`value` as an int >= minimum, or InputError naming the parameter."""
    try:
        number = int(value)  # type: ignore[call-overload]
        exact = number == value
    except (TypeError, ValueError):
        exact = False
    if not exact or isinstance(value, bool) or number < minimum:
        raise InputError(f"{name} must be a whole number >= {minimum}, got {value!r}")
    return number

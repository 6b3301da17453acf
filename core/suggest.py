"""Which alpha to look at: CGAL's optimal alpha, and the ranges where the topology holds longest."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .errors import InputError
from .signatures import Signatures


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


def cover_alpha(cells: np.ndarray, cell_enter: np.ndarray, n_points: int) -> float:
    """Smallest alpha at which every point that belongs to some cell is in a cell of the complex.

    cells: (c, dim + 1) int simplices; cell_enter: (c,) float64. Points in no cell at all (Qhull
    may leave some out of degenerate input) cannot satisfy the rule and are ignored.
    """
    first = np.full(n_points, np.inf)
    np.minimum.at(first, np.asarray(cells, dtype=np.int64).ravel(),
                  np.repeat(np.asarray(cell_enter, dtype=np.float64), cells.shape[1]))
    finite = first[np.isfinite(first)]
    return float(finite.max()) if len(finite) else 0.0


def optimal_alpha(signatures: Signatures, cover: float, n_components: int = 1) -> float:
    """Smallest spectrum alpha >= cover with at most n_components solid components (CGAL)."""
    n_components = whole_number(n_components, "n_components", 1)
    alphas = signatures.alphas
    ok = (alphas >= cover) & (signatures.solid_components <= n_components)
    hits = np.flatnonzero(ok)
    return float(alphas[hits[0]]) if len(hits) else float(alphas[-1])


def stable_ranges(signatures: Signatures, k: int | None = None) -> list[AlphaRange]:
    """The k (default all) longest maximal ranges of constant Betti numbers on a log scale.

    Left out, as no shape worth suggesting: the range starting at alpha 0 (bare points), the
    unbounded last one (the hull), and dust (more components than half the points).
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
    order = np.lexsort((low, -span))[:k]
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


def suggest_alphas(signatures: Signatures, k: int = 5) -> tuple[AlphaRange, ...]:
    """The k longest ranges of constant Betti numbers (log scale), best first."""
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

"""The pieces a shape's triangles make at one alpha, described for people (no Qt).

A scene opens as several pieces (core.topology.opening): the window and `alphascoop info` say
how many there are, what share of the points they hold and how large the largest ones are.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.query.index import TableIndex
from core.topology.opening import component_sizes, opening_forest, piece_size, point_spacing

SHOWN = 3  # the largest pieces named by their share


@dataclass(frozen=True)
class Pieces:
    """The pieces joined by triangles at `alpha`: (k,) int64 `sizes` (points, largest first)
    of those of at least `min_size` points; `n_points` in all; `spacing` the median
    nearest-neighbour distance (the alpha in spacings is alpha / spacing; 0: unknown)."""

    alpha: float
    sizes: np.ndarray
    min_size: int
    n_points: int
    spacing: float

    @property
    def held(self) -> float:
        """Share of the points in the pieces (0..1)."""
        return float(self.sizes.sum()) / self.n_points if self.n_points else 0.0

    @property
    def spacings(self) -> float | None:
        """The alpha in median nearest-neighbour spacings, None when it means nothing."""
        if self.spacing <= 0 or not np.isfinite(self.alpha):
            return None
        return float(self.alpha / self.spacing)

    def largest(self) -> list[float]:
        """Shares (0..1) of the points in the SHOWN largest pieces."""
        return [float(s) / self.n_points for s in self.sizes[:SHOWN]]

    def line(self) -> str:
        """'1 piece holds 99.8 % of the points' or '5 pieces hold 99.3 % of the points; the
        largest 88 %, 7.9 %, 2.2 %' (pieces of at least min_size points)."""
        count = len(self.sizes)
        if count == 0:
            return "no piece: the triangles join no points yet"
        held = f"{percent(self.held)} of the points"
        if count == 1:
            return f"1 piece holds {held}"
        shares = ", ".join(percent(s) for s in self.largest())
        return (f"{count:,} pieces of {self.min_size:,}+ points hold {held}; "
                f"the largest {shares}")

    def to_dict(self) -> dict:
        """JSON-ready: count, min_points, held and the largest shares (0..1)."""
        return {"count": len(self.sizes), "min_points": self.min_size,
                "held": round(self.held, 6), "largest": [round(s, 6) for s in self.largest()]}


def percent(share: float) -> str:
    """A share 0..1 as '88 %', '7.9 %', '0.31 %' (two significant digits below 10 %)."""
    value = 100.0 * share
    return f"{value:.0f} %" if value >= 10 else f"{value:.2g} %"


def pieces_at(index: TableIndex, points: np.ndarray, alpha: float) -> Pieces:
    """The Pieces of the complex with table `index` and (m, d) `points` at `alpha`."""
    n = len(points)
    size = piece_size(n)
    if len(index.level(2).enter) == 0:
        return Pieces(alpha, np.zeros(0, np.int64), size, n, point_spacing(index, points))
    a, b, weights = opening_forest(index, n)
    joined = int(np.searchsorted(weights, alpha, side="right"))
    sizes = component_sizes(n, a[:joined], b[:joined]).astype(np.int64)
    sizes = np.sort(sizes[sizes >= size])[::-1]
    return Pieces(float(alpha), sizes, size, n, point_spacing(index, points))

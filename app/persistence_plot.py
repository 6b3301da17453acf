"""The persistence diagram (birth against death alpha) drawn into one matplotlib axes.

Components are born at alpha 0, so the birth axis is symmetric-log (linear below the smallest
positive critical alpha, 0 included); classes that never die sit on a line above the top.
Features alive at the current alpha are those left of the vertical and above the horizontal
current-alpha line (birth <= alpha < death).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from app.signature_figure import TITLE_STYLE, plain_log_ticks

MAX_PAIRS = 4000  # longest-lived pairs drawn per diagram (rows come longest first)
PAIR_COLOURS = ("#4c9be8", "#59b86a")
PICK_RADIUS_PX = 6.0


@dataclass(frozen=True)
class DrawnPairs:
    """The pairs of one diagram as drawn: (n, 2) float64 (birth, death; inf kept), name."""

    name: str
    pairs: np.ndarray


def cavity_name(dim: int) -> str:
    """What the top homology of a dim-dimensional complex's complement is called."""
    return "holes" if dim == 2 else "voids"


def infinity_level(persistence, alphas: np.ndarray) -> float:
    """Where pairs that never die are drawn: twice the largest finite birth or death."""
    values = np.concatenate([persistence.diagram(0).ravel(),
                             persistence.diagram(persistence.dim - 1).ravel(), alphas[1:2]])
    finite = values[np.isfinite(values)]
    return 2.0 * float(finite.max()) if len(finite) and finite.max() > 0 else 1.0


class PersistenceArtists:
    """The diagram's artists on one axes, made once: a scatter per series (components, then
    holes or voids), the never-dies line and label, the diagonal and a legend. `update`
    changes their data only (no artist is added, no layout recomputed)."""

    def __init__(self, ax) -> None:
        """Create empty artists on ax (labels and title set once)."""
        self.ax = ax
        self.series = [ax.scatter([], [], s=9, color=colour, linewidths=0)
                       for colour in PAIR_COLOURS]
        self.top_line = ax.axhline(1.0, color="#888888", linewidth=0.8, linestyle=":")
        self.top_text = ax.text(0.01, 1.0, " never dies (∞)", transform=ax.get_yaxis_transform(),
                                fontsize="x-small", va="bottom", color="#555555")
        (self.diagonal,) = ax.plot([0, 1], [0, 1], color="#aaaaaa", linewidth=0.8)
        ax.set_xlabel("birth alpha (data units)", fontsize="x-small")
        ax.set_ylabel("death alpha", fontsize="x-small")
        ax.set_title("persistence", **TITLE_STYLE)

    def update(self, persistence, alphas: np.ndarray) -> list[DrawnPairs]:
        """Show persistence's component and hole/void pairs; returns what is drawn, by series."""
        ax = self.ax
        positive = alphas[alphas > 0]
        low = float(positive[0]) if len(positive) else 1.0
        top = infinity_level(persistence, alphas)
        drawn = []
        for scatter, (name, pairs) in zip(self.series, (
                ("components", persistence.diagram(0)),
                (cavity_name(persistence.dim), persistence.diagram(persistence.dim - 1))),
                strict=True):
            shown = np.asarray(pairs[:MAX_PAIRS], dtype=np.float64).reshape(-1, 2)
            scatter.set_offsets(np.column_stack([shown[:, 0], np.minimum(shown[:, 1], top)]))
            scatter.set_label(f"{name} ({len(pairs):,})" if len(shown) == len(pairs) else
                              f"{name} (longest {len(shown):,} of {len(pairs):,})")
            drawn.append(DrawnPairs(name, shown))
        self.top_line.set_ydata([top, top])
        self.top_text.set_y(top)
        self.diagonal.set_data([0, top], [0, top])
        ax.set_xscale("symlog", linthresh=low)
        plain_log_ticks(ax.xaxis, low)
        deaths = np.concatenate([d.pairs[:, 1] for d in drawn])
        if np.any(deaths[np.isfinite(deaths)] <= 0):  # weighted points: negative signed radii
            ax.set_yscale("symlog", linthresh=low)
            plain_log_ticks(ax.yaxis, low)
        else:
            ax.set_yscale("log")
            plain_log_ticks(ax.yaxis)
        ax.set_xlim(-0.5 * low, top * 1.5)
        ax.set_ylim(low * 0.8, top * 1.8)
        ax.legend(handles=self.series, fontsize="x-small", loc="lower right")
        return drawn


def nearest_pair(ax, drawn: list[DrawnPairs], x_px: float, y_px: float,
                 top: float) -> tuple[str, float, float] | None:
    """(series name, birth, death) of the drawn pair nearest display point (x_px, y_px), or None
    when none lies within PICK_RADIUS_PX."""
    best = None
    for series in drawn:
        if len(series.pairs) == 0:
            continue
        shown = np.column_stack([series.pairs[:, 0], np.minimum(series.pairs[:, 1], top)])
        screen = ax.transData.transform(shown)
        dist = np.hypot(screen[:, 0] - x_px, screen[:, 1] - y_px)
        row = int(np.argmin(dist))
        if dist[row] <= PICK_RADIUS_PX and (best is None or dist[row] < best[0]):
            best = (float(dist[row]), series.name, *map(float, series.pairs[row]))
    return None if best is None else best[1:]

"""The persistence diagram (birth against death alpha) drawn into one matplotlib axes.

Components are born at alpha 0, so the birth axis is symmetric-log (linear below the smallest
positive critical alpha, 0 included); classes that never die sit on a line above the top.
Features alive at the current alpha are those left of the vertical and above the horizontal
current-alpha line (birth <= alpha < death).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

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


def draw_persistence(ax, persistence, alphas: np.ndarray) -> list[DrawnPairs]:
    """Scatter the component and hole/void pairs on ax; returns what was drawn, by series."""
    positive = alphas[alphas > 0]
    low = float(positive[0]) if len(positive) else 1.0
    top = infinity_level(persistence, alphas)
    drawn = []
    for colour, (name, pairs) in zip(PAIR_COLOURS, (
            ("components", persistence.diagram(0)),
            (cavity_name(persistence.dim), persistence.diagram(persistence.dim - 1))), strict=True):
        shown = np.asarray(pairs[:MAX_PAIRS], dtype=np.float64)
        label = f"{name} ({len(pairs):,})" if len(shown) == len(pairs) else \
            f"{name} (longest {len(shown):,} of {len(pairs):,})"
        ax.scatter(shown[:, 0], np.minimum(shown[:, 1], top), s=9, color=colour,
                   label=label, linewidths=0)
        drawn.append(DrawnPairs(name, shown))
    ax.axhline(top, color="#888888", linewidth=0.8, linestyle=":")
    ax.text(0.01, top, " never dies (∞)", transform=ax.get_yaxis_transform(),
            fontsize="x-small", va="bottom", color="#555555")
    ax.plot([0, top], [0, top], color="#aaaaaa", linewidth=0.8)
    ax.set_xscale("symlog", linthresh=low)
    deaths = np.concatenate([d.pairs[:, 1] for d in drawn])
    if np.any(deaths[np.isfinite(deaths)] <= 0):  # weighted points: negative signed radii
        ax.set_yscale("symlog", linthresh=low)
    else:
        ax.set_yscale("log")
    ax.set_xlim(-0.5 * low, top * 1.5)
    ax.set_ylim(low * 0.8, top * 1.8)
    ax.set_xlabel("birth alpha (data units)", fontsize="x-small")
    ax.set_ylabel("death alpha", fontsize="x-small")
    ax.set_title("persistence", fontsize="small", pad=10)
    ax.legend(fontsize="x-small", loc="lower right")
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

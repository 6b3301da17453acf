"""The signatures dock's figure: four axes and their artists made once, in a fixed layout.

A dataset's topology arrives on the GUI thread; re-plotting with matplotlib's constrained
layout and mathtext tick labels froze the window for 0.6-3.9 s at 100k-200k points. Here the
axes keep their artists (the dataset only changes their data), the margins are fixed in
points (recomputed on resize with no text measured) and tick labels are plain text.
"""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import (
    FuncFormatter,
    LogLocator,
    MaxNLocator,
    NullFormatter,
    NullLocator,
)
from matplotlib.transforms import ScaledTranslation

# Margins in points (1/72 inch): room for tick labels, axis labels and the titles above the
# marker row. Fixed, so a redraw never measures text to lay the figure out.
LEFT_PT, RIGHT_PT, BOTTOM_PT, TOP_PT, GAP_PT = 50.0, 8.0, 30.0, 24.0, 52.0
XLABEL_PT, YLABEL_PT = 16.0, 32.0  # axis labels' distance from the axes (below, left)
WIDTH_RATIOS = (1.0, 1.0, 1.0, 1.1)
MAX_SAMPLES = 2000  # spectrum entries drawn per curve
MINOR_SUBS = (2.0, 5.0)  # minor ticks of a log axis, per decade
#: At most about this many decades labelled on a log axis (every decade of 1e-05 ... 100 ran
#: into each other at the window's width).
LOG_TICKS = 5
#: At most about this many decades labelled on a symmetric-log axis (more overlap in a
#: signature plot of the window's width).
SYMLOG_TICKS = 4
CURSOR_COLOUR = "#444444"
# Titles at a fixed height (y given): else every draw measures the axis under each title.
TITLE_STYLE = {"fontsize": "small", "pad": 10, "y": 1.0}


def log_samples(alphas: np.ndarray, count: int = MAX_SAMPLES) -> np.ndarray:
    """Indexes of at most ~count spectrum entries, log-spaced over the positive alphas."""
    positive = np.flatnonzero(alphas > 0)
    if len(positive) <= count:
        return positive
    lo, hi = np.log(alphas[positive[0]]), np.log(alphas[-1])
    picks = np.searchsorted(alphas, np.exp(np.linspace(lo, hi, count)), side="right") - 1
    return np.unique(np.clip(picks, positive[0], len(alphas) - 1))


def rank_samples(count_all: int, count: int = MAX_SAMPLES) -> np.ndarray:
    """Indexes of at most ~count entries evenly spread over all count_all spectrum entries."""
    if count_all <= count:
        return np.arange(count_all)
    return np.unique(np.linspace(0, count_all - 1, count).round().astype(np.int64))


def symlog_threshold(values: np.ndarray) -> float:
    """Width of the linear part of a symmetric-log axis: a low quantile of the non-zero |x|."""
    size = np.abs(values[values != 0])
    return float(np.quantile(size, 0.05)) if len(size) else 1.0


def decade_label(value: float, linthresh: float = 0.0) -> str:
    """A log axis's tick label: signed powers of ten in plain text ("0.01", "-1e+05"), other
    ticks unlabelled (matplotlib's default parses mathtext for every label). On a
    symmetric-log axis the decades inside its linear part (|value| < linthresh) are left
    unlabelled too: they crowd the 0."""
    if value == 0:
        return "0"
    exponent = np.log10(abs(value))
    if abs(exponent - round(exponent)) > 1e-6 or abs(value) < linthresh:
        return ""
    return f"{value:.0e}" if abs(round(exponent)) >= 4 else f"{value:g}"


def short_number(value: float, _position: object = None) -> str:
    """A linear axis's tick label: three significant digits, no offset text."""
    return f"{value:.3g}"


def margins(width_px: float, height_px: float, dpi: float) -> dict[str, float]:
    """subplots_adjust's arguments (figure fractions) for the fixed point margins on a
    canvas of width_px x height_px at dpi; clamped so a tiny canvas still gets axes."""
    px = dpi / 72.0
    width, height = max(width_px, 1.0), max(height_px, 1.0)
    left, right = min(LEFT_PT * px / width, 0.3), max(1 - RIGHT_PT * px / width, 0.7)
    bottom, top = min(BOTTOM_PT * px / height, 0.4), max(1 - TOP_PT * px / height, 0.6)
    n = len(WIDTH_RATIOS)
    axis_width = max((right - left) * width - (n - 1) * GAP_PT * px, n) / n
    return {"left": left, "right": right, "bottom": bottom, "top": top,
            "wspace": min(GAP_PT * px / axis_width, 1.0)}


def plain_log_ticks(axis, linthresh: float = 0.0) -> None:
    """Decade labels as plain text ("0.01", "1e+05"): no mathtext to parse on a redraw
    (linthresh: the linear part of a symmetric-log axis, left unlabelled but for 0)."""
    axis.set_major_formatter(FuncFormatter(lambda value, _pos: decade_label(value, linthresh)))
    axis.set_minor_formatter(NullFormatter())
    # Minor ticks at 2 and 5 per decade (log) or none (symmetric log): each tick is an
    # object made on the first draw, and eight a decade over many decades cost a second.
    if axis.get_scale() == "log":
        axis.set_major_locator(LogLocator(numticks=LOG_TICKS))
        axis.set_minor_locator(LogLocator(subs=MINOR_SUBS))
    else:  # symmetric log: every decade on both sides of 0 would crowd the labels
        axis.set_minor_locator(NullLocator())
        axis.get_major_locator().set_params(numticks=SYMLOG_TICKS)


def plain_linear_ticks(axis) -> None:
    """At most five short labels on a linear axis."""
    axis.set_major_locator(MaxNLocator(4))
    axis.set_major_formatter(FuncFormatter(short_number))


def new_figure() -> tuple[Figure, list]:
    """A figure with no layout engine and its four axes (three signature plots, the
    persistence diagram), hidden until a dataset's signatures arrive."""
    figure = Figure(figsize=(10, 2.4), layout="none")
    axes = list(figure.subplots(1, 4, width_ratios=WIDTH_RATIOS))
    for ax in axes:
        ax.tick_params(labelsize="x-small")
        ax.set_visible(False)
        # axis labels a fixed distance from the axes: else every draw (a slider step
        # moves the cursors) measures the tick labels of every axes to place them
        ax.xaxis.set_label_coords(0.5, 0.0, transform=ax.transAxes + ScaledTranslation(
            0.0, -XLABEL_PT / 72.0, figure.dpi_scale_trans))
        ax.yaxis.set_label_coords(0.0, 0.5, transform=ax.transAxes + ScaledTranslation(
            -YLABEL_PT / 72.0, 0.0, figure.dpi_scale_trans))
    return figure, axes


def fit(ax, x: np.ndarray, y: np.ndarray) -> None:
    """Scale ax to the data (x, y) alone: cursors and markers never stretch the view."""
    ax.ignore_existing_data_limits = True
    if len(x):
        finite = np.isfinite(x) & np.isfinite(y)
        ax.update_datalim(np.column_stack([x[finite], y[finite]]))
    ax.autoscale_view()


def set_alpha_scale(ax, weighted: bool, threshold: float) -> None:
    """Log alpha (radii), or symmetric-log alpha² for weighted points, with plain labels."""
    if weighted:
        ax.set_xscale("symlog", linthresh=threshold)
        ax.set_xlabel("alpha² (symmetric log, data units²)", fontsize="x-small")
        plain_log_ticks(ax.xaxis, threshold)
    else:
        ax.set_xscale("log")
        ax.set_xlabel("alpha (radius, data units)", fontsize="x-small")
        plain_log_ticks(ax.xaxis)

"""Signature plots (Edelsbrunner's viewer): Betti numbers and measures against log alpha, and
the persistence diagram.

A vertical cursor marks the current alpha; clicking a plot moves the alpha there. Markers at
the top of each plot show CGAL's optimal alpha (★) and the suggested alphas (▼); clicking one
goes to it. A readout under the plots gives the values under the mouse. Weighted points have
negative squared alphas: their plots use alpha² on a symmetric-log axis (linear around zero).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.backends.backend_qtagg import FigureCanvasQTAgg
from matplotlib.figure import Figure
from PySide6.QtWidgets import QLabel, QVBoxLayout, QWidget

from app.dataset import Dataset
from app.model import ExplorerModel
from app.palette import CLASS_COLOURS
from app.persistence_plot import DrawnPairs, draw_persistence, infinity_level, nearest_pair
from core.complex import AlphaComplex
from core.persistence import Persistence

MAX_SAMPLES = 2000
MIN_PLOT_HEIGHT = 160  # pixels: tick labels, titles and a readable plot area
N_SUGGESTIONS = 5
BETTI_COLOURS = ("#4c9be8", "#e4572e", "#59b86a")
OPTIMAL_COLOUR, SUGGESTED_COLOUR = "#e0a800", "#6f42c1"
COMPUTING = "Signatures: computing the topology… (the slider already works)"
HINT = ("Hover a plot to read its values; click to go to that alpha. "
        "★ optimal alpha (CGAL), ▼ suggested alphas: click to go there.")


@dataclass(frozen=True)
class Marker:
    """An alpha worth a click: where it is, and what it is (shown in the readout)."""

    alpha: float
    text: str


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


def markers_of(ac: AlphaComplex, optimal: float | None = None) -> tuple[Marker, list[Marker]]:
    """The optimal alpha (ac's own unless given: the dataset knows it) and the suggested
    alphas of a complex, as markers."""
    optimal = float(ac.optimal_alpha() if optimal is None else optimal)
    suggested = [
        Marker(r.alpha, f"suggestion {i}: Betti numbers {r.betti} for alpha in "
                        f"[{r.low:.4g}, {r.high:.4g})")
        for i, r in enumerate(ac.suggest_alphas(N_SUGGESTIONS), start=1)
    ]
    return Marker(optimal, "optimal alpha (CGAL): every point in one solid"), suggested


def persistence_of(dataset: Dataset) -> Persistence:
    """The dataset's persistence pairs: found with its topology (in a topology process, so
    the GUI thread does not compute them), else computed by its complex."""
    return dataset.ac.persistence() if dataset.persistence is None else dataset.persistence


def measure_names(dim: int) -> tuple[str, str]:
    """Titles of the measure and boundary-measure plots, with units."""
    if dim == 2:
        return "area (units²)", "perimeter (units)"
    return "volume (units³)", "boundary area (units²)"


def value_line(sig, alpha: float) -> str:
    """The readout for the signature entry in force at alpha: r, r², Betti numbers, measures."""
    row = max(sig.index(alpha), 0)
    names = ("b0", "b1", "b2")[: sig.betti.shape[1]]
    betti = "  ".join(f"{n} {int(b):,}" for n, b in zip(names, sig.betti[row], strict=True))
    measure, boundary = (name.split(" (")[0] for name in measure_names(sig.dim))
    return (f"r {alpha:.4g}  r² {alpha * abs(alpha):.4g}  ·  {betti}  ·  {measure} "
            f"{sig.measure[row]:.4g}  ·  {boundary} {sig.boundary_measure[row]:.4g}")


class SignaturesPanel(QWidget):
    """Three signature plots sharing a log-alpha axis and a persistence diagram, with a cursor
    at the model's alpha, clickable markers and a readout."""

    def __init__(self, model: ExplorerModel, parent: QWidget | None = None) -> None:
        """Create an empty figure; it fills when a dataset with signatures arrives."""
        super().__init__(parent)
        self.model = model
        self.figure = Figure(figsize=(10, 2.4), layout="constrained")
        self.canvas = FigureCanvasQTAgg(self.figure)
        self.canvas.setMinimumHeight(MIN_PLOT_HEIGHT)  # lower, the layout has no room for axes
        self.readout = QLabel(HINT)
        self.readout.setWordWrap(True)
        column = QVBoxLayout(self)
        column.addWidget(self.canvas, 1)
        column.addWidget(self.readout)
        self.cursors: list = []  # vertical current-alpha lines, one per plot
        self.death_cursor = None  # the horizontal current-alpha line of the persistence plot
        self.marker_lines: list = []  # (line artist, markers) per signature plot
        self.persistence_ax = None
        self.drawn_pairs: list[DrawnPairs] = []
        model.datasetChanged.connect(self.plot)
        model.topologyChanged.connect(self.plot)
        model.datasetReleased.connect(self.plot)
        model.alphaChanged.connect(self.move_cursor)
        self.canvas.mpl_connect("button_press_event", self._clicked)
        self.canvas.mpl_connect("motion_notify_event", self._hovered)

    def plot(self) -> None:
        """Draw the current dataset's signatures (clears the figure when there are none, and
        says so while its topology is being computed)."""
        self.figure.clear()
        self.cursors, self.marker_lines, self.drawn_pairs = [], [], []
        self.persistence_ax = self.death_cursor = None
        sig = self.model.dataset.signatures if self.model.dataset else None
        if sig is None:
            if self.model.dataset is not None:
                self.figure.text(0.5, 0.5, COMPUTING, ha="center", va="center", color="#666666")
            self.canvas.draw_idle()
            return
        axes = self.figure.subplots(1, 4, width_ratios=(1, 1, 1, 1.1))
        self._plot_signatures(sig, axes[:3])
        for ax in axes[:3]:
            self._add_markers(ax)
        self.persistence_ax = axes[3]
        self.drawn_pairs = draw_persistence(axes[3], persistence_of(self.model.dataset),
                                            np.asarray(sig.alphas))
        self.cursors.append(axes[3].axvline(sig.alphas[-1], color="#444444", linewidth=1))
        self.death_cursor = axes[3].axhline(sig.alphas[-1], color="#444444", linewidth=1)
        for ax in axes:
            ax.tick_params(labelsize="x-small")
        self.move_cursor()

    def _plot_signatures(self, sig, axes) -> None:
        """Betti numbers, measure and boundary measure against log alpha, with cursors."""
        weighted = self.model.weighted
        alphas = np.asarray(sig.alphas)
        rows = rank_samples(len(alphas)) if weighted else log_samples(alphas)
        x = self.plot_x(alphas[rows])
        names = ("b0 components", "b1 tunnels" if sig.dim == 3 else "b1 holes", "b2 voids")
        for k in range(sig.betti.shape[1]):
            axes[0].step(x, sig.betti[rows, k], where="post", color=BETTI_COLOURS[k],
                         label=names[k])
        axes[0].set_yscale("symlog", linthresh=10)
        axes[0].legend(fontsize="x-small")
        axes[1].step(x, sig.measure[rows], where="post", color=CLASS_COLOURS["interior"])
        axes[2].step(x, sig.boundary_measure[rows], where="post", color=CLASS_COLOURS["regular"])
        titles = ("Betti numbers", *measure_names(sig.dim))
        ylabels = ("count", *(name.split(" (")[1].rstrip(")") for name in titles[1:]))
        for ax, title, ylabel in zip(axes, titles, ylabels, strict=True):
            if weighted:
                ax.set_xscale("symlog", linthresh=symlog_threshold(x))
                ax.set_xlabel("alpha² (symmetric log, data units²)", fontsize="x-small")
            else:
                ax.set_xscale("log")
                ax.set_xlabel("alpha (radius, data units)", fontsize="x-small")
            ax.set_title(title, fontsize="small", pad=10)
            ax.set_ylabel(ylabel, fontsize="x-small")
            self.cursors.append(ax.axvline(x[0], color="#444444", linewidth=1))

    def _add_markers(self, ax) -> None:
        """The optimal (★) and suggested (▼) alphas at the top edge of ax (clickable)."""
        optimal, suggested = markers_of(self.model.dataset.ac, self.model.dataset.optimal_alpha)
        for markers, symbol, colour, size in ((suggested, "v", SUGGESTED_COLOUR, 7),
                                              ([optimal], "*", OPTIMAL_COLOUR, 13)):
            if not markers:
                continue
            (line,) = ax.plot(self.plot_x(np.array([m.alpha for m in markers])),
                              [1.0] * len(markers), symbol,
                              color=colour, markersize=size, clip_on=False,
                              transform=ax.get_xaxis_transform(), pickradius=6, zorder=5,
                              markeredgecolor="white", markeredgewidth=0.6)
            self.marker_lines.append((line, markers))

    def marker_at(self, event) -> Marker | None:
        """The marker under a mouse event (the nearest one where several overlap), if any."""
        best, best_distance = None, np.inf
        for line, markers in self.marker_lines:
            hit, info = line.contains(event)
            for i in info.get("ind", ()) if hit else ():
                x = line.get_transform().transform((line.get_xdata()[int(i)], 1.0))[0]
                if abs(x - event.x) < best_distance:
                    best, best_distance = markers[int(i)], abs(x - event.x)
        return best

    def move_cursor(self) -> None:
        """Put the cursors at the current alpha (redraw is coalesced by matplotlib)."""
        alpha = self.model.alpha
        if not self.cursors or not (alpha > 0 or self.model.weighted):
            return
        x = float(self.plot_x(np.array([alpha]))[0])
        for cursor in self.cursors[:-1]:
            cursor.set_xdata([x, x])
        self.cursors[-1].set_xdata([alpha, alpha])  # the persistence plot is in radii
        if self.death_cursor is not None:
            self.death_cursor.set_ydata([alpha, alpha])
        self.canvas.draw_idle()

    def _clicked(self, event) -> None:
        """A click on a marker goes to its alpha; elsewhere in a signature plot to the value
        under the mouse (or the birth of the pair clicked in the persistence diagram)."""
        if event.button != 1 or self.model.dataset is None:
            return
        marker = self.marker_at(event)
        if marker is not None:
            self.model.set_alpha(marker.alpha)  # radii (signed for weighted points)
        elif event.inaxes is self.persistence_ax and event.inaxes is not None:
            pair = self._pair_at(event)
            if pair is not None:
                self.model.set_alpha(pair[1])
        elif event.inaxes is not None and event.xdata is not None:
            if self.model.weighted:
                self.model.set_alpha2(float(event.xdata))
            else:
                self.model.set_alpha(float(event.xdata))

    def plot_x(self, alphas: np.ndarray) -> np.ndarray:
        """Where alphas (radii, signed for weighted points) sit on the signature plots' x axis:
        the radius itself, or for weighted points the signed square."""
        alphas = np.asarray(alphas, dtype=np.float64)
        return alphas * np.abs(alphas) if self.model.weighted else alphas

    def _pair_at(self, event) -> tuple[str, float, float] | None:
        """The persistence pair under the mouse (series name, birth, death), or None."""
        top = infinity_level(persistence_of(self.model.dataset), self.model.spectrum)
        return nearest_pair(self.persistence_ax, self.drawn_pairs, event.x, event.y, top)

    def _hovered(self, event) -> None:
        """Show the values under the mouse in the readout."""
        self.readout.setText(self.readout_text(event))

    def readout_text(self, event) -> str:
        """What the readout says for a mouse position (the hint outside the plots)."""
        sig = self.model.dataset.signatures if self.model.dataset else None
        if sig is None or event.inaxes is None or event.xdata is None:
            return HINT
        marker = self.marker_at(event)
        if marker is not None:
            return f"{marker.text}: r {marker.alpha:.4g} (click to go there)"
        if event.inaxes is self.persistence_ax:
            pair = self._pair_at(event)
            if pair is None:
                return (f"birth {max(event.xdata, 0.0):.4g}, death {event.ydata:.4g}: features "
                        "left of and above the current-alpha lines exist at that alpha")
            name, birth, death = pair
            return (f"{name[:-1]} born at r {birth:.4g}, dies at r {death:.4g} "
                    f"(click: go to its birth)")
        x = float(event.xdata)
        alpha = float(np.copysign(np.sqrt(abs(x)), x)) if self.model.weighted else x
        return value_line(sig, alpha)

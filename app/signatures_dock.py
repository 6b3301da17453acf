"""Signature plots (Edelsbrunner's viewer): Betti numbers and measures against log alpha.

Weighted points have negative squared alphas: their plots use alpha² on a symmetric-log axis
(linear around zero). A vertical cursor marks the current alpha; clicking a plot moves the
alpha there.
"""

from __future__ import annotations

import numpy as np
from matplotlib.backends.backend_qtagg import FigureCanvasQTAgg
from matplotlib.figure import Figure
from PySide6.QtWidgets import QVBoxLayout, QWidget

from app.model import ExplorerModel
from app.palette import CLASS_COLOURS

MAX_SAMPLES = 2000
BETTI_COLOURS = ("#4c9be8", "#e4572e", "#59b86a")


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


class SignaturesPanel(QWidget):
    """Three stacked plots sharing a log-alpha axis, with a cursor at the model's alpha."""

    def __init__(self, model: ExplorerModel, parent: QWidget | None = None) -> None:
        """Create an empty figure; it fills when a dataset with signatures arrives."""
        super().__init__(parent)
        self.model = model
        self.figure = Figure(figsize=(8, 2.2), layout="constrained")
        self.canvas = FigureCanvasQTAgg(self.figure)
        QVBoxLayout(self).addWidget(self.canvas)
        self.cursors: list = []
        model.datasetChanged.connect(self.plot)
        model.alphaChanged.connect(self.move_cursor)
        self.canvas.mpl_connect("button_press_event", self._clicked)

    def plot(self) -> None:
        """Draw the current dataset's signatures (clears the figure when there are none)."""
        self.figure.clear()
        self.cursors = []
        sig = self.model.dataset.signatures if self.model.dataset else None
        if sig is None:
            self.canvas.draw_idle()
            return
        weighted = self.model.weighted
        alphas = np.asarray(sig.alphas)
        rows = rank_samples(len(alphas)) if weighted else log_samples(alphas)
        x = alphas[rows] * np.abs(alphas[rows]) if weighted else alphas[rows]
        axes = self.figure.subplots(1, 3, sharex=True)
        names = ("b0", "b1", "b2")
        for k in range(sig.betti.shape[1]):
            axes[0].step(x, sig.betti[rows, k], where="post", color=BETTI_COLOURS[k],
                         label=names[k])
        axes[0].set_yscale("symlog", linthresh=10)
        axes[0].legend(fontsize="small")
        axes[1].step(x, sig.measure[rows], where="post", color=CLASS_COLOURS["interior"])
        axes[2].step(x, sig.boundary_measure[rows], where="post", color=CLASS_COLOURS["regular"])
        titles = ("Betti numbers", "area" if sig.dim == 2 else "volume",
                  "perimeter" if sig.dim == 2 else "boundary area")
        for ax, title in zip(axes, titles, strict=True):
            if weighted:
                ax.set_xscale("symlog", linthresh=symlog_threshold(x))
                ax.set_xlabel("alpha² (symmetric log)", fontsize="x-small")
            else:
                ax.set_xscale("log")
            ax.set_title(title, fontsize="small")
            ax.tick_params(labelsize="x-small")
            self.cursors.append(ax.axvline(x[0], color="#444444", linewidth=1))
        self.move_cursor()

    def move_cursor(self) -> None:
        """Put the cursor at the current alpha (redraw is coalesced by matplotlib)."""
        alpha = self.model.alpha2 if self.model.weighted else self.model.alpha
        if not self.cursors or not (alpha > 0 or self.model.weighted):
            return
        for cursor in self.cursors:
            cursor.set_xdata([alpha, alpha])
        self.canvas.draw_idle()

    def _clicked(self, event) -> None:
        """Clicking inside a plot moves the alpha to the clicked value."""
        if event.inaxes is not None and event.xdata is not None and event.button == 1:
            if self.model.weighted:
                self.model.set_alpha2(float(event.xdata))
            else:
                self.model.set_alpha(float(event.xdata))

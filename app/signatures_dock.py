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
from PySide6.QtWidgets import QLabel, QVBoxLayout, QWidget

from app.dataset import Dataset, suggestions_of
from app.model import ExplorerModel
from app.palette import CLASS_COLOURS
from app.persistence_plot import DrawnPairs, PersistenceArtists, infinity_level, nearest_pair
from app.plot_blit import Blitter
from app.signature_figure import (
    CURSOR_COLOUR,
    TITLE_STYLE,
    fit,
    log_samples,
    margins,
    new_figure,
    plain_linear_ticks,
    plain_log_ticks,
    rank_samples,
    set_alpha_scale,
    symlog_threshold,
)
from core.topology.persistence import Persistence

MIN_PLOT_HEIGHT = 160  # pixels: tick labels, titles and a readable plot area
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


def markers_of(dataset: Dataset) -> tuple[Marker, list[Marker]]:
    """The optimal alpha and the suggested alphas (app.dataset.suggestions_of) of a dataset
    that has its topology, as markers."""
    suggested = [
        Marker(r.alpha, f"suggestion {i}: Betti numbers {r.betti} for alpha in "
                        f"[{r.low:.4g}, {r.high:.4g})")
        for i, r in enumerate(suggestions_of(dataset), start=1)
    ]
    return (Marker(float(dataset.optimal_alpha),
                   "optimal alpha (CGAL): every point in one solid"), suggested)


def persistence_of(dataset: Dataset) -> Persistence:
    """The dataset's persistence pairs: found with its topology (in a topology process, so
    the GUI thread does not compute them), else computed by its complex."""
    return dataset.ac.persistence() if dataset.persistence is None else dataset.persistence


def measure_names(dim: int, unit: str | None = None) -> tuple[str, str]:
    """Titles of the measure and boundary-measure plots, with the data's unit ('Å', 'm';
    'units' when the file declares none)."""
    unit = unit or "units"
    if dim == 2:
        return f"area ({unit}²)", f"perimeter ({unit})"
    return f"volume ({unit}³)", f"boundary area ({unit}²)"


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
    at the model's alpha, clickable markers and a readout. The axes and their artists are
    made once; a dataset only changes their data (app.signature_figure: no layout engine)."""

    def __init__(self, model: ExplorerModel, parent: QWidget | None = None) -> None:
        """Create the figure's axes and artists, hidden until signatures arrive."""
        super().__init__(parent)
        self.model = model
        self.figure, axes = new_figure()
        self.canvas = FigureCanvasQTAgg(self.figure)
        self.canvas.setMinimumHeight(MIN_PLOT_HEIGHT)  # lower, there is no room for axes
        self.readout = QLabel(HINT)
        self.readout.setWordWrap(True)
        column = QVBoxLayout(self)
        column.addWidget(self.canvas, 1)
        column.addWidget(self.readout)
        self.computing = self.figure.text(0.5, 0.5, COMPUTING, ha="center", va="center",
                                          color="#666666", visible=False)
        self.steps = self._make_steps(axes[:3])
        self.persistence_ax = axes[3]
        self.persistence = PersistenceArtists(axes[3])
        # vertical current-alpha lines, one per plot (the persistence plot's last)
        self.cursors = [ax.axvline(1.0, color=CURSOR_COLOUR, linewidth=1) for ax in axes]
        self.death_cursor = axes[3].axhline(1.0, color=CURSOR_COLOUR, linewidth=1)
        self.marker_lines = [pair for ax in axes[:3] for pair in self._make_markers(ax)]
        # a step moves these over the figure's cached pixels: no full draw (app.plot_blit)
        self.blitter = Blitter(self.canvas, [*self.cursors, self.death_cursor])
        self.drawn_pairs: list[DrawnPairs] = []
        self._lay_out()
        model.datasetChanged.connect(self.plot)
        model.topologyChanged.connect(self.plot)
        model.datasetReleased.connect(self.plot)
        model.alphaChanged.connect(self.move_cursor)
        self.canvas.mpl_connect("button_press_event", self._clicked)
        self.canvas.mpl_connect("motion_notify_event", self._hovered)
        self.canvas.mpl_connect("resize_event", self._lay_out)

    @staticmethod
    def _make_steps(axes) -> list:
        """The step curves: per Betti number on the first plot, then measure and boundary."""
        steps = [axes[0].plot([], [], drawstyle="steps-post", color=colour)[0]
                 for colour in BETTI_COLOURS]
        axes[0].set_yscale("symlog", linthresh=10)
        plain_log_ticks(axes[0].yaxis)
        for ax, colour in zip(axes[1:], ("interior", "regular"), strict=True):
            steps.append(ax.plot([], [], drawstyle="steps-post", color=CLASS_COLOURS[colour])[0])
            plain_linear_ticks(ax.yaxis)
        for ax, title in zip(axes, ("Betti numbers", "measure", "boundary"), strict=True):
            ax.set_title(title, **TITLE_STYLE)
        axes[0].set_ylabel("count", fontsize="x-small")
        return steps

    @staticmethod
    def _make_markers(ax) -> list:
        """Empty (line, markers) pairs for the suggested (▼) and optimal (★) alphas at the top
        edge of ax (clickable; filled by plot)."""
        return [(ax.plot([], [], symbol, color=colour, markersize=size, clip_on=False,
                         transform=ax.get_xaxis_transform(), pickradius=6, zorder=5,
                         markeredgecolor="white", markeredgewidth=0.6)[0], [])
                for symbol, colour, size in (("v", SUGGESTED_COLOUR, 7),
                                             ("*", OPTIMAL_COLOUR, 13))]

    def _lay_out(self, _event=None) -> None:
        """Fixed margins for the canvas's size (no text is measured)."""
        box = self.figure.bbox
        self.figure.subplots_adjust(**margins(box.width, box.height, self.figure.dpi))

    def plot(self) -> None:
        """Show the current dataset's signatures (hides the axes when there are none, and
        says so while its topology is being computed)."""
        dataset = self.model.dataset
        sig = dataset.signatures if dataset is not None else None
        self.drawn_pairs = []
        for ax in self.figure.axes:
            ax.set_visible(sig is not None)
        self.computing.set_visible(dataset is not None and sig is None)
        if sig is not None:
            self._show_signatures(sig)
            self._show_markers(dataset)
            self.drawn_pairs = self.persistence.update(persistence_of(dataset),
                                                       np.asarray(sig.alphas))
            self._place_cursors()
        self.blitter.redraw()

    def _show_signatures(self, sig) -> None:
        """Betti numbers, measure and boundary measure against log alpha (sampled)."""
        weighted = self.model.weighted
        alphas = np.asarray(sig.alphas)
        rows = rank_samples(len(alphas)) if weighted else log_samples(alphas)
        x = self.plot_x(alphas[rows])
        names = ("b0 components", "b1 tunnels" if sig.dim == 3 else "b1 holes", "b2 voids")
        n_betti = sig.betti.shape[1]
        columns = [sig.betti[rows, k] if k < n_betti else np.zeros(0) for k in range(3)]
        columns += [sig.measure[rows], sig.boundary_measure[rows]]
        for step, y, label in zip(self.steps, columns, (*names, "", ""), strict=True):
            step.set_data(x[: len(y)], y)
            step.set_label(label)
        axes = self.figure.axes[:3]
        axes[0].legend(handles=self.steps[:n_betti], fontsize="x-small")
        titles = measure_names(sig.dim, self.model.dataset.unit)
        for ax, title in zip(axes[1:], titles, strict=True):
            ax.set_title(title, **TITLE_STYLE)
            ax.set_ylabel(title.split(" (")[1].rstrip(")"), fontsize="x-small")
        threshold = symlog_threshold(x) if weighted else 1.0
        for ax, curves in zip(axes, (self.steps[:n_betti], self.steps[3:4], self.steps[4:]),
                              strict=True):
            set_alpha_scale(ax, weighted, threshold)
            fit(ax, np.concatenate([c.get_xdata() for c in curves]),
                np.concatenate([c.get_ydata() for c in curves]))

    def _show_markers(self, dataset: Dataset) -> None:
        """Put the optimal (★) and suggested (▼) alphas of dataset on the marker lines."""
        optimal, suggested = markers_of(dataset)
        for i, (line, markers) in enumerate(self.marker_lines):
            markers[:] = suggested if i % 2 == 0 else [optimal]
            line.set_data(self.plot_x(np.array([m.alpha for m in markers])),
                          np.ones(len(markers)))

    def marker_at(self, event) -> Marker | None:
        """The marker under a mouse event (the nearest one where several overlap), if any."""
        best, best_distance = None, np.inf
        for line, markers in self.marker_lines:
            if not markers or not line.axes.get_visible():
                continue
            hit, info = line.contains(event)
            for i in info.get("ind", ()) if hit else ():
                x = line.get_transform().transform((line.get_xdata()[int(i)], 1.0))[0]
                if abs(x - event.x) < best_distance:
                    best, best_distance = markers[int(i)], abs(x - event.x)
        return best

    def move_cursor(self) -> None:
        """Put the cursors at the current alpha and blit them over the figure's cached
        pixels: a slider step redraws no axis, tick, legend or text."""
        if self._place_cursors():
            self.blitter.move()

    def _place_cursors(self) -> bool:
        """Set the cursors' data to the current alpha; False when there is nothing to show."""
        alpha = self.model.alpha
        if not self.drawn_pairs or not (alpha > 0 or self.model.weighted):
            return False
        x = float(self.plot_x(np.array([alpha]))[0])
        for cursor in self.cursors[:-1]:
            cursor.set_xdata([x, x])
        self.cursors[-1].set_xdata([alpha, alpha])  # the persistence plot is in radii
        self.death_cursor.set_ydata([alpha, alpha])
        return True

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

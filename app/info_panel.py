"""Info dock: facts about the data and about the shape at the current alpha.

Numbers are written for people (app.numbers): coordinates to a precision relative to the
data's extent, measures with the file's unit when it declares one, words in the singular for
one. The dock keeps its width whatever the text, so the 3D view beside it never moves.
"""

from __future__ import annotations

import html
from pathlib import Path

import numpy as np
from PySide6.QtCore import QSize, Qt
from PySide6.QtWidgets import QFrame, QLabel, QScrollArea, QSizePolicy, QVBoxLayout, QWidget

from app.model import ExplorerModel
from app.numbers import coordinate, plural, quantity, with_unit
from app.row_labels import RowLabels
from core.io.molecule import RADII_READERS, molecule_extension
from core.query.classes import INTERIOR, REGULAR, SINGULAR

BETTI_NAMES = {2: ("component", "hole"), 3: ("component", "tunnel", "void")}
WIDTH_CHARACTERS = 34  # the dock's width, in average character widths
#: a molecule's line while its measures are computed (app.worker.measures_job)
MEASURING = "exact area, volume, cavities and pockets: computing…"


def data_lines(model: ExplorerModel) -> list[str]:
    """Lines describing the dataset: file, point counts, extent, spacing, dimension, timings."""
    ds = model.dataset
    ac = ds.ac
    report = ds.report
    lines = [f"<b>{breakable(ds.path.name)}</b>"]
    if report is not None:  # the counts `alphascoop info` prints, in the same words
        lines.append(html.escape(report.count_line()))
        if len(ac.points) != report.n_points:
            lines.append(f"{len(ac.points):,} used as vertices")
    else:
        lines.append(f"{plural(ds.n_input, 'point')} read, {len(ac.points):,} used")
    if report is not None:
        lines.extend(box_lines(report.bbox, ds.unit))
    if report is not None and getattr(report, "spacing", 0):
        lines.append(f"spacing {with_unit(quantity(report.spacing), ds.unit)}")
    if report is not None and report.georef is not None:  # read from longitude/latitude
        lines.append(f"lengths in metres: {html.escape(report.georef.name)}")
    flat = " (planar 3D input)" if ac.dim < ac.ambient_dim else ""
    lines.append(f"{ac.dim}D complex{flat}, {plural(len(ac.simplices(ac.dim)), 'cell')}")
    lines.append(f"alpha mode: {html.escape(ac.mode.describe())}")
    lines.append(f"build: {html.escape(ac.build_info.describe())}")
    if ac.weights is not None:
        lines.append(weights_line(ds))
    if ds.opening_pieces is not None:
        lines.append(opening_line(ds))
    lines.append(f"read in {ds.load_seconds:.2f} s, {ds.build_line()}, {ds.topology_line()}")
    return lines + molecule_lines(model)


def weights_line(ds) -> str:
    """What the balls' radii are: a molecule's atoms (Bondi van der Waals radii, or a PQR or
    XYZR file's own, + the probe), else where the weights came from; and how many balls are
    hidden (none: not said)."""
    if ds.is_molecule:
        own = molecule_extension(Path(ds.path)) in RADII_READERS
        radii = "the file's radii" if own else "van der Waals radii (Bondi)"
        text = f"atoms as balls: {radii} + probe {ds.probe:g} Å"
    else:
        text = f"weighted: {getattr(ds.report, 'weights_from', None) or 'given weights'}"
    hidden = int((np.asarray(ds.ac.input_index) < 0).sum())
    if hidden:
        text += f"; {plural(hidden, 'hidden point')} (their ball adds nothing)"
    return html.escape(text)


def opening_line(ds) -> str:
    """Where the view opened and the pieces there: 'opens at 1.81 spacings: 5 pieces of 41+
    points hold 99 % of the points; the largest 88 %, 7.9 %, 2.2 %'."""
    pieces = ds.opening_pieces
    if ds.is_molecule:
        where = "opens at alpha² 0 (the union of the balls)"
    elif pieces.spacings is not None:
        where = f"opens at {pieces.spacings:.3g} spacings"
    else:
        where = "opens"
    return html.escape(f"{where}: {pieces.line()}")


def breakable(text: str) -> str:
    """text escaped for the dock; a name longer than the dock is wide gets a break
    opportunity after each '_', '.', '-' and '/', so it wraps instead of being cut off."""
    out = html.escape(text)
    if len(text) < WIDTH_CHARACTERS - 4:
        return out
    for mark in "_.-/":
        out = out.replace(mark, mark + "\u200b")
    return out


def molecule_lines(model: ExplorerModel) -> list[str]:
    """A molecule's measures (union of its balls at alpha² = 0), MEASURING while they are
    computed (or why they failed), or nothing."""
    ds = model.dataset
    if not ds.is_molecule:
        return []
    head = f"<b>molecule</b>, probe {ds.probe:g} Å (at alpha² 0)"
    m = ds.molecule
    if m is None:
        failure = model.measures_failure
        return [head, MEASURING if failure is None else f"measures failed: {failure}"]
    cavities = ", ".join(f"{v:.3g}" for v in m.cavities[:5]) + (" ..." if len(m.cavities) > 5
                                                                else "")
    return [head,
            f"surface area {m.surface_area:,.2f} Å² (exact)",
            f"volume {m.volume:,.2f} Å³ (exact, union of balls)",
            f"{len(m.cavities)} cavities" + (f": {cavities} Å³" if cavities else ""),
            f"{len(m.pockets)} pockets" + (f", largest {m.pockets.volume[0]:.3g} Å³"
                                           if len(m.pockets) else "")]


def box_lines(bbox, unit: str | None) -> list[str]:
    """One line per axis, 'x 636002.0 … 637179.1 (1177 m)': digits relative to the box's
    largest side, so a LiDAR box at 4.9e6 keeps its metres."""
    low, high = (np.asarray(corner, dtype=np.float64) for corner in bbox)
    extent = float(np.max(high - low)) if len(low) else 0.0
    return [f"{axis} {coordinate(lo, extent)} … {coordinate(hi, extent)} "
            f"({with_unit(quantity(hi - lo), unit)})"
            for axis, lo, hi in zip("xyz", low, high, strict=False)]


def class_counts(model: ExplorerModel) -> tuple[int, int, list[int]]:
    """(cells, regular facets, singular k-simplices for k < dim) at the current alpha.

    Read from the precomputed signatures (binary searches), never from the shape's arrays.
    """
    sig, dim = model.dataset.signatures, model.dataset.ac.dim
    counts = np.asarray(sig.counts_at(model.alpha))
    singular = [int(n) for n in counts[:dim, SINGULAR]]
    return int(counts[dim, INTERIOR]), int(counts[dim - 1, REGULAR]), singular


def alpha_line(model: ExplorerModel) -> str:
    """The current alpha in bold: 'alpha R', or for weighted points 'alpha² A2 (alpha R)'."""
    unit = model.dataset.unit
    radius = with_unit(quantity(model.alpha, 6), unit)
    at = (f"alpha² {with_unit(quantity(model.alpha2, 6), unit, 2)}"
          + (f" (alpha {radius})" if model.alpha >= 0 else "")
          if model.weighted else f"alpha {radius}")
    return f"<b>{at}</b>"


def waiting_lines(model: ExplorerModel) -> list[str]:
    """The shape block before the topology is known: what the slider's shape itself says."""
    dim, unit, shape = model.dataset.ac.dim, model.dataset.unit, model.shape
    measure = with_unit(quantity(shape.measure, 6), unit, dim)
    return [alpha_line(model), plural(len(shape.cells), "cell"),
            f"{'area' if dim == 2 else 'volume'} {measure}",
            "Betti numbers and class counts: computing…"]


def shape_lines(model: ExplorerModel) -> list[str]:
    """Lines describing the shape at the current alpha: classes, topology, measures."""
    if not model.dataset.has_topology:
        return waiting_lines(model)
    sig, dim, unit = model.dataset.signatures, model.dataset.ac.dim, model.dataset.unit
    cells, facets, singular = class_counts(model)
    lines = [alpha_line(model),
             f"{plural(cells, 'cell')}, {plural(facets, 'boundary facet')}",
             f"singular (points, edges{', triangles' if dim == 3 else ''}): "
             + ", ".join(f"{n:,}" for n in singular)]
    row = max(sig.index(model.alpha), 0)  # the slider may stand between critical values
    betti = sig.betti[row]
    lines.append(", ".join(plural(int(b), n) for b, n in zip(betti, BETTI_NAMES[dim],
                                                              strict=True)))
    boundary, measure = (float(v[row]) for v in (sig.boundary_measure, sig.measure))
    exact = " of the cells (the balls' exact figures: above)"
    cells = exact if model.dataset.is_molecule else ""
    lines.append(f"{'perimeter' if dim == 2 else 'area'} "
                 f"{with_unit(quantity(boundary, 6), unit, dim - 1)}{cells}")
    lines.append(f"{'area' if dim == 2 else 'volume'} "
                 f"{with_unit(quantity(measure, 6), unit, dim)}{cells}")
    return lines


class InfoPanel(QWidget):
    """Two text blocks, refreshed from the model."""

    def __init__(self, model: ExplorerModel, parent: QWidget | None = None) -> None:
        """Create the labels and follow model."""
        super().__init__(parent)
        self.model = model
        self.data = QLabel("No data yet: File → Open, or drop a file on the window.")
        self.shape = RowLabels()  # a slider step sets the text of the rows that changed only
        # the text scrolls when the dock is short, so wrapped lines are never drawn over
        scroll = QScrollArea(self)
        scroll.setWidgetResizable(True)
        scroll.setFrameShape(QFrame.Shape.NoFrame)
        scroll.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        inner = QWidget()
        column = QVBoxLayout(inner)
        column.setContentsMargins(0, 0, 0, 0)
        self.data.setTextFormat(Qt.TextFormat.RichText)
        self.data.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.data.setWordWrap(True)
        # the text never asks for width: the dock keeps its own (sizeHint below); its wrapped
        # lines keep their height
        self.data.setSizePolicy(QSizePolicy.Policy.Ignored, QSizePolicy.Policy.Minimum)
        column.addWidget(self.data)
        column.addWidget(self.shape)
        column.addStretch(1)
        scroll.setWidget(inner)
        outer = QVBoxLayout(self)
        outer.setContentsMargins(0, 0, 0, 0)
        outer.addWidget(scroll)
        model.datasetChanged.connect(self.show_data)
        model.alphaChanged.connect(self.show_shape)
        model.topologyChanged.connect(self.show_data)
        model.topologyChanged.connect(self.show_shape)
        model.measuresChanged.connect(self.show_data)
        model.datasetReleased.connect(self.data.clear)
        model.datasetReleased.connect(self.shape.clear)

    def sizeHint(self) -> QSize:
        """A fixed width of WIDTH_CHARACTERS characters, whatever the text shows."""
        return QSize(self.fontMetrics().averageCharWidth() * WIDTH_CHARACTERS,
                     super().sizeHint().height())

    def minimumSizeHint(self) -> QSize:
        """As wide as sizeHint: text changes never narrow or widen the dock."""
        return QSize(self.sizeHint().width(), super().minimumSizeHint().height())

    def show_data(self) -> None:
        """Refresh the data block."""
        self.data.setText("<br>".join(data_lines(self.model)))

    def show_shape(self) -> None:
        """Refresh the shape-at-alpha block (only its rows whose text changed)."""
        self.shape.set_lines(shape_lines(self.model))

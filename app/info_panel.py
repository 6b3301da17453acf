"""Info dock: facts about the data and about the shape at the current alpha."""

from __future__ import annotations

import html

import numpy as np
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QLabel, QVBoxLayout, QWidget

from app.model import ExplorerModel
from core.signatures import CLASSES

BETTI_NAMES = {2: ("components", "holes"), 3: ("components", "tunnels", "voids")}
SINGULAR, REGULAR, INTERIOR = (CLASSES.index(c) for c in ("singular", "regular", "interior"))


def data_lines(model: ExplorerModel) -> list[str]:
    """Lines describing the dataset: file, point counts, dimension, timings."""
    ds = model.dataset
    ac = ds.ac
    lines = [f"<b>{html.escape(ds.path.name)}</b>",
             f"{ds.n_input:,} points read, {len(ac.points):,} used"]
    report = ds.report
    if report is not None and getattr(report, "n_duplicates", 0):
        lines.append(f"{report.n_duplicates:,} duplicates merged")
    if report is not None and getattr(report, "spacing", 0):
        lines.append(f"spacing {report.spacing:.4g}")
    if report is not None and report.georef is not None:  # read from longitude/latitude
        lines.append(f"lengths in metres: {html.escape(report.georef.name)}")
    flat = " (planar 3D input)" if ac.dim < ac.ambient_dim else ""
    lines.append(f"{ac.dim}D complex{flat}, {len(ac.simplices(ac.dim)):,} cells")
    if ac.weights is not None:
        source = getattr(report, "weights_from", None) or "given weights"
        hidden = int((np.asarray(ac.input_index) < 0).sum())
        lines.append(f"weighted: {html.escape(source)}; {hidden:,} hidden points")
    lines.append(f"read in {ds.load_seconds:.2f} s, {ds.build_line()}")
    return lines + molecule_lines(model)


def molecule_lines(model: ExplorerModel) -> list[str]:
    """A molecule's measures (union of its balls at alpha² = 0), or nothing."""
    m = model.dataset.molecule
    if m is None:
        return []
    cavities = ", ".join(f"{v:.3g}" for v in m.cavities[:5]) + (" ..." if len(m.cavities) > 5
                                                                else "")
    return [f"<b>molecule</b>, probe {m.probe:g} Å (at alpha² 0)",
            f"surface area {m.surface_area:,.2f} Å² (exact)",
            f"volume {m.volume:,.2f} Å³ (exact)",
            f"{len(m.cavities)} cavities" + (f": {cavities} Å³" if cavities else "")]


def class_counts(model: ExplorerModel) -> tuple[int, int, list[int]]:
    """(cells, regular facets, singular k-simplices for k < dim) at the current alpha.

    Read from the precomputed signatures (binary searches), never from the shape's arrays.
    """
    sig, dim = model.dataset.signatures, model.dataset.ac.dim
    counts = np.asarray(sig.counts_at(model.alpha))
    singular = [int(n) for n in counts[:dim, SINGULAR]]
    return int(counts[dim, INTERIOR]), int(counts[dim - 1, REGULAR]), singular


def shape_lines(model: ExplorerModel) -> list[str]:
    """Lines describing the shape at the current alpha: classes, topology, measures."""
    sig, dim = model.dataset.signatures, model.dataset.ac.dim
    cells, facets, singular = class_counts(model)
    at = (f"alpha² {model.alpha2:.6g}" + (f" (alpha {model.alpha:.6g})" if model.alpha >= 0
                                          else "")
          if model.weighted else f"alpha {model.alpha:.6g}")
    lines = [f"<b>{at}</b>", f"{cells:,} cells, {facets:,} boundary facets",
             f"singular (points, edges{', triangles' if dim == 3 else ''}): "
             + ", ".join(f"{n:,}" for n in singular)]
    betti = sig.betti[model.index]
    lines.append(", ".join(f"{int(b):,} {n}" for b, n in zip(betti, BETTI_NAMES[dim], strict=True)))
    lines.append(f"{'perimeter' if dim == 2 else 'area'} "
                 f"{float(sig.boundary_measure[model.index]):.6g}")
    lines.append(f"{'area' if dim == 2 else 'volume'} {float(sig.measure[model.index]):.6g}")
    return lines


class InfoPanel(QWidget):
    """Two text blocks, refreshed from the model."""

    def __init__(self, model: ExplorerModel, parent: QWidget | None = None) -> None:
        """Create the labels and follow model."""
        super().__init__(parent)
        self.model = model
        self.data = QLabel("No data yet: File → Open, or drop a file on the window.")
        self.shape = QLabel()
        column = QVBoxLayout(self)
        for label in (self.data, self.shape):
            label.setTextFormat(Qt.TextFormat.RichText)
            label.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
            label.setWordWrap(True)
            column.addWidget(label)
        column.addStretch(1)
        model.datasetChanged.connect(self.show_data)
        model.alphaChanged.connect(self.show_shape)

    def show_data(self) -> None:
        """Refresh the data block."""
        self.data.setText("<br>".join(data_lines(self.model)))

    def show_shape(self) -> None:
        """Refresh the shape-at-alpha block."""
        self.shape.setText("<br>".join(shape_lines(self.model)))

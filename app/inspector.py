"""Wires inspection: a click in the view (the scene's picker) -> the table row (app.inspect) -> the
Inspect dock and the highlight (with the spoon when asked for)."""

from __future__ import annotations

import numpy as np
from PySide6.QtWidgets import QDockWidget

from app.inspect import inspect, spoon
from app.inspect_panel import InspectPanel
from app.model import ExplorerModel
from app.scene import Scene


class Inspector:
    """Owns the picker; keeps the panel and the highlight on the inspected simplex."""

    def __init__(self, model: ExplorerModel, scene: Scene, panel: InspectPanel,
                 dock: QDockWidget) -> None:
        """Observe clicks in the scene; show results in panel (dock raised on a hit)."""
        self.model, self.panel, self.dock = model, panel, dock
        self.picker = scene.add_picker(self.inspect_vertices, panel.clear)
        panel.cleared.connect(self.picker.clear)
        panel.spoonToggled.connect(lambda _on: self.redraw())

    def inspect_vertices(self, vertices: np.ndarray) -> None:
        """Show the simplex with these vertices in the panel and the view."""
        if self.model.dataset is None:
            return
        self.panel.show_item(inspect(self.model.dataset.ac, vertices))
        self.dock.show()
        self.dock.raise_()
        self.redraw()

    def redraw(self) -> None:
        """Draw the inspected simplex, with its spoon when the panel asks for it."""
        item = self.panel.item
        if item is None:
            return
        wanted = self.panel.spoon.isChecked() and self.panel.spoon.isEnabled()
        self.picker.show(item, spoon(self.model.dataset.ac, item) if wanted else None)

"""Colour by, on the app side: which mode, the values it shows (app.colouring) handed to the
scene's painter as arrays, and the View → Colour by menu. No VTK here (app.scene.painting).

In the modes that colour simplices (enter alpha, component) the values follow the shape after
each geometry change (`update`); point attributes are set once per mode.
"""

from __future__ import annotations

import numpy as np
from PySide6.QtGui import QAction, QActionGroup
from PySide6.QtWidgets import QMenu

from app.colouring import (
    CELL_LAYERS,
    CLASS,
    ColourMode,
    cell_values,
    modes_for,
    point_values,
    value_range,
)
from app.model import ExplorerModel
from app.scene import Scene
from core.topology.components import solid_labels


def legend_title(mode: ColourMode) -> str | None:
    """How the legend names a colour-by mode ('enter alpha', 'intensity'); None for class."""
    if mode.source is None:
        return None
    title = {"enter": "enter alpha"}.get(mode.key, mode.title)
    return title[:1].lower() + title[1:] if title[1:2].islower() else title


class Colourer:
    """Keeps a ColourMode on a Scene's layers: computes its values, the scene draws them."""

    def __init__(self, scene: Scene, model: ExplorerModel) -> None:
        """Start in class colours with no dataset."""
        self.scene, self.model = scene, model
        self.mode = CLASS
        self.modes = [CLASS]
        self.attributes: dict[str, np.ndarray] = {}

    def set_dataset(self, attributes: dict[str, np.ndarray]) -> None:
        """New dataset (new layers): its modes; keep the mode if the dataset offers it."""
        self.attributes = attributes
        self.modes = modes_for(attributes)
        keys = [mode.key for mode in self.modes]
        self.set_mode(self.mode.key if self.mode.key in keys else CLASS.key, render=False)

    def set_mode(self, key: str, render: bool = True) -> None:
        """Colour by the mode with this key (a key the dataset does not offer: class)."""
        self.mode = next((mode for mode in self.modes if mode.key == key), CLASS)
        values = point_values(self.mode, self.attributes) if self.mode.source == "points" \
            else None
        self.scene.painter.set_mode(self.mode, values)
        self.update()
        if render:
            self.scene.render()

    def update(self) -> None:
        """Re-colour after a geometry or visibility change (no render)."""
        if self.model.dataset is None or not self.scene.layers:
            return
        shown = self.scene.painter.paint(self._cell_values())
        values = np.concatenate([np.asarray(v, dtype=np.float64).ravel() for v in shown]) \
            if shown else np.zeros(0)
        low, high = value_range(self.mode, values, self.model.alpha, self.model.spectrum)
        self.scene.painter.set_range(low, high, legend_title(self.mode))

    def _cell_values(self) -> dict[str, np.ndarray | None]:
        """Per visible cell layer, the (c,) values of its drawn simplices in a cell mode."""
        shape = self.scene.shape
        if self.mode.source != "cells" or shape is None:
            return {}
        ac = self.model.dataset.ac
        labels = solid_labels(ac, shape.alpha) if self.mode.key == "component" else None
        return {name: cell_values(self.mode, ac, shape, name, labels)
                for name in self.scene.visible_layers() if name in CELL_LAYERS}


def fill_colour_menu(menu: QMenu, colourer: Colourer) -> dict[str, QAction]:
    """(Re)fill View → Colour by with one checkable action per mode; returns them by key."""
    menu.clear()
    group = QActionGroup(menu)
    actions = {}
    for mode in colourer.modes:
        action = menu.addAction(mode.title)
        action.setCheckable(True)
        action.setChecked(mode.key == colourer.mode.key)
        group.addAction(action)
        action.triggered.connect(lambda _=False, key=mode.key: colourer.set_mode(key))
        actions[mode.key] = action
    return actions


def add_colour_menu(menu: QMenu, colourer: Colourer) -> QMenu:
    """Add the Colour by submenu to menu; it lists the current dataset's modes when opened."""
    submenu = menu.addMenu("&Colour by")
    submenu.aboutToShow.connect(lambda: fill_colour_menu(submenu, colourer))
    fill_colour_menu(submenu, colourer)
    return submenu

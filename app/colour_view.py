"""Colour by, on the VTK side: scalars on the layers' meshes, their mappers' lookup table and
one colour bar; the View → Colour by menu.

Only mapper state and scalar arrays change: the layers' connectivity is never touched here. In
the modes that colour simplices (enter alpha, component) the values follow the shape after each
geometry change (`update`); point attributes are set once per mode.
"""

from __future__ import annotations

import numpy as np
import pyvista as pv
from PySide6.QtGui import QAction, QActionGroup
from PySide6.QtWidgets import QMenu

from app.colouring import (
    CELL_LAYERS,
    CLASS,
    MAX_CATEGORIES,
    ColourMode,
    cell_values,
    modes_for,
    point_values,
    value_range,
)
from app.model import ExplorerModel
from app.palette import TEXT
from app.scene import Scene
from core.components import solid_labels

SCALARS = "colour_by"
OWN_COLOURS = "rgb"  # a layer's own per-point colours (atom balls by element)
NAN_COLOUR = "#8c96a0"
BAR = {"vertical": True, "position_x": 0.88, "position_y": 0.2, "width": 0.07, "height": 0.55,
       "n_labels": 5, "fmt": "%.3g", "color": TEXT, "title_font_size": 14,
       "label_font_size": 12}


def lookup_table(mode: ColourMode) -> pv.LookupTable:
    """A lookup table for mode: tab20 for categories, viridis (log for alphas) otherwise."""
    if mode.categorical:
        table = pv.LookupTable(cmap="tab20", n_values=MAX_CATEGORIES)
    else:
        table = pv.LookupTable(cmap="viridis", n_values=256, log_scale=mode.log)
    table.nan_color = NAN_COLOUR
    return table


def legend_title(mode: ColourMode) -> str | None:
    """How the legend names a colour-by mode ('enter alpha', 'intensity'); None for class."""
    if mode.source is None:
        return None
    title = {"enter": "enter alpha"}.get(mode.key, mode.title)
    return title[:1].lower() + title[1:] if title[1:2].islower() else title


class Colourer:
    """Applies a ColourMode to a Scene's layers and keeps its colour bar."""

    def __init__(self, plotter: pv.BasePlotter, scene: Scene, model: ExplorerModel) -> None:
        """Start in class colours with no dataset."""
        self.plotter, self.scene, self.model = plotter, scene, model
        self.mode = CLASS
        self.modes = [CLASS]
        self.attributes: dict[str, np.ndarray] = {}
        self.table = lookup_table(CLASS)
        self.bar_title: str | None = None

    def set_dataset(self, attributes: dict[str, np.ndarray]) -> None:
        """New dataset (new layers): its modes; keep the mode if the dataset offers it."""
        self.attributes = attributes
        self.modes = modes_for(attributes)
        keys = [mode.key for mode in self.modes]
        self.bar_title = None  # the old layers' bar went with them
        self.set_mode(self.mode.key if self.mode.key in keys else CLASS.key, render=False)

    def set_mode(self, key: str, render: bool = True) -> None:
        """Colour by the mode with this key (a key the dataset does not offer: class)."""
        self.mode = next((mode for mode in self.modes if mode.key == key), CLASS)
        self.table = lookup_table(self.mode)
        self._remove_bar()
        if self.mode.source == "points":
            values = point_values(self.mode, self.attributes)
            for layer in self.scene.layers.values():
                if layer.mesh.n_points == len(values):  # not glyphs such as atom balls
                    layer.mesh.point_data[SCALARS] = values
        self.update()
        if render:
            self.scene.render()

    def update(self) -> None:
        """Re-colour after a geometry or visibility change (no render)."""
        if self.model.dataset is None or not self.scene.layers:
            return
        shape = self.scene.shape
        labels = None
        if self.mode.key == "component" and shape is not None:
            labels = solid_labels(self.model.dataset.ac, shape.alpha)
        shown = []
        for name, layer in self.scene.layers.items():
            if self.mode.source == "points" and SCALARS in layer.mesh.point_data:
                shown.append(self._use_points(layer))
            elif self.mode.source == "cells" and shape is not None and name in CELL_LAYERS \
                    and self.scene.styles[name].visible:
                values = cell_values(self.mode, self.model.dataset.ac, shape, name, labels)
                shown.append(self._use_cells(layer, values))
            elif OWN_COLOURS in layer.mesh.point_data:
                self._use_own(layer)
            else:
                layer.actor.mapper.SetScalarVisibility(False)
        data = [v for v in shown if v is not None and len(v)]
        values = np.concatenate([np.asarray(v, dtype=np.float64).ravel() for v in data]) \
            if data else np.zeros(0)
        low, high = value_range(self.mode, values, self.model.alpha, self.model.spectrum)
        self.table.scalar_range = (low, high)
        for layer in self.scene.layers.values():
            layer.actor.mapper.SetScalarRange(low, high)
        mapped = frozenset(name for name, layer in self.scene.layers.items()
                           if self._mapped(layer))
        self.scene.overlay.set_colour_by(legend_title(self.mode), mapped)
        if self.bar_title is None and self.mode.source is not None and not self.mode.rgb:
            self._add_bar()  # once per mode and dataset; later steps only move its range

    @staticmethod
    def _use_own(layer) -> None:
        """Draw a layer in its own per-point colours (atom balls by element)."""
        mapper = layer.actor.mapper
        mapper.SetScalarModeToUsePointFieldData()
        mapper.SelectColorArray(OWN_COLOURS)
        mapper.SetColorModeToDirectScalars()
        mapper.SetScalarVisibility(True)

    @staticmethod
    def _mapped(layer) -> bool:
        """The layer is painted by the mode's colour map (not its class or own colours)."""
        mapper = layer.actor.mapper
        return bool(mapper.GetScalarVisibility()) and mapper.GetArrayName() != OWN_COLOURS

    def _use_cells(self, layer, values: np.ndarray | None) -> np.ndarray | None:
        """Colour layer by its per-cell values (None: class colour)."""
        mapper = layer.actor.mapper
        if values is None or len(values) != len(layer.cells):
            mapper.SetScalarVisibility(False)
            return None
        layer.mesh.cell_data[SCALARS] = values
        mapper.SetScalarModeToUseCellFieldData()
        self._map(mapper)
        return values

    def _use_points(self, layer) -> np.ndarray:
        """Colour layer by the point attribute set in set_mode."""
        mapper = layer.actor.mapper
        mapper.SetScalarModeToUsePointFieldData()
        self._map(mapper)
        return layer.mesh.point_data[SCALARS]

    def _map(self, mapper) -> None:
        """Point mapper at the colour array through the lookup table (or direct RGB)."""
        mapper.SelectColorArray(SCALARS)
        mapper.SetLookupTable(self.table)
        mapper.SetUseLookupTableScalarRange(False)
        if self.mode.rgb:
            mapper.SetColorModeToDirectScalars()
        else:
            mapper.SetColorModeToMapScalars()
        mapper.SetScalarVisibility(True)

    def _add_bar(self) -> None:
        """One colour bar for the mode, tied to a coloured layer's mapper."""
        mapper = next((layer.actor.mapper for layer in self.scene.layers.values()
                       if self._mapped(layer)), None)
        if mapper is None:
            return
        self.bar_title = {"enter": "enters at alpha (r)",
                          "component": "solid component"}.get(self.mode.key, self.mode.title)
        self.plotter.add_scalar_bar(title=self.bar_title, mapper=mapper, render=False, **BAR)

    def _remove_bar(self) -> None:
        """Remove the mode's colour bar, if any."""
        if self.bar_title is not None and self.bar_title in self.plotter.scalar_bars:
            self.plotter.remove_scalar_bar(self.bar_title, render=False)
        self.bar_title = None


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

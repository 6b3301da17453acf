"""Colour by, on the VTK side: value arrays on the layers' meshes, their mappers' lookup table
and one colour bar. app.colour_view decides the values; this module only draws them.

Only mapper state and scalar arrays change: the layers' connectivity is never touched here.
"""

from __future__ import annotations

import numpy as np
import pyvista as pv

from app.colouring import CLASS, MAX_CATEGORIES, ColourMode
from app.palette import TEXT
from app.scene.layers import Layer
from app.scene.overlay import Overlay

SCALARS = "colour_by"
OWN_COLOURS = "rgb"  # a layer's own per-point colours (atom balls by element)
NAN_COLOUR = "#8c96a0"
BAR = {"vertical": True, "position_x": 0.88, "position_y": 0.2, "width": 0.07, "height": 0.55,
       "n_labels": 5, "fmt": "%.3g", "color": TEXT, "title_font_size": 14,
       "label_font_size": 12}
BAR_TITLES = {"enter": "enters at alpha (r)", "component": "solid component"}


def lookup_table(mode: ColourMode) -> pv.LookupTable:
    """A lookup table for mode: tab20 for categories, viridis (log for alphas) otherwise."""
    if mode.categorical:
        table = pv.LookupTable(cmap="tab20", n_values=MAX_CATEGORIES)
    else:
        table = pv.LookupTable(cmap="viridis", n_values=256, log_scale=mode.log)
    table.nan_color = NAN_COLOUR
    return table


def is_mapped(layer: Layer) -> bool:
    """The layer is painted by the colour map (not its class or its own colours)."""
    mapper = layer.actor.mapper
    return bool(mapper.GetScalarVisibility()) and mapper.GetArrayName() != OWN_COLOURS


def use_own(layer: Layer) -> None:
    """Draw a layer in its own per-point colours (atom balls by element) or per-cell ones
    (a molecule's pockets)."""
    mapper = layer.actor.mapper
    if OWN_COLOURS in layer.mesh.point_data:
        mapper.SetScalarModeToUsePointFieldData()
    else:
        mapper.SetScalarModeToUseCellFieldData()
    mapper.SelectColorArray(OWN_COLOURS)
    mapper.SetColorModeToDirectScalars()
    mapper.SetScalarVisibility(True)


class Painter:
    """Applies a colour mode's values to the scene's layers and keeps its colour bar."""

    def __init__(self, plotter: pv.BasePlotter, layers: dict[str, Layer],
                 overlay: Overlay) -> None:
        """Paint the scene's `layers` (its one dict) in plotter; class colours to start."""
        self.plotter, self.layers, self.overlay = plotter, layers, overlay
        self.mode = CLASS
        self.table = lookup_table(CLASS)
        self.bar_title: str | None = None

    def reset(self) -> None:
        """New layers: the old layers' colour bar went with them."""
        self.bar_title = None

    def set_mode(self, mode: ColourMode, point_values: np.ndarray | None = None) -> None:
        """Colour by mode from now on; `point_values` ((m,) float64 or (m, 3) uint8) go on
        every layer drawn on the dataset's points (not glyphs such as atom balls)."""
        self.mode = mode
        self.table = lookup_table(mode)
        self._remove_bar()
        if point_values is not None:
            for layer in self.layers.values():
                if layer.mesh.n_points == len(point_values):
                    layer.mesh.point_data[SCALARS] = point_values

    def paint(self, cell_values: dict[str, np.ndarray | None]) -> list[np.ndarray]:
        """Point every layer's mapper at what it shows: the point values of a point mode,
        the given (c,) per-cell values of the named layers (None: class colour), its own
        colours, or its class colour. Returns the non-empty value arrays shown."""
        shown = []
        for name, layer in self.layers.items():
            if self.mode.source == "points" and SCALARS in layer.mesh.point_data:
                shown.append(self._use_points(layer))
            elif name in cell_values:
                shown.append(self._use_cells(layer, cell_values[name]))
            elif OWN_COLOURS in layer.mesh.point_data or OWN_COLOURS in layer.mesh.cell_data:
                use_own(layer)
            else:
                layer.actor.mapper.SetScalarVisibility(False)
        return [values for values in shown if values is not None and len(values)]

    def set_range(self, low: float, high: float, legend: str | None) -> None:
        """Map [low, high] over the colours; the legend says `legend` (None: class colours)
        and drops the swatches of the mapped layers; one colour bar per mode and dataset."""
        self.table.scalar_range = (low, high)
        for layer in self.layers.values():
            layer.actor.mapper.SetScalarRange(low, high)
        mapped = frozenset(name for name, layer in self.layers.items() if is_mapped(layer))
        self.overlay.set_colour_by(legend, mapped)
        if self.bar_title is None and self.mode.source is not None and not self.mode.rgb:
            self._add_bar()  # later steps only move its range

    def _use_cells(self, layer: Layer, values: np.ndarray | None) -> np.ndarray | None:
        """Colour layer by its per-cell values (None or a stale length: class colour)."""
        mapper = layer.actor.mapper
        if values is None or len(values) != len(layer.cells):
            mapper.SetScalarVisibility(False)
            return None
        layer.mesh.cell_data[SCALARS] = values
        mapper.SetScalarModeToUseCellFieldData()
        self._map(mapper)
        return values

    def _use_points(self, layer: Layer) -> np.ndarray:
        """Colour layer by the point values set in set_mode."""
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
        mapper = next((layer.actor.mapper for layer in self.layers.values() if is_mapped(layer)),
                      None)
        if mapper is None:
            return
        self.bar_title = BAR_TITLES.get(self.mode.key, self.mode.title)
        self.plotter.add_scalar_bar(title=self.bar_title, mapper=mapper, render=False, **BAR)

    def _remove_bar(self) -> None:
        """Remove the mode's colour bar, if any."""
        if self.bar_title is not None and self.bar_title in self.plotter.scalar_bars:
            self.plotter.remove_scalar_bar(self.bar_title, render=False)
        self.bar_title = None

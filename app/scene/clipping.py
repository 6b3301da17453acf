"""The scene's clipping plane, to look inside the shape: interior cells, voids, the far side
of a surface.

The plane clips in the mappers (rendering only): no geometry is recomputed, the layers'
connectivity and cell ids stay as they are (so picking still maps to the table), and a slider
step needs nothing from here. In the window a plane widget moves and turns it.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pyvista as pv
from vtkmodules.vtkCommonDataModel import vtkPlane

from app.scene.layers import Layer


class Clipper:
    """One plane shared by every layer's mapper while clipping is on."""

    def __init__(self, plotter: pv.BasePlotter, layers: dict[str, Layer],
                 render: Callable[[], None]) -> None:
        """Clip the scene's `layers` (its one dict) in plotter; off until set_enabled(True)."""
        self.plotter, self.layers, self.render = plotter, layers, render
        self.plane = vtkPlane()
        self.enabled = False

    def set_enabled(self, on: bool) -> None:
        """Clip every layer with the plane, placed through the data's centre (without data the
        wish is kept for the next dataset)."""
        self.enabled = bool(on)
        if not self.layers:
            return
        if self.enabled:
            self._place_default()
        self.apply()
        self._widget(self.enabled)
        self.render()

    def _place_default(self) -> None:
        """Through the centre of the points, facing along x (the widget turns it)."""
        bounds = np.asarray(self.layers["points"].mesh.bounds).reshape(-1, 2)
        self.set_plane(bounds.mean(axis=1), (1.0, 0.0, 0.0), render=False)

    def apply(self) -> None:
        """Attach (or detach) the plane to every layer's mapper: after a new dataset too."""
        for layer in self.layers.values():
            mapper = layer.actor.mapper
            mapper.RemoveAllClippingPlanes()
            if self.enabled:
                mapper.AddClippingPlane(self.plane)

    def set_plane(self, origin, normal, render: bool = True) -> None:
        """Move the plane: what lies on the normal's side of origin is cut away."""
        self.plane.SetOrigin(*np.asarray(origin, dtype=np.float64))
        self.plane.SetNormal(*(-np.asarray(normal, dtype=np.float64)))
        if render:
            self.render()

    def _widget(self, on: bool) -> None:
        """The interactive plane (window only): dragging it moves the cut."""
        self.plotter.clear_plane_widgets()
        if not on or getattr(self.plotter, "iren", None) is None:
            return
        origin, normal = self.plane.GetOrigin(), -np.asarray(self.plane.GetNormal())
        self.plotter.add_plane_widget(
            lambda n, o: self.set_plane(o, n), normal=tuple(normal), origin=origin,
            bounds=self.layers["points"].mesh.bounds, implicit=True, outline_opacity=0.3,
            interaction_event="always", color="#ffd400", tubing=False, normal_rotation=True)


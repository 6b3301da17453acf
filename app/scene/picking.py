"""Clicking in the view to inspect: a VTK cell picker on the shown layers, and the highlight of
the inspected simplex and its spoon.

A left click without a drag (a drag rotates the view) picks the front-most cell of a visible
layer; the layer's drawn connectivity turns the picked cell id into vertices, and
app.inspect finds the table row from them. Esc clears.
"""

from __future__ import annotations

from collections.abc import Callable
from itertools import combinations

import numpy as np
import pyvista as pv
from PySide6.QtCore import QTimer
from vtkmodules.vtkRenderingCore import vtkCellPicker

from app.inspect import Inspection
from app.scene.data import as_xyz
from app.scene.layers import Layer

PICK_TOLERANCE = 0.004  # of the window diagonal: lines and points are thin targets
CLICK_SLOP_PX = 4  # a press and release further apart than this are a drag, not a click
HIGHLIGHT = "#ffd400"
SPOON_COLOUR = "#fff3b0"
OVERLAY_NAMES = ("inspect_simplex", "inspect_spoon")


def simplex_mesh(coords: np.ndarray) -> pv.PolyData:
    """Its vertices and every edge between them, as one polydata (lines and vertices)."""
    mesh = pv.PolyData(as_xyz(coords))
    count = len(coords)
    mesh.verts = pv.CellArray.from_regular_cells(np.arange(count, dtype=np.int32)[:, None])
    if count > 1:
        mesh.lines = pv.CellArray.from_regular_cells(
            np.array(list(combinations(range(count), 2)), dtype=np.int32))
    return mesh


def spoon_mesh(centre: np.ndarray, radius: float) -> pv.PolyData:
    """A sphere (3D input) or a circle in the z = 0 plane (2D input) of the given radius."""
    centre = np.asarray(centre, dtype=np.float64)
    if len(centre) == 2:
        return pv.Polygon(center=(*centre, 0.0), radius=radius, normal=(0, 0, 1), n_sides=120,
                          fill=False)
    return pv.Sphere(radius=radius, center=centre, theta_resolution=48, phi_resolution=24)


class ViewPicker:
    """Picks cells of the scene's visible layers under a click; draws the inspected simplex."""

    def __init__(self, plotter: pv.BasePlotter, layers: dict[str, Layer],
                 render: Callable[[], None], on_pick: Callable[[np.ndarray], None],
                 on_escape: Callable[[], None]) -> None:
        """Observe plotter's interactor (when it has one) over the scene's `layers`;
        on_pick(vertices) after a hit (made by Scene.add_picker)."""
        self.plotter, self.layers, self.render = plotter, layers, render
        self.on_pick, self.on_escape = on_pick, on_escape
        self.picker = vtkCellPicker()
        self.picker.SetTolerance(PICK_TOLERANCE)
        self._press: tuple[int, int] | None = None
        iren = getattr(plotter, "iren", None)
        if iren is not None:
            for event, handler in (("LeftButtonPressEvent", self._pressed),
                                   ("LeftButtonReleaseEvent", self._released),
                                   ("KeyPressEvent", self._key)):
                observer = iren.interactor.AddObserver(event, handler)
                # Passive: still called while a rotating interactor style holds the focus
                # (it swallows the release otherwise); the work runs after the event.
                iren.interactor.GetCommand(observer).SetPassiveObserver(1)

    def _position(self) -> tuple[int, int]:
        """The interactor's event position (display pixels, origin bottom left)."""
        x, y = self.plotter.iren.interactor.GetEventPosition()
        return int(x), int(y)

    def _pressed(self, *_) -> None:
        """Remember where the left button went down."""
        self._press = self._position()

    def _released(self, *_) -> None:
        """A release near the press is a click: pick there."""
        if self._press is None:
            return
        (x0, y0), (x, y) = self._press, self._position()
        self._press = None
        if abs(x - x0) <= CLICK_SLOP_PX and abs(y - y0) <= CLICK_SLOP_PX:
            QTimer.singleShot(0, lambda: self.click(x, y))

    def _key(self, *_) -> None:
        """Esc clears the inspected simplex."""
        if self.plotter.iren.interactor.GetKeySym() == "Escape":
            QTimer.singleShot(0, self.on_escape)

    def click(self, x: int, y: int) -> None:
        """What a click at display (x, y) does: pick, and hand the vertices on when it hits."""
        vertices = self.pick_at(x, y)
        if vertices is not None:
            self.on_pick(vertices)

    def pick_at(self, x: int, y: int) -> np.ndarray | None:
        """(k+1,) int32 vertices of the front-most visible layer cell at display (x, y)."""
        if not self.picker.Pick(x, y, 0, self.plotter.renderer):
            return None
        actor, cell = self.picker.GetActor(), self.picker.GetCellId()
        for layer in self.layers.values():
            if layer.actor is actor and 0 <= cell < len(layer.cells):
                return np.asarray(layer.cells[cell])
        return None

    def show(self, item: Inspection, spoon: tuple[np.ndarray, float] | None) -> None:
        """Draw item's simplex highlighted, and its spoon when given (replaces the last)."""
        self.plotter.add_mesh(simplex_mesh(item.coords), name=OVERLAY_NAMES[0], color=HIGHLIGHT,
                              line_width=5, point_size=12, render_points_as_spheres=True,
                              pickable=False, reset_camera=False, lighting=False)
        if spoon is None:
            self.plotter.remove_actor(OVERLAY_NAMES[1], reset_camera=False, render=False)
        else:
            self.plotter.add_mesh(spoon_mesh(*spoon), name=OVERLAY_NAMES[1], color=SPOON_COLOUR,
                                  opacity=0.3, pickable=False, reset_camera=False,
                                  line_width=2, smooth_shading=True)
        self.render()

    def clear(self) -> None:
        """Remove the highlight and the spoon."""
        for name in OVERLAY_NAMES:
            self.plotter.remove_actor(name, reset_camera=False, render=False)
        self.render()

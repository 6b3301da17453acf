"""The one module that owns VTK/pyvista objects: a persistent mesh and actor per layer.

A new dataset replaces the layers' points once; a new alpha only swaps their connectivity in
place (zero-copy numpy -> vtkCellArray), so a slider step never adds or removes an actor.
"""

from __future__ import annotations

import numpy as np
import pyvista as pv

POINT_SIZE = 3.0


def as_xyz(points: np.ndarray) -> np.ndarray:
    """(m, 3) float64 view/copy of (m, 2) or (m, 3) points (2D gets z = 0)."""
    points = np.asarray(points, dtype=np.float64)
    if points.shape[1] == 3:
        return np.ascontiguousarray(points)
    return np.column_stack([points, np.zeros(len(points))])


def cell_array(cells: np.ndarray) -> pv.CellArray:
    """vtkCellArray sharing memory with (k, s) int32 cells (s points each; copy only if needed)."""
    cells = np.ascontiguousarray(cells, dtype=np.int32)
    return pv.CellArray.from_regular_cells(cells.reshape(len(cells), -1))


class Scene:
    """Layers of one dataset drawn into a pyvista plotter (QtInteractor or off-screen)."""

    def __init__(self, plotter: pv.BasePlotter) -> None:
        """Draw into plotter; no layers until set_points."""
        self.plotter = plotter
        self.plotter.theme.allow_empty_mesh = True
        self.meshes: dict[str, pv.PolyData] = {}
        self.actors: dict[str, pv.Actor] = {}

    def set_points(self, points: np.ndarray) -> None:
        """Show a new dataset's (m, 2|3) points; replaces every layer's geometry."""
        xyz = as_xyz(points)
        if "points" not in self.meshes:
            self.meshes["points"] = pv.PolyData()
            self.actors["points"] = self.plotter.add_mesh(
                self.meshes["points"], color="#d8dee9", point_size=POINT_SIZE,
                render_points_as_spheres=False, name="points", reset_camera=False,
            )
        mesh = self.meshes["points"]
        mesh.points = xyz
        mesh.verts = cell_array(np.arange(len(xyz), dtype=np.int32)[:, None])
        self.plotter.reset_camera()

    def render(self) -> None:
        """Request one render of the plotter."""
        self.plotter.render()

"""The one module that owns VTK/pyvista objects: a persistent mesh and actor per layer.

A new dataset replaces the layers' points once; a new alpha only swaps their connectivity in
place (zero-copy numpy -> vtkCellArray), so a slider step never adds or removes an actor.
Hidden layers are not updated until shown again.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import pyvista as pv
from vtkmodules.vtkFiltersGeneral import vtkShrinkFilter

from app.camera import Z_UP, ViewFrame
from app.overlay import Overlay
from app.palette import BACKGROUND, MAX_BALLS, LayerStyle

SHRINK_FACTOR = 0.8
KINDS_3D = {
    "delaunay": "lines", "points": "verts", "interior": "tets", "surface": "tris",
    "singular_highlight": "tris", "singular_edges": "lines", "singular_points": "verts",
}
KINDS_2D = {
    "delaunay": "lines", "points": "verts", "interior": "tris", "boundary": "lines",
    "singular_edges": "lines", "singular_points": "verts",
}
STATIC_LAYERS = ("points", "delaunay", "balls", "cavities")
BALL_RESOLUTION = 10  # sphere glyph: 10 x 10 facets, about 160 triangles per ball
DRAW_OPTIONS = {
    "points": {"point_size": 3.0},
    "singular_points": {"point_size": 5.0, "render_points_as_spheres": True},
    "singular_edges": {"line_width": 3.0},
    "boundary": {"line_width": 2.0},
    "delaunay": {"line_width": 1.0},
}


def as_xyz(points: np.ndarray) -> np.ndarray:
    """(m, 3) float64 copy of (m, 2) or (m, 3) points (2D gets z = 0)."""
    points = np.asarray(points, dtype=np.float64)
    if points.shape[1] == 3:
        return np.ascontiguousarray(points)
    return np.column_stack([points, np.zeros(len(points))])


def cell_array(cells: np.ndarray) -> pv.CellArray:
    """vtkCellArray sharing memory with (k, s) int32 cells (copies only to fix the dtype)."""
    cells = np.ascontiguousarray(cells, dtype=np.int32)
    return pv.CellArray.from_regular_cells(cells if cells.ndim == 2 else cells[:, None])


def shape_cells(shape, name: str) -> np.ndarray:
    """(k, s) int32 simplices an AlphaShape gives the named layer.

    The 3D surface is what a scan looks like: regular and singular triangles as one surface
    (at small alphas much of a thin scan is singular); `singular_highlight` marks the latter.
    """
    if name == "interior":
        return shape.cells
    if name == "boundary":
        return shape.regular_facets
    if name == "surface":
        return np.concatenate([shape.regular_facets, shape.singular(2)])
    order = {"singular_points": 0, "singular_edges": 1, "singular_highlight": 2}[name]
    return shape.singular(order).reshape(-1, order + 1)


@dataclass
class Layer:
    """One drawn layer: its mesh (connectivity swapped in place) and actor."""

    kind: str
    mesh: pv.DataSet
    actor: pv.Actor | None = None
    dirty: bool = False
    cells: np.ndarray = field(default_factory=lambda: np.zeros((0, 1), dtype=np.int32))

    def set_cells(self, cells: np.ndarray) -> None:
        """Replace the layer's (k, s) connectivity in place (points stay)."""
        array = cell_array(cells)
        if self.kind == "tets":
            self.mesh.SetCells(pv.CellType.TETRA, array)
        elif self.kind == "tris":
            self.mesh.faces = array
        elif self.kind == "lines":
            self.mesh.lines = array
        else:
            self.mesh.verts = array
        self.mesh.Modified()
        self.cells = cells
        self.dirty = False


def ball_mesh(xyz: np.ndarray, radii: np.ndarray, limit: int = MAX_BALLS,
              rgb: np.ndarray | None = None) -> pv.PolyData:
    """Spheres of the given (m,) radii around at most `limit` of the (m, 3) points (evenly
    picked, so a big set still shows its spread); `rgb` (m, 3) uint8 colours them (point
    data "rgb" of the glyphs)."""
    pick = np.unique(np.linspace(0, len(xyz) - 1, min(limit, len(xyz))).round().astype(np.int64))
    centres = pv.PolyData(np.ascontiguousarray(xyz[pick]))
    centres["radius"] = np.asarray(radii, dtype=np.float64)[pick]
    if rgb is not None:
        centres["rgb"] = np.ascontiguousarray(rgb[pick], dtype=np.uint8)
    sphere = pv.Sphere(radius=1.0, theta_resolution=BALL_RESOLUTION,
                       phi_resolution=BALL_RESOLUTION)
    return centres.glyph(scale="radius", geom=sphere, orient=False)


def new_mesh(kind: str, xyz: np.ndarray) -> pv.DataSet:
    """An empty mesh of the kind's type on the shared (m, 3) points."""
    mesh = pv.UnstructuredGrid() if kind == "tets" else pv.PolyData()
    mesh.points = xyz
    return mesh


class Scene:
    """Layers of one dataset drawn into a pyvista plotter (QtInteractor or off-screen)."""

    def __init__(self, plotter: pv.BasePlotter, render: Callable[[], None] | None = None) -> None:
        """Draw into plotter; render() defaults to plotter.render (QtInteractor: pass update)."""
        self.plotter = plotter
        self.plotter.theme.allow_empty_mesh = True
        self.plotter.set_background(BACKGROUND)
        self.plotter.renderer.SetTwoSidedLighting(True)  # singular triangles face either way
        self._render = render or plotter.render
        self.layers: dict[str, Layer] = {}
        self.styles: dict[str, LayerStyle] = {}
        self.shape = None
        self.dim = 3
        self.frame = Z_UP
        self.overlay = Overlay(plotter)

    @property
    def meshes(self) -> dict[str, pv.DataSet]:
        """Layer name -> its mesh (read the drawn geometry here)."""
        return {name: layer.mesh for name, layer in self.layers.items()}

    def set_dataset(self, xyz: np.ndarray, dim: int, edges: np.ndarray,
                    styles: dict[str, LayerStyle], radii: np.ndarray | None = None,
                    frame: ViewFrame = Z_UP, unit: str | None = None,
                    rgb: np.ndarray | None = None) -> None:
        """New data: (m, 3) points, complex dimension, (e, 2) Delaunay edges, layer styles,
        for weighted points their (m,) radii (the balls layer, when styles has it; `rgb`
        (m, 3) uint8 colours the balls, e.g. atoms by element), the view frame (which way is
        up, app.camera) and the length unit the file declares (or None). A "cavities" style
        adds a layer of cells set by set_cells."""
        self.clear()
        self.dim, self.shape, self.frame = dim, None, frame
        self.overlay.unit = unit
        for name, kind in (KINDS_2D if dim == 2 else KINDS_3D).items():
            self.layers[name] = Layer(kind, new_mesh(kind, xyz))
            self.layers[name].actor = self._add_actor(name, styles[name])
            self.styles[name] = styles[name]
        if radii is not None and "balls" in styles:
            self.layers["balls"] = Layer("balls", ball_mesh(xyz, radii, rgb=rgb))
            self.layers["balls"].actor = self._add_actor("balls", styles["balls"])
            self.styles["balls"] = styles["balls"]
        if "cavities" in styles and dim == 3:
            self.layers["cavities"] = Layer("tets", new_mesh("tets", xyz))
            self.layers["cavities"].actor = self._add_actor("cavities", styles["cavities"])
            self.styles["cavities"] = styles["cavities"]
        self.layers["points"].set_cells(np.arange(len(xyz), dtype=np.int32)[:, None])
        self.layers["delaunay"].set_cells(edges)
        self.overlay.set_layers(self.styles)
        self.fit_view()

    def _add_actor(self, name: str, style: LayerStyle) -> pv.Actor:
        """Add the layer's one actor (only on a new dataset)."""
        layer = self.layers[name]
        source = layer.mesh
        if layer.kind == "tets":
            source = vtkShrinkFilter()
            source.SetInputData(layer.mesh)
            source.SetShrinkFactor(SHRINK_FACTOR)
        coloured = "rgb" in getattr(layer.mesh, "point_data", {})
        actor = self.plotter.add_mesh(
            source, color=None if coloured else style.colour, opacity=style.opacity,
            scalars="rgb" if coloured else None, rgb=coloured, name=name, reset_camera=False,
            lighting=layer.kind in ("tris", "tets", "balls") and (self.dim == 3
                                                                   or layer.kind == "balls"),
            **DRAW_OPTIONS.get(name, {}),
        )
        if name == "singular_highlight":  # drawn over the surface's own triangles
            actor.mapper.SetRelativeCoincidentTopologyPolygonOffsetParameters(-2.0, -2.0)
        actor.SetVisibility(style.visible)
        return actor

    def clear(self) -> None:
        """Remove every layer's actor (only when the dataset changes)."""
        for name in self.layers:
            self.plotter.remove_actor(name, reset_camera=False, render=False)
        self.layers.clear()
        self.styles.clear()

    def set_shape(self, shape) -> None:
        """Show an AlphaShape: swap the connectivity of visible layers, mark hidden ones dirty."""
        self.shape = shape
        self.overlay.set_alpha(shape.alpha)
        for name, layer in self.layers.items():
            if name in STATIC_LAYERS:
                continue
            if self.styles[name].visible:
                layer.set_cells(shape_cells(shape, name))
            else:
                layer.dirty = True

    def set_cells(self, name: str, cells: np.ndarray) -> None:
        """Swap one static layer's cells (the cavities at a new alpha), if it exists."""
        if name in self.layers:
            self.layers[name].set_cells(cells)

    def set_style(self, name: str, style: LayerStyle) -> None:
        """Change one layer's visibility, colour or opacity (no geometry work unless dirty)."""
        if name not in self.layers:
            return
        layer = self.layers[name]
        self.styles[name] = style
        if style.visible and layer.dirty and self.shape is not None:
            layer.set_cells(shape_cells(self.shape, name))
        prop = layer.actor.prop
        prop.color = style.colour
        prop.opacity = style.opacity
        layer.actor.SetVisibility(style.visible)
        self.overlay.set_layers(self.styles)

    def fit_view(self) -> None:
        """Fit the camera to all points: the frame's opening preset in perspective (3D), or
        top-down parallel (2D)."""
        renderer = self.plotter.renderer
        bounds = self.layers["points"].mesh.bounds if self.layers else None
        interactive = getattr(self.plotter, "iren", None) is not None
        if self.dim == 2 and self.is_flat():
            renderer.enable_parallel_projection()
            renderer.view_xy(render=False, bounds=bounds)
            if interactive:
                self.plotter.enable_2d_style()
            renderer.reset_camera(render=False, bounds=bounds)
            return
        renderer.disable_parallel_projection()
        if interactive:
            self.plotter.enable_trackball_style()
        self.view_preset(self.frame.start)

    def view_preset(self, preset: str) -> None:
        """Look at all points from a preset of app.camera.PRESETS (top, front, side, iso),
        centred and fitted; a 2D dataset keeps its top-down view."""
        if not self.layers or (self.dim == 2 and self.is_flat()):
            return
        bounds = self.layers["points"].mesh.bounds
        look, up = self.frame.direction(preset)
        centre = np.array([(bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2,
                           (bounds[4] + bounds[5]) / 2])
        camera = self.plotter.renderer.camera
        camera.focal_point = tuple(centre)
        camera.position = tuple(centre - look)
        camera.up = tuple(up)
        self.plotter.renderer.reset_camera(render=False, bounds=bounds)

    def is_flat(self) -> bool:
        """True when all points lie in the z = 0 plane (2D input)."""
        points = self.layers["points"].mesh.points
        return bool(len(points) == 0 or not np.any(points[:, 2]))

    def render(self) -> None:
        """Request one render."""
        self._render()

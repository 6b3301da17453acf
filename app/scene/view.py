"""The scene: the one owner of the plotter and every VTK object drawn in it, for the window
(app.scene.interactive) and the off-screen screenshot alike.

A new dataset replaces the layers' points once; a new alpha only swaps their connectivity in
place, so a slider step never adds or removes an actor. Hidden layers are not updated until
shown again. Other modules hand the scene numpy arrays (SceneData, shapes) and styles.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
import pyvista as pv
from vtkmodules.vtkFiltersGeneral import vtkShrinkFilter

from app.camera import Z_UP
from app.palette import BACKGROUND, LayerStyle
from app.pockets_layer import PocketArrays
from app.scene.clipping import Clipper
from app.scene.data import SceneData
from app.scene.layers import (
    DRAW_OPTIONS,
    KINDS_2D,
    KINDS_3D,
    SHRINK_FACTOR,
    STATIC_LAYERS,
    Layer,
    ball_actor,
    ball_mesh,
    coloured_cells,
    mark_exposed,
    new_mesh,
    outer_balls,
    shape_cells,
)
from app.scene.overlay import Overlay
from app.scene.painting import Painter
from app.scene.picking import ViewPicker
from app.scene.seen_balls import SeenBalls
from core.storage.atomic import atomic_path

LOD_CELLS = 16_000  # triangles a layer draws at most while the slider is dragged
#: A layer's share of LOD_CELLS by kind: a line or point costs a software renderer about what
#: a triangle does, a tetrahedron four triangles.
LOD_SHARE = {"tris": 1.0, "lines": 0.5, "verts": 0.5, "tets": 0.25}


def thinned(cells: np.ndarray, limit: int | None) -> np.ndarray:
    """At most `limit` of the (k, s) cells, evenly picked (all of them when limit is None)."""
    if limit is None or len(cells) <= limit:
        return cells
    return np.ascontiguousarray(cells[:: -(-len(cells) // limit)])


def drag_style(actor: pv.Actor, options: dict, dragging: bool) -> None:
    """A layer's look while dragging (lines 1 pixel wide, points flat squares: a software
    renderer draws them several times faster) or its full look again (its DRAW_OPTIONS)."""
    prop = actor.GetProperty()
    if "line_width" in options:
        prop.SetLineWidth(1.0 if dragging else options["line_width"])
    if options.get("render_points_as_spheres"):
        prop.SetRenderPointsAsSpheres(not dragging)


class Scene:
    """Layers of one dataset drawn into a pyvista plotter (QtInteractor or off-screen), with
    their overlay, clipping plane (`clipper`) and colour-by mapper state (`painter`)."""

    def __init__(self, plotter: pv.BasePlotter, render: Callable[[], None] | None = None,
                 defer: Callable[[Callable[[], None]], None] | None = None) -> None:
        """Draw into plotter; render() defaults to plotter.render (QtInteractor: pass update);
        defer(task) runs task after the frame (the window's event loop; None: at once), for
        the balls' id pass (app.scene.seen_balls). Made by Scene.off_screen or
        app.scene.interactive.interactive_scene."""
        self.plotter = plotter
        self.plotter.theme.allow_empty_mesh = True
        self.plotter.set_background(BACKGROUND)
        self.plotter.renderer.SetTwoSidedLighting(True)  # singular triangles face either way
        self._render = render or plotter.render
        self.lod_limit = LOD_CELLS  # cells a layer draws while the slider is dragged
        self.lod_cells: int | None = None  # the limit in force (None: the full frame)
        self._smoothing = (self.plotter.render_window.GetMultiSamples(),
                           self.plotter.renderer.GetUseFXAA())  # the full frame's
        self.layers: dict[str, Layer] = {}  # one dict for the scene's life (helpers share it)
        self.styles: dict[str, LayerStyle] = {}
        self.xyz = np.zeros((0, 3))  # the shown dataset's points (SceneData.xyz)
        self.shape = None
        self.dim = 3
        self.frame = Z_UP
        self.overlay = Overlay(plotter)
        self.clipper = Clipper(plotter, self.layers, self.render)
        self.painter = Painter(plotter, self.layers, self.overlay)
        self.seen = SeenBalls(plotter.render_window, plotter.renderer, defer)  # balls shown

    @classmethod
    def off_screen(cls, size: tuple[int, int]) -> Scene:
        """A scene drawing into an off-screen plotter of size (width, height) pixels."""
        return cls(pv.Plotter(off_screen=True, window_size=list(size)))

    @property
    def meshes(self) -> dict[str, pv.DataSet]:
        """Layer name -> its mesh (read the drawn geometry here)."""
        return {name: layer.mesh for name, layer in self.layers.items()}

    def visible_layers(self) -> list[str]:
        """Names of the layers drawn now."""
        return [name for name in self.layers if self.styles[name].visible]

    def set_dataset(self, data: SceneData) -> None:
        """New data (app.scene.data.scene_data): new layers, camera fitted; the only time
        actors are added. A clipping plane that is on stays on, through the new data."""
        self.clear()
        self.dim, self.shape, self.frame = data.dim, None, data.frame
        self.overlay.unit = data.unit
        self.painter.reset()
        styles = data.styles
        for name, kind in (KINDS_2D if data.dim == 2 else KINDS_3D).items():
            self._add_layer(name, Layer(kind, new_mesh(kind, data.xyz)), styles[name])
        if data.radii is not None and "balls" in styles:
            mesh = ball_mesh(data.xyz, data.radii, rgb=data.rgb, exposed=data.exposed)
            self._add_layer("balls", Layer("balls", mesh), styles["balls"])
        if "cavities" in styles and data.dim == 3:
            self._add_layer("cavities", Layer("tets", new_mesh("tets", data.xyz)),
                            styles["cavities"])
        self.xyz = data.xyz
        if data.pockets is not None and data.dim == 3:
            self._add_pockets(data.pockets, styles)
        self.layers["points"].set_cells(np.arange(len(data.xyz), dtype=np.int32)[:, None])
        self.layers["delaunay"].set_cells(data.edges)
        self.overlay.set_layers(self.styles)
        self.fit_view()
        if self.clipper.enabled:
            self.clipper.set_enabled(True)

    def add_pockets(self, pockets: PocketArrays, styles: dict[str, LayerStyle]) -> None:
        """A molecule's pockets and mouths (app.pockets_layer), measured after its first frame:
        the "pockets" and "mouths" layers of `styles` join the shown dataset's (replaced if
        there), clipped and in the legend like the others."""
        if self.dim != 3 or "points" not in self.layers:
            return
        for name in ("pockets", "mouths"):
            if name in self.layers:
                self.plotter.remove_actor(name, reset_camera=False, render=False)
                del self.layers[name], self.styles[name]
        self._add_pockets(pockets, styles)
        self.clipper.apply()
        self.overlay.set_layers(self.styles)

    def _add_pockets(self, pockets: PocketArrays, styles: dict[str, LayerStyle]) -> None:
        """Add the pockets' layers named in styles, in their own colours."""
        for name, kind, cells, rgb in (("pockets", "tets", pockets.cells, pockets.cell_rgb),
                                       ("mouths", "tris", pockets.mouths, pockets.mouth_rgb)):
            if name in styles:
                self._add_layer(name, coloured_cells(kind, self.xyz, cells, rgb), styles[name])

    def _add_layer(self, name: str, layer: Layer, style: LayerStyle) -> None:
        """Keep layer under name and add its one actor (only on a new dataset)."""
        self.layers[name] = layer
        self.styles[name] = style
        layer.actor = self._add_actor(name, style)
        if layer.kind == "balls":
            self._draw_balls(layer, style, self.clipper.enabled)

    def _add_actor(self, name: str, style: LayerStyle) -> pv.Actor:
        """Add the layer's one actor."""
        layer = self.layers[name]
        if layer.kind == "balls":  # sphere impostors: a mapper pyvista's add_mesh cannot make
            actor = ball_actor(layer.mesh, style.colour, style.opacity)
            outer = outer_balls(layer.mesh)
            layer.outer = outer if outer.n_points < layer.mesh.n_points else None
            self.plotter.add_actor(actor, name=name, reset_camera=False, render=False)
            actor.SetVisibility(style.visible)
            return actor
        source = layer.mesh
        if layer.kind == "tets":
            source = vtkShrinkFilter()
            source.SetInputData(layer.mesh)
            source.SetShrinkFactor(SHRINK_FACTOR)
        coloured = "rgb" in getattr(layer.mesh, "point_data", {})
        actor = self.plotter.add_mesh(
            source, color=None if coloured else style.colour, opacity=style.opacity,
            scalars="rgb" if coloured else None, rgb=coloured, name=name, reset_camera=False,
            render=False,  # one render once the dataset is set up, not one per layer
            lighting=layer.kind in ("tris", "tets") and self.dim == 3,
            **DRAW_OPTIONS.get(name, {}),
        )
        if name == "singular_highlight":  # drawn over the surface's own triangles
            actor.mapper.SetRelativeCoincidentTopologyPolygonOffsetParameters(-2.0, -2.0)
        actor.SetVisibility(style.visible)
        return actor

    def set_exposed(self, exposed: np.ndarray) -> None:
        """The balls with area on their union's boundary ((m,) bool), known once a molecule's
        measures arrive after its first frame: only those are drawn while opaque and uncut."""
        layer = self.layers.get("balls")
        if layer is None or layer.actor is None:
            return
        mark_exposed(layer.mesh, exposed)
        outer = outer_balls(layer.mesh)
        layer.outer = outer if outer.n_points < layer.mesh.n_points else None
        self._draw_balls(layer, self.styles["balls"], self.clipper.enabled)

    def _draw_balls(self, layer: Layer, style: LayerStyle, clipped: bool) -> None:
        """While the balls are opaque and uncut, draw only those seen from outside
        (layer.outer), and of those only the ones the view shows (self.seen); all of them
        when translucent or clipped (inner balls show then)."""
        if clipped or style.opacity < 1.0:
            self.seen.track(layer.actor, None)
            mapper = layer.actor.GetMapper()
            if mapper.GetInput() is not layer.mesh:
                mapper.SetInputData(layer.mesh)
            return
        self.seen.track(layer.actor, layer.mesh if layer.outer is None else layer.outer)

    def clear(self) -> None:
        """Remove every layer's actor and forget the shape (only when the dataset changes or
        is released)."""
        for name in self.layers:
            self.plotter.remove_actor(name, reset_camera=False, render=False)
        self.seen.track(None, None)
        self.layers.clear()
        self.styles.clear()
        self.shape = None

    def set_shape(self, shape) -> None:
        """Show an AlphaShape: swap the connectivity of visible layers, mark hidden ones dirty."""
        self.shape = shape
        self.overlay.set_alpha(shape.alpha)
        counts = {}
        for name, layer in self.layers.items():
            if name in STATIC_LAYERS:
                continue
            if self.styles[name].visible:
                cells = shape_cells(shape, name)
                layer.set_cells(thinned(cells, self._limit(layer)))
                counts[name] = len(cells)
            else:
                layer.dirty = True
        self.overlay.set_counts(counts)

    def _limit(self, layer: Layer) -> int | None:
        """Cells the layer draws at most now (None: all of them)."""
        if self.lod_cells is None:
            return None
        return max(1, int(self.lod_cells * LOD_SHARE.get(layer.kind, 1.0)))

    def set_level_of_detail(self, dragging: bool) -> None:
        """While the slider is dragged: at most `lod_limit` cells a layer (its LOD_SHARE of
        them, evenly picked), thin lines, flat points and no anti-aliasing, so frames keep
        up; after it, the full frame (one render)."""
        if dragging == (self.lod_cells is not None):
            return
        window, renderer = self.plotter.render_window, self.plotter.renderer
        if dragging:
            self._smoothing = (window.GetMultiSamples(), renderer.GetUseFXAA())
        samples, fxaa = (0, False) if dragging else self._smoothing
        window.SetMultiSamples(samples)
        renderer.SetUseFXAA(fxaa)
        for name, layer in self.layers.items():
            drag_style(layer.actor, DRAW_OPTIONS.get(name, {}), dragging)
        self.lod_cells = self.lod_limit if dragging else None
        if self.shape is not None:
            self.set_shape(self.shape)
        self.render()

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
            layer.set_cells(thinned(shape_cells(self.shape, name), self._limit(layer)))
        prop = layer.actor.prop
        prop.color = style.colour
        prop.opacity = style.opacity
        layer.actor.SetVisibility(style.visible)
        if layer.kind == "balls":
            self._draw_balls(layer, style, self.clipper.enabled)
        self.overlay.set_layers(self.styles)

    def set_clipping(self, on: bool) -> None:
        """Cut the layers open with the clipping plane (kept for the next dataset)."""
        if "balls" in self.layers:
            self._draw_balls(self.layers["balls"], self.styles["balls"], bool(on))
        self.clipper.set_enabled(on)

    def add_picker(self, on_pick: Callable[[np.ndarray], None],
                   on_escape: Callable[[], None]) -> ViewPicker:
        """Pick the visible layers' cells under a click: on_pick(vertices); Esc: on_escape()."""
        return ViewPicker(self.plotter, self.layers, self.render, on_pick, on_escape)

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

    def save_png(self, path: Path) -> None:
        """Write the view as a PNG image to path, atomically (core.storage.atomic), whatever path's
        extension."""
        from PIL import Image

        with atomic_path(path) as tmp:
            Image.fromarray(self.plotter.screenshot(return_img=True)).save(tmp, format="PNG")

    def close(self) -> None:
        """Release the plotter and its render window (before Qt goes), and the balls' id
        pass."""
        self.seen.close()
        self.plotter.close()

"""The balls a still view shows: one flat pass draws every ball in a colour of its own (its
id) into an off-screen window of the view's size and camera; the ids found in its pixels are
the balls that win a pixel among the balls. While the view stays, only those are drawn: the
same picture, since a ball that wins no pixel among the balls wins none among more layers,
and the balls kept are drawn in the same order (ties fall as before).

On a software renderer the balls' cost is the fragments shaded, every overlapping ball's:
a molecule's outer balls are several times more than those a view shows (those behind
others). The id pass costs about one frame of all the balls, once per view; a frame of a
still view (a slider step) draws the seen ones only. In the window the pass runs once the
new view's frame (every ball) is painted, so that frame comes as soon as before.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pyvista as pv
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkRenderingCore import (
    vtkCamera,
    vtkRenderer,
    vtkRenderWindow,
    vtkWindowToImageFilter,
)

from app.scene.layers import BALL_ORIGIN, ball_mapper

#: The id pass's shading in place of the balls' light: the ball's own colour (its id) as
#: it is, so the pixels read back are ids (diffuse 1, ambient 0, no light).
ID_SHADE = "  gl_FragData[0] = vec4(diffuseColor, 1.0);\n"


def id_colours(count: int) -> np.ndarray:
    """(count, 3) uint8: ball i's colour in the id pass, i + 1 in 24 bits (0 is no ball)."""
    code = np.arange(1, count + 1, dtype=np.int64)
    return np.stack([code & 255, (code >> 8) & 255, (code >> 16) & 255], axis=1).astype(np.uint8)


def seen_ids(pixels: np.ndarray, count: int) -> np.ndarray:
    """(count,) bool: the balls whose id colour (id_colours) is in the (..., 3+) uint8
    pixels of an id pass."""
    rgb = np.asarray(pixels, dtype=np.int64).reshape(-1, pixels.shape[-1])[:, :3]
    code = rgb[:, 0] | (rgb[:, 1] << 8) | (rgb[:, 2] << 16)
    code = code[(code > 0) & (code <= count)]
    return np.bincount(code - 1, minlength=count).astype(bool)


def ball_subset(mesh: pv.PolyData, keep: np.ndarray) -> pv.PolyData:
    """The balls of a ball mesh (app.scene.layers.ball_mesh) where (n,) bool keep is True, in
    the same order, with their point data and the mesh's origin."""
    subset = pv.PolyData(np.asarray(mesh.points)[keep])
    for name in mesh.point_data.keys():
        subset[name] = np.asarray(mesh.point_data[name])[keep]
    subset.field_data[BALL_ORIGIN] = mesh.field_data[BALL_ORIGIN]
    return subset


def view_key(renderer: vtkRenderer) -> tuple:
    """What the pixels a renderer draws depend on, of its camera and size: the camera's
    world-to-screen matrix at the renderer's aspect, and the renderer's size in pixels."""
    aspect = renderer.GetTiledAspectRatio()
    matrix = renderer.GetActiveCamera().GetCompositeProjectionTransformMatrix(aspect, -1, 1)
    return (tuple(matrix.GetElement(i, j) for i in range(4) for j in range(4)),
            tuple(renderer.GetSize()))


class IdPass:
    """An off-screen window drawing balls flat in their id colours, read back as pixels."""

    def __init__(self) -> None:
        """A single-sampled off-screen window on a black background (made on first use)."""
        self.window = vtkRenderWindow()
        self.window.SetOffScreenRendering(True)
        self.window.SetMultiSamples(0)
        self.renderer = vtkRenderer()
        self.renderer.SetBackground(0.0, 0.0, 0.0)
        self.window.AddRenderer(self.renderer)
        self.camera = vtkCamera()
        self.renderer.SetActiveCamera(self.camera)
        self.actor = pv.Actor()
        self.actor.GetShaderProperty().AddFragmentShaderReplacement(
            "//VTK::Light::Impl", True, ID_SHADE, False)
        self.actor.prop.ambient = 0.0
        self.actor.prop.diffuse = 1.0
        self.renderer.AddActor(self.actor)
        self.balls: pv.PolyData | None = None
        self.grab = vtkWindowToImageFilter()
        self.grab.SetInput(self.window)
        self.grab.SetInputBufferTypeToRGB()
        self.grab.ReadFrontBufferOff()
        self.grab.ShouldRerenderOff()
        self.usable = bool(self.window.SupportsOpenGL())  # else every ball is drawn

    def set_balls(self, mesh: pv.PolyData) -> None:
        """Draw mesh's balls (a ball mesh), each in its id colour."""
        self.balls = mesh
        ids = pv.PolyData(np.asarray(mesh.points))
        ids["radius"] = np.asarray(mesh["radius"])
        ids["rgb"] = id_colours(mesh.n_points)
        mapper = ball_mapper(ids)
        mapper.SetScalarModeToUsePointFieldData()
        mapper.SelectColorArray("rgb")
        mapper.SetColorModeToDirectScalars()
        mapper.SetScalarVisibility(True)
        self.actor.SetMapper(mapper)
        self.actor.SetPosition(*np.asarray(mesh.field_data[BALL_ORIGIN], dtype=np.float64))

    def seen(self, renderer: vtkRenderer, balls: pv.PolyData) -> np.ndarray:
        """(n,) bool: which of the n balls of a ball mesh win a pixel among them with
        renderer's camera and size."""
        if balls is not self.balls:
            self.set_balls(balls)
        width, height = renderer.GetSize()
        self.window.SetSize(max(width, 1), max(height, 1))
        self.camera.DeepCopy(renderer.GetActiveCamera())
        self.window.Render()
        self.grab.Modified()
        self.grab.Update()
        pixels = vtk_to_numpy(self.grab.GetOutput().GetPointData().GetScalars())
        return seen_ids(pixels, balls.n_points)

    def close(self) -> None:
        """Release the window and its context."""
        self.renderer.RemoveAllViewProps()
        self.window.Finalize()


class SeenBalls:
    """Draws a ball actor's balls as only those its view shows, checked before every render
    of the window: a new view (camera or size) draws them all while the view moves (an
    interaction in progress) and finds the seen ones again once it is still: at once, or
    when `defer` (a call later, after the frame: the window's event loop) runs it, the new
    view's frame drawing them all. A multisampled window draws them all (the id pass has
    one sample a pixel), and so does a machine where the id pass gets no OpenGL context."""

    def __init__(self, window: vtkRenderWindow, renderer: vtkRenderer,
                 defer: Callable[[Callable[[], None]], None] | None = None) -> None:
        """Watch window's renders of renderer's view; defer(task) runs task later (None:
        the id pass runs in the render that needs it)."""
        self.window: vtkRenderWindow | None = window
        self.renderer: vtkRenderer | None = renderer
        self.actor: pv.Actor | None = None
        self.balls: pv.PolyData | None = None  # every ball that may show (None: not culling)
        self.subset: pv.PolyData | None = None  # those the view `key` shows
        self.key: tuple | None = None
        self._pass: IdPass | None = None
        self.defer = defer
        self._pending = False  # a deferred id pass is waiting
        self._observer = window.AddObserver("StartEvent", self._before_render)

    def track(self, actor: pv.Actor | None, balls: pv.PolyData | None) -> None:
        """Draw actor's balls as the seen ones of `balls` (a ball mesh); None: leave actor's
        input alone (the caller draws them all: clipped or translucent)."""
        if balls is not self.balls or actor is not self.actor:
            self.key, self.subset = None, None
        self.actor, self.balls = actor, balls
        if actor is not None and balls is not None:
            drawn = actor.GetMapper().GetInput()
            if drawn is not balls and drawn is not self.subset:  # identity, not pyvista's ==
                self._set_input(balls)

    def forget_view(self) -> None:
        """Find the seen balls again at the next still render, as after a moved camera."""
        self.key = None

    def _id_pass(self) -> IdPass:
        """The id pass (made on first use)."""
        if self._pass is None:
            self._pass = IdPass()
        return self._pass

    def interacting(self) -> bool:
        """True while an interactor style moves the view (it raises the window's desired
        update rate above the still rate for as long as it does)."""
        interactor = self.window.GetInteractor()
        return (interactor is not None
                and self.window.GetDesiredUpdateRate() > interactor.GetStillUpdateRate())

    def still(self) -> bool:
        """True when the id pass can tell the balls this view shows: one sample a pixel,
        no interaction moving the view, an OpenGL context for the pass."""
        return (self.window.GetMultiSamples() == 0 and not self.interacting()
                and self._id_pass().usable)

    def _before_render(self, *_) -> None:
        """Before a render: the seen balls of the view when it is still and known (found now
        when new, or later with defer), else every ball."""
        if self.balls is None or self.actor is None or not self.actor.GetVisibility():
            return
        source = self.balls
        if self.still():
            key = view_key(self.renderer)
            if key != self.key and self.defer is None:
                self._find(key)
            elif key != self.key and not self._pending:
                self._pending = True
                self.defer(self._find_later)
            if key == self.key:
                source = self.subset
        self._set_input(source)

    def _find(self, key: tuple) -> None:
        """Find the balls the view `key` (the renderer's now) shows."""
        keep = self._id_pass().seen(self.renderer, self.balls)
        keep |= np.asarray(self.balls["radius"]) == 0  # the box's corners: the bounds
        self.subset, self.key = ball_subset(self.balls, keep), key

    def _find_later(self) -> None:
        """The deferred id pass: the balls the view shows now, for the frames that follow
        (the frame on screen, of every ball, is the same picture)."""
        self._pending = False
        if (self.window is None or self.balls is None or self.actor is None
                or not self.actor.GetVisibility() or not self.still()):
            return
        key = view_key(self.renderer)
        if key != self.key:
            self._find(key)
        self._set_input(self.subset)  # for the next frame

    def _set_input(self, source: pv.PolyData) -> None:
        """Draw source with the tracked actor (no change when it draws it already)."""
        mapper = self.actor.GetMapper()
        if mapper.GetInput() is not source:
            mapper.SetInputData(source)

    def close(self) -> None:
        """Stop watching the window and release the id pass."""
        if self.window is not None:
            self.window.RemoveObserver(self._observer)
        if self._pass is not None:
            self._pass.close()
        self._pass = self.window = self.renderer = None
        self.actor = self.balls = self.subset = None

"""The scene's layers: one persistent mesh per drawn layer, its kind, and the arrays it draws.

A new alpha only swaps a layer's connectivity in place (zero-copy numpy -> vtkCellArray).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pyvista as pv
from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLSphereMapper

from app.palette import MAX_BALLS

SHRINK_FACTOR = 0.8
KINDS_3D = {
    "delaunay": "lines", "points": "verts", "interior": "tets", "surface": "tris",
    "singular_highlight": "tris", "singular_edges": "lines", "singular_points": "verts",
}
KINDS_2D = {
    "delaunay": "lines", "points": "verts", "interior": "tris", "boundary": "lines",
    "singular_edges": "lines", "singular_points": "verts",
}
STATIC_LAYERS = ("points", "delaunay", "balls", "cavities", "pockets", "mouths")
BALL_ORIGIN = "origin"  # field data of a ball mesh: where its float32 centres are measured from
EXPOSED = "exposed"  # point data of a ball mesh: 1 where the ball has area on the union's boundary
BALL_ROWS = "rows"  # field data of a ball mesh: the rows of the points its balls are drawn at
#: The balls' shading in the impostor's fragment shader, in place of VTK's lights: one light
#: at the eye (a sphere's normal faces it at its centre) over a dim floor, so rims stay apart.
#: A software renderer shades every covered fragment of every overlapping ball; the
#: renderer's five-light kit cost about half of that.
BALL_LIGHT = """
  float facing = max(0.0, normalVCVSOutput.z);
  gl_FragData[0] = vec4(ambientColor + diffuseColor * (0.15 + 0.85 * facing), opacity);
"""
DRAW_OPTIONS = {
    "points": {"point_size": 3.0},
    "singular_points": {"point_size": 5.0, "render_points_as_spheres": True},
    "singular_edges": {"line_width": 3.0},
    "boundary": {"line_width": 2.0},
    "delaunay": {"line_width": 1.0},
}


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
    outer: pv.PolyData | None = None  # balls: those seen from outside (outer_balls), if fewer

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
              rgb: np.ndarray | None = None, exposed: np.ndarray | None = None) -> pv.PolyData:
    """The centres of balls of the given (m,) radii around at most `limit` of the (m, 3)
    points (evenly picked, so a big set still shows its spread), one vertex each, with a
    float32 "radius" array; `rgb` (m, 3) uint8 colours them (point data "rgb"); `exposed`
    (m,) bool marks the balls with some area on the union's boundary (point data
    "exposed", all True when not given: outer_balls draws only these).

    The balls are drawn as sphere impostors (ball_mapper): one point each, not a mesh. The
    centres are float32 (what the impostor mapper reads) measured from the field data's
    "origin" (the actor's position), so far-off coordinates keep their precision; two more
    points of radius 0 mark the corners of the balls' box (the view's bounds)."""
    pick = np.unique(np.linspace(0, len(xyz) - 1, min(limit, len(xyz))).round().astype(np.int64))
    centres = np.asarray(xyz, dtype=np.float64).reshape(-1, 3)[pick]
    radius = np.asarray(radii, dtype=np.float64)[pick]
    origin = centres.mean(axis=0) if len(centres) else np.zeros(3)
    # two balls of radius 0 (drawn as nothing) at the corners of the balls' box: the mapper's
    # bounds are its points', and the camera's clipping range must hold the whole balls
    corners = (np.array([(centres - radius[:, None]).min(axis=0),
                         (centres + radius[:, None]).max(axis=0)]) if len(centres)
               else np.zeros((0, 3)))
    mesh = pv.PolyData((np.concatenate([centres, corners]) - origin).astype(np.float32))
    mesh["radius"] = np.concatenate([radius, np.zeros(len(corners))]).astype(np.float32)
    if rgb is not None:
        colours = np.asarray(rgb, dtype=np.uint8)[pick]
        mesh["rgb"] = np.concatenate([colours, np.zeros((len(corners), 3), np.uint8)])
    mesh.field_data[BALL_ORIGIN] = origin
    mesh.field_data[BALL_ROWS] = pick
    mark_exposed(mesh, exposed)
    return mesh


def mark_exposed(mesh: pv.PolyData, exposed: np.ndarray | None) -> None:
    """Set a ball_mesh's "exposed" marks from (m,) bool `exposed` over all the points (None:
    every ball; the box corners always). A mesh thinned to fewer than the m balls marks every
    ball: a buried ball's cover may be among those left out, and then it shows."""
    pick = np.asarray(mesh.field_data[BALL_ROWS], dtype=np.int64)
    whole = exposed is not None and len(pick) == len(exposed)
    shown = np.asarray(exposed, bool)[pick] if whole else np.ones(len(pick), bool)
    corners = mesh.n_points - len(pick)
    mesh[EXPOSED] = np.concatenate([shown, np.ones(corners, bool)]).astype(np.uint8)


def outer_balls(mesh: pv.PolyData) -> pv.PolyData:
    """The balls of a ball_mesh that show from outside when all are drawn opaque and uncut:
    those with exposed area (a ball inside the union of the others is covered wherever it
    is seen from), with the box corners, in the same order and float32 values (the same
    picture, fewer fragments to shade)."""
    keep = np.asarray(mesh[EXPOSED], dtype=bool)
    outer = pv.PolyData(np.asarray(mesh.points)[keep])
    for name in mesh.point_data.keys():
        outer[name] = np.asarray(mesh.point_data[name])[keep]
    outer.field_data[BALL_ORIGIN] = mesh.field_data[BALL_ORIGIN]
    return outer


def ball_mapper(mesh: pv.PolyData) -> vtkOpenGLSphereMapper:
    """A mapper drawing each point of a ball_mesh as a lit sphere of its "radius" (data
    units): a screen-aligned impostor per ball, depth-correct where balls intersect, at the
    cost of a few points instead of ~160 triangles a ball."""
    mapper = vtkOpenGLSphereMapper()
    mapper.SetInputData(mesh)
    mapper.SetScaleArray("radius")
    mapper.SetScalarVisibility(False)
    return mapper


def shade_balls(actor: pv.Actor) -> None:
    """Light the balls with BALL_LIGHT (a replacement of the impostor shader's lighting)."""
    actor.GetShaderProperty().AddFragmentShaderReplacement("//VTK::Light::Impl", True,
                                                           BALL_LIGHT, False)


def ball_actor(mesh: pv.PolyData, colour: str, opacity: float) -> pv.Actor:
    """The balls' actor: ball_mapper at the mesh's origin, in its own "rgb" colours when it
    has them (atoms by element), else in colour."""
    mapper = ball_mapper(mesh)
    if "rgb" in mesh.point_data:
        mapper.SetScalarModeToUsePointFieldData()
        mapper.SelectColorArray("rgb")
        mapper.SetColorModeToDirectScalars()
        mapper.SetScalarVisibility(True)
    actor = pv.Actor(mapper=mapper)
    shade_balls(actor)
    actor.SetPosition(*np.asarray(mesh.field_data[BALL_ORIGIN], dtype=np.float64))
    actor.prop.color = colour
    actor.prop.opacity = opacity
    return actor


def coloured_cells(kind: str, xyz: np.ndarray, cells: np.ndarray, rgb: np.ndarray) -> Layer:
    """A layer of fixed cells, each in its own colour (cell data "rgb", (k, 3) uint8; none
    without cells: pyvista refuses an empty array, and a molecule may have no pockets)."""
    layer = Layer(kind, new_mesh(kind, xyz))
    layer.set_cells(cells)
    if len(cells):
        layer.mesh.cell_data["rgb"] = np.ascontiguousarray(rgb, dtype=np.uint8)
    return layer


def new_mesh(kind: str, xyz: np.ndarray) -> pv.DataSet:
    """An empty mesh of the kind's type on the shared (m, 3) points."""
    mesh = pv.UnstructuredGrid() if kind == "tets" else pv.PolyData()
    mesh.points = xyz
    return mesh

"""One palette for the whole app: simplex classes, layers, background (view, legend, plots)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

BACKGROUND = "#1f2a36"
TEXT = "#e8f1fb"

CLASS_COLOURS = {
    "exterior": "#8c96a0",
    "singular": "#e4572e",
    "regular": "#4c9be8",
    "interior": "#59b86a",
}

#: Tick marks on the alpha slider.
MARK_COLOURS = {"suggested": "#c9d1d9", "opening": "#4c9be8", "optimal": "#59b86a"}


@dataclass(frozen=True)
class LayerStyle:
    """How a layer is drawn: shown or not, colour '#rrggbb', opacity 0..1."""

    visible: bool
    colour: str
    opacity: float


LAYER_TITLES = {
    "surface": "Surface",
    "singular_highlight": "Singular triangles (highlight)",
    "boundary": "Boundary (regular)",
    "interior": "Interior cells",
    "singular_edges": "Singular edges",
    "singular_points": "Singular points",
    "points": "Points",
    "delaunay": "Delaunay edges",
    "balls": "Points as balls (own radius; at most 20,000 drawn)",
    "cavities": "Cavities (voids at this alpha)",
    "pockets": "Pockets (at alpha² 0, one colour each; click one)",
    "mouths": "Pocket mouths",
}

#: CPK colours of atoms by atomic number (Jmol's scheme); other elements are pink.
CPK_COLOURS = {1: "#ffffff", 6: "#909090", 7: "#3050f8", 8: "#ff0d0d", 9: "#90e050",
               11: "#ab5cf2", 12: "#8aff00", 15: "#ff8000", 16: "#ffff30", 17: "#1ff01f",
               20: "#3dff00", 26: "#e06633", 30: "#7d80b0", 34: "#ffa100", 35: "#a62929"}
CPK_OTHER = "#ff1493"
#: Molecules: the cavities (voids of the complex) at the current alpha, and the atoms shown.
CAVITY_STYLE = LayerStyle(True, "#f3a712", 0.9)
ATOM_STYLE = LayerStyle(True, "#8fb8de", 1.0)
#: Molecules: the pockets (each in its own colour, app.pockets_layer) and their mouths.
POCKET_STYLE = LayerStyle(True, "#4e79a7", 0.9)
MOUTH_STYLE = LayerStyle(True, "#ffffff", 0.6)


def cpk_rgb(atomic_numbers: np.ndarray) -> np.ndarray:
    """(n, 3) uint8 CPK colours of atoms given their (n,) atomic numbers."""
    table = np.full((256, 3), [int(CPK_OTHER[i:i + 2], 16) for i in (1, 3, 5)], np.uint8)
    for z, colour in CPK_COLOURS.items():
        table[z] = [int(colour[i:i + 2], 16) for i in (1, 3, 5)]
    return table[np.clip(np.asarray(atomic_numbers, np.int64), 0, 255)]


#: Weighted points drawn as balls of their own radius: at most this many (evenly picked).
MAX_BALLS = 20_000
BALL_STYLE = LayerStyle(False, "#8fb8de", 0.5)

#: Singular edges (sticks) and singular points (lone points) in colours of their own, in 2D
#: and 3D: a sparse scan's dust is named by the legend, not mistaken for the surface.
SINGULAR_EDGE_COLOUR, SINGULAR_POINT_COLOUR = "#f3a712", "#d65ac8"

#: 3D: the surface, and its lower-dimensional parts (dangling edges, lone points) each in
#: their own colour; singular triangles are a highlight to switch on.
DEFAULT_STYLES = {
    "surface": LayerStyle(True, CLASS_COLOURS["regular"], 1.0),
    "singular_highlight": LayerStyle(False, CLASS_COLOURS["singular"], 1.0),
    "interior": LayerStyle(False, CLASS_COLOURS["interior"], 0.35),
    "singular_edges": LayerStyle(True, SINGULAR_EDGE_COLOUR, 1.0),
    "singular_points": LayerStyle(True, SINGULAR_POINT_COLOUR, 1.0),
    "points": LayerStyle(False, "#c9d1d9", 1.0),
    "delaunay": LayerStyle(False, "#9aa5b1", 0.15),
}

#: In 2D the triangles are the cells and never singular: the boundary is the regular edges,
#: and singular edges and points (sticks and lone points) stand out in their own colours.
DEFAULT_STYLES_2D = {
    "boundary": LayerStyle(True, CLASS_COLOURS["regular"], 1.0),
    "interior": LayerStyle(True, CLASS_COLOURS["interior"], 0.6),
    "singular_edges": LayerStyle(True, SINGULAR_EDGE_COLOUR, 1.0),
    "singular_points": LayerStyle(True, SINGULAR_POINT_COLOUR, 1.0),
    "points": DEFAULT_STYLES["points"],
    "delaunay": DEFAULT_STYLES["delaunay"],
}


def default_styles(dim: int, weighted: bool = False) -> dict[str, LayerStyle]:
    """Layer styles a new dataset of dimension dim (2 or 3) starts with: one per drawn layer
    (weighted points add the balls layer)."""
    styles = dict(DEFAULT_STYLES_2D if dim == 2 else DEFAULT_STYLES)
    if weighted:
        styles["balls"] = BALL_STYLE
    return styles

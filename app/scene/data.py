"""What the scene draws of a dataset, as plain arrays: one function for the window and the
off-screen screenshot alike (no VTK here)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from app.camera import Z_UP, ViewFrame
from app.dataset import Dataset
from app.palette import LayerStyle
from app.pockets_layer import PocketArrays, pocket_arrays
from core.molecule.measures import exposed_balls


def as_xyz(points: np.ndarray) -> np.ndarray:
    """(m, 3) float64 copy of (m, 2) or (m, 3) points (2D gets z = 0)."""
    points = np.asarray(points, dtype=np.float64)
    if points.shape[1] == 3:
        return np.ascontiguousarray(points)
    return np.column_stack([points, np.zeros(len(points))])


@dataclass(frozen=True)
class SceneData:
    """A dataset as the scene takes it: (m, 3) float64 points `xyz`, the complex dimension,
    (e, 2) Delaunay `edges`, the layer `styles`, for weighted points their (m,) `radii` (the
    balls layer, when styles has it) and (m, 3) uint8 `rgb` ball colours (atoms by element;
    else None), (m,) bool `exposed`: the balls with area on the boundary of their union (a
    molecule's exact per-atom areas at the drawn radii; None: unknown, all drawn), the view
    `frame` (which way is up, app.camera) and the length `unit` the file declares (or None).
    A "cavities" style adds a layer of cells set by Scene.set_cells; `pockets` (a
    molecule's, app.pockets_layer) the "pockets" and "mouths" layers."""

    xyz: np.ndarray
    dim: int
    edges: np.ndarray
    styles: dict[str, LayerStyle]
    radii: np.ndarray | None = None
    rgb: np.ndarray | None = None
    frame: ViewFrame = Z_UP
    unit: str | None = None
    pockets: PocketArrays | None = None
    exposed: np.ndarray | None = None


def scene_data(dataset: Dataset, styles: dict[str, LayerStyle],
               rgb: np.ndarray | None = None) -> SceneData:
    """The arrays the scene draws of dataset, with these layer styles (and ball colours)."""
    ac = dataset.ac
    return SceneData(as_xyz(ac.to_ambient(ac.points)), ac.dim, ac.simplices(1), styles,
                     ball_radii(dataset), rgb, dataset.frame, dataset.unit,
                     pockets_of(dataset), exposed_of(dataset))


def ball_radii(dataset: Dataset) -> np.ndarray | None:
    """(m,) radii of the balls drawn for weighted points (sqrt of the weights), else None."""
    weights = dataset.ac.weights
    return None if weights is None else np.sqrt(np.maximum(weights, 0.0))


def pockets_of(dataset: Dataset) -> PocketArrays | None:
    """The drawn arrays of a molecule's pockets and mouths (app.pockets_layer); None while
    its measures are unknown, and for other point sets."""
    molecule = dataset.molecule
    return None if molecule is None else pocket_arrays(dataset.ac, molecule.pockets)


def exposed_of(dataset: Dataset) -> np.ndarray | None:
    """(m,) bool: the drawn balls with area on their union's boundary, from a molecule's
    measures (at alpha² 0 they are of the balls drawn); None while unknown."""
    molecule = dataset.molecule
    if molecule is None or molecule.alpha2 != 0:
        return None
    return exposed_balls(molecule.point_area, ball_radii(dataset))

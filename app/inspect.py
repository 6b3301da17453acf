"""What a picked simplex is (no Qt, no VTK): its table row, vertices, intervals, class at alpha.

The view hands over the vertices of the cell it picked; the row is looked up in the table, so
the mapping does not depend on how the layers are made up.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.query.classes import CLASSES
from core.query.spheres import find_simplex, simplex_sphere

KIND_NAMES = ("point", "edge", "triangle", "tetrahedron")


@dataclass(frozen=True)
class Inspection:
    """One simplex of the table: dimension k, its row in simplices(k), its (k+1,) int vertices,
    their (k+1, ambient_dim) float64 input coordinates, and (3,) enter/regular/interior alphas."""

    k: int
    row: int
    vertices: np.ndarray
    coords: np.ndarray
    intervals: np.ndarray
    dim: int

    @property
    def kind(self) -> str:
        """'point', 'edge', 'triangle' or 'tetrahedron' (in 2D a triangle is a cell)."""
        return KIND_NAMES[self.k]

    def class_index(self, alpha: float) -> int:
        """0 exterior, 1 singular, 2 regular, 3 interior at alpha (ac.classify's rule)."""
        return int(np.count_nonzero(self.intervals <= alpha))

    def class_name(self, alpha: float) -> str:
        """The class at alpha, by name (core.query.classes.CLASSES)."""
        return CLASSES[self.class_index(alpha)]


def inspect(ac, vertices: object) -> Inspection:
    """The Inspection of the simplex of ac with these point indices (InputError if none)."""
    k, row = find_simplex(ac, vertices)
    verts = np.array(ac.simplices(k)[row], dtype=np.int64)
    return Inspection(k=k, row=row, vertices=verts, coords=ac.to_ambient(ac.points[verts]),
                      intervals=np.array(ac.intervals(k)[row], dtype=np.float64), dim=ac.dim)


def spoon(ac, item: Inspection) -> tuple[np.ndarray, float]:
    """Centre (ambient_dim,) and radius of the item's smallest empty sphere."""
    return simplex_sphere(ac, item.k, item.row)


def alpha_text(value: float) -> str:
    """An alpha as 'r 0.0123 (r² 0.000151)', or '∞ (never)'."""
    if not np.isfinite(value):
        return "∞ (never)"
    return f"r {value:.6g} (r² {value * abs(value):.6g})"  # signed: weighted values < 0

"""Exact area and volume of a union of balls from its dual complex (short inclusion–exclusion).

Edelsbrunner ("The union of balls and its dual shape", Discrete Comput. Geom. 13, 1995): for
the dual complex K of the balls (the weighted alpha complex at alpha² = 0),
vol(∪B) = Σ_{σ ∈ K} (-1)^dim σ vol(∩_{i ∈ σ} B_i); the exposed area of sphere i follows
the same sum over the simplices of K that contain i (it is ∂vol/∂r_i).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.arrays import readonly
from core.molecule.intersections import four_balls, three_balls, two_balls
from core.parallel import together
from core.tolerances import EXPOSED_AREA_RTOL

CHUNK = 100_000  # simplices per vectorized batch (bounds the temporary arrays)
TERMS = {2: two_balls, 3: three_balls, 4: four_balls}


@dataclass(frozen=True, eq=False)
class UnionMeasures:
    """Area and volume of a union of balls; atom_area (n,) float64 exposed area per ball."""

    area: float
    volume: float
    atom_area: np.ndarray


def _terms(centres: np.ndarray, radii: np.ndarray, simplices: np.ndarray, n: int):
    """(Σ volumes, per-ball Σ areas (n,)) of the intersections of the simplices' balls."""
    volume, areas = 0.0, np.zeros(n)
    if simplices.size == 0:
        return volume, areas
    simplices = np.asarray(simplices, dtype=np.int64).reshape(-1, simplices.shape[-1])
    for start in range(0, len(simplices), CHUNK):
        rows = simplices[start:start + CHUNK]
        c = centres[rows]
        c = c - c[:, :1]  # relative to the first centre: no digits lost to large coordinates
        vol, area = TERMS[rows.shape[1]](c, radii[rows])
        volume += float(vol.sum())
        areas += np.bincount(rows.ravel(), weights=area.ravel(), minlength=n)
    return volume, areas


def union_measures(centres: np.ndarray, radii: np.ndarray, edges: np.ndarray,
                   triangles: np.ndarray, tetrahedra: np.ndarray,
                   vertices: np.ndarray | None = None) -> UnionMeasures:
    """Exact area and volume of the union of balls (centres (n, 3), radii (n,)).

    edges (., 2), triangles (., 3), tetrahedra (., 4) int: the dual complex's simplices as
    rows of `centres`; `vertices` the balls in it (default all; a ball hidden inside others
    is not). Per-ball exposed areas are clipped at 0 against rounding.
    """
    centres = np.asarray(centres, dtype=np.float64)
    radii = np.asarray(radii, dtype=np.float64)
    n = len(radii)
    present = np.ones(n, bool) if vertices is None else np.isin(np.arange(n), vertices)
    volume = float((4.0 / 3.0 * np.pi * radii[present] ** 3).sum())
    atom_area = np.where(present, 4.0 * np.pi * radii ** 2, 0.0)
    # the tetrahedra (about half the work) in a helper thread: numpy releases the GIL
    tets = together(lambda: _terms(centres, radii, np.asarray(tetrahedra), n))
    for sign, simplices in ((-1, edges), (1, triangles)):
        vol, areas = _terms(centres, radii, np.asarray(simplices), n)
        volume += sign * vol
        atom_area += sign * areas
    vol, areas = tets()
    volume -= vol
    atom_area -= areas
    atom_area = readonly(np.maximum(atom_area, 0.0))
    return UnionMeasures(float(atom_area.sum()), volume, atom_area)


def exposed_balls(atom_area: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """(n,) bool: the balls of (n,) radii whose (n,) exposed areas (UnionMeasures.atom_area)
    are more than the rounding of their sum (EXPOSED_AREA_RTOL of the sphere's area); the
    others lie inside the union of the rest."""
    sphere = 4.0 * np.pi * np.asarray(radii, dtype=np.float64) ** 2
    return np.asarray(atom_area, dtype=np.float64) > EXPOSED_AREA_RTOL * sphere

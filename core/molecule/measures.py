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
from core.geometry.power import signed_square
from core.molecule.intersections import ball_terms
from core.tolerances import EXPOSED_AREA_RTOL

#: Simplices per vectorized batch: each batch's many (3, m) temporaries stay in the caches
#: (rowwise, so a batch's size never changes a value).
CHUNK = 1 << 13


@dataclass(frozen=True, eq=False)
class UnionMeasures:
    """Area and volume of a union of balls; atom_area (n,) float64 exposed area per ball."""

    area: float
    volume: float
    atom_area: np.ndarray


def _terms(planes: np.ndarray, radii: np.ndarray, simplices: np.ndarray, n: int):
    """(Σ volumes, per-ball Σ areas (n,)) of the intersections of the simplices' balls, from
    the centres' (3, n) coordinate planes. Each batch gathers its corners straight into the
    component-major layout the formulas use and fills its rows; the sums are taken once
    over all rows (one bincount, and a total that does not depend on the batch size)."""
    if simplices.size == 0:
        return 0.0, np.zeros(n)
    corners = np.ascontiguousarray(np.asarray(simplices).reshape(-1, simplices.shape[-1]).T)
    k, count = corners.shape
    volumes = np.empty(count)
    areas = np.empty((k, count))
    for start in range(0, count, CHUNK):
        rows = corners[:, start:start + CHUNK]
        c = np.take(planes, rows, axis=1).transpose(1, 0, 2)  # (k, 3, m)
        c = c - c[:1]  # relative to the first centre: no digits lost to large coordinates
        volumes[start:start + CHUNK], areas[:, start:start + CHUNK] = ball_terms(
            c, np.take(radii, rows))
    return float(volumes.sum()), np.bincount(corners.ravel(), weights=areas.ravel(),
                                             minlength=n)


def in_complex(ac, k: int, alpha2: float = 0.0) -> np.ndarray:
    """(n_k,) bool: the k-simplices of a weighted AlphaComplex `ac` in its complex at alpha²
    (squared enter <= alpha2), from the enter column alone (no (n_k, 3) intervals stacked)."""
    return signed_square(ac.index.level(k).enter) <= alpha2


def dual_simplices(ac, alpha2: float = 0.0) -> list[np.ndarray]:
    """The vertices (., 1), edges, triangles and tetrahedra of a weighted 3D AlphaComplex
    `ac` in its complex at alpha² (the dual complex of its balls at 0). The levels k >= 1 are
    sorted by enter, so theirs are prefixes of ac.simplices(k), handed out as views."""
    out = [ac.simplices(0)[in_complex(ac, 0, alpha2)]]
    for k in range(1, 4):
        out.append(ac.simplices(k)[:int(np.count_nonzero(in_complex(ac, k, alpha2)))])
    return out


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
    present = np.full(n, vertices is None)
    if vertices is not None:
        present[np.asarray(vertices)] = True  # a scatter: no sorted search as np.isin's
    volume = float((4.0 / 3.0 * np.pi * radii[present] ** 3).sum())
    atom_area = np.where(present, 4.0 * np.pi * radii ** 2, 0.0)
    # in this thread: the batches are many short numpy passes, so a helper thread running
    # the tetrahedra beside them mostly waits for the GIL (no faster, more CPU)
    planes = np.ascontiguousarray(centres.T)
    for sign, simplices in ((-1, edges), (1, triangles), (-1, tetrahedra)):
        vol, areas = _terms(planes, radii, np.asarray(simplices), n)
        volume += sign * vol
        atom_area += sign * areas
    atom_area = readonly(np.maximum(atom_area, 0.0))
    return UnionMeasures(float(atom_area.sum()), volume, atom_area)


def exposed_balls(atom_area: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """(n,) bool: the balls of (n,) radii whose (n,) exposed areas (UnionMeasures.atom_area)
    are more than the rounding of their sum (EXPOSED_AREA_RTOL of the sphere's area); the
    others lie inside the union of the rest."""
    sphere = 4.0 * np.pi * np.asarray(radii, dtype=np.float64) ** 2
    return np.asarray(atom_area, dtype=np.float64) > EXPOSED_AREA_RTOL * sphere

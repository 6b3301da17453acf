"""One simplex at a time: find a simplex's row from its vertices, and its "spoon", the smallest
empty sphere through its vertices (the ball that carves it out of space at its enter alpha).

For an unattached simplex that is its own smallest circumsphere (radius = enter). An attached
one (a point inside that sphere) enters with a coface: its spoon is the coface's, found by
following the cofaces whose enter equals its own up to an unattached one.
"""

from __future__ import annotations

import numpy as np

from core.errors import InputError
from core.geometry.circumspheres import circumspheres
from core.tolerances import ON_SPHERE_RTOL


def find_simplex(ac, vertices: object) -> tuple[int, int]:
    """(k, row) of the simplex of `ac` with these point indices (any order), or InputError.

    One vectorized pass over the first column of simplices(k): for a click, not a hot path.
    """
    verts = np.sort(np.asarray(vertices, dtype=np.int64).ravel())
    k = len(verts) - 1
    if not 0 <= k <= ac.dim or len(np.unique(verts)) != len(verts):
        raise InputError(f"{len(verts)} distinct vertices make no simplex of a {ac.dim}D complex")
    table = ac.simplices(k)
    rows = np.flatnonzero(table[:, 0] == verts[0])
    rows = rows[(table[rows] == verts).all(axis=1)]
    if len(rows) == 0:
        raise InputError(f"no {k}-simplex with vertices {verts.tolist()} in the complex")
    return k, int(rows[0])


def _checked_row(ac, k: int, row: int) -> tuple[int, int]:
    """(k, row) as ints after range checks (InputError otherwise)."""
    if not 0 <= int(k) <= ac.dim:
        raise InputError(f"k must be between 0 and {ac.dim}, not {k}")
    count = len(ac.simplices(int(k)))
    if not 0 <= int(row) < count:
        raise InputError(f"row must be between 0 and {count - 1}, not {row}")
    return int(k), int(row)


def _cofaces(ac, k: int, row: int) -> np.ndarray:
    """(c,) int64 rows of simplices(k + 1) that have simplex (k, row) as a face."""
    return np.flatnonzero((ac.face_ids(k + 1) == row).any(axis=1))


def spoon_simplex(ac, k: int, row: int) -> tuple[int, int]:
    """(k', row') of the unattached simplex whose smallest circumsphere is the spoon of (k, row):
    (k, row) itself, or the coface (of a coface...) it enters with."""
    k, row = _checked_row(ac, k, row)
    enter = ac.intervals(k)[row, 0]
    while 0 < k < ac.dim:  # a vertex (enter 0) is its own spoon
        _, r2, _, _ = circumspheres(ac.points, ac.simplices(k)[row : row + 1])
        if np.sqrt(r2[0]) >= enter * (1.0 - ON_SPHERE_RTOL):
            break
        up = _cofaces(ac, k, row)
        up_enter = ac.intervals(k + 1)[up, 0]
        k, row = k + 1, int(up[np.argmin(up_enter)])
    return k, row


def simplex_sphere(ac, k: int, row: int) -> tuple[np.ndarray, float]:
    """The spoon of simplex (k, row): (ambient_dim,) float64 centre in input coordinates and
    its radius (= the simplex's enter alpha); for a vertex, the point itself and 0."""
    if getattr(ac, "weights", None) is not None:
        raise InputError("the spoon is drawn for classic complexes; a weighted simplex's ball "
                         "is an orthogonal sphere")
    k, row = spoon_simplex(ac, k, row)
    simplex = ac.simplices(k)[row : row + 1]
    if k == 0:
        return ac.to_ambient(ac.points[simplex[0]])[0], 0.0
    offset, r2, _, _ = circumspheres(ac.points, simplex)
    centre = ac.points[simplex[0, 0]] + offset[0]
    return ac.to_ambient(centre[None, :])[0], float(np.sqrt(r2[0]))

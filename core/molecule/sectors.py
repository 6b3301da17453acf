"""The part of a union of balls inside each tetrahedron of its regular triangulation, exact.

The short inclusion–exclusion of `measures` holds point by point, and each of its terms is
symmetric about the simplex it belongs to: a ball about its centre, the lens of two balls about
their axis, the body of three balls about the plane of their centres. Split at the
tetrahedra around them, each term falls into pieces in proportion to an angle: the solid angle
ω_v/4π of a tetrahedron at a vertex (ball sectors), its dihedral angle φ_e/2π at an edge (lens
wedges), one half on each side of a triangle (three-ball bodies). So for a tetrahedron T

    vol(∪B ∩ T) = Σ_v ω_v/4π vol(B_v) - Σ_{e ⊂ T, e ∈ K} φ_e/2π vol(∩B_e)
                  + Σ_{f ⊂ T, f ∈ K} ½ vol(∩B_f) - [T ∈ K] vol(∩B_T),

and the same sum of the sphere areas gives the exposed area of each of T's vertices in T
(Liang, Edelsbrunner, Fu, Sudhakar, Subramaniam, "Analytical shape computation of
macromolecules", Proteins 33, 1998). A piece can reach out of T through a facet (a ball
over its opposite facet) and a foreign ball can reach into T: there the split is not T's
share, and `exact_cells` clips each ball to its power cell and T instead (`regions` decides
which).

Arrays: centres (t, 4, 3) float64 (relative to the first vertex is best), radii (t, 4).
"""

from __future__ import annotations

import numpy as np

from core.molecule.intersections import three_balls, two_balls

TET_EDGES = ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3))  # local edge order
FACE_OF = (3, 3, 1, 3, 0, 0)  # a tet facet (opposite this vertex) containing each edge ...
EDGE_IN_FACE = (2, 1, 1, 0, 1, 0)  # ... and the edge's slot in that facet's face_ids row


def solid_angles(c: np.ndarray) -> np.ndarray:
    """(t, 4) float64 solid angle of each tetrahedron at each vertex, as a fraction of 4π
    (Van Oosterom and Strackee's formula)."""
    out = np.empty(c.shape[:2])
    for v in range(4):
        a, b, d = (c[:, w] - c[:, v] for w in range(4) if w != v)
        la, lb, ld = (np.linalg.norm(x, axis=1) for x in (a, b, d))
        num = np.abs(np.einsum("ij,ij->i", a, np.cross(b, d)))
        den = (la * lb * ld + np.einsum("ij,ij->i", a, b) * ld
               + np.einsum("ij,ij->i", a, d) * lb + np.einsum("ij,ij->i", b, d) * la)
        out[:, v] = 2.0 * np.arctan2(num, den) / (4.0 * np.pi)
    return out


def dihedral_angles(c: np.ndarray) -> np.ndarray:
    """(t, 6) float64 dihedral angle of each tetrahedron at each edge (TET_EDGES), as a
    fraction of 2π."""
    out = np.empty((len(c), 6))
    for e, (i, j) in enumerate(TET_EDGES):
        k, m = (w for w in range(4) if w not in (i, j))
        u = c[:, j] - c[:, i]
        u = u / np.linalg.norm(u, axis=1, keepdims=True)
        p, q = c[:, k] - c[:, i], c[:, m] - c[:, i]
        p = p - np.einsum("ij,ij->i", p, u)[:, None] * u
        q = q - np.einsum("ij,ij->i", q, u)[:, None] * u
        out[:, e] = np.arctan2(np.linalg.norm(np.cross(p, q), axis=1),
                               np.einsum("ij,ij->i", p, q)) / (2.0 * np.pi)
    return out


def tet_edge_ids(tet_faces: np.ndarray, tri_faces: np.ndarray) -> np.ndarray:
    """(t, 6) int64 edge rows of each tetrahedron in TET_EDGES order, from face_ids(3)
    (t, 4) and face_ids(2) (n_tri, 3) of a table whose simplices list vertices ascending."""
    tet_faces = np.asarray(tet_faces, np.int64)
    tri_faces = np.asarray(tri_faces, np.int64)
    return np.stack([tri_faces[tet_faces[:, f], s] for f, s in zip(FACE_OF, EDGE_IN_FACE,
                                                                     strict=True)], 1)


def tet_pieces(c: np.ndarray, r: np.ndarray, edge_in: np.ndarray, face_in: np.ndarray
               ) -> tuple[np.ndarray, np.ndarray]:
    """(covered volume (t,), exposed sphere area (t, 4)) of the balls inside each tetrahedron
    not in the complex: edge_in (t, 6) and face_in (t, 4, facet opposite each vertex) say
    which of its edges and triangles are in it. Tetrahedra of the complex are not asked for."""
    omega = solid_angles(c)
    volume = (omega * (4.0 / 3.0 * np.pi * r ** 3)).sum(1)
    area = omega * (4.0 * np.pi * r ** 2)
    phi = dihedral_angles(c)
    for e, (i, j) in enumerate(TET_EDGES):
        rows = np.flatnonzero(edge_in[:, e])
        if len(rows):
            pair = [i, j]
            lens, caps = two_balls(c[rows][:, pair], r[rows][:, pair])
            volume[rows] -= phi[rows, e] * lens
            area[rows, i] -= phi[rows, e] * caps[:, 0]
            area[rows, j] -= phi[rows, e] * caps[:, 1]
    for f in range(4):
        rows = np.flatnonzero(face_in[:, f])
        if len(rows):
            trio = [w for w in range(4) if w != f]
            body, parts = three_balls(c[rows][:, trio], r[rows][:, trio])
            volume[rows] += 0.5 * body
            area[rows[:, None], trio] += 0.5 * parts
    return volume, area


def tet_volumes(c: np.ndarray) -> np.ndarray:
    """(t,) float64 volume of each tetrahedron."""
    e = c[:, 1:] - c[:, :1]
    return np.abs(np.einsum("ij,ij->i", e[:, 0], np.cross(e[:, 1], e[:, 2]))) / 6.0

"""One pass over a triangulation's cells shared by the certification and the table: every
cell's circumcentre system (core.geometry.centre_terms) is computed once and gives the table
its cell spheres, and the certification its filtered orientation and in-sphere signs.

The vertex q across a facet of cell (p_0, ..., p_d) is strictly inside the cell's
circumsphere exactly when V = det |q - p_0|² - (q - p_0) . num has the sign opposite to det
(centre = p_0 + num / (2 det), so V / det = |q - p_0|² - 2 (q - p_0) . (centre - p_0)). V is
the lifted in-sphere determinant expanded along q's row: the same polynomial of the rounded
coordinate differences for every facet, so core.predicates' forward error bound (gamma_K times
the same expression in absolute values) proves its sign, and exact arithmetic decides only
the rows the bound leaves open (core.predicates.orientations and in_sphere on those rows).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .geometry import CHUNK, centre_terms, spheres_of
from .parallel import in_chunks
from .predicates import error_coefficient, uncertain

#: Largest number of roundings behind a monomial, per dimension: (det, V). Leaves (coordinate
#: differences) 1; 2D: det = a0 b1 - a1 b0 (4), |v|² (4), num (dual * |v|², a difference: 7),
#: V = det |q|² - (q0 num0 + q1 num1) (max(9, 10) + 1 = 11). 3D: duals = cross products (4),
#: det = a . dual_0 (8), |v|² (5), num = sum of |v_i|² dual_i (12), |q|² (5), det |q|² (14),
#: q . num (16), V = 17. Sums of three terms add at most 2 in any order; a fused multiply-add
#: only removes roundings.
ROUNDINGS = {2: (4, 11), 3: (8, 17)}
_CROSS = ((1, 2), (2, 0), (0, 1))  # component i of a x b is a[j] b[k] - a[k] b[j]


@dataclass(frozen=True)
class CellSpheres:
    """core.geometry.cell_spheres of a triangulation's cells, for the table (core.table)."""

    r2: np.ndarray  # (n,) squared circumradii
    det: np.ndarray  # (n,) d! signed measures (extended precision for ill-conditioned cells)
    flat: np.ndarray  # (n,) bool degenerate cells
    bits: np.ndarray  # (n,) uint8 attach bits


@dataclass(frozen=True)
class FirstPass:
    """The shared pass: cell spheres, and float signs with the rows the bound cannot settle."""

    spheres: CellSpheres
    orient: np.ndarray  # (n,) int8 sign of each cell's determinant
    orient_doubt: np.ndarray  # (n,) bool: that sign needs exact arithmetic
    side: np.ndarray  # (f,) int8 sign of V for each facet (t, q)
    side_doubt: np.ndarray  # (f,) bool: that sign needs exact arithmetic


def _dual_perms(absvec: np.ndarray) -> np.ndarray:
    """(d, n, d) the duals' expressions in absolute values, from (n, d, d) |edge vectors|."""
    if absvec.shape[2] == 2:
        a, b = absvec[:, 0], absvec[:, 1]
        return np.stack([b[:, ::-1], a[:, ::-1]])
    planes = np.ascontiguousarray(absvec.transpose(1, 2, 0))  # (vector, coordinate, n)
    out = np.empty((3, absvec.shape[0], 3))
    for slot, (u, w) in enumerate(_CROSS):
        first, second = planes[u], planes[w]
        for i, (j, k) in enumerate(_CROSS):
            np.add(first[j] * second[k], first[k] * second[j], out=out[slot, :, i])
    return out


def first_pass(points: np.ndarray, cells: np.ndarray, t: np.ndarray,
               q: np.ndarray) -> FirstPass:
    """The pass over the (n, d+1) `cells` of (m, d) `points` and the facets (t, q): cell t
    (ascending) and the vertex q across one of its facets."""
    n, d = len(cells), points.shape[1]
    r2, det, flat, bits = np.empty(n), np.empty(n), np.empty(n, bool), np.empty(n, np.uint8)
    orient, orient_doubt = np.empty(n, np.int8), np.empty(n, bool)
    side, side_doubt = np.empty(len(t), np.int8), np.empty(len(t), bool)
    coef_det, coef_v = (error_coefficient(k) for k in ROUNDINGS[d])

    def part(lo: int, hi: int) -> None:
        rows = cells[lo:hi]
        corners = np.take(points, rows.ravel(), axis=0).reshape(len(rows), d + 1, d)
        terms = centre_terms(corners[:, 1:] - corners[:, :1])
        _, r2[lo:hi], det[lo:hi], flat[lo:hi], bits[lo:hi] = spheres_of(points, rows, terms)
        duals = _dual_perms(np.abs(terms.vec))
        perm_det = np.einsum("nd,nd->n", np.abs(terms.vec[:, 0]), duals[0])
        orient[lo:hi] = np.sign(terms.det)
        orient_doubt[lo:hi] = uncertain(terms.det, perm_det, coef_det)
        perm_num = np.einsum("kn,knd->nd", terms.sq.T, duals)
        f0, f1 = np.searchsorted(t, (lo, hi))
        local = t[f0:f1] - lo
        rel = np.take(points, q[f0:f1], axis=0) - corners[local, 0]
        qq = np.einsum("nd,nd->n", rel, rel)
        num = terms.num[local]
        dot = rel[:, 0] * num[:, 0] + rel[:, 1] * num[:, 1]
        perm = np.abs(rel[:, 0]) * perm_num[local, 0] + np.abs(rel[:, 1]) * perm_num[local, 1]
        if d == 3:
            dot += rel[:, 2] * num[:, 2]
            perm += np.abs(rel[:, 2]) * perm_num[local, 2]
        value = terms.det[local] * qq - dot
        perm += perm_det[local] * qq
        side[f0:f1] = np.sign(value)
        side_doubt[f0:f1] = uncertain(value, perm, coef_v)

    in_chunks(part, n, CHUNK)
    return FirstPass(CellSpheres(r2, det, flat, bits), orient, orient_doubt, side, side_doubt)

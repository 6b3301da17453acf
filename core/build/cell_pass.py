"""One pass over a triangulation's cells shared by the certification and the table: every
cell's circumcentre system (core.geometry.circumspheres.centre_terms) is computed once and gives
the table its cell spheres, and the certification its filtered orientation and in-sphere signs.

The vertex q across a facet of cell (p_0, ..., p_d) is strictly inside the cell's
circumsphere exactly when V = det |q - p_0|² - (q - p_0) . num has the sign opposite to det
(centre = p_0 + num / (2 det), so V / det = |q - p_0|² - 2 (q - p_0) . (centre - p_0)). V is
the lifted in-sphere determinant of the rows [v, |v|²] (v = p_i - p_0, then q - p_0) expanded
along its last column, every minor into all its monomials: the same expression in absolute
values is the permanent of that matrix in absolute values, at most the product of its rows'
absolute sums (core.geometry.predicates.row_sum_bound). So core.geometry.predicates' forward error
bound (gamma_K times that) proves the sign, and exact arithmetic decides only the rows the bound
leaves open (core.geometry.predicates.orientations and in_sphere on those rows); the same for det.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.geometry.circumspheres import centre_terms, spheres_of
from core.geometry.predicates import error_coefficient, uncertain
from core.parallel import in_chunks

#: Largest number of roundings behind a monomial, per dimension: (det, V). Leaves (coordinate
#: differences) 1; 2D: det = a0 b1 - a1 b0 (4), |v|² (4), num (dual * |v|², a difference: 7),
#: V = det |q|² - (q0 num0 + q1 num1) (max(9, 10) + 1 = 11). 3D: duals = cross products (4),
#: det = a . dual_0 (8), |v|² (5), num = sum of |v_i|² dual_i (12), |q|² (5), det |q|² (14),
#: q . num (16), V = 17. Sums of three terms add at most 2 in any order; a fused multiply-add
#: only removes roundings.
ROUNDINGS = {2: (4, 11), 3: (8, 17)}
#: Cells per chunk: the pass's dozens of temporaries stay in the caches.
PASS_CHUNK = 1 << 14


@dataclass(frozen=True)
class CellSpheres:
    """core.geometry.circumspheres.cell_spheres of a triangulation's cells, for the table
    (core.build.table)."""

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


def _row_sum(rows: np.ndarray) -> np.ndarray:
    """(n,) sums of the d columns of (n, d) rows (column adds: faster than a short-axis sum)."""
    total = rows[:, 0] + rows[:, 1]
    if rows.shape[1] == 3:
        total += rows[:, 2]
    return total


def _product(factors: list[np.ndarray]) -> np.ndarray:
    total = factors[0] * factors[1]
    for factor in factors[2:]:
        total *= factor
    return total


def first_pass(points: np.ndarray, cells: np.ndarray, t: np.ndarray,
               q: np.ndarray) -> FirstPass:
    """The pass over the (n, d+1) `cells` of (m, d) `points` and the facets (t, q): cell t
    (ascending) and the vertex q across one of its facets. In cache-sized chunks, alternate
    ones in a helper thread; the rows come out the same whatever the chunking."""
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
        absvec = np.abs(terms.vec)
        sums = [_row_sum(absvec[:, k]) for k in range(d)]  # the rows' absolute sums
        orient[lo:hi] = np.sign(terms.det)
        orient_doubt[lo:hi] = uncertain(terms.det, _product(sums), coef_det)
        lifted = _product([row + terms.sq[:, k] for k, row in enumerate(sums)])
        f0, f1 = np.searchsorted(t, (lo, hi))
        local = t[f0:f1] - lo
        rel = np.take(points, q[f0:f1], axis=0) - corners[local, 0]
        qq = np.einsum("nd,nd->n", rel, rel)
        num = terms.num[local]
        dot = rel[:, 0] * num[:, 0] + rel[:, 1] * num[:, 1]
        if d == 3:
            dot += rel[:, 2] * num[:, 2]
        value = terms.det[local] * qq - dot
        side[f0:f1] = np.sign(value)
        perm = lifted[local] * (_row_sum(np.abs(rel)) + qq)
        side_doubt[f0:f1] = uncertain(value, perm, coef_v)

    in_chunks(part, n, PASS_CHUNK)
    return FirstPass(CellSpheres(r2, det, flat, bits), orient, orient_doubt, side, side_doubt)

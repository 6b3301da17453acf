"""Exact arithmetic on the binary values of float64 coordinates, for the few predicates whose
floating-point evaluation cannot be trusted (core.geometry.predicates decides which).

Every float64 is an integer mantissa times a power of two; scaled by one common power of two,
a set of coordinates becomes Python integers with exactly the same ratios, so the sign of any
homogeneous polynomial of them (a determinant, a dot product) is computed without error.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from fractions import Fraction
from itertools import combinations

import numpy as np


def exact_ints(values: np.ndarray) -> np.ndarray:
    """`values` (any shape, finite float64) as an object array of Python ints, all scaled by
    the same power of two (the smallest exponent present), so every ratio is exact."""
    flat = np.ascontiguousarray(values, dtype=np.float64).ravel()
    mant, expo = np.frexp(flat)
    mant = (mant * 2.0**53).astype(np.int64)  # exact: 53-bit significands
    expo = expo.astype(np.int64) - 53
    lowest = int(expo[mant != 0].min()) if (mant != 0).any() else 0
    shifts = np.where(mant != 0, expo - lowest, 0)
    out = np.array([int(m) << int(s) for m, s in zip(mant.tolist(), shifts.tolist(), strict=True)]
                   + [0], dtype=object)[:-1]
    return out.reshape(np.shape(values))


def determinant(rows: Sequence[Sequence[object]]) -> object:
    """Determinant of a square matrix whose entries are arrays (or numbers) of any ring type
    (float arrays, object arrays of ints, core.geometry.predicates' bounded floats), elementwise.

    Laplace expansion along the columns with every minor computed once (rows × 2^rows
    products): the same expression evaluates in floating point and exactly.
    """
    n = len(rows)
    minors: dict[tuple[int, ...], object] = {(r,): rows[r][n - 1] for r in range(n)}
    for size in range(2, n + 1):
        col = n - size
        step: dict[tuple[int, ...], object] = {}
        for subset in combinations(range(n), size):
            total = None
            for pos, r in enumerate(subset):
                term = rows[r][col] * minors[subset[:pos] + subset[pos + 1:]]
                if total is None:
                    total = term
                elif pos % 2:
                    total = total - term
                else:
                    total = total + term
            step[subset] = total
        minors = step
    return minors[tuple(range(n))]


def lifted_rows(vectors: Sequence[Sequence[object]]) -> list[list[object]]:
    """Rows [v, |v|²] of the in-sphere determinant for difference vectors v (each a list of
    d coordinate arrays)."""
    out = []
    for vec in vectors:
        sq = vec[0] * vec[0]
        for c in vec[1:]:
            sq = sq + c * c
        out.append([*vec, sq])
    return out


def perturbed_inside(vectors: list[list[np.ndarray]], ids: np.ndarray,
                     tie_weights: np.ndarray) -> np.ndarray:
    """(n,) bool: the query is inside the cell's circumsphere under the symbolic perturbation,
    for exactly cospherical cases (in-sphere determinant exactly 0).

    `vectors` (d+1 lists of d object int arrays): the cell's vertices minus the query point;
    `ids` (n, d+2) global indices of the cell's vertices and then the query's; `tie_weights`
    (n, d+2) their fixed weights in [0, 1) (float64 multiples of 2**-53). The rule (one for
    the whole build): every point's lifted height |p|² is lowered by eps * w + eps² *
    eps'^(N - index). The lifted determinant D = sum_i h_i C_i then takes the sign of
    -sum_i w_i C_i, or, where that is 0 too, of -C_j for the highest-indexed point j with
    C_j != 0; the query is inside when D has the sign of -C_q. This is the regular
    triangulation of infinitesimally weighted points (valid, unique, the same from both
    sides of a facet), and the first order is what Qhull computes with real weights eps * w.
    """
    d = len(vectors[0])
    n = len(ids)
    rows = [[*v, 1] for v in vectors] + [[0] * d + [1]]  # the lifted column removed
    cof = np.empty((d + 2, n), dtype=object)
    for i in range(d + 2):
        value = determinant([row for j, row in enumerate(rows) if j != i])
        cof[i] = np.broadcast_to(np.asarray(value, dtype=object), (n,))
        if (i + d) % 2:
            cof[i] = -cof[i]
    signs = np.array([[(v > 0) - (v < 0) for v in row] for row in cof.tolist()],
                     dtype=np.int64).reshape(d + 2, n)
    scaled = (np.asarray(tie_weights, dtype=np.float64) * 2.0**53).astype(np.int64)
    first = np.zeros(n, dtype=object)
    for i in range(d + 2):
        first = first + cof[i] * np.array([*scaled[:, i].tolist(), 0], dtype=object)[:-1]
    order = np.argsort(-np.asarray(ids), axis=1, kind="stable")  # highest index first
    ranked = np.take_along_axis(signs.T, order, axis=1)
    decisive = ranked[np.arange(n), np.argmax(ranked != 0, axis=1)]
    weighted = np.array([(v > 0) - (v < 0) for v in first.tolist()], dtype=np.int64)
    decisive = np.where(weighted != 0, weighted, decisive)
    return decisive == signs[d + 1]


def exact_signs(formula: Callable[..., object], vectors: list[list[np.ndarray]]) -> np.ndarray:
    """(n,) int8 signs of `formula(vectors)` evaluated on exact integers."""
    value = np.asarray(formula(vectors), dtype=object).ravel()
    return np.array([(v > 0) - (v < 0) for v in value.tolist()], dtype=np.int8)


def exact_radii(points: np.ndarray, simplices: np.ndarray) -> np.ndarray:
    """(n,) float64 radii of the smallest spheres through (n, k+1) simplices of (m, d)
    points, from their squares computed in rational arithmetic (non-degenerate simplices;
    for the few ill-conditioned ones whose float formula loses digits). A radius whose square
    would overflow float64 stays finite.

    The centre is p_0 + sum_i lam_i v_i with G lam = |v|²/2 (G the Gram matrix of the edge
    vectors v_i = p_i - p_0), so r² = lam . |v|² / 2; Cramer's rule keeps it in integers.
    """
    simplices = np.asarray(simplices)
    out = np.empty(len(simplices))
    if not len(simplices):
        return out
    flat = np.ascontiguousarray(points[simplices], dtype=np.float64)
    ints = exact_ints(flat)
    k = simplices.shape[1] - 1
    unit2 = Fraction(2) ** (2 * _lowest_exponent(flat))  # exact_ints' scale, squared
    for row, corners in enumerate(ints):
        vec = [[int(a) - int(b) for a, b in zip(corners[i], corners[0], strict=True)]
               for i in range(1, k + 1)]
        gram = [[sum(a * b for a, b in zip(u, v, strict=True)) for v in vec] for u in vec]
        half = [g[i] for i, g in enumerate(gram)]  # |v_i|² (the 1/2 is applied at the end)
        det = determinant(gram)
        lam = []
        for i in range(k):
            swapped = [[half[r] if c == i else gram[r][c] for c in range(k)] for r in range(k)]
            lam.append(determinant(swapped))
        num = sum(a * b for a, b in zip(lam, half, strict=True))
        out[row] = _sqrt(Fraction(num, 4 * det) * unit2) if det else np.inf
    return out


def _sqrt(value: Fraction) -> float:
    """sqrt of a positive rational as float64 (scaled by an even power of two first, so huge
    or tiny squares of representable radii do not overflow)."""
    half = (value.numerator.bit_length() - value.denominator.bit_length()) // 2
    return math.ldexp(math.sqrt(float(value / Fraction(2) ** (2 * half))), half)


def _lowest_exponent(values: np.ndarray) -> int:
    """The power of two exact_ints scales `values` by (its unit in the last place)."""
    nonzero = values[values != 0]
    if not len(nonzero):
        return 0
    return int(np.frexp(nonzero)[1].min()) - 53

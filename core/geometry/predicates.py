"""Filtered geometric predicates: signs of orientation, in-sphere and diametral-sphere tests,
computed in float64 with a proven error bound and exactly for the few the bound cannot settle.

Each predicate is one polynomial in coordinate differences, written once (core.geometry.exact's
`determinant`) and evaluated twice: in numpy over all rows with a running bound, then on exact
integers (core.geometry.exact) for the rows whose |value| does not exceed the bound. The bound is
the classic forward one: a sum of monomials, each through at most k roundings of relative size
u = 2**-53 (leaf differences included), is off by at most gamma_k times the same expression in
absolute values (the "permanent"), itself computed in float64 with the same k.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import cache

import numpy as np

from core.geometry.exact import (
    determinant,
    exact_ints,
    exact_signs,
    lifted_rows,
    perturbed_inside,
)
from core.parallel import halves

_U = 2.0**-53
#: Values whose permanent is below this are settled exactly: the bound ignores underflow.
_TINY = 1e-250
_CHUNK = 1 << 18

Formula = Callable[[list[list[object]]], object]


class Bounded:
    """A float64 array with its permanent (the same expression in absolute values) and the
    largest number of roundings behind any of its monomials."""

    __slots__ = ("count", "perm", "value")

    def __init__(self, value: np.ndarray, perm: np.ndarray, count: int) -> None:
        self.value, self.perm, self.count = value, perm, count

    def __add__(self, other: Bounded) -> Bounded:
        return Bounded(self.value + other.value, self.perm + other.perm,
                       max(self.count, other.count) + 1)

    def __sub__(self, other: Bounded) -> Bounded:
        return Bounded(self.value - other.value, self.perm + other.perm,
                       max(self.count, other.count) + 1)

    def __mul__(self, other: Bounded) -> Bounded:
        return Bounded(self.value * other.value, self.perm * other.perm,
                       self.count + other.count + 1)



def _differences(points: np.ndarray, base: np.ndarray, others: np.ndarray) -> list:
    """(k, d) contiguous float64 coordinate columns of points[others[:, i]] - points[base]."""
    columns = [np.ascontiguousarray(points[:, c]) for c in range(points.shape[1])]
    origin = [np.take(col, base) for col in columns]
    return [[np.take(col, others[:, i]) - o for col, o in zip(columns, origin, strict=True)]
            for i in range(others.shape[1])]


def _exact_vectors(points: np.ndarray, base: np.ndarray, others: np.ndarray) -> list:
    ints = exact_ints(points[np.column_stack((base, others))])  # (n, k+1, d), one exponent
    diff = ints[:, 1:] - ints[:, :1]
    return [[diff[:, i, c] for c in range(points.shape[1])] for i in range(diff.shape[1])]


@cache
def _roundings(formula: Formula, k: int, d: int) -> int:
    """The largest number of roundings behind a monomial of `formula` on k difference
    vectors in d dimensions (structural: found by one evaluation on Bounded scalars)."""
    one = np.ones(1)
    vectors = [[Bounded(one, one, 1) for _ in range(d)] for _ in range(k)]
    return formula(vectors).count


def error_coefficient(roundings: int) -> float:
    """c such that |value| > c * perm (the permanent as computed in float64) proves the sign
    of a value whose monomials went through at most `roundings` roundings: gamma_k with
    room for the permanent's own rounding errors."""
    return (2 * roundings + 2) * _U


def uncertain(value: np.ndarray, perm: np.ndarray, coef: float) -> np.ndarray:
    """(n,) bool: signs the bound cannot settle (|value| <= coef * perm), and those whose
    permanent is so small that underflow may hide digits, or not finite."""
    with np.errstate(invalid="ignore", over="ignore"):
        return ~(np.abs(value) > coef * perm) | ~(perm >= _TINY) | ~np.isfinite(perm)


def row_sum_bound(vectors: list, lifted: bool = False) -> np.ndarray:
    """An upper bound of the permanent of |M| for the determinant of the rows v_i (or
    [v_i, |v_i|²] when lifted): the product of the rows' absolute sums."""
    total = None
    for vec in vectors:
        row = np.abs(vec[0])
        for c in vec[1:]:
            row = row + np.abs(c)
        if lifted:
            row = row + _dot(vec, vec)
        total = row if total is None else total * row
    return total


def filtered_signs(formula: Formula, points: np.ndarray, base: np.ndarray,
                   others: np.ndarray, bound: Callable[[list], np.ndarray] | None = None
                   ) -> tuple[np.ndarray, np.ndarray]:
    """(n,) int8 exact signs of `formula` on the difference vectors points[others] - points[base]
    ((n,) and (n, k) int indices), and the (n,) bool rows that needed exact arithmetic.

    With `bound` (vectors -> an upper bound of the formula's permanent, e.g. row_sum_bound
    for determinants), the float pass evaluates the formula once on plain arrays; without,
    it carries the permanent alongside (Bounded)."""
    n, d = len(base), points.shape[1]
    signs = np.empty(n, dtype=np.int8)
    exact = np.zeros(n, dtype=bool)
    coef = error_coefficient(_roundings(formula, others.shape[1], d))

    def part(start: int, stop: int) -> None:
        for lo in range(start, stop, _CHUNK):
            sl = slice(lo, min(lo + _CHUNK, stop))
            vectors = _differences(points, base[sl], others[sl])
            if bound is None:
                leaves = [[Bounded(c, np.abs(c), 1) for c in vec] for vec in vectors]
                result = formula(leaves)
                value, perm = result.value, result.perm
            else:
                value, perm = formula(vectors), bound(vectors)
            signs[sl] = np.sign(value)
            exact[sl] = uncertain(value, perm, coef)

    halves(part, n)
    ids = np.flatnonzero(exact)
    if len(ids):
        signs[ids] = exact_signs(formula, _exact_vectors(points, base[ids], others[ids]))
    return signs, exact


def _dot(u: list, w: list) -> object:
    total = u[0] * w[0]
    for a, b in zip(u[1:], w[1:], strict=True):
        total = total + a * b
    return total


def _cross(u: list, v: list) -> list:
    return [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]


def orientation_formula(vectors: list) -> object:
    """det(p_1 - p_0, ..., p_d - p_0): d! times the signed measure."""
    return determinant(vectors)


def insphere_formula(vectors: list) -> object:
    """det([p_i - q, |p_i - q|²]) over a cell's d + 1 vertices p_i and a query q."""
    return determinant(lifted_rows(vectors))


def diametral_formula(vectors: list) -> object:
    """Negative exactly when the query is strictly inside the smallest sphere of an edge
    (vectors a - q, b - q) or of a 3D triangle (vectors b - a, c - a, q - a)."""
    if len(vectors) == 2:
        return _dot(vectors[0], vectors[1])
    u, v, w = vectors
    n = _cross(u, v)
    num_u, num_v = _cross(v, n), _cross(n, u)
    return (_dot(w, w) * _dot(n, n)
            - _dot(w, [_dot(u, u) * a + _dot(v, v) * b for a, b in zip(num_u, num_v, strict=True)]))


def orientations(points: np.ndarray, simplices: np.ndarray) -> tuple[np.ndarray, int]:
    """(n,) int8 exact signs of det(p_i - p_0) for (n, d+1) simplices, and how many rows
    needed exact arithmetic."""
    signs, exact = filtered_signs(orientation_formula, points, simplices[:, 0], simplices[:, 1:],
                                  row_sum_bound)
    return signs, int(exact.sum())


def in_sphere_sides(points: np.ndarray, cells: np.ndarray, queries: np.ndarray,
                    cell_signs: np.ndarray) -> tuple[np.ndarray, int]:
    """(n,) int8 exact side of query point i against the circumsphere of (n, d+1) cell i
    (non-flat, of orientation sign `cell_signs`): -1 strictly inside, 0 exactly on it, +1
    outside; and how many rows needed exact arithmetic."""
    d = points.shape[1]
    signs, exact = filtered_signs(insphere_formula, points, queries, cells,
                                  lambda vectors: row_sum_bound(vectors, lifted=True))
    # det([p_i - q, |p_i - q|²]) has the sign (-1)**d * orientation when q is inside
    sides = signs.astype(np.int8) * np.asarray(cell_signs, dtype=np.int8)
    return (sides if d % 2 else -sides).astype(np.int8), int(exact.sum())


def in_sphere(points: np.ndarray, cells: np.ndarray, queries: np.ndarray,
              cell_signs: np.ndarray, tie_weights: np.ndarray) -> tuple[np.ndarray, int]:
    """(n,) bool: query point i lies inside the circumsphere of (n, d+1) cell i (non-flat, of
    orientation sign `cell_signs`), exactly cospherical cases decided by the symbolic
    perturbation of core.geometry.exact.perturbed_inside with the points' (m,) `tie_weights`; and
    how many rows needed exact arithmetic."""
    sides, exact = in_sphere_sides(points, cells, queries, cell_signs)
    inside = sides < 0
    tie = np.flatnonzero(sides == 0)
    if len(tie):
        vectors = _exact_vectors(points, queries[tie], cells[tie])
        ids = np.column_stack((cells[tie], queries[tie]))
        inside[tie] = perturbed_inside(vectors, ids, tie_weights[ids])
    return inside, exact


def diametral_signs(points: np.ndarray, simplices: np.ndarray,
                    queries: np.ndarray) -> tuple[np.ndarray, int]:
    """(n,) int8 exact signs of query i against the smallest sphere of edge or (3D) triangle
    i ((n, 2) or (n, 3)): -1 strictly inside (the attachment test), 0 on it, 1 outside; and
    how many rows needed exact arithmetic."""
    if simplices.shape[1] == 2:
        signs, exact = filtered_signs(diametral_formula, points, queries, simplices)
    else:
        others = np.column_stack((simplices[:, 1:], queries))
        signs, exact = filtered_signs(diametral_formula, points, simplices[:, 0], others)
    return signs, int(exact.sum())

"""Independent references for weighted tables: gudhi's weighted alpha complex, and power
distances / orthogonal spheres computed by plain linear algebra, simplex by simplex.

Nothing here reads the implementation's tables; the tests compare the two sides.
"""

from __future__ import annotations

import numpy as np
from reference import canonical, simplex_tree_table


def gudhi_weighted_table(points: np.ndarray, weights: np.ndarray,
                         precision: str = "exact") -> dict:
    """gudhi as {k: (simplices, enter_sq, regular_sq, interior_sq)}, vertex ids = input rows;
    "vertices" = the input rows that are vertices (the others are hidden); "st" the tree."""
    import gudhi

    pts = np.asarray(points, dtype=np.float64)
    st = gudhi.AlphaComplex(points=pts, weights=[float(w) for w in weights],
                            precision=precision).create_simplex_tree()
    table = simplex_tree_table(st, len(pts))
    return {**table, "vertices": table[0][0][:, 0]}


def gudhi_betti(st, dim: int, alpha2: np.ndarray) -> np.ndarray:
    """(s, dim) Betti numbers of gudhi's filtration at each squared value, from persistence."""
    st.compute_persistence(min_persistence=-1.0)
    out = np.zeros((len(alpha2), dim), dtype=np.int64)
    for k in range(dim):
        pairs = np.asarray(st.persistence_intervals_in_dimension(k)).reshape(-1, 2)
        born = pairs[:, 0][None, :] <= alpha2[:, None]
        alive = pairs[:, 1][None, :] > alpha2[:, None]
        out[:, k] = (born & alive).sum(axis=1)
    return out


def ours_by_input_rows(ac, k: int) -> tuple[np.ndarray, np.ndarray]:
    """Our k-simplices as canonical input-row tuples, squared intervals in that order.

    Needs duplicate-free input; hidden points (input_index -1) name no vertex."""
    index = np.asarray(ac.input_index)
    rows_of = np.full(len(ac.points), -1, dtype=np.int64)
    shown = np.flatnonzero(index >= 0)
    rows_of[index[shown]] = shown
    assert (rows_of >= 0).all(), "a vertex that is no input row"
    rows, order = canonical(rows_of[np.asarray(ac.simplices(k))])
    return rows, np.asarray(ac.intervals_sq(k))[order]


def orthosphere(points: np.ndarray, weights: np.ndarray) -> tuple[np.ndarray, float]:
    """Centre and power of the smallest sphere orthogonal to the (k+1) weighted points:
    c = p0 + V y (V the edge vectors) with |c - p_i|² - w_i equal for all i, by lstsq."""
    p0, vec = points[0], points[1:] - points[0]
    rhs = 0.5 * ((vec * vec).sum(axis=1) - (weights[1:] - weights[0]))
    y = np.linalg.solve(vec @ vec.T, rhs) if len(vec) else np.zeros(0)
    c = p0 + y @ vec
    return c, float(((c - p0) ** 2).sum() - weights[0])


def power(points: np.ndarray, weights: np.ndarray, x: np.ndarray) -> np.ndarray:
    """(n,) power distances |x - p|² - w of point x to every weighted point."""
    return ((points - x) ** 2).sum(axis=1) - weights

"""The vertex level of the interval table: vertices enter at 0 (weighted: at -sqrt(w), or
with their first edge when attached), regular and interior over their edges."""

from __future__ import annotations

import numpy as np

from core.build.levels import Level
from core.geometry.power import edge_powers, signed_sqrt


def vertex_level(n_points: int, edges: Level, points: np.ndarray | None = None,
                 weights: np.ndarray | None = None, bits: np.ndarray | None = None) -> Level:
    """Level 0: vertices enter at 0 (weighted: at -sqrt(w), or with their first edge when
    a neighbour has negative power to their sphere); regular/interior over their edges.
    Edges without values (a mode's table) give vertices without values. `bits`: the
    edges' (e,) edge_powers bits when the edge pass has them, else computed here."""
    edges.face_ids = edges.simplices[:, ::-1].copy()
    simplices = np.arange(n_points, dtype=np.int32)[:, None]
    if len(edges.enter) < len(edges.simplices):
        return Level(simplices, np.empty(0), np.empty(0), np.empty(0))
    regular = np.full(n_points, np.inf)
    interior = np.full(n_points, -np.inf)
    for col in (0, 1):
        np.minimum.at(regular, edges.simplices[:, col], edges.enter)
        np.maximum.at(interior, edges.simplices[:, col], edges.interior)
    if weights is None:
        return Level(simplices, np.zeros(n_points), regular, interior)
    if bits is None:
        bits = edge_powers(points, weights, edges.simplices)[2]
    attached = np.zeros(n_points, dtype=bool)
    attached[edges.simplices[(bits & 2) != 0, 0]] = True  # vertex 1 below vertex 0's power
    attached[edges.simplices[(bits & 1) != 0, 1]] = True
    enter = np.where(attached, regular, np.minimum(signed_sqrt(-weights), regular))
    return Level(simplices, enter, regular, interior)

"""The union of the tiles' owned simplices: the whole shape at alpha, its components (a
union-find over the member edges across tiles) and its measures (sums over tiles)."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from core.arrays import readonly
from core.build.points import Frame
from core.tiled.result import TileResult


@dataclass(frozen=True, eq=False)
class TiledShape:
    """The alpha shape at one alpha, assembled from tiles; arrays are read-only.

    `points` (u, dim) float64 the vertices of the complex (complex coordinates; `frame`
    maps planar 3D input back), `ids` (u,) int64 their global ids (input rows, ascending).
    Per dimension k: `simplices[k]` (n_k, k+1) int64 rows of `points`, ascending within a
    row, tile after tile; `classes[k]` (n_k,) int8 (1 singular, 2 regular,
    3 interior); `intervals[k]` (n_k, 3) enter/regular/interior (NaN above alpha).
    `regular` (r, dim) int64 REGULAR facets oriented away from their cell. `alpha` is the
    table value (signed radius), `alpha2` its signed square.
    """

    dim: int
    ambient_dim: int
    frame: Frame | None
    alpha: float
    alpha2: float
    points: np.ndarray
    ids: np.ndarray
    simplices: tuple[np.ndarray, ...]
    classes: tuple[np.ndarray, ...]
    intervals: tuple[np.ndarray, ...]
    regular: np.ndarray
    measure: float
    boundary_measure: float
    components: int
    n_points: int
    hidden: int
    weighted: bool
    n_tiles: int

    def counts(self) -> dict[str, dict[str, int]]:
        """Simplices per dimension and class (exterior ones are not known to a tiled build:
        they are never listed)."""
        names = ("vertices", "edges", "triangles", "tetrahedra")
        return {names[k]: {c: int(np.count_nonzero(self.classes[k] == v))
                           for c, v in (("singular", 1), ("regular", 2), ("interior", 3))}
                for k in range(self.dim + 1)}

    def euler(self) -> int:
        """Euler characteristic of the complex: sum over k of (-1)^k n_k."""
        return int(sum((-1) ** k * len(s) for k, s in enumerate(self.simplices)))

    def betti(self) -> list[int] | None:
        """Betti numbers in 2D (components, holes = components - Euler characteristic);
        None in 3D, where tunnels and voids need more than the counts."""
        return [self.components, self.components - self.euler()] if self.dim == 2 else None

    def to_ambient(self, coords: np.ndarray) -> np.ndarray:
        """Map (k, dim) complex coordinates to the input space."""
        coords = np.asarray(coords, dtype=np.float64)
        return coords if self.frame is None else self.frame.origin + coords @ self.frame.basis


def merge_tiles(results: Iterable[TileResult], *, dim: int, ambient_dim: int,
                frame: Frame | None, alpha: float, alpha2: float, weighted: bool
                ) -> TiledShape:
    """Assemble the tiles' owned simplices (each simplex is owned by exactly one tile)."""
    parts: dict[str, list] = {"ids": [], "coords": [], "regular": []}
    per_k: list[list[tuple]] = [[] for _ in range(dim + 1)]
    measure = boundary = 0.0
    n_points = hidden = n_tiles = 0
    for result in results:
        parts["ids"].append(result.vertex_ids)
        parts["coords"].append(result.vertex_coords)
        parts["regular"].append(result.regular)
        for k in range(dim + 1):
            per_k[k].append((result.simplices[k], result.classes[k], result.intervals[k]))
        measure += result.measure
        boundary += result.boundary
        n_points += result.points
        hidden += result.hidden
        n_tiles += 1
    ids, first = np.unique(np.concatenate(parts["ids"] or [np.empty(0, np.int64)]),
                           return_index=True)
    coords = np.concatenate(parts["coords"] or [np.empty((0, dim))])[first]
    simplices, classes, intervals = [], [], []
    row_of = _row_lookup(ids)
    for k in range(dim + 1):
        s, c, iv = _level(per_k[k], k, row_of)
        simplices.append(readonly(s))
        classes.append(readonly(c))
        intervals.append(readonly(iv))
    regular = np.concatenate(parts["regular"] or [np.empty((0, dim), np.int64)])
    return TiledShape(dim, ambient_dim, frame, float(alpha), float(alpha2), readonly(coords),
                      readonly(ids), tuple(simplices), tuple(classes), tuple(intervals),
                      readonly(row_of[regular].astype(np.int64)), measure, boundary,
                      components(len(ids), simplices[1] if dim >= 1 else None),
                      n_points, hidden, weighted, n_tiles)


def _row_lookup(ids: np.ndarray) -> np.ndarray:
    """(ids[-1] + 1,) the row of each global id in the ascending `ids` (a gather per vertex
    instead of a binary search: 5-10x faster on the tens of millions of vertices of a big
    merge), int32 where the rows fit."""
    dtype = np.int32 if len(ids) < 2**31 else np.int64
    lookup = np.zeros(int(ids[-1]) + 1 if len(ids) else 0, dtype=dtype)
    lookup[ids] = np.arange(len(ids), dtype=dtype)
    return lookup


def _level(parts: list[tuple], k: int, row_of: np.ndarray):
    """The k-simplices of all tiles as rows of the merged points (`row_of` a global id's
    row; tile after tile: no sort, the merge costs about its copies), with their classes
    and intervals."""
    if not parts:
        return np.empty((0, k + 1), np.int64), np.empty(0, np.int8), np.empty((0, 3))
    s = np.empty((sum(len(p[0]) for p in parts), k + 1), dtype=np.int64)
    start = 0
    for p in parts:  # gathered straight into the result: no concatenated copy to cast
        s[start:start + len(p[0])] = row_of[p[0]]
        start += len(p[0])
    c = np.concatenate([p[1] for p in parts])
    iv = np.concatenate([p[2] for p in parts]).reshape(-1, 3)
    return s, c, iv


def components(n: int, edges: np.ndarray | None) -> int:
    """Connected components of n vertices joined by (e, 2) edges (a union-find over all
    tiles' member edges, by scipy's connected_components)."""
    if n == 0:
        return 0
    if edges is None or len(edges) == 0:
        return n
    graph = coo_matrix((np.ones(len(edges), dtype=np.int8), (edges[:, 0], edges[:, 1])),
                       shape=(n, n))
    return int(connected_components(graph, directed=False)[0])

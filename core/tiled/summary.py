"""The numbers of a tiled shape without its simplices: counts per class, measures and
components, folded in tile by tile (a union-find over the input rows), so a run of 10^7-10^8
points never holds the whole shape (`alphascoop info --tiled` needs only these).

The counts and measures are the sums merge_tiles makes; the components are those of the
member edges over the global ids, as merge.components finds them on the merged shape.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

_NAMES = ("vertices", "edges", "triangles", "tetrahedra")
COUNT_BLOCK = 1 << 18  # rows a block of Components.count


@dataclass(frozen=True)
class TiledSummary:
    """What a tiled shape at one alpha amounts to: `classes[k]` (singular, regular,
    interior) counts of the k-simplices, `measure` volume (3D) or area (2D), `boundary_measure`
    area or perimeter, `components`, `n_points` input rows, `hidden` weighted points, tiles.
    Read as TiledShape is by `alphascoop info --tiled`."""

    dim: int
    ambient_dim: int
    weighted: bool
    alpha: float
    alpha2: float
    classes: tuple[tuple[int, int, int], ...]
    measure: float
    boundary_measure: float
    components: int
    n_points: int
    hidden: int
    n_tiles: int

    def counts(self) -> dict[str, dict[str, int]]:
        """Simplices per dimension and class, as TiledShape.counts gives them."""
        return {_NAMES[k]: dict(zip(("singular", "regular", "interior"), c, strict=True))
                for k, c in enumerate(self.classes)}

    def euler(self) -> int:
        """Euler characteristic of the complex: sum over k of (-1)^k n_k."""
        return int(sum((-1) ** k * sum(c) for k, c in enumerate(self.classes)))

    def betti(self) -> list[int] | None:
        """Betti numbers in 2D (components, holes); None in 3D (TiledShape.betti)."""
        return [self.components, self.components - self.euler()] if self.dim == 2 else None


class Components:
    """Connected components of the vertices of n input rows joined by edges, fed a tile's
    edges at a time: a union-find whose roots are the smallest row of their component (a
    root points at a smaller one when two join), so a tile costs its edges, not n."""

    def __init__(self, n: int) -> None:
        self.parent = np.arange(n, dtype=np.int64)
        self.vertex = np.zeros(n, dtype=bool)

    def find(self, rows: np.ndarray) -> np.ndarray:
        """(r,) the root of each row (and those rows then point at it directly)."""
        root = self.parent[rows]
        while True:
            up = self.parent[root]
            if np.array_equal(up, root):
                break
            root = up
        self.parent[rows] = root
        return root

    def add(self, vertices: np.ndarray, edges: np.ndarray) -> None:
        """Mark (v,) vertex rows and join the (e, 2) edges' ends."""
        self.vertex[vertices] = True
        if len(edges) == 0:
            return
        roots, inverse = np.unique(self.find(np.ravel(edges)), return_inverse=True)
        pairs = inverse.reshape(-1, 2)
        graph = coo_matrix((np.ones(len(pairs), dtype=np.int8), (pairs[:, 0], pairs[:, 1])),
                           shape=(len(roots), len(roots)))
        _, group = connected_components(graph, directed=False)
        least = np.full(group.max() + 1, np.iinfo(np.int64).max, dtype=np.int64)
        np.minimum.at(least, group, roots)  # the smallest root of each group
        moved = roots != least[group]
        self.parent[roots[moved]] = least[group[moved]]

    def count(self) -> int:
        """Components among the marked vertices: the marked roots (a row is a root exactly
        where it is its own parent), counted a block of rows at a time so that no (n,)
        temporary joins the union-find's arrays."""
        total = 0
        for start in range(0, len(self.parent), COUNT_BLOCK):
            stop = min(start + COUNT_BLOCK, len(self.parent))
            own = self.parent[start:stop] == np.arange(start, stop, dtype=np.int64)
            total += int(np.count_nonzero(own & self.vertex[start:stop]))
        return total


def summarize_tiles(results: Iterable[Mapping[str, np.ndarray]], *, dim: int,
                    ambient_dim: int, n_rows: int, alpha: float, alpha2: float,
                    weighted: bool) -> TiledSummary:
    """The summary of the tiles' owned simplices (input rows below `n_rows`), one tile's
    result held at a time: each given as its arrays (TileResult.to_arrays names; an open
    .npz is read only for the classes, the edges, the vertices and the numbers)."""
    classes = np.zeros((dim + 1, 3), dtype=np.int64)
    measure = boundary = 0.0
    n_points = hidden = n_tiles = 0
    joined = Components(n_rows)
    for arrays in results:
        for k in range(dim + 1):
            classes[k] += np.bincount(arrays[f"classes{k}"], minlength=4)[1:4]
        joined.add(arrays["vertex_ids"], arrays["simplices1"])
        numbers = arrays["numbers"]  # TileResult.to_arrays: measure, boundary, points, hidden
        measure += float(numbers[0])
        boundary += float(numbers[1])
        n_points += int(numbers[2])
        hidden += int(numbers[3])
        n_tiles += 1
    return TiledSummary(dim, ambient_dim, weighted, float(alpha), float(alpha2),
                        tuple(tuple(int(x) for x in row) for row in classes), measure,
                        boundary, joined.count(), n_points, hidden, n_tiles)

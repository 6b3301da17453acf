"""A merged tiled shape seen as the complex and shape core.export writes: the exporters
(PLY, OBJ, STL, VTU, GeoJSON, ...) run unchanged on it.

The "complex" holds only the members at alpha (the tiles never see the whole
triangulation): its simplices are the shape's, and a facet's missing neighbour cell is the
outside. That is all the writers need: the surface, the polygons, the manifold split across
the solid's wedges, and the VTU blocks (intervals above alpha are NaN).
"""

from __future__ import annotations

import numpy as np

from core.arrays import readonly, row_index
from core.tiled.merge import TiledShape


class MergedShape:
    """The shape's classes as core.shape.AlphaShape names them (read-only arrays)."""

    def __init__(self, merged: TiledShape, facets_in_order: np.ndarray) -> None:
        self._m = merged
        self.alpha = merged.alpha
        self.alpha2 = merged.alpha2
        self.dim = merged.dim
        self.points = merged.points
        self.measure = merged.measure
        classes = merged.classes[merged.dim - 1]
        self.regular_facet_ids = readonly(np.flatnonzero(classes == 2))
        self.regular_facets = readonly(facets_in_order)
        self.cell_ids = readonly(np.arange(len(merged.simplices[merged.dim])))
        self.cells = merged.simplices[merged.dim]
        self.boundary_facets = readonly(merged.simplices[merged.dim - 1][classes <= 2])

    def singular_ids(self, k: int) -> np.ndarray:
        """(s,) rows of the k-simplices that are SINGULAR."""
        return readonly(np.flatnonzero(self._m.classes[k] == 1))

    def singular(self, k: int) -> np.ndarray:
        """(s, k+1) SINGULAR k-simplices."""
        return readonly(self._m.simplices[k][self.singular_ids(k)])


class MergedComplex:
    """What core.export reads of a complex, for a merged tiled shape."""

    def __init__(self, merged: TiledShape) -> None:
        self.merged = merged
        self.dim = merged.dim
        self.ambient_dim = merged.ambient_dim
        self.frame = merged.frame
        self.points = merged.points
        self.mode = None
        #: Weighted shapes: an empty array (exports only ask whether there are weights).
        self.weights = np.empty(0) if merged.weighted else None
        #: The input rows hidden by heavier balls (exports count them), as -1 entries.
        self.input_index = np.full(merged.hidden, -1, dtype=np.int64)
        betti = merged.betti()
        self.betti = None if betti is None else (lambda *a, **k: betti)
        self._face_ids: dict[int, np.ndarray] = {}
        regular = merged.regular
        order = np.argsort(row_index(merged.simplices[self.dim - 1], np.sort(regular, axis=1)))
        self._shape = MergedShape(merged, readonly(regular[order]))

    def shape(self, alpha: float | None = None, *, alpha2: float | None = None) -> MergedShape:
        """The merged shape (it exists at its own alpha only)."""
        return self._shape

    def simplices(self, k: int) -> np.ndarray:
        """(n_k, k+1) member k-simplices."""
        return self.merged.simplices[k]

    def intervals(self, k: int) -> np.ndarray:
        """(n_k, 3) enter/regular/interior of the members (NaN above alpha)."""
        return self.merged.intervals[k]

    def to_ambient(self, coords: np.ndarray) -> np.ndarray:
        """Complex coordinates to the input space."""
        return self.merged.to_ambient(coords)

    def face_ids(self, k: int) -> np.ndarray:
        """(n_k, k+1) row in simplices(k-1) of the face opposite each vertex."""
        if k not in self._face_ids:
            s = self.simplices(k)
            faces = np.concatenate([np.delete(s, i, axis=1) for i in range(k + 1)])
            rows = row_index(self.simplices(k - 1), faces)
            self._face_ids[k] = readonly(rows.reshape(k + 1, -1).T)
        return self._face_ids[k]

    def facet_cells(self) -> np.ndarray:
        """(n_facets, 2) member cells on both sides of each member facet (-1: outside)."""
        faces = self.face_ids(self.dim)
        out = np.full((len(self.simplices(self.dim - 1)), 2), -1, dtype=np.int64)
        flat = faces.ravel()
        cells = np.repeat(np.arange(len(faces)), self.dim + 1)
        order = np.argsort(flat, kind="stable")
        flat, cells = flat[order], cells[order]
        second = np.r_[False, flat[1:] == flat[:-1]]
        out[flat[~second], 0] = cells[~second]
        out[flat[second], 1] = cells[second]
        return readonly(out)

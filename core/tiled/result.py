"""What a tile hands to the merge: its owned simplices in global ids, and how local points
get their global id."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Global vertex id of a local point no input row maps to (hidden weighted points).
NO_ID = np.iinfo(np.int64).max


@dataclass(frozen=True)
class TileResult:
    """What a tile owns at alpha, in global vertex ids (input rows; a merged duplicate is
    its first row). Per dimension k: `simplices[k]` (n_k, k+1) int64 rows ascending,
    `classes[k]` (n_k,) int8 (1 singular, 2 regular, 3 interior) and `intervals[k]`
    (n_k, 3) float64 enter/regular/interior (values above alpha are NaN: a tile cannot
    know them). `regular` (r, dim) int64 REGULAR facets oriented away from their cell;
    `vertex_ids` (v,) / `vertex_coords` (v, dim) every vertex the kept simplices use;
    `measure` volume (3D) or area (2D) of the kept cells, `boundary` area (3D) or length
    (2D) of the kept REGULAR facets; `points` and `hidden` count the core's input rows."""

    simplices: tuple[np.ndarray, ...]
    classes: tuple[np.ndarray, ...]
    intervals: tuple[np.ndarray, ...]
    regular: np.ndarray
    vertex_ids: np.ndarray
    vertex_coords: np.ndarray
    measure: float
    boundary: float
    points: int
    hidden: int

    def to_arrays(self) -> dict[str, np.ndarray]:
        """The result as named arrays (np.savez; read back by from_arrays)."""
        out = {"regular": self.regular, "vertex_ids": self.vertex_ids,
               "vertex_coords": self.vertex_coords,
               "numbers": np.array([self.measure, self.boundary, self.points, self.hidden],
                                   dtype=np.float64)}
        for k, (s, c, iv) in enumerate(zip(self.simplices, self.classes, self.intervals,
                                           strict=True)):
            out[f"simplices{k}"], out[f"classes{k}"], out[f"intervals{k}"] = s, c, iv
        return out

    @classmethod
    def from_arrays(cls, arrays) -> TileResult:
        """A result from `to_arrays`'s names (an np.load of the saved file)."""
        dim = arrays["regular"].shape[1]
        numbers = arrays["numbers"]
        return cls(tuple(arrays[f"simplices{k}"] for k in range(dim + 1)),
                   tuple(arrays[f"classes{k}"] for k in range(dim + 1)),
                   tuple(arrays[f"intervals{k}"] for k in range(dim + 1)),
                   arrays["regular"], arrays["vertex_ids"], arrays["vertex_coords"],
                   float(numbers[0]), float(numbers[1]), int(numbers[2]), int(numbers[3]))


def global_ids(input_index: np.ndarray, rows: np.ndarray, m: int) -> np.ndarray:
    """(m,) int64 smallest input row of each of the m local points (NO_ID: none)."""
    ids = np.full(m, NO_ID, dtype=np.int64)
    seen = input_index >= 0
    np.minimum.at(ids, input_index[seen], rows[seen])
    return ids

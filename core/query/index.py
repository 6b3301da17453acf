"""TableIndex: the interval table and the per-alpha lookups built on it, frozen and public.

Every query at one alpha (core/query/shape.py), the moving alpha of core/query/cursor.py, the files
of core/storage/tables.py and the curves of core/topology/signatures.py read the table through this
object, handed to them explicitly. Its arrays are read-only; the derived ones (oriented facets, the
facets by interior, cumulative measures, the spectrum, stacked intervals) are computed on
first use and kept.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from core.arrays import first_cofaces, readonly
from core.build.levels import Level, Table
from core.parallel import take


def facing_out(facets: np.ndarray, flip: np.ndarray, inside_second: np.ndarray | bool,
               out: np.ndarray | None = None) -> np.ndarray:
    """(f, dim) int32 facets facing out of the cell inside them (3D: normal (b-a)x(c-a)
    points out; 2D: the inside lies left of a->b). A stored facet faces out of its cell 0
    unless `flip` ((f,) bool); out of its cell 1 (`inside_second`) it is the reverse.
    Written into `out` when given."""
    out = np.array(facets, dtype=np.int32) if out is None else out
    if out is not facets:
        out[:] = facets
    reverse = flip ^ inside_second
    last = out[:, -1].copy()  # the last two columns swapped where reverse, without a gather
    np.copyto(out[:, -1], out[:, -2], where=reverse)
    np.copyto(out[:, -2], last, where=reverse)
    return out


def oriented_facets(facets: np.ndarray, flip: np.ndarray) -> np.ndarray:
    """(2 f, dim) int32 from (f, dim) facets: row 2i is facet i facing out of its cell 0, row
    2i+1 out of its cell 1, so orienting any facets is a single gather."""
    out = np.empty((2 * len(facets), facets.shape[1]), dtype=np.int32)
    for side in (0, 1):
        facing_out(facets, flip, bool(side), out[side::2])
    return out


@dataclass(frozen=True, eq=False)
class TableIndex:
    """The interval table of a complex (core/build/table.py) and what queries look up in it.

    `table`: the levels (simplices sorted by enter and their enter/regular/interior values),
    facet-cell adjacency, cell measures, facet order by interior; `weighted`: values are
    signed radii and the vertices enter at their own values (not all at 0); `known_spectrum`:
    the spectrum when it is already known (saved with the signatures), else None.
    """

    table: Table
    weighted: bool = False
    known_spectrum: np.ndarray | None = field(default=None, repr=False)
    _intervals: dict = field(default_factory=dict, init=False, repr=False)
    _first_cofaces: dict = field(default_factory=dict, init=False, repr=False)

    def __post_init__(self) -> None:
        for level in self.table.levels:
            for arr in (level.simplices, level.enter, level.regular, level.interior,
                        level.face_ids):
                if arr is not None:
                    readonly(arr)
        for arr in (self.table.facet_cells, self.table.facet_flip, self.table.cell_measure,
                    self.table.facet_order):
            if arr is not None:  # the facet order is sorted, read-only, on first use
                readonly(arr)

    @property
    def dim(self) -> int:
        """2 or 3: the dimension of the cells."""
        return len(self.table.levels) - 1

    def level(self, k: int) -> Level:
        """The k-simplices and their values; ValueError unless 0 <= k <= dim."""
        if not 0 <= k <= self.dim:
            raise ValueError(f"k must be between 0 and {self.dim}, not {k}")
        return self.table.levels[k]

    def simplices(self, k: int) -> np.ndarray:
        """(n_k, k+1) int32 k-simplices, rows ascending, sorted by enter."""
        return self.level(k).simplices

    def intervals(self, k: int) -> np.ndarray:
        """(n_k, 3) float64 enter <= regular <= interior (stacked on first use, kept)."""
        if k not in self._intervals:
            level = self.level(k)
            self._intervals[k] = readonly(np.stack((level.enter, level.regular,
                                                    level.interior), axis=1))
        return self._intervals[k]

    def face_ids(self, k: int) -> np.ndarray:
        """(n_k, k+1) int32 row in simplices(k-1) of the face opposite each vertex (k >= 1)."""
        if k < 1:
            raise ValueError("vertices have no faces: k must be >= 1")
        return self.level(k).face_ids

    def first_cofaces(self, k: int) -> np.ndarray:
        """(n_{k-1},) int32 lowest row of simplices(k) that has each (k-1)-simplex as a face
        (n_k: none); shared by the topology's forests and the opening alpha, kept."""
        if k not in self._first_cofaces:
            self._first_cofaces[k] = readonly(first_cofaces(self.face_ids(k),
                                                            len(self.level(k - 1).enter)))
        return self._first_cofaces[k]

    def facet_cells(self) -> np.ndarray:
        """(n_{dim-1}, 2) int32 the cells on both sides of each facet, -1 = outside."""
        return self.table.facet_cells

    def cell_measures(self) -> np.ndarray:
        """(n_dim,) float64 volume (3D) or area (2D) of every cell."""
        return self.table.cell_measure

    def counts(self) -> tuple[int, ...]:
        """Number of simplices per dimension, vertices first."""
        return tuple(len(level.enter) for level in self.table.levels)

    def entered(self, k: int, at: float) -> int:
        """Number of k-simplices with enter <= at (a prefix for k >= 1: sorted by enter)."""
        return int(np.searchsorted(self.level(k).enter, at, side="right"))

    def spectrum(self) -> np.ndarray:
        """(s,) float64 sorted distinct values where the complex changes (0 first; weighted:
        the vertices' values)."""
        return self._spectrum

    def last_value(self) -> float:
        """The spectrum's last (largest) value, without sorting all values for it."""
        if self.known_spectrum is not None:
            return float(self.known_spectrum[-1])
        levels = self.table.levels
        tops = [float(np.max(lv.enter)) for lv in levels[0 if self.weighted else 1:]
                if len(lv.enter)]
        return max(tops, default=0.0) if self.weighted else max([0.0, *tops])

    @cached_property
    def _spectrum(self) -> np.ndarray:
        if self.known_spectrum is not None:
            return readonly(self.known_spectrum)
        levels = self.table.levels
        first = [levels[0].enter] if self.weighted else [[0.0]]
        values = np.concatenate(first + [lv.enter for lv in levels[1:]])
        values.sort(kind="stable")  # levels k >= 1 are sorted by enter: a merge of runs
        keep = np.empty(len(values), dtype=bool)
        keep[0] = True
        np.not_equal(values[1:], values[:-1], out=keep[1:])
        return readonly(values[keep])

    @cached_property
    def oriented_facets(self) -> np.ndarray:
        """(2 n_facets, dim) int32 every facet facing out of its cell 0 (row 2i) and out of
        its cell 1 (row 2i+1); see `oriented_facets`."""
        return readonly(oriented_facets(self.table.levels[self.dim - 1].simplices,
                                        self.table.facet_flip))

    @cached_property
    def facet_cell0(self) -> np.ndarray:
        """(n_facets,) int32 contiguous first column of facet_cells (orientation lookups)."""
        return readonly(np.ascontiguousarray(self.table.facet_cells[:, 0]))

    @cached_property
    def facets_by_interior(self) -> tuple[np.ndarray, np.ndarray]:
        """Facet interior and enter values in ascending interior order (contiguous, for scans
        of the facets not yet interior)."""
        facets = self.table.levels[self.dim - 1]
        return (self.interiors_sorted,
                readonly(take(facets.enter, self.table.facet_interior_order)))

    @cached_property
    def interiors_sorted(self) -> np.ndarray:
        """(n_facets,) float64 the facets' interior values in ascending order (by
        facet_interior_order): all a slider cursor needs of facets_by_interior."""
        facets = self.table.levels[self.dim - 1]
        return readonly(take(facets.interior, self.table.facet_interior_order))

    @cached_property
    def cumulative_measure(self) -> np.ndarray:
        """(n_dim,) float64 measure of the first j+1 cells (by enter), at j."""
        return readonly(np.cumsum(self.table.cell_measure))

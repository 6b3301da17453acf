"""Arrays of a saved table (format version 3) that are not stored but derived from the
stored ones, each in one vectorized pass: a facet's regular and interior from its cells'
enter values, face ids from the vertices' rows and `facet_slots`, the spectrum and the volume
curve from the enter values and cell measures (core/storage/compact.py uses them)."""

from __future__ import annotations

from collections.abc import Callable, Mapping

import numpy as np

from core.parallel import searchsorted_ascending
from core.storage import steps

CELLS_IN = " cells in"  # unpack's scratch entry (no member has a space in its name)


def dim_of(a: Mapping[str, np.ndarray]) -> int:
    """The table's dimension."""
    return int(a["dim"])


def _regular(k: int) -> Callable[[Mapping], np.ndarray]:
    def derive(a: Mapping) -> np.ndarray:
        dim = dim_of(a)
        if k == dim:
            return a[f"enter_{k}"]
        return a[f"enter_{dim}"][a["facet_cells"][:, 0]]  # cell 0: the lower-numbered one
    return derive


def _interior(k: int) -> Callable[[Mapping], np.ndarray]:
    def derive(a: Mapping) -> np.ndarray:
        dim = dim_of(a)
        if k == dim:
            return a[f"enter_{k}"]
        second = a["facet_cells"][:, 1]  # the later of a facet's cells (-1: on the hull)
        out = a[f"enter_{dim}"][second]
        out[second < 0] = np.inf
        return out
    return derive


def _face_ids_1(a: Mapping) -> np.ndarray:
    vertices = a["simplices_0"][:, 0]
    row = np.empty(len(vertices), dtype=np.int32)
    row[vertices] = np.arange(len(vertices), dtype=np.int32)
    return row[a["simplices_1"][:, ::-1]]


def _face_ids_top(a: Mapping) -> np.ndarray:
    """The cells' face ids from facet_cells and `facet_slots` (which vertex of each of its
    cells a facet is opposite: 2 bits per side); -1 where no facet names a slot."""
    dim = dim_of(a)
    cells, slots = a["facet_cells"], a["facet_slots"]
    out = np.full((len(a[f"simplices_{dim}"]), dim + 1), -1, dtype=np.int32)
    flat = out.reshape(-1)
    for lo in range(0, len(cells), steps.STRETCH):
        part, slot = cells[lo:lo + steps.STRETCH], slots[lo:lo + steps.STRETCH]
        rows = np.arange(lo, lo + len(part), dtype=np.int32)
        for side in (0, 1):
            at = part[:, side].astype(np.intp)
            at *= dim + 1
            at += (slot >> 2 * side) & 3
            if side:
                has = part[:, 1] >= 0
                at, rows = at[has], rows[has]
            flat[at] = rows
    return out


def facet_slots(face_ids: np.ndarray, facet_cells: np.ndarray) -> np.ndarray:
    """(f,) uint8 for each facet the column of its cell 0 (bits 0-1) and of its cell 1 (bits
    2-3) that it is opposite (face_ids: the cells' (c, dim + 1) facet rows)."""
    width = face_ids.shape[1]
    facets = face_ids.reshape(-1)
    column = np.tile(np.arange(width, dtype=np.uint8), len(face_ids))
    cell = np.repeat(np.arange(len(face_ids), dtype=np.int32), width)
    second = facet_cells[facets, 1] == cell
    out = np.zeros(len(facet_cells), dtype=np.uint8)
    out[facets[~second]] = column[~second]
    out[facets[second]] |= column[second] << 2
    return out


def _sig_alphas(a: Mapping) -> np.ndarray:
    values = a["enter_values"]
    if "enter_steps_0" in a:  # the vertices' values (0, classic) are among them
        return values
    return np.union1d(a["enter_0"], values)


def cells_in(a: Mapping) -> np.ndarray:
    """(s,) number of cells in at each spectrum value (kept in `a` while unpacking)."""
    if CELLS_IN in a:
        return a[CELLS_IN]
    return searchsorted_ascending(a[f"enter_{dim_of(a)}"], a["sig_alphas"], "right")


def _sig_measure(a: Mapping) -> np.ndarray:
    measure = np.asarray(a["cell_measure"])
    counts = cells_in(a)
    if isinstance(a, dict):
        a[CELLS_IN] = counts
    cumulative = np.empty(len(measure) + 1)
    cumulative[0] = 0.0
    np.cumsum(measure, out=cumulative[1:])
    return np.take(cumulative, counts)


Derivation = tuple[tuple[str, ...], Callable[[Mapping], np.ndarray]]
SIGNATURES = ("sig_betti", "sig_betti_steps")  # either is there when the signatures are


def derivations(dim: int) -> dict[str, Derivation]:
    """Derivable arrays in the order they are derived: name -> (any of these is there when
    it was saved, how)."""
    out: dict[str, Derivation] = {"face_ids_1": (("simplices_1",), _face_ids_1),
                                  f"face_ids_{dim}": (("facet_slots",), _face_ids_top)}
    for k in (dim, dim - 1):  # the lower faces' are ranks (_pack_ranks)
        out[f"regular_{k}"] = ((f"enter_{k}",), _regular(k))
        out[f"interior_{k}"] = ((f"enter_{k}",), _interior(k))
    out["sig_alphas"] = (SIGNATURES, _sig_alphas)
    out["sig_measure"] = (SIGNATURES, _sig_measure)
    return out

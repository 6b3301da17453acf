"""The compact layout of a saved table (format version 3): what is cheap to derive is not
stored, and what is stored is narrowed, so an entry takes under half the bytes (about 900 a
point on a scan, where every array stored took about 2,100).

`pack` turns the full arrays (core/storage/tables.py names them) into the members a file holds;
`unpack` turns them back, every array equal to the one packed (same dtype, same bits). Each
codec below replaces some arrays; `pack` keeps an array as it is whenever its codec does not
give it back exactly (a table of a mode whose values follow other rules, a weighted one), so
the layout is never lossy. Derived, in one vectorized pass each:
- a facet's regular and interior: the enter values of its cells 0 and 1 (cells are sorted
  by enter and cell 0 is the lower-numbered one; inf on the hull); a cell's are its enter;
- face_ids_1 from the vertices' rows; the cells' face ids from facet_cells and
  `facet_slots` (which vertex of each cell a facet is opposite, 2 bits a side);
- sig_alphas (the spectrum) from the enter values; sig_measure from the cell measures.
Narrowed (core/storage/steps.py): enter_k as steps in the rank of its value among
`enter_values`; regular_k and interior_k of the lower faces as int32 ranks among them;
simplices_k (k >= 1) as the first vertex and uint16 steps across the row; topology forests as
steps in rows of the level whose enter values they hold; sig_betti and sig_solid as int8 steps
along the spectrum; sig_boundary once per number of cells in; facet_flip as bits; input_index
and topo_dual_edges as int32. Kept as they are: points, simplices_0, face_ids_2 (3D),
facet_cells, cell_measure, facet_interior_order and the small ones.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

import numpy as np

from core.parallel import both, searchsorted_ascending
from core.storage import steps

Arrays = dict[str, np.ndarray]
FORESTS = (("topo_vertex_forest", lambda dim: 1), ("topo_dual_forest", lambda dim: dim - 1),
           ("topo_solid_forest", lambda dim: dim))
NARROW_INTS = ("input_index", "topo_dual_edges")  # int64 -> int32 when they fit
CELLS_IN = " cells in"  # unpack's scratch entry (no member has a space in its name)


def _dim(a: Mapping[str, np.ndarray]) -> int:
    return int(a["dim"])


def _same(a: np.ndarray, b: np.ndarray) -> bool:
    """Exactly the same array: dtype, shape and bits (inf and NaN included)."""
    a, b = np.asarray(a), np.asarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


# --- derived arrays: name -> (needs, derive(a) -> array) --------------------------------------
def _regular(k: int) -> Callable[[Mapping], np.ndarray]:
    def derive(a: Mapping) -> np.ndarray:
        dim = _dim(a)
        if k == dim:
            return a[f"enter_{k}"]
        return a[f"enter_{dim}"][a["facet_cells"][:, 0]]  # cell 0: the lower-numbered one
    return derive


def _interior(k: int) -> Callable[[Mapping], np.ndarray]:
    def derive(a: Mapping) -> np.ndarray:
        dim = _dim(a)
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
    dim = _dim(a)
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


def _cells_in(a: Mapping) -> np.ndarray:
    """(s,) number of cells in at each spectrum value (kept in `a` while unpacking)."""
    if CELLS_IN in a:
        return a[CELLS_IN]
    return searchsorted_ascending(a[f"enter_{_dim(a)}"], a["sig_alphas"], "right")


def _sig_measure(a: Mapping) -> np.ndarray:
    measure = np.asarray(a["cell_measure"])
    cells_in = _cells_in(a)
    if isinstance(a, dict):
        a[CELLS_IN] = cells_in
    cumulative = np.empty(len(measure) + 1)
    cumulative[0] = 0.0
    np.cumsum(measure, out=cumulative[1:])
    return np.take(cumulative, cells_in)


Derivation = tuple[tuple[str, ...], Callable[[Mapping], np.ndarray]]
SIGNATURES = ("sig_betti", "sig_betti_steps")  # either is there when the signatures are


def _derived(dim: int) -> dict[str, Derivation]:
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


# --- narrowed arrays ------------------------------------------------------------------------
def _pack_enter(a: Mapping, out: Arrays) -> None:
    """enter_k of every ascending level as steps in the rank of its value."""
    dim = _dim(a)
    levels = [k for k in range(dim + 1) if _ascending(a[f"enter_{k}"])]
    if not levels:
        return
    values = np.unique(np.concatenate([a[f"enter_{k}"] for k in levels]))
    out["enter_values"] = values
    for k in levels:
        rank = np.searchsorted(values, a[f"enter_{k}"])
        out[f"enter_steps_{k}"], out[f"enter_far_{k}"] = steps.encode_sorted(rank)
        del out[f"enter_{k}"]


def _ascending(values: np.ndarray) -> bool:
    return values.dtype == np.float64 and values.ndim == 1 and not np.isnan(values).any() and (
        len(values) < 2 or bool(np.all(values[1:] >= values[:-1])))


def _pack_ranks(a: Mapping, out: Arrays) -> None:
    """regular_k and interior_k below the facets as int32 ranks among the enter values
    (their values are enter values of cofaces, interior inf on the hull: rank len(values))."""
    if "enter_values" not in out:
        return
    values = np.append(out["enter_values"], np.inf)
    for k in range(_dim(a) - 1):
        for name in (f"regular_{k}", f"interior_{k}"):
            rank = np.searchsorted(values, a[name])
            if len(rank) and int(rank.max()) < len(values) and _same(values[rank], a[name]):
                out[f"{name}_ranks"] = rank.astype(np.int32)
                del out[name]


def _unpack_ranks(a: Arrays) -> None:
    if "enter_values" not in a:
        return
    values = np.append(a["enter_values"], np.inf)
    for k in range(_dim(a) - 1):
        for name in (f"regular_{k}", f"interior_{k}"):
            if f"{name}_ranks" in a:
                a[name] = values[a.pop(f"{name}_ranks")]


def _unpack_enter(a: Arrays) -> None:
    for k in range(_dim(a) + 1):
        if f"enter_steps_{k}" in a:
            a[f"enter_{k}"] = steps.take_sorted(a[f"enter_steps_{k}"], a.pop(f"enter_far_{k}"),
                                                a["enter_values"])


def _pack_simplices(a: Mapping, out: Arrays) -> None:
    """simplices_k (k >= 1): the first vertex and uint16 steps across each row."""
    for k in range(1, _dim(a) + 1):
        rows = a[f"simplices_{k}"]
        if rows.dtype != np.int32 or rows.ndim != 2:
            continue
        out[f"simplices_first_{k}"] = np.ascontiguousarray(rows[:, 0])
        out[f"simplices_steps_{k}"], out[f"simplices_far_{k}"] = steps.encode(
            np.diff(rows, axis=1), np.uint16)
        del out[f"simplices_{k}"]


def _unpack_simplices(a: Arrays) -> None:
    for k in range(1, _dim(a) + 1):
        if f"simplices_first_{k}" in a:
            a[f"simplices_{k}"] = steps.cumulative_rows(
                a.pop(f"simplices_first_{k}"), a.pop(f"simplices_steps_{k}"),
                a.pop(f"simplices_far_{k}"))


def _pack_forests(a: Mapping, out: Arrays) -> None:
    """Each topology forest as steps in the rows of the level whose enter values it holds."""
    dim = _dim(a)
    for name, level in FORESTS:
        if name not in a:
            continue
        enter = a[f"enter_{level(dim)}"]
        if not _ascending(enter):
            continue
        rows = np.searchsorted(enter, a[name])
        if len(rows) and (rows[-1] >= len(enter) or not _same(enter[rows], a[name])):
            continue
        out[f"{name}_steps"], out[f"{name}_far"] = steps.encode_sorted(rows)
        del out[name]


def _unpack_forests(a: Arrays) -> None:
    dim = _dim(a)
    for name, level in FORESTS:
        if f"{name}_steps" in a:
            a[name] = steps.take_sorted(a.pop(f"{name}_steps"), a.pop(f"{name}_far"),
                                        a[f"enter_{level(dim)}"])


def _pack_signatures(a: Mapping, out: Arrays) -> None:
    """sig_betti and sig_solid as int8 steps along the spectrum (one row per curve, so that
    each sums up contiguously); sig_boundary once per run of equal cell counts (it is a
    function of the cells in)."""
    if "sig_betti" not in a:
        return
    for name in ("sig_betti", "sig_solid"):
        curves = np.asarray(a[name]).reshape(len(a[name]), -1).T
        out[f"{name}_steps"], out[f"{name}_far"] = steps.encode(
            np.diff(curves, axis=1, prepend=np.zeros((len(curves), 1), curves.dtype)), np.int8)
        del out[name]
    starts = _run_starts(_cells_in(a))
    out["sig_boundary_runs"] = a["sig_boundary"][starts]
    del out["sig_boundary"]


def _run_starts(cells_in: np.ndarray) -> np.ndarray:
    if not len(cells_in):
        return np.zeros(0, dtype=np.int64)
    return np.flatnonzero(np.diff(cells_in, prepend=cells_in[0] - 1))


def _unpack_signatures(a: Arrays) -> None:
    for name in ("sig_betti", "sig_solid"):
        if f"{name}_steps" in a:
            curves = steps.cumulative_curves(a.pop(f"{name}_steps"), a.pop(f"{name}_far"))
            a[name] = curves if name == "sig_betti" else curves.reshape(-1)
    if "sig_boundary_runs" in a:
        a["sig_boundary"] = _by_run(_cells_in(a), a.pop("sig_boundary_runs"))


def _by_run(cells_in: np.ndarray, runs: np.ndarray) -> np.ndarray:
    """runs[j] for every entry of the j-th run of equal cells_in."""
    if not len(cells_in):
        return np.zeros(0, dtype=runs.dtype)
    change = np.empty(len(cells_in), dtype=np.intp)
    change[0] = 0
    np.not_equal(cells_in[1:], cells_in[:-1], out=change[1:])
    np.cumsum(change, out=change)
    return np.take(runs, change)


def _pack_small(a: Mapping, out: Arrays) -> None:
    """facet_flip as bits; input_index and topo_dual_edges as int32 when they fit."""
    out["facet_flip_bits"] = np.packbits(a["facet_flip"])
    del out["facet_flip"]
    for name in NARROW_INTS:
        if name in a and a[name].dtype == np.int64 and (
                a[name].size == 0 or int(np.abs(a[name]).max()) < 2**31 - 1):
            out[f"{name}_32"] = a[name].astype(np.int32)
            del out[name]


def _pack_slots(a: Mapping, out: Arrays) -> None:
    """facet_slots, from which the cells' face ids follow (_face_ids_top)."""
    dim = _dim(a)
    out["facet_slots"] = facet_slots(a[f"face_ids_{dim}"], a["facet_cells"])


def _unpack_small(a: Arrays) -> None:
    if "facet_flip_bits" in a:
        n_facets = len(a[f"simplices_{_dim(a) - 1}"])
        a["facet_flip"] = np.unpackbits(a.pop("facet_flip_bits"), count=n_facets).view(bool)
    for name in NARROW_INTS:
        if f"{name}_32" in a:
            a[name] = a.pop(f"{name}_32").astype(np.int64)


# --- the two directions -------------------------------------------------------------------
def pack(full: Mapping[str, np.ndarray]) -> Arrays:
    """The members of a version-3 file holding the table whose full arrays are `full`: every
    array `unpack` gives back exactly is left out or narrowed; any other is kept as is."""
    out = dict(full)
    for packer in (_pack_small, _pack_simplices, _pack_enter, _pack_ranks, _pack_forests,
                   _pack_signatures, _pack_slots):
        trial = dict(out)
        packer(full, trial)
        if _unpacks_to(trial, full):
            out = trial
    context = {**full, **out}
    for name, (_, derive) in _derived(_dim(full)).items():
        if name in full and _gives_back(derive, context, name):
            del out[name]
    return out if _unpacks_to(out, full) else dict(full)


def _gives_back(derive: Callable[[Mapping], np.ndarray], context: Mapping, name: str) -> bool:
    try:
        return _same(derive(context), context[name])
    except (IndexError, KeyError, TypeError, ValueError):
        return False


def _unpacks_to(members: Arrays, full: Mapping[str, np.ndarray]) -> bool:
    try:
        got = unpack(members)
    except (IndexError, KeyError, TypeError, ValueError):
        return False
    return set(got) == set(full) and all(_same(got[name], full[name]) for name in full)


def unpack(members: Mapping[str, np.ndarray]) -> Arrays:
    """The full arrays of a table from a version-3 file's members (a file that stores them all
    comes back as it is). KeyError, IndexError or ValueError for members that do not fit
    together (the caller's checks name them). The structure (simplices, face ids) and the
    values (intervals, topology, signatures) are unpacked at once, on two threads."""
    given = dict(members)
    dim = _dim(given)
    structure, values = both(lambda: _unpacked(given, STRUCTURE, dim),
                             lambda: _unpacked(given, VALUES, dim))
    kept = {name: array for name, array in structure.items()
            if name in values or name not in given}
    kept.update((name, array) for name, array in values.items() if name not in given)
    for name in ("enter_values", "facet_slots", CELLS_IN,
                 *(f"enter_steps_{k}" for k in range(dim + 1))):
        kept.pop(name, None)
    return kept


def _unpacked(given: Arrays, passes: tuple, dim: int) -> Arrays:
    """`given` (copied) after the passes of one group: unpack functions, then derived names."""
    a = dict(given)
    unpackers, derived = passes
    for unpacker in unpackers:
        unpacker(a)
    for name, (needs, derive) in _derived(dim).items():
        if derived(name) and name not in a and any(key in a for key in needs):
            a[name] = derive(a)
    if passes is VALUES:
        _unpack_signatures(a)
    return a


def _is_face_ids(name: str) -> bool:
    return name.startswith("face_ids_")


STRUCTURE = ((_unpack_simplices, _unpack_small), _is_face_ids)
VALUES = ((_unpack_enter, _unpack_ranks, _unpack_forests), lambda name: not _is_face_ids(name))

"""The compact layout of a saved table (format version 3): what is cheap to derive is not
stored, and what is stored is narrowed, so an entry takes under half the bytes (about 900 a
point on a scan, where every array stored took about 2,100).

`pack` turns the full arrays (core/storage/tables.py names them) into the members a file holds;
`unpack` turns them back, every array equal to the one packed (same dtype, same bits). Each
codec below replaces some arrays; `pack` keeps an array as it is whenever its codec does not
give it back exactly (a table of a mode whose values follow other rules, a weighted one), so
the layout is never lossy. Derived (core/storage/derived.py), one vectorized pass each:
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

from core.arrays import unique_sorted
from core.parallel import both
from core.storage import derived, steps
from core.storage.derived import CELLS_IN, derivations, dim_of, facet_slots

Arrays = dict[str, np.ndarray]
FORESTS = (("topo_vertex_forest", lambda dim: 1), ("topo_dual_forest", lambda dim: dim - 1),
           ("topo_solid_forest", lambda dim: dim))
NARROW_INTS = ("input_index", "topo_dual_edges")  # int64 -> int32 when they fit


def _same(a: np.ndarray, b: np.ndarray) -> bool:
    """Exactly the same array: dtype, shape and bits (inf and NaN included)."""
    a, b = np.asarray(a), np.asarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


# --- narrowed arrays ------------------------------------------------------------------------
def _pack_enter(a: Mapping, out: Arrays) -> None:
    """enter_k of every ascending level as steps in the rank of its value."""
    dim = dim_of(a)
    levels = [k for k in range(dim + 1) if _ascending(a[f"enter_{k}"])]
    if not levels:
        return
    values = unique_sorted(np.concatenate([a[f"enter_{k}"] for k in levels]), kind="stable")
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
    for k in range(dim_of(a) - 1):
        for name in (f"regular_{k}", f"interior_{k}"):
            rank = np.searchsorted(values, a[name])
            if len(rank) and int(rank.max()) < len(values) and _same(values[rank], a[name]):
                out[f"{name}_ranks"] = rank.astype(np.int32)
                del out[name]


def _unpack_ranks(a: Arrays) -> None:
    if "enter_values" not in a:
        return
    values = np.append(a["enter_values"], np.inf)
    for k in range(dim_of(a) - 1):
        for name in (f"regular_{k}", f"interior_{k}"):
            if f"{name}_ranks" in a:
                a[name] = values[a.pop(f"{name}_ranks")]


def _unpack_enter(a: Arrays) -> None:
    for k in range(dim_of(a) + 1):
        if f"enter_steps_{k}" in a:
            a[f"enter_{k}"] = steps.take_sorted(a[f"enter_steps_{k}"], a.pop(f"enter_far_{k}"),
                                                a["enter_values"])


def _pack_simplices(a: Mapping, out: Arrays) -> None:
    """simplices_k (k >= 1): the first vertex and uint16 steps across each row."""
    for k in range(1, dim_of(a) + 1):
        rows = a[f"simplices_{k}"]
        if rows.dtype != np.int32 or rows.ndim != 2:
            continue
        out[f"simplices_first_{k}"] = np.ascontiguousarray(rows[:, 0])
        out[f"simplices_steps_{k}"], out[f"simplices_far_{k}"] = steps.encode(
            np.diff(rows, axis=1), np.uint16)
        del out[f"simplices_{k}"]


def _unpack_simplices(a: Arrays) -> None:
    for k in range(1, dim_of(a) + 1):
        if f"simplices_first_{k}" in a:
            a[f"simplices_{k}"] = steps.cumulative_rows(
                a.pop(f"simplices_first_{k}"), a.pop(f"simplices_steps_{k}"),
                a.pop(f"simplices_far_{k}"))


def _pack_forests(a: Mapping, out: Arrays) -> None:
    """Each topology forest as steps in the rows of the level whose enter values it holds."""
    dim = dim_of(a)
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
    dim = dim_of(a)
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
    starts = _run_starts(derived.cells_in(a))
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
        a["sig_boundary"] = _by_run(derived.cells_in(a), a.pop("sig_boundary_runs"))


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
    dim = dim_of(a)
    out["facet_slots"] = facet_slots(a[f"face_ids_{dim}"], a["facet_cells"])


def _unpack_small(a: Arrays) -> None:
    if "facet_flip_bits" in a:
        n_facets = len(a[f"simplices_{dim_of(a) - 1}"])
        a["facet_flip"] = np.unpackbits(a.pop("facet_flip_bits"), count=n_facets).view(bool)
    for name in NARROW_INTS:
        if f"{name}_32" in a:
            a[name] = a.pop(f"{name}_32").astype(np.int64)


# --- the two directions -------------------------------------------------------------------
PACKERS = (_pack_small, _pack_simplices, _pack_enter, _pack_ranks, _pack_forests,
           _pack_signatures, _pack_slots)


def pack(full: Mapping[str, np.ndarray]) -> Arrays:
    """The members of a version-3 file holding the table whose full arrays are `full`: every
    array `unpack` gives back exactly is left out or narrowed; any other is kept as is.

    Every codec at once, checked by one unpack, is the usual case; only a table one of them
    does not give back (a mode's values, weighted vertices) tries them one by one."""
    out = dict(full)
    for packer in PACKERS:
        packer(full, out)
    out = without_derived(full, out)
    if unpacks_to(out, full):
        return out
    out = dict(full)
    for packer in PACKERS:
        trial = dict(out)
        packer(full, trial)
        if unpacks_to(trial, full):
            out = trial
    out = without_derived(full, out)
    return out if unpacks_to(out, full) else dict(full)


def without_derived(full: Mapping[str, np.ndarray], out: Arrays) -> Arrays:
    """`out` without the arrays a derivation gives back exactly."""
    context, ways = {**full, **out}, derivations(dim_of(full))
    return {name: array for name, array in out.items()
            if not (name in ways and name in full
                    and _gives_back(ways[name][1], context, name))}


def _gives_back(derive: Callable[[Mapping], np.ndarray], context: Mapping, name: str) -> bool:
    try:
        return _same(derive(context), context[name])
    except (IndexError, KeyError, TypeError, ValueError):
        return False


def unpacks_to(members: Arrays, full: Mapping[str, np.ndarray]) -> bool:
    """Whether `members` unpack to exactly the arrays `full` (members unpack rejects: no)."""
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
    dim = dim_of(given)
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
    unpackers, derived_here = passes
    for unpacker in unpackers:
        unpacker(a)
    for name, (needs, derive) in derivations(dim).items():
        if derived_here(name) and name not in a and any(key in a for key in needs):
            a[name] = derive(a)
    if passes is VALUES:
        _unpack_signatures(a)
    return a


def _is_face_ids(name: str) -> bool:
    return name.startswith("face_ids_")


STRUCTURE = ((_unpack_simplices, _unpack_small), _is_face_ids)
VALUES = ((_unpack_enter, _unpack_ranks, _unpack_forests), lambda name: not _is_face_ids(name))

"""Small array helpers shared by the core."""

from __future__ import annotations

import numpy as np


def ascends(values: np.ndarray) -> bool:
    """Whether the (n,) values are already in ascending order."""
    return len(values) < 2 or bool(np.all(values[1:] >= values[:-1]))


def readonly(arr: np.ndarray) -> np.ndarray:
    """`arr` with its writeable flag cleared (a widget must not corrupt the table)."""
    arr.flags.writeable = False
    return arr


def contiguous_readonly(arr: np.ndarray) -> np.ndarray:
    """`arr` as a C-contiguous read-only array (copied only when it is not contiguous)."""
    arr = np.ascontiguousarray(arr)
    arr.flags.writeable = False
    return arr


def owned_readonly(arr: np.ndarray) -> np.ndarray:
    """`arr` as a read-only C-contiguous array owning its memory (a view is copied, so no
    writeable base can change it); no copy when it already is one."""
    if not arr.flags.writeable and arr.flags.c_contiguous:
        return arr
    if arr.base is not None or not arr.flags.c_contiguous:
        arr = np.array(arr, order="C")
    arr.flags.writeable = False
    return arr


def first_cofaces(face_ids: np.ndarray, n_faces: int) -> np.ndarray:
    """(n_faces,) int32 lowest row of the (c, k + 1) `face_ids` (each coface's k + 1 face rows)
    that holds each face; c for a face in no coface."""
    first = np.full(n_faces, len(face_ids), dtype=np.int32)
    rows = np.arange(len(face_ids), dtype=np.int32)
    for column in range(face_ids.shape[1]):
        np.minimum.at(first, face_ids[:, column], rows)
    return first


def row_index(table: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """(q,) int64: the index of the first row of the (t, c) int `table` equal to each of the
    (q, c) int `rows`, -1 where none is. One stable lexsort of both (no hashing of rows;
    np.unique(axis=0) costs 2.6x the CPU)."""
    both = np.concatenate((table, rows))
    order = np.lexsort(both.T[::-1])  # stable: equal rows side by side, the table's first
    ordered = both[order]
    start = np.ones(len(both), dtype=bool)
    start[1:] = (ordered[1:] != ordered[:-1]).any(axis=1)
    head = order[start]  # each run of equal rows starts with its first table row, if any
    found = np.where(head < len(table), head, -1).astype(np.int64)
    out = np.empty(len(both), dtype=np.int64)
    out[order] = found[np.cumsum(start) - 1]
    return out[len(table):]


def unique_sorted(values: np.ndarray, kind: str | None = None) -> np.ndarray:
    """The sorted distinct values of an array without NaN, flattened: np.unique(values), by
    one sort and a mask. numpy 2.4's np.unique hashes integers (4-15x slower when most are
    distinct); kind="stable" sorts an array made of a few ascending runs by merging them."""
    ordered = np.sort(values, axis=None, kind=kind)
    keep = np.empty(len(ordered), dtype=bool)
    keep[:1] = True
    np.not_equal(ordered[1:], ordered[:-1], out=keep[1:])
    return ordered[keep]


def compact_ids(ids: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """(u,) int64 the ids in range(n) that occur in `ids`, ascending, and for each of `ids`
    (same shape) its row among them: np.unique(ids, return_inverse=True) by a mask over
    range(n) and its running count, no sort."""
    used = np.zeros(n, dtype=bool)
    used[ids] = True
    rows = np.cumsum(used, dtype=np.int64) - 1
    return np.flatnonzero(used), rows[ids]

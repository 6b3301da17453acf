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

"""Small array helpers shared by the core."""

from __future__ import annotations

import numpy as np


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


def split_index(values: np.ndarray, base: int) -> tuple[np.ndarray, np.ndarray]:
    """np.divmod(values, base) for an integer array and a positive int, the same values: a
    floor division (numpy divides by a scalar with a fast multiply) and one product,
    several times faster than np.divmod, which does not."""
    quotient = values // base
    return quotient, values - quotient * base

"""Integers as narrow steps: differences stored in one or two bytes, the rare larger ones apart.

A sorted index array (enter values by their rank in the spectrum, forest rows) or the vertex ids
across a row of a simplex (points in space-filling order) changes by small amounts from one
entry to the next; its differences fit a byte or two, where the ids need four or eight. The
step dtype's extreme value (its max when unsigned, its min when signed) marks a step held in
the (e,) int64 `far` array instead, in C order, so every value round-trips exactly.
"""

from __future__ import annotations

import numpy as np


def marker(dtype: np.dtype) -> int:
    """The step value that says "look in far": the dtype's max (unsigned) or min (signed)."""
    info = np.iinfo(dtype)
    return int(info.max) if info.min == 0 else int(info.min)


def encode(steps: np.ndarray, dtype: type) -> tuple[np.ndarray, np.ndarray]:
    """(narrow, far): integer `steps` as `dtype`, the marker where a step does not fit below
    it, and those steps' (e,) int64 values in C order."""
    info, mark = np.iinfo(dtype), marker(dtype)
    wide = np.asarray(steps, dtype=np.int64)
    out_of_range = (wide < info.min) | (wide > info.max) | (wide == mark)
    narrow = np.where(out_of_range, mark, wide).astype(dtype)
    return narrow, wide[out_of_range]


def decode(narrow: np.ndarray, far: np.ndarray, dtype: type = np.int64) -> np.ndarray:
    """The steps `encode` narrowed, as `dtype` (ValueError when far does not fill the
    markers: a damaged or crafted pair)."""
    out = narrow.astype(dtype)
    at = narrow == marker(narrow.dtype)
    if int(np.count_nonzero(at)) != len(far):
        raise ValueError("steps and their far values disagree")
    out[at] = far
    return out


def encode_sorted(values: np.ndarray, dtype: type = np.uint8) -> tuple[np.ndarray, np.ndarray]:
    """(narrow, far) of the (n,) non-decreasing non-negative integers `values` (their
    differences, the first from 0)."""
    values = np.asarray(values, dtype=np.int64)
    return encode(np.diff(values, prepend=np.int64(0)), dtype)


def decode_sorted(narrow: np.ndarray, far: np.ndarray) -> np.ndarray:
    """(n,) int64 the values `encode_sorted` stored."""
    return np.cumsum(decode(narrow, far), dtype=np.int64)

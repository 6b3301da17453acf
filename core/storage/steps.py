"""Integers as narrow steps: differences stored in one or two bytes, the rare larger ones apart.

A sorted index array (enter values by their rank in the spectrum, forest rows) or the vertex ids
across a row of a simplex (points in space-filling order) changes by small amounts from one
entry to the next; its differences fit a byte or two, where the ids need four or eight. The
step dtype's extreme value (its max when unsigned, its min when signed) marks a step held in
the (e,) int64 `far` array instead, in C order, so every value round-trips exactly.
"""

from __future__ import annotations

import numpy as np

STRETCH = 1 << 18  # entries unpacked at a time


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
    narrow = np.ascontiguousarray(np.where(out_of_range, mark, wide).astype(dtype))
    return narrow, np.ascontiguousarray(wide[out_of_range])


def encode_sorted(values: np.ndarray, dtype: type = np.uint8) -> tuple[np.ndarray, np.ndarray]:
    """(narrow, far) of the (n,) non-decreasing non-negative integers `values` (their
    differences, the first from 0; take_sorted gives them back)."""
    values = np.asarray(values, dtype=np.int64)
    return encode(np.diff(values, prepend=np.int64(0)), dtype)


def decode(narrow: np.ndarray, far: np.ndarray, dtype: type = np.intp) -> np.ndarray:
    """The steps `encode` narrowed, as `dtype`, in narrow's shape (ValueError when far does
    not fill the markers: a damaged or crafted pair)."""
    out = narrow.astype(dtype)
    out.reshape(-1)[_markers(narrow, far)] = far
    return out


def take_sorted(narrow: np.ndarray, far: np.ndarray, values: np.ndarray) -> np.ndarray:
    """values[the (n,) integers `encode_sorted` stored] (IndexError for one out of range),
    in stretches of STRETCH entries whose temporaries stay small (fresh memory is what a
    reopen pays for most)."""
    out = np.empty(len(narrow), dtype=values.dtype)
    at = _markers(narrow, far)
    carry = 0
    for lo in range(0, len(narrow), STRETCH):
        ranks = narrow[lo:lo + STRETCH].astype(np.intp)
        _fill(ranks, at, far, lo)
        np.cumsum(ranks, out=ranks)
        ranks += carry
        carry = int(ranks[-1])
        out[lo:lo + len(ranks)] = values[ranks]
    return out


def _markers(narrow: np.ndarray, far: np.ndarray) -> np.ndarray:
    """(e,) flat positions of the markers in narrow; ValueError unless far fills them."""
    at = np.flatnonzero(narrow.reshape(-1) == marker(narrow.dtype))
    if len(at) != len(far):
        raise ValueError("steps and their far values disagree")
    return at


def _fill(wide: np.ndarray, at: np.ndarray, far: np.ndarray, lo: int) -> None:
    """Put the far values whose markers fall in wide (the flat stretch from lo) in place."""
    first, last = np.searchsorted(at, [lo, lo + wide.size])
    if last > first:
        wide.reshape(-1)[at[first:last] - lo] = far[first:last]


def cumulative_rows(first: np.ndarray, narrow: np.ndarray, far: np.ndarray) -> np.ndarray:
    """(n, k + 1) int32 rows from their (n,) first entries and the (n, k) steps across each
    row `encode` narrowed (in stretches, as take_sorted)."""
    n, k = narrow.shape
    out = np.empty((n, k + 1), dtype=np.int32)
    at = _markers(narrow, far)
    rows = max(1, STRETCH // max(k, 1))
    for lo in range(0, n, rows):
        across = narrow[lo:lo + rows].astype(np.int32)
        _fill(across, at, far, lo * k)
        block = out[lo:lo + rows]
        block[:, 0] = first[lo:lo + rows]
        for column in range(1, k + 1):  # column by column: rows are only k + 1 long
            np.add(block[:, column - 1], across[:, column - 1], out=block[:, column])
    return out


def cumulative_curves(narrow: np.ndarray, far: np.ndarray) -> np.ndarray:
    """(s, r) int32 the r curves whose (r, s) steps along s `encode` narrowed, summed up."""
    curves = decode(narrow, far, np.int32)
    np.cumsum(curves, axis=1, out=curves)
    return np.ascontiguousarray(curves.T)

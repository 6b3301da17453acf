"""Integers as narrow steps: differences stored in one or two bytes, the rare larger ones apart.

A sorted index array (enter values by their rank in the spectrum, forest rows) or the vertex ids
across a row of a simplex (points in space-filling order) changes by small amounts from one
entry to the next; its differences fit a byte or two, where the ids need four or eight. The
step dtype's extreme value (its max when unsigned, its min when signed) marks a step held in
the (e,) int64 `far` array instead, in C order, so every value round-trips exactly.
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

CHUNK = 1 << 16  # entries decoded at a time


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


def chunks(narrow: np.ndarray, far: np.ndarray, dtype: type, size: int = CHUNK
           ) -> Iterator[tuple[int, np.ndarray]]:
    """(start, wide) for each stretch of `size` entries of the flat `narrow`: the steps as
    `dtype`, far values in place. Stretches keep the temporaries in cache and out of fresh
    memory (a reopen's cost is otherwise page faults). ValueError, once all are read, when
    far does not fill the markers (a damaged or crafted pair)."""
    mark, used = marker(narrow.dtype), 0
    for lo in range(0, len(narrow), size):
        part = narrow[lo:lo + size]
        wide = part.astype(dtype)
        at = np.flatnonzero(part == mark)
        if len(at):
            if used + len(at) > len(far):
                raise ValueError("steps and their far values disagree")
            wide[at] = far[used:used + len(at)]
            used += len(at)
        yield lo, wide
    if used != len(far):
        raise ValueError("steps and their far values disagree")


def decode(narrow: np.ndarray, far: np.ndarray, dtype: type = np.int64) -> np.ndarray:
    """The steps `encode` narrowed, as `dtype`, in narrow's shape."""
    out = np.empty(narrow.shape, dtype=dtype)
    flat = out.reshape(-1)
    for lo, wide in chunks(narrow.reshape(-1), far, dtype):
        flat[lo:lo + len(wide)] = wide
    return out


def take_sorted(narrow: np.ndarray, far: np.ndarray, values: np.ndarray) -> np.ndarray:
    """values[the (n,) integers `encode_sorted` stored] (IndexError for one out of range)."""
    out = np.empty(len(narrow), dtype=values.dtype)
    carry = 0
    for lo, wide in chunks(narrow, far, np.int64):
        np.cumsum(wide, out=wide)
        wide += carry
        carry = int(wide[-1])
        np.take(values, wide, out=out[lo:lo + len(wide)])
    return out


def cumulative_rows(first: np.ndarray, narrow: np.ndarray, far: np.ndarray) -> np.ndarray:
    """(n, k + 1) int32 rows from their (n,) first entries and the (n, k) steps across each
    row `encode` narrowed."""
    n, k = narrow.shape
    out = np.empty((n, k + 1), dtype=np.int32)
    out[:, 0] = first
    rows = max(1, CHUNK // max(k, 1))
    for lo, wide in chunks(narrow.reshape(-1), far, np.int32, rows * k):
        start = lo // k
        block, across = out[start:start + len(wide) // k], wide.reshape(-1, k)
        for column in range(1, k + 1):
            np.add(block[:, column - 1], across[:, column - 1], out=block[:, column])
    return out


def cumulative_curves(narrow: np.ndarray, far: np.ndarray) -> np.ndarray:
    """(s, r) int32 the r curves whose (r, s) steps along s `encode` narrowed, summed up."""
    r, s = narrow.shape
    out = np.empty((s, r), dtype=np.int32)
    mark, used = marker(narrow.dtype), 0
    for i in range(r):
        count = int(np.count_nonzero(narrow[i] == mark))
        carry = 0
        for lo, wide in chunks(narrow[i], far[used:used + count], np.int32):
            np.cumsum(wide, out=wide)
            wide += carry
            carry = int(wide[-1])
            out[lo:lo + len(wide), i] = wide
        used += count
    if used != len(far):
        raise ValueError("steps and their far values disagree")
    return out

"""Sorting a level by its enter values: a packed float32-key sort made exact by a stable
pass, on two threads."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from core.parallel import PARALLEL_ABOVE, PASSES, both, halves, together


def argsort_radii(values: np.ndarray) -> np.ndarray:
    """Stable argsort of (n,) float64 values (inf allowed; negative ones for weighted
    tables), n < 2**32.

    np.sort of (float32 key, index) packed in a uint64 is several times faster than
    np.argsort here; float32 rounding is monotone, so a stable pass over the nearly sorted
    result restores the exact float64 order. The packing, unpacking and that pass run on
    two threads (the pass in two parts cut where the float32 key changes).
    """
    n = len(values)
    if n >= 2**32:
        return np.argsort(values, kind="stable")
    negative = bool(n) and bool(values.min() < 0)
    packed = np.empty(n, dtype=np.uint64)

    def pack(lo: int, hi: int) -> None:
        with np.errstate(over="ignore"):  # beyond float32's range: inf keys, fixed below
            key = values[lo:hi].astype(np.float32)
        bits = key.view(np.uint32)
        if negative:  # IEEE order as unsigned: flip negatives, set positives' sign
            bits = np.where(key < 0, ~bits, bits | np.uint32(0x80000000))
        out = packed[lo:hi]
        out[:] = bits
        out <<= np.uint64(32)
        out |= np.arange(lo, hi, dtype=np.uint64)

    halves(pack, n, PASSES)
    packed.sort()
    order = np.empty(n, dtype=np.int64)

    def unpack(lo: int, hi: int) -> None:
        np.bitwise_and(packed[lo:hi], np.uint64(0xFFFFFFFF), out=order[lo:hi].view(np.uint64))

    halves(unpack, n, PASSES)
    return stable_fix(values, order, _key_cut(packed))


def _key_cut(packed: np.ndarray) -> int:
    """A position near the middle of the sorted (key << 32 | index) array where the key
    changes: n where the middle key runs to the end, 0 for the largest key or short arrays
    (either means one part)."""
    n = len(packed)
    if n < PARALLEL_ABOVE:
        return 0
    key = int(packed[n // 2 - 1]) >> 32
    if key == 0xFFFFFFFF:
        return 0
    return int(np.searchsorted(packed, np.uint64((key + 1) << 32)))


def stable_fix(values: np.ndarray, order: np.ndarray, cut: int) -> np.ndarray:
    """order[np.argsort(values[order], kind="stable")]: in two parts on two threads when
    every value before `cut` is at most every value from it (0: in one part)."""
    def fix(lo: int, hi: int) -> np.ndarray:
        part = order[lo:hi]
        return part[np.argsort(np.take(values, part), kind="stable")]

    if 0 < cut < len(order):
        first, second = both(lambda: fix(0, cut), lambda: fix(cut, len(order)))
        if values[first[-1]] <= values[second[0]]:
            out = np.empty_like(order)
            both(lambda: np.copyto(out[:cut], first), lambda: np.copyto(out[cut:], second))
            return out
    return fix(0, len(order))


def sort_order(enter: np.ndarray, sort: bool) -> np.ndarray | None:
    """The order that sorts a level by enter, None when the level keeps its built order."""
    return argsort_radii(enter) if sort else None


def sort_order_beside(enter: np.ndarray, sort: bool) -> Callable[[], np.ndarray | None]:
    """sort_order started in a helper thread (core.parallel.together), for the caller to do
    the level's other work meanwhile; returns the function that waits for it."""
    if not sort:
        return lambda: None
    return together(lambda: argsort_radii(enter))

"""Cell neighbours from the cells alone (gmsh returns none): facets matched by packed keys.

Every facet is keyed at its slot cell * (d+1) + i (the facet opposite vertex i of a cell),
so the matched slots give both the neighbour table and, free, each neighbour's column that
points back (the `mirror`, which the certification and the table would otherwise find by a
random gather of the neighbours' rows). The argsort of the keys is most of the pass: long
key arrays are split at a sampled median key (equal keys stay together) and the two parts
sorted at once on two threads.
"""

from __future__ import annotations

import math

import numpy as np

from core.parallel import PARALLEL_ABOVE, PASSES, both, halves


def _packed(cells: np.ndarray, columns: list[list[int]], base: int,
            dtype: type) -> np.ndarray:
    """(t * len(columns),) facet keys in `dtype`, the facet of columns[i] of every cell at
    slot cell * len(columns) + i, its vertices packed in base `base`."""
    keys = np.empty((len(cells), len(columns)), dtype=dtype)
    for i, cols in enumerate(columns):
        part = cells[:, cols[0]].astype(dtype)
        for c in cols[1:]:
            part *= dtype(base)
            part += cells[:, c].astype(dtype)
        keys[:, i] = part
    return keys.ravel()


def _columns(width: int) -> list[list[int]]:
    """The columns of the facet opposite each vertex of a cell of `width` vertices."""
    return [[j for j in range(width) if j != i] for i in range(width)]


def _one_key(cells: np.ndarray, n_points: int) -> np.ndarray | None:
    """(t * (d+1),) uint64 facet keys (slot cell * (d+1) + i: the facet opposite vertex i),
    packed in halves on two threads; None where m**d does not fit in 64 bits."""
    width = cells.shape[1]
    if float(n_points) ** (width - 1) >= 2.0**64:
        return None
    keys = np.empty(cells.size, dtype=np.uint64)

    def part(start: int, stop: int) -> None:
        keys[start * width:stop * width] = _packed(cells[start:stop], _columns(width),
                                                   n_points, np.uint64)

    halves(part, len(cells), PASSES)
    return keys


def _match_sorted(keys: np.ndarray, slots: np.ndarray, other: np.ndarray) -> bool:
    """other[a] = b and other[b] = a for the slots of every two equal `keys`, sorted by
    them; whether no key is there three times."""
    same = keys[1:] == keys[:-1]
    first, second = slots[:-1][same], slots[1:][same]
    other[first] = second
    other[second] = first
    return not bool(np.any(same[1:] & same[:-1]))


def _match_part(keys: np.ndarray, pivot: np.uint64, low: bool, other: np.ndarray) -> bool:
    """_match_sorted on the keys below `pivot` (`low`), or on those at or above it."""
    mask = keys < pivot if low else keys >= pivot
    slots = np.flatnonzero(mask)
    part = np.compress(mask, keys)
    del mask
    order = np.argsort(part)
    part = part[order]
    slots = slots[order]
    del order
    return _match_sorted(part, slots, other)


def _match_keys(keys: np.ndarray, other: np.ndarray) -> bool:
    """Every two slots with equal uint64 `keys` matched in `other` (_match_sorted). Long
    key arrays are split at a sampled median value, so equal keys stay together, and the
    two parts are sorted at once on two threads (the argsort is most of the pass)."""
    if len(keys) < PARALLEL_ABOVE:
        order = np.argsort(keys)
        return _match_sorted(keys[order], order, other)
    step = max(1, len(keys) // 4096)
    while math.gcd(step, 12) != 1:  # not a multiple of a cell's 3 or 4 slots: every column
        step += 1
    sample = np.sort(keys[::step])
    pivot = sample[len(sample) // 2]
    low, high = both(lambda: _match_part(keys, pivot, True, other),
                     lambda: _match_part(keys, pivot, False, other))
    return low and high


def _match_lexsorted(cells: np.ndarray, n_points: int, other: np.ndarray) -> bool:
    """_match_keys where m**d does not fit in 64 bits: a lexsort of (first vertices, last
    vertex), in one thread."""
    columns = _columns(cells.shape[1])
    head = _packed(cells, [cols[:-1] for cols in columns], n_points, np.int64)
    tail = np.stack([cells[:, cols[-1]] for cols in columns], axis=1).ravel()
    order = np.lexsort((tail, head))
    head, tail = head[order], tail[order]
    same = (head[1:] == head[:-1]) & (tail[1:] == tail[:-1])
    first, second = order[:-1][same], order[1:][same]
    other[first] = second
    other[second] = first
    return not bool(np.any(same[1:] & same[:-1]))


def paired(cells: np.ndarray, n_points: int) -> tuple[np.ndarray, np.ndarray, bool]:
    """(t, d+1) int32 neighbour opposite each vertex (-1 = none) of (t, d+1) ascending
    cells on `n_points` points, (t, d+1) int8 the neighbour's column that holds the cell
    (its `mirror`, -1 = none), and whether every facet is in at most two cells (a facet in
    three or more makes no triangulation; the tables are then meaningless)."""
    t, width = cells.shape
    index = np.int32 if width * t < 2**31 else np.int64
    other = np.full(width * t, -1, dtype=index)  # the slot across each slot
    keys = _one_key(cells, n_points)
    if keys is None:
        manifold = _match_lexsorted(cells, n_points, other)
    else:
        manifold = _match_keys(keys, other)
    del keys
    mirror = np.empty(width * t, dtype=np.int8)
    nbrs = np.empty(width * t, dtype=np.int32)

    def part(start: int, stop: int) -> None:
        across = other[start:stop]
        cell = across // width  # -1 stays; a division by a constant, not a remainder
        np.copyto(nbrs[start:stop], cell, casting="unsafe")
        np.subtract(across, cell * width, out=mirror[start:stop], casting="unsafe")
        mirror[start:stop][across < 0] = -1

    halves(part, len(other), PASSES)
    return nbrs.reshape(t, width), mirror.reshape(t, width), manifold


def neighbours(cells: np.ndarray, n_points: int) -> tuple[np.ndarray, bool]:
    """paired() without the mirror: the neighbour table and whether it is manifold."""
    nbrs, _, manifold = paired(cells, n_points)
    return nbrs, manifold
